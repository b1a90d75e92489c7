"""Analytic vs simulated values turned into verdicts with stated tolerances (numpy only)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class Check:
    """One comparison. ``error`` is relative (``|sim - ref| / |ref|``) or absolute, as ``kind`` says.

    ``passed`` is False when the simulated value is missing or not finite: a diverged run never
    passes silently. ``why`` states where the tolerance comes from.
    """

    name: str
    analytic: Any
    simulated: Any
    error: float
    tolerance: float
    kind: str
    unit: str
    why: str

    @property
    def passed(self) -> bool:
        """Whether the error is finite and within the tolerance."""
        return math.isfinite(self.error) and self.error <= self.tolerance

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict: complex numbers as ``[re, im]`` (``complex`` says the values are complex, so that a
        reader tells an eigenvalue ``[re, im]`` from a vector of two reals), non-finite numbers as ``None``."""
        complex_ = is_complex(self.analytic) or is_complex(self.simulated)
        return {
            "name": self.name,
            "analytic": _json_value(self.analytic, complex_),
            "simulated": _json_value(self.simulated, complex_),
            "complex": complex_,
            "error": jsonable(self.error),
            "error_kind": self.kind,
            "tolerance": self.tolerance,
            "unit": self.unit,
            "passed": self.passed,
            "why": self.why,
        }


def _json_value(value: Any, complex_: bool) -> Any:
    """A check's value for its JSON: where either of the check's values is complex, both are written as ``[re, im]``
    (a real one with im 0), so that a reader meets one shape per check."""
    if not complex_ or value is None or isinstance(value, str):
        return jsonable(value)
    try:
        array = np.asarray(value, dtype=complex)
    except (TypeError, ValueError):  # not numeric (a category): as it is
        return jsonable(value)
    return jsonable(complex(array) if array.ndim == 0 else array)


def is_complex(value: Any) -> bool:
    """Whether ``value`` (a number, an array or a nested list) holds complex numbers."""
    if isinstance(value, str):
        return False
    if isinstance(value, list | tuple):
        return any(is_complex(v) for v in value)
    return bool(np.iscomplexobj(value))


def jsonable(value: Any) -> Any:
    """Numbers, arrays and complex values as JSON types (complex -> ``[re, im]``, NaN -> None)."""
    if isinstance(value, np.ndarray):
        return [jsonable(v) for v in value.tolist()]
    if isinstance(value, list | tuple):
        return [jsonable(v) for v in value]
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, complex | np.complexfloating):
        return [jsonable(float(value.real)), jsonable(float(value.imag))]
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        return float(value) if math.isfinite(value) else None
    return value


def relative(name: str, analytic: float, simulated: float, tolerance: float, unit: str, why: str) -> Check:
    """A check on the relative error ``|simulated - analytic| / |analytic|``."""
    error = abs(simulated - analytic) / abs(analytic) if math.isfinite(simulated) else math.nan
    return Check(name=name, analytic=analytic, simulated=simulated, error=error, tolerance=tolerance, kind="relative",
                 unit=unit, why=why)


def absolute(name: str, analytic: complex | float, simulated: complex | float, tolerance: float,
             unit: str, why: str) -> Check:
    """A check on the absolute error ``|simulated - analytic|`` (complex values: modulus of the difference)."""
    error = abs(simulated - analytic) if np.isfinite(simulated) else math.nan
    return Check(name=name, analytic=analytic, simulated=simulated, error=float(error), tolerance=tolerance,
                 kind="absolute", unit=unit, why=why)


def fraction(name: str, agree: int, total: int, tolerance: float, why: str) -> Check:
    """A check on the fraction of cases that disagree (analytic 0 disagreements)."""
    error = (total - agree) / total if total else math.nan
    return Check(name=name, analytic=0.0, simulated=(total - agree) / total if total else math.nan, error=error,
                 tolerance=tolerance, kind="fraction", unit="", why=why)


def categorical(name: str, analytic: str, simulated: str, wrong: int, total: int, why: str) -> Check:
    """A check on categories: the analytic and the simulated category (``"none"`` if empty), error = the fraction
    ``wrong / total`` of cases whose category differs."""
    return Check(name=name, analytic=analytic, simulated=simulated or "none",
                 error=wrong / total if total else math.nan, tolerance=0.0, kind="fraction", unit="", why=why)


def most_common(items: Sequence[str]) -> str:
    """The most frequent of ``items`` ("" if none)."""
    return max(set(items), key=list(items).count) if items else ""
