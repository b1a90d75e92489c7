"""The extension point, walked by a plugin the package never imports.

tests/plugin_example/ holds ``toy_ball.py`` (the ``bouncing-ball`` scenario, written against the public extension point
only) and ``toy_ball-0.1.dist-info/`` (its METADATA and its entry point in the group ``mjpoincare.scenarios``): a
distribution that importlib.metadata finds on the path, without pip. With that folder on PYTHONPATH (subprocesses), the
registry lists the toy, ``mjpoincare validate`` runs it, and the scenario contract (tests/test_scenario_contract.py) and
the gate contract (tests/test_gate.py) collect and pass its items; without it, nothing in the package sees it.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
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
    "defaults_pass_check_params_and_tolerances_exist", "model_compiles_and_probe_batches_fit_it", "one_render_frame",
    "validation_json_round_trips")}
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
