"""MuJoCo C behind the rollout seam (:class:`mjpoincare.core.seam.Batch`): ``mujoco.rollout``'s thread pool, no Python
between steps.

MuJoCo's reaction to a numerical blow-up (NaN/huge qacc) is to *reset* the data and carry on silently; a chunk
detects that per trajectory from the recorded time (it stops advancing by one step per step), and the data's
warnings go into the batch's report when it closes.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Sequence
from types import TracebackType

import mujoco
import numpy as np
from mujoco import rollout as mj_rollout

from mjpoincare.core.cost import check_chunk
from mjpoincare.core.seam import STATE_SPEC, RolloutReport


def _warning_lines(datas: list[mujoco.MjData]) -> list[str]:
    lines = []
    for name, kind in mujoco.mjtWarning.__members__.items():
        if name == "mjNWARNING":
            continue
        count = sum(int(d.warning[int(kind)].number) for d in datas)
        if count:
            lines.append(f"{name}: raised {count} time(s)")
    return lines


def _native_chunk(pool: mj_rollout.Rollout, model: mujoco.MjModel | list[mujoco.MjModel],
                  datas: list[mujoco.MjData], current: np.ndarray, n: int, dt: float,
                  report: RolloutReport, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Step ``current`` (B, nstate), or its ``rows`` (k,) only, ``n`` steps in MuJoCo (with ``control`` (B, n, nu)
    as ctrl, if given; ``model`` one for all or a list of B); returns the raw states of the stepped trajectories
    (k, n, nstate) and the chunk (B, n + 1, nstate) with its first row prepended, where rows from a divergence on
    (NaN, or MuJoCo's silent reset, seen as time not advancing by one step per step) are NaN and the trajectory is
    flagged in ``report``, and every trajectory not in ``rows`` is NaN throughout (not flagged)."""
    index = np.arange(current.shape[0]) if rows is None else np.asarray(rows, int)
    start_states = current[index]
    models = model if isinstance(model, mujoco.MjModel) else [model[i] for i in index]
    check_chunk(start_states.shape[0], n, current.shape[1])
    start = time.perf_counter()
    states, sensordata = pool.rollout(models, datas, start_states, None if control is None else control[index],
                                      nstep=n)
    report.wall_s += time.perf_counter() - start
    report.steps += start_states.shape[0] * n
    report.batch_steps += n
    stepped = np.concatenate([start_states[:, None, :], states], axis=1)
    expected = stepped[:, :1, 0] + dt * np.arange(n + 1)[None, :]
    bad = ~np.isfinite(stepped).all(axis=2) | (np.abs(stepped[:, :, 0] - expected) > 0.5 * dt)
    bad = np.logical_or.accumulate(bad | report.diverged[index, None], axis=1)
    report.diverged[index] |= bad[:, -1]
    stepped[bad] = np.nan
    if sensordata.shape[-1]:
        report.record_sensors(np.where(bad[:, 1:, None], np.nan, sensordata))
    if rows is None:
        return states, stepped
    full = np.full((current.shape[0], n + 1, current.shape[1]), np.nan)
    full[index] = stepped
    return states, full


def switch_contact_filter(released: dict[tuple[int, int], tuple[int, int]], model: mujoco.MjModel, index: int,
                          geom: int, on: bool) -> None:
    """:meth:`Batch.set_contact` through the collision filter (MuJoCo C, every release): trajectory ``index``'s own
    ``model`` gets ``geom_contype`` and ``geom_conaffinity`` 0 at ``geom`` when its contact is switched off (no pair
    with it passes the filter; MuJoCo docs, "Collision detection"), and the pair kept in ``released`` back when it is
    switched on again (switching twice either way changes nothing)."""
    if on:
        if (index, geom) in released:
            model.geom_contype[geom], model.geom_conaffinity[geom] = released.pop((index, geom))
    elif (index, geom) not in released:
        released[index, geom] = (int(model.geom_contype[geom]), int(model.geom_conaffinity[geom]))
        model.geom_contype[geom] = 0
        model.geom_conaffinity[geom] = 0


class MujocoBatch:
    """:class:`Batch` on MuJoCo C: ``mujoco.rollout``'s thread pool over ``models``. One model is shared by every
    trajectory until an event changes a trajectory's: that trajectory then gets its own copy (the caller's model is
    never changed). A list gives each trajectory its own model, changed in place by its events. A context manager
    (the pool and, at exit, the data's warnings in ``report``)."""

    def __init__(self, models: Sequence[mujoco.MjModel] | mujoco.MjModel, state0: np.ndarray, threads: int = 2
                 ) -> None:
        self._current = np.array(state0, dtype=float)
        batch = self._current.shape[0]
        self._shared = models if isinstance(models, mujoco.MjModel) else None
        self.models: list[mujoco.MjModel] = [models] * batch if isinstance(models, mujoco.MjModel) else list(models)
        first = self.models[0]
        self._datas = [mujoco.MjData(first) for _ in range(max(1, threads))]
        self._event_data: mujoco.MjData | None = None
        self._released: dict[tuple[int, int], tuple[int, int]] = {}
        self.timestep = first.opt.timestep
        self._pool = mj_rollout.Rollout(nthread=threads)
        self.report = RolloutReport(diverged=np.zeros(self._current.shape[0], bool))

    def __enter__(self) -> MujocoBatch:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self._pool.close()
        self.report.final_state = self._current
        self.report.warnings = _warning_lines(self._datas) + self.report.warnings

    def _model(self, index: int) -> mujoco.MjModel:
        """Trajectory ``index``'s own model, to change (copied from the shared one on its first change)."""
        if self._shared is not None and self.models[index] is self._shared:
            self.models[index] = copy.copy(self._shared)
        return self.models[index]

    def run_chunk(self, nstep: int, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> np.ndarray:
        models = self._shared if self._shared is not None and all(m is self._shared for m in self.models) \
            else self.models
        states, full = _native_chunk(self._pool, models, self._datas, self._current, nstep, self.timestep,
                                     self.report, control, rows)
        self._current[slice(None) if rows is None else np.asarray(rows, int)] = states[:, -1, :]
        return full

    def states(self) -> np.ndarray:
        return self._current.copy()

    def set_states(self, indices: np.ndarray, states: np.ndarray) -> None:
        self._current[np.asarray(indices, int)] = states

    def set_contact(self, index: int, geom: int, on: bool) -> None:
        switch_contact_filter(self._released, self._model(index), index, geom, on)

    def set_eq_active(self, index: int, eq: int, on: bool) -> None:
        self._model(index).eq_active0[eq] = on

    def set_actuator(self, index: int, actuator: int, *, bias: float | None = None, gear: float | None = None
                     ) -> None:
        model = self._model(index)
        if bias is not None:
            model.actuator_biasprm[actuator, 0] = bias
        if gear is not None:
            model.actuator_gear[actuator, 0] = gear

    def set_friction(self, index: int, mu: float) -> None:
        model = self._model(index)
        model.geom_friction[:, 0] = mu

    def advance(self, index: int, state: np.ndarray, seconds: float, ctrl: np.ndarray | None = None) -> np.ndarray:
        """One event ``mjData`` serves the batch, set from ``state`` and ``ctrl`` each time (its solver warmstart
        carries over)."""
        model = self.models[index]
        if self._event_data is None:
            self._event_data = mujoco.MjData(model)
        mujoco.mj_setState(model, self._event_data, state, STATE_SPEC)
        self._event_data.ctrl[:] = 0.0 if ctrl is None else ctrl
        fractional_step(model, self._event_data, seconds)
        out = np.empty_like(state)
        mujoco.mj_getState(model, self._event_data, out, STATE_SPEC)
        return out


def fractional_step(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> None:
    """Advance ``data`` by one step of ``seconds`` (a fraction of the timestep) with the model's own integrator:
    how an event controller lands a state on its guard. The model's timestep is restored even if the step raises."""
    dt = model.opt.timestep
    model.opt.timestep = seconds
    try:
        mujoco.mj_step(model, data)
    finally:
        model.opt.timestep = dt
