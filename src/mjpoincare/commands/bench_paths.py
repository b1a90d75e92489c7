"""``mjpoincare bench SCENARIO --paths``: the wall time against the error of the suite's paths to an accurate value.

Three paths, each a whole validation of the scenario (the pipeline users run):

* ``fast``: the fast preset;
* ``accurate``: the accurate preset (the path the accurate verdicts take);
* ``fast + Richardson``: the fast preset and its two coarser grids, 2h and 4h (``validate --extrapolate``,
  :mod:`mjpoincare.commands.extrapolate`; Celik et al. 2008, Roache 1998): a component's Richardson value where its
  three-grid order is clean, its fast value elsewhere.

For each accuracy check's scalar components the absolute error against the analytic value, and the wall time of the
path (for the Richardson path: all three grids), go into one table and one plot. The plot shows where the cheap path
reaches the accurate preset's error, and at what cost; it judges nothing.
"""

from __future__ import annotations

import io
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import mujoco

from mjpoincare import scenarios
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.converge import components
from mjpoincare.commands.extrapolate import coarse_grids, extrapolate
from mjpoincare.commands.validation import run_steps, run_validation
from mjpoincare.core import progress
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.result import write_bytes, write_json

#: The paths, in the order they are run and drawn.
PATHS = ("fast", "accurate", "fast + Richardson")


def _check_of(component: str) -> str:
    """The check a scalar component (``name``, ``name[i]``, ``name.re``) belongs to."""
    return component.split("[")[0].split(".")[0]


def _accuracy_components(values: Mapping[str, list[float]], accuracy: tuple[str, ...]) -> dict[str, float]:
    """|simulated - analytic| of each scalar component of the accuracy checks."""
    return {key: abs(float(s) - float(a)) for key, (a, s) in values.items() if _check_of(key) in accuracy}


def measure_paths(name: str, assignments: Mapping[str, str]) -> dict[str, Any]:
    """Run the three :data:`PATHS` of scenario ``name``: per path its wall time (s), whether every check passed
    (the Richardson path: the fast run's checks, which extrapolation never changes), and per accuracy component its
    absolute error; the Richardson path also names the components without a clean order (their fast error is
    kept). Bad input raises before any run."""
    scenario = scenarios.get(name)
    accuracy = scenario.accuracy_checks
    grids = coarse_grids(name, assignments, "fast")
    steps = sum(run_steps(name, {**assignments, **grid}, "fast") for grid in ({}, *grids)) + run_steps(
        name, assignments, "accurate")
    refuse_long(steps, f"bench {name} --paths (3 paths)", allow=False, remedy="raise timestep")
    rows: list[dict[str, Any]] = []
    with progress.bar(len(PATHS), f"bench {name} --paths", unit="path") as bar:
        runs = {}
        for preset in ("fast", "accurate"):
            runs[preset] = result = run_validation(name, assignments, preset)
            values, _ = components(result.checks)
            rows.append({"path": preset, "wall_s": result.timing["wall_s"], "passed": result.passed,
                         "errors": _accuracy_components(values, accuracy), "not_clean": []})
            bar.update(1)
        fast = runs["fast"]
        entry = extrapolate(name, assignments, "fast", 0, fast.checks, fast.timing["wall_s"])
        errors, not_clean = {}, []
        for comp in entry["components"]:
            if _check_of(comp["component"]) not in accuracy:
                continue
            clean = math.isfinite(comp["error_extrapolated"])
            errors[comp["component"]] = comp["error_extrapolated"] if clean else comp["error_plain"]
            if not clean:
                not_clean.append(comp["component"])
        rows.append({"path": PATHS[2], "wall_s": entry["wall_s"], "passed": fast.passed, "errors": errors,
                     "not_clean": not_clean})
        bar.update(1)
    return {"scenario": name, "mujoco_version": mujoco.__version__, "accuracy": list(accuracy), "paths": rows}


def format_table(data: Mapping[str, Any]) -> str:
    """One row per path: wall time, every check passing, each accuracy component's error (``*`` where the
    Richardson path kept the fast value: no clean order)."""
    rows = data["paths"]
    keys = list(rows[0]["errors"])
    return markdown_table(
        ("path", "wall s", "checks", *(f"{k} error" for k in keys)),
        [(r["path"], f"{r['wall_s']:.2f}", "pass" if r["passed"] else "FAIL",
          *(f"{r['errors'].get(k, math.nan):.2e}{'*' if k in r['not_clean'] else ''}" for k in keys)) for r in rows])


def plot(data: Mapping[str, Any], path: str) -> None:
    """Each accuracy component's error against each path's wall time (log-log), one line per component through the
    three paths in order of wall time, on one figure."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 4.5))
    ax = fig.subplots()
    rows = data["paths"]
    markers = dict(zip(PATHS, ("o", "s", "^"), strict=True))
    rows = sorted(rows, key=lambda r: r["wall_s"])
    for key in rows[0]["errors"]:
        walls = [r["wall_s"] for r in rows]
        errors = [max(r["errors"].get(key, math.nan), 1e-17) for r in rows]
        line, = ax.plot(walls, errors, "-", lw=0.8, alpha=0.6)
        for r, w, e in zip(rows, walls, errors, strict=True):
            ax.plot([w], [e], markers[r["path"]], color=line.get_color(), mfc="none" if key in r["not_clean"] else None)
        ax.annotate(key, (walls[0], errors[0]), fontsize=6, xytext=(3, 3), textcoords="offset points")
    for label, marker in markers.items():
        ax.plot([], [], marker, color="k", label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the path, s (2 threads)")
    ax.set_ylabel("|simulated - analytic| (open: no clean order, fast value kept)")
    ax.set_title(f"{data['scenario']}: the paths to an accurate value (MuJoCo {data['mujoco_version']})", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    buffer = io.BytesIO()
    fig.savefig(buffer, format=Path(path).suffix.lstrip(".").lower(), dpi=120)
    write_bytes(buffer.getvalue(), path)


def run_paths(name: str, assignments: Mapping[str, str], output: str, json_path: str | None) -> int:
    """Measure the paths, print the table, write the PNG (and JSON); exit 0."""
    data = measure_paths(name, assignments)
    print(f"{name}: the paths to an accurate value (error = |simulated - analytic| of each accuracy component; "
          "* no clean three-grid order, the fast value kept)")
    print(format_table(data))
    plot(data, output.format(scenario=name))
    if json_path:
        write_json(jsonable(data), json_path.format(scenario=name))
    return 0
