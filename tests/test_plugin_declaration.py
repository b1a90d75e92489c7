"""A system author's mistakes, planted one at a time into a copy of the toy plugin (tests/plugin_example/), are caught
when the registry loads it: one line naming the plugin, the field and the fix, exit 2 before any simulation, and every
other scenario still listed (:mod:`mjpoincare.scenarios.declaration`)."""

from __future__ import annotations

import dataclasses
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from mjpoincare.core.params import PluginDeprecationWarning
from mjpoincare.scenarios import REGISTRY
from mjpoincare.scenarios.base import RENAMED_FIELDS, DeclarationError, Scenario
from mjpoincare.scenarios.gate_cases import GateCase

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "tests" / "plugin_example"
NAME = "bouncing-ball"

#: mistake -> (the toy's text, the mistaken text, what the one line must say)
MISTAKES = {
    "a misspelled Scenario field": ("camera_distance=2.0,", "camera_distanse=2.0,",
                                    "Scenario has no field 'camera_distanse'; did you mean 'camera_distance'?"),
    "a misspelled setting in a preset": ('"fast": {"timestep": 1e-4,', '"fast": {"timestpe": 1e-4,',
                                         "presets['fast'] sets 'timestpe', which is not a simulator setting; did you "
                                         "mean 'timestep'?"),
    "a misspelled mechanism": ('seam_mechanisms=("rollout",)', 'seam_mechanisms=("rolout",)',
                               "seam_mechanisms= names 'rolout', not a seam mechanism; did you mean 'rollout'?"),
    "a misspelled field's old name": ('seam_mechanisms=("rollout",)', 'mechanisims=("rollout",)',
                                      "Scenario has no field 'mechanisims'; did you mean 'seam_mechanisms'?"),
    "a tolerance of 0": ('"flight_period": 1.5e-3}', '"flight_period": 0.0}',
                         "Tolerances: the bound of 'flight_period' must be a finite number > 0 (got 0.0)"),
    "a NaN tolerance": ('"flight_period": 1.5e-3}', '"flight_period": float("nan")}',
                        "Tolerances: the bound of 'flight_period' must be a finite number > 0 (got nan)"),
    "a misspelled tolerance key": ('"flight_period": 1.5e-3}', '"flight_perod": 1.5e-3}',
                                   "tolerances['fast'] bounds 'flight_perod', which names no declared check; did you "
                                   "mean 'flight_period'?"),
    "a check without a bound at one preset": ('"eigenvalue": 5e-3, "flight_period": 4e-4}', '"eigenvalue": 5e-3}',
                                              "tolerances['accurate'] has no bound for 'flight_period', which "
                                              "tolerances['fast'] bounds: give it a bound at every preset"),
    "a misspelled preset in the tolerances": ('    "accurate": Tolerances(', '    "acurate": Tolerances(',
                                              "tolerances names 'acurate', which is not a preset; did you mean "
                                              "'accurate'?"),
    "a preset without tolerances": ('PRESETS: dict[str, dict[str, float | int | str]] = {',
                                    'PRESETS: dict[str, dict[str, float | int | str]] = {\n    "coarse": {},',
                                    "tolerances has no Tolerances for preset 'coarse'"),
    "a parameter without bounds": ('Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, True)',
                                   'Param("gravity", 9.81, "gravity, m/s^2", float)',
                                   "Param 'gravity' has no bounds: give low= and high="),
    "a name that differs from its entry point": ('    name="bouncing-ball", summary=',
                                                 '    name="bouncing_ball", summary=',
                                                 "name='bouncing_ball' differs from its entry point 'bouncing-ball'"),
}


def _plant(folder: Path, *changes: tuple[str, str]) -> Path:
    """A copy of the toy plugin in ``folder`` with each ``(old, new)`` of ``changes`` made (``old`` found exactly
    once)."""
    shutil.copytree(EXAMPLE, folder, ignore=shutil.ignore_patterns("__pycache__"))
    source = folder / "toy_ball.py"
    text = source.read_text()
    for old, new in changes:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    source.write_text(text)
    return folder


def _mjpoincare(folder: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """``mjpoincare args`` with ``folder`` (a plugin distribution) first on the path."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(folder), os.environ.get("PYTHONPATH", "")]),
           "PYTHONDONTWRITEBYTECODE": "1"}
    script = Path(sys.executable).with_name("mjpoincare")
    return subprocess.run([str(script), *args], cwd=folder, env=env, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("mistake", list(MISTAKES))
def test_a_planted_mistake_is_one_line_before_any_simulation(mistake: str, tmp_path: Path) -> None:
    """``validate`` of the broken plugin: exit 2, one line naming the plugin's entry point and the mistake, nothing
    simulated (no table); ``list``: every other scenario listed, the one line on stderr, exit 2."""
    old, new, said = MISTAKES[mistake]
    folder = _plant(tmp_path / "plugin", (old, new))
    run = _mjpoincare(folder, "validate", NAME)
    lines = run.stderr.strip().splitlines()
    assert run.returncode == 2 and len(lines) == 1, run.stderr
    assert "plugin toy-ball (toy_ball:BOUNCING_BALL)" in lines[0] and said in lines[0], lines[0]
    assert "check" not in run.stdout and "Traceback" not in run.stderr
    listed = _mjpoincare(folder, "list")
    assert listed.returncode == 2 and "rimless-wheel: " in listed.stdout and f"{NAME}: " not in listed.stdout
    assert listed.stderr.strip().splitlines() == lines


def test_the_other_scenarios_run_beside_a_broken_plugin(tmp_path: Path) -> None:
    """A broken plugin on the path leaves another scenario's validation alone."""
    old, new, _ = MISTAKES["a misspelled setting in a preset"]
    folder = _plant(tmp_path / "plugin", (old, new))
    run = _mjpoincare(folder, "validate", "slotted-skate", "--set", "timestep=2e-4")
    assert run.returncode == 0, run.stderr[-2000:]


@pytest.mark.parametrize(("returned", "said"), [
    ("Evaluation(out, None)", "Evaluation: rollout= must be the RolloutReport"),
    ("Evaluation([], report)", "evaluate reported no check"),
    ("Evaluation([relative('restitutoin', 1.0, 1.0, 0.1, '', '')], report)",
     "evaluate reported check 'restitutoin', which bench_checks= (checks= is empty) does not declare; did you "
     "mean 'restitution'?"),
    ("Evaluation(out, report, {'analytic': {}})", "extras['analytic'] is now the field analytic="),
])
def test_what_evaluate_returns_is_checked_on_its_first_return(returned: str, said: str, tmp_path: Path) -> None:
    """An Evaluation of the wrong shape, one with no check, or a check the scenario does not declare: one line, exit 2
    (the author's mistake, not a physics FAIL)."""
    folder = _plant(tmp_path / "plugin", ("    return Evaluation(out, report, extras, analytic=analytic, fit=summary)",
                                          f"    return {returned}"))
    run = _mjpoincare(folder, "validate", NAME)
    lines = run.stderr.strip().splitlines()
    assert run.returncode == 2 and len(lines) == 1 and said in lines[0], run.stderr[-2000:]


#: The toy's declaration by the fields' new names -> by their old names (RENAMED_FIELDS; the toy has no seam mode).
OLD_STYLE = {"check_params_with_settings=": "check_inputs=", "bench_checks=": "accuracy_checks=",
             "validation_batches=": "probe=", "exact_model_bench=": "reference_bench=", "video_states=": "clip=",
             "seam_mechanisms=": "mechanisms="}


def test_an_old_style_declaration_loads_and_warns_once_per_renamed_field(tmp_path: Path) -> None:
    """The toy declared with the fields' old names loads, its declaration checked, with one warning per old name,
    attributed to the declaration's line and naming the new name; read by the new names, it is the same scenario."""
    folder = _plant(tmp_path / "plugin", *OLD_STYLE.items())
    code = ("import warnings; warnings.simplefilter('always'); from mjpoincare import scenarios; "
            f"s = scenarios.get({NAME!r}); print(s.validation_batches.__name__, s.video_states.__name__, "
            "s.exact_model_bench.__name__, s.check_params_with_settings.__name__, s.bench_checks, s.seam_mechanisms)")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(folder), os.environ.get("PYTHONPATH", "")]),
           "PYTHONDONTWRITEBYTECODE": "1"}
    run = subprocess.run([sys.executable, "-c", code], cwd=folder, env=env, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.split(maxsplit=4)[:4] == ["validation_batches", "video_states", "exact_model_bench",
                                               "check_params_with_settings"], run.stdout
    assert "('restitution', 'eigenvalue', 'flight_period') ('rollout',)" in run.stdout
    warned = [line for line in run.stderr.splitlines() if "PluginDeprecationWarning" in line]
    assert len(warned) == len(OLD_STYLE), run.stderr
    for old in OLD_STYLE.values():
        said = [line for line in warned if f"Scenario: {old} is renamed {RENAMED_FIELDS[old[:-1]]}=" in line]
        assert len(said) == 1 and "toy_ball.py:" in said[0], (old, warned)


def test_the_command_line_shows_an_old_name_once(tmp_path: Path) -> None:
    """Python hides a DeprecationWarning outside ``__main__``; ``mjpoincare`` shows a plugin's old names, each once,
    and still lists the scenario."""
    folder = _plant(tmp_path / "plugin", *OLD_STYLE.items())
    run = _mjpoincare(folder, "list")
    assert run.returncode == 0 and f"{NAME}:" in run.stdout, run.stderr[-2000:]
    warned = [line for line in run.stderr.splitlines() if "PluginDeprecationWarning" in line]
    assert len(warned) == len(OLD_STYLE), run.stderr


def test_a_renamed_field_by_either_name() -> None:
    """Each old name works in a declaration and in a read, one warning naming the new name each time; giving both
    names is refused in one line."""
    scenario = REGISTRY["rimless-wheel"]
    for old, new in RENAMED_FIELDS.items():
        value = getattr(scenario, new)
        with pytest.warns(PluginDeprecationWarning, match=rf"^Scenario: {old}= is renamed {new}=") as warned:
            declared = Scenario(**{f.name: getattr(scenario, f.name) for f in dataclasses.fields(scenario)
                                   if f.name != new}, **{old: value})
        assert len(warned) == 1 and getattr(declared, new) is value
        with pytest.warns(PluginDeprecationWarning, match=rf"^Scenario\.{old} is renamed Scenario\.{new}") as read:
            assert getattr(scenario, old) is value
        assert len(read) == 1
        with pytest.raises(DeclarationError, match=rf"^Scenario: {old}= is the old name of {new}=: give {new}= only"):
            dataclasses.replace(scenario, **{old: value})
    with pytest.warns(PluginDeprecationWarning, match="Scenario.mechanisms_for is renamed Scenario.seam_mechanisms"):
        assert scenario.mechanisms_for({}) == scenario.seam_mechanisms_for({})


def test_a_gate_case_s_checks_as_one_string_still_work_with_a_warning() -> None:
    """``GateCase.of`` takes the gated checks as a tuple of names; the old space-separated string gives the same case,
    with one warning showing the tuple to write."""
    new = GateCase.of("bouncing-ball", "fast", ("restitution", "stable"), drop_height=2.0)
    with pytest.warns(PluginDeprecationWarning, match=r"give the gated checks as a tuple of names, "
                                                      r"\('restitution', 'stable'\)") as warned:
        old = GateCase.of("bouncing-ball", "fast", "restitution stable", drop_height=2.0)
    assert len(warned) == 1 and old == new and new.gated == ("restitution", "stable")


def test_the_contract_tests_run_beside_a_broken_plugin(tmp_path: Path) -> None:
    """With a broken plugin on the path, the contract tests collect: the broken plugin fails the one test that every
    scenario loads, in the registry's line, and the built-in scenarios' tests run (here the ones that simulate
    nothing)."""
    old, new, said = MISTAKES["a misspelled setting in a preset"]
    folder = _plant(tmp_path / "plugin", (old, new))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(folder), os.environ.get("PYTHONPATH", "")]),
           "PYTHONDONTWRITEBYTECODE": "1"}
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-rf",
                          str(ROOT / "tests" / "test_scenario_contract.py"), "-k", "loads or tolerances_with_reasons"],
                         cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    out = run.stdout
    assert run.returncode == 1 and "INTERNALERROR" not in out and "error" not in out.splitlines()[-1], out[-3000:]
    failed = [line for line in out.splitlines() if line.startswith("FAILED")]
    assert len(failed) == 1 and "test_every_registered_scenario_loads" in failed[0] and said in out, out[-3000:]
    assert re.search(r"1 failed, (\d+) passed", out) and int(re.search(r"(\d+) passed", out)[1]) >= 12, out[-300:]
