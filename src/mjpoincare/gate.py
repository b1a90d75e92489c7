"""The regression gate: which checks the test suite asserts, on which runs, in which form, and the smallest change
each form can see.

A MuJoCo result differs between machines, library builds, thread counts and seeds at the 1e-4 level (the impact
onset jitters on the step grid and amplifies rounding). Every check of every gate run is asserted in one of three
forms:

- **gated**: its error plus its spread under :data:`PERTURBATIONS` stays within half its tolerance (:data:`MARGIN`);
  asserted to pass.
- **watched** (:class:`Watch`): it passes, but its error plus its spread lies between half its tolerance and its
  tolerance; asserted to stay within its tolerance plus its measured spread.
- **declared miss** (:class:`Miss`): it misses, by an error declared with its measured spread and its mechanism; a
  strict expected miss whose band, the declared error widened by the spread on both sides, is never wider than the
  check's tolerance. Where the spread itself exceeds half the tolerance (a fit that rounding-sized changes of the
  starts move by more than that), no such band exists: the miss is declared **unresolved** and asserted in its band
  only, and the margins table says so; the gate cannot see a change of that check smaller than its band.

``mjpoincare margins`` measures the spread and prints, per check, its form, its margin, whether it holds there and
its **resolution**: the smallest change of its error the gate can tell from jitter (a gated or watched check's
spread, a declared miss's band), so that a change below it is known to be invisible. Tolerances are the scenarios'
own; nothing here changes them.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from functools import cache

from mjpoincare import scenarios
from mjpoincare.analysis.tables import text_table
from mjpoincare.params import Value
from mjpoincare.result import Result
from mjpoincare.scenarios.gate_cases import GateCase, span
from mjpoincare.validation import run_validation

#: A gated check's error plus its spread must stay within this fraction of its tolerance.
MARGIN = 0.5
#: Perturbations that must not change a verdict: (label, seed, extra settings).
PERTURBATIONS: tuple[tuple[str, int, Mapping[str, Value]], ...] = (
    ("seed 1", 1, {}),
    ("threads 1", 0, {"threads": 1}),
    ("starts x(1+1e-12)", 0, {"start_perturbation": 1e-12}),
    ("starts x(1+1e-9)", 0, {"start_perturbation": 1e-9}),
)


@cache
def _validate(scenario: str, preset: str, seed: int, values: tuple[tuple[str, Value], ...]) -> Result:
    return run_validation(scenario, dict(values), preset, seed)


def run_case(case: GateCase, seed: int = 0, **extra: Value) -> Result:
    """The case's validation, with ``seed`` and ``extra`` settings (cached per process: tests of one run share it)."""
    return _validate(case.scenario, case.preset, seed, tuple(sorted({**dict(case.values), **extra}.items())))


def cases() -> tuple[GateCase, ...]:
    """Every registered scenario's gate cases, scenario by scenario (the registry's order)."""
    return tuple(c for scenario in scenarios.REGISTRY.values() for c in scenario.gate_cases)


def case(label: str) -> GateCase:
    """The gate case with this label (e.g. ``rimless-wheel[fast]``)."""
    found = next((c for c in cases() if c.label == label), None)
    if found is None:
        raise KeyError(f"no gate case {label!r}; cases: {', '.join(c.label for c in cases())}")
    return found


def margin_rows(cases: Iterable[GateCase], compare: Mapping[tuple[str, str], float] | None = None, *,
                perturb: bool = True) -> list[dict[str, object]]:
    """For every check of every case: error, spread (largest change of the error under :data:`PERTURBATIONS` unless
    not ``perturb``, and against ``compare``'s errors from another environment, keyed by (case label, check)),
    tolerance, the ratio (error + spread) / tolerance, the check's form in the gate, whether it holds there (a gated
    check within :data:`MARGIN`; a watched check passing; a declared miss missing under every perturbation, with its
    error in its band), its resolution (a gated or watched check's spread, a miss's band width), and a declared
    miss's error (``declared``: [low, high]) and xfail reason (``miss``)."""
    rows: list[dict[str, object]] = []
    for case in cases:
        base = run_case(case)
        variants = [run_case(case, seed, **extra) for _, seed, extra in PERTURBATIONS] if perturb else []
        misses = {m.check: m for m in case.misses}
        watched = {w.check: w for w in case.watched}
        for check in base.checks:
            others = [next((c.error for c in v.checks if c.name == check.name), math.nan) for v in variants]
            if compare and (case.label, check.name) in compare:
                others.append(compare[(case.label, check.name)])
            spread = max((abs(e - check.error) if math.isfinite(e) and math.isfinite(check.error) else math.inf
                          for e in others), default=0.0)
            ratio = ((check.error + spread) / check.tolerance if check.tolerance > 0
                     else (0.0 if check.error + spread == 0 else math.inf))
            miss = misses.get(check.name)
            status = ("gated" if check.name in case.gated else "declared miss" if miss is not None
                      else "watched" if check.name in watched else "not in the gate")
            if status == "gated":
                holds, resolution = ratio <= MARGIN, spread
            elif miss is not None:
                low, high = miss.band
                missing = not check.passed and not any(math.isfinite(e) and e <= check.tolerance for e in others)
                holds = miss.matches(check.error) and (missing or not miss.resolved)
                resolution = high - low
                status = status if miss.resolved else "declared miss, unresolved"
            else:
                holds, resolution = check.passed and status == "watched", spread
            rows.append({"case": case.label, "check": check.name, "error": check.error, "spread": spread,
                         "tolerance": check.tolerance, "ratio": ratio, "status": status, "holds": holds,
                         "resolution": resolution, "declared": list(miss.bounds) if miss else None,
                         "miss": miss.reason(case.preset) if miss else ""})
    return rows


def margin_table(rows: list[dict[str, object]]) -> str:
    """The margin table a person reads (``declared``: a declared miss's error, to compare with ``error``;
    ``resolution``: the smallest change of the error the gate tells from jitter; ``NOT HELD``: a gated check without
    the margin, a watched check that fails, a declared miss that passes or has left its band, or a check the gate does
    not name)."""
    head = ("case", "check", "error", "declared", "spread", "tolerance", "(err+spread)/tol", "resolution", "form", "")
    body = [(str(r["case"]), str(r["check"]), f"{r['error']:.3g}",
             span(*r["declared"]) if isinstance(r["declared"], list) else "", f"{r['spread']:.2g}",
             f"{r['tolerance']:.3g}", f"{r['ratio']:.2f}", f"{r['resolution']:.2g}", str(r["status"]),
             "" if r["holds"] else "NOT HELD")
            for r in rows]
    return text_table(head, body)
