"""The package's layers point one way, and no module imports itself through others; a module's layer is the folder
it lies in.

The layers, lowest first (a module may import its own layer and those below, never one above), each a folder whose
``__init__`` says what lives there and what it may import:

- ``analysis/`` (``mjpoincare.analysis``): formulas, fits, the exact references, one folder per system under
  ``theory/`` (numpy and scipy only);
- ``core/``: parameters, settings, the result record, the rollout seam's protocol, the job loop, progress, the stamp;
- ``engines/``: the seam's implementations (``backends/``: MuJoCo C, MJX, Warp, Drake's plant) and the outside peers
  (``peers/``: Drake's hybrid models);
- ``simulation/``: the chunked event loop over any engine and the seam's self-test;
- ``scenarios/``: one folder per system, and the records every system declares (``base``, ``gate_cases``);
- the registry: ``scenarios/__init__``, the list of scenarios and the resolution of a run's inputs;
- ``commands/``: validate, sweep, converge, bench, stress, tune, render, report;
- ``gate/``: the regression gate's forms, environments, baseline, power and release history;
- ``pages/``: the generated pages, from runs;
- the faces: the modules at the top of ``src/mjpoincare/`` (:data:`FACES`), what a user imports.

A module in no such folder and not a face has no layer, and fails :func:`test_every_module_has_a_layer`.

Two seams more: no command or face imports one system's scenario module (they find systems through the registry),
and no scenario imports an engine's module (it steps through ``simulate``, which opens an engine with
``backends.open_batch``).

Every import counts, a late one inside a function too: a late import dodges a cycle at import time, not the
dependency. The model is Drake's ``BUILD`` dependencies and dm_control's domain modules (which import only
``base``, ``common`` and ``utils``).
"""

from __future__ import annotations

import ast
import shutil
from collections import defaultdict
from collections.abc import Iterator, Mapping
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Where each top-level package of the distribution lives in the checkout.
SOURCES = {"mjpoincare": ROOT / "src" / "mjpoincare", "mjpoincare.analysis": ROOT / "analysis"}
LAYERS = ("analysis", "core", "engines", "simulation", "scenarios", "registry", "commands", "gate", "pages", "face")
#: Folder (package) -> layer: every module below a folder is in its layer (the deepest folder listed wins).
FOLDERS: dict[str, str] = {
    "mjpoincare.analysis": "analysis", "mjpoincare.core": "core", "mjpoincare.engines": "engines",
    "mjpoincare.simulation": "simulation", "mjpoincare.scenarios": "scenarios", "mjpoincare.commands": "commands",
    "mjpoincare.gate": "gate", "mjpoincare.pages": "pages",
}
#: The modules at the top of the package: what a user imports (the faces) and the registry's own module.
FACES = ("mjpoincare.__init__", "mjpoincare.__main__", "mjpoincare.cli", "mjpoincare.api", "mjpoincare.pytest_plugin",
         "mjpoincare.envs", "mjpoincare.plugin")
#: The registry: the scenarios folder's own ``__init__``.
REGISTRY = "mjpoincare.scenarios.__init__"


def modules(sources: Mapping[str, Path]) -> dict[str, Path]:
    """Every module of the distribution: dotted name (a package as ``pkg.__init__``) -> file."""
    found = {}
    for package, base in sources.items():
        for path in sorted(base.rglob("*.py")):
            found[".".join([package, *path.relative_to(base).with_suffix("").parts])] = path
    return found


def _target(name: str, known: Mapping[str, Path]) -> str | None:
    """The module an import of ``name`` loads, if it is one of ours (a package as its ``__init__``)."""
    if name in known:
        return name
    if f"{name}.__init__" in known:
        return f"{name}.__init__"
    return None


def imports(name: str, path: Path, known: Mapping[str, Path]) -> Iterator[tuple[str, int]]:
    """(imported module of ours, line) for every import statement of module ``name``, late ones included;
    ``from package import submodule`` counts as importing the submodule, not the package."""
    package = name.rsplit(".", 1)[0] if not name.endswith(".__init__") else name[: -len(".__init__")]
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if (target := _target(alias.name, known)) is not None:
                    yield target, node.lineno
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1] + ([base] if base else []))
            for alias in node.names:
                target = _target(f"{base}.{alias.name}", known) or _target(base, known)
                if target is not None:
                    yield target, node.lineno


def layer(name: str) -> str:
    """The layer of module ``name``: the registry's, a face's (:data:`FACES`), or its deepest folder's in
    :data:`FOLDERS`; KeyError for a module in no layer (a module at the top of the package that is no face)."""
    if name == REGISTRY:
        return "registry"
    if name in FACES:
        return "face"
    for folder in sorted(FOLDERS, key=len, reverse=True):
        if name.startswith(folder + "."):
            return FOLDERS[folder]
    raise KeyError(name)


def graph(sources: Mapping[str, Path]) -> dict[str, dict[str, int]]:
    """module -> {imported module of ours: first line}."""
    known = modules(sources)
    edges: dict[str, dict[str, int]] = defaultdict(dict)
    for name, path in known.items():
        edges[name]
        for target, line in imports(name, path, known):
            if target != name:
                edges[name].setdefault(target, line)
    return dict(edges)


def upward(edges: Mapping[str, Mapping[str, int]]) -> list[str]:
    """Every import of a higher layer, as ``module:line (layer) -> module (layer)``."""
    rank = {name: i for i, name in enumerate(LAYERS)}
    found = []
    for name, targets in sorted(edges.items()):
        for target, line in sorted(targets.items()):
            if rank[layer(target)] > rank[layer(name)]:
                found.append(f"{name}:{line} ({layer(name)}) -> {target} ({layer(target)})")
    return found


def cycles(edges: Mapping[str, Mapping[str, int]]) -> list[list[str]]:
    """The import cycles: the strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in edges.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def unplaced(sources: Mapping[str, Path]) -> list[str]:
    """Every module in no layer: at the top of the package and no face, or in a folder :data:`FOLDERS` lacks."""
    out = []
    for name in modules(sources):
        try:
            layer(name)
        except KeyError:
            out.append(name)
    return out


def test_every_module_has_a_layer() -> None:
    assert unplaced(SOURCES) == [], "modules in no layer's folder and no face"


def test_no_layer_imports_one_above_it() -> None:
    assert upward(graph(SOURCES)) == []


def test_no_import_cycles() -> None:
    assert cycles(graph(SOURCES)) == []


#: The scenarios layer's framework modules, which a command may import (the records, the gate's case records, the
#: papers' result records, the registry); every other module of ``mjpoincare.scenarios`` is one system's.
SCENARIO_FRAMEWORK = ("mjpoincare.scenarios.base", "mjpoincare.scenarios.gate_cases",
                      "mjpoincare.scenarios.paper_results", "mjpoincare.scenarios.__init__")


def seam_reaches(edges: Mapping[str, Mapping[str, int]]) -> list[str]:
    """Imports past the seams, as ``module:line -> module``: a command or a face importing one system's scenario
    module (it must find systems through the registry), and a scenario importing an engine's module (it must step
    through :func:`mjpoincare.simulation.simulate.rollout_batch` / ``event_rollout``, which open an engine with
    :func:`mjpoincare.engines.backends.open_batch`)."""
    found = []
    for name, targets in sorted(edges.items()):
        for target, line in sorted(targets.items()):
            command = layer(name) in ("commands", "face") and layer(target) == "scenarios" and (
                target not in SCENARIO_FRAMEWORK)
            engine = layer(name) == "scenarios" and target.startswith("mjpoincare.engines.backends")
            if command or engine:
                found.append(f"{name}:{line} -> {target}")
    return found


def test_no_command_names_a_scenario_and_no_scenario_names_an_engine() -> None:
    assert seam_reaches(graph(SOURCES)) == []


def test_analysis_knows_no_simulator() -> None:
    """The analysis layer imports neither MuJoCo nor dm_control (it works on arrays and formulas only)."""
    offenders = []
    for name, path in modules({"mjpoincare.analysis": SOURCES["mjpoincare.analysis"]}).items():
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            offenders += [f"{name}: {n}" for n in names if n.split(".")[0] in {"mujoco", "dm_control"}]
    assert offenders == []


@pytest.fixture()
def planted(tmp_path: Path) -> dict[str, Path]:
    """A copy of the sources in which the core's parameter module imports the CLI inside a function."""
    copies = {}
    for package, base in SOURCES.items():
        copies[package] = tmp_path / package
        shutil.copytree(base, copies[package], ignore=shutil.ignore_patterns("__pycache__"))
    params = copies["mjpoincare"] / "core" / "params.py"
    params.write_text(params.read_text() + "\n\ndef _planted() -> None:\n    from mjpoincare import cli  # noqa\n")
    return copies


def test_a_planted_upward_import_is_found(planted: dict[str, Path]) -> None:
    found = upward(graph(planted))
    assert any(f.startswith("mjpoincare.core.params:") and f.endswith("-> mjpoincare.cli (face)") for f in found), found


def test_a_module_placed_in_no_layer_is_found(planted: dict[str, Path]) -> None:
    """A new module put at the top of the package beside the faces is in no layer."""
    (planted["mjpoincare"] / "helpers.py").write_text('"""A helper put where no layer is."""\n')
    assert unplaced(planted) == ["mjpoincare.helpers"]


def test_a_planted_cycle_is_found(planted: dict[str, Path]) -> None:
    """The planted import closes a cycle: the CLI reaches the parameter module through the registry."""
    assert any({"mjpoincare.core.params", "mjpoincare.cli"} <= set(c) for c in cycles(graph(planted)))


def test_a_planted_reach_past_the_seams_is_found(planted: dict[str, Path]) -> None:
    """A command that imports one system's module, and a scenario that imports an engine, are both reported."""
    sweep = planted["mjpoincare"] / "commands" / "sweep.py"
    sweep.write_text(sweep.read_text() + "\n\ndef _planted() -> None:\n"
                     "    from mjpoincare.scenarios import rimless_wheel  # noqa\n")
    wheel = planted["mjpoincare"] / "scenarios" / "rimless_wheel" / "runs.py"
    wheel.write_text(wheel.read_text() + "\n\ndef _planted() -> None:\n"
                     "    from mjpoincare.engines.backends import mujoco_c  # noqa\n")
    reaches = seam_reaches(graph(planted))
    assert any(r.startswith("mjpoincare.commands.sweep:")
               and r.endswith("-> mjpoincare.scenarios.rimless_wheel.__init__") for r in reaches), reaches
    assert any(r.startswith("mjpoincare.scenarios.rimless_wheel.runs:")
               and r.endswith("-> mjpoincare.engines.backends.mujoco_c") for r in reaches), reaches
