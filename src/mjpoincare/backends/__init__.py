"""Backends other than MuJoCo C behind the rollout seam (:class:`mjpoincare.simulate.Batch`): MJX (JAX) and MuJoCo
Warp, each in its own module, imported only when asked for (optional extras ``mjpoincare[mjx]``, ``mjpoincare[warp]``).
"""

from __future__ import annotations

import importlib
import importlib.util

import mujoco
import numpy as np

from mjpoincare.params import ParameterError
from mjpoincare.simulate import Batch

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
