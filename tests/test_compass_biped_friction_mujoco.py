"""Regression: MuJoCo's compass biped with Coulomb friction against Gamus & Or (2015) Secs. 4-5 (seed 002).

Gaits A (passive, 1 deg, mu = 1), I (constant torques, level ground, mu = 0.2), III (PD tracking of Gait C with
phase reset, fed as native control, level ground, mu = 0.2), B (passive, mu = 0.14, slip+ -> stick -> slip-) and
the unstable C (passive, mu = 0.2) and II (constant torques, mu = 0.2), fitted over their first 2 steps; fast
preset, the scenario's own tolerances. The checks MuJoCo misses are asserted as strict xfails with the
measured error, never with a loosened tolerance.
"""

from __future__ import annotations

from functools import cache

import pytest
from mjpoincare.analysis.checks import Check

from mjpoincare.cli import main
from mjpoincare.result import Result
from mjpoincare.scenarios import compass_biped_friction as sc
from mjpoincare.scenarios import compass_biped_friction_stance as stance
from mjpoincare.validation import resolve_inputs, run_validation

pytestmark = pytest.mark.mujoco


@cache
def _run(gait: str) -> Result:
    return run_validation("compass-biped-friction", {"gait": gait}, "fast")


def _checks(gait: str) -> dict[str, Check]:
    return {c.name: c for c in _run(gait).checks}


def test_gait_a_fixed_point_eigenvalues_and_critical_friction() -> None:
    """Gait A: fixed point, multipliers, step, and mu_c = 0.174918 from MuJoCo's momentum rate (002 Sec. 4.1)."""
    result = _run("a")
    assert result.passed, result.table()
    assert abs(_checks("a")["critical_friction"].analytic - 0.174918) < 1e-6


def test_gait_i_cost_of_transport_speed_and_eigenvalues() -> None:
    """Gait I (E_eff torques as tau_ankle = 1.65, tau_hip = -0.54 N m): c_mt 0.01747, v 0.6342, |lambda|max 0.7148
    (002 Sec. 5, eq 29)."""
    result = _run("i")
    assert result.passed, result.table()
    by_name = _checks("i")
    assert abs(by_name["cost_of_transport"].analytic - 0.01747) < 1e-4
    assert abs(by_name["speed"].analytic - 0.6342) < 1e-4


@pytest.mark.parametrize("gait", ["iii", "b"])
def test_gait_step_and_phases(gait: str) -> None:
    """Gaits III and B: fixed point, step period, length, speed, phase sequence, impact kind (and III's cost)
    within tolerance."""
    by_name = _checks(gait)
    names = ["fixed_point", "step_period", "step_length", "speed", "phase_sequence", "impact_kind"]
    names += ["cost_of_transport", "phase_times"] if gait == "iii" else []
    for name in names:
        assert by_name[name].passed, _run(gait).table()


@pytest.mark.xfail(strict=True, reason="measured: smallest multiplier 0.052 vs 0.087 (error 0.035 > 0.03, fast)")
def test_gait_iii_eigenvalues() -> None:
    """Gait III's 3 largest multipliers (-0.567, 0.313, 0.087; the 4th ~0 is invisible on the legs-parallel
    section where the foot sticks)."""
    assert _checks("iii")["eigenvalues"].passed, _run("iii").table()


@pytest.mark.xfail(strict=True, reason="measured: 0.218 +- 0.717j, 0.443 vs 0.346 +- 0.744j, 0.338 (error 0.131 "
                   "at the fast preset; 0.036 accurate; 0.012 at a 4 us step with a 0.1 ms contact): the soft impact "
                   "(0.19 mm deep, fast) starts the slip+ ~2.5 ms late and the sliding foot rises at ~mu v_t "
                   "(MuJoCo's convex contact); slip+ covers 3.51 mm vs 4.05 (fast), 3.84 (accurate), 3.96 (4 us)")
def test_gait_b_eigenvalues() -> None:
    """Gait B's multipliers (|lambda|max 0.8206, 002 Sec. 4.2), starts inside the sticking-impact border."""
    assert _checks("b")["eigenvalues"].passed, _run("b").table()


def test_gait_b_starts_stay_on_the_sticking_impact_branch() -> None:
    """002's Gait B impact is sticking with |sigma~| = 0.126 against mu = 0.14: the slipping-impact border is
    0.0037 away (rate units), so the starts are kept inside it (the compass-biped size 0.023 straddled it and half
    the trajectories left Gait B)."""
    g = sc.gait(resolve_inputs("compass-biped-friction", {"gait": "b"}, "fast")[2])
    assert 0.003 < sc.impact_border(g) < 0.0045


def test_gait_c_unstable_classified() -> None:
    """Gait C (mu = 0.2, |lambda|max 1.53 > 1, 002 Sec. 4.2): slipping impact, slip+ -> stick, found unstable from
    the first 2 steps of MuJoCo."""
    by_name = _checks("c")
    for name in ("step_period", "step_length", "speed", "phase_sequence", "phase_times", "impact_kind"):
        assert by_name[name].passed, _run("c").table()
    assert max(abs(complex(*v) if isinstance(v, list) else v) for v in _run("c").extras["fit"]["eigenvalues"]) > 1


@pytest.mark.xfail(strict=True, reason="measured: fitted 1.581, -0.002 +- 0.308j vs 1.5305, -0.054 +- 0.285j "
                   "(error 0.057 > 0.03, fast); fixed point off by 0.0091")
def test_gait_c_eigenvalues() -> None:
    """Gait C's 3 largest multipliers."""
    assert _checks("c")["eigenvalues"].passed, _run("c").table()


@pytest.mark.xfail(strict=True, reason="measured: fitted |lambda|max 0.790 vs 1.157, step length +7.1 %, period "
                   "+2.6 % at the fast preset: its 1 ms contact is as long as the 5 ms slip+ after the slipping "
                   "impact (x_dot+ read 0.026 vs 0.084 m/s at 0+); the accurate preset holds it (eigenvalues 0.021)")
def test_gait_ii() -> None:
    """Gait II (tau1 = -0.69, tau2 = 0.12 -> Q = (0.57, 0.12), level ground, mu = 0.2): slipping impact, unstable."""
    assert _run("ii").passed, _run("ii").table()


def test_gait_b_phase_times() -> None:
    """Gait B's phase switches (002: slip+ -> stick 0.0894 s, stick -> slip- 0.7202 s) as the stance-foot speed
    threshold sees them on both sides: 0.0878 s and 0.7309 s for the exact foot (the slip- speed grows slowly, so
    the threshold crosses 10 ms after the switch in the exact model too)."""
    check = _checks("b")["phase_times"]
    assert check.passed, _run("b").table()
    assert check.analytic == pytest.approx([0.0878, 0.7309], abs=2e-4)


def test_exact_steps_read_by_the_simulation_classifier() -> None:
    """The phase labels the checks compare against: the exact foot through the same 5 mm/s detector. Gait B keeps
    002's three phases (switches seen 1.6 ms early and 10.7 ms late); Gait II's 5.2 ms slip+ ends inside the first
    5 ms that the detector skips, so it reads 'stick' (its slipping impact is the impact_kind check's)."""
    p_b = resolve_inputs("compass-biped-friction", {"gait": "b"}, "fast")[2]
    p_ii = resolve_inputs("compass-biped-friction", {"gait": "ii"}, "fast")[2]
    b = stance.classified_pattern(sc.gait(p_b), 1e-4)
    assert [lab for lab, _ in b] == ["slip+", "stick", "slip-"]
    assert [t for _, t in b[1:]] == pytest.approx([0.0878, 0.7309], abs=2e-4)
    assert sc.gait(p_ii).record.phases == ("slip+", "stick")
    assert [lab for lab, _ in stance.classified_pattern(sc.gait(p_ii), 1e-4)] == ["stick"]


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [("mu=-0.1", "mu must be in [0, 1000]"), ("gait=d", "gait must be one of a, b, c, i, ii, iii"),
     ("mu=0.15", "mu must be >= 0.17492"), ("kp=3", "kp, kd apply to gait=iii only")],
)
def test_bad_input(assignment: str, needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "compass-biped-friction", "--set", assignment]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err
