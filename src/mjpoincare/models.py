"""Load the MJCF files in ``models/`` as :class:`mujoco.MjSpec` and compile them with clear errors."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import mujoco

from mjpoincare.params import ParameterError, Value
from mjpoincare.settings import apply_unskip

MODELS_DIR = Path(__file__).resolve().parents[2] / "models"


def load_spec(filename: str) -> mujoco.MjSpec:
    """Parse ``models/<filename>``; a missing or malformed file raises :class:`ParameterError`."""
    path = MODELS_DIR / filename
    if not path.is_file():
        raise ParameterError(f"model file {path} not found")
    try:
        return mujoco.MjSpec.from_file(str(path))
    except ValueError as err:  # MuJoCo's XML parser reports malformed models as ValueError
        raise ParameterError(f"model {path.name} is malformed: {str(err).splitlines()[0]}") from None


def compile_spec(spec: mujoco.MjSpec, settings: Mapping[str, Value] | None = None) -> mujoco.MjModel:
    """Compile ``spec`` (after undoing the skip ``settings["unskip"]`` names, if any); a compile error is reported
    as one line naming the model."""
    if settings is not None:
        apply_unskip(spec, settings)
    try:
        return spec.compile()
    except ValueError as err:
        raise ParameterError(f"model {spec.modelname!r} does not compile: {str(err).splitlines()[0]}") from None
