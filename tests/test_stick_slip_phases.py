"""analysis.stick_slip_phases on synthetic stances whose contact modes, phases and gait types are known."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest
from mjpoincare.analysis import stick_slip_phases as phases
from mjpoincare.analysis.contact_modes import EXCLUDED, SLIP_NEG, SLIP_POS, STICK
from mjpoincare.analysis.stick_slip_phases import Classifier, Rows, Runs, Steps

PHI, DT, N = 0.3, 1e-4, 400  # half step angle (rad), row spacing (s), rows per stance
MU, V_THR = 0.5, 0.01
STANCE_FRICTION = -0.1  # f_t/f_n of a sticking row: well inside the cone

Pattern = Callable[[np.ndarray, np.ndarray], np.ndarray]


def classifier(batch: int = 1) -> Classifier:
    return Classifier(mu=np.full(batch, MU), v_thr=V_THR, impact_window=5 * DT)


def synthetic(slipping: Pattern, slip_speed: Pattern, *, stances: int = 6, rate: np.ndarray | None = None,
              clearance: np.ndarray | None = None) -> Rows:
    """One trajectory rolling forward over ``stances`` steps of N rows: theta from -phi to phi in each, the stance
    foot sliding forward (friction on the cone, speed ``slip_speed``) where ``slipping(step, u)`` with u the
    fraction of the stance, sticking elsewhere."""
    k = np.arange(stances * N + 1)
    j, u = k // N, (k % N) / N
    sl = slipping(j, u)
    rows = {"time": k * DT, "theta": -PHI + 2 * PHI * u, "slip": np.where(sl, slip_speed(j, u), 0.0),
            "force_t": np.where(sl, -MU, STANCE_FRICTION), "force_n": np.ones(k.size),
            "rate": np.ones(k.size) if rate is None else rate, "clearance": np.zeros(k.size) if clearance is None
            else clearance}
    return phases.stance_rows(**{name: v[None, :] for name, v in rows.items()}, half_step=PHI, timestep=DT,
                              weight=1.0, cls=classifier())


def table(rows: Rows) -> Steps:
    return phases.step_table(rows, classifier(), 8, backward_rate=-0.01, flight_clearance=1e-3)


def b_gait(j: np.ndarray, u: np.ndarray) -> np.ndarray:
    return u >= 0.7  # stick, then slip from theta = 0.4 phi on


def constant(speed: float) -> Pattern:
    return lambda j, u: np.full(u.shape, speed)


def bare_rows(mode: np.ndarray, stance: np.ndarray, theta: np.ndarray) -> Rows:
    z = np.zeros(mode.shape)
    return Rows(time=z, theta=theta, rate=z, slip=z, clearance=z, ratio=z, force_t=z, force_n=z, stance=stance,
                since=z, wrap=z.astype(bool), mode=mode, vmode=mode)


def bare_steps(kind: list[str], mid_rate: list[float] | None = None, failure: str = "", failure_step: int = -1
               ) -> Steps:
    """One trajectory's step table: every step with a type is complete."""
    k = np.array([kind], dtype=str)
    nan = np.full(k.shape, np.nan)
    empty = np.zeros(0, int)
    return Steps(mid_rate=nan if mid_rate is None else np.array([mid_rate], float), mid_slip=nan, post_slip=nan,
                 impact_slipping=np.zeros(k.shape, bool), impulse_ratio=nan, slip_rows=nan, stick_rows=nan,
                 onset=nan, kind=k, complete=k != "", failure=np.array([failure]),
                 failure_step=np.array([failure_step]), vkind=k, runs=Runs(empty, empty, empty, empty, empty))


def test_window_sum_is_centred_and_kept_inside_the_rows() -> None:
    x = np.random.default_rng(0).normal(size=(2, 13))
    for width in (2, 3, 4):
        starts = [max(0, i - width // 2) for i in range(13)]  # shifted right at the start, cut short at the end
        expected = np.array([[row[lo: lo + width].sum() for lo in starts] for row in x])
        np.testing.assert_allclose(phases.window_sum(x, width), expected, atol=1e-12)
    same = phases.window_sum(x, 1)
    np.testing.assert_array_equal(same, x)
    assert same is not x


def test_stance_rows_transfers_modes_and_impact_windows() -> None:
    rows = synthetic(b_gait, constant(0.1), stances=3)
    k = np.arange(rows.theta.shape[1])
    np.testing.assert_array_equal(rows.stance[0], np.minimum(k // N, 3))
    np.testing.assert_array_equal(np.nonzero(rows.wrap[0])[0], [N - 1, 2 * N - 1, 3 * N - 1])
    np.testing.assert_allclose(rows.since[0, N + 7], 7 * DT, rtol=1e-9)
    mode = rows.mode[0]
    assert (mode[N - 1] == EXCLUDED) and (mode[N: N + 5] == EXCLUDED).all()  # the transfer and its impact window
    assert (mode[N + 10: N + 270] == STICK).all()
    assert (mode[N + 290: 2 * N - 10] == SLIP_POS).all()  # friction on the cone, foot sliding forward
    np.testing.assert_allclose(rows.ratio[0, N + 100], STANCE_FRICTION)
    assert (rows.vmode[0, N + 290: 2 * N - 10] == SLIP_POS).all()


def test_stance_rows_backward_friction_and_lost_contact() -> None:
    k = np.arange(N + 1)
    u = (k % N) / N
    f_n = np.where((u > 0.2) & (u < 0.3), 0.0, 1.0)  # a hop: no normal force
    rows = phases.stance_rows(time=k[None] * DT, theta=(-PHI + 2 * PHI * u)[None], rate=np.ones((1, k.size)),
                              slip=np.full((1, k.size), -0.1), clearance=np.zeros((1, k.size)),
                              force_t=(MU * f_n)[None], force_n=f_n[None], half_step=PHI, timestep=DT, weight=1.0,
                              cls=classifier())
    assert (rows.mode[0, 100:110] == EXCLUDED).all() and np.isnan(rows.ratio[0, 100:110]).all()
    assert (rows.mode[0, 150:250] == SLIP_NEG).all() and (rows.vmode[0, 150:250] == SLIP_NEG).all()


def test_phase_runs_merge_flicker() -> None:
    s, p, n, x = STICK, SLIP_POS, SLIP_NEG, EXCLUDED
    mode = np.array([[x] * 3 + [s] * 20 + [n] * 3 + [p] * 20 + [s] * 3 + [p] * 30 + [x] * 4 + [p] * 3 + [s] * 30 + [x]],
                    np.int8)
    stance = np.array([[0] * 79 + [1] * 38])
    theta = np.arange(mode.size, dtype=float)[None] * 0.01
    runs = phases.phase_runs(bare_rows(mode, stance, theta), np.ones(mode.shape, bool), DT, merge_phase=1e-3)
    # stance 0: runs shorter than 1 ms (10 rows) join the phase before them; stance 1 starts with a short slip run,
    # which joins the stick phase after it
    names, starts = phases.phase_sequence(runs, 0, 0)
    assert names == ("stick", "slip+") and starts == pytest.approx((0.03, 0.26))
    names, starts = phases.phase_sequence(runs, 0, 1)
    assert names == ("stick",) and starts == pytest.approx((0.83,))
    unmerged = phases.phase_runs(bare_rows(mode, stance, theta), np.ones(mode.shape, bool), DT, merge_phase=1e-4)
    assert list(unmerged.mode) == [s, n, p, s, p, p, s]


@pytest.mark.parametrize(("slipping", "speed", "kind", "sequence"), [
    (lambda j, u: np.zeros(u.shape, bool), constant(0.1), "A", ("stick",)),
    (b_gait, constant(0.1), "B", ("stick", "slip+")),
    (lambda j, u: (u < 0.2) | (u >= 0.7), constant(0.1), "C", ("slip+", "stick", "slip+")),
    (lambda j, u: np.ones(u.shape, bool), lambda j, u: 0.05 + 0.01 * j, "D+", ("slip+",)),
    (lambda j, u: np.ones(u.shape, bool), lambda j, u: 0.1 - 0.01 * j, "D-", ("slip+",)),
])
def test_step_table_gait_types(slipping: Pattern, speed: Pattern, kind: str, sequence: tuple[str, ...]) -> None:
    steps = table(synthetic(slipping, speed))
    assert steps.complete[0, :5].all() and not steps.complete[0, 5:].any()  # the sixth has no next post-impact row
    assert list(steps.kind[0, :5]) == [kind] * 5
    assert steps.failure[0] == "" and phases.outcome(steps, 0) == kind
    assert phases.phase_sequence(steps.runs, 0, 2)[0] == sequence
    np.testing.assert_allclose(steps.mid_rate[0, :6], 1.0)
    assert bool(steps.impact_slipping[0, 0]) == (kind[0] in "CD")


def test_step_table_slip_onset_and_velocity_only_type() -> None:
    steps = table(synthetic(b_gait, constant(0.1)))
    # friction reaches the cone at theta = 0.4 phi; the 1 ms force window delays it by half a window (5 rows)
    np.testing.assert_allclose(steps.onset[0, :5], 0.4 * PHI + 5 * 2 * PHI / N, atol=1e-9)
    c_gait = table(synthetic(lambda j, u: (u < 0.2) | (u >= 0.7), constant(0.1)))  # the last slip phase's onset
    np.testing.assert_allclose(c_gait.onset[0, :5], 0.4 * PHI + 5 * 2 * PHI / N, atol=1e-9)
    creeping = table(synthetic(b_gait, constant(0.2 * V_THR)))  # the slip is slower than v_thr
    assert phases.outcome(creeping, 0) == "B" and phases.outcome(creeping, 0, velocity_only=True) == "A"


@pytest.mark.parametrize(("fault", "failure"), [("rate", "backward"), ("clearance", "detached")])
def test_step_table_failures(fault: str, failure: str) -> None:
    k = np.arange(6 * N + 1)
    bad = np.where(k >= 3 * N + 100, 1.0, 0.0)
    rows = synthetic(b_gait, constant(0.1), rate=1.0 - 1.5 * bad) if fault == "rate" else \
        synthetic(b_gait, constant(0.1), clearance=0.01 * bad)
    steps = table(rows)
    assert steps.failure[0] == failure and steps.failure_step[0] == 3
    assert phases.outcome(steps, 0) == failure
    assert list(np.nonzero(steps.complete[0])[0]) == [0, 1, 2]  # nothing after the failing row counts


def test_gait_types_table() -> None:
    t, f = True, False
    complete = np.array([[t, t, t, t, t, t, f]])
    impact = np.array([[f, f, t, t, t, t, f]])
    slip = np.array([[f, t, t, t, t, t, f]])
    stick = np.array([[t, t, t, f, f, f, t]])
    dx = np.array([[0.0, 0.0, 0.0, 0.1, -0.1, 0.0, 0.0]])
    assert list(phases.gait_types(complete, impact, slip, stick, dx)[0]) == ["A", "B", "C", "D+", "D-", "D-", ""]


def test_settled_steps_stop_at_the_failure() -> None:
    steps = bare_steps(["A"] * 8 + ["", ""])
    np.testing.assert_array_equal(phases.settled_steps(steps, 0, 5), [4, 5, 6, 7])  # at most the second half
    np.testing.assert_array_equal(phases.settled_steps(steps, 0, 2), [6, 7])
    failed = bare_steps(["A"] * 8 + ["", ""], failure="detached", failure_step=6)
    np.testing.assert_array_equal(phases.settled_steps(failed, 0, 5), [3, 4, 5])
    assert phases.settled_steps(bare_steps([""] * 4), 0, 5).size == 0


def test_settled_rows_are_the_contact_rows_of_settled_steps_of_the_type() -> None:
    steps = bare_steps(["B", "A", "A", "B", "A", "A", ""])
    stance = np.repeat(np.arange(7), 4)[None]
    mode = np.tile(np.array([EXCLUDED, STICK, STICK, SLIP_POS], np.int8), 7)[None]
    rows = bare_rows(mode, stance, np.zeros(stance.shape))
    mask = phases.settled_rows(rows, steps, [0], "A", 5)  # settled: steps 3, 4, 5; of type A: 4, 5
    np.testing.assert_array_equal(np.nonzero(mask[0])[0], [17, 18, 19, 21, 22, 23])


def test_midstance_pairs_keep_consecutive_steps_of_the_type() -> None:
    rate = [1.0, 2.0, 3.0, 4.0, np.nan, 6.0, 7.0, 8.0, 9.0]
    steps = bare_steps(["D-", "C", "C", "C", "C", "C", "C", "D-", "C"], rate)
    x, y = phases.midstance_pairs(steps, [0], "C", 12)
    np.testing.assert_array_equal(np.c_[x, y], [[2.0, 3.0], [3.0, 4.0], [6.0, 7.0]])
    x, _ = phases.midstance_pairs(steps, [0], "C", 2)
    np.testing.assert_array_equal(x[:, 0], [2.0, 3.0])
    failed = bare_steps(["C"] * 9, rate, failure="backward", failure_step=3)
    np.testing.assert_array_equal(phases.midstance_pairs(failed, [0], "C", 12)[0][:, 0], [1.0, 2.0])


def test_steps_to_converge() -> None:
    rate = np.array([1.5, 1.2, 1.05, 1.01, 1.0, 1.0])
    assert phases.steps_to_converge(rate, np.array(["A"] * 6), "A", 0.02) == 3
    assert phases.steps_to_converge(rate, np.array(["A"] * 4 + ["B", "A"]), "A", 0.02) == 5
    assert phases.steps_to_converge(rate, np.array(["A"] * 6), "A", 0.6) == 0
    assert phases.steps_to_converge(rate, np.array(["A"] * 6), "", 0.02) == -1
    assert phases.steps_to_converge(np.array([1.0, np.nan]), np.array(["A"] * 2), "A", 0.02) == -1


def test_creep_counts_stick_rows_of_trajectories_that_did_not_fail() -> None:
    rows = bare_rows(np.array([[STICK, STICK, STICK, SLIP_POS], [STICK] * 4], np.int8), np.zeros((2, 4), int),
                     np.zeros((2, 4)))
    rows.slip = np.array([[1e-3, -2e-3, 3e-3, 0.5], [9.0] * 4])
    steps = bare_steps(["A"])
    steps.failure = np.array(["", "backward"])
    c = phases.creep(rows, steps)
    assert c["median"] == pytest.approx(2e-3) and c["max"] == pytest.approx(3e-3)


def test_step_report_pads_a_short_reference() -> None:
    steps = table(synthetic(b_gait, constant(0.1)))
    report = phases.step_report(steps, 0, np.array(["B", "B"]), np.array([1.0, 1.0]))
    assert [r["step"] for r in report] == [1, 2, 3, 4, 5]
    assert [r["reference_kind"] for r in report] == ["B", "B", "", "", ""]
    assert np.isnan(report[2]["reference_mid_rate"]) and report[0]["phases"] == ["stick", "slip+"]
    assert all(r["impact"] == "sticking" for r in report)


def test_fit_midstance_map_recovers_a_linear_map() -> None:
    """theta_dot_k+1 = 1 + 0.5 (theta_dot_k - 1) along the C steps: fixed point 1, multiplier 0.5."""
    rate = [1.0 + 0.4 * 0.5**k for k in range(10)]
    fit, x, x_next = phases.fit_midstance_map(bare_steps(["C"] * 10, rate), [0], "C", 12, seed=0)
    np.testing.assert_allclose(x_next, 1.0 + 0.5 * (x - 1.0))
    assert x.shape == (9,)
    assert float(fit.fixed_point[0]) == pytest.approx(1.0)
    assert float(np.real(fit.eigenvalues[0])) == pytest.approx(0.5)
