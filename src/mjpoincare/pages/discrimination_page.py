"""``python -m mjpoincare.pages.discrimination_page``: ``docs/results/discrimination.md``, whether each check of the
gate tells the right physics from the nearest wrong one; generated, never typed.

For every check of every gate case, the page puts the distance its scenario's :class:`~mjpoincare.scenarios.base.Rival`
computes from the theory (the error a simulator reproducing the rival physics exactly would show) against what the
check lets through: its tolerance plus the error the gate measured and that error's spread over the ensemble of
environments (``docs/results/gate/margins.json``, ``make margins``). The ratio of the two is above 1 where the check
rejects the rival.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mjpoincare import scenarios
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_values
from mjpoincare.core.result import write_text
from mjpoincare.core.stamp import stamp_table
from mjpoincare.gate import forms, records

#: The gate's margins (the runs this page reads) and the page, relative to the repository root.
MARGINS = records.SOURCE / records.MARGINS
PAGE = Path("docs/results/discrimination.md")
#: A tolerance more than this many times the measured error plus its spread is listed: only a rival it must still
#: reject explains its width.
WIDE = 100.0
#: The check every run reports that is the run's numerical health, not physics: it has no rival.
HEALTH = "stable"


@dataclass(frozen=True)
class Row:
    """One check of one gate case against its rival.

    Attributes:
        case: the gate case's label.
        check: the check's name.
        tolerance: the check's tolerance at the case's preset.
        error: the error the gate measured.
        spread: that error's spread over the ensemble of environments and perturbations.
        physics: the rival physics.
        distance: the check's error under the rival (None: no check can tell them apart).
        indistinct: why not, where ``distance`` is None.
        weak: why no gate case's check tells the rival apart, where none does.
    """

    case: str
    check: str
    tolerance: float
    error: float
    spread: float
    physics: str
    distance: float | None
    indistinct: str
    weak: str = ""

    @property
    def allowed(self) -> float:
        """What the check lets through: tolerance + measured error + spread."""
        return self.tolerance + self.error + self.spread

    @property
    def ratio(self) -> float | None:
        """distance / (tolerance + error + spread): above 1 where the check rejects the rival (inf where nothing is
        let through and the rival differs)."""
        if self.distance is None:
            return None
        if self.allowed == 0.0:
            return math.inf if self.distance > 0.0 else 0.0
        return self.distance / self.allowed


def rows(margins: dict[str, Any]) -> list[Row]:
    """Every check of every gate case in ``margins`` (the JSON ``make margins`` writes) against its rival."""
    out = []
    for row in margins["rows"]:
        if row["check"] == HEALTH:
            continue
        case = forms.case(row["case"])
        scenario = scenarios.get(case.scenario)
        rival = scenario.rivals[row["check"]]
        _, _, params, _ = resolve_values(case.scenario, dict(case.values), case.preset)
        distance = None if rival.distance is None else float(rival.distance(params))
        out.append(Row(case=row["case"], check=row["check"], tolerance=float(row["tolerance"]),
                       error=float(row["error"]), spread=float(row["spread"]), physics=rival.physics,
                       distance=distance, indistinct=rival.indistinct, weak=rival.weak))
    return out


def rejects(row: Row) -> bool:
    """Whether the row's check rejects its rival (ratio above 1)."""
    return row.ratio is not None and row.ratio > 1.0


def told_elsewhere(table: Sequence[Row]) -> dict[tuple[str, str], Row]:
    """Per (scenario, check): the gate case whose check rejects its rival by the largest ratio (absent where no case
    does)."""
    best: dict[tuple[str, str], Row] = {}
    for r in table:
        key = (forms.case(r.case).scenario, r.check)
        if rejects(r) and (key not in best or (r.ratio or 0.0) > (best[key].ratio or 0.0)):
            best[key] = r
    return best


def unexplained(table: Sequence[Row]) -> list[Row]:
    """The rows that cannot tell their rival apart with no reason the page can give: no gate case of the scenario
    rejects the rival with this check and its rival states no ``weak`` reason."""
    told = told_elsewhere(table)
    return [r for r in table if r.ratio is not None and not rejects(r)
            and (forms.case(r.case).scenario, r.check) not in told and not r.weak]


def _number(value: float) -> str:
    return "inf" if math.isinf(value) else f"{value:.3g}"


def _verdict(row: Row, told: dict[tuple[str, str], Row]) -> str:
    if row.ratio is None:
        return "cannot tell: " + row.indistinct
    if rejects(row):
        return "rejects"
    other = told.get((forms.case(row.case).scenario, row.check))
    if other is not None:
        return f"cannot tell here; {other.case} does (ratio {_number(other.ratio or 0.0)})"
    return "**cannot tell**: " + (row.weak or "no reason given")


def render(margins: dict[str, Any]) -> str:
    """The page from the margins JSON (its stamp is the runs')."""
    table = rows(margins)
    told = told_elsewhere(table)
    weak = [r for r in table if r.ratio is not None and not rejects(r)]
    nowhere = [r for r in weak if (forms.case(r.case).scenario, r.check) not in told]
    lines = [
        "# Does each check tell the right physics from the nearest wrong one?", "",
        "Generated by `python -m mjpoincare.pages.discrimination_page` from the gate's margins "
        f"(`{MARGINS.as_posix()}`, `make margins`) and each scenario's rivals; never typed.", "",
        "For every check of every gate case: the nearest plausible wrong physics (its *rival*), the error a simulator "
        "reproducing that physics exactly would show in the check (*distance*, computed from the theory under both "
        "physics), and what the check lets through: its tolerance plus the error the gate measured and that error's "
        "spread over the gate's environments. *ratio* = distance / (tolerance + error + spread): above 1 the check "
        "rejects the rival. A category check (tolerance 0) rejects any rival whose category differs (ratio inf).",
        "", stamp_table(margins["stamp"]), "",
        f"{sum(1 for r in table if rejects(r))} of {len(table)} checks reject their rival; {len(weak)} cannot tell it "
        f"apart, {len(weak) - len(nowhere)} of them where another gate case of the scenario does; "
        f"{sum(1 for r in table if r.ratio is None)} have no distance (no check can tell, with the reason). "
        "Told apart by no gate case (each with its reason in its table)"
        + (": " + ", ".join(f"{r.case} {r.check} ({_number(r.ratio or 0.0)})" for r in nowhere) if nowhere else
           ": none") + ".",
        "",
    ]
    wide = [r for r in table if r.tolerance > WIDE * (r.error + r.spread)]
    lines += [f"## Tolerances more than {WIDE:g} times the measured error and spread", "",
              "A tolerance that wide is explained only by a rival it must still reject (ratio above 1); the others "
              "are wider than both the measurement and the nearest wrong physics ask for.", ""]
    lines += [markdown_table(
        ("case", "check", "tolerance", "error + spread", "tolerance / (error + spread)", "ratio", "verdict"),
        [(r.case, r.check, _number(r.tolerance), _number(r.error + r.spread),
          _number(r.tolerance / (r.error + r.spread)) if r.error + r.spread > 0 else "inf",
          "—" if r.ratio is None else _number(r.ratio), _verdict(r, told)) for r in wide]), ""]
    for name in dict.fromkeys(forms.case(r.case).scenario for r in table):
        mine = [r for r in table if forms.case(r.case).scenario == name]
        lines += [f"## {name}", ""]
        physics = dict.fromkeys((r.check, r.physics) for r in mine)
        lines += [markdown_table(("check", "rival physics"), [(check, text) for check, text in physics]), ""]
        lines += [markdown_table(
            ("case", "check", "tolerance", "error", "spread", "distance", "ratio", "verdict"),
            [(r.case, r.check, _number(r.tolerance), _number(r.error), _number(r.spread),
                   "—" if r.distance is None else _number(r.distance),
                   "—" if r.ratio is None else _number(r.ratio), _verdict(r, told)) for r in mine]), ""]
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    """Write the page from the margins JSON."""
    parser = argparse.ArgumentParser(prog="python -m mjpoincare.pages.discrimination_page", description=__doc__)
    parser.add_argument("--json", type=Path, default=MARGINS, help="the margins JSON (make margins)")
    parser.add_argument("--out", type=Path, default=PAGE, help="the page to write")
    args = parser.parse_args(argv)
    write_text(render(json.loads(args.json.read_text())), str(args.out))
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
