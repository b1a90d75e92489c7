"""Dedicated MuJoCo experiments for the results of 003 (Kisa 2020, Ch. 4) the scenario's validation does not run: the
stance leg's phase curve of the periodic gait of Fig. 18 and one step of the Poincare map (4.18) from MuJoCo's own
section states (:mod:`mjpoincare.scenarios.paper_results`)."""

from __future__ import annotations

import itertools
import math

import numpy as np

from mjpoincare.analysis.sections import level_crossings
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.analysis.theory.compass_biped.figures import stance_phase_curve
from mjpoincare.core.params import Values
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import JointIndex
from mjpoincare.scenarios.compass_biped.controller import GaitController
from mjpoincare.scenarios.compass_biped.runs import (
    CHUNK_SECONDS,
    biped,
    initial_section_states,
    post_impact_states,
    walk,
)
from mjpoincare.scenarios.paper_results import Reading, Runner
from mjpoincare.simulation.simulate import KeptRows, event_rollout

#: Heel strikes walked from the analytic fixed point for Fig. 18: each step crosses every stance angle once.
FIG18_STEPS = 6
#: Heel strikes per start of the one-step map's walk (its legs-parallel samples give 3 one-step pairs per start).
MAP_STEPS = 3
#: The walk of each preset, once per process: every point of the figure reads the same walk.
_WALKS: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}


def fig18_walk(runner: Runner, params: Values, settings: Values) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The scenario's model walked FIG18_STEPS heel strikes from the analytic fixed point, with the scenario's gait
    controller: time (T,), both legs' thesis-frame angles theta = hinge + gamma (2, T) and rates (2, T)."""
    bp = biped(params)
    model = runner.build(params, settings)
    radius = float(settings["foot_radius"])
    x_star = theory.fixed_point(bp)
    controller = GaitController(model, bp, 1, radius)
    recorder = KeptRows(controller)
    nstep = math.ceil((FIG18_STEPS + 0.5) * theory.step_period(bp, x_star) / model.opt.timestep)
    event_rollout(model, post_impact_states(model, bp, x_star[None, :], radius), nstep, recorder,
                  **rollout_options(settings), chunk_steps=max(10, round(CHUNK_SECONDS / model.opt.timestep)),
                  setup=controller.configure)
    rows = np.concatenate(recorder.rows)  # trajectory 0's kept rows: time, qpos, qvel
    time, qpos, qvel = rows[:, 0], rows[:, 1 : 1 + model.nq], rows[:, 1 + model.nq :]
    legs = [JointIndex.of(model, f"leg{i}") for i in (0, 1)]
    angles = np.stack([qpos[:, leg.qpos] for leg in legs]) + bp.slope
    rates = np.stack([qvel[:, leg.dof] for leg in legs])
    return time, angles, rates


def fig18_point(theta: float, runner: Runner) -> Reading:
    """003 Fig. 18 (top): the stance leg's rate dtheta_st where its angle crosses ``theta`` on the periodic gait, at
    the scenario's defaults (Fig. 18's parameters). MuJoCo's value: the mean over the walk's upward crossings of theta
    by either leg (a leg rises only while it is the stance leg: the swing leg falls from theta_sw+ back to
    theta_st+), its spread half their range; the theory's: :func:`stance_phase_curve` on the exact cycle. Absolute
    error against the scenario's fixed_point tolerance."""
    params, settings = runner.inputs({})
    if runner.preset not in _WALKS:
        _WALKS[runner.preset] = fig18_walk(runner, params, settings)
    time, angles, rates = _WALKS[runner.preset]
    found = level_crossings(np.broadcast_to(time, angles.shape), angles, rates[:, :, None], level=theta,
                            direction=+1)
    values = found.values[:, 0]
    value = float(np.mean(values))
    bp = biped(params)
    analytic = float(stance_phase_curve(bp, theory.fixed_point(bp), [theta])[0])
    return Reading(analytic=analytic, mujoco=value, error=abs(value - analytic),
                   tolerance=runner.tolerance("fixed_point"), spread=float(np.ptp(values)) / 2,
                   detail=f"{values.size} crossings over {FIG18_STEPS} steps")


def fig18_curve(thetas: np.ndarray, runner: Runner) -> np.ndarray:
    """The theory's stance-leg phase curve of 003 Fig. 18 (:func:`stance_phase_curve` on the exact cycle) at the
    scenario's defaults."""
    bp = biped(runner.inputs({}, checked=False)[0])
    return stance_phase_curve(bp, theory.fixed_point(bp), thetas)


def fig18_angles(count: int) -> tuple[float, ...]:
    """``count`` stance angles spanning the gait's swing, theta_st+ to theta_st-, 5 % in from each end (each crossed
    away from the soft impact's window)."""
    bp = theory.kisa()
    x_star = theory.fixed_point(bp)
    first, last = float(x_star[0]), float(theory.step(bp, x_star).x_minus[0])
    inset = 0.05 * (last - first)
    return tuple(float(v) for v in np.linspace(first + inset, last - inset, count))


def one_step_map(runner: Runner) -> Reading:
    """003 eqs (4.15)-(4.18) on the legs-parallel section (4.20): the scenario's walk of its perturbed starts (the
    validation's, :func:`initial_section_states`) for MAP_STEPS heel strikes; each consecutive pair of MuJoCo's
    section samples (y_k, y_k+1) against the exact map of y_k (swing 4.19, impact 4.17 with the relabelling 4.7,
    swing to the next crossing: :func:`theory.parallel_return_map`). MuJoCo's value: y_k+1 at the pair with the
    largest residual (max-abs over the pairs and the 3 coordinates), against the scenario's fixed_point tolerance."""
    params, settings = runner.inputs({})
    bp = biped(params)
    model = runner.build(params, settings)
    controller, _ = walk(model, bp, initial_section_states(bp, model.opt.timestep), MAP_STEPS, settings)
    pairs = [(a, b) for seq in controller.samples for a, b in itertools.pairwise(seq)]
    predicted = [theory.parallel_return_map(bp, a) for a, _ in pairs]
    residual = [float(np.max(np.abs(np.asarray(b) - p))) for (_, b), p in zip(pairs, predicted, strict=True)]
    worst = int(np.argmax(residual))
    return Reading(analytic=predicted[worst].tolist(), mujoco=np.asarray(pairs[worst][1]).tolist(),
                   error=residual[worst], tolerance=runner.tolerance("fixed_point"), kind="max-abs",
                   detail=f"{len(pairs)} one-step pairs from {len(controller.samples)} starts; median residual "
                   f"{float(np.median(residual)):.2g}")
