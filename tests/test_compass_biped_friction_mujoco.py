"""Regression: MuJoCo's compass biped with Coulomb friction against Gamus & Or (2015) Secs. 4-5 (002).

Gaits A (passive, 1 deg, mu = 1), I (constant torques, level ground, mu = 0.2), III (PD tracking of Gait C with
phase reset, fed as native control, level ground, mu = 0.2), B (passive, mu = 0.14, slip+ -> stick -> slip-) and
the unstable C (passive, mu = 0.2) and II (constant torques, mu = 0.2), fitted over their first 2 steps; fast
preset, the scenario's own tolerances. The runs' verdicts (and the checks MuJoCo misses, as strict xfails with the
measured error) are the gate's (:func:`mjpoincare.gate.forms.cases`, tests/test_gate.py); this module checks what they
are compared against and how the gaits are classified.
"""

from __future__ import annotations

import pytest
from mjpoincare.analysis.checks import Check
from mjpoincare.analysis.theory.compass_biped_friction import stance_measurements as stance

from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.core.result import Result
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios import compass_biped_friction as sc
from mjpoincare.scenarios.compass_biped_friction import start_design as design

pytestmark = pytest.mark.mujoco


def _run(gait: str) -> Result:
    label = "compass-biped-friction[fast]" if gait == "a" else f"compass-biped-friction[fast,gait={gait}]"
    return gate.run_case(gate.case(label))


def _checks(gait: str) -> dict[str, Check]:
    return {c.name: c for c in _run(gait).checks}


def test_gait_a_critical_friction_reference() -> None:
    """Gait A's mu_c = 0.174918 (002 Sec. 4.1) is the analytic value its MuJoCo check compares against (the run's
    verdicts are the gate's: tests/test_gate.py)."""
    assert abs(_checks("a")["critical_friction"].analytic - 0.174918) < 1e-6


def test_gait_i_references() -> None:
    """Gait I (E_eff torques as tau_ankle = 1.65, tau_hip = -0.54 N m): c_mt 0.01747, v 0.6342, |lambda|max 0.7148
    (002 Sec. 5, eq 29)."""
    by_name = _checks("i")
    assert abs(by_name["cost_of_transport"].analytic - 0.01747) < 1e-4
    assert abs(by_name["speed"].analytic - 0.6342) < 1e-4


def test_gait_b_starts_stay_on_the_sticking_impact_branch() -> None:
    """002's Gait B impact is sticking with |sigma~| = 0.126 against mu = 0.14: the slipping-impact border is
    0.0037 away (rate units), so the starts are kept inside it (the compass-biped size 0.023 straddled it and half
    the trajectories left Gait B)."""
    g = sc.gait(resolve_inputs("compass-biped-friction", {"gait": "b"}, "fast")[2])
    assert 0.003 < design.impact_border(g) < 0.0045


def test_gait_b_phase_times_reference() -> None:
    """Gait B's phase switches as the stance-foot speed threshold reads them from the exact foot, 0.0878 s and
    0.7309 s: what the MuJoCo check compares against. The exact model switches at 0.0894 s (slip+ -> stick) and
    0.7202 s (stick -> slip-), the event-driven solution that the time-stepping scheme confirms
    (tests/test_theory_compass_biped_time_stepping.py); 002 plots them in Fig. 4.2b without printing them. The
    threshold reads the first 1.6 ms early and the second 10.7 ms late (the slip- speed grows slowly)."""
    check = _checks("b")["phase_times"]
    assert check.analytic == pytest.approx([0.0878, 0.7309], abs=2e-4)


def test_gait_c_found_unstable() -> None:
    """Gait C (mu = 0.2, |lambda|max 1.53 > 1, 002 Sec. 4.2): the map fitted from MuJoCo's first 2 steps is unstable
    too (its checks' verdicts are the gate's)."""
    assert max(abs(v) for v in _run("c").fit.eigenvalues) > 1


def test_exact_steps_read_by_the_simulation_classifier() -> None:
    """The phase labels the checks compare against: the exact foot through the same 5 mm/s detector. Gait B keeps
    002's three phases (switches seen 1.6 ms early and 10.7 ms late); Gait II's 5.2 ms slip+ ends inside the first
    5 ms that the detector skips, so it reads 'stick' (that slip is the impact_slip check's)."""
    p_b = resolve_inputs("compass-biped-friction", {"gait": "b"}, "fast")[2]
    p_ii = resolve_inputs("compass-biped-friction", {"gait": "ii"}, "fast")[2]
    b = stance.classified_pattern(sc.gait(p_b), 1e-4)
    assert [lab for lab, _ in b] == ["slip+", "stick", "slip-"]
    assert [t for _, t in b[1:]] == pytest.approx([0.0878, 0.7309], abs=2e-4)
    assert sc.gait(p_ii).record.phases == ("slip+", "stick")
    assert [lab for lab, _ in stance.classified_pattern(sc.gait(p_ii), 1e-4)] == ["stick"]


def test_gait_ii_impact_slip_reference() -> None:
    """Gait II's slip after its slipping impact (002 Sec. 5) ends 5.2 ms after the impact, past the 5 ms window
    that impact_slip compares: the exact foot's slide over that window is all but < 1 um of the whole stance's
    slip (the step record's slip_distance, 0.22 mm)."""
    check = _checks("ii")["impact_slip"]
    record = sc.gait(resolve_inputs("compass-biped-friction", {"gait": "ii"}, "fast")[2]).record
    assert record.phases == ("slip+", "stick") and record.phase_times[1] > stance.RELEASE_SKIP
    assert 0.0 < record.slip_distance - check.analytic < 1e-6


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [("mu=-0.1", "mu must be in [0, 1000]"), ("gait=d", "gait must be one of a, b, c, i, ii, iii"),
     ("mu=0.15", "mu must be >= 0.17492"), ("kp=3", "kp, kd apply to gait=iii only")],
)
def test_bad_input(assignment: str, needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "compass-biped-friction", "--set", assignment]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err
