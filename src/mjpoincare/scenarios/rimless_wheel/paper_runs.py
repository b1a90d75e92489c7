"""Dedicated MuJoCo experiments for the results of 003 (Kisa 2020, Sec. 3) the scenario's validation does not run: the
regions of Table 1 / Fig. 14, the existence bound (3.16), the gamma > alpha branch of (3.14), the standing multiplier
(Thm 3.10) and the trajectories of Figs. 5, 6, 12 and 13 (:mod:`mjpoincare.scenarios.paper_results`).

Every run builds the scenario's model (:func:`mjpoincare.scenarios.rimless_wheel.build`) at the preset's settings and
rolls a batch of starts natively (:func:`mjpoincare.simulation.simulate.rollout_batch`); the validation's parameter
check is not applied, because these slopes are the ones it refuses (below the existence bound, above the no-flight
bound). Post-impact speeds are read off the recorded trajectories: over each stance between support transfers (wraps of
the stance angle), every state at least :data:`SETTLE` seconds from either transfer is pulled back to the impact along
the exact sticking stance flow (003 eqs 3.3-3.5) and the median taken, so the soft impact's transient (the pitch rate
rings for ~20 ms after it) does not enter the reading.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import mujoco
import numpy as np

from mjpoincare.analysis.sections import wrap_events, wrap_phase
from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.analysis.theory.rimless_wheel.basins import basin_band_edges
from mjpoincare.analysis.theory.rimless_wheel.figures import existence_bound_curve, figure_sequence
from mjpoincare.core.params import Values
from mjpoincare.core.seam import Chunk
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import JointIndex
from mjpoincare.scenarios.paper_results import Reading, Runner, bisect
from mjpoincare.scenarios.rimless_wheel.runs import (
    FLIGHT_CLEARANCE,
    chunk_steps,
    post_impact_states,
    wheel,
)
from mjpoincare.simulation.simulate import initial_states, rollout_batch

#: Seconds after a support transfer (and before the next) left out of the post-impact speed's reading: the soft
#: impact's transient in the pitch rate.
SETTLE = 0.02
#: Final window (s) over which a run's end state is judged.
WINDOW = 1.0
#: |omega| below which the final window is standing, as a fraction of the largest |omega| the run had: the Zeno
#: rocking of 003 Sec. 3.3 has died out.
REST_FRACTION = 0.02


@dataclass(frozen=True)
class Runs:
    """A batch's recorded trajectories: time, wrapped stance angle psi (stance spoke from the slope normal), pitch rate
    omega and the lowest foot's clearance, each (B, T); ``w`` the analytic wheel of the model."""

    w: theory.RimlessWheel
    time: np.ndarray
    psi: np.ndarray
    omega: np.ndarray
    clearance: np.ndarray

    def post_impact_speeds(self, row: int) -> np.ndarray:
        """Trajectory ``row``'s post-impact speeds: over each stance between support transfers, every state from
        SETTLE s after the transfer to SETTLE s before the next one pulled back to the impact angle gamma -+ alpha by
        the energy integral omega+^2 = omega^2 + 2 rate2 (cos theta - cos theta+) (003 eq 3.5), their median, with the
        step's direction as sign (a plastic impact keeps it, 003 eq 3.11). A stance too short for the window (the
        Zeno tail of a rocking wheel) reads nothing; a transfer in the first step (a start at psi = +alpha, which
        the wrap puts at -alpha) is none."""
        w = self.w
        events = wrap_events(self.time[row:row + 1], self.psi[row:row + 1], w.alpha)
        first = events.time > self.time[row, 1]  # a start on the uphill spoke (psi = +alpha) wraps at once
        t, sign = events.time[first], events.values[first, 0]
        ends = np.append(t[1:], self.time[row, -1] + SETTLE)
        out = []
        for k in range(len(t)):
            keep = (self.time[row] >= t[k] + SETTLE) & (self.time[row] <= ends[k] - SETTLE)
            if not keep.any():
                continue
            theta = self.psi[row, keep] + w.slope
            theta_post = w.slope - sign[k] * w.alpha
            sq = self.omega[row, keep] ** 2 + 2.0 * w.rate2 * (np.cos(theta) - math.cos(theta_post))
            out.append(sign[k] * math.sqrt(max(float(np.median(sq)), 0.0)))
        return np.asarray(out)

    def end_state(self, row: int) -> str:
        """Trajectory ``row``'s end state over the last WINDOW: ``flight`` (all feet a centimetre up at some time
        in it), ``standing`` (|omega| below REST_FRACTION of the run's largest), ``rolling`` (omega > 0 throughout)
        or ``rocking``."""
        last = self.time[row] >= self.time[row, -1] - WINDOW
        if np.max(self.clearance[row, last]) > FLIGHT_CLEARANCE * self.w.leg_length:
            return "flight"
        if np.max(np.abs(self.omega[row, last])) < REST_FRACTION * np.max(np.abs(self.omega[row])):
            return "standing"
        return "rolling" if np.all(self.omega[row, last] > 0) else "rocking"

    def highest_flight(self, row: int) -> float:
        """The largest height (m) of the lowest foot above the slope over trajectory ``row``: the wheel flew if it is
        above FLIGHT_CLEARANCE x leg_length."""
        return float(np.max(self.clearance[row]))


def setup(runner: Runner, spokes: int, slope: float, mu: float | None = None
          ) -> tuple[Values, Values, theory.RimlessWheel]:
    """The scenario's parameters at ``spokes``, ``slope`` and ``mu`` (the rest its defaults; not the scenario's
    cross-checks, which refuse these slopes), the runner's preset settings and the analytic wheel of the model (hub
    gyration raised as the scenario's model has it)."""
    values = {"spokes": str(spokes), "slope": repr(float(slope))} | ({} if mu is None else {"mu": repr(float(mu))})
    params, settings = runner.inputs(values, checked=False)
    return params, settings, wheel(params)


def _roll(runner: Runner, params: Values, settings: Values, w: theory.RimlessWheel,
          make_states: Callable[[mujoco.MjModel, float], np.ndarray], seconds: float) -> Runs:
    """Build the scenario's model, make the starts with ``make_states(model, foot_radius)`` and roll them for
    ``seconds``, recording every state."""
    model = runner.build(params, settings)
    radius = float(settings["foot_radius"])
    states = make_states(model, radius)
    chunks: list[Chunk] = []
    steps = chunk_steps(model) * max(1, math.ceil(seconds / (chunk_steps(model) * model.opt.timestep)))
    rollout_batch(model, states, steps, chunks.append, **rollout_options(settings), chunk_steps=chunk_steps(model))
    cat = [chunks[0]] + [Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]) for c in chunks[1:]]
    time = np.concatenate([c.time for c in cat], axis=1)
    qpos = np.concatenate([c.qpos for c in cat], axis=1)
    qvel = np.concatenate([c.qvel for c in cat], axis=1)
    pitch, z = JointIndex.of(model, "pitch"), JointIndex.of(model, "z")
    psi = wrap_phase(qpos[:, :, pitch.qpos], w.alpha)
    clearance = qpos[:, :, z.qpos] - (w.leg_length - radius) * np.cos(psi) - radius
    return Runs(w=w, time=time, psi=psi, omega=qvel[:, :, pitch.dof], clearance=clearance)


def roll_post_impact(runner: Runner, spokes: int, slope: float, omega0: np.ndarray, seconds: float,
                     mu: float | None = None) -> Runs:
    """Starts just after an impact with post-impact speeds ``omega0`` (the map's section, 003 Sec. 3.2)."""
    params, settings, w = setup(runner, spokes, slope, mu)
    return _roll(runner, params, settings, w,
                 lambda model, r: post_impact_states(model, w, np.asarray(omega0, float), r), seconds)


def roll_mid_swing(runner: Runner, spokes: int, slope: float, theta0: float, omega0: float, seconds: float) -> Runs:
    """One start at the mid-swing state (theta(0), theta_dot(0)) of 003 Figs. 5, 6, 12, 13: the stance spoke at
    theta from the vertical (psi = theta - gamma from the slope normal), its foot on the slope, the hub rotating
    about it."""
    params, settings, w = setup(runner, spokes, slope)

    def states(model: mujoco.MjModel, radius: float) -> np.ndarray:
        psi, l = theta0 - w.slope, w.leg_length
        qpos = np.array([[0.0, (l - radius) * math.cos(psi) + radius, psi]])
        qvel = np.array([[l * omega0 * math.cos(psi), -l * omega0 * math.sin(psi), omega0]])
        return initial_states(model, qpos, qvel)

    return _roll(runner, params, settings, w, states, seconds)


# --- the experiments ------------------------------------------------------------------------------------------------
SPOKES = 8  # alpha = pi/8, the wheel of every figure of 003 Sec. 3
#: The mid-swing starts of 003's phase plots: figure -> (slope gamma, theta(0), theta_dot(0)), as the captions state.
FIGURE_STARTS: dict[str, tuple[float, float, float]] = {
    "5": (0.025, -0.132, 2.0), "6": (math.pi / 7, 0.292, 5.0),
    "12": (math.pi / 15, -0.105, -5.0), "13": (math.pi / 15, -0.105, -4.85)}
FIGURE_SECONDS = 10.0  # Fig. 12's approach to omega*: 20 steps of 0.42 s leave 0.5^20 of the offset
REGION_SECONDS = 10.0  # every start of the region runs settles (stands or rolls within 1e-3 of omega*) by then
#: Relative tolerance of the located existence bound (Fig. 14, eq 3.16); the bisection stops at a quarter of it.
CURVE_TOLERANCE = 0.03
BOUND_START = 1.5  # the existence-bound runs start at this multiple of omega_f, above any rolling fixed point's basin


def _observed(runs: Runs, row: int, star: float, tolerance: float) -> tuple[str, bool]:
    """A run's end state for the region tables, with the last post-impact speed where it rolls, and whether a rolling
    end state sits on the rolling fixed point (relative ``tolerance``)."""
    state = runs.end_state(row)
    if state != "rolling":
        return state, True
    last = float(runs.post_impact_speeds(row)[-1])
    return f"rolling {last:.4f}", abs(last / star - 1.0) <= tolerance


def outcomes_reading(runner: Runner, slope: float, omega0: list[float]) -> Reading:
    """003 Table 1 at one slope: each post-impact start's end state in MuJoCo (standing, rolling onto omega*_roll,
    or flight) against the one the theory's region gives it (:func:`theory.predicted_outcome`: R_A of each fixed
    point, eqs 3.17-3.18 in Ω5). Error: the starts whose end state differs, or whose rolling misses omega*_roll by
    more than the scenario's omega_post_impact tolerance."""
    runs = roll_post_impact(runner, SPOKES, slope, np.asarray(omega0), REGION_SECONDS)
    w = runs.w
    star = theory.rolling_fixed_point(w)
    tol = runner.tolerance("omega_post_impact")
    predicted = [theory.predicted_outcome(w, om) for om in omega0]
    observed = [_observed(runs, i, star, tol) for i in range(len(omega0))]
    wrong = sum(not (o.split()[0] == p and ok) for p, (o, ok) in zip(predicted, observed, strict=True))
    flew = max(runs.highest_flight(i) for i in range(len(omega0)))
    return Reading(analytic=predicted, mujoco=[o for o, _ in observed], error=float(wrong), tolerance=0.0,
                   kind="count", detail=f"region {theory.region(w)} (gamma {slope:.5g}, n {SPOKES}); starts omega+ "
                   f"{', '.join(f'{om:.4g}' for om in omega0)}; omega*_roll {star:.5g}; highest flight {flew:.3g} m")


def region_1(runner: Runner) -> Reading:
    """003 Table 1, Ω1 (gamma > alpha, Fig. 6's slope pi/7): every start rolls onto omega*_roll (R_A = R)."""
    return outcomes_reading(runner, math.pi / 7, [0.2, 1.0, -0.5, -1.5])


def region_2(runner: Runner) -> Reading:
    """003 Table 1, Ω2 (gamma = alpha = pi/8): every start off 0 rolls onto omega*_roll (R_A = R minus {0})."""
    return outcomes_reading(runner, math.pi / SPOKES, [0.2, 1.0, -0.5, -1.5])


def region_3(runner: Runner) -> Reading:
    """003 Table 1, Ω3 (Fig. 5's slope 0.025): every start stands (R_A(omega*_stop) = R minus H), on both branches
    and both sides of omega_f and omega_b."""
    w = setup(runner, SPOKES, 0.025)[2]
    omega_f, omega_b = theory.forward_threshold(w), theory.backward_threshold(w)
    return outcomes_reading(runner, 0.025, [0.5 * omega_f, 1.3 * omega_f, 2.0 * omega_f, 0.5 * omega_b,
                                            1.5 * omega_b])


def region_5(runner: Runner) -> Reading:
    """003 Table 1, Ω5 (Figs. 11-13's slope pi/15): one start in each basin band of (3.17)-(3.18) next to the origin:
    (0, omega_f) and (omega_2^0, 0) stand, above omega_f rolls, I^0_roll rolls, I^1_stop stands, I^1_roll rolls."""
    slope = math.pi / 15
    w = setup(runner, SPOKES, slope)[2]
    omega1, omega2 = basin_band_edges(w, 2)
    omega_f, star = theory.forward_threshold(w), theory.rolling_fixed_point(w)
    starts = [0.5 * omega_f, 1.2 * star, 0.5 * omega2[0], 0.5 * (omega1[0] + omega2[0]), 0.5 * (omega2[1] + omega1[0]),
              0.5 * (omega1[1] + omega2[1])]
    return outcomes_reading(runner, slope, [float(s) for s in starts])


def region_4(runner: Runner) -> Reading:
    """003 Table 1, Ω4 (gamma = gamma*(alpha), on the curve of Fig. 14): no rolling fixed point, a semistable ghost at
    omega_f (R_A = (omega_f, inf) minus H): from above omega_f the post-impact speed falls towards omega_f and stays
    above it. MuJoCo's value: the lowest forward post-impact speed of a run from BOUND_START omega_f (before the run
    ends or its wheel rocks back), against omega_f; relative error, the scenario's omega_post_impact tolerance."""
    slope = existence_bound(runner)
    w = setup(runner, SPOKES, slope)[2]
    omega_f = theory.forward_threshold(w)
    runs = roll_post_impact(runner, SPOKES, slope, np.array([BOUND_START * omega_f]),
                            bound_seconds(runner, SPOKES))
    post = runs.post_impact_speeds(0)
    forward = post[: int(np.argmax(post < 0))] if np.any(post < 0) else post
    low = float(np.min(forward))
    return Reading(analytic=omega_f, mujoco=low, error=abs(low / omega_f - 1.0),
                   tolerance=runner.tolerance("omega_post_impact"), kind="rel",
                   detail=f"gamma* {slope:.6g} rad; {len(forward)} forward impacts, then "
                   f"{'a rock back' if np.any(post < 0) else 'the run ends'} ({runs.end_state(0)} at the end)")


def bound_seconds(runner: Runner, spokes: int) -> float:
    """How long an existence-bound run lasts: twice the theory's time for a wheel started at BOUND_START omega_f to
    fall through omega_f at gamma*(1 - CURVE_TOLERANCE/8), half the bisection's last step below the bound (the ghost
    of the rolling fixed point at omega_f slows the fall the nearer the bound: 11 s at n = 8, 82 s at n = 20)."""
    w = setup(runner, spokes, existence_bound(runner, spokes) * (1.0 - CURVE_TOLERANCE / 8))[2]
    omega_f = theory.forward_threshold(w)
    omega, seconds = BOUND_START * omega_f, 0.0
    while omega > omega_f:
        seconds += theory.step_period(w, omega)
        omega = float(theory.return_map(w, omega))
    return 2.0 * seconds


def no_rolling_cycle(slope: float, runner: Runner, spokes: int = SPOKES) -> bool:
    """Whether MuJoCo's wheel at ``slope`` has no rolling cycle: started above omega_f (BOUND_START omega_f), it rolls
    back within :func:`bound_seconds` (a forward step failed: the speed fell through omega_f, 003 eq 3.16)."""
    w = setup(runner, spokes, slope)[2]
    runs = roll_post_impact(runner, spokes, slope, np.array([BOUND_START * theory.forward_threshold(w)]),
                            bound_seconds(runner, spokes))
    return bool(np.any(runs.omega[0] < 0))


def existence_bound(runner: Runner, spokes: int = SPOKES) -> float:
    """The theory's existence bound gamma* (003 eq 3.16 generalised, 002 eq 18) for the scenario's model at its
    defaults and ``spokes``."""
    w = setup(runner, spokes, 0.05)[2]
    return theory.existence_bound(spokes, w.gyration, w.leg_length, w.gravity)


def fig14_point(alpha: float, runner: Runner) -> Reading:
    """003 Fig. 14: the Ω4 curve gamma*(alpha) at alpha = pi/n, located in MuJoCo by bisection (:func:`bisect`) of
    :func:`no_rolling_cycle` on [0.8, 1.25] gamma*; relative error, its spread the final bracket's half-width."""
    spokes = round(math.pi / alpha)
    star = existence_bound(runner, spokes)
    low, high, runs = bisect(lambda g: no_rolling_cycle(g, runner, spokes), 0.8 * star, 1.25 * star,
                             CURVE_TOLERANCE * star / 4)
    located = 0.5 * (low + high)
    return Reading(analytic=star, mujoco=located, error=abs(located / star - 1.0), tolerance=CURVE_TOLERANCE,
                   kind="rel", spread=0.5 * (high - low), detail=f"n {spokes}: bracket [{low:.6g}, {high:.6g}] rad "
                   f"after {runs} runs")


def fig14_curve(alphas: np.ndarray, runner: Runner) -> np.ndarray:
    """The theory's Ω4 curve gamma*(alpha) of 003 Fig. 14 (at the model's hub gyration, raised to MIN_GYRATION l)."""
    kappa = setup(runner, SPOKES, 0.05)[2].kappa
    return np.array([existence_bound_curve(float(a), kappa) for a in np.atleast_1d(alphas)])


#: gamma > alpha at 12 spokes: slope 2 alpha, where a backward step between omega_b and -sqrt(K) stays in contact.
STEEP_SPOKES, STEEP_SLOPE = 12, math.pi / 6


def steep_branch(runner: Runner) -> Reading:
    """003 eq (3.14), gamma > alpha: three starts between omega_b (3.7) and -sqrt(K) (at 1/4, 1/2, 3/4 of the way in
    omega^2). The corrected map has each complete a backward step, P = -beta sqrt(omega^2 - K) < 0; (3.14) as printed
    has it rock back, -beta omega > 0. MuJoCo's value: the first post-impact speed of each; max-abs error against the
    corrected map, tolerance the scenario's omega_post_impact one times the speed scale sqrt(K)."""
    w = setup(runner, STEEP_SPOKES, STEEP_SLOPE)[2]
    omega_b = -math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope + w.alpha)))
    starts = [-math.sqrt(w.K + f * (omega_b**2 - w.K)) for f in (0.25, 0.5, 0.75)]
    runs = roll_post_impact(runner, STEEP_SPOKES, STEEP_SLOPE, np.asarray(starts), 1.0)
    analytic = [float(theory.return_map(w, om)) for om in starts]
    first = [float(runs.post_impact_speeds(i)[0]) for i in range(len(starts))]
    printed = [-w.beta * om for om in starts]
    return Reading(analytic=analytic, mujoco=first, error=float(np.max(np.abs(np.subtract(first, analytic)))),
                   tolerance=runner.tolerance("omega_post_impact") * math.sqrt(w.K), kind="max-abs",
                   detail=f"n {STEEP_SPOKES}, gamma {STEEP_SLOPE:.5g}: starts {', '.join(f'{s:.4f}' for s in starts)}; "
                   f"(3.14) as printed: {', '.join(f'{p:.4f}' for p in printed)}; highest flight "
                   f"{max(runs.highest_flight(i) for i in range(len(starts))):.2g} m")


def standing_multiplier(runner: Runner) -> Reading:
    """003 Thm 3.10: the standing fixed point's multiplier P'(0) = -beta (-cos 2 alpha) in Ω3 (Fig. 5's slope 0.025):
    the ratio of successive post-impact speeds of a rocking wheel, from three starts inside (omega_b, omega_f).
    MuJoCo's value: the median ratio over the first four rocking impacts of each (spread: half their range); absolute
    error, the scenario's tolerance on the rolling multiplier."""
    w = setup(runner, SPOKES, 0.025)[2]
    omega_f, omega_b = theory.forward_threshold(w), theory.backward_threshold(w)
    starts = [0.8 * omega_f, 0.5 * omega_f, 0.8 * omega_b]
    runs = roll_post_impact(runner, SPOKES, 0.025, np.asarray(starts), 2.0)
    ratios = np.concatenate([np.diff(np.log(np.abs(p[:5]))) for p in
                             (np.concatenate([[s], runs.post_impact_speeds(i)]) for i, s in enumerate(starts))])
    ratios = -np.exp(ratios)
    value = float(np.median(ratios))
    return Reading(analytic=theory.standing_multiplier(w), mujoco=value,
                   error=abs(value - theory.standing_multiplier(w)), tolerance=runner.tolerance("eigenvalue"),
                   spread=float(np.ptp(ratios)) / 2, detail=f"{ratios.size} rocking impacts from starts "
                   f"{', '.join(f'{s:.4g}' for s in starts)}")


def figure_run(runner: Runner, figure: str) -> tuple[Runs, np.ndarray]:
    """MuJoCo's run of ``figure``'s mid-swing start and the theory's first six post-impact speeds of it."""
    slope, theta0, omega0 = FIGURE_STARTS[figure]
    runs = roll_mid_swing(runner, SPOKES, slope, theta0, omega0, FIGURE_SECONDS)
    return runs, figure_sequence(runs.w, theta0, omega0, 6)


def sequence_reading(runner: Runner, figure: str) -> Reading:
    """A figure's post-impact speeds theta_dot_0 .. theta_dot_5 and its end state. Error: the largest gap between
    MuJoCo's and the theory's speeds over the largest |theta_dot_n| of the run (a rocking tail's small speeds carry
    the absolute error of the larger ones before them), against the scenario's omega_post_impact tolerance; infinite
    where the end state differs or fewer than six impacts were read."""
    runs, seq = figure_run(runner, figure)
    limit = "rolling" if theory.predicted_outcome(runs.w, float(seq[0])) == "rolling" else "standing"
    got = runs.post_impact_speeds(0)[:6]
    end = runs.end_state(0)
    scale = float(np.max(np.abs(seq)))
    error = float(np.max(np.abs(got - seq))) / scale if got.size == 6 and end == limit else math.inf
    return Reading(analytic=[*seq.tolist(), limit], mujoco=[*got.tolist(), end], error=error,
                   tolerance=runner.tolerance("omega_post_impact"), kind="max-abs / max |theta_dot_n|",
                   detail=f"Fig. {figure}: highest flight {runs.highest_flight(0):.3g} m, largest |omega| "
                   f"{float(np.max(np.abs(runs.omega[0]))):.3g} rad/s")


def fig5(runner: Runner) -> Reading:
    """003 Fig. 5 (Ω3, gamma = 0.025, theta(0) = -0.132, theta_dot(0) = 2): three forward steps, then rocking to
    omega*_stop."""
    return sequence_reading(runner, "5")


def fig6(runner: Runner) -> Reading:
    """003 Fig. 6 (Ω1, gamma = pi/7, theta(0) = 0.292, theta_dot(0) = 5): converging to omega*_roll from above."""
    return sequence_reading(runner, "6")


def limit_reading(runner: Runner, figure: str) -> Reading:
    """A figure's stated limit (its caption): omega*_roll (relative error of the last post-impact speed, the
    scenario's omega_post_impact tolerance) or omega*_stop (the end state standing). The first post-impact speeds
    are in the detail: the start's stance force is negative (the spoke would have to pull), so MuJoCo's wheel
    flies off its first step and the early speeds are not the map's."""
    runs, seq = figure_run(runner, figure)
    w = runs.w
    post = runs.post_impact_speeds(0)
    end = runs.end_state(0)
    rolls = theory.predicted_outcome(w, float(seq[0])) == "rolling"
    star = theory.rolling_fixed_point(w)
    detail = (f"Fig. {figure}: first post-impact speeds {', '.join(f'{p:.4f}' for p in post[:6])} (theory "
              f"{', '.join(f'{p:.4f}' for p in seq)}); highest flight {runs.highest_flight(0):.3g} m; ends {end}")
    if rolls:
        last = float(post[-1]) if end == "rolling" else math.nan
        return Reading(analytic=star, mujoco=last, error=abs(last / star - 1.0) if end == "rolling" else math.inf,
                       tolerance=runner.tolerance("omega_post_impact"), kind="rel", detail=detail)
    speed = float(np.max(np.abs(runs.omega[0, runs.time[0] >= runs.time[0, -1] - WINDOW])))
    return Reading(analytic=0.0, mujoco=speed, error=speed, tolerance=REST_FRACTION * star, kind="abs",
                   detail=detail + "; MuJoCo's value: the largest |omega| over the last second")


def fig12(runner: Runner) -> Reading:
    """003 Fig. 12 (Ω5, gamma = pi/15, theta(0) = -0.105, theta_dot(0) = -5): converging to omega*_roll from below."""
    return limit_reading(runner, "12")


def fig13(runner: Runner) -> Reading:
    """003 Fig. 13 (Ω5, gamma = pi/15, theta(0) = -0.105, theta_dot(0) = -4.85): converging to omega*_stop."""
    return limit_reading(runner, "13")


#: 003 Sec. 3.1's four-spoked wheel: a slope and a start whose forward step passes the vertical and keeps the spoke
#: loaded (omega0^2 between 2 (g/l)(1 - cos(alpha - gamma)) = 5.60 and (g/l) cos(gamma + alpha) - K = 6.59 s^-2).
FOUR_SLOPE, FOUR_START = 0.01, 2.45
FOUR_MU = 2.0  # twice the friction its sticking impact needs, tan alpha = 1 (the scenario's default mu is 1)
#: Seconds after the four-spoked wheel's impact before its kinetic energy is read: the soft contact rings on the two
#: feet for ~50 ms after it (|omega| up to 4 % of the pre-impact speed) before the wheel rests.
FOUR_RING = 0.1


def four_spokes(runner: Runner) -> Reading:
    """003 Sec. 3.1: a wheel of 4 spokes loses all its energy at an impact (cos 2 alpha = 0, eq 3.11; with the model's
    hub inertia the speed ratio is beta = kappa/(1 + kappa), the energy ratio beta^2). MuJoCo's value: the largest
    omega^2 from FOUR_RING after the first impact to the end of a 2 s run over the theory's pre-impact omega^2 =
    omega0^2 + K (eq 3.5); absolute error against beta^2, tolerance the energy a speed ratio of the scenario's
    impact_coefficient tolerance keeps (its square)."""
    runs = roll_post_impact(runner, 4, FOUR_SLOPE, np.array([FOUR_START]), 2.0, mu=FOUR_MU)
    w = runs.w
    impact = float(wrap_events(runs.time, runs.psi, w.alpha).time[0])
    pre = FOUR_START**2 + w.K
    ring = (runs.time[0] >= impact + SETTLE) & (runs.time[0] < impact + FOUR_RING)
    after = runs.time[0] >= impact + FOUR_RING
    energy = float(np.max(runs.omega[0, after] ** 2)) / pre
    return Reading(analytic=w.beta**2, mujoco=energy, error=abs(energy - w.beta**2),
                   tolerance=runner.tolerance("impact_coefficient") ** 2, kind="abs",
                   detail=f"n 4, gamma {FOUR_SLOPE}, mu {FOUR_MU}: impact at {impact:.3f} s, pre-impact speed "
                   f"{math.sqrt(pre):.4f} rad/s; the contact's ringing from {SETTLE} to {FOUR_RING} s after it: "
                   f"|omega| up to {float(np.max(np.abs(runs.omega[0, ring]))) / math.sqrt(pre):.3g} of the "
                   "pre-impact speed; "
                   f"highest flight {runs.highest_flight(0):.2g} m")
