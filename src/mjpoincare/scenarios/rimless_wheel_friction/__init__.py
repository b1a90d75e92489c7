"""Scenario ``rimless-wheel-friction``: the planar rimless wheel with Coulomb friction, stick-slip gaits A-D.

Analytic reference: Gamus & Or (2015), Sec. 3 and Appendix A, through the exact event-driven hybrid simulator of
:mod:`mjpoincare.analysis.theory.rimless_wheel_friction`, run from the simulated starts by
:mod:`mjpoincare.analysis.stick_slip_reference`. Gait types (002 Sec. 3.3): A sticking impact and stick throughout;
B sticking impact, stick -> slip; C slipping impact, slip -> stick -> slip; D slipping impact and forward slip
throughout (D+ / D-: the slip speed grows / shrinks each step; D- is a transient).

Model: the planar wheel of :mod:`mjpoincare.scenarios.rimless_wheel`, rebuilt by its ``build`` with the hub's radius
of gyration sqrt(kappa) l and friction ``mu`` on both the feet and the floor. The model, the batch and the
measurement, vectorised on the recorded rows: :mod:`mjpoincare.scenarios.rimless_wheel_friction.rollout` (mid-stance
section theta = 0; contact modes from friction-cone saturation, phases, impacts and gait types by
:mod:`mjpoincare.analysis.stick_slip_phases` with its per-preset thresholds; the force ratio and mu_c by
:mod:`mjpoincare.analysis.force_ratio`). Rates are nondimensional (002's units, m = l = 1,
omega_c = sqrt(g/(l(1+kappa))) = 1). The friction sweep and the regions of attraction, which reuse that experiment:
:mod:`mjpoincare.scenarios.rimless_wheel_friction.sweep` and :mod:`mjpoincare.scenarios.rimless_wheel_friction.basins`.
Why the presets, thresholds and starts are what they are: docs/scenarios/rimless-wheel-friction.md.
"""

from __future__ import annotations

import math
from dataclasses import asdict
from typing import Any

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis import stick_slip_phases as phases
from mjpoincare.analysis import stick_slip_reference as reference
from mjpoincare.analysis.sections import level_crossings
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.core.params import Param, ParameterError
from mjpoincare.core.settings import search_space
from mjpoincare.scenarios.base import (
    AnalyticValues,
    CoveragePoint,
    Evaluation,
    FitSummary,
    Reported,
    ReturnMapPlot,
    Scenario,
    Soak,
    StressCase,
    Tolerances,
    Values,
    at_preset,
)
from mjpoincare.scenarios.gate_cases import GateCase, Watch
from mjpoincare.scenarios.rimless_wheel.runs import MIN_GYRATION, WHEEL_FOOT
from mjpoincare.scenarios.rimless_wheel_friction.basins import REGION_MAP
from mjpoincare.scenarios.rimless_wheel_friction.paper_results import PAPER_RESULTS
from mjpoincare.scenarios.rimless_wheel_friction.rivals import RIVALS
from mjpoincare.scenarios.rimless_wheel_friction.rollout import (
    D_SIM_STEPS,
    FIT_OFFSETS,
    FIT_PAIRS,
    SETTLED_STEPS,
    SIM_STEPS,
    build,
    classifier,
    fit_starts,
    friction_wheel,
    gait_start,
    period_seconds,
    rate_unit,
    reference_gait,
    row_signals,
    run_batch,
    simulate,
    sliding_contact,
    start_states,
)
from mjpoincare.scenarios.rimless_wheel_friction.sweep import MU_SWEEP
from mjpoincare.simulation.simulate import plain_clip

PAPER_SLOPE = math.radians(13.0)

PARAMS: tuple[Param, ...] = (
    Param("spokes", 10, "number of spokes n (phi = pi/n)", int, 3, 64),
    Param("kappa", 1.0 / 3.0, "hub inertia kappa = I_c/(m l^2) (002 eq 11; slip needs kappa > 0)", float, 0.0, 1.0),
    Param("slope", PAPER_SLOPE, "slope alpha, rad (paper: 13 deg)", float, 0.0, math.pi / 2, True, True),
    Param("mu", 0.3, "Coulomb friction coefficient, static = kinetic (paper's stick-slip case 0.3: Type B)", float,
          0.0, 1e3),
    Param("leg_length", 1.0, "spoke length l, m", float, 0.0, 100.0, low_open=True),
    Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, low_open=True),
)

#: Contact: the stiffest time constant MuJoCo allows (2 steps) and damping ratio 3 (why, and the measurements behind
#: every constant of this block: docs/scenarios/rimless-wheel-friction.md, "Presets, thresholds and starts").
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 0.0002, "solref_timeconst": 0.0004, "solref_dampratio": 3.0, "integrator": "implicitfast",
        "cone": "elliptic", "impratio": 10.0, "noslip_iterations": 0, "foot_radius": 0.0005},
    "accurate": {"timestep": 0.0002, "solref_timeconst": 0.0004, "solref_dampratio": 3.0, "integrator": "implicitfast",
        "cone": "elliptic", "impratio": 10.0, "noslip_iterations": 0, "foot_radius": 0.0005},
    "coarse": {"timestep": 4e-4, "solref_timeconst": 8e-4, "solref_dampratio": 3.0, "integrator": "implicitfast",
               "cone": "elliptic"},
}

#: Why each bound is what it is (the same at every preset).
REASONS: dict[str, str] = {
    "midstance_rate": "theta_dot at mid-stance (002 Sec. 3.3); measured 0.8-1.5e-3 (fast) and 0.2-1.3e-3 (accurate) "
                      "for A, B, C: the 0.5 mm foot's rolling alone gives +6e-4, the rest grows with the contact time "
                      "constant",
    "eigenvalue": "multiplier of a quadratic fit of the mid-stance map theta_dot_k -> theta_dot_k+1 (a conjugate "
                  "of the post-impact map, 002 eq 17 / Sec. 3.3; C: lambda_max, its other multiplier is 0); 0.02: "
                  "the Type C fit (mu = 0.24) moves by 7.4e-3 over the gate's environments, and the sticking "
                  "impact's beta^2 = 0.734 (Type A) is 0.028 from the Type B multiplier 0.762 at the defaults, "
                  "beyond 0.02 plus the measured error 4.7e-3",
    "dx_per_step": "change of the slip speed per step of a D gait (002 Sec. 3.3, Fig. 3.6), from mid-stance x_dot; "
                   "relative, 10 %: the slip speeds are small and their change per step a small difference of them",
    "slip_onset": "theta where the last slip phase of a B step starts (friction reaches the cone, 002 eq 22), "
                  "0.02 rad, 3 % of the stance's 2 phi (paper set)",
    "critical_friction": "max |f_t/f_n| along the settled A stances of the fitting starts (impulses binned by 2 mrad "
                         "of theta, the ends extrapolated to -+phi) against mu_c (002 eq 23); relative, 2 %",
    "sliding_contact_law": "largest relative residual, over the stance foot's sliding rows (MuJoCo's elliptic-cone "
                           "middle zone, outside impact windows), of MuJoCo's documented contact law for a sliding "
                           "step (analysis/soft_contact, eq 1: its reference acceleration, regulariser and cone) "
                           "evaluated on the rows' distance, velocities, accelerations and force; it holds to the "
                           "solver's tolerance (1e-10) and the rows' rounding, so 1e-6 leaves room for both and "
                           "is far below the 1e-2 to 1e-1 the law explains in the lift ratio",
    "v_thr": "foot speed above which it moves: 20-75x the median creep of a stuck foot, 2-7x its 99th percentile "
             "(MuJoCo's regularised friction; the creep is independent of impratio 1-1000, noslip 0-3 and the cone, "
             "and grows with the contact time constant)",
}

_FAST_BOUNDS = {"midstance_rate": 5e-3, "eigenvalue": 0.02, "dx_per_step": 0.1, "slip_onset": 0.02,
                "critical_friction": 0.02, "sliding_contact_law": 1e-6}
TOLERANCES: dict[str, Tolerances] = {
    "fast": Tolerances(bounds=_FAST_BOUNDS, reasons=REASONS),
    "accurate": Tolerances(bounds={**_FAST_BOUNDS, "midstance_rate": 2e-3}, reasons=REASONS),
    "coarse": Tolerances(bounds=_FAST_BOUNDS, reasons=REASONS),  # the region maps' preset keeps the fast tolerances
}


# --- inputs -------------------------------------------------------------------------------------------------------


def check_params(params: Values) -> None:
    """Refuse what the theory excludes (002 Sec. 3, eqs 18/21; Appendix A): the theory's own validation, kappa > 0
    (slip needs hub inertia: eq 42 gives f_n = 0 at kappa = 0; MuJoCo's pitch needs inertia too) and a mu with a
    stable gait (below the D branch the wheel rolls back)."""
    w = friction_wheel(params)
    try:
        theory.validate(w)
    except ValueError as err:
        raise ParameterError(str(err)) from None
    low = MIN_GYRATION**2
    if w.kappa < low:
        raise ParameterError(
            f"kappa must be in [{low:g}, 1] (got {w.kappa:g}): slipping needs hub inertia (002 eq 42: f_n = "
            f"kappa (...)/D vanishes at kappa = 0) and MuJoCo's pitch joint needs it (see rimless-wheel)")
    if not theory.attractors(w):
        raise ParameterError(theory.no_gait_reason(w))


# --- the checks ---------------------------------------------------------------------------------------------------

#: Every check :func:`evaluate` reports at some mu, in its order; :func:`checks_at`: those of the gait mu settles on.
CHECKS = ("gait_type", "midstance_rate", "eigenvalue", "impact_kind", "phase_sequence", "sliding_contact_law",
          "slip_onset", "dx_per_step", "critical_friction")


def checks_at(params: Values, settings: Values) -> tuple[str, ...]:
    """The checks :func:`evaluate` reports for the gait ``mu`` settles on (002 Sec. 3.3): every gait's type, mid-stance
    map, impact kind and phases; the sliding rows' contact law where the gait slips (types B, C, D); Type B's slip
    onset (002 eq 22), a D gait's slip growth per step (Fig. 3.6) and Type A's critical friction (002 eq 23)."""
    kind = reference_gait(friction_wheel(params)).kind
    own = {"sliding_contact_law": kind != "A", "slip_onset": kind == "B", "dx_per_step": kind.startswith("D"),
           "critical_friction": kind == "A"}
    return tuple(check for check in CHECKS if own.get(check, True))


def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
    """Simulate the reference gait's post-impact state, its perturbations and a slipping start in one batch;
    compare settled type, mid-stance rate, multiplier, slip onset, impact kind and (D) slip growth per step."""
    w = friction_wheel(params)
    gait = reference_gait(w)
    tol = at_preset(TOLERANCES, RIMLESS_WHEEL_FRICTION.name, preset)
    starts, fit_mask = fit_starts(gait, w)
    nsteps = D_SIM_STEPS if gait.kind.startswith("D") else SIM_STEPS
    run = run_batch(params, settings, preset, starts, nsteps)
    rows, steps, cls, report = run.rows, run.steps, run.cls, run.report
    refs = [reference.reference_run(w, tuple(z), nsteps) for z in starts]
    out: list[checks.Check] = []
    sim_types = [phases.outcome(steps, b) for b in range(len(starts))]
    agree = sum(r.outcome == t for r, t in zip(refs, sim_types, strict=True))
    main = int(np.nonzero(fit_mask)[0][len(FIT_OFFSETS) // 2])
    out.append(checks.categorical(
        "gait_type", refs[main].outcome, sim_types[main], len(starts) - agree, len(starts),
        "settled type (failure, else the type of the last step) of each start (the gait's post-impact state, "
        "theta_dot0 offsets, a slipping start) vs the reference's theory.settle from the same start (002 Sec. 3.3); "
        f"error = fraction that differ: simulated {sim_types}, reference {[r.outcome for r in refs]}"))
    extras: dict[str, Any] = {}
    summary: FitSummary | None = None
    plot: ReturnMapPlot | None = None
    reported: dict[str, Reported] = {}
    try:
        fit, x, x_next = phases.fit_midstance_map(steps, np.nonzero(fit_mask)[0], gait.kind, FIT_PAIRS, seed)
        mid_sim, lam_sim = float(fit.fixed_point[0]), float(np.real(fit.eigenvalues[0]))  # 1-D map: real
        summary = FitSummary.of(fit)
        grid = np.linspace(float(x.min()), float(x.max()), 40)
        plot = ReturnMapPlot(
            label="mid-stance theta_dot (nondimensional)", x=x, x_next=x_next, analytic_x=grid,
            analytic_y=gait.midstance_rate + abs(gait.eigenvalues[0]) * (grid - gait.midstance_rate),
            analytic_eigenvalues=[complex(e) for e in gait.eigenvalues])
    except ValueError as err:  # too few samples: every start failed or left the gait
        mid_sim = lam_sim = math.nan
        extras["fit_error"] = str(err)
    out.append(checks.relative("midstance_rate", gait.midstance_rate, mid_sim, tol["midstance_rate"], "",
                               f"fixed point of the mid-stance map vs the reference gait {gait.kind} "
                               f"({tol.reasons['midstance_rate']})"))
    lam_ref = complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])
    out.append(checks.absolute("eigenvalue", lam_ref.real if lam_ref.imag == 0 else lam_ref, lam_sim,
                               tol["eigenvalue"], "", tol.reasons["eigenvalue"]))
    settled = phases.settled_steps(steps, main, SETTLED_STEPS)
    impact_sim = ["slipping" if steps.impact_slipping[main, j] else "sticking" for j in settled]
    out.append(checks.categorical(
        "impact_kind", gait.impact, checks.most_common(impact_sim), sum(k != gait.impact for k in impact_sim),
        len(settled), f"kind of the settled steps' impacts ({impact_sim}) vs the gait's (002 eq 44): slipping when "
        "the new foot's speed after the impact window exceeds v_thr or the impulse ratio is on the cone; "
        f"v_thr = {cls.v_thr:g} ({tol.reasons['v_thr']}); error = fraction that differ"))
    measured = [phases.phase_sequence(steps.runs, main, int(j)) for j in settled]
    names = [" > ".join(ph[0]) for ph in measured]
    out.append(checks.categorical(
        "phase_sequence", " > ".join(gait.phases), checks.most_common(names),
        sum(ph[0] != gait.phases for ph in measured), len(settled),
        f"stick/slip phases of the settled steps ({names}) vs the gait's (002 eq 35): a row slips when its friction "
        "is on the cone (force ratio of the hub's recorded acceleration over 1 ms); error = fraction that differ"))
    if gait.kind != "A":  # the gait slips (002 Sec. 3.3): its sliding rows against MuJoCo's contact law
        sliding = sliding_contact(run.rec, run.model, params, settings, rows, cls)
        out.append(checks.absolute("sliding_contact_law", 0.0, sliding.residual, tol["sliding_contact_law"], "",
                                   f"{tol.reasons['sliding_contact_law']} ({sliding.rows} sliding rows)"))
        extras["sliding_contact"] = asdict(sliding)
        reported["sliding_lift_ratio"] = Reported(**sliding.reported())
    if gait.kind == "B":
        onset_sim = float(np.nanmedian(steps.onset[main, settled])) if settled.size else math.nan
        out.append(checks.absolute("slip_onset", gait.phase_angles[-1], onset_sim, tol["slip_onset"], "rad",
                                   tol.reasons["slip_onset"]))
    if gait.kind.startswith("D"):
        dx = np.diff(steps.mid_slip[main, settled]) if settled.size > 1 else np.zeros(0)
        dx = dx[np.isfinite(dx)]
        dx_sim = float(np.mean(dx)) if dx.size else math.nan
        out.append(checks.relative("dx_per_step", gait.dx_per_step, dx_sim, tol["dx_per_step"], "",
                                   tol.reasons["dx_per_step"]))
    if gait.kind == "A":
        pooled = phases.settled_rows(rows, steps, np.nonzero(fit_mask)[0], "A", SETTLED_STEPS)
        mu_c, mu_c_sim, extras["force_ratio_profile"] = reference.force_ratio_comparison(w, rows, pooled)
        out.append(checks.relative("critical_friction", mu_c, mu_c_sim, tol["critical_friction"], "",
                                   tol.reasons["critical_friction"]))
    extras["steps"] = phases.step_report(steps, main, refs[main].kinds, refs[main].mid_rate)
    extras["thresholds"] = {"v_thr": cls.v_thr, "saturation_eps": cls.eps, "impact_window_s": cls.impact_window,
                            "creep": phases.creep(rows, steps)}
    extras["starts"] = [{"theta_dot0": float(z[0]), "x_dot0": float(z[1]), "simulated": t,
                         "simulated_velocity_only": phases.outcome(steps, b, velocity_only=True),
                         "reference": r.outcome, "reference_steps": r.settle_steps}
                        for b, (z, t, r) in enumerate(zip(starts, sim_types, refs, strict=True))]
    return Evaluation(out, report, extras, analytic=AnalyticValues.from_values(reference.gait_values(w, gait)),
                      fit=summary, return_map=plot, reported=reported)


# --- validation batches, exact-model bench, video states, soak --------------------------------------------------------


def validation_batches(params: Values, settings: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The model and the (initial states, steps) of the batch :func:`evaluate` runs."""
    w = friction_wheel(params)
    gait = reference_gait(w)
    starts, _ = fit_starts(gait, w)
    model = build(params, settings)
    nstep = math.ceil(SIM_STEPS * period_seconds(params, np.array([w.mu])) / model.opt.timestep)
    return model, [(start_states(model, params, settings, starts), nstep)]


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact reference (theory.step, the generic Appendix-A integrator at tolerance ``rtol``) through the same
    mid-stance fit: wall time and the eigenvalue / mid-stance errors against the fast-method gait."""
    w = friction_wheel(params)
    gait = reference_gait(w)
    starts, mask = fit_starts(gait, w)
    return reference.generic_bench(w, gait, starts[mask], FIT_PAIRS + 1, rtol)


def video_states(params: Values, settings: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """States of a clip from the reference gait's post-impact state perturbed by +10 % in theta_dot."""
    gait = reference_gait(friction_wheel(params))
    th, xd = gait_start(gait)
    state0 = start_states(model, params, settings, np.array([[1.1 * th, xd]]))
    return plain_clip(model, state0, nstep)


def soak(params: Values, settings: Values, impacts: int) -> Soak:
    """``impacts`` steps on the reference gait in one trajectory: the mid-stance theta_dot of each step."""
    w = friction_wheel(params)
    gait = reference_gait(w)
    model = build(params, settings)
    seconds = impacts * period_seconds(params, np.array([w.mu])) + 0.5
    rec, report = simulate(model, np.array([w.mu]), start_states(model, params, settings,
                                                                 np.array([gait_start(gait)])), seconds,
                           settings)
    cls = classifier(w.mu, settings, "fast", 1)
    rows = row_signals(rec, model, params, settings, rate_unit(params), cls)
    phi = math.pi / w.spokes
    mid = level_crossings(rec.time, rows.theta, rows.rate[:, :, None], max_jump=phi)
    return Soak(mid.values[:, 0], gait.midstance_rate, "mid-stance theta_dot (nondimensional)", report)


STRESS_CASES = (
    StressCase("type A", {"mu": "2"}, "no slip (mu > mu_c = 0.914)"),
    StressCase("type B near the A/B edge", {"mu": "0.85"}, "a short slip phase before each impact"),
    StressCase("type C", {"mu": "0.24"}, "slipping impact, slip -> stick -> slip"),
    StressCase("type D+", {"mu": "0.2"}, "forward slip throughout, the slip speed grows each step"),
    StressCase("low friction D+", {"mu": "0.1"}, "near the D branch's lower end (0.080)"),
    StressCase("huge friction", {"mu": "1000"}, "friction far above mu_c"),
    StressCase("light hub", {"kappa": "0.05"}, "kappa = 0.05: the slip normal force ~ kappa (002 eq 42); Type C"),
    StressCase("light hub, no gait", {"kappa": "0.01"}, "kappa = 0.01, mu = 0.3: no stable gait of types A-D+",
               expect="refused"),
    StressCase("below the D branch", {"mu": "0.05"}, "no stable gait: the wheel rolls back", expect="refused"),
    StressCase("point-mass hub", {"kappa": "0"}, "slip needs kappa > 0 (002 eq 42)", expect="refused"),
    StressCase("slope above alpha_max", {"slope": "0.3"}, "f_n < 0 on the sticking gait (002 eq 21)",
               expect="refused"),
)


#: Where a preset must hold (mjpoincare tune): one point per stick-slip gait type the default validation judges,
#: from high to low friction: Type A (no slip), Type B (the defaults, mu = 0.3) and Type C (slipping impact).
_FRICTION_WHEEL = ("gait_type", "midstance_rate", "eigenvalue", "impact_kind", "phase_sequence", "slip_onset",
                   "sliding_contact_law", "stable")
#: The gate's runs of this scenario (:mod:`mjpoincare.gate.forms`), as measured by ``mjpoincare margins`` (MuJoCo 4.0.0,
#: numpy 2.4.6, scipy 1.17.1, this repository's CPU): each spread is the measured one rounded up to 2 digits. A
#: declared miss's range spans this measurement and the one an earlier margins run declared (machines and builds
#: differ by more than the perturbations move some fits).
GATE_CASES: tuple[GateCase, ...] = (
    GateCase.of("rimless-wheel-friction", "fast", _FRICTION_WHEEL),
    GateCase.of("rimless-wheel-friction", "fast", ("gait_type", "midstance_rate", "eigenvalue", "impact_kind",
                                                   "phase_sequence", "stable"), mu=2.0, watched=[
                    Watch(check="critical_friction", spread=7.1e-4, why="0.79 of its tolerance: the bisection of the "
                          "slip onset over the soft contact's stick-slip threshold")]),
    GateCase.of("rimless-wheel-friction", "fast", ("gait_type", "midstance_rate", "eigenvalue", "impact_kind",
                                                   "phase_sequence", "sliding_contact_law", "stable"), mu=0.24),
    GateCase.of("rimless-wheel-friction", "accurate", tuple(c for c in _FRICTION_WHEEL if c != "midstance_rate"),
                watched=[
        Watch(check="midstance_rate", spread=4.2e-9, why="0.70 of its tolerance: the searched accurate preset is the "
              "fast one's soft contact, whose first-order bias this is; every stiffer contact tried hops at the impact "
              "and misses a category check")]),
    GateCase.of("rimless-wheel-friction", "coarse", _FRICTION_WHEEL),
)


COVERAGE = (
    CoveragePoint("Type B", {}, "mu = 0.3 (the paper's stick-slip case): slip before each impact"),
    CoveragePoint("Type A", {"mu": "2"}, "mu = 2 > mu_c: no slip"),
    CoveragePoint("Type C", {"mu": "0.24"}, "mu = 0.24: slipping impact, slip -> stick -> slip"),
    CoveragePoint("Type D+", {"mu": "0.2"}, "mu = 0.2: slipping impact and a slip speed that grows every step; "
                  "MuJoCo's sliding foot lifts off and the wheel flies (docs/scenarios/rimless-wheel-friction.md, "
                  "Findings)",
                  miss_at=("fast", "accurate")),
)

RIMLESS_WHEEL_FRICTION = Scenario(
    name="rimless-wheel-friction",
    summary="rimless wheel with Coulomb friction: stick-slip gait types A-D, multipliers, slip onset, impacts",
    source="Gamus & Or 2015 Sec. 3 (eq 11-26, Figs 3.3-3.8) and Appendix A (eq 31-45, corrected)",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    bench_checks=("midstance_rate", "eigenvalue"),
    validation_batches=validation_batches,
    exact_model_bench=exact_model_bench,
    video_states=video_states,
    track_body="hub",
    frame_tilt="slope",
    camera_distance=5.5,  # the whole 12-spoke wheel and its contact in frame, seen from slightly above
    camera_elevation=-10.0,
    stress_cases=STRESS_CASES,
    soak=soak,
    region_map=REGION_MAP,
    param_sweeps={"mu": MU_SWEEP},
    seam_mechanisms=("rollout", "friction", "contact_fields"),
    checks=CHECKS,
    checks_at=checks_at,
    tolerances=TOLERANCES,
    gate_cases=GATE_CASES,
    paper_results=PAPER_RESULTS,
    rivals=RIVALS,
    coverage=COVERAGE,
    search_space=search_space("timestep", "solref_timeconst", "solref_dampratio", "integrator", "foot_radius",
                              "cone", "impratio", "noslip_iterations"),
    default=True, foot=WHEEL_FOOT,
)
