"""Scenario ``compass-biped-friction``: the compass biped with Coulomb friction, passive and actuated.

Analytic reference: Gamus & Or (2015), 002, Sec. 4 (passive Gaits A, B on a 1 deg slope, eq 27, Figs
4.1-4.2) and Sec. 5 (Gait I: constant torques, eq 28; Gait III: PD tracking with phase reset, eq 30; cost of
transport eq 29); re-derived in :mod:`mjpoincare.analysis.theory.compass_biped_friction`.

MuJoCo side: the ``compass-biped`` model rebuilt with 002's parameters (l = 1.6 m, d = 0.8 m: a = b = 0.8 m,
m = 4 kg, m_h = 2 kg, g = 9.8 m/s^2) by :func:`mjpoincare.scenarios.compass_biped.build`, and its contact
protocol (swing foot off until ahead and clear, trailing foot released at heel strike;
:class:`mjpoincare.scenarios.compass_biped.controller.FrictionGaitController`). Angles: the stance hinge
is 002's theta1, the swing hinge is -theta2 (002 eq 27: theta2 is the swing leg's hip->foot direction), so the
paper's generalised forces map to hinge torques as stance = Q_theta1, swing = -Q_theta2:

* Gait I (E_eff, Q = (-tau1 - tau2, tau2) = (2.19, 0.54) N m): ankle torque 1.65 N m on the stance hinge and hip
  torque -0.54 N m on the tendon (stance hinge tau_ankle - tau_hip = 2.19, swing hinge tau_hip = -0.54).
* Gait III (direct PD, eq 30): each ankle actuator gets gainprm[0] = 1 and biasprm = (0, -kp, -kd); the
  reference term is ctrl, fed natively through :func:`mjpoincare.simulation.simulate.event_rollout`'s ``control``:
  stance ctrl = kp theta1^r + kd theta1_dot^r, swing ctrl = -(kp theta2^r + kd theta2_dot^r), phi = time since the
  trajectory's last heel strike (phase reset).

Checks: the fixed point and multipliers of the return map on the legs-parallel section (hinge angles equal,
mid-stance, away from the soft impact; fitted from perturbed starts), step length / period / speed and (actuated)
the cost of transport with the actuator work integrated from the recorded rows; Gait A: the friction ratio
|f_t/f_n| from the centre-of-mass acceleration (the only contact is the stance foot) against 002's mu_c; every
gait: the stance phases, the impact kind and the slide in the first 5 ms after the impact from the stance foot's
tangential velocity and position, against the exact step read the same way (measured by
:mod:`mjpoincare.analysis.theory.compass_biped_friction.stance_measurements`, checked in
:mod:`mjpoincare.scenarios.compass_biped_friction.stance`). Reported without a verdict: how deep the switched-off
swing foot goes below the slope (002 Sec. 4.1 ignores this scuffing).
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.adaptive_stopping import StoppingRule, return_map_settling
from mjpoincare.analysis.eigenvalues import eigenvalue_error, match_eigenvalues
from mjpoincare.analysis.returnmap import fit_return_map, regress_at, sample_pairs
from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.analysis.theory.compass_biped.step_measurements import crossing_steps, swing_foot_report
from mjpoincare.analysis.theory.compass_biped_friction.stance_measurements import classified_pattern, stance_rows
from mjpoincare.core.params import Param, ParameterError
from mjpoincare.scenarios import compass_biped as cb
from mjpoincare.scenarios.base import (
    AnalyticValues,
    CoveragePoint,
    Evaluation,
    FitSummary,
    Reported,
    Scenario,
    StressCase,
    Tolerances,
    Values,
    at_preset,
)
from mjpoincare.scenarios.compass_biped.runs import BIPED_FOOT, legs_parallel_figures
from mjpoincare.scenarios.compass_biped_friction.gait_choice import friction, gait, gait_name
from mjpoincare.scenarios.compass_biped_friction.gate import GATE_CASES
from mjpoincare.scenarios.compass_biped_friction.paper_results import PAPER_RESULTS
from mjpoincare.scenarios.compass_biped_friction.presets import PRESETS
from mjpoincare.scenarios.compass_biped_friction.rivals import RIVALS
from mjpoincare.scenarios.compass_biped_friction.stance import stance_checks
from mjpoincare.scenarios.compass_biped_friction.start_design import (
    FIT_DEGREE,
    SETTLE,
    design,
    horizon,
    initial_section_states,
    post_impact_states,
    unstable,
)
from mjpoincare.scenarios.compass_biped_friction.walk import build, run_gait

GAITS = ("a", "b", "c", "i", "ii", "iii")
#: 002 types of each named gait (classify: A stick throughout, B sticking impact with slip, C slipping impact);
#: Gait I, like the passive A/B branch, slips during the stance below its mu_c (type B from mu ~0.17 down).
KIND = {"A": ("A",), "B": ("B",), "C": ("C",), "I": ("A", "B"), "II": ("C",), "III": ("C",)}
#: Gaits 002 reports unstable (C: Sec. 4.2; II: Sec. 5); B and I past their stability loss are refused.
UNSTABLE = ("C", "II")
#: The actuated gaits (002 Sec. 5), whose cost of transport is checked (eq 29).
ACTUATED = ("I", "II", "III")
#: Every check :func:`evaluate` reports for some gait, in its order; :func:`checks_at`: those of one gait.
CHECKS = ("fixed_point", "eigenvalues", "gait_stability", "step_period", "step_length", "speed", "cost_of_transport",
          "friction_ratio_window", "critical_friction", "phase_sequence", "phase_times", "impact_kind", "impact_slip")

PARAMS: tuple[Param, ...] = (
    Param("gait", "a", "002 gait: a, b, c (passive, 1 deg slope; c unstable), i, ii (constant torques; ii unstable),"
          " iii (PD tracking Gait C)", str, choices=GAITS),
    Param("mu", 0.0, "Coulomb friction; 0 = the gait's paper value (A 1, B 0.14, C 0.2, I 0.2, II 0.2, III 0.2)",
          float, 0.0, 1e3),
    Param("kp", 15.0, "Gait III PD stiffness, N m/rad (002 eq 30)", float, 0.0, 1e4),
    Param("kd", 15.0, "Gait III PD damping, N m s/rad (002 eq 30)", float, 0.0, 1e4),
)

#: Why each tolerance is what it is: docs/scenarios/compass-biped-friction.md, "Tolerances and start design".
TOLERANCES: dict[str, Tolerances] = {
    "accurate": Tolerances(
        bounds={"fixed_point": 1e-3, "eigenvalues": 0.01, "step_period": 1e-3, "step_length": 1e-3, "speed": 1e-3,
                "cost_of_transport": 5e-3, "friction_ratio": 2e-3, "phase_time": 2e-3},
        why="0.2 ms overdamped contact and 20 us steps: impact window ~1 ms; 1e-3 is the accuracy the accurate "
            "preset promises",
    ),
    "fast": Tolerances(
        bounds={"fixed_point": 5e-3, "eigenvalues": 0.03, "step_period": 5e-3, "step_length": 5e-3, "speed": 5e-3,
                "cost_of_transport": 1e-2, "friction_ratio": 5e-3, "phase_time": 5e-3},
        why="a soft contact of 0.3 ms over 0.12 ms steps (the searched fast preset): its impact lasts a few "
            "steps, where the exact one is instantaneous, so the one-step map, and through its fit the multipliers, "
            "carry a few times the accurate preset's error",
    ),
}

#: A stable gait's starts stop once more steps no longer sharpen its fit (:mod:`mjpoincare.analysis.adaptive_stopping`);
#: first look at 3 samples per trajectory (2 pairs each: 34 pairs for the cubic fit's 20 coefficients per coordinate);
#: trajectory 0 walks on to SETTLE + 2 samples, so that it has settled stances to check.
STOPPING = StoppingRule(min_samples=3)
SETTLED_SAMPLES = SETTLE + 2


def check_params(params: Values) -> None:
    """Refuse parameters without the named gait of 002 (continuation fails, or a gait of another type). Unstable
    gaits (C, II; B and I past their stability loss) are accepted: they are fitted over a short horizon."""
    name, mu = gait_name(params), friction(params)
    if name != "III" and (float(params["kp"]), float(params["kd"])) != (15.0, 15.0):
        raise ParameterError(f"kp, kd apply to gait=iii only (got gait={params['gait']})")
    try:
        g = gait(params)
    except (ValueError, RuntimeError) as err:
        raise ParameterError(f"mu={mu:g}: no Gait {name} of 002 ({str(err).splitlines()[0]})") from None
    expected = KIND[name]
    if g.kind not in expected:
        raise ParameterError(f"mu={mu:g}: the gait found is of type {g.kind}, not Gait {name}'s {'/'.join(expected)} "
                             f"({theory.describe(g.record)}); mu_c of the A/B branch is 0.1749")


def stability_class(radius: float) -> str:
    """``"stable"`` when a map's spectral radius ``radius`` is below 1 (002 Sec. 4.2), else ``"unstable"``."""
    return "stable" if radius < 1.0 else "unstable"


def checks_at(params: Values, settings: Values) -> tuple[str, ...]:
    """The checks :func:`evaluate` reports for the gait at ``params``: every gait's map, step and stance checks, the
    actuated gaits' cost of transport (002 eq 29), Gait A's friction ratio and mu_c (002 Sec. 4.1), and the phase
    switch times where the exact step, classified on the ``settings``' timestep grid as the simulated rows are, has
    more than one phase
    (:func:`~mjpoincare.analysis.theory.compass_biped_friction.stance_measurements.classified_pattern`; Gait II's 5.2 ms
    slip+ ends inside the window the labels skip). A run without settled stances, or whose phases differ from the exact
    step's, does not report the stance checks it cannot measure: they fail as missing."""
    name = gait_name(params)
    own = {"cost_of_transport": name in ACTUATED, "friction_ratio_window": name == "A",
           "critical_friction": name == "A",
           "phase_times": len(classified_pattern(gait(params), float(settings["timestep"]))) > 1}
    return tuple(check for check in CHECKS if own.get(check, True))


def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
    """Simulate perturbed gaits, fit the legs-parallel return map, and check it and the gait's friction, phases
    and cost against 002 (via :mod:`mjpoincare.analysis.theory.compass_biped_friction`)."""
    g = gait(params)
    name = gait_name(params)
    model = build(params, settings)
    tol = at_preset(TOLERANCES, COMPASS_BIPED_FRICTION.name, preset)
    why = tol.why
    steps, degree, settle = design(g)
    settling = None if unstable(g) or not settings["adaptive_stopping"] else return_map_settling(
        STOPPING, degree=degree, seed=seed, fixed_point_tolerance=tol["fixed_point"],
        eigenvalue_tolerance=tol["eigenvalues"])
    c, report, _ = run_gait(params, settings, model, initial_section_states(g, model.opt.timestep), steps,
                        settling=settling, first_samples=SETTLED_SAMPLES)
    out: list[checks.Check] = []
    extras: dict[str, object] = {"gait": name, "mu": friction(params), "analytic_pattern": theory.describe(g.record)}
    y_star_th, _ = theory.legs_parallel(g)
    lam = g.eigenvalues[:3]  # sorted by modulus, descending
    sequences = [np.array(v) for v in c.samples]
    try:
        x, x_next = sample_pairs(sequences)
        fit = fit_return_map(x, x_next, degree=degree, seed=seed)
    except ValueError as err:
        out.append(checks.absolute("fixed_point", y_star_th, math.nan, tol["fixed_point"], "rad, rad/s",
                                   f"no return map: {err}"))
        return Evaluation(out, report, extras)
    y_star = fit.fixed_point
    out.append(checks.Check(name="fixed_point", analytic=y_star_th, simulated=y_star,
                            error=float(np.max(np.abs(y_star - y_star_th))), tolerance=tol["fixed_point"],
                            kind="max-abs", unit="rad, rad/s",
                            why="legs-parallel state (theta1, theta1_dot, -theta2_dot), 002 eq 27 frame, of the fitted "
                            "map vs the analytic step from z*; " + why))
    matched = match_eigenvalues(lam, fit.eigenvalues)
    out.append(checks.Check(name="eigenvalues", analytic=lam, simulated=matched,
                            error=float(np.max(np.abs(matched - lam))), tolerance=tol["eigenvalues"], kind="max-abs",
                            unit="", why="the 3 largest multipliers of 002's post-impact map (Newton + finite "
                            f"differences) vs the degree-{degree} fit of the MuJoCo legs-parallel samples (bootstrap "
                            f"std of the fitted multipliers {float(np.max(np.abs(fit.eigenvalue_std))):.2g}: an "
                            "error well above it is MuJoCo's map, not the sampling); " + why))
    radius, radius_fit = float(np.max(np.abs(lam))), float(np.max(np.abs(fit.eigenvalues)))
    kind, kind_fit = stability_class(radius), stability_class(radius_fit)
    out.append(checks.categorical("gait_stability", kind, kind_fit, int(kind != kind_fit), 1,
                                  why=f"stable when every multiplier lies inside the unit circle (002 Sec. 4.2): "
                                  f"|lambda|max {radius:.4g} analytic, {radius_fit:.4g} of the fitted map; an "
                                  "eigenvalue error that reads an unstable gait as stable, or the reverse, fails here"))
    ys, dts, lengths, works = crossing_steps(c.samples, c.sample_times, c.strikes, first=1, step_work=c.step_work)
    rec = g.record
    # quadratic where the map is fitted as a cubic over the full design; affine for a type-B gait's narrow starts and
    # an unstable gait's single step per start (too few samples for a quadratic's 10 terms)
    regression = cb.STEP_REGRESSION_DEGREE if degree == FIT_DEGREE else 1
    period_sim = regress_at(y_star, ys, dts, regression)
    length_sim = regress_at(y_star, ys, lengths, regression)
    out.append(checks.relative("step_period", rec.period, period_sim, tol["step_period"], "s",
                               f"time between legs-parallel crossings, regressed (degree {regression}) at the fitted "
                               "fixed point"))
    out.append(checks.relative("step_length", rec.step_length, length_sim, tol["step_length"], "m",
                               f"distance between successive stance feet (002 S), regressed (degree {regression}) at "
                               "the fitted fixed point"))
    out.append(checks.relative("speed", theory.average_speed(rec), length_sim / period_sim, tol["speed"], "m/s",
                               "average speed S/T (002 Sec. 5)"))
    if name in ACTUATED:
        work_sim = regress_at(y_star, ys, works, regression)
        cmt = work_sim / (g.biped.total_mass * g.biped.g * length_sim)
        out.append(checks.relative("cost_of_transport", theory.cost_of_transport(g.biped, rec), cmt,
                                   tol["cost_of_transport"], "", "c_mt = W/(M_tot g S) (002 eq 29), W = sum "
                                   "of actuator force x hinge rate x dt over the recorded rows of a step, regressed at "
                                   "the fitted fixed point"))
        extras["actuator_work"] = {"analytic": rec.actuator_work, "simulated": work_sim}
    stances = stance_rows(np.concatenate(c.rows0), [t for t, _ in c.strikes[0]], g.biped,
                          float(settings["foot_radius"]))[settle:]
    out += stance_checks(g, name, stances, model.opt.timestep, float(settings["solref_timeconst"]), tol, extras)
    if settling is not None:
        extras["adaptive_stopping"] = settling.to_dict()
    reported = {"swing_foot_depth": Reported(**swing_foot_report(c.swing_low, -g.record.min_swing_height))}
    analytic = AnalyticValues(eigenvalues=g.eigenvalues, values={"z": g.z, "legs_parallel": y_star_th})
    plot, convergence = legs_parallel_figures(
        "legs-parallel angle theta1 (rad)", ["theta1 (rad)", "theta1_dot (rad/s)", "-theta2_dot (rad/s)"], x, x_next,
        lam, y_star_th, sequences)
    return Evaluation(out, report, extras, analytic=analytic, fit=FitSummary.of(fit), return_map=plot,
                      section_convergence=convergence, reported=reported)


def validation_batches(params: Values, settings: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """Model and initial states of the gait batch (contacts fixed: the raw-rate reference)."""
    g = gait(params)
    model = build(params, settings)
    starts = post_impact_states(model, g.biped, initial_section_states(g, model.opt.timestep),
                                float(settings["foot_radius"]))
    return model, [(starts, horizon(g, design(g)[0], model.opt.timestep))]


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact map (stance integration at relative tolerance ``rtol``) over the fast preset's starts and steps,
    through the same fit; the legs-parallel samples are read on the reference trajectory of each post-impact state."""
    g = gait(params)
    start = time.perf_counter()
    y_star, _ = theory.legs_parallel(g)
    sequences = []
    for z in initial_section_states(g, float(PRESETS["fast"]["timestep"]))[:6]:
        seq = []
        for _ in range(design(g)[0]):
            gz = theory.Gait(g.biped, g.actuation, z, g.jacobian, g.eigenvalues, g.record, g.kind)
            seq.append(theory.legs_parallel(gz)[0])
            z = theory.return_map(g.biped, z, g.actuation, rtol)
        sequences.append(np.array(seq))
    fit = fit_return_map(*sample_pairs(sequences), degree=design(g)[1])
    lam = g.eigenvalues[:3]  # sorted by modulus, descending
    return {"rtol": rtol, "wall_s": time.perf_counter() - start,
            "fixed_point_error": float(np.max(np.abs(fit.fixed_point - y_star))),
            "eigenvalues_error": eigenvalue_error(lam, fit.eigenvalues)}


def video_states(params: Values, settings: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """States of a clip from the analytic fixed point, with the gait's contact switching and actuation."""
    g = gait(params)
    steps = math.ceil(nstep * model.opt.timestep / g.record.period)
    _, _, kept = run_gait(params, settings, model, g.z[None, :], steps, wrap=True)
    assert kept is not None
    return kept.states(nstep)


STRESS_CASES = (
    StressCase("Gait A at mu_c", {"gait": "a", "mu": "0.176"}, "just above 002's mu_c = 0.1749"),
    StressCase("Gait B near stability loss", {"gait": "b", "mu": "0.115"}, "|lambda|max -> 1 at mu = 0.1104"),
    StressCase("Gait I low friction", {"gait": "i", "mu": "0.12"}, "close to its stability loss at 0.1035"),
    StressCase("Gait A below mu_c", {"gait": "a", "mu": "0.15"}, "that is Gait B", expect="refused"),
    StressCase("Gait B unstable", {"gait": "b", "mu": "0.1"}, "past the stability loss: 2-step fit"),
    StressCase("negative friction", {"mu": "-0.1"}, "mu must be >= 0", expect="refused"),
    StressCase("unknown gait", {"gait": "d"}, "002 has no Gait D for the compass biped", expect="refused"),
)


#: Where a preset must hold (mjpoincare tune): each of the paper's gaits. Gaits B, C, II and III miss their eigenvalue
#: tolerance at both presets (docs/scenarios/compass-biped-friction.md, Findings: the soft impact against B's
#: stick-slip stance, C's and II's unstable 2-step fits, III's tracking through the soft impact), so the search
#: reports its best settings for them without requiring them of a preset.
COVERAGE = tuple(CoveragePoint(f"Gait {g.upper()}", {"gait": g}, why, miss_at=("fast", "accurate") if miss else ())
                 for g, why, miss in (
    ("a", "passive, mu = 1: sticking", False), ("b", "passive, mu = 0.14: slip after the impact", True),
    ("c", "passive, mu = 0.2: unstable", True), ("i", "constant torques, mu = 0.2", False),
    ("ii", "constant torques, mu = 0.2: unstable, slipping impact", True),
    ("iii", "PD tracking Gait C, mu = 0.2", True)))

COMPASS_BIPED_FRICTION = Scenario(
    name="compass-biped-friction",
    summary="compass biped with Coulomb friction (002): Gaits A/B/C (slope), I/II/III (actuated, level ground)",
    source="Gamus & Or 2015 Secs. 4-5 (eqs 27-30, Figs 4.1-5.2); derivation page docs/theory/stick-slip.md Secs. 3, 7",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    bench_checks=("eigenvalues", "fixed_point", "step_length"),
    validation_batches=validation_batches,
    exact_model_bench=exact_model_bench,
    video_states=video_states,
    track_body="hip",
    camera_distance=3.5,
    stress_cases=STRESS_CASES,
    seam_mechanisms=("rollout", "contact", "actuator", "control", "fractional_step"),
    checks=CHECKS,
    checks_at=checks_at,
    rivals=RIVALS,
    tolerances=TOLERANCES,
    gate_cases=GATE_CASES,
    coverage=COVERAGE,
    foot=BIPED_FOOT,
    paper_results=PAPER_RESULTS,
)
