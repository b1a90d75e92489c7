"""What the array engines' batches share (MJX, MuJoCo Warp): the current states of the trajectories and of the
padding, the bookkeeping of a finished chunk and the flagging of a divergence (:class:`mjpoincare.core.seam.Batch`)."""

from __future__ import annotations

from types import TracebackType

import mujoco
import numpy as np

from mjpoincare.core.seam import RolloutReport, switch_contact

#: The model fields a trajectory's events change on the array engines, one copy per trajectory: contacts are
#: released through ``geom_margin`` (neither MJX nor MuJoCo Warp can change ``geom_contype`` at run time), friction
#: through ``geom_friction``, actuators through ``actuator_biasprm`` and ``actuator_gear``.
EVENT_FIELDS = ("geom_margin", "geom_friction", "actuator_biasprm", "actuator_gear")

#: MuJoCo's bound on a position or velocity (``mjMAXVAL``): beyond it MuJoCo C warns and resets the data, which
#: :class:`~mjpoincare.engines.backends.mujoco_c.MujocoBatch` flags as a divergence; an engine that does not reset is
#: flagged the same.
MAXVAL = 1e10

def flag_divergence(current: np.ndarray, states: np.ndarray, diverged: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The recorded chunk (B, n + 1, nstate) from the start ``current`` (B, nstate) and the states after each step
    ``states`` (B, n, nstate), NaN from a divergence on (non-finite or beyond :data:`MAXVAL`: the backends do not
    reset), and its mask (B, n + 1); ``diverged`` (B,) is updated in place."""
    full = np.concatenate([current[:, None, :], states], axis=1)
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(full).all(axis=2) | (np.abs(full[:, :, 1:]) > MAXVAL).any(axis=2)
    bad = np.logical_or.accumulate(bad | diverged[:, None], axis=1)
    diverged |= bad[:, -1]
    full[bad] = np.nan
    return full, bad


class ArrayBatch:
    """What the array backends' batches share (:class:`mjpoincare.core.seam.Batch`): the current states of the B
    trajectories and of the padding, and the bookkeeping of a finished chunk.

    Padding: a batch opened with ``size`` > B steps ``size`` trajectories, the B starts and ``size`` - B copies of
    the last start, so that every rollout of a run has one shape and MJX and Warp compile once (the ``batch``
    setting). The padding is never seen: chunks, states, divergence flags, sensor extremes and step counts are the B
    trajectories' only; it takes no events (its contacts, constraints and actuators stay as the model has them).
    """

    #: The current states (size, nstate): the B trajectories' first, then the padding's.
    _current: np.ndarray
    #: Divergence flags of every row of ``_current``.
    _diverged: np.ndarray
    #: B, the trajectories the caller asked for.
    _real: int
    #: Every row's own copy of the model fields its events change (:data:`EVENT_FIELDS`), (rows, ...) each.
    _fields: dict[str, np.ndarray]
    #: Every row's ``eq_active``, (rows, neq).
    _eq: np.ndarray
    #: (row, geom) -> the margin a released contact had (:func:`mjpoincare.core.seam.switch_contact`).
    _released: dict[tuple[int, int], float]
    report: RolloutReport
    timestep: float

    def _start(self, model: mujoco.MjModel, state0: np.ndarray, size: int) -> int:
        """Hold the starts ``state0`` (B, nstate), padded to ``size`` rows when ``size`` > B, and every row's copy of
        ``model``'s event fields; the number of rows."""
        real = state0.shape[0]
        rows = max(real, size)
        self._real = real
        self._current = np.concatenate([state0, np.repeat(state0[-1:], rows - real, axis=0)]).astype(float)
        self._diverged = np.zeros(rows, bool)
        self.report = RolloutReport(diverged=np.zeros(real, bool))
        self.timestep = model.opt.timestep
        self._fields = {name: np.tile(getattr(model, name), (rows,) + (1,) * getattr(model, name).ndim)
                        for name in EVENT_FIELDS}
        self._eq = np.tile(model.eq_active0.astype(bool), (rows, 1))
        self._released = {}
        return rows

    def __enter__(self) -> ArrayBatch:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self._finish()

    def set_contact(self, index: int, geom: int, on: bool) -> None:
        switch_contact(self._released, self._fields["geom_margin"][index], index, geom, on)

    def set_eq_active(self, index: int, eq: int, on: bool) -> None:
        self._eq[index, eq] = on

    def set_actuator(self, index: int, actuator: int, *, bias: float | None = None, gear: float | None = None
                     ) -> None:
        if bias is not None:
            self._fields["actuator_biasprm"][index, actuator, 0] = bias
        if gear is not None:
            self._fields["actuator_gear"][index, actuator, 0] = gear

    def set_friction(self, index: int, mu: float) -> None:
        self._fields["geom_friction"][index, :, 0] = mu

    def states(self) -> np.ndarray:
        return self._current[: self._real].copy()

    def set_states(self, indices: np.ndarray, states: np.ndarray) -> None:
        self._current[np.asarray(indices, int)] = states

    def _controls(self, control: np.ndarray | None, nstep: int, nu: int) -> np.ndarray:
        """The ctrl of every row and step (rows, nstep, nu): the B trajectories' ``control`` (B, nstep, nu), zero for
        the padding (and for everyone when ``control`` is None)."""
        out = np.zeros((self._current.shape[0], nstep, nu))
        if control is not None:
            out[: self._real] = control
        return out

    def _finish(self) -> None:
        """On leaving the batch: the B trajectories' last states."""
        self.report.final_state = self.states()

    def _finish_chunk(self, states: np.ndarray, sensordata: np.ndarray, nstep: int, seconds: float,
                      rows: np.ndarray | None = None) -> np.ndarray:
        """Count the chunk's ``nstep`` steps and ``seconds``, flag divergences (:func:`flag_divergence`), fold the
        sensor readings ``sensordata`` (rows, nstep, nsensordata) into the report's extremes (divergent rows left
        out) and continue from the last states of ``states`` (rows, nstep, nstate); the B trajectories' recorded
        chunk (B, nstep + 1, nstate). With ``rows`` (k,) (:meth:`mjpoincare.core.seam.Batch.run_chunk`), every other
        trajectory keeps its state and its divergence flag, is NaN in the chunk and stays out of the sensor
        extremes."""
        real = self._real
        self.report.wall_s += seconds
        self.report.steps += real * nstep
        self.report.batch_steps += nstep
        others = np.zeros(self._current.shape[0], bool)
        if rows is not None:
            others[:real] = True
            others[np.asarray(rows, int)] = False
        flags = self._diverged.copy()
        full, bad = flag_divergence(self._current, states, self._diverged)
        self._diverged[others] = flags[others]
        bad[others] = True
        full[others] = np.nan
        self.report.diverged = self._diverged[:real].copy()
        if sensordata.shape[-1]:
            self.report.record_sensors(np.where(bad[:real, 1:, None], np.nan, sensordata[:real]))
        self._current = np.where(others[:, None], self._current, states[:, -1, :])
        return full[:real]
