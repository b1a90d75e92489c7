"""The papers' results a scenario covers (its ``paper_results``), and how MuJoCo is run for each.

A :class:`PaperResult` is one quantitative result of a paper of ``docs/references.md`` (a fixed point, a multiplier,
a bound, a gait boundary, a table row, a curve of a figure, a number stated in the text): where the paper states it,
the value it prints, the suite's own derivation and its independent exact check, and one of the MuJoCo runs below.
``mjpoincare reproduce`` runs them (:mod:`mjpoincare.commands.reproduce`); ``docs/results/papers/`` is generated from
its JSON.

The runs:

- :class:`AtValidation`: the scenario's validation at some parameters, read by a :data:`Reader` (one of its checks, or
  a quantity of its fitted map); results that share the parameters share the run.
- :class:`Experiment`: a dedicated MuJoCo experiment (a transient, a count, a window of starts) that the validation
  does not run.
- :class:`Curve`: a figure's curve over a parameter, one MuJoCo point per value, beside the theory's curve.
- :class:`Bracket`: a bifurcation or a bound located in MuJoCo by bisection on a parameter.
- :class:`Refusal`: not runnable in MuJoCo, with the physical reason.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import mujoco
import numpy as np

from mjpoincare.core.params import Values
from mjpoincare.core.result import Result

PAPERS = ("000", "001", "002", "003")


@dataclass(frozen=True)
class Reading:
    """One MuJoCo value of a result beside the suite's analytic value.

    Attributes:
        analytic: the suite's value (a number; or a list where the result is a vector or a set of multipliers).
        mujoco: MuJoCo's value, in the same form.
        error: the distance between them, in the measure ``kind`` names.
        tolerance: the bound on ``error`` for a pass, in the same measure.
        kind: how ``error`` is measured (``abs``, ``rel``, ``max-abs``, ``category``, ...).
        spread: MuJoCo's value's uncertainty (the bootstrap's or the ensemble's half-width; NaN: not measured), the
            error bar of a figure's point.
        detail: one line on how the value was read (samples, starts, impacts).
    """

    analytic: Any
    mujoco: Any
    error: float
    tolerance: float
    kind: str = "abs"
    spread: float = math.nan
    detail: str = ""

    @property
    def passed(self) -> bool:
        """Whether the error is finite and within the tolerance."""
        return math.isfinite(self.error) and self.error <= self.tolerance


class Runner(Protocol):
    """What a result's MuJoCo run may ask of the command that runs it (:mod:`mjpoincare.commands.reproduce` passes one
    in): the preset, the scenario's validation at some parameters, its resolved inputs, its model and its tolerances.
    A scenario's runs reach the validation, the registry and their own package's ``Scenario`` through it, never by
    importing them (layers above, or the package that imports them)."""

    preset: str

    def validate(self, assignments: Mapping[str, str]) -> Result:
        """The scenario's validation at ``--set``-style ``assignments`` and this preset."""
        ...

    def inputs(self, assignments: Mapping[str, str], *, checked: bool = True) -> tuple[Values, Values]:
        """The scenario's parameters (its defaults updated by ``assignments``) and this preset's simulator settings;
        ``checked=False`` skips the scenario's own cross-checks of the parameters (a run outside the theory's range,
        e.g. a slope where no gait exists)."""
        ...

    def build(self, params: Values, settings: Values) -> mujoco.MjModel:
        """The scenario's model at resolved inputs (its ``build``)."""
        ...

    def tolerance(self, check: str, mode: str | None = None) -> float:
        """The scenario's tolerance of ``check`` at this preset (``mode``: the table of a scenario with one per
        mode)."""
        ...


#: ``(result) -> Reading``: reads one result off a validation's :class:`~mjpoincare.core.result.Result`.
Reader = Callable[["Result"], Reading]


def check_reader(name: str) -> Reader:
    """A reader of the validation's check ``name``: its analytic and simulated values, error and tolerance (a check
    the run does not report reads as missing, error NaN)."""
    return _CheckReader(name)


@dataclass(frozen=True)
class _CheckReader:
    name: str

    def __call__(self, result: Result) -> Reading:
        for check in result.checks:
            if check.name == self.name:
                return Reading(analytic=check.analytic, mujoco=check.simulated, error=float(check.error),
                               tolerance=float(check.tolerance), kind=check.kind, detail=f"check {self.name}")
        return Reading(analytic=None, mujoco=None, error=math.nan, tolerance=math.nan, kind="missing",
                       detail=f"the run reports no check {self.name}")


def largest_multiplier_reader(tolerance_of: str) -> Reader:
    """A reader of the fitted map's largest multiplier modulus abs(lambda)max against the theory's, with the bootstrap's
    spread of it (half the 5-95 % range of the replicates' abs(lambda)max), held to the tolerance the run's check
    ``tolerance_of`` holds at its preset (NaN where the run does not report it)."""
    return _LargestMultiplier(tolerance_of)


@dataclass(frozen=True)
class _LargestMultiplier:
    tolerance_of: str

    def __call__(self, result: Result) -> Reading:
        tol = next((float(c.tolerance) for c in result.checks if c.name == self.tolerance_of), math.nan)
        if result.fit is None or result.analytic is None or result.analytic.eigenvalues is None:
            return Reading(analytic=None, mujoco=None, error=math.nan, tolerance=tol, detail="the run fits no map")
        analytic = float(np.max(np.abs(np.asarray(result.analytic.eigenvalues, complex))))
        fitted = float(np.max(np.abs(np.asarray(result.fit.eigenvalues, complex))))
        return Reading(analytic=analytic, mujoco=fitted, error=abs(fitted - analytic), tolerance=tol,
                       spread=replicate_spread(result.fit.record), detail="abs(lambda)max of the fitted map; spread: "
                       "half the 5-95 % range of its bootstrap replicates")


def replicate_spread(record: Mapping[str, Any]) -> float:
    """Half the 5-95 % range of abs(lambda)max over a fit record's bootstrap replicates (NaN: none recorded)."""
    reps = record.get("eigenvalue_replicates")
    if not reps:
        return math.nan
    mods = []
    for rep in reps:
        values = np.asarray([complex(*v) if isinstance(v, (list, tuple)) else complex(v) for v in rep])
        mods.append(float(np.max(np.abs(values))))
    lo, hi = np.percentile(mods, [5, 95])
    return float(hi - lo) / 2


@dataclass(frozen=True)
class AtValidation:
    """MuJoCo's value is read off the scenario's validation at ``assignments`` (on top of its defaults).

    Attributes:
        read: the :data:`Reader` (:func:`check_reader`, :func:`largest_multiplier_reader`, or the scenario's own).
        assignments: ``--set``-style parameter values.
    """

    read: Reader
    assignments: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class Experiment:
    """A dedicated MuJoCo experiment: ``run(runner) -> Reading`` (a module-level function of the scenario's package,
    so that worker processes can run it; :class:`Runner`)."""

    run: Callable[[Runner], Reading]


@dataclass(frozen=True)
class Curve:
    """A figure's curve: the theory's curve and one MuJoCo point (with its spread) per value of a parameter.

    Attributes:
        x: the values at which MuJoCo is run, in the paper's units (at least 8).
        point: ``(x, runner) -> Reading``: MuJoCo's point at ``x`` beside the theory's value there (module level;
            :class:`Runner`).
        theory: ``(xs, runner) -> ys``: the theory's curve on a dense grid of the paper's x axis (the runner gives the
            scenario's parameters: ``runner.inputs({}, checked=False)``).
        x_label: the paper's x axis, with its unit.
        y_label: the paper's y axis, with its unit.
        lines: horizontal reference lines of the figure (e.g. abs(lambda) = 1), by label.
        dense: the theory curve's points (fewer where each costs a shooting solve).
    """

    x: tuple[float, ...]
    point: Callable[[float, Runner], Reading]
    theory: Callable[[np.ndarray, Runner], np.ndarray]
    x_label: str
    y_label: str
    lines: Mapping[str, float] = field(default_factory=dict)
    dense: int = 200

    def __post_init__(self) -> None:
        if len(self.x) < 8:
            raise ValueError(f"a figure's curve needs at least 8 MuJoCo points (got {len(self.x)})")


@dataclass(frozen=True)
class Bracket:
    """A bifurcation or bound located in MuJoCo by bisection on one parameter.

    Attributes:
        low: a value on the ``below`` side.
        high: a value on the other side.
        below: ``(value, runner) -> bool``: whether MuJoCo's run at ``value`` is on ``low``'s side (module level;
            :class:`Runner`).
        theory: the theory's location (``(runner) -> value``).
        tolerance: the bound on abs(located - theory) for a pass; also where the bisection stops (a quarter of it).
        unit: the parameter's unit.
    """

    low: float
    high: float
    below: Callable[[float, Runner], bool]
    theory: Callable[[Runner], float]
    tolerance: float
    unit: str = ""


@dataclass(frozen=True)
class Refusal:
    """Not runnable in MuJoCo: ``reason`` is physical and measured (a gait that lifts off, a region with no motion to
    sample, a state MuJoCo's soft contact cannot hold)."""

    reason: str


Run = AtValidation | Experiment | Curve | Bracket | Refusal


@dataclass(frozen=True)
class PaperResult:
    """One result of a paper, declared by the scenario that covers it.

    Attributes:
        id: unique over all scenarios, starting with the paper's short name (``002-alpha-min``).
        paper: the short name in ``docs/references.md`` (``000`` to ``003``).
        location: where the paper states it (equation, table, figure, section), as printed.
        quantity: what it is, in the paper's terms, with its unit.
        paper_value: the value the paper prints (text, as printed: "0.71", "1.4 deg"; "" where it prints none).
        independent: the suite's independent exact computation that checks its analytic value (an event-driven
            solve_ivp, a closed form against a shooting method), with the test that pins it.
        run: how MuJoCo is run for it (:data:`Run`).
        presets: the presets ``mjpoincare reproduce`` runs it at (a figure or a bracket: the fast one).
        miss: a declared miss: the measured mechanism by which MuJoCo misses it ("" where it is expected to pass).
        disagreement: where the suite's value differs from the paper's printed one: what decides (the independent
            exact computation), and which value MuJoCo is checked against and why.
        why: why the tolerance is what it is (the measured error and spread it holds with margin, and the nearest
            wrong physics it rejects); "" for a check's reader, whose check states it.
        gate: the regression gate asserts its verdict at the fast preset (a number the paper states at the scenario's
            default parameters, cheap to run).
    """

    id: str
    paper: str
    location: str
    quantity: str
    paper_value: str
    independent: str
    run: Run
    presets: tuple[str, ...] = ("fast", "accurate")
    miss: str = ""
    disagreement: str = ""
    why: str = ""
    gate: bool = False

    def __post_init__(self) -> None:
        if self.paper not in PAPERS or not self.id.startswith(f"{self.paper}-"):
            raise ValueError(f"paper result {self.id!r}: its id starts with its paper ({', '.join(PAPERS)})")
        if isinstance(self.run, (Curve, Bracket)) and self.presets != ("fast",):
            raise ValueError(f"paper result {self.id!r}: a figure or a bracket runs at the fast preset only")

    @property
    def kind(self) -> str:
        """``point``, ``experiment``, ``figure``, ``bracket`` or ``refused``."""
        return {AtValidation: "point", Experiment: "experiment", Curve: "figure", Bracket: "bracket",
                Refusal: "refused"}[type(self.run)]


def verdict(reading: Reading | None, result: PaperResult) -> str:
    """``pass``, ``miss`` (failing, and declared a miss with its mechanism), ``FAIL``, or ``refused``."""
    if reading is None:
        return "refused"
    if reading.passed:
        return "pass"
    return "miss" if result.miss else "FAIL"


def bisect(below: Callable[[float], bool], low: float, high: float, tolerance: float) -> tuple[float, float, int]:
    """Shrink ``[low, high]`` (``below(low)``, not ``below(high)``) to a width of at most ``tolerance``.

    Returns:
        The bracket's ends and the runs it took.

    Raises:
        ValueError: the ends are not on the two sides.
    """
    runs = 2
    if not below(low) or below(high):
        raise ValueError(f"[{low:g}, {high:g}] does not bracket the crossing")
    while abs(high - low) > tolerance:
        mid = (low + high) / 2
        runs += 1
        if below(mid):
            low = mid
        else:
            high = mid
    return low, high, runs


def unique_ids(results: Sequence[PaperResult]) -> None:
    """Refuse two results with one id."""
    seen: set[str] = set()
    for r in results:
        if r.id in seen:
            raise ValueError(f"paper result id {r.id!r} is declared twice")
        seen.add(r.id)
