"""``mjpoincare sweep``: one parameter over a list of values, fitted against analytic eigenvalues.

Each value is a full validation. The table lists, per value, every check's error and the fitted
and analytic eigenvalue of smallest real part; ``--locate period-doubling`` estimates where that
eigenvalue reaches -1 from the simulated values (linear interpolation between the two values that
bracket -1, or extrapolation from the last two), beside the same estimate from the analytic values;
``--locate stability-loss`` likewise where the largest eigenvalue modulus |lambda|max reaches 1 (a stability loss
through a complex pair or a real multiplier, e.g. Gait B and I of Gamus & Or 2015 Sec. 4.2/5 against mu).

Scale-out. The values are independent: ``--workers N`` validates N of them at once in separate
processes (each with ``threads`` = cores / N unless ``--set threads=`` says otherwise), and
``--engine dask`` hands them to a Dask cluster instead (``--scheduler ADDRESS``, or a local cluster
of N worker processes). Each finished point goes into the results file at once (whole or not at
all), and ``--resume`` skips the values that file already holds, so an interrupted sweep loses at
most the points in flight.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from typing import Any

from mjpoincare import progress
from mjpoincare.analysis.checks import jsonable
from mjpoincare.parallel import check_engine, point_assignments, run_jobs
from mjpoincare.params import ParameterError
from mjpoincare.result import resumed_rows, write_json
from mjpoincare.validation import resolve_inputs, run_validation


def _lowest(values: Sequence[Any]) -> float:
    """Real part of the eigenvalue with the smallest real part (eigenvalues as [re, im] pairs or numbers)."""
    reals = [v[0] if isinstance(v, list) else float(v) for v in values]
    return min(reals)


def _largest_modulus(values: Sequence[Any]) -> float:
    """|lambda|max of eigenvalues given as [re, im] pairs or numbers."""
    return max(math.hypot(*v) if isinstance(v, list) else abs(float(v)) for v in values)


def crossing(xs: Sequence[float], ys: Sequence[float], level: float = -1.0) -> float:
    """Where the piecewise-linear curve (xs, ys) reaches ``level``: interpolated inside a bracket, else
    extrapolated from the last two points (NaN when the slope is zero)."""
    for i in range(len(xs) - 1):
        if (ys[i] - level) * (ys[i + 1] - level) <= 0 and ys[i] != ys[i + 1]:
            return xs[i] + (level - ys[i]) * (xs[i + 1] - xs[i]) / (ys[i + 1] - ys[i])
    if len(xs) < 2 or ys[-1] == ys[-2]:
        return math.nan
    return xs[-1] + (level - ys[-1]) * (xs[-1] - xs[-2]) / (ys[-1] - ys[-2])


def sweep_point(name: str, param: str, value: str, assignments: Mapping[str, str], preset: str | None
                ) -> dict[str, Any]:
    """One sweep row: the validation at ``param = value`` reduced to errors, eigenvalues and wall time
    (a top-level function so that worker processes and Dask can run it)."""
    result = run_validation(name, {**assignments, param: value}, preset).to_dict()
    analytic = result.get("analytic", {}).get("eigenvalues")
    return {param: float(value), "value": value, "passed": result["passed"],
            "errors": {c["name"]: c["error"] for c in result["checks"]},
            "fitted_lowest": _lowest(result["fit"]["eigenvalues"]) if "fit" in result else math.nan,
            "analytic_lowest": _lowest(analytic) if analytic is not None else math.nan,
            "fitted_max_modulus": _largest_modulus(result["fit"]["eigenvalues"]) if "fit" in result else math.nan,
            "analytic_max_modulus": _largest_modulus(analytic) if analytic is not None else math.nan,
            "wall_s": result["timing"]["wall_s"]}


def run_sweep(name: str, param: str, values: list[str], assignments: Mapping[str, str], preset: str | None,
              json_path: str | None, locate: str | None, *, workers: int = 1, engine: str = "local",
              scheduler: str | None = None, resume: bool = False) -> int:
    """Validate at each value; print the table (and the located bifurcation); exit 0, or 1 if a check failed."""
    check_engine(workers, engine)
    if resume and (not json_path or json_path == "-"):
        raise ParameterError("--resume needs --json PATH (the results file to resume from)")
    point_set = point_assignments(assignments, workers)
    for value in values:  # every input is checked before the first simulation
        resolve_inputs(name, {**point_set, param: value}, preset)
    header = {"scenario": name, "param": param, "assignments": dict(assignments), "preset": preset}
    done = resumed_rows(json_path, header) if resume else []
    finished = {r["value"] for r in done}
    todo = [v for v in values if v not in finished]
    rows = [r for r in done if r["value"] in set(values)]
    start = time.perf_counter()
    jobs = [(name, param, value, point_set, preset) for value in todo]
    with progress.bar(len(values), f"sweep {param}", unit="point", initial=len(rows)) as bar:
        for row in run_jobs(sweep_point, jobs, workers=workers, engine=engine, scheduler=scheduler):
            rows.append(row)
            if json_path and json_path != "-":
                write_json(jsonable({**header, "rows": rows}), json_path)
            bar.set_postfix_str(f"{param}={row['value']}: {'pass' if row['passed'] else 'FAIL'}")
            bar.update(1)
    wall = time.perf_counter() - start
    rows.sort(key=lambda r: values.index(r["value"]))
    names = list(dict.fromkeys(n for r in rows for n in r["errors"]))  # rows may carry different checks
    lines = [f"| {param} | " + " | ".join(f"{n} error" for n in names) + " | lowest Re λ fitted | analytic |",
             "|" + "---|" * (3 + len(names))]
    for r in rows:
        errs = " | ".join("—" if r["errors"].get(n) is None else f"{r['errors'][n]:.2e}" for n in names)
        lines.append(f"| {r[param]:g} | {errs} | {r['fitted_lowest']:.4f} | {r['analytic_lowest']:.4f} |")
    busy = sum(r["wall_s"] for r in rows if r["value"] in todo)
    lines.append(f"\n{len(todo)} points run ({len(values) - len(todo)} resumed) in {wall:.1f} s wall with "
                 f"{engine} engine, {workers} worker(s); {busy:.1f} s of validation")
    payload: dict[str, Any] = {**header, "rows": rows, "wall_s": wall, "workers": workers, "engine": engine}
    if locate == "period-doubling":
        xs = [r[param] for r in rows]
        fitted = crossing(xs, [r["fitted_lowest"] for r in rows])
        analytic = crossing(xs, [r["analytic_lowest"] for r in rows])
        payload["period_doubling"] = {"fitted": fitted, "analytic_same_grid": analytic}
        lines.append(f"\nfirst period doubling (lowest eigenvalue = -1): {param} = {fitted:.5f} from the simulation, "
                     f"{analytic:.5f} from the analytic eigenvalues on the same grid")
    if locate == "stability-loss":
        xs = [r[param] for r in rows]
        fitted = crossing(xs, [r["fitted_max_modulus"] for r in rows], level=1.0)
        analytic = crossing(xs, [r["analytic_max_modulus"] for r in rows], level=1.0)
        payload["stability_loss"] = {"fitted": fitted, "analytic_same_grid": analytic}
        lines.append(f"\nstability loss (|lambda|max = 1): {param} = {fitted:.5f} from the simulation, {analytic:.5f} "
                     "from the analytic eigenvalues on the same grid")
        lines += [f"  {r[param]:g}: |lambda|max fitted {r['fitted_max_modulus']:.4f}, analytic "
                  f"{r['analytic_max_modulus']:.4f}" for r in rows]
    print("\n".join(lines))
    if json_path:
        write_json(jsonable(payload), json_path)
    return 0 if all(r["passed"] for r in rows) else 1
