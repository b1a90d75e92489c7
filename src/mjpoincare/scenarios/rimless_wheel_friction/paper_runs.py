"""MuJoCo experiments for the results of 002 (Gamus & Or 2015) Sec. 3 that the friction wheel's validation does not
run: the impulse ratio of the sticking impact (eq 25), the Type D- transient of Fig. 3.6, the slip onset of
Fig. 3.8(b), the points of Fig. 3.5, and the predicates of the bounds located by bisection (the attraction window of
eq 26 and Fig. 3.8(a), the slope bounds of eqs 18 and 21, the gait-type edges in mu of Sec. 3.3).

Each runs the scenario's own batched rollout (:func:`~mjpoincare.scenarios.rimless_wheel_friction.rollout.run_batch`)
and its step table, at the scenario's preset settings; the theory's side comes from the same exact model
(:mod:`mjpoincare.analysis.theory.rimless_wheel_friction`) under the same start and predicate.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from mjpoincare.analysis import stick_slip_phases as phases
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.scenarios.base import Values
from mjpoincare.scenarios.paper_results import Reading, Runner, bisect, replicate_spread
from mjpoincare.scenarios.rimless_wheel_friction.basins import MU_NO_SLIP
from mjpoincare.scenarios.rimless_wheel_friction.rollout import (
    D_SIM_STEPS,
    D_START_SLIP,
    SETTLED_STEPS,
    SIM_STEPS,
    fit_starts,
    friction_wheel,
    reference_gait,
    run_batch,
)

#: The Fig. 3.6 transient: mu = 0.3, post-impact (theta_dot, x_dot) = (1.12, 0.7) (002 Sec. 3.3).
TRANSIENT_MU = 0.3
TRANSIENT_START = (1.12, 0.7)
TRANSIENT_STEPS = 24
#: Fig. 3.8(b): mu = 1, theta_dot0 = 1, x_dot0 = 0.
ONSET_MU = 1.0
ONSET_RATE = 1.0
#: Steps from the start of a slope-bound run (the map contracts by beta^2 = 0.73 per step: 40 steps reach 4e-6 of the
#: start's offset) and its simulated time, s (the gait's step takes about 0.5 s; near alpha_min the wheel crawls over
#: the top for longer, and a run that has not finished its steps has not failed either).
BOUND_STEPS = 40
BOUND_SECONDS = 40.0
#: The slope-bound runs start here (post-impact theta_dot, nondimensional): inside the attraction window of eq 26
#: for every slope of their brackets, so that the run ends rolling exactly when the gait exists.
BOUND_START = 0.6


def inputs(runner: Runner, **values: float) -> tuple[Values, Values]:
    """The scenario's parameters (its defaults, ``mu`` etc. from ``values``) and the runner's preset settings; the
    slope is set after the scenario's own checks, so that a bound's run may go where no gait exists."""
    slope = values.pop("slope", None)
    params, settings = runner.inputs({k: str(v) for k, v in values.items()})
    return ({**params, "slope": slope} if slope is not None else dict(params)), settings


def first_step_failure(params: Values, settings: Values, preset: str, theta_dot0: float) -> str:
    """The failure ("backward", "detached" or "") of MuJoCo's first step from the post-impact (theta_dot0, 0), the
    way :func:`theory.attraction_window` judges the exact model's (002 Sec. 3.4)."""
    run = run_batch(params, settings, preset, np.array([[theta_dot0, 0.0]]), 2, extra=2.0)
    failed = run.steps.failure[0] and int(run.steps.failure_step[0]) == 0
    return str(run.steps.failure[0]) if failed else ""


def window_lower_below(theta_dot0: float, runner: Runner) -> bool:
    """The first step from theta_dot0 rolls back (below the window's lower edge, eq 26), at mu = 1."""
    params, settings = inputs(runner, mu=ONSET_MU)
    return first_step_failure(params, settings, runner.preset, theta_dot0) == "backward"


def window_lower_theory(runner: Runner) -> float:
    """The exact model's lower edge at mu = 1 (:func:`theory.attraction_window`)."""
    return theory.attraction_window(_wheel(runner, mu=ONSET_MU), tol=1e-7)[0]


def window_upper_below(theta_dot0: float, runner: Runner) -> bool:
    """The first step from theta_dot0 keeps contact (below the window's upper edge, Fig. 3.8(a)), at mu = 1."""
    params, settings = inputs(runner, mu=ONSET_MU)
    return first_step_failure(params, settings, runner.preset, theta_dot0) != "detached"


def window_upper_theory(runner: Runner) -> float:
    """The exact model's upper edge at mu = 1 (:func:`theory.attraction_window`)."""
    return theory.attraction_window(_wheel(runner, mu=ONSET_MU), tol=1e-7)[1]


def _wheel(runner: Runner, **values: float) -> theory.FrictionWheel:
    """The theory's wheel at the scenario's default parameters, updated by ``values`` (unchecked)."""
    return friction_wheel({**runner.inputs({}, checked=False)[0], **values})


def rolls_on(params: Values, settings: Values, preset: str) -> bool:
    """MuJoCo's wheel started at BOUND_START keeps rolling for BOUND_STEPS steps (no backward roll, no detachment)."""
    run = run_batch(params, settings, preset, np.array([[BOUND_START, 0.0]]), BOUND_STEPS, seconds=BOUND_SECONDS)
    return not run.steps.failure[0]


def alpha_min_below(slope_deg: float, runner: Runner) -> bool:
    """Below alpha_min (002 eq 18) the wheel rolls back: MuJoCo's wheel at mu = MU_NO_SLIP does not keep rolling."""
    params, settings = inputs(runner, mu=MU_NO_SLIP, slope=math.radians(slope_deg))
    return not rolls_on(params, settings, runner.preset)


def alpha_min_theory(runner: Runner) -> float:
    """alpha_min in degrees (002 eq 18 with equality; :func:`theory.slope_bounds`)."""
    w = _wheel(runner)
    return math.degrees(theory.slope_bounds(w.spokes, w.kappa)[0])


def alpha_max_below(slope_deg: float, runner: Runner) -> bool:
    """Below alpha_max the gait keeps contact: MuJoCo's wheel at mu = MU_NO_SLIP keeps rolling."""
    params, settings = inputs(runner, mu=MU_NO_SLIP, slope=math.radians(slope_deg))
    return rolls_on(params, settings, runner.preset)


def alpha_max_theory_unbounded(runner: Runner) -> float:
    """alpha_max in degrees (002 eq 21, unbounded friction; :func:`theory.slope_bounds`)."""
    w = _wheel(runner)
    return math.degrees(theory.slope_bounds(w.spokes, w.kappa)[1])


def impulse_ratio(runner: Runner) -> Reading:
    """The sticking impact's impulse ratio F~_t/F~_n on the Type A gait at mu = 1 (002 eq 25), from the impacts of
    the settled steps of the scenario's fit starts, against :func:`theory.impulse_ratio`."""
    params, settings = inputs(runner, mu=ONSET_MU)
    w = friction_wheel(params)
    gait = reference_gait(w)
    starts, mask = fit_starts(gait, w)
    run = run_batch(params, settings, runner.preset, starts, SIM_STEPS)
    ratios = np.concatenate([run.steps.impulse_ratio[b, phases.settled_steps(run.steps, b, SETTLED_STEPS)]
                             for b in np.nonzero(mask)[0]])
    ratios = ratios[np.isfinite(ratios)]
    analytic = theory.impulse_ratio(w.spokes, w.kappa)
    value = float(np.median(ratios)) if ratios.size else math.nan
    spread = float(np.percentile(ratios, 95) - np.percentile(ratios, 5)) / 2 if ratios.size else math.nan
    return Reading(analytic=analytic, mujoco=value, error=abs(value - analytic), tolerance=IMPULSE_TOLERANCE,
                   spread=spread, detail=f"median over {ratios.size} settled impacts")


#: The impulse ratio's tolerance (absolute; see the result's why).
IMPULSE_TOLERANCE = 0.01


def transient_run(runner: Runner) -> tuple[theory.FrictionWheel, phases.Steps, Values]:
    """MuJoCo's Fig. 3.6 transient: TRANSIENT_STEPS steps from TRANSIENT_START at mu = 0.3."""
    params, settings = inputs(runner, mu=TRANSIENT_MU)
    run = run_batch(params, settings, runner.preset, np.array([TRANSIENT_START]), TRANSIENT_STEPS)
    return friction_wheel(params), run.steps, params


def exact_transient(w: theory.FrictionWheel) -> list[theory.StepRecord]:
    """The exact model's steps of the same transient, up to TRANSIENT_STEPS."""
    return list(theory.settle(w, TRANSIENT_START, max_steps=TRANSIENT_STEPS, tol=0.0).records)


def first_sticking_impact(runner: Runner) -> Reading:
    """The impact at which the Fig. 3.6 transient's slip first stops (002 Sec. 3.3: "after k = 15 impacts"): MuJoCo's
    step index (1-based) of the first sticking impact, against the exact model's."""
    w, steps, _ = transient_run(runner)
    sticking = np.nonzero(steps.complete[0] & ~steps.impact_slipping[0].astype(bool))[0]
    value = float(sticking[0] + 1) if sticking.size else math.nan
    exact = exact_transient(w)
    analytic = float(next(k for k, r in enumerate(exact, 1) if r.impact == "sticking"))
    return Reading(analytic=analytic, mujoco=value, error=abs(value - analytic), tolerance=0.0, kind="count",
                   detail=f"MuJoCo impact kinds {''.join('s' if s else 'k' for s in steps.impact_slipping[0][:18])}"
                          " (s slipping, k sticking)")


def slip_per_step(runner: Runner) -> Reading:
    """Delta x_dot per step of the D- gait the Fig. 3.6 transient follows (002 Fig. 3.6(c): -0.0517): the mean change of
    MuJoCo's mid-stance slip speed over the transient's slipping steps 5-12 (theta_dot settled, lambda ~ 0.35), against
    the exact D- gait's."""
    w, steps, _ = transient_run(runner)
    mid = steps.mid_slip[0, 4:12]
    value = float(np.mean(np.diff(mid)))
    spread = float(np.std(np.diff(mid)))
    gait = theory.find_gait(w, "D")
    analytic = gait.dx_per_step if gait is not None else math.nan
    return Reading(analytic=analytic, mujoco=value, error=abs(value - analytic) / abs(analytic),
                   tolerance=SLIP_TOLERANCE, kind="rel", spread=spread, detail="mean over steps 5-12")


#: Delta x_dot's tolerance (relative; see the result's why).
SLIP_TOLERANCE = 0.05


def slip_onset(runner: Runner) -> Reading:
    """Fig. 3.8(b): the first step from theta_dot0 = 1 at mu = 1 sticks, then slips at theta = 0.163; MuJoCo's onset
    (the start of the step's last slip phase) against the exact step's."""
    params, settings = inputs(runner, mu=ONSET_MU)
    run = run_batch(params, settings, runner.preset, np.array([[ONSET_RATE, 0.0]]), 2)
    value = float(run.steps.onset[0, 0])
    record = theory.step(friction_wheel(params), (ONSET_RATE, 0.0))
    analytic = float(record.phase_angles[-1])
    return Reading(analytic=analytic, mujoco=value, error=abs(value - analytic), tolerance=ONSET_TOLERANCE,
                   detail=f"phases of the exact step: {' > '.join(record.phases)}")


#: The onset's tolerance, rad (see the result's why).
ONSET_TOLERANCE = 0.01

#: Fig. 3.5's friction values: D+ (0.1-0.22), C (0.24), B (0.27-0.8), A (1.0).
FIG35_MU = (0.1, 0.15, 0.2, 0.22, 0.24, 0.27, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0)


def fig35_fixed_point(mu: float, runner: Runner) -> Reading:
    """Fig. 3.5(a)'s point at ``mu``: the fitted fixed point of MuJoCo's mid-stance map against the gait's (the
    validation's ``midstance_rate``), spread from its bootstrap."""
    result = runner.validate({"mu": str(mu)})
    check = next(c for c in result.checks if c.name == "midstance_rate")
    record = result.fit.record if result.fit is not None else {}
    spread = float(np.std([r[0] for r in record.get("fixed_point_replicates", [])] or [math.nan]))
    return Reading(analytic=check.analytic, mujoco=check.simulated, error=check.error, tolerance=check.tolerance,
                   kind=check.kind, spread=spread, detail=f"gait {result.extras['starts'][0]['reference']}")


def fig35_multiplier(mu: float, runner: Runner) -> Reading:
    """Fig. 3.5(b)'s point at ``mu``: MuJoCo's fitted multiplier (the validation's ``eigenvalue``), spread from its
    bootstrap."""
    result = runner.validate({"mu": str(mu)})
    check = next(c for c in result.checks if c.name == "eigenvalue")
    spread = replicate_spread(result.fit.record) if result.fit is not None else math.nan
    return Reading(analytic=float(np.real(check.analytic)), mujoco=check.simulated, error=check.error,
                   tolerance=check.tolerance, kind=check.kind, spread=spread)


def _stable_gait(mu: float, runner: Runner) -> theory.Gait | None:
    """The stable gait at ``mu`` (None where there is none, or ``mu`` is outside the scenario's range)."""
    try:
        gaits = theory.attractors(_wheel(runner, mu=float(mu)))
    except ValueError:  # a ParameterError: no gait at this mu
        return None
    return gaits[0] if gaits else None


def fig35_fixed_point_theory(mus: np.ndarray, runner: Runner) -> np.ndarray:
    """The stable gait's mid-stance theta_dot over mu (NaN where none)."""
    return np.array([g.midstance_rate if (g := _stable_gait(m, runner)) else math.nan for m in mus])


def fig35_multiplier_theory(mus: np.ndarray, runner: Runner) -> np.ndarray:
    """The stable gait's largest multiplier modulus over mu (NaN where none)."""
    return np.array([float(np.max(np.abs(g.eigenvalues))) if (g := _stable_gait(m, runner)) else math.nan for m in mus])


def gait_type_below(mu: float, runner: Runner) -> bool:
    """MuJoCo's wheel settles on a slipping gait (B) rather than A: the settled type from the Type A gait's own start
    (002 Sec. 3.3's A/B edge, mu_c)."""
    params, settings = inputs(runner, mu=mu)
    w = friction_wheel(params)
    start = (theory.sticking_fixed_point(w), 0.0)
    run = run_batch(params, settings, runner.preset, np.array([start]), SIM_STEPS)
    return phases.outcome(run.steps, 0) != "A"


def ab_edge_theory(runner: Runner) -> float:
    """The A/B edge in mu (:func:`theory.gait_boundaries`)."""
    w = _wheel(runner)
    return theory.gait_boundaries(w.kappa, w.spokes, w.slope).ab


def d_lower_edge(runner: Runner) -> Reading:
    """The D branch's lower edge in mu (002 Sec. 3.3: below it the wheel rolls back): MuJoCo's runs from the D gait's
    start (theta_dot* at mu = D_LOWER_START_MU, slip D_START_SLIP) over D_LOWER_MUS in one batch, 12 steps each; the
    edge between the last mu that rolls back and the first that settles, against the exact model's."""
    params, settings = inputs(runner, mu=D_LOWER_START_MU)
    start = (float(theory.find_gait(friction_wheel(params), "D").fixed_point[0]), D_START_SLIP)
    mus = np.asarray(D_LOWER_MUS)
    run = run_batch(params, settings, runner.preset, np.tile(start, (mus.size, 1)), D_SIM_STEPS, mus=mus, extra=5.0)
    failures = [str(f) or "none" for f in run.steps.failure]
    back = [m for m, f in zip(mus, failures, strict=True) if f == "backward"]
    fine = [m for m, f in zip(mus, failures, strict=True) if f == "none"]
    edge = (max(back) + min(fine)) / 2 if back and fine and max(back) < min(fine) else math.nan
    analytic = d_lower_theory(runner)
    return Reading(analytic=analytic, mujoco=edge, error=abs(edge - analytic), tolerance=D_LOWER_TOLERANCE,
                   detail="failures by mu: " + ", ".join(f"{m:g} {f}" for m, f in zip(mus, failures, strict=True)))


#: The mu whose D gait gives the lower-edge runs their start, the mu grid, and the edge's tolerance (the grid's step).
D_LOWER_START_MU = 0.1
D_LOWER_MUS = (0.06, 0.07, 0.075, 0.08, 0.085, 0.09, 0.1)
D_LOWER_TOLERANCE = 0.01


def d_lower_theory(runner: Runner) -> float:
    """The D branch's lower edge in mu (:func:`theory.gait_boundaries`)."""
    w = _wheel(runner)
    return theory.gait_boundaries(w.kappa, w.spokes, w.slope).d_lower


def _edge(below: Callable[[float], bool], low: float, high: float, tolerance: float) -> tuple[float, float]:
    """MuJoCo's edge by bisection on [low, high] to ``tolerance``: (edge, half the final bracket); (NaN, NaN) where
    the interval does not bracket it."""
    try:
        low, high, _ = bisect(below, low, high, tolerance)
    except ValueError:
        return math.nan, math.nan
    return (low + high) / 2, (high - low) / 2


def _window_point(mu: float, runner: Runner, side: int, tolerance: float) -> Reading:
    params, settings = inputs(runner, mu=mu)
    exact = theory.attraction_window(friction_wheel(params), tol=1e-7)[side]
    failure = "backward" if side == 0 else "detached"

    def below(th: float) -> bool:
        failed = first_step_failure(params, settings, runner.preset, th) == failure
        return failed if side == 0 else not failed

    low, high = (exact / 2, exact * 1.5) if side == 0 else (exact - WINDOW_SEARCH, exact + WINDOW_SEARCH)
    edge, spread = _edge(below, low, high, tolerance / 8)
    return Reading(analytic=exact, mujoco=edge, error=abs(edge - exact), tolerance=tolerance, spread=spread,
                   detail="bisection on the first step's outcome")


#: Half-width of an upper window edge's search around the exact edge (nondimensional rate; a lower edge's search
#: spans half to 1.5 times the exact edge).
WINDOW_SEARCH = 0.1
#: Tolerances of the window's edges (nondimensional; see the results' why).
LOWER_EDGE_TOLERANCE = 0.002
UPPER_EDGE_TOLERANCE = 0.03


def fig38a_lower(mu: float, runner: Runner) -> Reading:
    """Fig. 3.8(a)'s lower edge theta_dot_min(mu) in MuJoCo (bisection) against the exact model's."""
    return _window_point(mu, runner, 0, LOWER_EDGE_TOLERANCE)


def fig38a_upper(mu: float, runner: Runner) -> Reading:
    """Fig. 3.8(a)'s upper edge theta_dot_max(mu) in MuJoCo (bisection) against the exact model's."""
    return _window_point(mu, runner, 1, UPPER_EDGE_TOLERANCE)


def fig38a_lower_theory(mus: np.ndarray, runner: Runner) -> np.ndarray:
    """The exact model's theta_dot_min over mu."""
    return np.array([theory.attraction_window(_wheel(runner, mu=float(m)), tol=1e-6)[0] for m in mus])


def fig38a_upper_theory(mus: np.ndarray, runner: Runner) -> np.ndarray:
    """The exact model's theta_dot_max over mu."""
    return np.array([theory.attraction_window(_wheel(runner, mu=float(m)), tol=1e-6)[1] for m in mus])


def fig37_lower(slope_deg: float, runner: Runner) -> Reading:
    """Fig. 3.7's lower edge theta_dot_min(alpha) (eq 26) in MuJoCo at mu = MU_NO_SLIP, against eq 26."""
    params, settings = inputs(runner, mu=MU_NO_SLIP, slope=math.radians(slope_deg))
    exact = float(fig37_lower_theory(np.array([slope_deg]), runner)[0])
    edge, spread = _edge(lambda th: first_step_failure(params, settings, runner.preset, th) == "backward", exact / 2,
                         exact * 1.5, LOWER_EDGE_TOLERANCE / 8)
    return Reading(analytic=exact, mujoco=edge, error=abs(edge - exact), tolerance=LOWER_EDGE_TOLERANCE,
                   spread=spread, detail="bisection on the first step's outcome")


def fig37_lower_theory(slopes_deg: np.ndarray, runner: Runner) -> np.ndarray:
    """eq 26: theta_dot_min = sqrt(2 (1 - cos(alpha - phi))) (alpha < phi)."""
    phi = math.pi / _wheel(runner).spokes
    return np.sqrt(2 * (1 - np.cos(np.radians(slopes_deg) - phi)))
