"""Regression: MuJoCo's passive compass biped against the exact hybrid model (Kisa 2020 Ch. 4; Goswami et al.).

The gait runs with the contact switching the analytic model assumes (no scuffing, trailing foot released at
heel strike); tolerances are the scenario's own.
"""

from __future__ import annotations

import pytest
from mjpoincare.analysis.theory import compass_biped as theory

from mjpoincare import gate
from mjpoincare.cli import main

pytestmark = pytest.mark.mujoco


def test_fast_validation_avoids_scuffing() -> None:
    """Its verdict is the gate's (tests/test_gate.py)."""
    result = gate.case("compass-biped[fast]").run()
    assert result.extras["scuffs_avoided"] > 0  # equal legs do pass through the slope mid-swing ...
    by_name = {c.name: c for c in result.checks}
    assert by_name["swing_foot_contacts"].simulated == 0  # ... but the switched-off foot never touched


def test_constant_torques_move_the_gait_as_the_theory_says() -> None:
    """Ankle and hip torques are MuJoCo actuators switched to the stance leg at each heel strike: the gait they
    give matches the exact actuated model (fast preset tolerances)."""
    result = gate.case("compass-biped[fast,tau_ankle=0.5,tau_hip=0.2]").run()
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
