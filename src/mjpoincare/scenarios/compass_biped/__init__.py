"""Scenario ``compass-biped``: the passive compass-gait walker on a slope, sticking contact.

Analytic reference: Kiša (2020) Ch. 4 (EoM 4.5, impact law 4.15-4.17, gait of Fig. 18), the same
model as Goswami et al. (1996/98); see :mod:`mjpoincare.analysis.theory.compass_biped` (Newton shooting on the
exact hybrid model, finite-difference eigenvalues).

Contact protocol, as the analytic model assumes (003 Sec. 4.1): the swing foot's contact is off
from heel strike until the foot is ahead of the stance foot and clear of the ground (it passes
through the slope mid-swing, as the exact model's foot does; how deep is reported, without a
verdict), and the trailing foot's contact is switched off just before the next heel strike
(so the impact impulse acts at the new foot only). The switching is done by
:class:`mjpoincare.scenarios.compass_biped.controller.GaitController` through the rollout seam: MuJoCo steps natively
between events and each event restarts from the recorded state where it happened.

Poincaré section: legs parallel (003 eq 4.20), mid-swing, far from the soft impact. Its samples are
pulled back to the post-impact section with the exact swing flow for the ``fixed_point`` check; the
eigenvalues are section-independent.
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.adaptive_stopping import FitSettling, StoppingRule, return_map_settling
from mjpoincare.analysis.eigenvalues import eigenvalue_error, match_eigenvalues
from mjpoincare.analysis.returnmap import fit_return_map, regress_at, sample_pairs
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.analysis.theory.compass_biped.step_measurements import (
    crossing_steps,
    swing_foot_detail,
    swing_foot_report,
)
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.mjcf_loader import compile_spec, load_spec
from mjpoincare.core.params import Param, ParameterError
from mjpoincare.core.seam import RolloutReport
from mjpoincare.core.settings import search_space
from mjpoincare.scenarios.base import (
    AnalyticValues,
    CoveragePoint,
    Evaluation,
    FitSummary,
    Reported,
    Scenario,
    Soak,
    StressCase,
    Tolerances,
    Values,
    at_preset,
)
from mjpoincare.scenarios.compass_biped.controller import GaitController
from mjpoincare.scenarios.compass_biped.drake import drake_peer
from mjpoincare.scenarios.compass_biped.paper_results import PAPER_RESULTS
from mjpoincare.scenarios.compass_biped.rivals import RIVALS
from mjpoincare.scenarios.compass_biped.runs import (
    BIPED_FOOT,
    BIPED_IMPEDANCE,
    CHUNK_SECONDS,
    RELEASE_FALL_STEPS,
    STEPS,
    biped,
    initial_section_states,
    legs_parallel_figures,
    post_impact_states,
    release_tolerance,
    walk,
)
from mjpoincare.scenarios.gate_cases import GateCase
from mjpoincare.simulation.simulate import event_clip

PARAMS: tuple[Param, ...] = (
    Param("m_h", 10.0, "hip mass, kg", float, 0.0, 1e6, low_open=True),
    Param("m_l", 5.0, "leg point mass, kg", float, 0.0, 1e6, low_open=True),
    Param("a", 0.5, "foot to leg mass, m", float, 0.0, 100.0, low_open=True),
    Param("b", 0.5, "leg mass to hip, m", float, 0.0, 100.0, low_open=True),
    Param("slope", 0.04, "slope gamma, rad", float, 0.0, math.pi / 2, True, True),
    Param("mu", 1.0, "Coulomb friction (the gait needs about 0.25)", float, 0.0, 1e3),
    Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, low_open=True),
    Param("tau_ankle", 0.0, "constant ground torque on the stance leg, N m (clockwise: pushes the hip downhill)",
          float, -1e3, 1e3),
    Param("tau_hip", 0.0, "constant hip torque between the legs, N m (003 eq 4.5, B = (-1, 1))", float, -1e3, 1e3),
)

#: Both read off the preset search's studies (docs/results/tune/compass-biped.md); over-damped contact (why:
#: docs/scenarios/compass-biped.md, "Presets and start design"), and MuJoCo's own default impedance (solimp 0.9-0.95)
#: for the feet: at the suite's nearly hard 0.99-0.999 the loaded stance foot hovers within 1e-9 m of the slope and
#: its contact drops out of the step whenever the separation rounds above 0 (BIPED_IMPEDANCE).
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 8.72679790015e-05, "solref_timeconst": 0.000436830906143, "solref_dampratio": 4.37663471602,
             "integrator": "implicitfast", "foot_radius": 0.000256709130874, **BIPED_IMPEDANCE},
    "accurate": {"timestep": 2.5e-05, "solref_timeconst": 5.4e-05, "solref_dampratio": 5.89,
                 "integrator": "implicitfast", "foot_radius": 0.000484, **BIPED_IMPEDANCE},
}
TOLERANCES: dict[str, Tolerances] = {
    "accurate": Tolerances(
        bounds={"fixed_point": 1e-3, "eigenvalues": 0.01, "step_period": 1e-3, "step_length": 1e-3},
        why="the suite's accuracy target for an impact window of a few contact time constants; the preset is the "
            "cheapest setting a search found to hold it at every coverage point (docs/results/tune/compass-biped.md)"
    ),
    "fast": Tolerances(
        bounds={"fixed_point": 5e-3, "eigenvalues": 0.03, "step_period": 5e-3, "step_length": 5e-3},
        why="a soft over-damped contact of 0.44 ms over 0.09 ms steps (the searched fast preset): its impact "
            "lasts a few steps, where the exact one is instantaneous, so the one-step map, and through its fit the "
            "multipliers, carry a few times the accurate preset's error"
    ),
}

FIT_DEGREE = 3  # cubic: over the +-0.03 spread a quadratic fit's Jacobian absorbs the cubic terms (see STARTS)
#: The fitting batch stops once more steps no longer sharpen the fit (:mod:`mjpoincare.analysis.adaptive_stopping`);
#: first look at 3 samples per trajectory: 34 pairs for the cubic fit's 20 coefficients per coordinate.
STOPPING = StoppingRule(min_samples=3)
STEP_REGRESSION_DEGREE = 2  # per-step quantities regressed on the section state (an affine one is biased by the spread)


#: The largest hip-to-leg mass ratio m_h / m_l the model is run at. MuJoCo sizes a contact's softness by the
#: contact's own effective inverse mass (R = (1 - d) / d times the diagonal of A, "Solver parameters" of MuJoCo's
#: computation chapter); at a heel strike that is the light swing leg's, while the momentum the contact must stop
#: is the hip's, so the lighter the leg, the softer the heel strike is for the hip. Measured at the presets'
#: impedance (docs/scenarios/compass-biped.md, "Findings"; docs/scripts/cb_mass_ratio.py): the fixed point's error
#: grows about tenfold per decade of the ratio past 1e3, and past 1e4 the fast preset's biped falls.
MAX_MASS_RATIO = 1e4


def check_params(params: Values) -> None:
    """Refuse a hip-to-leg mass ratio past :data:`MAX_MASS_RATIO`, a slope with no stable passive gait, and friction
    below what the gait needs."""
    ratio = float(params["m_h"]) / float(params["m_l"])
    if ratio > MAX_MASS_RATIO:
        raise ParameterError(f"m_h / m_l must be <= {MAX_MASS_RATIO:g} (got {ratio:g}): past it MuJoCo's heel-strike "
                             "contact, as soft as the light swing leg's mass makes it, cannot stop the hip, and the "
                             "simulated biped falls")
    bp = biped(params)
    try:
        x_star = theory.fixed_point(bp)
        lam = theory.eigenvalues(bp, x_star)
        step = theory.step(bp, x_star)
    except (RuntimeError, ValueError) as err:
        raise ParameterError(f"slope={bp.slope:g} has no passive period-1 gait for these masses and lengths "
                             f"({str(err).splitlines()[0]})") from None
    if np.max(np.abs(lam)) >= 1.0:
        raise ParameterError(f"slope={bp.slope:g} gives an unstable passive gait (|lambda|max = "
                             f"{np.max(np.abs(lam)):.3f} >= 1): the stable range ends at the first period doubling")
    if step.min_normal_force_ratio <= 0:
        raise ParameterError(f"slope={bp.slope:g}: the stance foot would lift off during the gait")
    if float(params["mu"]) < step.required_friction:
        raise ParameterError(f"mu must be >= {step.required_friction:.4f} (the friction the passive gait needs) "
                             f"for these parameters (got {params['mu']})")


def build(params: Values, settings: Values) -> mujoco.MjModel:
    """The MJCF biped rebuilt through MjSpec with ``p`` (physics) and ``s`` (simulator settings)."""
    spec = load_spec("compass_biped.xml")
    sim_settings.apply_options(spec, settings)
    g, slope = float(params["gravity"]), float(params["slope"])
    spec.option.gravity = [g * math.sin(slope), 0.0, -g * math.cos(slope)]
    a, b, r = float(params["a"]), float(params["b"]), float(settings["foot_radius"])
    length = a + b
    spec.body("hip").mass = float(params["m_h"])
    mu = float(params["mu"])
    for i in (0, 1):
        leg = spec.body(f"leg{i}")
        leg.mass = float(params["m_l"])
        leg.ipos = [0.0, 0.0, -b]
        spec.geom(f"shank{i}").fromto = [0, 0, 0, 0, 0, -(length - r)]
        spec.geom(f"mass{i}").pos = [0, 0, -b]
        foot = spec.geom(f"foot{i}")
        foot.pos = [0, 0, -(length - r)]
        foot.size = [r, 0, 0]
        foot.friction = [mu, 0, 0]
        foot.solref = sim_settings.solref(settings)
        foot.solimp = sim_settings.solimp(settings)
    floor = spec.geom("slope")
    floor.friction = [mu, 0, 0]
    floor.solref = sim_settings.solref(settings)
    floor.solimp = sim_settings.solimp(settings)
    return compile_spec(spec, settings)


def _simulate(params: Values, settings: Values, settle: FitSettling | None = None
               ) -> tuple[GaitController, RolloutReport, theory.CompassBiped, mujoco.MjModel]:
    """The scenario's walk: its model, and the STARTS section states around the fixed point walked STEPS steps."""
    bp = biped(params)
    model = build(params, settings)
    controller, report = walk(model, bp, initial_section_states(bp, model.opt.timestep), STEPS, settings, settle)
    return controller, report, bp, model


def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
    """Simulate the perturbed gaits until their fit settles, fit the legs-parallel return map and check it against
    the theory."""
    tol = at_preset(TOLERANCES, COMPASS_BIPED.name, preset)
    # the fixed point's tolerance is stated for the post-impact state, which the exact swing flow maps the fitted
    # legs-parallel one to at about the same size
    settle = return_map_settling(STOPPING, degree=FIT_DEGREE, seed=seed, fixed_point_tolerance=tol["fixed_point"],
                                 eigenvalue_tolerance=tol["eigenvalues"]) if settings["adaptive_stopping"] else None
    controller, report, bp, model = _simulate(params, settings, settle)
    why = tol.why
    x_star = theory.fixed_point(bp)
    lam = theory.eigenvalues(bp, x_star)
    sequences = [np.array(seq) for seq in controller.samples]
    out: list[checks.Check] = []
    extras: dict[str, object] = {}
    try:
        x, x_next = sample_pairs(sequences)
        fit = fit_return_map(x, x_next, degree=FIT_DEGREE, seed=seed)
    except ValueError as err:
        out.append(checks.absolute("fixed_point", x_star, math.nan, tol["fixed_point"], "rad, rad/s",
                                   f"no return map: {err}"))
        return Evaluation(out, report, extras)
    y_star = fit.fixed_point
    try:
        x_sim = theory.post_impact_from_parallel(bp, y_star)
    except RuntimeError as err:  # the fitted gait lies where the exact biped falls: a physics failure, reported
        out.append(checks.absolute("fixed_point", x_star, math.nan, tol["fixed_point"], "rad, rad/s",
                                   f"the fitted legs-parallel fixed point {np.round(y_star, 6).tolist()} has no "
                                   f"exact pull-back: {str(err).splitlines()[0]}"))
        return Evaluation(out, report, extras)
    out.append(checks.Check(name="fixed_point", analytic=x_star, simulated=x_sim,
                            error=float(np.max(np.abs(x_sim - x_star))), tolerance=tol["fixed_point"], kind="max-abs",
                            unit="rad, rad/s",
                            why="post-impact state (theta_st, theta_sw, dtheta_st, dtheta_sw), thesis frame, from the "
                            "fitted legs-parallel fixed point pulled back by the exact swing flow; " + why))
    matched = match_eigenvalues(lam, fit.eigenvalues)
    out.append(checks.Check(name="eigenvalues", analytic=lam, simulated=matched,
                            error=float(np.max(np.abs(matched - lam))), tolerance=tol["eigenvalues"], kind="max-abs",
                            unit="", why="3 multipliers of the 3-D section map (Newton shooting + finite "
                            "differences on the exact model) vs the cubic fit of the MuJoCo samples"))
    ys, dts, lengths, _ = crossing_steps(controller.samples, controller.sample_times, controller.strikes)
    period_sim = regress_at(y_star, ys, dts, STEP_REGRESSION_DEGREE)
    length_sim = regress_at(y_star, ys, lengths, STEP_REGRESSION_DEGREE)
    out.append(checks.relative("step_period", theory.step_period(bp, x_star), period_sim, tol["step_period"], "s",
                               "time between legs-parallel crossings, regressed (quadratic) on the section state at "
                               "the fitted fixed point"))
    out.append(checks.relative("step_length", theory.step_length(bp, x_star), length_sim, tol["step_length"], "m",
                               "distance between successive stance feet, regressed (quadratic) at the fitted fixed "
                               "point: an affine regression is biased by the starts' spread (3e-4 quadratic against "
                               "1.3e-3 affine over the first 6 steps, 5.6e-4 over 10, accurate preset)"))
    accel, release_tol = release_tolerance(model, bp, x_star, float(settings["foot_radius"]))
    depth = max(controller.release_depth, default=math.nan)
    out.append(checks.Check(name="trailing_foot_release", analytic=0.0, simulated=depth, error=depth,
                            tolerance=release_tol, kind="max-abs", unit="m",
                            why="deepest the released trailing foot went below its height at release within 20 ms of "
                            f"heel strike, against its free fall from rest over {RELEASE_FALL_STEPS} steps, |a| dt^2 "
                            f"n(n+1)/2 (semi-implicit Euler; a = {accel:.3g} m/s^2, its unsupported acceleration at "
                            "the exact pre-impact state): the new foot reaches the slope 2 steps after the release "
                            "and its contact reverses the trailing foot within the next step, 3 |a| dt^2 from rest; "
                            "measured over 250 releases each: mean 3.1 |a| dt^2, max 5.6 (fast), mean 2.9, max 5.9 "
                            "(20 us steps, 0.2 ms contact; the spread is the foot's speed at release, up to ~1e-3 m/s "
                            "either way; a stiffer contact catches the foot sooner). A "
                            "deeper dip: the foot was released steps early, or kept falling after the heel strike, "
                            "whose impact law (003 eqs 4.15-4.17) has it lift off unloaded"))
    exact_depth = -theory.lowest_swing_height(bp, x_star)
    reported = {"swing_foot_depth": Reported(**swing_foot_report(controller.swing_low, exact_depth))}
    extras["swing_foot"] = swing_foot_detail(bp, controller.swing_low[0], controller.samples[0],
                                             float(settings["foot_radius"]), exact_depth)
    extras["adaptive_stopping"] = None if settle is None else settle.to_dict()
    extras["trailing_foot"] = {"analytic_liftoff_velocity": theory.step(bp, x_star).liftoff_velocity,
                               "measured_vertical_speed_20ms": float(np.mean(controller.release_speed))
                               if controller.release_speed else math.nan, "releases": len(controller.release_depth)}
    y_star_th = theory.legs_parallel_state(bp, x_star)[0]
    analytic = AnalyticValues(eigenvalues=lam, values={"fixed_point": x_star, "legs_parallel_fixed_point": y_star_th,
                                                       "step": _step_summary(bp, x_star)})
    plot, convergence = legs_parallel_figures(
        "legs-parallel angle theta (rad)", ["theta (rad)", "dtheta_st (rad/s)", "dtheta_sw (rad/s)"], x, x_next, lam,
        y_star_th, sequences)
    return Evaluation(out, report, extras, analytic=analytic, fit=FitSummary.of(fit), return_map=plot,
                      section_convergence=convergence, reported=reported)



def _step_summary(bp: theory.CompassBiped, x_star: np.ndarray) -> dict[str, float]:
    step = theory.step(bp, x_star)
    return {"required_friction": step.required_friction, "min_normal_force_ratio": step.min_normal_force_ratio,
            "trailing_foot_liftoff_velocity": step.liftoff_velocity}



def validation_batches(params: Values, settings: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """Model and initial states of the gait batch (contacts fixed: the raw-rate reference)."""
    bp = biped(params)
    model = build(params, settings)
    period = theory.step_period(bp, theory.fixed_point(bp))
    starts = post_impact_states(model, bp, initial_section_states(bp, model.opt.timestep),
                                float(settings["foot_radius"]))
    return model, [(starts, math.ceil((STEPS + 0.5) * period / model.opt.timestep))]


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact reference (solve_ivp at ``rtol``) over the default preset's starts and steps, through the same
    fit: its error is the floor the experiment design sets."""
    bp = biped(params)
    start = time.perf_counter()
    sequences = []
    for x in initial_section_states(bp, float(PRESETS["fast"]["timestep"])):  # the default preset's design
        seq = []
        for _ in range(STEPS):
            seq.append(theory.legs_parallel_state(bp, x)[0])
            x = theory.step(bp, x, rtol=rtol, atol=rtol).x_plus_next
        sequences.append(np.array(seq))
    fit = fit_return_map(*sample_pairs(sequences), degree=FIT_DEGREE)
    wall = time.perf_counter() - start
    x_star = theory.fixed_point(bp)
    x_sim = theory.post_impact_from_parallel(bp, fit.fixed_point)
    lam = theory.eigenvalues(bp, x_star)
    return {"rtol": rtol, "wall_s": wall, "fixed_point_error": float(np.max(np.abs(x_sim - x_star))),
            "eigenvalues_error": eigenvalue_error(lam, fit.eigenvalues)}


def soak(params: Values, settings: Values, impacts: int) -> Soak:
    """``impacts`` steps from the analytic fixed point: the stance leg's rate at each legs-parallel crossing."""
    bp = biped(params)
    x_star = theory.fixed_point(bp)
    controller, report = walk(build(params, settings), bp, x_star[None, :], impacts, settings)
    samples = np.array(controller.samples[0]).reshape(-1, 3)[:, 1]
    return Soak(samples, float(theory.legs_parallel_state(bp, x_star)[0][1]),
                "stance-leg rate at legs-parallel (rad/s)", report)


STRESS_CASES = (
    StressCase("Goswami walker", {"m_h": "2", "m_l": "1", "slope": "0.0524"}, "m_h/m = 2 on 3 degrees"),
    StressCase("near period doubling", {"m_h": "2", "m_l": "1", "slope": "0.0755"},
               "|lambda|max = 0.93: slow flip mode"),
    StressCase("shallow slope", {"slope": "0.01"}, "slow, short steps"),
    StressCase("friction at the bound", {"mu": "0.25"}, "just above the friction the gait needs"),
    StressCase("heavy legs", {"m_l": "10"}, "m_h/m_l = 1"),
    StressCase("masses low on the legs", {"a": "0.4", "b": "0.6"}, "leg masses 0.4 m above the feet"),
    StressCase("light hip", {"m_h": "20", "m_l": "5"}, "m_h/m_l = 4: no period-1 gait at 0.04 (the Newton "
               "shooting finds none)", expect="refused"),
    StressCase("unstable slope", {"m_h": "2", "m_l": "1", "slope": "0.08"}, "past the period doubling",
               expect="refused"),
    StressCase("negative mass", {"m_h": "-1"}, "masses must be positive", expect="refused"),
    StressCase("too little friction", {"mu": "0.05"}, "below what the gait needs", expect="refused"),
)


def video_states(params: Values, settings: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """States of a clip from the analytic post-impact fixed point, with the gait's contact switching."""
    bp = biped(params)
    start = post_impact_states(model, bp, theory.fixed_point(bp)[None, :], float(settings["foot_radius"]))
    controller = GaitController(model, bp, 1, float(settings["foot_radius"]))
    chunk = max(10, round(CHUNK_SECONDS / model.opt.timestep))
    return event_clip(model, start, nstep, controller, chunk, setup=controller.configure).states(nstep)


#: The checks :func:`evaluate` reports, at any parameters: the fitted map's fixed point and multipliers, the step and
#: the trailing foot's release (003 eqs 4.15-4.20; a run with too few samples reports the fixed point alone, the
#: others then fail as missing).
CHECKS = ("fixed_point", "eigenvalues", "step_period", "step_length", "trailing_foot_release")


#: Where a preset must hold (mjpoincare tune): the defaults, Goswami's walker (m_h/m = 2, 3 degrees: a larger step
#: angle and faster impacts) and the gate's actuated gait. As for the rimless wheel, no point lies closer than the
#: defaults to a limit where a checked quantity vanishes: towards slope 0 the step length goes to 0 while the soft
#: impact's displacement of the foot does not, so the step length's relative error grows without bound (a study with
#: slope 0.01 as a coverage point found no setting within the accurate tolerances there).
_BIPED = ("fixed_point", "step_period", "step_length", "stable")
#: The gate's runs of this scenario (:mod:`mjpoincare.gate.forms`), as measured by ``mjpoincare margins`` over its
#: ensemble of environments (docs/results/gate/: MuJoCo 4.0.0, numpy 2.4.6, scipy 1.17.1; the OpenBLAS kernels Prescott
#: to Zen, numpy at its baseline, and the perturbations): each spread is the measured one rounded up to 2 digits.
GATE_CASES: tuple[GateCase, ...] = (
    GateCase.of("compass-biped", "fast", ("eigenvalues", "trailing_foot_release", *_BIPED)),
    GateCase.of("compass-biped", "fast", ("eigenvalues", "trailing_foot_release", *_BIPED), tau_ankle=0.5, tau_hip=0.2),
    GateCase.of("compass-biped", "accurate", ("eigenvalues", "trailing_foot_release", *_BIPED)),
)


COVERAGE = (
    CoveragePoint("defaults", {}, "m_h = 10, m = 5, slope 0.04"),
    CoveragePoint("Goswami walker", {"m_h": "2", "m_l": "1", "slope": "0.0524"}, "m_h/m = 2 on 3 degrees"),
    CoveragePoint("actuated", {"tau_ankle": "0.5", "tau_hip": "0.2"}, "the regression gate's actuated gait: constant "
                  "ankle and hip torques (003 eq 4.5)"),
)

COMPASS_BIPED = Scenario(
    name="compass-biped",
    summary="passive compass-gait walker on a slope: fixed point, 3 eigenvalues, step period and length",
    source="Kisa 2020 Ch. 4 (eq 4.5, 4.15-4.20, Fig. 18); Goswami et al. 1996/98 benchmark",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    bench_checks=("fixed_point", "eigenvalues", "step_period", "step_length"),
    validation_batches=validation_batches,
    exact_model_bench=exact_model_bench,
    video_states=video_states,
    track_body="hip",
    frame_tilt="slope",
    camera_distance=3.0,
    stress_cases=STRESS_CASES,
    soak=soak,
    seam_mechanisms=("rollout", "contact", "actuator", "fractional_step"),
    checks=CHECKS,
    rivals=RIVALS,
    tolerances=TOLERANCES,
    gate_cases=GATE_CASES,
    peers=(drake_peer(biped),),
    coverage=COVERAGE,
    search_space=search_space("timestep", "solref_timeconst", "solref_dampratio", "integrator", "foot_radius"),
    paper_results=PAPER_RESULTS,
    default=True, foot=BIPED_FOOT,
)
