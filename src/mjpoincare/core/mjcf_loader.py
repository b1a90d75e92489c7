"""Load the MJCF files shipped as package data (``mjpoincare.mjcf``, built from the top-level ``models/``) as
:class:`mujoco.MjSpec` and compile them with clear errors."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from importlib import resources
from importlib.abc import Traversable
from pathlib import Path

import mujoco

from mjpoincare.core.params import ParameterError, Value
from mjpoincare.core.settings import apply_unskip

#: The package holding the MJCF files (``models/`` in the source tree, ``mjpoincare/mjcf/`` in a wheel).
MODELS_PACKAGE = "mjpoincare.mjcf"
#: An edit every compiled model gets in this context (:func:`planted`), None outside it.
_PLANTED: ContextVar[Callable[[mujoco.MjModel], object] | None] = ContextVar("planted", default=None)
#: The files the models ``<include>``, by the name they include them with (relative to the models' folder).
INCLUDES = ("common/looks.xml",)


def model_file(filename: str) -> Traversable:
    """The shipped MJCF file ``filename`` (readable with ``read_text``; a path on disk in any install)."""
    return resources.files(MODELS_PACKAGE) / filename


def load_spec(filename: str | os.PathLike[str]) -> mujoco.MjSpec:
    """Parse an MJCF model with the shared files it may include (:data:`INCLUDES`: ``<include
    file="common/looks.xml"/>`` gives the sky, the floor's material and the headlight every built-in has).

    Args:
        filename: a built-in's model, by its name in the package's models (``"rimless_wheel_2d.xml"``), or a
            plugin's own model file, by its path (a :class:`pathlib.Path`, or a string naming an existing file with
            a folder in it, e.g. ``Path(__file__).with_name("toy.xml")``).

    Returns:
        the parsed spec; a missing or malformed file raises :class:`ParameterError` (one line naming it).
    """
    own = isinstance(filename, os.PathLike) or os.path.dirname(filename) != ""
    source: Traversable | Path = Path(filename) if own else model_file(str(filename))
    if not source.is_file():
        where = "" if own else f" in {MODELS_PACKAGE}"
        raise ParameterError(f"model file {filename} not found{where}")
    include = {name: model_file(name).read_bytes() for name in INCLUDES}
    try:
        return mujoco.MjSpec.from_string(source.read_text(), include=include)
    except ValueError as err:  # MuJoCo's XML parser reports malformed models as ValueError
        raise ParameterError(f"model {filename} is malformed: {str(err).splitlines()[0]}") from None


def compile_spec(spec: mujoco.MjSpec, settings: Mapping[str, Value] | None = None) -> mujoco.MjModel:
    """Compile ``spec`` (after undoing the skip ``settings["unskip"]`` names, if any); a compile error is reported
    as one line naming the model."""
    if settings is not None:
        apply_unskip(spec, settings)
    try:
        model = spec.compile()
    except ValueError as err:
        raise ParameterError(f"model {spec.modelname!r} does not compile: {str(err).splitlines()[0]}") from None
    edit = _PLANTED.get()
    if edit is not None:
        edit(model)
    return model


@contextmanager
def planted(edit: Callable[[mujoco.MjModel], object] | None) -> Iterator[None]:
    """Within the block, every model :func:`compile_spec` compiles is passed to ``edit`` first (the gate's power
    measurement plants physics changes this way, :mod:`mjpoincare.gate.power`); None: no edit. Context-local: other
    threads and the caller's state are untouched."""
    token = _PLANTED.set(edit)
    try:
        yield
    finally:
        _PLANTED.reset(token)
