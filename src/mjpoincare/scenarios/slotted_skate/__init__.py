"""Scenario ``slotted-skate``: the discrete Chaplygin sleigh, pegs switched by a controller.

Analytic reference: Coleman & Holmes (1999), return map in (D, E, theta, H) (B.3, B.4), impact law
(3.6)-(3.7), stability eigenvalue sigma_4 (3.10); see :mod:`mjpoincare.analysis.theory.slotted_skate`.

The peg is a MuJoCo joint equality in the "peg chart" (models/slotted_skate.xml): the controller
(:class:`~mjpoincare.scenarios.slotted_skate.pegs.PegController`) stops each trajectory exactly at the
slot end (a fractional step from the last state inside the slot), reads E and H about the old peg there,
and re-parametrises the state for the new peg at the other slot end; the next constraint solve is the
plastic impact. Stepping
between events is native (:func:`mjpoincare.simulation.simulate.event_rollout`); contact is disabled, gravity
is off, and the skate is the only body.

Samples are taken at the end of each stance: E and H about the peg are stance invariants (3.3)-(3.4),
so E_k, H_k read there are the post-impact values of impact k-1 whatever the constraint softness.
"""

from __future__ import annotations

import itertools
import math

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.returnmap import fit_return_map
from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.core.params import Param, ParameterError
from mjpoincare.core.seam import RolloutReport
from mjpoincare.core.settings import rollout_options, search_space
from mjpoincare.scenarios.base import (
    AnalyticValues,
    CoveragePoint,
    Evaluation,
    FitSummary,
    Scenario,
    StressCase,
    Values,
    at_preset,
)
from mjpoincare.scenarios.gate_cases import GateCase
from mjpoincare.scenarios.slotted_skate.design import (
    FINAL_SPEED_RESOLUTION,
    IMPACTS,
    final_impacts,
    has_final_state,
    initial_conditions,
    run_duration,
    skate,
)
from mjpoincare.scenarios.slotted_skate.paper_results import PAPER_RESULTS
from mjpoincare.scenarios.slotted_skate.pegs import PegController, build
from mjpoincare.scenarios.slotted_skate.regions import REGION_MAP
from mjpoincare.scenarios.slotted_skate.rivals import RIVALS
from mjpoincare.scenarios.slotted_skate.tolerances import TOLERANCES
from mjpoincare.simulation.simulate import event_clip, event_rollout, initial_states

PARAMS: tuple[Param, ...] = (
    Param("l0", 1.0, "signed distance from the slot's front end forward to the mass centre, m", float, -1e3, 1e3),
    Param("delta", 1.0 / 3.0, "slot length, m", float, 0.0, 1e3, low_open=True),
    Param("rho", 1.0, "radius of gyration about the mass centre, m", float, 0.0, 1e3, low_open=True),
    Param("mass", 1.0, "mass, kg", float, 0.0, 1e6, low_open=True),
    Param("V0", 1.0, "initial slot speed, m/s (sign = direction; not 0)", float, -1e3, 1e3),
    Param("Omega0", 0.1, "initial angular velocity, rad/s", float, -1e3, 1e3),
    Param("heading0", 0.0, "initial heading, rad", float, -1e3, 1e3),
)

#: Dead-beat peg constraint (derivation page docs/theory/slotted-skate.md, Sec. 4.3): time constant = 2 steps,
#: dmin = dmax = 0.9999.
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 0.000494893858142, "solref_timeconst": 0.00390610197978, "integrator": "rk4",
        "solimp_dmin": 0.9999, "solimp_dmax": 0.9999, "solimp_width": 0.001, "iterations": 200,
        "tolerance": 4.67917456765e-11, "solref_dampratio": 0.568133114898},
    "accurate": {"timestep": 0.0002, "solref_timeconst": 0.0004, "integrator": "rk4", "solimp_dmin": 0.9999,
        "solimp_dmax": 0.9999, "solimp_width": 0.001, "iterations": 200, "tolerance": 1e-14, "solref_dampratio": 1.0},
}
#: H_k+1/H_k is judged only while |H_k| >= RATIO_FLOOR x the run's largest |H| (why: docs/scenarios/slotted-skate.md)
RATIO_FLOOR = 1e-4
def check_params(params: Values) -> None:
    """Refuse a skate at rest or sliding nowhere: the peg protocol needs slot motion (V0 != 0)."""
    if float(params["V0"]) == 0.0:
        raise ParameterError("V0 must be non-zero (an initial state with no slot motion never reaches a slot end)")
    theory.validate(skate(params))


def start_states(model: mujoco.MjModel, params: Values, V0: np.ndarray, Omega0: np.ndarray) -> np.ndarray:
    """Initial states: the peg at the slot end where it enters (front for V0 > 0), no lateral motion."""
    l0, delta = float(params["l0"]), float(params["delta"])
    s0 = np.where(V0 > 0, l0, l0 + delta)
    qpos = np.stack([np.full_like(V0, float(params["heading0"])), s0, np.zeros_like(V0)], axis=1)
    qvel = np.stack([Omega0, V0, np.zeros_like(V0)], axis=1)
    return initial_states(model, qpos, qvel)


def _nondim(params: Values) -> tuple[float, float, float]:
    """Scales (energy, momentum, time) of the paper's units: m v0^2, m rho v0, rho / v0 (v0 = |V0|)."""
    m, rho, v0 = float(params["mass"]), float(params["rho"]), abs(float(params["V0"]))
    return m * v0 * v0, m * rho * v0, rho / v0


def _simulate(params: Values, settings: Values) -> tuple[PegController, object]:
    model = build(params, settings)
    V, Om = initial_conditions(params)
    controller = PegController(model, params, np.where(V > 0, float(params["l0"]),
                                                       float(params["l0"]) + float(params["delta"])))
    nstep = math.ceil(run_duration(params, V, Om) / model.opt.timestep)
    report = event_rollout(model, start_states(model, params, V, Om), nstep, controller, **rollout_options(settings),
                           chunk_steps=max(10, min(2000, nstep // 20)))
    return controller, report


def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
    """Peg-switched MuJoCo runs against the exact return map, impact by impact, and sigma_4 for both directions."""
    controller, report = _simulate(params, settings)
    sk = skate(params)
    tol = at_preset(TOLERANCES, SLOTTED_SKATE.name, preset)
    why = tol.why
    e_unit, h_unit, t_unit = _nondim(params)
    lo, _rho = float(params["l0"]), float(params["rho"])
    worst = {"energy": 0.0, "heading": 0.0, "duration": 0.0}
    reversal_mismatch, reversals, ratios = 0, 0, {True: [], False: []}
    pairs: dict[bool, list[tuple[float, float]]] = {True: [], False: []}
    for samples in controller.samples:
        h_floor = RATIO_FLOOR * max((abs(x[3]) for x in samples), default=0.0)
        for (d0, e0, th0, h0, t0), (d1, e1, th1, h1, t1) in itertools.pairwise(samples):
            D0 = 0.0 if d0 == lo else sk.Delta
            step = theory.return_map(sk, D0, e0 / e_unit, th0, h0 / h_unit)
            observed_reversal = d1 != d0  # a reversal returns the peg to its entry end; the next goes in opposite
            reversal_mismatch += int(observed_reversal != step.reversed)
            reversals += int(observed_reversal)
            worst["energy"] = max(worst["energy"], abs(e1 / e_unit - step.E_plus))
            worst["heading"] = max(worst["heading"], abs(th1 - step.theta_plus))
            worst["duration"] = max(worst["duration"], abs((t1 - t0) / t_unit - step.duration))
            if not step.reversed and abs(h0) > max(h_floor, 1e-12 * h_unit):
                forward = D0 == 0.0
                ratios[forward].append(h1 / h0)
                pairs[forward].append((h0 / h_unit, h1 / h_unit))
    out: list[checks.Check] = []
    extras: dict[str, object] = {}
    forward_fit: FitSummary | None = None
    for forward, label in ((True, "forward"), (False, "backward")):
        ref = theory.sigma4(sk, forward)
        sim = float(np.median(ratios[forward])) if ratios[forward] else math.nan
        err = float(np.max(np.abs(np.array(ratios[forward]) - ref))) if ratios[forward] else math.nan
        out.append(checks.Check(name=f"sigma4_{label}", analytic=ref, simulated=sim, error=err, tolerance=tol["sigma4"],
                                kind="max-abs", unit="",
                                why=f"H_k+1/H_k over every non-reversing {label} impact (3.10); " + why))
        if len(pairs[forward]) >= 3:
            h = np.array(pairs[forward])
            fit = fit_return_map(h[:, :1], h[:, 1:], degree=1, seed=seed)
            lam = complex(fit.eigenvalues[0]).real
            out.append(checks.absolute(f"sigma4_fit_{label}", ref, lam, tol["sigma4"], "",
                                       "slope of the affine return map H_k -> H_k+1 fitted by least squares"))
            extras[f"fit_{label}"] = fit.to_dict()
            if forward:
                forward_fit = FitSummary.of(fit)
            stable_sim, stable_ref = abs(lam) < 1, abs(ref) < 1
            out.append(checks.Check(name=f"stability_{label}", analytic="stable" if stable_ref else "unstable",
                                    simulated="stable" if stable_sim else "unstable",
                                    error=float(stable_sim != stable_ref), tolerance=0.0, kind="mismatch", unit="",
                                    why="straight motion stable iff |sigma4| < 1 (3.11-3.12)"))
    out.append(checks.Check(name="energy_loss", analytic=0.0, simulated=worst["energy"], error=worst["energy"],
                            tolerance=tol["energy_loss"], kind="max-abs", unit="m v0^2",
                            why="E_k+1 against the map's E+ = E + C1 H^2 (3.7, B.3/B.4), every impact: H "
                            "alone is blind to the impact law"))
    out.append(checks.Check(name="heading", analytic=0.0, simulated=worst["heading"], error=worst["heading"],
                            tolerance=tol["heading"], kind="max-abs", unit="rad",
                            why="heading at each slot end against the map's theta+ (B.1 quadrature)"))
    out.append(checks.Check(name="reversals", analytic=0.0, simulated=float(reversal_mismatch),
                            error=float(reversal_mismatch), tolerance=0.0, kind="count", unit="",
                            why=f"stances whose reversal (B.5) differs from the map ({reversals} reversals seen)"))
    predicted_n, observed_n = _collisions_before_reversal(sk, controller.samples, e_unit, h_unit, lo)
    if predicted_n:
        wrong = sum(int(a != b) for a, b in zip(predicted_n, observed_n, strict=True))
        out.append(checks.Check(name="collisions_before_reversal", analytic=predicted_n, simulated=observed_n,
                                error=float(wrong), tolerance=0.0, kind="count", unit="",
                                why="impacts before the first reversing stance (B.6-B.7), per start whose reversal "
                                "falls inside the simulated stances"))
    final_checks, final_report = _final_state_checks(params, settings, sk, tol["final_speed"])
    out.extend(final_checks)
    if forward_fit is not None:  # the result's fit and analytic eigenvalues (the sweep's columns): the forward map
        lam = float(np.real(forward_fit.eigenvalues[0]))
        if lam > 0 and theory.sigma4(sk, True) > 0:  # (V*/Delta) ln sigma4, V* = 1, vs the sleigh (2.1, 4.1)
            extras["smooth_limit"] = {"discrete_rate_simulated": math.log(lam) / sk.Delta,
                                      "discrete_rate_exact": theory.smooth_limit_rate(sk),
                                      "sleigh_rate": theory.sleigh_rate(sk.L0)}
    extras["max_stance_time_error"] = worst["duration"]
    extras["reversals_seen"] = reversals
    extras["impacts"] = sum(len(x) for x in controller.samples)
    analytic = AnalyticValues(eigenvalues=[theory.sigma4(sk, True)], values={"stability": theory.stability(sk)})
    return Evaluation(out, report if final_report is None else report.merge(final_report), extras, analytic=analytic,
                      fit=forward_fit)


def _collisions_before_reversal(sk: theory.SlottedSkate, runs: list[list[tuple[float, ...]]], e_unit: float,
                                h_unit: float, lo: float) -> tuple[list[int], list[int]]:
    """Per run: (B.6) predicted number of non-reversing impacts before the first reversal, and the number seen.

    Only where (B.6) applies (L0 > 0 or L0 < -Delta), a reversal is predicted, and it falls inside the run."""
    if -sk.Delta <= sk.L0 <= 0.0:
        return [], []
    predicted, observed = [], []
    for samples in runs:
        if len(samples) < 2 or abs(samples[0][3]) < 1e-12 * h_unit:
            continue
        d0, e0, _, h0, _ = samples[0]
        n = theory.collisions_before_reversal(sk, 0.0 if d0 == lo else sk.Delta, e0 / e_unit, h0 / h_unit)
        if not _reversal_inside(n, len(samples)):
            continue
        flips = [k for k, (a, b) in enumerate(itertools.pairwise(samples)) if b[0] != a[0]]
        predicted.append(n)
        observed.append(flips[0] if flips else len(samples))
    return predicted, observed


def _reversal_inside(n: int, samples: int) -> bool:
    """Whether a start is judged by collisions_before_reversal: (B.6) predicts a reversal after ``n`` non-reversing
    impacts (n >= 0) and its stance is among the ``samples`` simulated ones."""
    return n >= 0 and n + 1 < samples


def _reversal_predicted(params: Values, sk: theory.SlottedSkate) -> bool:
    """Whether collisions_before_reversal exists at ``params``: (B.6) applies (L0 > 0 or L0 < -Delta) and some start
    of the batch reverses inside the stances the run simulates, by the map from the start (B.6-B.7 for the reversal,
    the map's stance durations against the run's duration for the stances)."""
    if -sk.Delta <= sk.L0 <= 0.0:
        return False
    V, Om = initial_conditions(params)
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    horizon = run_duration(params, V, Om) * v0 / rho
    for v, om in zip(V, Om, strict=True):
        q = theory.initial_state(sk, v / v0, om * rho / v0, 0.0)
        if abs(q.H_plus) < 1e-12:
            continue
        n = theory.collisions_before_reversal(sk, q.D_plus, q.E_plus, q.H_plus)
        stances, elapsed = 0, 0.0
        while n >= 0 and stances < n + 2:  # the stances that end inside the run, up to the reversal's
            q = theory.return_map(sk, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
            elapsed += q.duration
            if elapsed > horizon:
                break
            stances += 1
        if _reversal_inside(n, stances):
            return True
    return False


def _final_run(params: Values, model: mujoco.MjModel, decay: tuple[theory.MapStep, int, float, int, float]
               ) -> tuple[np.ndarray, int]:
    """The user's start (1, nstate) and the steps that carry it past the map's final impact (:func:`final_impacts`)
    by 10 % plus two stances."""
    q, _, duration, _, _ = decay
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    start = start_states(model, params, np.array([float(params["V0"])]), np.array([float(params["Omega0"])]))
    return start, math.ceil((1.1 * duration + 2.0 * q.duration) * rho / v0 / model.opt.timestep)


def _final_state_checks(params: Values, settings: Values, sk: theory.SlottedSkate, tolerance: float
                        ) -> tuple[list[checks.Check], RolloutReport | None]:
    """The user's start run until its rotation has died out: final slot speed (B.10/B.12) and reversal count, and
    the run's report (None when the map's rotation does not decay: no final state to check)."""
    decay = final_impacts(params, sk)
    if decay is None:
        return [], None
    _, n, _, reversals, v_final = decay
    v0 = abs(float(params["V0"]))
    model = build(params, settings)
    start, nstep = _final_run(params, model, decay)
    entry = float(params["l0"]) if float(params["V0"]) > 0 else float(params["l0"]) + float(params["delta"])
    controller = PegController(model, params, np.array([entry]))
    report = event_rollout(model, start, nstep, controller, **rollout_options(settings),
                           chunk_steps=max(10, min(2000, nstep // 50)))
    samples = controller.samples[0]
    e_unit = float(params["mass"]) * v0 * v0
    if len(samples) < n + 1:
        return [checks.relative("final_speed", v_final, math.nan, tolerance, "v0", "the run ended early")], report
    d_last, e_last = samples[n][0], samples[n][1] / e_unit
    v_last = math.copysign(math.sqrt(2.0 * e_last), 1.0 if d_last == float(params["l0"]) else -1.0)
    seen = sum(int(b[0] != a[0]) for a, b in itertools.pairwise(samples[: n + 1]))
    return [
        checks.absolute("final_speed", v_final, v_last, tolerance, "v0",
                        f"slot speed at impact {n}, where the map's own is within {FINAL_SPEED_RESOLUTION:g} v0 of "
                        "its limit, against (B.10)/(B.12) by the map iterated to the end"),
        checks.Check(name="final_reversals", analytic=reversals, simulated=seen, error=float(abs(seen - reversals)),
                     tolerance=0.0, kind="count", unit="",
                     why=f"reversals over those {n} impacts: the map's count against the simulation's"),
    ], report


def validation_batches(params: Values, settings: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """Model and initial states of the batches: the map's starts and, where the map's rotation decays, the user's start
    run to its final state (each its whole duration without pegs switched)."""
    model = build(params, settings)
    V, Om = initial_conditions(params)
    batches = [(start_states(model, params, V, Om), math.ceil(run_duration(params, V, Om) / model.opt.timestep))]
    decay = final_impacts(params, skate(params))
    if decay is not None:
        batches.append(_final_run(params, model, decay))
    return model, batches


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact stance integration (solve_ivp at ``rtol``) over the same batch: time and sigma_4 error."""
    import time

    sk = skate(params)
    V, Om = initial_conditions(params)
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    start = time.perf_counter()
    worst = 0.0
    for v, om in zip(V, Om, strict=True):
        steps = theory.simulate_exact(sk, v / v0, om * rho / v0, 0.0, IMPACTS, rtol=rtol)
        for a, b in itertools.pairwise(steps):
            if not b.reversed and abs(a.H_plus) > 1e-12:
                worst = max(worst, abs(b.H_plus / a.H_plus - theory.sigma4(sk, a.D_plus == 0.0)))
    return {"rtol": rtol, "wall_s": time.perf_counter() - start, "sigma4_forward_error": worst}


def video_states(params: Values, settings: Values, model: mujoco.MjModel, nstep: int
         ) -> tuple[np.ndarray, np.ndarray]:
    """States of a clip of the first trajectory (peg-chart coordinates) and the peg's position for each row,
    to be put in ``mocap_pos`` so that the rendered skate moves across the plane."""
    V, Om = initial_conditions(params)
    first_peg = float(params["l0"]) if V[0] > 0 else float(params["l0"]) + float(params["delta"])
    controller = PegController(model, params, np.array([first_peg]))
    kept = event_clip(model, start_states(model, params, V[:1], Om[:1]), nstep, controller, 200,
                      tag=lambda: np.array([*controller.peg[0], 0.0]))
    return kept.states(nstep), kept.tagged(nstep)[:, None, :]


STRESS_CASES = (
    StressCase("slow spin (P5)", {"Omega0": "0.001"}, "Fig 9: a thousand times smaller rotation"),
    StressCase("fast spin", {"Omega0": "3"}, "rotation dominates the slot speed"),
    StressCase("fast slide", {"V0": "20"}, "20x the slot speed: few steps per stance"),
    StressCase("short slot", {"delta": "0.02"}, "100 impacts per unit length: near the smooth sleigh"),
    StressCase("long slot", {"delta": "3"}, "long stances, large heading change per stance"),
    StressCase("slot behind the mass centre", {"l0": "-2"}, "L0 < -Delta: the other stability region"),
    StressCase("heavy skate", {"mass": "1000", "rho": "10"}, "scale: 1000 kg, rho = 10 m"),
    StressCase("no slot motion", {"V0": "0"}, "never reaches a slot end", expect="refused"),
    StressCase("zero-length slot", {"delta": "0"}, "delta must be > 0", expect="refused"),
)


#: Every check :func:`evaluate` reports for some parameters, in its order; :func:`checks_at`: those at given ones.
CHECKS = ("sigma4_forward", "sigma4_fit_forward", "stability_forward", "sigma4_backward", "sigma4_fit_backward",
          "stability_backward", "energy_loss", "heading", "reversals", "collisions_before_reversal", "final_speed",
          "final_reversals")


def checks_at(params: Values, settings: Values) -> tuple[str, ...]:
    """The checks :func:`evaluate` reports at ``params``: sigma4 (3.10), its fit and the stability verdict (3.11-3.12)
    each way, whatever the samples (a run with fewer than 3 non-reversing pairs a way fails that way's fit as
    missing), the map's impact checks (B.1-B.5); the collisions before the first reversal where (B.6) predicts one
    inside the run, and the final state where the map's rotation decays (B.10/B.12)."""
    sk = skate(params)
    own = {"collisions_before_reversal": _reversal_predicted(params, sk),
           "final_speed": has_final_state(params, sk)}
    own["final_reversals"] = own["final_speed"]
    return tuple(check for check in CHECKS if own.get(check, True))


#: Where a preset must hold (mjpoincare tune): the defaults, the other stability region (slot behind the mass centre),
#: the regression gate's two other points (a long slot behind the mass centre; the mirrored defaults) and a fast slide
#: (20x the slot speed: few steps per stance, the hardest impacts on the pegs).
_SKATE = (*CHECKS, "stable")
#: The gate's runs of this scenario (:mod:`mjpoincare.gate.forms`), as measured by ``mjpoincare margins`` (MuJoCo 4.0.0,
#: numpy 2.4.6, scipy 1.17.1, this repository's CPU): each spread is the measured one rounded up to 2 digits. A
#: declared miss's range spans this measurement and the one an earlier margins run declared (machines and builds
#: differ by more than the perturbations move some fits).
GATE_CASES: tuple[GateCase, ...] = (
    GateCase.of("slotted-skate", "fast", _SKATE),
    GateCase.of("slotted-skate", "fast", _SKATE, l0=-1.4142135623730951, delta=0.7071067811865476),
    GateCase.of("slotted-skate", "accurate", _SKATE),
    GateCase.of("slotted-skate", "accurate", _SKATE, l0=-1.0, delta=1 / 3),
)


COVERAGE = (
    CoveragePoint("defaults", {}, "l0 = 1, delta = 1/3, V0 = 1"),
    CoveragePoint("slot behind", {"l0": "-2"}, "L0 < -Delta: the other stability region"),
    CoveragePoint("long slot behind", {"l0": "-1.4142135623730951", "delta": "0.7071067811865476"},
                  "l0 = -sqrt 2, delta = 1/sqrt 2: the gate's point with the slowest backward decay"),
    CoveragePoint("mirrored", {"l0": "-1", "delta": "0.3333333333333333"}, "l0 = -1: the defaults' mirror"),
    CoveragePoint("fast slide", {"V0": "20"}, "20x the slot speed: few steps per stance"),
)

SLOTTED_SKATE = Scenario(
    name="slotted-skate",
    summary="discrete Chaplygin sleigh: pegs as switched equality constraints; sigma4, energy loss, reversals",
    source="Coleman & Holmes 1999 (eq 3.1-3.12, B.1-B.5)",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    bench_checks=("sigma4_forward", "energy_loss", "heading"),
    validation_batches=validation_batches,
    exact_model_bench=exact_model_bench,
    video_states=video_states,
    track_body="skate",
    frame_tilt=None,
    camera_distance=4.0,
    camera_elevation=-89.0,
    stress_cases=STRESS_CASES,
    region_map=REGION_MAP,
    seam_mechanisms=("rollout", "fractional_step"),
    checks=CHECKS,
    checks_at=checks_at,
    rivals=RIVALS,
    tolerances=TOLERANCES,
    gate_cases=GATE_CASES,
    coverage=COVERAGE,
    paper_results=PAPER_RESULTS,
    search_space=search_space("timestep", "solref_timeconst", "solref_dampratio", "integrator", "iterations",
                              "tolerance"),
    default=True,
)
