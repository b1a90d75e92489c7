"""The chunked event loop over any engine of the rollout seam: no Python between steps.

A batch of initial states is stepped by an engine (:mod:`mjpoincare.engines.backends`; MuJoCo C's threaded
``mujoco.rollout`` by default) in native chunks of ``chunk_steps`` steps. Each chunk's recorded states (time, qpos,
qvel) are handed to a consumer (usually a vectorised section detector) and then dropped, so memory stays
``O(batch x chunk_steps)`` whatever the duration. Consecutive chunks overlap by one row so that a crossing at a
chunk boundary is seen once.

Events go through one seam, :class:`mjpoincare.core.seam.Batch`: run a chunk, rewrite chosen trajectories' states,
switch a trajectory's contacts, equality constraints or actuators, and land a state on a guard with a fractional
step. Every engine implements it, and no scenario changes from one to the other. Diverged trajectories are flagged
per trajectory and MuJoCo's warnings, captured by :func:`mjpoincare.core.mjlog.captured_mujoco_log`, go into the report.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import mujoco
import numpy as np
from mujoco import rollout as mj_rollout

from mjpoincare.core.mjlog import captured_mujoco_log
from mjpoincare.core.params import Value
from mjpoincare.core.seam import STATE_SPEC, Batch, Chunk, RolloutReport
from mjpoincare.engines.backends import open_batch


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
    finished: Callable[[], np.ndarray] | None = None,
    engine_options: Mapping[str, Value] | None = None,
) -> RolloutReport:
    """Step every initial state in ``state0`` (B, nstate) for ``nstep`` steps, in native chunks.

    ``consume`` is called with each :class:`Chunk`. ``start_perturbation``: every start's velocities are scaled by
    ``1 + start_perturbation`` (a rounding-sized change for measuring a verdict's sensitivity; 0 leaves them).
    Trajectories whose time does not advance by exactly one timestep per step (MuJoCo reset them after an
    instability) or that contain NaN/inf are flagged in ``diverged``; their rows after the divergence are set to NaN
    before ``consume`` sees them, so no sample is taken from a reset state. ``batch``: the trajectories MJX and
    Warp step (:func:`open_batch`). ``stop`` (optional) is asked after each chunk has been consumed; when it answers
    True the rollout ends there (adaptive stopping, :mod:`mjpoincare.analysis.adaptive_stopping`). ``finished``
    (optional), asked after each chunk has been consumed: a mask (B,) of the trajectories whose result is already
    known; they are stepped no further (:meth:`~mjpoincare.core.seam.Batch.run_chunk`'s ``rows``: their rows of later
    chunks are NaN, never a divergence) and the rollout ends when every one is.
    ``engine_options``: the engine's own options (:func:`mjpoincare.engines.backends.open_batch`).
    """
    start = perturbed_starts(state0, model.nq, model.nv, start_perturbation)
    with captured_mujoco_log() as log:
        with open_batch(model, start, threads=threads, backend=backend, precision=precision, batch=batch,
                        engine_options=engine_options) as rollout:
            done, rows = 0, None
            while done < nstep:
                n = min(chunk_steps, nstep - done)
                consume(_chunk_of(rollout.run_chunk(n, rows=rows), model.nq, model.nv))
                done += n
                if finished is not None:
                    active = ~finished()
                    if not active.any():
                        break
                    rows = None if active.all() else np.flatnonzero(active)
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
    finished: Callable[[], np.ndarray] | None = None,
    engine_options: Mapping[str, Value] | None = None,
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
    ``start_perturbation``, ``batch``, ``stop``, ``finished``, ``engine_options``: as in :func:`rollout_batch`; a
    trajectory with its ``nstep`` kept steps is stepped no further either.
    """
    batch_size = state0.shape[0]
    nq, nv = model.nq, model.nv
    kept = np.zeros(batch_size, int)
    with captured_mujoco_log() as log:
        with open_batch(model, perturbed_starts(state0, nq, nv, start_perturbation), threads=threads,
                        backend=backend, precision=precision, batch=batch, engine_options=engine_options) as rollout:
            if setup is not None:
                setup(rollout)
            known = np.zeros(batch_size, bool)
            while (~(done := (kept >= nstep) | known)).any():
                before = rollout.states()
                ctrl = None if control is None else np.ascontiguousarray(control(before[:, 0]), dtype=float)
                full = rollout.run_chunk(chunk_steps, ctrl, rows=None if not done.any() else np.flatnonzero(~done))
                full[done, 0], full[done, 1:] = before[done], np.nan  # finished ones idle; nothing is sampled
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
                if finished is not None:
                    known |= np.asarray(finished(), bool)
                if stop is not None and stop():
                    break
        rollout.report.warnings += log
    return rollout.report


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
