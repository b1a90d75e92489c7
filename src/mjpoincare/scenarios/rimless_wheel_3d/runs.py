"""The experiment design and the MuJoCo runs of ``rimless-wheel-3d`` (Coleman, Chatterjee & Ruina 1997): the fitting
and planar-cycle batches, the mid-stance states they start from, and the mid-stance samples read from the rollouts of
either impact mode. Used by :mod:`mjpoincare.scenarios.rimless_wheel_3d`; why each number is what it is:
docs/scenarios/rimless-wheel-3d.md."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import mujoco
import numpy as np

from mjpoincare.analysis.rigid_body_kinematics import matrix_to_quat
from mjpoincare.analysis.sections import Crossings, level_crossings, wrap_phase
from mjpoincare.analysis.start_designs import random_directions
from mjpoincare.analysis.theory import rimless_wheel_3d as theory
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid
from mjpoincare.analysis.theory.rimless_wheel_3d.section import fit_map, section_state
from mjpoincare.core.seam import Chunk, RolloutReport
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import JointIndex, Values
from mjpoincare.scenarios.rimless_wheel_3d.ideal import IdealImpactController
from mjpoincare.simulation.simulate import event_rollout, initial_states, rollout_batch

FIT_STARTS = 24  # random directions around the planar cycle (plus the cycle itself)
FIT_IMPACTS = 12  # mid-stance samples per fitting trajectory
#: Size of the 5-D offsets of the fitting starts (rad and sqrt(g/l) units), per impact mode; see :func:`fit_starts`.
PERTURBATION: dict[str, float] = {"ideal": 5e-4, "contact": 3e-3}
PLANAR_IMPACTS = 40  # planar-cycle runs: mu^2 = 0.90 per impact leaves 1.5 % of a start offset after 40 impacts
PLANAR_HEADINGS = (0.0, 0.5)  # extra headings of the planar-cycle check (besides ``heading``)
PLANAR_TAIL = 10  # the last samples of a planar run are compared with the cycle at their own heading
CHUNK_SECONDS = 0.5  # native steps between looks (contact mode)
EVENT_CHUNK_FRACTION = 0.25  # ideal mode: chunk = this fraction of a step period (steps after an event are wasted)


def wheel(params: Values, heading: float | None = None) -> theory.RimlessWheel3D:
    """The nondimensional analytic wheel (001 Sec. 2) for the parameters (at ``heading`` if given)."""
    return theory.RimlessWheel3D(spokes=int(params["spokes"]), slope=float(params["slope"]), J=float(params["J"]),
                                 heading=float(params["heading"]) if heading is None else heading)


def rate_unit(params: Values) -> float:
    """sqrt(g/l): the paper's rates (m = l = g = 1) times this are rad/s."""
    return math.sqrt(float(params["gravity"]) / float(params["leg_length"]))


def is_ideal(params: Values) -> bool:
    """``impact=ideal``: the stance foot a ball joint, the impacts exact
    (:mod:`~mjpoincare.scenarios.rimless_wheel_3d.ideal`)."""
    return str(params["impact"]) == "ideal"


def nondim(x: np.ndarray, unit: float) -> np.ndarray:
    """Section states with rates in rad/s -> the paper's units (rates / sqrt(g/l))."""
    out = np.array(x, dtype=float)
    out[..., 2:] /= unit
    return out


def section_start_states(model: mujoco.MjModel, params: Values, settings: Values, x: np.ndarray) -> np.ndarray:
    """MuJoCo states at mid-stance (theta = 0 on spoke 0) for nondimensional section states x (B, 5).

    Contact mode: the stance foot sphere touches the plane at the origin and the body moves as a rotation about
    that contact point (no slip). Ideal mode: the ball joint's quaternion and body angular velocity.
    """
    l, unit = float(params["leg_length"]), rate_unit(params)
    radius = float(settings["foot_radius"])
    x = np.atleast_2d(x)
    qpos, qvel = [], []
    for psi, phi, *rates in x:
        R = hybrid.pose(psi, phi, 0.0)
        omega = hybrid.angular_velocity(psi, phi, rates) * unit
        quat = matrix_to_quat(R)
        if is_ideal(params):
            qpos.append(quat)
            qvel.append(R.T @ omega)
        else:
            hub = np.array([0.0, 0.0, radius]) + (l - radius) * R[:, 2]
            qpos.append(np.concatenate([hub, quat]))
            qvel.append(np.concatenate([np.cross(omega, hub), R.T @ omega]))
    return initial_states(model, np.array(qpos), np.array(qvel))


# --- simulation: contact mode -----------------------------------------------------------------------------------


class ContactRecorder:
    """Consumes rollout chunks: mid-stance samples and the largest clearance of the lowest foot (hops)."""

    def __init__(self, model: mujoco.MjModel, params: Values, settings: Values, batch: int) -> None:
        free = JointIndex.of(model, "free")  # hub position (3), orientation quaternion (4); velocity (3), omega (3)
        self.hub_z, self.quat = free.qpos + 2, slice(free.qpos + 3, free.qpos + 7)
        self.omega = slice(free.dof + 3, free.dof + 6)
        self.beta = math.pi / int(params["spokes"])
        self.length, self.radius = float(params["leg_length"]), float(settings["foot_radius"])
        self.mid = Crossings.empty(5)
        self.max_clearance = np.zeros(batch)

    def __call__(self, chunk: Chunk) -> None:
        theta, values = section_state(chunk.qpos[..., self.quat], chunk.qvel[..., self.omega])
        phase = wrap_phase(theta, self.beta)
        self.mid = self.mid.concat(level_crossings(chunk.time, phase, values, max_jump=self.beta))
        lowest = chunk.qpos[..., self.hub_z] - (self.length - self.radius) * np.cos(values[..., 1]) * np.cos(phase)
        self.max_clearance = np.fmax(self.max_clearance, np.nanmax(lowest - self.radius, axis=1))


# --- runs -------------------------------------------------------------------------------------------------------


@dataclass
class Run:
    """Mid-stance samples of one batch (per trajectory, rates in rad/s), the rollout report and diagnostics."""

    sequences: list[np.ndarray]
    report: RolloutReport
    max_clearance: float = math.nan
    guard_error: float = math.nan


def step_seconds(params: Values) -> float:
    """Step period of the planar cycle, s (001 eq 15 quadrature)."""
    return theory.step_period(wheel(params)) / rate_unit(params)


def steps_for(params: Values, dt: float, impacts: int) -> int:
    """Native steps that cover ``impacts`` + 1.2 step periods."""
    return math.ceil((impacts + 1.2) * step_seconds(params) / dt)


def event_chunk(params: Values, dt: float) -> int:
    """Steps per chunk of the ideal mode's event rollout."""
    return max(10, round(EVENT_CHUNK_FRACTION * step_seconds(params) / dt))


def batches(params: Values, w: theory.RimlessWheel3D) -> tuple[tuple[np.ndarray, int], tuple[np.ndarray, int]]:
    """(nondimensional starts, impacts) of the fit batch and of the planar batch (one cycle per planar heading)."""
    planar = np.array([hybrid.midstance_fixed_point(wheel_at(w, h)) for h in planar_headings(params)])
    return (fit_starts(w, PERTURBATION[str(params["impact"])]), FIT_IMPACTS), (planar, PLANAR_IMPACTS)


def simulate_starts(params: Values, settings: Values, model: mujoco.MjModel, x0: np.ndarray, impacts: int) -> Run:
    """Simulate the starts x0 (nondimensional mid-stance states) for ``impacts`` + 1 step periods."""
    state0 = section_start_states(model, params, settings, x0)
    dt = model.opt.timestep
    nstep = steps_for(params, dt, impacts)
    options = rollout_options(settings)
    if is_ideal(params):
        controller = IdealImpactController(wheel(params), float(params["leg_length"]), len(x0))
        report = event_rollout(model, state0, nstep, controller, **options,
                               chunk_steps=event_chunk(params, dt))
        return Run(first_samples(controller.mid, len(x0), impacts, params), report, guard_error=controller.guard_error)
    recorder = ContactRecorder(model, params, settings, len(x0))
    report = rollout_batch(model, state0, nstep, recorder, **options,
                           chunk_steps=max(1, round(CHUNK_SECONDS / dt)))
    return Run(first_samples(recorder.mid, len(x0), impacts, params), report,
                max_clearance=float(np.nanmax(recorder.max_clearance)))


def first_samples(mid: Crossings, batch: int, impacts: int, params: Values) -> list[np.ndarray]:
    """Per trajectory, the first ``impacts`` mid-stance samples after the start (which is itself on the section:
    a crossing in its first half step period is the start, not a sample), as the exact reference takes them."""
    late = mid.time > 0.5 * step_seconds(params)
    kept = Crossings(mid.trajectory[late], mid.time[late], mid.values[late])
    return [seq[:impacts] for seq in kept.sequences(batch)]


def fit_starts(w: theory.RimlessWheel3D, size: float, starts: int = FIT_STARTS) -> np.ndarray:
    """The mid-stance fixed point and ``starts`` offsets of size ``size`` in +- pairs of random 5-D directions (seed 0).

    The pairs keep the samples' centroid on the cycle to second order (one-sided offsets biased an affine fit at
    first order in ``size``). With the quadratic fit of :func:`fit_map`, the exact map through the same starts and
    fit ('reference_fit') is off by at most 4e-5 (Table-2 case), 1e-4 (n = 8, alpha = 0.25) and 1e-3 (n = 12,
    alpha = 0.125, where lambda5 = 0.973 nears the neutral 1) at ``size`` = 3e-3, 4e-6 / 3e-6 / 5e-5 at 5e-4. The
    ideal mode, free of noise, uses 5e-4; the contact mode 3e-3, against the ~1e-5 scatter soft impacts put on the
    mid-stance pitch rate (bootstrap std of lambda2: 1.6e-3 at 2e-3)."""
    x_star = hybrid.midstance_fixed_point(w)
    directions = random_directions(starts // 2, 5)
    return np.vstack([x_star, x_star + size * directions, x_star - size * directions])


def planar_headings(params: Values) -> list[float]:
    """Headings of the planar-cycle check: PLANAR_HEADINGS and ``heading``, where a rolling cycle exists."""
    return [h for h in sorted({float(params["heading"]), *PLANAR_HEADINGS}) if cycle_exists(wheel(params, h))]


def cycle_exists(w: theory.RimlessWheel3D) -> bool:
    """A rolling planar cycle exists for ``w`` (001 Sec. 5, :func:`theory.validate`)."""
    try:
        theory.validate(w)
    except ValueError:
        return False
    return True


def wheel_at(w: theory.RimlessWheel3D, heading: float) -> theory.RimlessWheel3D:
    """The same wheel at another heading."""
    return theory.RimlessWheel3D(w.spokes, w.slope, w.J, heading)


def reference_sequences(w: theory.RimlessWheel3D, size: float, rtol: float) -> list[np.ndarray]:
    """The exact hybrid map (solve_ivp DOP853 at relative and absolute tolerance ``rtol``) iterated FIT_IMPACTS times
    from each of :func:`fit_starts` (offsets of ``size``): the samples the fit batch would give without MuJoCo."""
    sequences = []
    for x in fit_starts(w, size):
        seq = []
        for _ in range(FIT_IMPACTS):
            x = hybrid.midstance_map(w, x, rtol=rtol, atol=rtol)[0]
            seq.append(x)
        sequences.append(np.array(seq))
    return sequences


def exact_model_bench(params: Values, rtol: float) -> dict[str, float]:
    """The exact hybrid reference (solve_ivp DOP853 at relative and absolute tolerance ``rtol``) from the same starts
    through the same fit: its error is the floor the experiment design (perturbation size, quadratic fit) sets."""
    w = wheel(params)
    ref = hybrid.midstance_eigenvalues(w)
    start = time.perf_counter()
    sequences = reference_sequences(w, PERTURBATION[str(params["impact"])], rtol)
    fitted = fit_map(sequences, w.heading, hybrid.family_tangent(hybrid.midstance_fixed_point, w))
    wall = time.perf_counter() - start
    x_ref, point = hybrid.midstance_fixed_point(w), fitted.cycle.fixed_point
    out: dict[str, float] = {"rtol": rtol, "wall_s": wall, "pitch_rate_error": abs(point[4] - x_ref[4]) / x_ref[4],
                             "bank_error": abs(point[1] - x_ref[1])}
    simulated = fitted.eigen.named() if fitted.eigen is not None else {}
    for name, value in ref.named().items():
        out[f"{name}_error"] = abs(simulated.get(name, math.nan) - value)
    return out
