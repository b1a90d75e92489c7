"""``mjpoincare bench SCENARIO --paths``: the wall time against the error of the suite's paths to an accurate value.

Three paths, each a whole validation of the scenario (the pipeline users run):

* ``fast``: the fast preset;
* ``accurate``: the accurate preset (the path the accurate verdicts take);
* ``fast + Richardson``: the fast preset and its two coarser grids, 2h and 4h (``validate --extrapolate``,
  :mod:`mjpoincare.commands.extrapolate`; Celik et al. 2008, Roache 1998): a component's Richardson value where its
  three-grid order is clean, its fast value elsewhere.

For each accuracy check's scalar components the absolute error against the analytic value, and the wall time of the
path (for the Richardson path: all three grids), go into one table and one plot. The plot shows where the cheap path
reaches the accurate preset's error, and at what cost; it judges nothing. ``--compare`` draws another build's paths
(its ``--json``: an earlier commit, another MuJoCo) beside these, dashed and labelled with that build's commit.
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
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import write_bytes, write_json
from mjpoincare.core.stamp import git_state

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
    accuracy = scenario.bench_checks
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
    sha, dirty = git_state()
    build = f"{sha[:7]}{'+' if dirty else ''}" if sha else "this build"
    return {"scenario": name, "mujoco_version": mujoco.__version__, "build": build, "accuracy": list(accuracy),
            "paths": rows}


def load_compare(path: str, name: str) -> dict[str, Any]:
    """Another build's ``bench NAME --paths --json`` to draw beside this one; refused (before any run) when it is not
    one, or is of another scenario."""
    import json

    try:
        data = json.loads(Path(path).read_text())
    except (OSError, ValueError) as err:
        raise ParameterError(f"--compare {path}: not a readable bench --paths JSON ({err})") from None
    if not isinstance(data, dict) or "paths" not in data:
        raise ParameterError(f"--compare {path}: not a bench --paths JSON (no 'paths')")
    if data.get("scenario") != name:
        raise ParameterError(f"--compare {path} is of {data.get('scenario')!r}, not {name!r}")
    return data


def format_table(data: Mapping[str, Any]) -> str:
    """One row per path: wall time, every check passing, each accuracy component's error (``*`` where the
    Richardson path kept the fast value: no clean order)."""
    rows = data["paths"]
    keys = list(rows[0]["errors"])
    return markdown_table(
        ("path", "wall s", "checks", *(f"{k} error" for k in keys)),
        [(r["path"], f"{r['wall_s']:.2f}", "pass" if r["passed"] else "FAIL",
          *(f"{r['errors'].get(k, math.nan):.2e}{'*' if k in r['not_clean'] else ''}" for k in keys)) for r in rows])


def plot(data: Mapping[str, Any], path: str, compare: Mapping[str, Any] | None = None) -> None:
    """Each accuracy component's error against each path's wall time (log-log), one line per component through the
    three paths in order of wall time, on one figure; ``compare``'s the same, dashed, in the same colour per
    component."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.5, 5))
    ax = fig.subplots()
    markers = dict(zip(PATHS, ("o", "s", "^"), strict=True))
    colours: dict[str, Any] = {}
    for build, style in ((data, "-"), *(((compare, "--"),) if compare is not None else ())):
        rows = sorted(build["paths"], key=lambda r: r["wall_s"])
        for key in data["paths"][0]["errors"]:
            walls = [r["wall_s"] for r in rows]
            errors = [max(r["errors"].get(key, math.nan), 1e-17) for r in rows]
            line, = ax.plot(walls, errors, style, lw=0.8, alpha=0.6, color=colours.get(key))
            colours.setdefault(key, line.get_color())
            for r, w, e in zip(rows, walls, errors, strict=True):
                ax.plot([w], [e], markers[r["path"]], color=colours[key],
                        mfc="none" if key in r["not_clean"] else None)
            if style == "-":
                ax.annotate(key, (walls[0], errors[0]), fontsize=6, xytext=(3, 3), textcoords="offset points")
    for label, marker in markers.items():
        ax.plot([], [], marker, color="k", label=label)
    if compare is not None:
        ax.plot([], [], "-", color="k", label=f"{data.get('build', 'this build')} (solid)")
        ax.plot([], [], "--", color="k", label=f"{compare.get('build', 'compared build')} (dashed)")
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


def run_paths(name: str, assignments: Mapping[str, str], output: str, json_path: str | None,
              compare: str | None = None) -> int:
    """Measure the paths, print the table (and ``compare``'s, another build's JSON), write the PNG (and JSON);
    exit 0."""
    other = load_compare(compare, name) if compare else None
    data = measure_paths(name, assignments)
    print(f"{name}: the paths to an accurate value (error = |simulated - analytic| of each accuracy component; "
          "* no clean three-grid order, the fast value kept)")
    print(format_table(data))
    if other is not None:
        print(f"compared build {other.get('build', '(unnamed)')} (MuJoCo {other.get('mujoco_version')}):")
        print(format_table(other))
    plot(data, output.format(scenario=name), other)
    if json_path:
        write_json(jsonable(data), json_path.format(scenario=name))
    return 0
