"""What a run reports beside its checks, as records: the values the commands read (``sweep``'s analytic and fitted
columns, the report's figures, the table's reported lines) are fields here, never keys of a free-form dict.

A scenario's :class:`~mjpoincare.scenarios.base.Evaluation` fills the ones it has; the result
(:class:`mjpoincare.core.result.Result`) carries them, and its JSON writes each under its own top-level key, the
scenario's free-form extras under ``extras`` (so that no extra can overwrite a field of the result).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np


def complex_values(values: Any) -> np.ndarray:
    """``(n,)`` complex array of eigenvalues given as numbers or as the JSON's ``[re, im]`` pairs."""
    return np.array([complex(*v) if isinstance(v, list | tuple) else complex(v) for v in values], dtype=complex)


@dataclass(frozen=True)
class AnalyticValues:
    """The theory's values at the run's parameters.

    Attributes:
        eigenvalues: ``(d,)`` complex: the multipliers of the linearised return map at the analytic fixed point
            (``sweep``'s analytic column, the report's crosses in the complex plane).
        values: every other analytic value worth writing (fixed point, gait, impact kind, ...), JSON-ready,
            written beside ``eigenvalues`` under the result's ``analytic`` key.
    """

    eigenvalues: Sequence[complex] | np.ndarray
    values: Mapping[str, Any] = field(default_factory=dict)

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> AnalyticValues:
        """The record of a theory's summary dict that holds ``eigenvalues`` among its values."""
        rest = {k: v for k, v in values.items() if k != "eigenvalues"}
        return cls(eigenvalues=values["eigenvalues"], values=rest)

    def to_dict(self) -> dict[str, Any]:
        """The JSON's ``analytic`` object: ``values`` and ``eigenvalues``."""
        return {**self.values, "eigenvalues": self.eigenvalues}


@dataclass(frozen=True)
class FitSummary:
    """The fitted return map (the empirical Poincaré map of the section samples).

    Attributes:
        eigenvalues: ``(d,)`` complex multipliers of the fitted map (``sweep``'s fitted column, the report's dots).
        record: the fit's whole JSON-ready record (fixed point, Jacobian, bootstrap spreads, replicates, ...), as
            :meth:`mjpoincare.analysis.returnmap.ReturnMapFit.to_dict` writes it: the result's ``fit`` key, which the
            report's figures read (``fixed_point``, ``eigenvalue_replicates``).
    """

    eigenvalues: Sequence[complex] | np.ndarray
    record: Mapping[str, Any]

    @classmethod
    def of(cls, fit: Any) -> FitSummary:
        """The summary of a fit with ``eigenvalues`` and ``to_dict()`` (a ``ReturnMapFit``)."""
        return cls(eigenvalues=np.asarray(fit.eigenvalues, dtype=complex), record=fit.to_dict())

    @classmethod
    def from_record(cls, record: Mapping[str, Any]) -> FitSummary:
        """The summary of a fit's record (its ``eigenvalues`` as numbers or ``[re, im]`` pairs)."""
        return cls(eigenvalues=complex_values(record["eigenvalues"]), record=record)

    def to_dict(self) -> dict[str, Any]:
        """The JSON's ``fit`` object (the record)."""
        return dict(self.record)


@dataclass(frozen=True)
class ReturnMapPlot:
    """The report's empirical return map: section samples x_k -> x_k+1 of one coordinate, the analytic map over their
    range, and the analytic eigenvalues of the linearised map at the fixed point.

    Attributes:
        label: the plotted section coordinate with its unit (the report's x-axis label).
        x: ``(m,)`` the coordinate at crossing k of each sample pair.
        x_next: ``(m,)`` the same coordinate at crossing k+1.
        analytic_x: ``(g,)`` grid over the samples' range on which the analytic map is drawn.
        analytic_y: ``(g,)`` the analytic map on ``analytic_x`` (NaN where the scenario has no closed form of the
            1-D map).
        analytic_eigenvalues: ``(d,)`` the analytic multipliers, shown against the fitted ones in the complex plane.
    """

    label: str
    x: np.ndarray
    x_next: np.ndarray
    analytic_x: np.ndarray
    analytic_y: np.ndarray
    analytic_eigenvalues: Sequence[complex] | np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """The JSON's ``return_map`` object, which :func:`mjpoincare.commands.report.write_report` reads (values as
        given)."""
        return {"label": self.label, "x": self.x, "x_next": self.x_next, "analytic_x": self.analytic_x,
                "analytic_y": self.analytic_y, "analytic_eigenvalues": self.analytic_eigenvalues}


@dataclass(frozen=True)
class SectionConvergence:
    """Each section coordinate's approach to the analytic fixed point (the report's panel for a map with no 1-D
    analytic form).

    Attributes:
        labels: ``(d,)`` the coordinates' names with units.
        fixed_point: ``(d,)`` the analytic fixed point x*.
        sequences: per sampled trajectory, its consecutive section samples ``(k, d)``.
    """

    labels: Sequence[str]
    fixed_point: Sequence[float] | np.ndarray
    sequences: Sequence[Any]

    def to_dict(self) -> dict[str, Any]:
        """The JSON's ``section_convergence`` object."""
        return {"labels": list(self.labels), "fixed_point": self.fixed_point, "sequences": self.sequences}


@dataclass(frozen=True)
class BasinMap:
    """Simulated end states over the analytic regions of attraction (the report's basin figure).

    Attributes:
        table: per start, a row ``{"omega0", "analytic", "simulated", "judged", ...}``.
        bands: the analytic regions ``[low, high, outcome]`` along the start's axis.
    """

    table: Sequence[Mapping[str, Any]]
    bands: Sequence[Sequence[Any]]


@dataclass(frozen=True)
class Reported:
    """A figure the check table shows and does not judge (one ``reported`` line under the table).

    Attributes:
        value: the number.
        unit: its unit ("" if none).
        note: what it is and why it is not judged.
    """

    value: float
    unit: str
    note: str

    def to_dict(self) -> dict[str, Any]:
        """The JSON's entry under ``reported``."""
        return {"value": self.value, "unit": self.unit, "note": self.note}
