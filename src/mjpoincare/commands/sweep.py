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

A scenario's own facets run here too, on inputs resolved and checked before any simulation: its region map
(``--grid``, :func:`run_region_map`) and its own sweep of a parameter (``--param NAME`` where it declares one,
:func:`run_own_sweep`, resumable as above). The facets compute; this module prints, writes the files and returns
the exit code.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_inputs, run_validation
from mjpoincare.core.parallel import ResumableRows, check_engine, point_assignments
from mjpoincare.core.params import parse_grid
from mjpoincare.core.result import write_json
from mjpoincare.scenarios.base import ParamSweep, RegionMap

#: The sweep JSON's shape (``schema``), written beside the resumable header.
SWEEP_SCHEMA = "mjpoincare.sweep/1"


def _lowest(values: Sequence[complex] | np.ndarray | None) -> float:
    """Real part of the eigenvalue with the smallest real part (NaN: no eigenvalues)."""
    return math.nan if values is None or not len(values) else float(np.min(np.real(np.asarray(values, complex))))


def _largest_modulus(values: Sequence[complex] | np.ndarray | None) -> float:
    """|lambda|max of the eigenvalues (NaN: no eigenvalues)."""
    return math.nan if values is None or not len(values) else float(np.max(np.abs(np.asarray(values, complex))))


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
    result = run_validation(name, {**assignments, param: value}, preset)
    fitted = None if result.fit is None else result.fit.eigenvalues
    analytic = None if result.analytic is None else result.analytic.eigenvalues
    return {param: float(value), "value": value, "passed": result.passed,
            "errors": {c.name: jsonable(c.error) for c in result.checks},
            "tolerances": {c.name: jsonable(c.tolerance) for c in result.checks},
            "failed": [c.name for c in result.checks if not c.passed],
            "fitted_lowest": _lowest(fitted), "analytic_lowest": _lowest(analytic),
            "fitted_max_modulus": _largest_modulus(fitted), "analytic_max_modulus": _largest_modulus(analytic),
            "wall_s": result.timing["wall_s"]}


def run_sweep(name: str, param: str, values: list[str], assignments: Mapping[str, str], preset: str | None,
              json_path: str | None, locate: str | None, *, workers: int = 1, engine: str = "local",
              scheduler: str | None = None, resume: bool = False, plot: str | None = None) -> int:
    """Validate at each value; print the table (and the located bifurcation); exit 0, or 1 if a check failed."""
    check_engine(workers, engine, scheduler)
    point_set = point_assignments(assignments, workers)
    for value in values:  # every input is checked before the first simulation
        resolve_inputs(name, {**point_set, param: value}, preset)
    header = {"scenario": name, "param": param, "assignments": dict(assignments), "preset": preset}
    points = ResumableRows.open(header, json_path, "value", values, resume=resume, restore=_null_as_nan)
    todo = points.todo
    start = time.perf_counter()
    rows = points.run(sweep_point, [(name, param, value, point_set, preset) for value in todo],
                      label=f"sweep {param}", unit="point",
                      describe=lambda new: f"{param}={new[0]['value']}: {'pass' if new[0]['passed'] else 'FAIL'}",
                      workers=workers, engine=engine, scheduler=scheduler)
    wall = time.perf_counter() - start
    names = list(dict.fromkeys(n for r in rows for n in r["errors"]))  # rows may carry different checks
    lines = [markdown_table(
        (param, *(f"{n} error" for n in names), "lowest Re λ fitted", "analytic", "verdict"),
        [(f"{r[param]:g}", *("—" if r["errors"].get(n) is None else f"{r['errors'][n]:.2e}" for n in names),
          f"{r['fitted_lowest']:.4f}", f"{r['analytic_lowest']:.4f}", verdict(r)) for r in rows])]
    busy = sum(r["wall_s"] for r in rows if r["value"] in todo)
    lines.append(f"\n{len(todo)} points run ({len(points.keys) - len(todo)} resumed) in {wall:.1f} s wall with "
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
    if plot:
        from mjpoincare.commands.sweep_plot import write_sweep_plot

        write_sweep_plot(rows, param, name, plot)
        lines.append(f"wrote {plot}")
    print("\n".join(lines))
    if json_path:
        write_json(jsonable({"schema": SWEEP_SCHEMA, **payload}), json_path)
    return 0 if all(r["passed"] for r in rows) else 1


def verdict(row: Mapping[str, Any]) -> str:
    """A sweep row's verdict: PASS, or FAIL with the checks that failed (the exit code is 1 when any row fails)."""
    if row["passed"]:
        return "PASS"
    failed = row.get("failed", [])
    return f"FAIL ({', '.join(failed)})" if failed else "FAIL"


def _null_as_nan(row: dict[str, Any]) -> dict[str, Any]:
    """A resumed row's fields as the run made them: JSON null (how a NaN is written) back to NaN."""
    return {k: math.nan if v is None else v for k, v in row.items()}


def run_region_map(name: str, facet: RegionMap, grid: str, assignments: Mapping[str, str], preset: str | None,
                   json_path: str | None, output: str, *, workers: int) -> int:
    """``mjpoincare sweep SCENARIO --grid``: the scenario's region map over the grid.

    Args:
        name: the scenario.
        facet: its region map.
        grid: the ``--grid`` text (:func:`mjpoincare.core.params.parse_grid` over the map's axes).
        assignments: ``--set`` parameters and settings.
        preset: the preset (None: the scenario's default).
        json_path: where the map's data goes as JSON (None: nowhere; ``-``: stdout).
        output: the PNG's path.
        workers: processes the map may use.

    Returns:
        The exit code: 0 when the map passes (:attr:`RegionMap.passed`), 1 when not.
    """
    x, y = parse_grid(grid, facet.axes).values()
    _, preset_name, params, settings = resolve_inputs(name, assignments, preset)
    data = facet.compute(params, settings, preset_name, x, y, workers=workers)
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    facet.plot(data, output)
    print(facet.summary(data))
    print(f"wrote {output}")
    if json_path:
        write_json(jsonable({"scenario": name, **data}), json_path)
    return 0 if facet.passed(data) else 1


def run_own_sweep(name: str, param: str, facet: ParamSweep, values: Sequence[str], assignments: Mapping[str, str],
                  preset: str | None, json_path: str | None, *, resume: bool, workers: int) -> int:
    """``mjpoincare sweep SCENARIO --param NAME`` where the scenario has its own sweep of ``NAME``.

    The other inputs are resolved as a validation's (an assignment of ``param`` itself is left out: the values replace
    it), and the values are checked against ``param``'s declared range only, both before any simulation. The rows,
    one per value in increasing order, go into ``json_path`` after every job of the sweep, and ``resume`` skips the
    values that file holds.

    Args:
        name: the scenario.
        param: the swept parameter.
        facet: the scenario's sweep of it.
        values: the values as given (``--values``).
        assignments: ``--set`` parameters and settings.
        preset: the preset (None: the scenario's default).
        json_path: the results file (None: none; ``-``: stdout at the end).
        resume: keep the rows ``json_path`` holds of the same sweep.
        workers: processes the sweep's references may use (it may use more).

    Returns:
        The exit code: 0 when the sweep passes (:attr:`ParamSweep.passed`), 1 when not.
    """
    scenario, preset_name, params, settings = resolve_inputs(
        name, {k: v for k, v in assignments.items() if k != param}, preset)
    declared = next(p for p in scenario.params if p.name == param)
    points = sorted(float(declared.coerce(v)) for v in values)
    header = {"scenario": name, "param": param, "assignments": dict(assignments), "preset": preset_name}
    sweep = ResumableRows.open(header, json_path, param, points, resume=resume, restore=_null_as_nan)
    todo = sweep.todo
    start = time.perf_counter()
    jobs = facet.plan(params, settings, todo, workers=workers)
    plan_wall = time.perf_counter() - start
    rows = sweep.run(facet.compute, [(params, settings, preset_name, *job) for job in jobs], label=f"{param} sweep",
                     unit=param, describe=lambda new: f"{param} {new[0][param]:.4g}..{new[-1][param]:.4g}")
    summary = facet.summarize(params, rows)
    wall = time.perf_counter() - start
    print(facet.table(rows, summary))
    print(f"{len(todo)} {param} values run in {wall:.1f} s ({plan_wall:.1f} s of reference)")
    if json_path:
        write_json(jsonable({**header, "rows": rows, "summary": summary, "wall_s": wall}), json_path)
    return 0 if facet.passed(summary) else 1
