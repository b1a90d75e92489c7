"""A system author's mistakes, planted one at a time into a copy of the toy plugin (tests/plugin_example/), are caught
when the registry loads it: one line naming the plugin, the field and the fix, exit 2 before any simulation, and every
other scenario still listed (:mod:`mjpoincare.scenarios.declaration`)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

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
    "a misspelled mechanism": ('mechanisms=("rollout",)', 'mechanisms=("rolout",)',
                               "mechanisms= names 'rolout', not a seam mechanism; did you mean 'rollout'?"),
    "a tolerance of 0": ('"flight_period": 1.5e-3}', '"flight_period": 0.0}',
                         "Tolerances: the bound of 'flight_period' must be a finite number > 0 (got 0.0)"),
    "a NaN tolerance": ('"flight_period": 1.5e-3}', '"flight_period": float("nan")}',
                        "Tolerances: the bound of 'flight_period' must be a finite number > 0 (got nan)"),
    "a parameter without bounds": ('Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, True)',
                                   'Param("gravity", 9.81, "gravity, m/s^2", float)',
                                   "Param 'gravity' has no bounds: give low= and high="),
    "a name that differs from its entry point": ('    name="bouncing-ball", summary=',
                                                 '    name="bouncing_ball", summary=',
                                                 "name='bouncing_ball' differs from its entry point 'bouncing-ball'"),
}


def _plant(folder: Path, old: str, new: str) -> Path:
    """A copy of the toy plugin in ``folder`` with ``old`` replaced by ``new`` (exactly once)."""
    shutil.copytree(EXAMPLE, folder, ignore=shutil.ignore_patterns("__pycache__"))
    source = folder / "toy_ball.py"
    text = source.read_text()
    assert text.count(old) == 1, old
    source.write_text(text.replace(old, new))
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
    folder = _plant(tmp_path / "plugin", old, new)
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
    folder = _plant(tmp_path / "plugin", old, new)
    run = _mjpoincare(folder, "validate", "slotted-skate", "--set", "timestep=2e-4")
    assert run.returncode == 0, run.stderr[-2000:]


@pytest.mark.parametrize(("returned", "said"), [
    ("Evaluation(out, None)", "Evaluation: rollout= must be the RolloutReport"),
    ("Evaluation([], report)", "evaluate reported no check"),
    ("Evaluation([relative('restitutoin', 1.0, 1.0, 0.1, '', '')], report)",
     "evaluate reported check 'restitutoin', which accuracy_checks= (checks= is empty) does not declare; did you "
     "mean 'restitution'?"),
    ("Evaluation(out, report, {'analytic': {}})", "extras['analytic'] is now the field analytic="),
])
def test_what_evaluate_returns_is_checked_on_its_first_return(returned: str, said: str, tmp_path: Path) -> None:
    """An Evaluation of the wrong shape, one with no check, or a check the scenario does not declare: one line, exit 2
    (the author's mistake, not a physics FAIL)."""
    folder = _plant(tmp_path / "plugin", "    return Evaluation(out, report, extras, analytic=analytic, fit=summary)",
                    f"    return {returned}")
    run = _mjpoincare(folder, "validate", NAME)
    lines = run.stderr.strip().splitlines()
    assert run.returncode == 2 and len(lines) == 1 and said in lines[0], run.stderr[-2000:]
