"""Scenario ``rimless-wheel``: the planar rimless wheel on a slope, sticking contact.

Analytic reference: Kiša (2020) Sec. 3 (return map 3.13-3.14 corrected, fixed points, Table 1
regions, basins 3.17-3.18) with the hub inertia of Gamus & Or (eq 12-25); see
:mod:`mjpoincare.analysis.theory.rimless_wheel`.

Poincaré section. The post-impact instant is smeared over the soft contact's impact window, so
the wheel is sampled at **mid-stance** (stance spoke normal to the slope, wrapped hinge angle
``psi`` crossing 0 upward, linearly interpolated) and each sample is pulled back to the
post-impact section with the exact stance energy integral (003 eq 3.5 / 002 eq 13). The pull-back
is a fixed conjugacy of the map, so fixed point and multiplier are those of the post-impact map;
any error MuJoCo makes at the impact or during the swing shows in the samples.
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.adaptive_stopping import StoppingRule, return_map_settling
from mjpoincare.analysis.period_regression import period_at
from mjpoincare.analysis.returnmap import fit_return_map, sample_pairs
from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.analysis.theory.rimless_wheel.hybrid import simulate_hybrid
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.mjcf_loader import compile_spec, load_spec
from mjpoincare.core.params import Param, ParameterError
from mjpoincare.core.settings import search_space
from mjpoincare.scenarios.base import (
    AnalyticValues,
    BasinMap,
    CoveragePoint,
    Evaluation,
    FitSummary,
    ReturnMapPlot,
    Scenario,
    Soak,
    StressCase,
    Tolerances,
    Values,
    at_preset,
)
from mjpoincare.scenarios.gate_cases import GateCase, Watch
from mjpoincare.scenarios.rimless_wheel import basin_judging
from mjpoincare.scenarios.rimless_wheel.drake import drake_peer
from mjpoincare.scenarios.rimless_wheel.paper_results import PAPER_RESULTS
from mjpoincare.scenarios.rimless_wheel.rivals import RIVALS
from mjpoincare.scenarios.rimless_wheel.runs import (
    FIT_STEPS,
    MIN_GYRATION,
    WHEEL_FOOT,
    Recorder,
    final_outcomes,
    fit_seconds,
    post_impact_samples,
    post_impact_states,
    simulate,
    wheel,
    whole_chunks,
)
from mjpoincare.simulation.simulate import plain_clip

PARAMS: tuple[Param, ...] = (
    Param("spokes", 8, "number of spokes n (alpha = pi/n)", int, 3, 64),
    Param("slope", 0.08, "slope gamma, rad", float, 0.0, math.pi / 2, True, True),
    Param("leg_length", 1.0, "spoke length l, m", float, 0.0, 100.0, low_open=True),
    Param("mass", 1.0, "hub mass m, kg", float, 0.0, 1e6, low_open=True),
    Param("gyration", 0.0, f"hub radius of gyration, m (0 = point mass, modelled as {MIN_GYRATION:g} l: MuJoCo's "
          "pitch joint needs an inertia; kappa = (gyration/l)^2)", float, 0.0, 100.0),
    Param("mu", 1.0, "Coulomb friction coefficient (sticking needs mu >= the required friction)", float, 0.0,
          1e3),
    Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, low_open=True),
)

#: Simulator presets (why: docs/scenarios/rimless-wheel.md, "Presets and experiment design").
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 0.000925480824676, "solref_timeconst": 0.00194042995546, "integrator": "implicitfast",
        "solref_dampratio": 1.36478083041, "foot_radius": 0.000109265647622},
    "accurate": {"timestep": 2.5e-05, "solref_timeconst": 0.00025, "integrator": "implicitfast",
        "solref_dampratio": 2.0, "foot_radius": 0.000125},
}

TOLERANCES: dict[str, Tolerances] = {
    "accurate": Tolerances(
        bounds={"omega_post_impact": 1e-3, "eigenvalue": 0.01, "impact_coefficient": 1e-3, "step_period": 1e-3},
        why="the suite's accuracy target; the error is first order in the step and the contact time constant "
            "(docs/convergence.md), and the preset is the cheapest setting a search found to hold it at every "
            "coverage point (docs/results/tune/rimless-wheel.md)"
    ),
    "fast": Tolerances(
        bounds={"omega_post_impact": 0.01, "eigenvalue": 0.02, "impact_coefficient": 0.01, "step_period": 0.01},
        why="ten times the accuracy target: the error is first order in the contact time constant, and the preset "
            "is the cheapest setting a search found to hold it at every coverage point "
            "(docs/results/tune/rimless-wheel.md)"
    ),
}

#: The fitting batch stops once more impacts no longer sharpen the fit (:mod:`mjpoincare.analysis.adaptive_stopping`);
#: 3 samples per trajectory give the step period's quadratic regression in two speeds 12 pairs for its 6 terms.
STOPPING = StoppingRule(min_samples=3)
FIT_DEGREE = 2  # the map omega+ -> omega+ is fitted as a quadratic
FIT_BATCH = 6
BASIN_SECONDS = 6.0  # at most; the slowest standing case of the default grid settles after 3.3 s


def _gyration_text(params: Values, w: theory.RimlessWheel) -> str:
    """The hub gyration as given, and the value the model and the theory use where it was raised to MIN_GYRATION l
    (a point-mass hub has no rotational inertia for MuJoCo's pitch joint)."""
    given = float(params["gyration"])
    if given == w.gyration:
        return f"gyration={given:g}"
    return f"gyration={given:g} (modelled as {w.gyration:g} m, MuJoCo's smallest hub: {MIN_GYRATION:g} l)"


def check_params(params: Values) -> None:
    """Refuse parameters outside the theory's assumptions, naming the bound (003 eq 3.16, no-flight, 002 eq 22)."""
    if float(params["gyration"]) > float(params["leg_length"]):
        raise ParameterError(f"gyration must be in [0, leg_length={params['leg_length']:g}] m "
                             f"(got {params['gyration']})")
    w = wheel(params)
    low = theory.existence_bound(w.spokes, w.gyration, w.leg_length)
    high = theory.no_flight_bound(w.spokes, w.gyration, w.leg_length)
    if high <= low:
        raise ParameterError(
            f"spokes={w.spokes} has no flight-free rolling gait (existence bound {low:.4f} rad >= no-flight "
            f"bound {high:.4f} rad); use spokes >= 6")
    if not low < w.slope < high:
        raise ParameterError(
            f"slope must be in ({low:.4f}, {high:.4f}) rad for spokes={w.spokes}, {_gyration_text(params, w)}: "
            f"above the existence bound (003 eq 3.16) and below the no-flight bound (got {w.slope:g})")
    need = theory.required_friction(w)
    if float(params["mu"]) < need:
        raise ParameterError(
            f"mu must be >= {need:.4f} (the friction a sticking gait needs, 002 eq 22-25) for these spokes and "
            f"slope (got {params['mu']}); stick-slip gaits are not part of this scenario")


def build(params: Values, settings: Values) -> mujoco.MjModel:
    """The MJCF wheel rebuilt through MjSpec with ``p`` (physics) and ``s`` (simulator settings)."""
    spec = load_spec("rimless_wheel_2d.xml")
    sim_settings.apply_options(spec, settings)
    g, slope, l = float(params["gravity"]), float(params["slope"]), float(params["leg_length"])
    spec.option.gravity = [g * math.sin(slope), 0.0, -g * math.cos(slope)]
    hub = spec.body("hub")
    mass = float(params["mass"])
    inertia = mass * wheel(params).gyration ** 2
    hub.mass = mass
    hub.inertia = [inertia, inertia, inertia]
    radius = float(settings["foot_radius"])
    template_spoke, template_foot = spec.geom("spoke0"), spec.geom("foot0")
    spoke_size, spoke_rgba = list(template_spoke.size), list(template_spoke.rgba)
    foot_rgba = list(template_foot.rgba)
    for geom in [g for g in hub.geoms if g.name.startswith(("spoke", "foot"))]:
        spec.delete(geom)
    mu = float(params["mu"])
    for k in range(int(params["spokes"])):
        angle = 2.0 * math.pi * k / int(params["spokes"])
        direction = np.array([-math.sin(angle), 0.0, -math.cos(angle)])
        hub.add_geom(name=f"spoke{k}", type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=spoke_size, rgba=spoke_rgba,
                     fromto=[0, 0, 0, *((l - radius) * direction)], contype=0, conaffinity=0, mass=0)
        hub.add_geom(name=f"foot{k}", type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[radius, 0, 0], rgba=foot_rgba,
                     pos=(l - radius) * direction, contype=1, conaffinity=0, condim=3, friction=[mu, 0, 0],
                     solref=sim_settings.solref(settings), solimp=sim_settings.solimp(settings), mass=0)
    floor = spec.geom("slope")
    floor.friction = [mu, 0, 0]
    floor.solref = sim_settings.solref(settings)
    floor.solimp = sim_settings.solimp(settings)
    return compile_spec(spec, settings)


def _fit_checks(w: theory.RimlessWheel, rec: Recorder, batch: int, tol: Tolerances,
                why: str, seed: int) -> tuple[list[checks.Check], FitSummary, ReturnMapPlot, dict[str, object]]:
    gamma, alpha = w.slope, w.alpha
    times = rec.mid.times(batch)
    post = post_impact_samples(w, rec, batch)
    x, x_next = sample_pairs(post)
    fit = fit_return_map(x, x_next, degree=FIT_DEGREE, seed=seed)
    star_sim = float(fit.fixed_point[0])
    eig_sim = complex(fit.eigenvalues[0])
    pre = np.asarray(theory.phase_speed(w, x[:, 0], gamma + alpha), float)
    beta_sim = float(np.median(x_next[:, 0] / pre))
    period_sim = period_at(star_sim, [p[:-1] for p in post], [p[1:] for p in post], [np.diff(t) for t in times])
    star = theory.rolling_fixed_point(w)
    out = [
        checks.relative("omega_post_impact", star, star_sim, tol["omega_post_impact"], "rad/s",
                        "post-impact speed at the rolling fixed point (003 3.13, 002 eq 16); " + why),
        checks.absolute("eigenvalue", theory.rolling_multiplier(w), eig_sim, tol["eigenvalue"], "",
                        "return-map multiplier beta^2 (002 eq 17) from a quadratic fit of the samples; the fit's "
                        "own bias is ~1e-3 (synthetic tests) on top of the simulation error"),
        checks.relative("impact_coefficient", w.beta, beta_sim, tol["impact_coefficient"], "",
                        "omega+/omega- (003 eq 3.11, 002 eq 14) estimated from consecutive mid-stance samples, each "
                        "carried to its impact by the exact stance energy integral (003 eqs 3.3-3.5): the contact "
                        "model's error and the stance's integration error together, not the contact alone; the foot "
                        "sphere adds ~+0.7 r/l"),
        checks.relative("step_period", theory.step_period(w, star), period_sim, tol["step_period"], "s",
                        "time between mid-stance crossings, regressed (quadratic) on the two post-impact speeds "
                        "it spans and taken at the fitted fixed point; same error sources as omega_post_impact"),
    ]
    grid = np.linspace(float(x.min()), float(x.max()), 60)
    plot = ReturnMapPlot(label="post-impact speed omega+ (rad/s)", x=x[:, 0], x_next=x_next[:, 0], analytic_x=grid,
                         analytic_y=np.asarray(theory.return_map(w, grid), float),
                         analytic_eigenvalues=[theory.rolling_multiplier(w)])
    return out, FitSummary.of(fit), plot, {"max_clearance_rolling": float(np.max(rec.max_clearance))}


def _basin_checks(w: theory.RimlessWheel, rec: Recorder, omega0: np.ndarray) -> tuple[list[checks.Check], BasinMap]:
    simulated = final_outcomes(w, rec)
    predicted = [basin_judging.predicted_outcome(w, float(om)) for om in omega0]
    judged = basin_judging.judged(w, [float(om) for om in omega0], predicted)
    agree = judged & (np.array(predicted) == simulated)
    table = [{"omega0": float(om), "predicted": p, "simulated": str(sm), "judged": bool(j), "max_clearance": float(c)}
             for om, p, sm, j, c in zip(omega0, predicted, simulated, judged, rec.max_clearance, strict=True)]
    check = checks.fraction(
        "basins", int(agree.sum()), int(judged.sum()), 0.0,
        "end state (rolling/standing) from a grid of post-impact speeds vs the regions of attraction "
        "(003 Table 1, eq 3.17-3.18); speeds within 2% of a basin edge or whose analytic run would lift off are "
        "reported, not judged")
    return [check], BasinMap(table=table, bands=theory.basin_bands(w))


def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
    """Run the fitting batch and the basin grid (two rollout batches) and check them against the theory."""
    w = wheel(params)
    model = build(params, settings)
    tol = at_preset(TOLERANCES, RIMLESS_WHEEL.name, preset)
    why = tol.why
    fit_speeds = theory.fit_initial_speeds(w, FIT_BATCH)
    settle = None if not settings["adaptive_stopping"] else return_map_settling(
        STOPPING, degree=FIT_DEGREE, seed=seed, fixed_point_tolerance=tol["omega_post_impact"],
        eigenvalue_tolerance=tol["eigenvalue"], relative=True)
    fit_rec, fit_report = simulate(model, w, fit_speeds, fit_seconds(w), settings, settling=settle)
    fit: FitSummary | None = None
    plot: ReturnMapPlot | None = None
    try:
        fit_checks, fit, plot, extras = _fit_checks(w, fit_rec, len(fit_speeds), tol, why, seed)
    except ValueError as err:  # too few samples: a diverged or stalled run
        fit_checks = [checks.relative("omega_post_impact", theory.rolling_fixed_point(w), math.nan,
                                      tol["omega_post_impact"], "rad/s", f"no return map: {err}")]
        extras = {}
    basin_speeds = theory.basin_initial_speeds(w)
    basin_rec, basin_report = simulate(model, w, basin_speeds, BASIN_SECONDS, settings, until_decided=True)
    basin_checks, basins = _basin_checks(w, basin_rec, basin_speeds)
    extras["adaptive_stopping"] = None if settle is None else settle.to_dict()
    analytic = AnalyticValues(eigenvalues=[theory.rolling_multiplier(w)], values={
        "region": theory.region(w), "beta": w.beta, "omega_forward_threshold": theory.forward_threshold(w),
        "existence_bound": theory.existence_bound(w.spokes, w.gyration, w.leg_length),
        "no_flight_bound": theory.no_flight_bound(w.spokes, w.gyration, w.leg_length),
        "required_friction": theory.required_friction(w), "impact_impulse_ratio": theory.impact_impulse_ratio(w),
        "standing_multiplier": theory.standing_multiplier(w), "effective_gyration": w.gyration, "kappa": w.kappa,
    })
    return Evaluation(fit_checks + basin_checks, fit_report.merge(basin_report), extras, analytic=analytic, fit=fit,
                      return_map=plot, basins=basins)


def validation_batches(params: Values, settings: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The model and the (initial states, steps) of each rollout batch :func:`evaluate` runs."""
    w = wheel(params)
    model = build(params, settings)
    radius = float(settings["foot_radius"])
    batches = []
    for speeds, seconds in ((theory.fit_initial_speeds(w, FIT_BATCH), fit_seconds(w)),
                            (theory.basin_initial_speeds(w), BASIN_SECONDS)):
        batches.append((post_impact_states(model, w, speeds, radius), whole_chunks(model, seconds)))
    return model, batches


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact hybrid reference (solve_ivp, tolerance ``rtol``) through the same fit: time and errors."""
    w = wheel(params)
    start = time.perf_counter()
    sequences = []
    for omega0 in theory.fit_initial_speeds(w, FIT_BATCH):
        run = simulate_hybrid(w, float(omega0), FIT_STEPS, rtol=rtol, atol=0.1 * rtol)
        sequences.append(np.concatenate([[omega0], run.omega_post]))
    fit = fit_return_map(*sample_pairs(sequences), degree=2)
    wall = time.perf_counter() - start
    star = theory.rolling_fixed_point(w)
    return {"rtol": rtol, "wall_s": wall,
            "omega_post_impact_error": abs(float(fit.fixed_point[0]) - star) / star,
            "eigenvalue_error": abs(complex(fit.eigenvalues[0]) - theory.rolling_multiplier(w))}


def soak(params: Values, settings: Values, impacts: int) -> Soak:
    """``impacts`` steps from the rolling fixed point in one trajectory: the post-impact speed of each step."""
    w = wheel(params)
    star = theory.rolling_fixed_point(w)
    rec, report = simulate(build(params, settings), w, np.array([star]), impacts * theory.step_period(w, star) + 0.5,
                           settings)
    post = np.asarray(theory.post_impact_speed(w, w.slope, rec.mid.sequences(1)[0][:, 0]), float)
    return Soak(post, star, "post-impact speed omega+ (rad/s)", report)


STRESS_CASES = (
    StressCase("slope near existence bound", {"slope": "0.070"}, "just above 003 eq 3.16 (0.0682 for n = 8)"),
    StressCase("slope near no-flight bound", {"slope": "0.255"}, "just below the no-flight bound (0.2621)"),
    StressCase("many spokes", {"spokes": "32", "slope": "0.05"}, "n = 32: short steps, 4x more impacts"),
    StressCase("few spokes", {"spokes": "6", "slope": "0.2"}, "n = 6: hard impacts (beta^2 = 0.25)"),
    StressCase("friction at the bound", {"mu": "0.42"}, "mu 1% above the required 0.4142 (002 eq 22-25)"),
    StressCase("heavy hub", {"gyration": "0.9"}, "kappa = 0.81: slow multiplier beta^2 = 0.84"),
    StressCase("long spokes", {"leg_length": "10", "slope": "0.1"}, "l = 10 m: slow steps, 10x the impact speed"),
    StressCase("friction below bound", {"mu": "0.3"}, "stick-slip: outside this scenario's sticking theory",
               expect="refused"),
    StressCase("slope below existence", {"slope": "0.05"}, "no rolling gait exists (003 eq 3.16)", expect="refused"),
    StressCase("two spokes", {"spokes": "2"}, "fewer than 3 spokes is not a wheel", expect="refused"),
)


def video_states(params: Values, settings: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """States of a clip that starts just after an impact, 20 % above the rolling fixed point's speed."""
    w = wheel(params)
    state0 = post_impact_states(model, w, np.array([1.2 * theory.rolling_fixed_point(w)]),
                                float(settings["foot_radius"]))
    return plain_clip(model, state0, nstep)


#: The checks :func:`evaluate` reports, at any parameters: the fitted map's four (003 eqs 3.11-3.13, 002 eqs 14-17;
#: a run with too few samples reports the first alone, the others then fail as missing) and the regions of
#: attraction (003 Table 1, eqs 3.17-3.18).
CHECKS = ("omega_post_impact", "eigenvalue", "impact_coefficient", "step_period", "basins")

#: Where a preset must hold (mjpoincare tune). No point lies closer to the existence bound than the defaults: there the
#: wheel barely vaults the spoke, its speed over the top goes to 0 and the step period diverges, so the period's
#: error grows without bound for any fixed setting (its sensitivity to omega+, d ln T / d ln omega+, is 2.7 at slope
#: 0.08 and 10.9 at 0.07 for n = 8). The tolerances hold from the defaults up. Nothing is singular at the no-flight
#: bound: the steep point sits 5 % of the n = 8 slope range below it, where the impacts are hardest without flight.
_WHEEL = (*CHECKS, "stable")
_HOP_PERIOD = ("the step period is timed from impact to impact, and MuJoCo's soft impact lets the wheel leave the "
               "slope briefly, which lengthens it")
#: The gate's runs of this scenario (:mod:`mjpoincare.gate.forms`), as measured by ``mjpoincare margins`` (MuJoCo 4.0.0,
#: numpy 2.4.6, scipy 1.17.1, this repository's CPU): each spread is the measured one rounded up to 2 digits. A
#: declared miss's range spans this measurement and the one an earlier margins run declared (machines and builds
#: differ by more than the perturbations move some fits).
GATE_CASES: tuple[GateCase, ...] = (
    GateCase.of("rimless-wheel", "fast", _WHEEL),
    GateCase.of("rimless-wheel", "accurate", tuple(c for c in _WHEEL if c != "step_period"), watched=[
        Watch(check="step_period", spread=2.6e-6, why="0.96 of its tolerance: " + _HOP_PERIOD
              + "; the searched preset trades it against the six-spoke wheel's hop")]),
    GateCase.of("rimless-wheel", "accurate", _WHEEL, spokes=10, slope=0.1),
    GateCase.of("rimless-wheel", "accurate", _WHEEL, spokes=12, slope=0.1),
    GateCase.of("rimless-wheel", "accurate", tuple(c for c in _WHEEL if c != "omega_post_impact"), spokes=8,
                slope=0.2, watched=[
        Watch(check="omega_post_impact", spread=5.4e-5, why="0.48 of its tolerance, 0.53 with its spread: the error "
              "grows with the slope, the impacts' speed through the soft contact (0.39 of its tolerance at slope 0.08, "
              "0.76 at 0.25 in the preset's study)")]),
    GateCase.of("rimless-wheel", "accurate", _WHEEL, spokes=6, slope=0.22),
)


COVERAGE = (
    CoveragePoint("defaults", {}, "n = 8, slope 0.08: the lowest slope the tolerances are stated for"),
    CoveragePoint("steep", {"slope": "0.25"}, "slope 0.25 below the no-flight bound 0.2621: hard impacts, the soft "
                  "contact's hop"),
    CoveragePoint("six spokes", {"spokes": "6", "slope": "0.22"}, "n = 6: beta^2 = 0.25, the hardest impacts"),
)

RIMLESS_WHEEL = Scenario(
    name="rimless-wheel",
    summary="planar rimless wheel on a slope: rolling fixed point, multiplier, impact law, basins",
    source="Kisa 2020 Sec. 3 (eq 3.11-3.18, Table 1); Gamus & Or eq 12-25 (hub inertia, friction)",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    bench_checks=("omega_post_impact", "eigenvalue", "impact_coefficient", "step_period"),
    validation_batches=validation_batches,
    exact_model_bench=exact_model_bench,
    video_states=video_states,
    track_body="hub",
    frame_tilt="slope",
    camera_distance=4.0,
    stress_cases=STRESS_CASES,
    soak=soak,
    seam_mechanisms=("rollout",),
    checks=CHECKS,
    tolerances=TOLERANCES,
    gate_cases=GATE_CASES,
    rivals=RIVALS,
    peers=(drake_peer(wheel),),
    coverage=COVERAGE,
    search_space=search_space("timestep", "solref_timeconst", "solref_dampratio", "integrator", "foot_radius"),
    paper_results=PAPER_RESULTS,
    default=True, foot=WHEEL_FOOT,
)
