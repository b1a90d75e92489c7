"""Batched rollouts through :mod:`mujoco.rollout`: no Python between steps.

A batch of initial states is stepped by MuJoCo's threaded C++ rollout in native chunks of
``chunk_steps`` steps. Each chunk's recorded states (time, qpos, qvel) are handed to a consumer
(usually a vectorised section detector) and then dropped, so memory stays
``O(batch x chunk_steps)`` whatever the duration. Consecutive chunks overlap by one row so that
a crossing at a chunk boundary is seen once.

Events go through one seam, :class:`Batch`: run a chunk, rewrite chosen trajectories' states, switch a
trajectory's contacts, equality constraints or actuators, and land a state on a guard with a fractional step.
:class:`MujocoBatch` implements it on MuJoCo C; a backend that batches ``mjData`` (MJX, MuJoCo Warp) implements the
same methods, and no scenario changes.

MuJoCo's reaction to a numerical blow-up (NaN/huge qacc) is to *reset* the data and carry on
silently; :func:`rollout_batch` detects that per trajectory from the recorded time, and reports
MuJoCo's warnings, captured by :func:`mjpoincare.mjlog.captured_mujoco_log`.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from types import TracebackType
from typing import Protocol

import mujoco
import numpy as np
from mujoco import rollout as mj_rollout

from mjpoincare.mjlog import captured_mujoco_log

STATE_SPEC = mujoco.mjtState.mjSTATE_FULLPHYSICS


@dataclass(frozen=True)
class Chunk:
    """States recorded over one chunk: ``time`` (B, T), ``qpos`` (B, T, nq), ``qvel`` (B, T, nv).

    Row 0 repeats the last row of the previous chunk (or is the initial state).
    """

    time: np.ndarray
    qpos: np.ndarray
    qvel: np.ndarray


@dataclass
class RolloutReport:
    """What a batch rollout did: ``steps`` simulated (trajectory-steps), ``batch_steps`` (each chunk's steps once:
    the steps a GPU takes one after the other, whatever the batch size), ``wall_s`` spent stepping, ``compile_s``
    spent compiling (MJX and Warp; 0 on MuJoCo C), divergence, warnings."""

    steps: int = 0
    wall_s: float = 0.0
    diverged: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    warnings: list[str] = field(default_factory=list)
    final_state: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    #: Smallest and largest value of each sensor over all recorded steps (empty when the model has none).
    sensor_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    sensor_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: Each sensor's largest value over the batch in the first two recorded steps (the scale of the initial states;
    #: two because MuJoCo's energy sensors lag the state by one step).
    sensor_first: np.ndarray = field(default_factory=lambda: np.zeros(0))
    compile_s: float = 0.0
    batch_steps: int = 0

    def merge(self, other: RolloutReport) -> RolloutReport:
        """One report for two batches run one after the other."""
        low, high = _sensor_extremes(self, other.sensor_min, other.sensor_max)
        first = (np.fmax(self.sensor_first, other.sensor_first) if self.sensor_first.size and other.sensor_first.size
                 else (self.sensor_first if self.sensor_first.size else other.sensor_first))
        return RolloutReport(steps=self.steps + other.steps, wall_s=self.wall_s + other.wall_s,
                             diverged=np.concatenate([self.diverged, other.diverged]),
                             warnings=self.warnings + other.warnings, final_state=self.final_state,
                             sensor_min=low, sensor_max=high, sensor_first=first,
                             compile_s=self.compile_s + other.compile_s,
                             batch_steps=self.batch_steps + other.batch_steps)

    def record_sensors(self, sensordata: np.ndarray) -> None:
        """Fold a chunk's sensor readings (..., nsensordata) into the extremes (NaN rows ignored)."""
        if sensordata.shape[-1] == 0 or not np.isfinite(sensordata).any():
            return
        if self.sensor_first.size == 0:
            first = sensordata.reshape(-1, *sensordata.shape[-2:])[:, :2].reshape(-1, sensordata.shape[-1])
            self.sensor_first = np.where(np.isnan(first), -np.inf, first).max(axis=0)
        flat = sensordata.reshape(-1, sensordata.shape[-1])
        nan = np.isnan(flat)
        self.sensor_min, self.sensor_max = _sensor_extremes(self, np.where(nan, np.inf, flat).min(axis=0),
                                                            np.where(nan, -np.inf, flat).max(axis=0))

    @property
    def steps_per_s(self) -> float:
        """Raw simulation rate over all trajectories."""
        return self.steps / self.wall_s if self.wall_s > 0 else float("nan")


def _sensor_extremes(report: RolloutReport, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    if report.sensor_min.size == 0:
        return low, high
    if low.size == 0:
        return report.sensor_min, report.sensor_max
    return np.fmin(report.sensor_min, low), np.fmax(report.sensor_max, high)


def initial_states(model: mujoco.MjModel, qpos: np.ndarray, qvel: np.ndarray) -> np.ndarray:
    """Full-physics state vectors (B, nstate) for the given (B, nq) positions and (B, nv) velocities."""
    data = mujoco.MjData(model)
    qpos = np.atleast_2d(qpos)
    qvel = np.atleast_2d(qvel)
    out = np.empty((qpos.shape[0], mujoco.mj_stateSize(model, STATE_SPEC)))
    for i in range(qpos.shape[0]):
        mujoco.mj_resetData(model, data)
        data.qpos[:] = qpos[i]
        data.qvel[:] = qvel[i]
        mujoco.mj_getState(model, data, out[i], STATE_SPEC)
    return out


def perturbed_starts(state0: np.ndarray, nq: int, nv: int, relative: float) -> np.ndarray:
    """A copy of the full-physics states ``state0`` (B, nstate) with the velocities scaled by ``1 + relative``."""
    current = np.array(state0, dtype=float)
    if relative:
        current[:, 1 + nq : 1 + nq + nv] *= 1.0 + relative
    return current


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
                  report: RolloutReport, control: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Step ``current`` (B, nstate) ``n`` steps in MuJoCo (with ``control`` (B, n, nu) as ctrl, if given);
    returns the raw states (B, n, nstate) and the
    chunk with its first row prepended, where rows from a divergence on (NaN, or MuJoCo's silent reset,
    seen as time not advancing by one step per step) are NaN and the trajectory is flagged in ``report``."""
    start = time.perf_counter()
    states, sensordata = pool.rollout(model, datas, current, control, nstep=n)
    report.wall_s += time.perf_counter() - start
    report.steps += current.shape[0] * n
    report.batch_steps += n
    full = np.concatenate([current[:, None, :], states], axis=1)
    expected = full[:, :1, 0] + dt * np.arange(n + 1)[None, :]
    bad = ~np.isfinite(full).all(axis=2) | (np.abs(full[:, :, 0] - expected) > 0.5 * dt)
    bad = np.logical_or.accumulate(bad | report.diverged[:, None], axis=1)
    report.diverged |= bad[:, -1]
    full[bad] = np.nan
    if sensordata.shape[-1]:
        report.record_sensors(np.where(bad[:, 1:, None], np.nan, sensordata))
    return states, full


#: ``geom_margin`` of a geom whose contacts are switched off on MJX and MuJoCo Warp: a contact would need a
#: penetration deeper than 1000 km. Those backends can change ``geom_margin`` per trajectory at runtime but not
#: ``geom_contype`` (MuJoCo docs, "Collision detection": a contact is generated when the distance is below the
#: margin). MuJoCo C before 3.5 still generates the contact of a geom resting on a plane with this margin, so
#: :class:`MujocoBatch` switches contacts with the collision filter instead (:func:`switch_contact_filter`).
RELEASED_MARGIN = -1e6


def switch_contact(released: dict[tuple[int, int], float], margins: np.ndarray, index: int, geom: int, on: bool
                   ) -> None:
    """:meth:`Batch.set_contact` through the margin (MJX, MuJoCo Warp): trajectory ``index``'s geom margins
    ``margins`` (a writable view of its own, (ngeom,)) get :data:`RELEASED_MARGIN` at ``geom`` when its contact is
    switched off, and the margin kept in ``released`` back when it is switched on again (switching twice either way
    changes nothing)."""
    if on:
        if (index, geom) in released:
            margins[geom] = released.pop((index, geom))
    elif (index, geom) not in released:
        released[index, geom] = float(margins[geom])
        margins[geom] = RELEASED_MARGIN


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


class Batch(Protocol):
    """B trajectories stepped in native chunks, with per-trajectory events between chunks: the seam a backend
    implements. States are full-physics vectors (nstate,) (MuJoCo docs, "State": ``mjSTATE_FULLPHYSICS``)."""

    report: RolloutReport
    #: The timestep of every trajectory, s.
    timestep: float

    def __enter__(self) -> Batch:
        """The batch, ready to run (a backend may compile here)."""
        ...

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        """Release the batch; ``report`` then holds the final states and the backend's warnings."""
        ...

    def run_chunk(self, nstep: int, control: np.ndarray | None = None) -> np.ndarray:
        """Step every trajectory ``nstep`` steps from its current state (``control`` (B, nstep, nu): the ctrl of each
        step); the recorded states (B, nstep + 1, nstate), row 0 the start, NaN from a divergence on (flagged in
        ``report``). Each trajectory's current state becomes its last step."""
        ...

    def states(self) -> np.ndarray:
        """The current states (B, nstate), a copy."""
        ...

    def set_states(self, indices: np.ndarray, states: np.ndarray) -> None:
        """Continue trajectories ``indices`` (k,) from ``states`` (k, nstate); the others are untouched."""
        ...

    def set_contact(self, index: int, geom: int, on: bool) -> None:
        """Switch geom ``geom``'s contacts off (none is generated) or back on, in trajectory ``index`` only."""
        ...

    def set_eq_active(self, index: int, eq: int, on: bool) -> None:
        """Switch equality constraint ``eq`` off or on, in trajectory ``index`` only."""
        ...

    def set_actuator(self, index: int, actuator: int, *, bias: float | None = None, gear: float | None = None
                     ) -> None:
        """Trajectory ``index``'s actuator ``actuator``: its constant bias force (``biasprm[0]``) and/or its ``gear[0]``
        (MuJoCo docs, "Actuation model")."""
        ...

    def set_friction(self, index: int, mu: float) -> None:
        """Trajectory ``index``'s sliding friction coefficient: every geom's ``friction[0]`` (MuJoCo mixes a contact's
        friction as the larger of its two geoms', so every contact of the trajectory then has ``mu``)."""
        ...

    def advance(self, index: int, state: np.ndarray, seconds: float) -> np.ndarray:
        """``state`` (nstate,) after one step of ``seconds`` (a fraction of the timestep) of trajectory ``index``'s
        model and integrator: how an event controller lands a state on its guard."""
        ...


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

    def run_chunk(self, nstep: int, control: np.ndarray | None = None) -> np.ndarray:
        models = self._shared if self._shared is not None and all(m is self._shared for m in self.models) \
            else self.models
        states, full = _native_chunk(self._pool, models, self._datas, self._current, nstep, self.timestep,
                                     self.report, control)
        self._current = states[:, -1, :].copy()
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

    def advance(self, index: int, state: np.ndarray, seconds: float) -> np.ndarray:
        """One event ``mjData`` serves the batch, set from ``state`` each time (its solver warmstart carries over)."""
        model = self.models[index]
        if self._event_data is None:
            self._event_data = mujoco.MjData(model)
        mujoco.mj_setState(model, self._event_data, state, STATE_SPEC)
        fractional_step(model, self._event_data, seconds)
        out = np.empty_like(state)
        mujoco.mj_getState(model, self._event_data, out, STATE_SPEC)
        return out


def open_batch(model: mujoco.MjModel, state0: np.ndarray, *, threads: int, backend: str = "mujoco",
               precision: str = "float64", batch: int = 0) -> Batch:
    """The :class:`Batch` of ``backend`` (``mujoco``: :class:`MujocoBatch`; ``mjx``, ``warp``: their optional
    packages, :mod:`mjpoincare.backends`) over ``model`` and the starts ``state0`` (B, nstate), as a context manager.
    ``batch``: MJX and Warp step max(B, ``batch``) trajectories, the rest padding that is never seen, so that every
    rollout of a run has one shape and compiles once (MuJoCo C compiles nothing and ignores it)."""
    if backend == "mujoco":
        return MujocoBatch(model, state0, threads)
    from mjpoincare.backends import open_backend_batch

    return open_backend_batch(backend, model, state0, precision=precision, size=batch)


def _chunk_of(full: np.ndarray, nq: int, nv: int) -> Chunk:
    return Chunk(time=full[:, :, 0], qpos=full[:, :, 1 : 1 + nq], qvel=full[:, :, 1 + nq : 1 + nq + nv])


def rollout_batch(
    model: mujoco.MjModel,
    state0: np.ndarray,
    nstep: int,
    consume: Callable[[Chunk], None],
    *,
    threads: int = 2,
    chunk_steps: int = 20000,
    start_perturbation: float = 0.0,
    backend: str = "mujoco",
    precision: str = "float64",
    batch: int = 0,
    stop: Callable[[], bool] | None = None,
) -> RolloutReport:
    """Step every initial state in ``state0`` (B, nstate) for ``nstep`` steps, in native chunks.

    ``consume`` is called with each :class:`Chunk`. ``start_perturbation``: every start's velocities are scaled by
    ``1 + start_perturbation`` (a rounding-sized change for measuring a verdict's sensitivity; 0 leaves them).
    Trajectories whose time does not advance by exactly one timestep per step (MuJoCo reset them after an
    instability) or that contain NaN/inf are flagged in ``diverged``; their rows after the divergence are set to NaN
    before ``consume`` sees them, so no sample is taken from a reset state. ``batch``: the trajectories MJX and
    Warp step (:func:`open_batch`). ``stop`` (optional) is asked after each chunk has been consumed; when it answers
    True the rollout ends there (adaptive stopping, :mod:`mjpoincare.analysis.adaptive_stopping`).
    """
    start = perturbed_starts(state0, model.nq, model.nv, start_perturbation)
    with captured_mujoco_log() as log:
        with open_batch(model, start, threads=threads, backend=backend, precision=precision, batch=batch) as rollout:
            done = 0
            while done < nstep:
                n = min(chunk_steps, nstep - done)
                consume(_chunk_of(rollout.run_chunk(n), model.nq, model.nv))
                done += n
                if stop is not None and stop():
                    break
        rollout.report.warnings += log
    return rollout.report


def event_rollout(
    model: mujoco.MjModel,
    state0: np.ndarray,
    nstep: int,
    on_chunk: Callable[[Chunk, Batch], np.ndarray | tuple[np.ndarray, dict[int, np.ndarray]]],
    *,
    threads: int = 2,
    chunk_steps: int = 200,
    control: Callable[[np.ndarray], np.ndarray] | None = None,
    start_perturbation: float = 0.0,
    setup: Callable[[Batch], None] | None = None,
    backend: str = "mujoco",
    precision: str = "float64",
    batch: int = 0,
    stop: Callable[[], bool] | None = None,
) -> RolloutReport:
    """Batched rollout with a controller that acts at events, without Python between steps.

    ``model``: shared by every trajectory; an event changes a trajectory's own copy through the :class:`Batch`
    (``model`` itself is never changed).
    ``setup(batch)`` (optional) runs before the first chunk (e.g. the initial contacts). The batch is stepped in
    native chunks of ``chunk_steps``; ``on_chunk(chunk, batch)`` inspects the recorded chunk (vectorised), may switch
    trajectories' contacts, constraints or actuators through ``batch``, and for each trajectory returns the row to
    continue from: ``chunk_steps`` to go on, or an earlier row ``k >= 1`` where an event happened. Trajectory ``b``
    then restarts exactly from its recorded state at row ``k`` (no event overshoot) and rows after ``k`` are
    discarded. ``on_chunk`` may also return ``(rows, overrides)`` where ``overrides[b]`` is the full state to continue
    from instead of row ``k`` (e.g. after a fractional step, :meth:`Batch.advance`, that lands exactly on the event,
    or a re-parametrisation of the state). Every trajectory is stepped until it has ``nstep`` kept steps; one that
    has them idles at its last kept state. Steps discarded after an event are counted in ``steps`` (they cost time).

    ``control`` (optional): called before each chunk with each trajectory's current time (B,); returns the
    ctrl of every step of the chunk, (B, chunk_steps, nu), which ``mujoco.rollout`` applies natively (row k
    acts on the step from recorded row k to k + 1). A time-varying feedforward (e.g. a reference trajectory in
    the phase since the last event, which the controller tracks) thus needs no Python between steps; rows
    after an event are discarded and the next chunk's control starts from the restart row.
    ``start_perturbation``, ``batch``, ``stop``: as in :func:`rollout_batch`.
    """
    batch_size = state0.shape[0]
    nq, nv = model.nq, model.nv
    kept = np.zeros(batch_size, int)
    with captured_mujoco_log() as log:
        with open_batch(model, perturbed_starts(state0, nq, nv, start_perturbation), threads=threads,
                        backend=backend, precision=precision, batch=batch) as rollout:
            if setup is not None:
                setup(rollout)
            while (kept < nstep).any():
                before = rollout.states()
                ctrl = None if control is None else np.ascontiguousarray(control(before[:, 0]), dtype=float)
                full = rollout.run_chunk(chunk_steps, ctrl)
                done = kept >= nstep
                full[done, 1:] = np.nan  # finished trajectories idle; nothing is sampled from them
                answer = on_chunk(_chunk_of(full, nq, nv), rollout)
                rows_out, overrides = answer if isinstance(answer, tuple) else (answer, {})
                restart = np.clip(np.asarray(rows_out, int), 1, chunk_steps)
                restart[rollout.report.diverged | done] = chunk_steps
                early = np.nonzero(restart < chunk_steps)[0]
                rollout.set_states(early, full[early, restart[early]])
                for b, state in overrides.items():
                    if not (rollout.report.diverged[b] or done[b]):
                        rollout.set_states(np.array([b]), state[None, :])
                rollout.set_states(np.nonzero(done)[0], before[done])
                kept += np.where(done, 0, restart)
                if stop is not None and stop():
                    break
        rollout.report.warnings += log
    return rollout.report


def fractional_step(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> None:
    """Advance ``data`` by one step of ``seconds`` (a fraction of the timestep) with the model's own integrator:
    how an event controller lands a state on its guard. The model's timestep is restored even if the step raises."""
    dt = model.opt.timestep
    model.opt.timestep = seconds
    try:
        mujoco.mj_step(model, data)
    finally:
        model.opt.timestep = dt


def plain_clip(model: mujoco.MjModel, state0: np.ndarray, nstep: int) -> np.ndarray:
    """A render clip without events: the first full-physics state of ``state0`` (B, nstate) stepped ``nstep`` steps
    in one native rollout (MuJoCo's log captured); the states after each step, (nstep, nstate)."""
    with captured_mujoco_log():
        states, _ = mj_rollout.rollout(model, mujoco.MjData(model), state0[:1], nstep=nstep)
    return states[0]


class KeptRows:
    """Wraps an :func:`event_rollout` controller and keeps trajectory 0's kept rows (a render clip).

    ``tag`` (optional) is read before the controller acts on each chunk; its value is kept beside each row
    of that chunk (e.g. a mocap position that the controller moves at the event)."""

    def __init__(self, on_chunk: Callable[[Chunk, Batch], np.ndarray | tuple[np.ndarray, dict]],
                 tag: Callable[[], np.ndarray] | None = None) -> None:
        self.on_chunk, self.tag = on_chunk, tag
        self.rows: list[np.ndarray] = []
        self.tags: list[np.ndarray] = []

    def __call__(self, chunk: Chunk, batch: Batch) -> np.ndarray | tuple[np.ndarray, dict]:
        tag = self.tag() if self.tag is not None else None
        answer = self.on_chunk(chunk, batch)
        restart = answer[0] if isinstance(answer, tuple) else answer
        k = max(1, int(restart[0]))
        self.rows.append(np.concatenate([chunk.time[0, 1 : k + 1, None], chunk.qpos[0, 1 : k + 1],
                                         chunk.qvel[0, 1 : k + 1]], axis=1))
        if tag is not None:
            self.tags.append(np.repeat(np.asarray(tag)[None], k, axis=0))
        return answer

    def states(self, nstep: int) -> np.ndarray:
        """The first ``nstep`` kept full-physics states (time, qpos, qvel) of trajectory 0."""
        return np.concatenate(self.rows)[:nstep]

    def tagged(self, nstep: int) -> np.ndarray:
        """The tag beside each of the first ``nstep`` kept states."""
        return np.concatenate(self.tags)[:nstep]


def event_clip(model: mujoco.MjModel, state0: np.ndarray, nstep: int,
               controller: Callable[[Chunk, Batch], np.ndarray | tuple[np.ndarray, dict]],
               chunk_steps: int, tag: Callable[[], np.ndarray] | None = None,
               setup: Callable[[Batch], None] | None = None) -> KeptRows:
    """A render clip with events: ``state0`` (1, nstate) run ``nstep`` steps by :func:`event_rollout` on ``model``
    (one thread) with ``controller`` (and ``setup``, as there); the kept rows (:meth:`KeptRows.states`,
    :meth:`KeptRows.tagged`)."""
    kept = KeptRows(controller, tag=tag)
    event_rollout(model, state0, nstep, kept, threads=1, chunk_steps=chunk_steps, setup=setup)
    return kept
