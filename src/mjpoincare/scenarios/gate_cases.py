"""The gate's records: each scenario declares, as its ``gate_cases``, the validation runs the regression gate
(:mod:`mjpoincare.gate.forms`) asserts and, per check, the form it is asserted in: gated, watched (:class:`Watch`) or a
declared miss (:class:`Miss`) with its measured error, spread and mechanism."""

from __future__ import annotations

import warnings
from collections.abc import Iterable
from dataclasses import dataclass, field

from mjpoincare.core.allowance import allowance
from mjpoincare.core.params import PluginDeprecationWarning, Value


@dataclass(frozen=True)
class Miss:
    """A check the case's run misses, asserted as a strict expected miss.

    ``measured``: the error ``mjpoincare margins`` measures, one number, or (low, high) where the ensemble of
    environments gives a range; ``spread``: the largest change of that error over the ensemble (environments and
    perturbations), measured with it (the band allows :func:`mjpoincare.core.allowance.allowance` of it); ``tolerance``:
    the check's tolerance at the case's preset (quoted in the reason; tests/test_gate.py compares it with the run's);
    ``mechanism``: why MuJoCo misses, in words (the numbers behind it are in the scenario modules and the Findings of
    docs/scenarios/<scenario>.md).

    A miss whose band (the measured error widened by its allowance) would be wider than its tolerance is
    ``resolved=False``: no machine's digits pin it, so it is asserted as a miss only, its error above its tolerance and
    at most ``ceiling`` (the largest error the ensemble gives, with room for what it has not seen, stated with the
    mechanism); never as a strict expected failure, and the margins table says so.
    """

    check: str
    measured: float | tuple[float, float]
    spread: float
    tolerance: float
    mechanism: str
    resolved: bool = True
    ceiling: float | None = None

    def __post_init__(self) -> None:
        if (self.ceiling is None) == (not self.resolved):
            raise ValueError(f"{self.check}: an unresolved miss states a ceiling, a resolved one does not")

    @property
    def bounds(self) -> tuple[float, float]:
        """(low, high) of the declared error (low == high for one number)."""
        return self.measured if isinstance(self.measured, tuple) else (self.measured, self.measured)

    @property
    def band(self) -> tuple[float, float]:
        """The errors the miss accepts: the declared error widened on both sides by its allowance
        (:func:`mjpoincare.core.allowance.allowance` of its spread and tolerance); an unresolved miss's: above its
        tolerance, at most its ceiling."""
        if self.ceiling is not None:
            return self.tolerance, self.ceiling
        low, high = self.bounds
        room = allowance(self.spread, self.tolerance)
        return low - room, high + room

    def reason(self, preset: str) -> str:
        """The xfail reason: the declared error and spread against the tolerance, and the mechanism."""
        if self.ceiling is not None:
            return (f"unresolved, above {self.tolerance:g} and at most {self.ceiling:g} ({preset}; measured "
                    f"{span(*self.bounds)} ± {self.spread:.2g}): {self.mechanism}")
        return (f"measured {span(*self.bounds)} ± {self.spread:.2g} vs {self.tolerance:g} ({preset}): "
                f"{self.mechanism}")

    def matches(self, error: float) -> bool:
        """Whether ``error`` lies within the miss's band (an unresolved miss's: above the tolerance, at most the
        ceiling)."""
        low, high = self.band
        return low < error <= high if self.ceiling is not None else low <= error <= high


@dataclass(frozen=True)
class Watch:
    """A check that passes without the gate's margin: asserted to stay within its tolerance in every environment of
    the ensemble, its error's largest change there within the allowance (:func:`mjpoincare.core.allowance.allowance`)
    of ``spread`` (what ``mjpoincare margins`` measured);
    ``why``: why it sits there (what sets its error at this preset)."""

    check: str
    spread: float
    why: str


@dataclass(frozen=True)
class GateCase:
    """One validation run of the gate and what the tests assert of it.

    ``gated``: checks asserted to pass; ``misses``: checks asserted as strict expected misses; ``watched``: checks
    asserted within their tolerance. Together they name every check of the run
    (tests/test_gate.py).
    """

    scenario: str
    preset: str
    values: tuple[tuple[str, Value], ...] = ()
    gated: tuple[str, ...] = ()
    misses: tuple[Miss, ...] = field(default=())
    watched: tuple[Watch, ...] = field(default=())

    @property
    def label(self) -> str:
        """``scenario[preset,name=value,...]``, the case's test id."""
        return f"{self.scenario}[{','.join([self.preset, *(f'{k}={v}' for k, v in self.values)])}]"

    @classmethod
    def of(cls, scenario: str, preset: str, gated: tuple[str, ...] | str, misses: Iterable[Miss] = (),
           watched: Iterable[Watch] = (), **values: Value) -> GateCase:
        """The case of ``scenario`` at ``preset`` with parameter ``values``; ``gated``: the gated checks' names (a
        space-separated string of them, the old form, still works until the next release, with a
        :class:`~mjpoincare.core.params.PluginDeprecationWarning`)."""
        if isinstance(gated, str):
            warnings.warn(f"GateCase.of({scenario!r}, {preset!r}, {gated!r}): give the gated checks as a tuple of "
                          f"names, {tuple(gated.split())!r} (a space-separated string works until the next release)",
                          PluginDeprecationWarning, stacklevel=2)
            gated = tuple(gated.split())
        return cls(scenario=scenario, preset=preset, values=tuple(values.items()), gated=tuple(gated),
                   misses=tuple(misses), watched=tuple(watched))


def span(low: float, high: float) -> str:
    """A declared error as the reason and the margins table print it: ``0.0123`` or ``0.109-0.131``."""
    return f"{low:g}" if low == high else f"{low:g}-{high:g}"
