"""Backends other than MuJoCo C behind the rollout seam (:class:`mjpoincare.simulate.Batch`): MJX (JAX) and MuJoCo
Warp, each in its own module, imported only when asked for (optional extras ``mjpoincare[mjx]``, ``mjpoincare[warp]``).
"""

from __future__ import annotations

import importlib
import importlib.util
from collections.abc import Mapping

import mujoco
import numpy as np

from mjpoincare.params import ParameterError, Value
from mjpoincare.simulate import STATE_SPEC, Batch, RolloutReport

#: MuJoCo's bound on a position or velocity (``mjMAXVAL``): beyond it MuJoCo C warns and resets the data, which
#: :func:`mjpoincare.simulate.rollout_batch` flags as a divergence; a backend that does not reset is flagged the same.
MAXVAL = 1e10
#: Settings each backend cannot honour: (setting, value) -> the missing feature.
UNSUPPORTED: dict[str, dict[tuple[str, Value], str]] = {
    "mjx": {("diagnostics", 1): "MJX has no kinetic-energy sensor (mjSENS_E_KINETIC)"},
}
#: The packages each backend needs, and the extra that installs them.
REQUIRES = {"mjx": (("jax", "mujoco.mjx"), "mjpoincare[mjx]"), "warp": (("warp", "mujoco_warp"), "mjpoincare[warp]")}


def check_installed(backend: str) -> None:
    """Refuse ``backend`` when its packages are missing, naming them and the extra (before any simulation)."""
    if backend not in REQUIRES:
        return
    modules, extra = REQUIRES[backend]
    missing = [m for m in modules if not _importable(m)]
    if missing:
        raise ParameterError(f"backend={backend} needs {', '.join(missing)}: pip install '{extra}'")


def check_settings(settings: Mapping[str, Value]) -> None:
    """Refuse a setting the chosen backend cannot honour (:data:`UNSUPPORTED`), in one line, before any simulation."""
    backend = str(settings["backend"])
    for (name, value), missing in UNSUPPORTED.get(backend, {}).items():
        if settings.get(name) == value:
            raise ParameterError(f"backend={backend} cannot run {name}={value}: {missing}")


def _importable(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except ModuleNotFoundError:  # a parent package is missing
        return False


def open_backend_batch(backend: str, model: mujoco.MjModel, state0: np.ndarray, *, precision: str, size: int = 0
                       ) -> Batch:
    """The backend's batch (:class:`mjpoincare.simulate.Batch`) over ``model`` and the starts ``state0`` (B, nstate),
    padded to ``size`` trajectories when ``size`` > B (:class:`ArrayBatch`)."""
    check_installed(backend)
    module = importlib.import_module(f"mjpoincare.backends.{backend}")
    batch: Batch = module.open_batch(model, state0, precision=precision, size=size)
    return batch


def state_layout(model: mujoco.MjModel, backend: str) -> None:
    """Refuse a model whose full-physics state holds more than (time, qpos, qvel, act): the backends' state is
    rebuilt from those four (MuJoCo docs, "State")."""
    if mujoco.mj_stateSize(model, STATE_SPEC) != 1 + model.nq + model.nv + model.na:
        raise ParameterError(f"backend={backend} needs a state of time, qpos, qvel and act only (this model has "
                             "history, plugin or plastic state)")


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
    """What the array backends' batches share (:class:`mjpoincare.simulate.Batch`): the current states of the B
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
    report: RolloutReport

    def _start(self, state0: np.ndarray, size: int) -> int:
        """Hold the starts ``state0`` (B, nstate), padded to ``size`` rows when ``size`` > B; the number of rows."""
        real = state0.shape[0]
        rows = max(real, size)
        self._real = real
        self._current = np.concatenate([state0, np.repeat(state0[-1:], rows - real, axis=0)]).astype(float)
        self._diverged = np.zeros(rows, bool)
        self.report = RolloutReport(diverged=np.zeros(real, bool))
        return rows

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

    def _finish_chunk(self, states: np.ndarray, sensordata: np.ndarray, nstep: int, seconds: float) -> np.ndarray:
        """Count the chunk's ``nstep`` steps and ``seconds``, flag divergences (:func:`flag_divergence`), fold the
        sensor readings ``sensordata`` (rows, nstep, nsensordata) into the report's extremes (divergent rows left
        out) and continue from the last states of ``states`` (rows, nstep, nstate); the B trajectories' recorded
        chunk (B, nstep + 1, nstate)."""
        real = self._real
        self.report.wall_s += seconds
        self.report.steps += real * nstep
        self.report.batch_steps += nstep
        full, bad = flag_divergence(self._current, states, self._diverged)
        self.report.diverged = self._diverged[:real].copy()
        if sensordata.shape[-1]:
            self.report.record_sensors(np.where(bad[:real, 1:, None], np.nan, sensordata[:real]))
        self._current = states[:, -1, :].copy()
        return full[:real]
