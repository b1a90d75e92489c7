"""The compass bipeds' step and stance measurements (analysis.theory.compass_biped.step_measurements,
analysis.theory.compass_biped_friction.stance_measurements) on synthetic records whose steps, depths, phases and
slides are known, and the exact-model helpers they lean on (Kiša 2020 Ch. 4; Gamus & Or 2015 eq 27)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.theory import compass_biped as cb
from mjpoincare.analysis.theory import compass_biped_friction as cf
from mjpoincare.analysis.theory.compass_biped.step_measurements import (
    crossing_steps,
    swing_foot_detail,
    swing_foot_report,
)
from mjpoincare.analysis.theory.compass_biped_friction import stance_measurements as st
from scipy.integrate import solve_ivp


def _walk() -> tuple[list[list[np.ndarray]], list[list[float]], list[list[tuple[float, float]]]]:
    """One trajectory: crossings at t = 0.5, 1.5, 2.5, 3.5 with y_k = (k, 0, 0), heel strikes at t = 1, 2, 3 onto
    feet at x = 0.4, 1.0, 1.9 (the first stance foot at 0): steps 0.4, 0.6, 0.9 long."""
    samples = [[np.array([float(k), 0.0, 0.0]) for k in range(4)]]
    times = [[0.5, 1.5, 2.6, 3.5]]
    strikes = [[(1.0, 0.4), (2.0, 1.0), (3.0, 1.9)]]
    return samples, times, strikes


def test_crossing_steps_pairs_each_crossing_with_the_step_its_swing_ends() -> None:
    samples, times, strikes = _walk()
    ys, dts, lengths, works = crossing_steps(samples, times, strikes)
    assert ys[:, 0].tolist() == [0.0, 1.0, 2.0]  # the last crossing has no successor
    assert dts == pytest.approx([1.0, 1.1, 0.9])
    assert lengths == pytest.approx([0.4, 0.6, 0.9])
    assert works.size == 0


def test_crossing_steps_from_a_later_strike_with_the_work_of_each_step() -> None:
    samples, times, strikes = _walk()
    ys, _, lengths, works = crossing_steps(samples, times, strikes, first=1, step_work=[[10.0, 20.0]])
    assert ys[:, 0].tolist() == [1.0]  # crossing 0 precedes strike 0; crossing 2's step has no recorded work
    assert lengths == pytest.approx([0.6])
    assert works.tolist() == [20.0]


def test_crossing_steps_drops_a_crossing_with_no_strike_after_it() -> None:
    samples, times, strikes = _walk()
    _, _, lengths, _ = crossing_steps(samples, times, [strikes[0][:2]])
    assert lengths == pytest.approx([0.4, 0.6])


def test_swing_foot_report_takes_the_deepest_of_every_trajectory() -> None:
    swing_low = [[(-0.002, -1e-5), (-0.001, -2e-5)], [(-0.003, -5e-6)]]
    report = swing_foot_report(swing_low, 0.0021)
    assert report["value"] == pytest.approx(0.003)
    note = str(report["note"])
    assert "run's 3 swings" in note and "from the fixed point 0.002 m" in note and "dips 0.0021 m" in note
    assert "up to 2e-05 m deep" in note


def test_lowest_swing_height_is_the_minimum_of_the_exact_swing() -> None:
    bp = cb.CompassBiped()
    x_star = cb.fixed_point(bp)
    period = cb.step_period(bp, x_star)
    sol = solve_ivp(lambda _t, y: [y[2], y[3], *cb.swing_dynamics(bp, y[:2], y[2:])], (0.0, period), x_star,
                    method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    dense = min(cb.swing_foot_height(bp, sol.sol(t)[:2]) for t in np.linspace(0.0, period, 20001))
    low = cb.lowest_swing_height(bp, x_star)
    assert low < 0.0  # the exact foot passes through the slope mid-swing
    assert low == pytest.approx(dense, abs=1e-9) and low <= dense + 1e-12


def test_swing_foot_detail_scales_the_exact_dip_of_the_same_swing() -> None:
    bp = cb.CompassBiped()
    x_star = cb.fixed_point(bp)
    y_star = cb.legs_parallel_state(bp, x_star)[0]
    exact = -cb.lowest_swing_height(bp, x_star)
    detail = swing_foot_detail(bp, [(-0.002, -1e-4)], [y_star, y_star], 5e-4, exact)
    assert detail["depth"] == [0.002] and detail["depth_below_stance_foot"] == pytest.approx([0.0019])
    assert detail["exact_depth_same_swing"] == pytest.approx([exact * (bp.l - 5e-4) / bp.l], rel=1e-7)


def _reference() -> cf.ReferenceTrajectory:
    t = np.linspace(0.0, 1.0, 11)
    theta = np.column_stack([np.sin(t), t**2])
    theta_dot = np.column_stack([np.cos(t), 2 * t])
    theta_ddot = np.column_stack([-np.sin(t), np.full_like(t, 2.0)])
    return cf.ReferenceTrajectory(t, theta, theta_dot, theta_ddot)


def test_reference_at_is_the_reference_evaluated_point_by_point() -> None:
    ref = _reference()
    phase = np.array([0.0, 0.03, 0.37, 0.5, 0.999, 1.0, 1.4])
    vectorised = np.array(st.reference_at(ref, phase))
    for k, p in enumerate(phase):
        assert vectorised[:, k] == pytest.approx(ref.evaluate(float(p)), abs=1e-12)


def _stance(v: np.ndarray, dt: float = 1e-4) -> dict[str, np.ndarray]:
    t = dt * np.arange(1, v.size + 1)
    return {"t": t, "v_t": v}


def test_phases_merge_flicker_and_skip_the_impact_windows() -> None:
    dt = 1e-4
    v = np.zeros(3000)
    v[:40] = 1.0  # inside the first RELEASE_SKIP: not seen
    v[1000:2000] = 0.02  # slip+ from 0.1 s
    v[1500:1505] = 0.0  # 0.5 ms of flicker, shorter than the shared MERGE_PHASE (1 ms): merged away
    v[1700:1710] = 0.0  # 1 ms, as long as MERGE_PHASE: a phase of its own
    v[2500:] = -0.02  # slip- up to the end
    labels = st.phases(_stance(v, dt), dt)
    assert [lab for lab, _ in labels] == ["stick", "slip+", "stick", "slip+", "stick", "slip-"]
    assert [t for _, t in labels[1:]] == pytest.approx([0.1001, 0.1701, 0.1711, 0.2001, 0.2501])


def test_impact_velocity_is_read_after_the_contact_relaxes() -> None:
    v = np.linspace(1.0, 0.0, 1000)
    stance = _stance(v)
    i = int(np.searchsorted(stance["t"], st.IMPACT_TIMECONSTS * 1e-3))
    assert st.impact_velocity(stance, 1e-3) == v[i]


def test_impact_slip_from_the_touchdown() -> None:
    dt = 1e-4
    t = dt * np.arange(1, 201)
    height = 1e-3 - 0.1 * t  # crosses 0 at t = 0.01
    x = 0.5 * t  # slides at 0.5 m/s
    assert st.impact_slip({"t": t, "height": height, "x": x}) == pytest.approx(0.5 * st.RELEASE_SKIP, rel=1e-9)


def test_stance_rows_of_a_biped_at_rest() -> None:
    """Standing still on the stance foot with the legs fixed: no slip, zero height, f_t/f_n = tan(slope)."""
    bp = cf.FrictionBiped(slope=0.05, mu=1.0)
    radius = 5e-4
    n = 50
    t = 1e-3 * np.arange(n)
    q = np.full(n, 0.1)
    lever = bp.l - radius
    rows = np.column_stack([t, np.zeros(n), lever * np.sin(q), lever * np.cos(q) + radius, q, -q,
                            np.zeros((n, 4))])
    (stance,) = st.stance_rows(rows, [1.0], bp, radius)
    assert stance["t"].size == n - 1  # rows strictly after the start
    assert np.abs(stance["v_t"]).max() == 0.0 and np.abs(stance["height"]).max() < 1e-15
    assert stance["ratio"] == pytest.approx(-math.tan(bp.slope))
    assert stance["x"] == pytest.approx(0.0, abs=1e-15)


def test_legs_parallel_is_where_the_hinges_meet_on_the_way_up() -> None:
    g = cf.paper_gait("A", math.inf)
    y, t = cf.legs_parallel(g)
    r = cf.reference_trajectory(g.biped, g.z, g.actuation, samples=2001).evaluate(t)
    assert r[0] + r[1] == pytest.approx(0.0, abs=1e-12) and r[2] + r[3] > 0.0  # theta1 + theta2 rises through 0
    assert y == pytest.approx([r[0], r[2], -r[3]], abs=0.0)
    assert 0.0 < t < g.record.period
