"""MuJoCo Warp behind the rollout seam: :class:`WarpBatch` (float32, MuJoCo Warp's only precision).

The batch is one ``mujoco_warp`` Data of B worlds. A block of up to :data:`BLOCK` steps (per step: a kernel writing
the step's ctrl, ``mujoco_warp.step``, a kernel recording the state, a kernel advancing the step index held on the
device) is captured once per chunk length as a Warp graph (a CUDA graph on a GPU, an API capture replayed in C++ on
the ``cpu`` device); a chunk of ``nstep`` steps replays it ``nstep / block`` times. Warp compiles its kernels at the
first step (cached on disk across processes); that and the captures count as compile time.

Per-trajectory events write per-world model arrays (``put_model``'s ``batch_sizes``): ``geom_margin`` (contacts
released by :data:`mjpoincare.core.seam.RELEASED_MARGIN`; ``geom_contype`` is filtered once in ``put_model`` and
cannot change at runtime), ``geom_friction``, ``actuator_biasprm``, ``actuator_gear``, and the data's
``eq_active``. A fractional step runs on a separate one-world model and data.
"""

from __future__ import annotations

import time
from types import TracebackType
from typing import Any

import mujoco
import mujoco_warp as mjw
import numpy as np
import warp as wp

from mjpoincare.core.params import ParameterError
from mjpoincare.engines.backends import state_layout
from mjpoincare.engines.backends.arrays import EVENT_FIELDS, ArrayBatch

#: Most steps captured in one graph: capturing issues every launch from Python once (slow on the CPU), replaying
#: runs them natively; a chunk replays its graph nstep / block times.
BLOCK = 50
#: Seconds spent in first steps (Warp's kernel compiling or loading) and graph captures in this process (read by
#: the findings table).


def quiet() -> wp.ScopedLogLevel:
    """Warp's info messages (its banner, module loads) off inside the block only: they would go to stdout, into the
    CLI's table."""
    return wp.ScopedLogLevel(wp.LOG_WARNING)


@wp.kernel
def _set_state(state: wp.array2d(dtype=float), nq: int, nv: int, time_: wp.array(dtype=float),
               qpos: wp.array2d(dtype=float), qvel: wp.array2d(dtype=float), act: wp.array2d(dtype=float)):
    w = wp.tid()
    time_[w] = state[w, 0]
    for i in range(nq):
        qpos[w, i] = state[w, 1 + i]
    for i in range(nv):
        qvel[w, i] = state[w, 1 + nq + i]
    for i in range(act.shape[1]):
        act[w, i] = state[w, 1 + nq + nv + i]


@wp.kernel
def _set_ctrl(controls: wp.array3d(dtype=float), step: wp.array(dtype=int), ctrl: wp.array2d(dtype=float)):
    w = wp.tid()
    for i in range(ctrl.shape[1]):
        ctrl[w, i] = controls[w, step[0], i]


@wp.kernel
def _count(step: wp.array(dtype=int)):
    step[0] = step[0] + 1


@wp.kernel
def _record(time_: wp.array(dtype=float), qpos: wp.array2d(dtype=float), qvel: wp.array2d(dtype=float),
            act: wp.array2d(dtype=float), sensordata: wp.array2d(dtype=float), step: wp.array(dtype=int),
            rows: wp.array3d(dtype=float), sensors: wp.array3d(dtype=float)):
    w = wp.tid()
    k = step[0]
    nq, nv = qpos.shape[1], qvel.shape[1]
    rows[w, k, 0] = time_[w]
    for i in range(nq):
        rows[w, k, 1 + i] = qpos[w, i]
    for i in range(nv):
        rows[w, k, 1 + nq + i] = qvel[w, i]
    for i in range(act.shape[1]):
        rows[w, k, 1 + nq + nv + i] = act[w, i]
    for i in range(sensordata.shape[1]):
        sensors[w, k, i] = sensordata[w, i]


def _block(nstep: int) -> int:
    """Steps per captured graph for a chunk of ``nstep``: the largest divisor of ``nstep`` up to :data:`BLOCK`."""
    return max(d for d in range(1, min(nstep, BLOCK) + 1) if nstep % d == 0)


def put_model(model: mujoco.MjModel, worlds: int) -> Any:
    """``mujoco_warp.put_model`` with the event fields (:data:`~mjpoincare.engines.backends.arrays.EVENT_FIELDS`) per
    world (``worlds`` of them); a feature MuJoCo Warp lacks raises :class:`ParameterError` naming it."""
    try:
        return mjw.put_model(model, batch_sizes=dict.fromkeys(EVENT_FIELDS, worlds))
    except NotImplementedError as error:
        raise ParameterError(f"backend=warp cannot run this model: {error}") from error


def _overflow_lines(overflow: np.ndarray) -> list[str]:
    """MuJoCo Warp's overflow bitmasks (B,) as warning lines: a full buffer (contacts, constraints, ...). The solver
    reaching its iteration limit is left out, as MuJoCo C does not warn about it either."""
    lines = []
    for flag in mjw.OverflowType:
        count = int(((overflow & int(flag)) != 0).sum())
        if count and flag not in (mjw.OverflowType.ITERATIONS, mjw.OverflowType.LS_ITERATIONS):
            lines.append(f"mujoco_warp overflow {flag.name}: in {count} trajectory(ies)")
    return lines


class WarpBatch(ArrayBatch):
    """:class:`mjpoincare.core.seam.Batch` on MuJoCo Warp: B worlds of ``model`` from the starts ``state0``
    (B, nstate), padded to ``size`` (:class:`ArrayBatch`), on Warp's default device. The caller's model is never
    changed."""

    def __init__(self, model: mujoco.MjModel, state0: np.ndarray, size: int = 0) -> None:
        state_layout(model, "warp")
        self._model = model
        batch = self._start(model, np.asarray(state0, float), size)
        with quiet():
            self._device = wp.get_device()
            self._mw = put_model(model, batch)
            self._data = mjw.put_data(model, mujoco.MjData(model), nworld=batch)
            self._event_model = put_model(model, 1)
            self._event_data = mjw.put_data(model, mujoco.MjData(model), nworld=1)
            self._step = wp.zeros(1, dtype=int)
        #: Per chunk length: its ctrl (B, nstep, nu), states (B, nstep, nstate) and sensor (B, nstep, nsensordata)
        #: buffers and its captured block of steps.
        self._buffers: dict[int, tuple[wp.array, wp.array, wp.array, Any]] = {}
        self._warm = False

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        super().__exit__(kind, error, trace)
        self.report.warnings += _overflow_lines(self._data.overflow.numpy()[: self._real])

    def _load(self, model: Any, data: Any, rows: slice, state: np.ndarray) -> None:
        """Write trajectories ``rows``' fields, ``eq_active`` and ``state`` (k, nstate) into ``model``/``data``."""
        for name, values in self._fields.items():
            getattr(model, name).assign(values[rows].astype(np.float32))
        data.eq_active.assign(self._eq[rows])
        wp.launch(_set_state, dim=state.shape[0], inputs=[wp.array(state.astype(np.float32), dtype=float),
                                                          self._model.nq, self._model.nv],
                  outputs=[data.time, data.qpos, data.qvel, data.act])

    def _steps(self, block: int, controls: wp.array, rows: wp.array, sensors: wp.array) -> None:
        """Issue ``block`` steps, each at the step index held on the device (advanced after each step)."""
        d = self._data
        for _ in range(block):
            wp.launch(_set_ctrl, dim=d.nworld, inputs=[controls, self._step], outputs=[d.ctrl])
            mjw.step(self._mw, d)
            wp.launch(_record, dim=d.nworld, inputs=[d.time, d.qpos, d.qvel, d.act, d.sensordata, self._step],
                      outputs=[rows, sensors])
            wp.launch(_count, dim=1, inputs=[self._step])

    def _first_step(self) -> None:
        """Compile (or load) Warp's kernels outside the timed chunks, on a throwaway copy of the start."""
        start = time.perf_counter()
        with quiet():
            data = mjw.put_data(self._model, mujoco.MjData(self._model), nworld=self._data.nworld)
            mjw.step(self._mw, data)
            wp.synchronize_device(self._device)
        self.report.compile_s += time.perf_counter() - start
        self._warm = True

    def run_chunk(self, nstep: int, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> np.ndarray:
        if not self._warm:
            self._first_step()
        batch, model = self._current.shape[0], self._model
        if nstep not in self._buffers:
            self._buffers[nstep] = (wp.zeros((batch, nstep, model.nu), dtype=float),
                                    wp.zeros((batch, nstep, self._current.shape[1]), dtype=float),
                                    wp.zeros((batch, nstep, model.nsensordata), dtype=float), None)
        controls, recorded, sensors, graph = self._buffers[nstep]
        block = _block(nstep)
        controls.assign(self._controls(control, nstep, model.nu).astype(np.float32))
        with quiet():
            if graph is None:
                start = time.perf_counter()
                with wp.ScopedCapture(device=self._device) as capture:
                    self._steps(block, controls, recorded, sensors)
                graph = capture.graph
                self._buffers[nstep] = (controls, recorded, sensors, graph)
                self.report.compile_s += time.perf_counter() - start
            self._load(self._mw, self._data, slice(None), self._current)
            start = time.perf_counter()
            self._step.zero_()
            for _ in range(nstep // block):
                wp.capture_launch(graph)
            wp.synchronize_device(self._device)
            states, sensordata = recorded.numpy().astype(float), sensors.numpy().astype(float)
        return self._finish_chunk(states, sensordata, nstep, time.perf_counter() - start, rows)

    def advance(self, index: int, state: np.ndarray, seconds: float, ctrl: np.ndarray | None = None) -> np.ndarray:
        """One step on the one-world event model and data (its solver warmstart carries over, as in MuJoCo C's)."""
        model, data = self._event_model, self._event_data
        with quiet():
            self._load(model, data, slice(index, index + 1), state[None, :])
            control = np.zeros(self._model.nu) if ctrl is None else ctrl
            data.ctrl.assign(np.asarray(control, np.float32)[None, :])
            model.opt.timestep.assign(np.array([seconds], np.float32))
            mjw.step(model, data)
            out = np.concatenate([data.time.numpy(), data.qpos.numpy()[0], data.qvel.numpy()[0],
                                  data.act.numpy()[0]])
        return out.astype(float)


def open_batch(model: mujoco.MjModel, state0: np.ndarray, *, precision: str, size: int = 0) -> WarpBatch:
    """:class:`WarpBatch` over ``model`` from ``state0`` (B, nstate), padded to ``size``; ``precision`` must be
    ``float32``."""
    if precision != "float32":
        raise ParameterError(f"backend=warp runs in float32 only (got precision={precision})")
    return WarpBatch(model, state0, size)
