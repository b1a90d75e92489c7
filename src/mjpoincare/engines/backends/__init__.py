"""The engines behind the rollout seam (:class:`mjpoincare.core.seam.Batch`): MuJoCo C (:mod:`.mujoco_c`), MJX (JAX,
:mod:`.mjx`) and MuJoCo Warp (:mod:`.warp`), each in its own module, the last two imported only when asked for
(optional extras ``mjpoincare[mjx]``, ``mjpoincare[warp]``). :func:`open_batch` is the one way in.
"""

from __future__ import annotations

import importlib
import importlib.util
from collections.abc import Mapping

import mujoco
import numpy as np

from mjpoincare.core.params import ParameterError, Value
from mjpoincare.core.seam import STATE_SPEC, Batch
from mjpoincare.core.settings import BACKEND_PRECISIONS
from mjpoincare.engines.backends.mujoco_c import MujocoBatch

#: Settings each backend cannot honour: (setting, value) -> the missing feature.
UNSUPPORTED: dict[str, dict[tuple[str, Value], str]] = {
    "mjx": {("diagnostics", 1): "MJX has no kinetic-energy sensor (mjSENS_E_KINETIC)"},
    "drake": {("diagnostics", 1): "the Drake backend records no MuJoCo sensors"},
}
#: The seam mechanisms (keys of :data:`mjpoincare.simulation.seam_check.MECHANISMS`) whose self-tests fail on each
#: backend, so that every run of a scenario that uses one is refused before any simulation (Drake: docs/engines.md says
#: why).
LACKS: dict[str, tuple[str, ...]] = {"drake": ("contact", "equality", "actuator", "control", "fractional_step")}
#: The packages each backend needs, and the extra that installs them.
REQUIRES = {"mjx": (("jax", "mujoco.mjx"), "mjpoincare[mjx]"), "warp": (("warp", "mujoco_warp"), "mjpoincare[warp]"),
            "drake": (("pydrake",), "mjpoincare[peers]")}


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


def check_backend(settings: dict[str, Value]) -> None:
    """Resolve ``precision=auto`` to the backend's first precision (in place), and refuse a backend and precision
    that do not go together (:data:`mjpoincare.core.settings.BACKEND_PRECISIONS`), a backend whose packages are missing,
    or a setting the backend cannot honour, each in one line naming them (before any simulation)."""
    backend = str(settings["backend"])
    allowed = BACKEND_PRECISIONS[backend]
    if settings["precision"] == "auto":
        settings["precision"] = allowed[0]
    if settings["precision"] not in allowed:
        raise ParameterError(f"precision must be {' or '.join(allowed)} with backend={backend} "
                             f"(got {settings['precision']})")
    check_installed(backend)
    check_settings(settings)


def open_batch(model: mujoco.MjModel, state0: np.ndarray, *, threads: int, backend: str = "mujoco",
               precision: str = "float64", batch: int = 0, engine_options: Mapping[str, Value] | None = None
               ) -> Batch:
    """The :class:`~mjpoincare.core.seam.Batch` of ``backend`` over ``model`` and the starts ``state0`` (B, nstate), as
    a context manager.

    Args:
        model: the model every trajectory starts from (never changed: an event changes a trajectory's own copy).
        state0: full-physics starts, (B, nstate).
        threads: MuJoCo C's thread pool size (the array engines ignore it).
        backend: ``mujoco`` (:class:`~mjpoincare.engines.backends.mujoco_c.MujocoBatch`), ``mjx`` or ``warp`` (their
            optional packages).
        precision: the array engines' float type (MuJoCo C is float64).
        batch: MJX and Warp step max(B, ``batch``) trajectories, the rest padding that is never seen, so that every
            rollout of a run has one shape and compiles once (MuJoCo C compiles nothing and ignores it).
        engine_options: the engine's own keyword arguments (Drake: ``approximation``, ``hydroelastic``).

    Returns:
        The batch (enter it with ``with``).
    """
    if backend == "mujoco":
        return MujocoBatch(model, state0, threads)
    check_installed(backend)
    module = importlib.import_module(f"mjpoincare.engines.backends.{backend}")
    opened: Batch = module.open_batch(model, state0, precision=precision, size=batch, **(engine_options or {}))
    return opened


def state_layout(model: mujoco.MjModel, backend: str) -> None:
    """Refuse a model whose full-physics state holds more than (time, qpos, qvel, act): the backends' state is
    rebuilt from those four (MuJoCo docs, "State")."""
    if mujoco.mj_stateSize(model, STATE_SPEC) != 1 + model.nq + model.nv + model.na:
        raise ParameterError(f"backend={backend} needs a state of time, qpos, qvel and act only (this model has "
                             "history, plugin or plastic state)")
