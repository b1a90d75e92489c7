"""Declared, validated parameters: one record per name, with its type, default and bounds.

Every scenario parameter and every simulator setting is a :class:`Param`. The CLI's
``--set name=value`` text, presets and Python callers all go through :meth:`Param.coerce`,
so a bad value is refused in one place with one line naming the parameter and its range.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy

Value = float | int | str
#: Resolved parameters or settings by name.
Values = Mapping[str, Value]


class ParameterError(ValueError):
    """An invalid parameter: the message is one line naming the parameter and the allowed range."""


@dataclass(frozen=True)
class Param:
    """One named parameter with its default, type and allowed range.

    ``low``/``high`` bound numbers (``low_open``/``high_open`` make the bound strict);
    ``choices`` restricts strings.
    """

    name: str
    default: Value
    doc: str
    kind: type = float
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple[str, ...] | None = None

    def range_text(self) -> str:
        """The allowed range in words, e.g. ``in (0, 1.571)`` or ``one of euler, rk4``."""
        if self.choices is not None:
            return "one of " + ", ".join(self.choices)
        if self.low is not None and self.high is not None:
            left = "(" if self.low_open else "["
            right = ")" if self.high_open else "]"
            return f"in {left}{self.low:g}, {self.high:g}{right}"
        if self.low is not None:
            return f"{'>' if self.low_open else '>='} {self.low:g}"
        if self.high is not None:
            return f"{'<' if self.high_open else '<='} {self.high:g}"
        return "any " + self.kind.__name__

    def coerce(self, value: Any) -> Value:
        """Convert ``value`` (text or number) to this parameter's type and check its range."""
        if self.kind is str:
            text = str(value).strip()
            if self.choices is not None and text not in self.choices:
                hint = "; values are case-sensitive" if text.lower() in self.choices else ""
                raise ParameterError(f"{self.name} must be {self.range_text()} (got {value!r}{hint})")
            return text
        if isinstance(value, bool):
            raise ParameterError(f"{self.name} must be a number {self.range_text()} (got {value!r})")
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ParameterError(
                f"{self.name} must be a number {self.range_text()} (got {value!r})"
            ) from None
        if not math.isfinite(number):
            raise ParameterError(f"{self.name} must be a finite number {self.range_text()} (got {value!r})")
        if self.kind is int:
            if number != int(number):
                raise ParameterError(f"{self.name} must be an integer {self.range_text()} (got {value!r})")
            number = int(number)
        if not self._inside(number):
            unit = f" {self.unit}" if self.unit else ""
            hint = ""
            if self.unit == "rad" and self._inside(math.radians(number)):
                hint = f"; if that was degrees, {number:g} deg = {math.radians(number):.6g} rad"
            raise ParameterError(f"{self.name} must be {self.range_text()}{unit} (got {value}{hint})")
        return number

    def _inside(self, number: float) -> bool:
        too_low = self.low is not None and (number <= self.low if self.low_open else number < self.low)
        too_high = self.high is not None and (number >= self.high if self.high_open else number > self.high)
        return not (too_low or too_high)

    @property
    def unit(self) -> str:
        """The unit the description names after its last comma (``"slope gamma, rad"`` -> ``rad``; "" for none)."""
        found = _UNIT.search(self.doc)
        return found.group(1).strip() if found else ""


#: A unit at the end of a parameter's description, after a comma and before any parenthesis.
_UNIT = re.compile(r",\s*((?:rad|deg|m|kg|s|N m|m/s\^2|m/s|rad/s|1/s|J)(?:\s*[a-z]*)?)\s*(?:\(.*)?$")


def parse_assignments(items: Iterable[str]) -> dict[str, str]:
    """Parse CLI ``name=value`` strings into a dict; a name given twice is refused (which value was meant is not
    guessed)."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise ParameterError(f"--set expects name=value (got {item!r})")
        if name.strip() in out:
            raise ParameterError(f"--set {name.strip()} is given twice ({out[name.strip()]!r} and {value.strip()!r}); "
                                 "give it once")
        out[name.strip()] = value.strip()
    return out


def typed(declared: Sequence[Param], values: Mapping[str, Any]) -> None:
    """Refuse text where ``declared`` expects a number, for Python callers (the command line's ``--set`` is text and
    goes through :func:`parse_assignments`): ``spokes="8"`` raises, ``spokes=8`` passes."""
    by_name = {p.name: p for p in declared}
    for name, value in values.items():
        param = by_name.get(name)
        if param is not None and param.kind is not str and isinstance(value, str):
            raise ParameterError(f"{name} must be a number {param.range_text()}, not text (got {value!r}; text is "
                                 "for the command line's --set)")


def resolve(
    declared: Sequence[Param], base: Mapping[str, Value], overrides: Mapping[str, Any]
) -> dict[str, Value]:
    """Values for ``declared``: ``base`` (defaults or a preset) updated by ``overrides``, all checked.

    Names in ``overrides`` that are not declared are left for the caller (see :func:`unknown`).
    """
    by_name = {p.name: p for p in declared}
    values = {name: by_name[name].coerce(value) for name, value in base.items()}
    for name, value in overrides.items():
        if name in by_name:
            values[name] = by_name[name].coerce(value)
    return values


def did_you_mean(word: str, known: Iterable[str], renamed: Mapping[str, str] | None = None) -> str:
    """``; did you mean 'x'?`` naming the closest of ``known`` to ``word`` (difflib's ratio at least 0.6), or
    nothing: the hint every refusal of an unknown name carries. ``renamed``: old names -> their new ones, among the
    candidates too, a close old name suggesting its new one."""
    renamed = renamed or {}
    close = difflib.get_close_matches(word, [*known, *renamed], n=1, cutoff=0.6)
    return f"; did you mean {renamed.get(close[0], close[0])!r}?" if close else ""


class PluginDeprecationWarning(DeprecationWarning):
    """A plugin's declaration uses an old form of the plugin API (a field's old name, a gate case's checks as one
    string), which still works until the next release: the warning names the new form."""


def unknown(names: Iterable[str], *declared: Sequence[Param]) -> None:
    """Raise :class:`ParameterError` for the first name not declared in any of ``declared``."""
    known = sorted({p.name for group in declared for p in group})
    for name in names:
        if name not in known:
            raise ParameterError(f"unknown parameter {name!r}{did_you_mean(name, known)} (known: {', '.join(known)})")


def _span(start: str, stop: str, count: str) -> list[str]:
    """``count`` evenly spaced values from ``start`` to ``stop`` (both included), each as text of 10 significant
    digits (ValueError for text that is not a finite number or a count)."""
    ends = float(start), float(stop)
    if not all(map(math.isfinite, ends)):
        raise ValueError(f"not finite: {start}:{stop}")
    return [f"{v:.10g}" for v in numpy.linspace(*ends, int(count))]


#: The most values a ``--values`` list or range may give: one sweep point per value, each a whole validation, so
#: more is a typo (a COUNT with a zero too many), refused before any simulation.
MAX_VALUES = 1000


def parse_values(text: str) -> list[str]:
    """``0.07,0.072,0.074`` or ``0.07:0.076:4`` (start:stop:count) -> value strings: at least one, at most
    :data:`MAX_VALUES`, none twice (ParameterError, one line, otherwise)."""
    if text.count(":") == 2:
        count = text.split(":")[2].strip()
        if count.isdigit() and int(count) > MAX_VALUES:
            raise ParameterError(f"--values START:STOP:COUNT needs COUNT <= {MAX_VALUES} (got {count})")
        try:
            values = _span(*text.split(":"))
        except ValueError:
            raise ParameterError(f"--values START:STOP:COUNT expects numbers (got {text!r})") from None
        if not values:
            raise ParameterError(f"--values START:STOP:COUNT needs COUNT >= 1 (got {text!r})")
    else:
        values = [v.strip() for v in text.split(",") if v.strip()]
        if not values:
            raise ParameterError("--values needs at least one value")
        if len(values) > MAX_VALUES:
            raise ParameterError(f"--values gives {len(values)} values, more than {MAX_VALUES}")
    twice = sorted({v for v in values if values.count(v) > 1})
    if twice:
        raise ParameterError(f"--values gives {', '.join(twice)} more than once")
    return values


def grid_syntax(axes: Sequence[Param]) -> str:
    """The ``--grid`` syntax over ``axes``, e.g. ``x=START:STOP:N,y=START:STOP:N``."""
    return ",".join(f"{axis.name}=START:STOP:N" for axis in axes)


def parse_grid(text: str, axes: Sequence[Param]) -> dict[str, numpy.ndarray]:
    """A region map's ``--grid``: the values along each of its axes.

    Args:
        text: every axis once, comma-separated, as ``NAME=START:STOP:N`` (:func:`grid_syntax`), e.g.
            ``x=-1.5:0.5:30,y=0.05:1:30``: N >= 2 values from START to STOP, both included, each rounded to 10
            significant digits as a ``--values`` range is.
        axes: the map's axes, each a :class:`Param` naming the axis, what it is (``doc``) and its bounds.

    Returns:
        Axis name -> its values, shape (N,), in the order of ``axes``.

    Raises:
        ParameterError: one line, on axes other than ``axes``, on a range that is not START:STOP:N with N >= 2
            (naming the axis), and on a value outside its axis's bounds (naming the axis and the bound).
    """
    specs = {}
    for part in text.split(","):
        name, _, spec = part.partition("=")
        specs[name.strip()] = spec.strip()
    if set(specs) != {axis.name for axis in axes}:
        raise ParameterError(f"--grid expects {grid_syntax(axes)} with N >= 2 (got {text!r})")
    grid = {}
    for axis in axes:
        spec = specs[axis.name]
        try:
            values = numpy.array([float(v) for v in _span(*spec.split(":"))])
        except (TypeError, ValueError):  # TypeError: not three fields
            values = numpy.zeros(0)
        if values.size < 2:
            raise ParameterError(f"--grid {axis.name} expects START:STOP:N with numbers START, STOP and an integer "
                                 f"N >= 2 (got {axis.name}={spec})")
        for value in values:
            try:
                axis.coerce(float(value))
            except ParameterError:
                raise ParameterError(f"--grid {axis.name} = {axis.doc} must be {axis.range_text()} "
                                     f"(got {value:g})") from None
        grid[axis.name] = values
    return grid
