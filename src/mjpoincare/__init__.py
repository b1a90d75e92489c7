"""mjpoincare: analytic Poincare-map results of impacting systems, checked in MuJoCo.

``mjpoincare.validate(scenario, preset=None, seed=0, **values) -> Result`` is the Python API (see
:mod:`mjpoincare.api`). The names below are loaded on first use, so that ``mjpoincare.analysis`` (numpy and scipy
only) imports without MuJoCo; ``__version__`` is the installed distribution's version.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mjpoincare.core.version import VERSION as __version__

if TYPE_CHECKING:
    from mjpoincare.api import validate
    from mjpoincare.core.params import ParameterError
    from mjpoincare.core.result import Result

_LAZY = {"validate": "mjpoincare.api", "Result": "mjpoincare.core.result", "ParameterError": "mjpoincare.core.params"}
__all__ = ["ParameterError", "Result", "__version__", "validate"]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'mjpoincare' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
