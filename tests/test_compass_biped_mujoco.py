"""Regression: MuJoCo's passive compass biped against the exact hybrid model (Kisa 2020 Ch. 4; Goswami et al.).

The gait runs with the contact switching the analytic model assumes (swing foot's contact off until it is ahead
and clear, trailing foot released at heel strike); tolerances are the scenario's own.
"""

from __future__ import annotations

import pytest
from mjpoincare.analysis.theory import compass_biped as theory

from mjpoincare import gate
from mjpoincare.cli import main
from mjpoincare.scenarios import compass_biped as cb

pytestmark = pytest.mark.mujoco


def test_switched_off_swing_foot_dips_as_the_exact_swing() -> None:
    """The swing foot passes through the slope mid-swing, as the exact model's does (003 Sec. 4.1 ignores it). On
    every swing of the trajectory from the fixed point, its depth below the stance foot is the exact swing's (from
    the post-impact state its legs-parallel sample pulls back to, legs l - r to the slope) within (r/l) x the exact
    gait's depth: MuJoCo's foot spheres (radius r) are point feet only to O(r/l). A foot whose contact stayed on
    would stop at the slope. The run's deepest dip below the slope is reported without a verdict, in the table and
    the JSON (the run's verdicts are the gate's: tests/test_gate.py)."""
    result = gate.run_case(gate.case("compass-biped[fast]"))
    swing = result.extras["swing_foot"]
    r_over_l = result.settings["foot_radius"] / (result.params["a"] + result.params["b"])
    below, exact = swing["depth_below_stance_foot"], swing["exact_depth_same_swing"]
    # every swing the run walked (the batch stops once its fit settles), the last one after the last heel strike
    assert len(below) == len(exact) and cb.STOPPING.min_samples <= len(below) <= cb.STEPS + 1
    assert max(abs(m - e) for m, e in zip(below, exact, strict=True)) <= r_over_l * swing["exact_depth"]
    reported = result.extras["reported"]["swing_foot_depth"]
    assert reported["unit"] == "m" and reported["value"] >= max(swing["depth"])  # perturbed starts included
    assert "swing_foot_depth" not in {c.name for c in result.checks}
    assert "reported swing_foot_depth: " in result.table()
    assert result.to_dict()["reported"]["swing_foot_depth"]["value"] == reported["value"]


def test_constant_torques_move_the_gait_as_the_theory_says() -> None:
    """Ankle and hip torques are MuJoCo actuators switched to the stance leg at each heel strike: the gait they
    give matches the exact actuated model (fast preset tolerances)."""
    result = gate.run_case(gate.case("compass-biped[fast,tau_ankle=0.5,tau_hip=0.2]"))
    passive = theory.fixed_point(theory.CompassBiped())
    assert abs(result.extras["analytic"]["fixed_point"][2] - passive[2]) > 0.01  # the torques matter


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [("m_h=-1", "m_h must be in (0, 1e+06]"), ("a=0", "a must be in (0, 100]"),
     ("slope=0.09", "unstable passive gait"), ("mu=0.1", "mu must be >= 0.2496")],
)
def test_bad_input(assignment: str, needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "compass-biped", "--set", assignment]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1
