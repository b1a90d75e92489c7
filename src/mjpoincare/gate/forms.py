"""The regression gate: which checks the test suite asserts, on which runs, in which form, and the smallest change
each form can see.

A MuJoCo result differs between machines, library builds, thread counts and seeds at the 1e-4 level (the impact
onset jitters on the step grid and amplifies rounding). Every check of every gate run is asserted in one of three
forms:

- **gated**: its error plus its spread under :data:`PERTURBATIONS` stays within half its tolerance (:data:`MARGIN`);
  asserted to pass.
- **watched** (:class:`Watch`): it passes, but its error plus its spread lies between half its tolerance and its
  tolerance; asserted to stay within its tolerance, in every environment of the ensemble.
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
from mjpoincare.commands.validation import run_validation
from mjpoincare.core.allowance import FLOOR, MULTIPLE, allowance
from mjpoincare.core.params import Value
from mjpoincare.core.result import Result
from mjpoincare.gate.environments import Errors
from mjpoincare.scenarios.gate_cases import GateCase, span

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
    """Every registered scenario's gate cases, scenario by scenario (the registry's order); a plugin that does not
    load has none (its one line in ``scenarios.REGISTRY.broken``)."""
    return tuple(c for name in scenarios.loadable() for c in scenarios.REGISTRY[name].gate_cases)


def case(label: str) -> GateCase:
    """The gate case with this label (e.g. ``rimless-wheel[fast]``)."""
    found = next((c for c in cases() if c.label == label), None)
    if found is None:
        raise KeyError(f"no gate case {label!r}; cases: {', '.join(c.label for c in cases())}")
    return found


def margin_rows(cases: Iterable[GateCase], compare: Mapping[tuple[str, str], float] | None = None, *,
                perturb: bool = True, environments: Mapping[str, Errors] | None = None) -> list[dict[str, object]]:
    """For every check of every case: error, spread (largest change of the error under :data:`PERTURBATIONS` unless not
    ``perturb``, in each of ``environments``, label -> (case label, check) -> error, from
    :func:`mjpoincare.gate.environments.run_ensemble`, and against ``compare``'s errors from another environment),
    the lowest and highest error with the environment or perturbation that gave it (``low``, ``high``: [error,
    label]), the error under each perturbation (``perturbations``) and in each environment (``environments``),
    tolerance, the ratio (error + spread) / tolerance, the check's form in the gate, whether it holds there (a gated
    check within :data:`MARGIN`; a watched check passing everywhere, its spread within its declared one's allowance;
    a declared miss missing everywhere, with every error in its band), its resolution (a gated or watched check's
    spread, a miss's band width), and a declared miss's error (``declared``: [low, high]) and xfail reason
    (``miss``)."""
    rows: list[dict[str, object]] = []
    for case in cases:
        base = run_case(case)
        variants = [(label, run_case(case, seed, **extra)) for label, seed, extra in PERTURBATIONS] if perturb else []
        for check in base.checks:
            others = [(label, next((c.error for c in v.checks if c.name == check.name), math.nan))
                      for label, v in variants]
            key = (case.label, check.name)
            others += [(label, errors[key]) for label, errors in (environments or {}).items() if key in errors]
            if compare and key in compare:
                others.append(("--compare", compare[key]))
            spread = max((abs(e - check.error) if math.isfinite(e) and math.isfinite(check.error) else math.inf
                          for _, e in others), default=0.0)
            finite = [(e, label) for label, e in [("this run", check.error), *others] if math.isfinite(e)]
            low, high = (min(finite), max(finite)) if finite else ((math.nan, ""), (math.nan, ""))
            ratio = ((check.error + spread) / check.tolerance if check.tolerance > 0
                     else (0.0 if check.error + spread == 0 else math.inf))
            row: dict[str, object] = {
                "case": case.label, "check": check.name, "error": check.error, "spread": spread,
                "low": list(low), "high": list(high),
                "perturbations": {label: error for label, error in others[:len(variants)]},
                "environments": {label: errors[key] for label, errors in (environments or {}).items()
                                 if key in errors},
                "tolerance": check.tolerance, "ratio": ratio}
            rows.append({**row, **judge(case, row)})
    return rows


def _number(value: object) -> float:
    """A number of a margins row; the JSON writes a non-finite one as null (a spread or ratio that is infinite, an
    error that is NaN): read back as infinite, which no form holds."""
    return math.inf if value is None else float(value)  # type: ignore[arg-type]


def judge(case: GateCase, row: Mapping[str, object]) -> dict[str, object]:
    """The form a measured check (``row``: its error, spread, lowest and highest error over the ensemble, tolerance
    and ratio, as :func:`margin_rows` measures them) takes in ``case`` as the case declares it today, and whether it
    holds there: a gated check within :data:`MARGIN`; a watched check passing everywhere, its spread within its
    declared one's allowance; a declared miss missing everywhere, every error in its band (an unresolved one: above its
    tolerance, at most its ceiling). With it the resolution (a gated or watched check's spread, a miss's band width),
    and a declared miss's error (``declared``) and xfail reason (``miss``). A pure function of the measurement and
    the declaration: a declaration changed since the measurement is judged against it without simulating again."""
    name = str(row["check"])
    error, spread, tolerance, ratio = (_number(row[k]) for k in ("error", "spread", "tolerance", "ratio"))
    low, high = (_number(row[side][0]) for side in ("low", "high"))  # type: ignore[index]
    miss = next((m for m in case.misses if m.check == name), None)
    watch = next((w for w in case.watched if w.check == name), None)
    finite = math.isfinite(spread) and math.isfinite(error)
    if name in case.gated:
        status, holds, resolution = "gated", finite and ratio <= MARGIN, spread
    elif miss is not None:
        band_low, band_high = miss.band
        inside = finite and miss.matches(low) and miss.matches(high)
        holds = inside and (low > tolerance or not miss.resolved)
        status = "declared miss" if miss.resolved else "declared miss, unresolved"
        resolution = band_high - band_low
    else:
        status = "watched" if watch is not None else "not in the gate"
        holds = (watch is not None and finite and high <= tolerance
                 and spread <= allowance(watch.spread, tolerance))
        resolution = spread
    return {"status": status, "holds": holds, "resolution": resolution,
            "declared": list(miss.bounds) if miss else None, "miss": miss.reason(case.preset) if miss else ""}


def judged(rows: Iterable[Mapping[str, object]]) -> list[dict[str, object]]:
    """Committed margin rows (:func:`margin_rows`) with their forms judged against today's declarations
    (:func:`judge`)."""
    return [{**row, **judge(case(str(row["case"])), row)} for row in rows]


def _extreme(at: object, error: object) -> str:
    """The environment or perturbation of a row's lowest or highest error, with the error where it is not the run's
    own."""
    value, label = at  # type: ignore[misc]
    return str(label) if value == error else f"{label} ({value:.4g})"


def margin_table(rows: list[dict[str, object]]) -> str:
    """The margin table a person reads (``declared``: a declared miss's error, to compare with ``error``;
    ``resolution``: the smallest change of the error the gate tells from jitter; ``NOT HELD``: a gated check without
    the margin, a watched check that fails, a declared miss that passes or has left its band, or a check the gate does
    not name)."""
    head = ("case", "check", "error", "declared", "spread", "tolerance", "(err+spread)/tol", "resolution", "form",
            "lowest at", "highest at", "")
    body = [(str(r["case"]), str(r["check"]), f"{r['error']:.3g}",
             span(*r["declared"]) if isinstance(r["declared"], list) else "", f"{r['spread']:.2g}",
             f"{r['tolerance']:.3g}", f"{r['ratio']:.2f}", f"{r['resolution']:.2g}", str(r["status"]),
             *(_extreme(r[side], r["error"]) for side in ("low", "high")), "" if r["holds"] else "NOT HELD")
            for r in rows]
    return text_table(head, body)


def outside_ensemble(row: Mapping[str, object] | None, error: float) -> str:
    """Where ``error`` lies against a margins row's range of errors over the ensemble (its ``low`` and ``high``:
    [error, environment]), and the environment that gave the error closest to it; ``row`` None: none measured."""
    if row is None:
        return f"error {error:.6g}; the ensemble has no measurement of this check (make margins)"
    (low, low_at), (high, high_at) = row["low"], row["high"]  # type: ignore[misc]
    if error < low:
        where, closest = f"{low - error:.2g} below", low_at
    elif error > high:
        where, closest = f"{error - high:.2g} above", high_at
    else:
        where, closest = "inside", low_at if error - low <= high - error else high_at
    return (f"error {error:.6g} lies {where} the ensemble's range {low:.6g} to {high:.6g} (closest: {closest}); "
            "outside it, something other than the CPU's code paths moved the value (MuJoCo, numpy, the code): find "
            "what before re-measuring with make margins")


def environment_disagreements(there: Errors, here: Errors, spreads: Mapping[tuple[str, str], float],
                              tolerances: Mapping[tuple[str, str], float], environment: str) -> list[str]:
    """One line per check whose error in another ``environment`` (``there``) moves from this process's (``here``)
    by more than its allowance (:func:`mjpoincare.core.allowance.allowance` of its measured spread, ``spreads``, and its
    tolerance, ``tolerances``), or that one of the two lacks."""
    out = []
    for key in sorted(set(here) | set(there)):
        a, b = here.get(key, math.nan), there.get(key, math.nan)
        allowed = allowance(spreads.get(key, 0.0), tolerances.get(key, math.nan), a)
        if not (math.isfinite(a) and math.isfinite(b)):
            if not (math.isnan(a) and math.isnan(b) and key in here and key in there):
                out.append(f"{key[0]}::{key[1]}: {a:.6g} here, {b:.6g} under {environment}")
        elif abs(b - a) > allowed:
            out.append(f"{key[0]}::{key[1]}: {a:.6g} here, {b:.6g} under {environment}: moved {abs(b - a):.2g}, "
                       f"{abs(b - a) / allowed:.3g} x its allowance {allowed:.2g} (the larger of {MULTIPLE:g} x its "
                       f"spread {spreads.get(key, 0.0):.2g} and {FLOOR:g} x its tolerance)")
    return out
