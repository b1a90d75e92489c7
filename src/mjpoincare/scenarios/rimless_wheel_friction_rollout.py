"""The friction wheel's MuJoCo runs and their measurement (Gamus & Or 2015, Sec. 3): a batch rolled out with every
recorded row kept, 002's variables of each row read from the wheel's joints
(:func:`mjpoincare.analysis.rimless_wheel_rows.wheel_rows`), and the per-preset thresholds of the stick/slip
classification (why they are what they are: docs/scenarios/rimless-wheel-friction.md). Used by
:mod:`mjpoincare.scenarios.rimless_wheel_friction` and, through it, its friction sweep and region maps."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.analysis.rimless_wheel_rows import impact_window, wheel_rows
from mjpoincare.analysis.stick_slip_phases import Classifier, Rows
from mjpoincare.scenarios.base import JointIndex, Values
from mjpoincare.settings import rollout_options
from mjpoincare.simulate import Batch, Chunk, RolloutReport, event_rollout

#: Speed (nondimensional, units l omega_c) above which the stance foot moves: impacts and the velocity-only
#: classification.
V_THRESHOLD: dict[str, float] = {"fast": 5e-3, "accurate": 2e-3, "coarse": 1e-2}
IMPACT_WINDOW_TC = 5.0  # the impact window is at least this many contact time constants


def simulate(model: mujoco.MjModel, mu: np.ndarray, state0: np.ndarray, seconds: float, s: Values
             ) -> tuple[Chunk, RolloutReport]:
    """Roll every initial state out for ``seconds`` (one :func:`mujoco.rollout` batch, trajectory b with friction
    ``mu[b]`` on its feet and floor, native chunks of 0.5 s) and keep every recorded row: ``time`` (B, T), ``qpos``
    and ``qvel`` (B, T, 3)."""
    dt = model.opt.timestep
    nstep = max(1, math.ceil(seconds / dt))
    chunk = math.ceil(nstep / math.ceil(nstep / max(1, round(0.5 / dt))))  # equal chunks of <= 0.5 s: no overshoot
    parts: list[Chunk] = []

    def keep(c: Chunk, _batch: Batch) -> np.ndarray:
        parts.append(c if not parts else Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]))
        return np.full(c.time.shape[0], chunk)

    def frictions(batch: Batch) -> None:
        for b, value in enumerate(mu):
            batch.set_friction(b, float(value))

    report = event_rollout(model, state0, nstep, keep, chunk_steps=chunk, setup=frictions, **rollout_options(s))
    time_ = np.concatenate([c.time for c in parts], axis=1)[:, : nstep + 1]
    qpos = np.concatenate([c.qpos for c in parts], axis=1)[:, : nstep + 1]
    qvel = np.concatenate([c.qvel for c in parts], axis=1)[:, : nstep + 1]
    return Chunk(time_, qpos, qvel), report


def row_signals(rec: Chunk, model: mujoco.MjModel, p: Values, s: Values, unit: float, cls: Classifier) -> Rows:
    """002's variables and the contact force of every recorded row of ``rec`` (joints ``x``, ``z``, ``pitch`` of
    ``model``, whose gravity is the slope frame's), nondimensional with ``unit`` = omega_c (1/s)."""
    x, z, pitch = (JointIndex.of(model, name) for name in ("x", "z", "pitch"))
    return wheel_rows(time=rec.time, pitch=rec.qpos[:, :, pitch.qpos], pitch_rate=rec.qvel[:, :, pitch.dof],
                      hub_x_dot=rec.qvel[:, :, x.dof], hub_z=rec.qpos[:, :, z.qpos], hub_z_dot=rec.qvel[:, :, z.dof],
                      gravity=np.asarray(model.opt.gravity), spokes=int(p["spokes"]),
                      leg_length=float(p["leg_length"]), foot_radius=float(s["foot_radius"]), rate_unit=unit,
                      timestep=float(s["timestep"]), cls=cls)


def classifier(mu: np.ndarray | float, s: Values, preset: str, batch: int) -> Classifier:
    """Thresholds for ``preset``: ``V_THRESHOLD``; the impact window of the soft contact (:func:`impact_window`), at
    least IMPACT_WINDOW_TC contact time constants. The others are the classifier's."""
    window = impact_window(float(s["timestep"]), float(s["solref_timeconst"]), float(s["solref_dampratio"]),
                           IMPACT_WINDOW_TC)
    return Classifier(mu=np.broadcast_to(np.asarray(mu, float), (batch,)).copy(),
                      v_thr=V_THRESHOLD.get(preset, V_THRESHOLD["fast"]), impact_window=window)
