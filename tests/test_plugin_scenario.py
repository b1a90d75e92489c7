"""The extension point, walked by a plugin the package never imports.

tests/plugin_example/ holds ``toy_ball.py`` (the ``bouncing-ball`` scenario, written against the public extension point
only) and ``toy_ball-0.1.dist-info/`` (its METADATA and its entry point in the group ``mjpoincare.scenarios``): a
distribution that importlib.metadata finds on the path, without pip. With that folder on PYTHONPATH (subprocesses), the
registry lists the toy, ``mjpoincare validate`` runs it, and the scenario contract (tests/test_scenario_contract.py) and
the gate contract (tests/test_gate.py) collect and pass its items; without it, nothing in the package sees it.
"""

from __future__ import annotations

import dataclasses
import importlib.util
import inspect
import os
import re
import subprocess
import sys
import typing
from pathlib import Path

import pytest

from mjpoincare import scenarios

ROOT = Path(__file__).resolve().parent.parent
PLUGIN = ROOT / "tests" / "plugin_example"
NAME = "bouncing-ball"
PRESETS = ("fast", "accurate")
CHECKS = ("restitution", "eigenvalue", "flight_period", "stable")
#: What each contract must collect and pass for the toy: test function -> the ids' parameter parts.
CONTRACT = {f"test_{test}[{NAME}[{preset}]]" for preset in PRESETS for test in (
    "defaults_accepted_and_tolerances_with_reasons", "model_compiles_and_validation_batches_fit_it", "one_render_frame",
    "a_validation_reports_the_checks_its_scenario_declares_and_its_json_round_trips")}
GATE = ({f"test_gated_check[{NAME}[{preset}]::{check}]" for preset in PRESETS for check in CHECKS}
        | {f"test_every_check_of_the_run_is_gated_watched_or_a_declared_miss[{NAME}[{preset}]]" for preset in PRESETS}
        | {f"test_every_preset_of_every_scenario_is_in_the_gate_on_its_defaults[{NAME}]"})

pytestmark = pytest.mark.mujoco


def _env(plugin: bool) -> dict[str, str]:
    """This environment with the plugin's folder first on PYTHONPATH, or without it anywhere there (no bytecode is
    written beside the fixture)."""
    paths = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and Path(p).resolve() != PLUGIN]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(([str(PLUGIN)] if plugin else []) + paths),
            "PYTHONDONTWRITEBYTECODE": "1"}


def _run(args: list[str], *, plugin: bool = True) -> subprocess.CompletedProcess[str]:
    """``args`` in a subprocess from the repository's root, with or without the plugin on the path."""
    return subprocess.run(args, cwd=ROOT, env=_env(plugin), capture_output=True, text=True, timeout=300)


def _mjpoincare(*args: str, plugin: bool = True) -> subprocess.CompletedProcess[str]:
    """The ``mjpoincare`` command (the console script beside this interpreter, else its module)."""
    script = Path(sys.executable).with_name("mjpoincare")
    command = [str(script)] if script.exists() else [sys.executable, "-m", "mjpoincare.cli"]
    return _run([*command, *args], plugin=plugin)


def _passed_items(test_file: str) -> set[str]:
    """The toy's items of ``test_file`` that passed in a pytest subprocess (``-k bouncing-ball``), after asserting that
    the run passed and selected items, every one of which passed (none failed, skipped or expected to fail)."""
    run = _run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rA", test_file, "-k", NAME])
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-2000:]
    summary = re.search(r"^(\d+) passed, \d+ deselected in ", run.stdout, re.M)
    assert summary, "not a run in which every selected item passed:\n" + run.stdout[-2000:]
    passed = {m.group(1) for m in re.finditer(rf"^PASSED {re.escape(test_file)}::(\S+)$", run.stdout, re.M)}
    assert passed and len(passed) == int(summary.group(1)), run.stdout[-4000:]
    return passed


def test_the_registry_lists_the_plugin() -> None:
    run = _mjpoincare("list")
    assert run.returncode == 0, run.stderr
    assert re.search(rf"^{NAME}: toy plugin", run.stdout, re.M), run.stdout
    assert re.search(r"^rimless-wheel: ", run.stdout, re.M), "the built-in scenarios are still listed"


def test_validate_runs_the_plugin_and_prints_its_check_table() -> None:
    run = _mjpoincare("validate", NAME)
    assert run.returncode == 0, run.stdout + run.stderr
    assert f"{NAME}  preset=fast" in run.stdout and re.search(r"^check\s+analytic\s+simulated", run.stdout, re.M)
    for check in CHECKS:
        assert re.search(rf"^{check}\s.*PASS$", run.stdout, re.M), run.stdout


def test_the_scenario_contract_accepts_the_plugin() -> None:
    assert _passed_items("tests/test_scenario_contract.py") >= CONTRACT


def test_the_gate_contract_accepts_the_plugin() -> None:
    assert _passed_items("tests/test_gate.py") >= GATE


def test_without_the_plugin_on_the_path_nothing_sees_it() -> None:
    """Neither this process nor a fresh one (PYTHONPATH without the folder) knows the toy, and no source of the package
    names its module."""
    assert NAME not in scenarios.REGISTRY and importlib.util.find_spec("toy_ball") is None, (
        "this test process sees the toy: run the suite without tests/plugin_example on the path")
    listed = _mjpoincare("list", plugin=False)
    assert listed.returncode == 0 and NAME not in listed.stdout and "rimless-wheel" in listed.stdout
    refused = _mjpoincare("validate", NAME, plugin=False)
    assert refused.returncode == 2 and f"unknown scenario {NAME!r}" in refused.stderr, refused.stderr
    sources = [*ROOT.glob("src/**/*.py"), *ROOT.glob("analysis/**/*.py"), ROOT / "pyproject.toml"]
    assert not [str(f) for f in sources if "toy_ball" in f.read_text()]


def test_the_toy_imports_only_the_public_plugin_module() -> None:
    """The toy's every import of this package is from :mod:`mjpoincare.plugin`, and each name it takes is there."""
    import ast

    from mjpoincare import plugin

    tree = ast.parse((PLUGIN / "toy_ball.py").read_text())
    ours = [(node.module, [alias.name for alias in node.names]) for node in ast.walk(tree)
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mjpoincare")]
    ours += [(alias.name, []) for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names
             if alias.name.startswith("mjpoincare")]
    assert ours and all(module == "mjpoincare.plugin" for module, _ in ours), ours
    assert {name for _, names in ours for name in names} <= set(plugin.__all__)


def test_every_public_plugin_name_resolves_and_is_documented() -> None:
    from mjpoincare import plugin

    assert plugin.__all__ == sorted(plugin.__all__, key=lambda n: (n[0].islower(), n))
    for name in plugin.__all__:
        assert getattr(plugin, name) is not None, name
        assert f":func:`{name}`" in plugin.__doc__ or f":class:`{name}`" in plugin.__doc__ or (
            f":data:`{name}`" in plugin.__doc__), f"{name} is exported but not described in the module docstring"


def _types_named(hint: object, found: set[type]) -> None:
    """Every class of the package that ``hint`` names (through unions, containers and callables), and those the
    fields of a named dataclass name in turn."""
    if typing.get_origin(hint) is not None:
        for arg in typing.get_args(hint):
            _types_named(arg, found)
    elif isinstance(hint, list | tuple):
        for arg in hint:
            _types_named(arg, found)
    elif inspect.isclass(hint) and hint.__module__.startswith("mjpoincare") and hint not in found:
        found.add(hint)
        if dataclasses.is_dataclass(hint):
            for field_hint in typing.get_type_hints(hint).values():
                _types_named(field_hint, found)


def test_every_type_a_scenario_field_names_is_exported_by_the_public_module() -> None:
    """A system author builds every documented field of :class:`Scenario` from ``mjpoincare.plugin`` alone: each
    class of the package that a field's type names (and, for a record, its fields' types) is exported there, as the
    same object."""
    from mjpoincare import plugin
    from mjpoincare.plugin import Scenario

    named: set[type] = set()
    _types_named(Scenario, named)
    missing = sorted(t.__name__ for t in named if getattr(plugin, t.__name__, None) is not t)
    assert missing == [], f"named by Scenario's fields but not exported by mjpoincare.plugin: {missing}"
    assert {"Foot", "Peer", "ParamSweep", "RegionMap", "Soak"} <= {t.__name__ for t in named}


def test_sweep_on_the_plugin_shows_its_analytic_eigenvalue() -> None:
    """The toy's analytic values and fit are fields of its Evaluation, so the generic sweep's columns are finite: the
    apex map's multiplier e^2 beside the fitted one, and a verdict per row."""
    run = _mjpoincare("sweep", NAME, "--param", "drop_height", "--values", "0.8,1.0")
    assert run.returncode == 0, run.stdout + run.stderr
    rows = [line.strip("|").split("|") for line in run.stdout.splitlines() if re.match(r"^\| (0\.8|1) \|", line)]
    assert len(rows) == 2
    for row in rows:
        fitted, analytic, verdict = (cell.strip() for cell in row[-3:])
        assert float(analytic) == pytest.approx(0.553654, abs=5e-5)  # e^2 at zeta = 0.1 (4 digits printed)
        assert abs(float(fitted) - float(analytic)) < 0.015 and verdict == "PASS"


def test_a_parameter_against_a_setting_is_refused_before_any_simulation(tmp_path: Path) -> None:
    """The toy's ``check_params_with_settings`` sees the parameters and the settings together: a radius under twice
    the ball's deepest penetration at that contact softness is refused in one line, exit 2, before any rollout,
    nothing written."""
    code = ("import sys\n"
            "from mjpoincare.engines.backends import mujoco_c\n"
            "def refuse(*a, **k):\n"
            "    raise SystemExit('simulated before checking the inputs')\n"
            "mujoco_c._native_chunk = refuse\n"
            "from mjpoincare.cli import main\n"
            "sys.exit(main(sys.argv[1:]))\n")
    out = tmp_path / "out.json"
    run = _run([sys.executable, "-c", code, "validate", NAME, "--set", "radius=0.005", "--json", str(out)])
    assert run.returncode == 2, run.stdout + run.stderr
    assert run.stderr.count("\n") == 1 and "radius=0.005 m must be at least twice" in run.stderr
    assert "solref_timeconst=0.01" in run.stderr and not out.exists()
    stiffer = _mjpoincare("validate", NAME, "--set", "radius=0.005", "--set", "solref_timeconst=0.002")
    assert stiffer.returncode in (0, 1) and "restitution" in stiffer.stdout  # a stiffer contact: accepted, run


def test_a_plugin_model_gets_the_shared_looks(tmp_path: Path) -> None:
    """The toy's own MJCF file includes ``common/looks.xml`` through the public ``load_spec``: its model has the
    gradient sky and the floor's checker material, and a still of it shows the sky (not black) above the floor."""
    code = ("import mujoco, toy_ball\n"
            "m = toy_ball.build({'drop_height': 1.0, 'radius': 0.05, 'gravity': 9.81}, "
            "{**__import__('mjpoincare.core.settings', fromlist=['DEFAULTS']).DEFAULTS})\n"
            "sky = [i for i in range(m.ntex) if m.tex_type[i] == mujoco.mjtTexture.mjTEXTURE_SKYBOX]\n"
            "print(len(sky), m.mat('grid').id == m.geom('floor').matid[0])\n")
    model = _run([sys.executable, "-c", code])
    assert model.returncode == 0 and model.stdout.split() == ["1", "True"], model.stdout + model.stderr
    still = _mjpoincare("render", NAME, "-o", str(tmp_path / "still.png"), "--seconds", "0.1", "--size", "64x48")
    assert still.returncode == 0, still.stderr
    import mediapy

    sky = mediapy.read_image(str(tmp_path / "still.png"))[:4].reshape(-1, 3).mean(axis=0)
    assert sky.min() > 40, sky  # the gradient sky's top (a missing skybox renders black)


@pytest.mark.parametrize(("key", "field", "record"), [("fit", "fit", "FitSummary"),
                                                      ("analytic", "analytic", "AnalyticValues"),
                                                      ("basin_bands", "basins", "BasinMap")])
def test_a_former_extra_key_is_refused_naming_its_field(key: str, field: str, record: str) -> None:
    """A plugin written when the commands read ``extras["fit"]`` and the like fails in one line naming the field and
    the record that replaced the key (its values would otherwise sit unread under the JSON's ``extras``)."""
    from mjpoincare.plugin import Evaluation

    refusal = rf"extras\['{key}'\] is now the field {field}= \(a mjpoincare.plugin.{record}\)"
    with pytest.raises(TypeError, match=refusal):
        Evaluation([], None, {key: {}})  # type: ignore[arg-type]
