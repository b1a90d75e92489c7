"""The regression gate: which checks the test suite asserts, on which runs, and by what margin each holds.

A MuJoCo result differs between machines, library builds, thread counts and seeds at the 1e-4 level (the impact
onset jitters on the step grid and amplifies rounding), so a check is asserted only where its error plus its spread
under such perturbations stays within half its tolerance (:data:`MARGIN`). A check that misses is asserted as a
strict expected miss carrying its measured number; a check of a gated run that is neither is reported, not asserted.
``mjpoincare margins`` measures the spread and prints the table (check, error, spread, tolerance, margin), so a
fragile assertion is seen before it breaks CI. Tolerances are the scenarios' own; nothing here changes them.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cache

from mjpoincare.params import Value
from mjpoincare.result import Result

#: A gated check's error plus its spread must stay within this fraction of its tolerance.
MARGIN = 0.5
#: Perturbations that must not change a verdict: (label, seed, extra settings).
PERTURBATIONS: tuple[tuple[str, int, Mapping[str, Value]], ...] = (
    ("seed 1", 1, {}),
    ("threads 1", 0, {"threads": 1}),
    ("starts x(1+1e-12)", 0, {"start_perturbation": 1e-12}),
)


@dataclass(frozen=True)
class GateCase:
    """One validation run of the gate and what the tests assert of it.

    ``gated``: checks asserted to pass; ``misses``: (check, measured miss) pairs asserted as strict expected misses;
    ``reported``: checks that pass here but without the margin, so that no test asserts them (the margins table
    shows their numbers).
    """

    scenario: str
    preset: str
    values: tuple[tuple[str, Value], ...] = ()
    gated: tuple[str, ...] = ()
    misses: tuple[tuple[str, str], ...] = field(default=())
    reported: tuple[str, ...] = ()

    @property
    def label(self) -> str:
        """``scenario[preset,name=value,...]``, the case's test id."""
        return f"{self.scenario}[{','.join([self.preset, *(f'{k}={v}' for k, v in self.values)])}]"

    def run(self, seed: int = 0, **extra: Value) -> Result:
        """The case's validation (cached per process: tests of one run share it)."""
        return _validate(self.scenario, self.preset, seed, tuple(sorted({**dict(self.values), **extra}.items())))


@cache
def _validate(scenario: str, preset: str, seed: int, values: tuple[tuple[str, Value], ...]) -> Result:
    from mjpoincare.api import validate

    return validate(scenario, preset, seed, **dict(values))


def _case(scenario: str, preset: str, gated: str, misses: Mapping[str, str] | None = None, reported: str = "",
          **values: Value) -> GateCase:
    return GateCase(scenario, preset, tuple(values.items()), tuple(gated.split()), tuple((misses or {}).items()),
                    tuple(reported.split()))


GATE: tuple[GateCase, ...] = (
    _case("rimless-wheel", "fast", ""),
    _case("rimless-wheel", "accurate", ""),
    *(_case("rimless-wheel", "accurate", "", spokes=n, slope=a) for n, a in ((8, 0.08), (10, 0.1), (12, 0.1), (8, 0.2),
                                                                             (6, 0.22))),
    _case("compass-biped", "fast", ""),
    _case("compass-biped", "fast", "", tau_ankle=0.5, tau_hip=0.2),
    _case("compass-biped", "accurate", ""),
    _case("slotted-skate", "fast", ""),
    _case("slotted-skate", "fast", "", l0=-1.4142135623730951, delta=0.7071067811865476),
    _case("slotted-skate", "accurate", ""),
    _case("slotted-skate", "accurate", "", l0=1.0, delta=1 / 3),
    _case("slotted-skate", "accurate", "", l0=-1.0, delta=1 / 3),
    _case("rimless-wheel-3d", "fast", ""),
    _case("rimless-wheel-3d", "fast", "", impact="ideal"),
    _case("rimless-wheel-3d", "accurate", ""),
    _case("rimless-wheel-friction", "fast", ""),
    _case("rimless-wheel-friction", "fast", "", mu=2.0),
    _case("rimless-wheel-friction", "fast", "", mu=0.24),
    _case("rimless-wheel-friction", "accurate", ""),
    _case("rimless-wheel-friction", "coarse", ""),
    *(_case("compass-biped-friction", "fast", "", gait=g) for g in ("a", "b", "c", "i", "ii", "iii")),
    _case("compass-biped-friction", "accurate", ""),
)


def margin_rows(cases: Iterable[GateCase], compare: Mapping[tuple[str, str], float] | None = None
                ) -> list[dict[str, object]]:
    """For every check of every case: error, spread (largest change of the error under :data:`PERTURBATIONS`, and
    against ``compare``'s errors from another environment, keyed by (case label, check)), tolerance, the ratio
    (error + spread) / tolerance, and the check's status in the gate."""
    rows: list[dict[str, object]] = []
    for case in cases:
        base = case.run()
        variants = [case.run(seed, **extra) for _, seed, extra in PERTURBATIONS]
        misses = dict(case.misses)
        for check in base.checks:
            others = [next((c.error for c in v.checks if c.name == check.name), math.nan) for v in variants]
            if compare and (case.label, check.name) in compare:
                others.append(compare[(case.label, check.name)])
            spread = max((abs(e - check.error) if math.isfinite(e) and math.isfinite(check.error) else math.inf
                          for e in others), default=0.0)
            ratio = ((check.error + spread) / check.tolerance if check.tolerance > 0
                     else (0.0 if check.error + spread == 0 else math.inf))
            status = ("gated" if check.name in case.gated else "expected miss" if check.name in misses
                      else "reported, no margin" if check.name in case.reported else "not in the gate")
            holds = (ratio <= MARGIN if status == "gated" else
                     (not check.passed and not any(math.isfinite(e) and e <= check.tolerance for e in others))
                     if status == "expected miss" else True)
            rows.append({"case": case.label, "check": check.name, "error": check.error, "spread": spread,
                         "tolerance": check.tolerance, "ratio": ratio, "status": status, "holds": holds,
                         "miss": misses.get(check.name, "")})
    return rows


def margin_table(rows: list[dict[str, object]]) -> str:
    """The margin table a person reads."""
    head = ("case", "check", "error", "spread", "tolerance", "(err+spread)/tol", "status", "")
    body = [(str(r["case"]), str(r["check"]), f"{r['error']:.3g}", f"{r['spread']:.2g}", f"{r['tolerance']:.3g}",
             f"{r['ratio']:.2f}", str(r["status"]), "" if r["holds"] else "NO MARGIN") for r in rows]
    widths = [max(len(x[i]) for x in (head, *body)) for i in range(len(head))]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(x, widths, strict=True)).rstrip() for x in (head, *body))
