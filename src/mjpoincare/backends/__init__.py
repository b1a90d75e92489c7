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


def open_backend_batch(backend: str, model: mujoco.MjModel, state0: np.ndarray, *, precision: str) -> Batch:
    """The backend's batch (:class:`mjpoincare.simulate.Batch`) over ``model`` and the starts ``state0``."""
    check_installed(backend)
    module = importlib.import_module(f"mjpoincare.backends.{backend}")
    batch: Batch = module.open_batch(model, state0, precision=precision)
    return batch


def state_layout(model: mujoco.MjModel, backend: str) -> None:
    """Refuse a model whose full-physics state holds more than (time, qpos, qvel, act): the backends' state is
    rebuilt from those four (MuJoCo docs, "State")."""
    if mujoco.mj_stateSize(model, STATE_SPEC) != 1 + model.nq + model.nv + model.na:
        raise ParameterError(f"backend={backend} needs a state of time, qpos, qvel and act only (this model has "
                             "history, plugin or plastic state)")


def flag_divergence(current: np.ndarray, states: np.ndarray, report: RolloutReport, sensordata: np.ndarray
                    ) -> np.ndarray:
    """The recorded chunk (B, n + 1, nstate): the start ``current`` (B, nstate) and the states after each step
    ``states`` (B, n, nstate), NaN from a divergence on (non-finite or beyond :data:`MAXVAL`: the backends do not
    reset), the trajectory flagged in ``report``; ``sensordata`` (B, n, nsensordata) is folded into the report's
    sensor extremes, divergent rows left out."""
    full = np.concatenate([current[:, None, :], states], axis=1)
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(full).all(axis=2) | (np.abs(full[:, :, 1:]) > MAXVAL).any(axis=2)
    bad = np.logical_or.accumulate(bad | report.diverged[:, None], axis=1)
    report.diverged |= bad[:, -1]
    full[bad] = np.nan
    if sensordata.shape[-1]:
        report.record_sensors(np.where(bad[:, 1:, None], np.nan, sensordata))
    return full


class ArrayBatch:
    """What the array backends' batches share (:class:`mjpoincare.simulate.Batch`): the current states ``_current``
    (B, nstate) and the bookkeeping of a finished chunk."""

    _current: np.ndarray
    report: RolloutReport

    def states(self) -> np.ndarray:
        return self._current.copy()

    def set_states(self, indices: np.ndarray, states: np.ndarray) -> None:
        self._current[np.asarray(indices, int)] = states

    def _finish_chunk(self, states: np.ndarray, sensordata: np.ndarray, nstep: int, seconds: float) -> np.ndarray:
        """Count the chunk's ``nstep`` steps and ``seconds``, flag divergences (:func:`flag_divergence`) and continue
        from its last states (B, nstep, nstate); the recorded chunk (B, nstep + 1, nstate)."""
        self.report.wall_s += seconds
        self.report.steps += self._current.shape[0] * nstep
        full = flag_divergence(self._current, states, self.report, sensordata)
        self._current = states[:, -1, :].copy()
        return full
