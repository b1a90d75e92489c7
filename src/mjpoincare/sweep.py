"""``mjpoincare sweep``: one parameter over a list of values, fitted against analytic eigenvalues.

Each value is a full validation. The table lists, per value, every check's error and the fitted
and analytic eigenvalue of smallest real part; ``--locate period-doubling`` estimates where that
eigenvalue reaches -1 from the simulated values (linear interpolation between the two values that
bracket -1, or extrapolation from the last two), beside the same estimate from the analytic values.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mjpoincare.params import ParameterError
from mjpoincare.result import write_json
from mjpoincare.validate import resolve_inputs, run_validation


def parse_values(text: str) -> list[str]:
    """``0.07,0.072,0.074`` or ``0.07:0.076:4`` (start:stop:count) -> value strings."""
    if text.count(":") == 2:
        start, stop, count = text.split(":")
        try:
            return [f"{v:.10g}" for v in np.linspace(float(start), float(stop), int(count))]
        except ValueError:
            raise ParameterError(f"--values START:STOP:COUNT expects numbers (got {text!r})") from None
    values = [v.strip() for v in text.split(",") if v.strip()]
    if not values:
        raise ParameterError("--values needs at least one value")
    return values


def _lowest(values: Sequence[Any]) -> float:
    """Real part of the eigenvalue with the smallest real part (eigenvalues as [re, im] pairs or numbers)."""
    reals = [v[0] if isinstance(v, list) else float(v) for v in values]
    return min(reals)


def crossing(xs: Sequence[float], ys: Sequence[float], level: float = -1.0) -> float:
    """Where the piecewise-linear curve (xs, ys) reaches ``level``: interpolated inside a bracket, else
    extrapolated from the last two points (NaN when the slope is zero)."""
    for i in range(len(xs) - 1):
        if (ys[i] - level) * (ys[i + 1] - level) <= 0 and ys[i] != ys[i + 1]:
            return xs[i] + (level - ys[i]) * (xs[i + 1] - xs[i]) / (ys[i + 1] - ys[i])
    if len(xs) < 2 or ys[-1] == ys[-2]:
        return math.nan
    return xs[-1] + (level - ys[-1]) * (xs[-1] - xs[-2]) / (ys[-1] - ys[-2])


def run_sweep(name: str, param: str, values: list[str], assignments: Mapping[str, str], preset: str | None,
              json_path: str | None, locate: str | None) -> int:
    """Validate at each value; print the table (and the located bifurcation); exit 0, or 1 if a check failed."""
    for value in values:  # every input is checked before the first simulation
        resolve_inputs(name, {**assignments, param: value}, preset)
    rows: list[dict[str, Any]] = []
    for value in values:
        result = run_validation(name, {**assignments, param: value}, preset).to_dict()
        analytic = result.get("analytic", {}).get("eigenvalues")
        row = {param: float(value), "passed": result["passed"],
               "errors": {c["name"]: c["error"] for c in result["checks"]},
               "fitted_lowest": _lowest(result["fit"]["eigenvalues"]) if "fit" in result else math.nan,
               "analytic_lowest": _lowest(analytic) if analytic is not None else math.nan,
               "wall_s": result["timing"]["wall_s"]}
        rows.append(row)
        if sys.stderr.isatty() and not os.environ.get("CI"):
            print(f"{param}={value}: {'pass' if row['passed'] else 'FAIL'} ({row['wall_s']:.1f} s)", file=sys.stderr)
    names = list(rows[0]["errors"])
    lines = [f"| {param} | " + " | ".join(f"{n} error" for n in names) + " | lowest Re λ fitted | analytic |",
             "|" + "---|" * (3 + len(names))]
    for r in rows:
        errs = " | ".join("—" if r["errors"][n] is None else f"{r['errors'][n]:.2e}" for n in names)
        lines.append(f"| {r[param]:g} | {errs} | {r['fitted_lowest']:.4f} | {r['analytic_lowest']:.4f} |")
    payload: dict[str, Any] = {"scenario": name, "param": param, "rows": rows}
    if locate == "period-doubling":
        xs = [r[param] for r in rows]
        fitted = crossing(xs, [r["fitted_lowest"] for r in rows])
        analytic = crossing(xs, [r["analytic_lowest"] for r in rows])
        payload["period_doubling"] = {"fitted": fitted, "analytic_same_grid": analytic}
        lines.append(f"\nfirst period doubling (lowest eigenvalue = -1): {param} = {fitted:.5f} from the simulation, "
                     f"{analytic:.5f} from the analytic eigenvalues on the same grid")
    print("\n".join(lines))
    if json_path:
        write_json(payload, json_path)
    return 0 if all(r["passed"] for r in rows) else 1
