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

from analysis.checks import jsonable
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


def parse_grid(text: str) -> tuple[np.ndarray, np.ndarray]:
    """``x=-1.5:0.5:30,y=0.05:1:30`` -> the two axes (x = l0/delta, y = 1/delta^2 for the slotted skate)."""
    axes: dict[str, np.ndarray] = {}
    for part in text.split(","):
        name, _, spec = part.partition("=")
        values = parse_values(spec)
        axes[name.strip()] = np.array([float(v) for v in values])
    if set(axes) != {"x", "y"} or min(len(a) for a in axes.values()) < 2:
        raise ParameterError(f"--grid expects x=START:STOP:N,y=START:STOP:N with N >= 2 (got {text!r})")
    if axes["y"].min() <= 0:
        raise ParameterError(f"--grid y = 1/delta^2 must be > 0 (got {text!r})")
    return axes["x"], axes["y"]


def run_regions(name: str, grid: str, assignments: Mapping[str, str], preset: str | None, json_path: str | None,
                output: str) -> int:
    """Stability regions on a grid from simulation against the analytic ones, with a PNG (slotted skate)."""
    from mjpoincare.scenarios import slotted_skate as skate

    if name != "slotted-skate":
        raise ParameterError(f"--grid maps stability regions of slotted-skate only (got {name!r})")
    x, y = parse_grid(grid)
    _, _, params, settings = resolve_inputs(name, assignments, preset)
    result = skate.region_map(params, settings, x, y)
    simulated, analytic = skate.region_classes(result["measured"]), skate.region_classes(result["analytic"])
    edge = skate.boundary_cells(analytic, result["analytic"])
    judged = ~edge
    mismatch = (simulated != analytic) & judged
    lines = [f"{name}: {x.size}x{y.size} grid (l0/delta, 1/delta^2), forward and backward, "
             f"{result['steps']:.3g} steps in {result['wall_s']:.1f} s of rollout"]
    for i, label in enumerate(("forward", "backward")):
        lines.append(f"  {label}: {int(mismatch[i].sum())} mismatches in {int(judged[i].sum())} cells off the analytic "
                     f"boundaries ({int((simulated[i] != analytic[i]).sum())} in all {x.size * y.size}); "
                     f"max |sigma4 error| {np.nanmax(np.abs(result['measured'][i] - result['analytic'][i])):.2e}")
    print("\n".join(lines))
    _plot_regions(result, simulated, analytic, output.format(scenario=name))
    if json_path:
        write_json(jsonable({"scenario": name, "x": x, "y": y, "simulated": simulated, "analytic": analytic,
                             "boundary": edge, "sigma4_measured": result["measured"],
                             "sigma4_analytic": result["analytic"], "mismatches": int(mismatch.sum())}), json_path)
    return 0 if not mismatch.any() and result["diverged"] == 0 else 1


def _plot_regions(result: dict[str, Any], simulated: np.ndarray, analytic: np.ndarray, path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from pathlib import Path

    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    cmap = ListedColormap(["#d9d9d9", "#f4a6a6", "#9fd49f", "#7fb3e6", "#f7d07a"])  # nan, unstable, stable, wobble..
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    x, y = result["x"], result["y"]
    for i, (ax, label) in enumerate(zip(axes, ("V > 0 (forward)", "V < 0 (backward)"), strict=True)):
        ax.pcolormesh(x, y, simulated[i] + 1, cmap=cmap, vmin=0, vmax=4, shading="nearest")
        sig = result["analytic"][i]
        ax.contour(x, y, np.abs(sig), levels=[1.0], colors="k", linewidths=1.2)
        ax.contour(x, y, sig, levels=[0.0], colors="k", linestyles="--", linewidths=1.0)
        bad = (simulated[i] != analytic[i])
        yy, xx = np.nonzero(bad)
        ax.plot(x[xx], y[yy], "kx", ms=4)
        ax.set_title(f"{label}: simulated classes, analytic |sigma4| = 1 (solid), sigma4 = 0 (dashed)", fontsize=8)
        ax.set_xlabel("l0 / delta")
    axes[0].set_ylabel("1 / delta^2 (rho = 1)")
    fig.text(0.5, 0.01, "red: unstable, green: stable, blue: stable wobble, yellow: unstable wobble; x: mismatch",
             ha="center", fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
