"""MJX (MuJoCo in JAX) behind the rollout seam: :class:`MjxBatch`.

A chunk of ``nstep`` steps is one compiled ``jax.lax.scan`` of ``mjx.step`` vmapped over the batch, compiled ahead of
time (``jit(...).lower(...).compile()``: a plain ``jax.jit`` recompiled when fed its own output) and cached per model
structure, batch size and chunk length, so batches of the same shapes compile once per process.

Per-trajectory events change per-trajectory arrays passed to the compiled chunk: ``geom_margin`` (contacts released
by :data:`mjpoincare.core.seam.RELEASED_MARGIN`; MJX cannot change ``geom_contype`` at runtime), ``geom_friction``,
``actuator_biasprm``, ``actuator_gear`` and the data's ``eq_active``.

Precision: ``float64`` runs everything the batch does (``put_model``, compiling, stepping, copying back) inside JAX's
scoped x64 context, ``jax.enable_x64(True)``, which restores the caller's setting on exit; ``float32`` runs inside
``jax.enable_x64(False)``. The global ``jax_enable_x64`` flag is never set.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager
from typing import Any

import jax
import jax.numpy as jnp
import mujoco
import numpy as np
from mujoco import mjx

from mjpoincare.core.params import ParameterError
from mjpoincare.engines.backends import state_layout
from mjpoincare.engines.backends.arrays import EVENT_FIELDS, ArrayBatch

#: Compiled chunks and fractional steps, by (kind, model structure, argument shapes): shared by every batch.
_COMPILED: dict[tuple, Any] = {}


@contextmanager
def precision_scope(precision: str) -> Iterator[None]:
    """JAX's x64 setting for ``precision`` (``float64`` or ``float32``) inside the block only."""
    with jax.enable_x64(precision == "float64"):
        yield


def put_model(model: mujoco.MjModel) -> mjx.Model:
    """``mjx.put_model``; a feature MJX lacks raises :class:`ParameterError` naming it. A model with contacts
    disabled goes in with the pyramidal cone: without contacts the cone changes nothing, and MJX's elliptic-cone
    solver fails to trace when there is no contact (it indexes with an empty float array)."""
    if model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT:
        model = copy.copy(model)
        model.opt.cone = mujoco.mjtCone.mjCONE_PYRAMIDAL
    try:
        return mjx.put_model(model)
    except NotImplementedError as error:
        raise ParameterError(f"backend=mjx cannot run this model: {error}") from error


def _one_step(mx: mjx.Model, fields: tuple[jax.Array, ...], d: mjx.Data) -> mjx.Data:
    """One step of one trajectory with its own (geom_margin, geom_friction, actuator_biasprm, actuator_gear)."""
    margin, friction, biasprm, gear = fields
    return mjx.step(mx.replace(geom_margin=margin, geom_friction=friction, actuator_biasprm=biasprm,
                               actuator_gear=gear), d)


def _with_state(d: mjx.Data, state: jax.Array, eq: jax.Array, nq: int, nv: int) -> mjx.Data:
    """``d`` (batched or not) at the full-physics ``state`` (..., nstate) with ``eq_active`` ``eq`` (..., neq)."""
    return d.replace(time=state[..., 0], qpos=state[..., 1 : 1 + nq], qvel=state[..., 1 + nq : 1 + nq + nv],
                     act=state[..., 1 + nq + nv :], eq_active=eq)


def _state_of(d: mjx.Data) -> jax.Array:
    """The full-physics state (..., nstate) of ``d``."""
    return jnp.concatenate([d.time[..., None], d.qpos, d.qvel, d.act], axis=-1)


def _chunk(mx: mjx.Model, fields: tuple[jax.Array, ...], d: mjx.Data, state: jax.Array, eq: jax.Array,
           ctrl: jax.Array) -> tuple[mjx.Data, jax.Array, jax.Array]:
    """From ``state`` (B, nstate), step every trajectory once per row of ``ctrl`` (B, n, nu); the data after the last
    step, the states after each step (B, n, nstate) and the sensor readings (B, n, nsensordata)."""
    step = jax.vmap(_one_step, in_axes=(None, 0, 0))

    def body(data: mjx.Data, c: jax.Array) -> tuple[mjx.Data, tuple[jax.Array, jax.Array]]:
        # keep the carry's dtypes: under x64, mjx.step returns the tendon wrap indices (make_data: int32) as int64
        data = jax.tree.map(lambda new, old: new.astype(old.dtype), step(mx, fields, data.replace(ctrl=c)), data)
        return data, (_state_of(data), data.sensordata)

    d = _with_state(d, state, eq, mx.nq, mx.nv)
    d, (rows, sensors) = jax.lax.scan(body, d, jnp.swapaxes(ctrl, 0, 1))
    return d, jnp.swapaxes(rows, 0, 1), jnp.swapaxes(sensors, 0, 1)


def _fraction(mx: mjx.Model, fields: tuple[jax.Array, ...], d: mjx.Data, state: jax.Array, eq: jax.Array,
              seconds: jax.Array, ctrl: jax.Array) -> jax.Array:
    """``state`` (nstate,) after one step of ``seconds`` under ``ctrl`` (nu,) with one trajectory's fields and
    ``eq_active`` ``eq``."""
    d = _with_state(d, state, eq, mx.nq, mx.nv).replace(ctrl=ctrl)
    return _state_of(_one_step(mx.replace(opt=mx.opt.replace(timestep=seconds)), fields, d))


def _compiled(kind: str, function: Callable[..., Any], *args: Any) -> tuple[Any, float]:
    """``function`` compiled ahead of time for ``args`` (cached by ``kind`` and the arguments' structure), and the
    seconds spent compiling it now (0 when cached)."""
    leaves, tree = jax.tree.flatten(args)
    key = (kind, tree, tuple((np.shape(leaf), str(getattr(leaf, "dtype", type(leaf).__name__))) for leaf in leaves))
    if key in _COMPILED:
        return _COMPILED[key], 0.0
    start = time.perf_counter()
    _COMPILED[key] = jax.jit(function).lower(*args).compile()
    return _COMPILED[key], time.perf_counter() - start


class MjxBatch(ArrayBatch):
    """:class:`mjpoincare.core.seam.Batch` on MJX: B trajectories of ``model`` from the starts ``state0``
    (B, nstate) in ``precision`` (``float64`` or ``float32``), padded to ``size`` (:class:`ArrayBatch`). The
    caller's model is never changed; every trajectory's event-changed fields live in this batch's arrays."""

    def __init__(self, model: mujoco.MjModel, state0: np.ndarray, precision: str = "float64", size: int = 0) -> None:
        state_layout(model, "mjx")
        self._model, self._precision = model, precision
        batch = self._start(model, np.asarray(state0, float), size)
        with self._scope():
            self._mx = put_model(model)
            self._single = mjx.make_data(self._mx)
            self._data = jax.tree.map(lambda x: jnp.broadcast_to(x, (batch, *jnp.shape(x))), self._single)
            self._dtype = self._single.qpos.dtype

    def _scope(self) -> AbstractContextManager[None]:
        return precision_scope(self._precision)

    def _event_fields(self, rows: slice | int = slice(None)) -> tuple[jax.Array, ...]:
        """Rows ``rows``' (geom_margin, geom_friction, actuator_biasprm, actuator_gear), as :func:`_step` takes them."""
        return tuple(jnp.asarray(self._fields[name][rows], self._dtype) for name in EVENT_FIELDS)

    def run_chunk(self, nstep: int, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> np.ndarray:
        ctrl = self._controls(control, nstep, self._model.nu)
        with self._scope():
            args = (self._mx, self._event_fields(), self._data, jnp.asarray(self._current, self._dtype),
                    jnp.asarray(self._eq), jnp.asarray(ctrl, self._dtype))
            chunk, seconds = _compiled("chunk", _chunk, *args)
            self.report.compile_s += seconds
            start = time.perf_counter()
            self._data, recorded, sensors = jax.block_until_ready(chunk(*args))
            states, sensordata = np.asarray(recorded, float), np.asarray(sensors, float)
        return self._finish_chunk(states, sensordata, nstep, time.perf_counter() - start, rows)

    def advance(self, index: int, state: np.ndarray, seconds: float, ctrl: np.ndarray | None = None) -> np.ndarray:
        """One compiled single-trajectory step from fresh data (no solver warmstart carried over)."""
        with self._scope():
            control = np.zeros(self._model.nu) if ctrl is None else ctrl
            args = (self._mx, self._event_fields(index), self._single, jnp.asarray(state, self._dtype),
                    jnp.asarray(self._eq[index]), jnp.asarray(seconds, self._dtype),
                    jnp.asarray(control, self._dtype))
            fraction, seconds = _compiled("fraction", _fraction, *args)
            self.report.compile_s += seconds
            return np.asarray(fraction(*args), float)


def open_batch(model: mujoco.MjModel, state0: np.ndarray, *, precision: str, size: int = 0) -> MjxBatch:
    """:class:`MjxBatch` over ``model`` from ``state0`` (B, nstate) in ``precision``, padded to ``size``."""
    return MjxBatch(model, state0, precision, size)
