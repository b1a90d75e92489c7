"""``mjpoincare list --ranges``: each numeric parameter's range that a run accepts with the others at their defaults.

A parameter's declared bounds (:class:`~mjpoincare.core.params.Param`) are what the value may be at all; a scenario's
own checks (``check_params`` and ``check_params_with_settings``: a gait must exist, be stable, keep its foot
down, ...) refuse
more, and what they refuse depends on the other parameters. This finds, by bisection between the default (accepted)
and each declared bound, where the refusal starts when only that parameter moves: the accepted interval around the
default, each end to :data:`RELATIVE` of its magnitude. It assumes the accepted values around the default form an
interval (a refusal inside it would not be found).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mjpoincare.commands.validation import resolve_values
from mjpoincare.core.params import Param, ParameterError

#: Bisection stops when the bracket is this fraction of the edge's magnitude.
RELATIVE = 1e-3
#: At most this many evaluations of the scenario's checks per side.
MAX_STEPS = 40


@dataclass(frozen=True)
class AcceptedRange:
    """Where a numeric parameter is accepted with the others at their defaults: ``low`` to ``high``, each the
    declared bound when the checks refuse nothing on that side, else the last accepted value the bisection found;
    ``why_low`` / ``why_high``: the refusal just past that end (empty when it is the declared bound)."""

    low: float
    high: float
    why_low: str
    why_high: str

    def text(self, param: Param) -> str:
        """``accepted at the defaults: [0.0682, 0.2621]`` (an end the checks set in square brackets), or empty when
        the declared bounds are the range."""
        if not (self.why_low or self.why_high):
            return ""
        low = "[" + _number(self.low) if self.why_low else ("(" if param.low_open else "[") + _number(self.low)
        high = _number(self.high) + "]" if self.why_high else _number(self.high) + (")" if param.high_open else "]")
        return f"accepted at the defaults: {low}, {high}"


def _number(x: float) -> str:
    return f"{x:.4g}"


def _refusal(name: str, param: Param, value: float) -> str:
    """Empty when ``name`` accepts ``param = value`` (the others at their defaults), else the refusal's line."""
    text = str(int(value)) if param.kind is int else repr(float(value))
    try:
        resolve_values(name, {param.name: text}, None)
    except ParameterError as err:
        return str(err)
    return ""


def _inside(param: Param, bound: float, default: float) -> float:
    """The declared bound, or a point just inside it (1e-6 of the way to the default) when it is excluded."""
    open_end = param.low_open if bound < default else param.high_open
    return bound + (default - bound) * 1e-6 if open_end and param.kind is not int else bound


def _edge(name: str, param: Param, default: float, bound: float) -> tuple[float, str]:
    """The last accepted value from ``default`` toward ``bound``, and the refusal past it ("" when none)."""
    if math.isinf(bound):
        return bound, ""
    end = _inside(param, bound, default)
    why = _refusal(name, param, end)
    if not why:
        return bound, ""
    good, bad = default, end
    geometric = good * bad > 0 and max(abs(good), abs(bad)) / min(abs(good), abs(bad)) > 10
    for _ in range(MAX_STEPS):
        if param.kind is int and abs(bad - good) <= 1:
            break
        if param.kind is not int and abs(bad - good) <= RELATIVE * max(abs(good), abs(bad)):
            break
        mid = math.copysign(math.sqrt(good * bad), good) if geometric else (good + bad) / 2
        if param.kind is int:
            mid = float(round(mid)) if round(mid) not in (good, bad) else float(int((good + bad) / 2))
        refusal = _refusal(name, param, mid)
        if refusal:
            bad, why = mid, refusal
        else:
            good = mid
    return good, why


def accepted_range(name: str, param: Param) -> AcceptedRange | None:
    """The accepted interval of numeric ``param`` of scenario ``name`` around its default (None for a parameter that
    is not a number, or whose default is refused)."""
    if param.kind not in (int, float) or isinstance(param.default, bool) or _refusal(name, param, param.default):
        return None
    default = float(param.default)
    low, why_low = _edge(name, param, default, -math.inf if param.low is None else float(param.low))
    high, why_high = _edge(name, param, default, math.inf if param.high is None else float(param.high))
    return AcceptedRange(low=low, high=high, why_low=why_low, why_high=why_high)
