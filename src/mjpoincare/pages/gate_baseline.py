"""``python -m mjpoincare.pages.gate_baseline`` (``make baseline``): ``docs/results/gate/baseline.json``, the gate's
regression baseline (:mod:`mjpoincare.gate.baseline`).

Every gate case runs here, and again under the rounding perturbations (:data:`mjpoincare.gate.baseline.ROUNDING`); each
check's resolution is the largest change of its error over those runs and over the environments of the committed
ensemble measurement (``docs/results/gate/margins.json``, ``make margins``: every OpenBLAS kernel the CPU runs, numpy
at its baseline, the oldest numpy/scipy). A run whose error lies outside the range of that measurement's
environments has moved for a reason the ensemble did not sample (the code, MuJoCo, numpy): the spread measured there
no longer describes it, and the command refuses (exit 1) with the checks that moved, to be re-measured by
``make margins`` first.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from mjpoincare.gate import baseline, records
from mjpoincare.gate import forms as gate
from mjpoincare.pages.gate_page import GATE_DIR, MARGINS

#: Where ``make baseline`` writes, relative to the repository root.
BASELINE = GATE_DIR / records.BASELINE


def main(argv: Sequence[str] | None = None) -> int:
    """Run the gate cases, take each check's resolution from the margins JSON, write the baseline."""
    parser = argparse.ArgumentParser(prog="python -m mjpoincare.pages.gate_baseline", description=__doc__)
    parser.add_argument("--margins", default=str(MARGINS), help="the ensemble measurement (make margins)")
    parser.add_argument("--out", default=str(BASELINE), help="the baseline to write")
    args = parser.parse_args(argv)
    rows = {(r["case"], r["check"]): r for r in json.loads(Path(args.margins).read_text())["rows"]}
    from mjpoincare.core.stamp import environment

    stamp = environment()
    records, outside = [], []
    for case in gate.cases():
        result = gate.run_case(case)
        measured: dict[str, float] = {}
        for check in result.checks:
            row = rows.get((case.label, check.name))
            errors = [] if row is None else [row["error"], *row["environments"].values()]
            if not errors or None in errors or not min(errors) <= check.error <= max(errors):
                outside.append(f"{case.label}::{check.name}: error {check.error:.6g}, the ensemble's environments "
                               + (f"{min(errors):.6g} to {max(errors):.6g}" if errors and None not in errors
                                  else "did not measure it"))
            else:
                measured[check.name] = max(abs(e - check.error) for e in errors)
        perturbed = [{c.name: c.error for c in gate.run_case(case, seed, **extra).checks}
                     for label, seed, extra in gate.PERTURBATIONS if label in baseline.ROUNDING]
        resolutions = {name: max(spread, measured.get(name, 0.0))
                       for name, spread in baseline.spreads(result, perturbed).items()}
        records.append((baseline.run_key(result), baseline.entry(result, resolutions)))
    if outside:
        print("\n".join(["not written: these errors lie outside the ensemble measurement "
                         f"({args.margins}); re-measure with make margins first", *outside]), file=sys.stderr)
        return 1
    from mjpoincare.core.result import write_json

    write_json(baseline.updated(None, records, stamp), args.out)
    print(f"{args.out}: {sum(len(r['checks']) for _, r in records)} checks of {len(records)} runs")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
