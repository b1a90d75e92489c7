"""``mjpoincare sweep slotted-skate --grid x=START:STOP:N,y=START:STOP:N``: stability regions of straight motion over
(L0/Delta, 1/Delta^2), the axes of Coleman & Holmes 1999 Fig. 2, simulated against the analytic sigma4 (3.10)
(PNG + JSON)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import jsonable
from mjpoincare.params import ParameterError
from mjpoincare.result import write_json
from mjpoincare.scenarios import slotted_skate as skate
from mjpoincare.validation import resolve_inputs


def parse_grid(text: str) -> tuple[np.ndarray, np.ndarray]:
    """``x=-1.5:0.5:30,y=0.05:1:30`` -> the two axes (x = l0/delta, y = 1/delta^2)."""
    from mjpoincare.sweep import parse_values

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


def run_regions(grid: str, assignments: Mapping[str, str], preset: str | None, json_path: str | None,
                output: str) -> int:
    """Stability regions on a grid from simulation against the analytic ones, with a PNG; exit 0 when every cell off
    the analytic boundaries has the analytic class and no trajectory diverged."""
    name = skate.SLOTTED_SKATE.name
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
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure

    cmap = ListedColormap(["#d9d9d9", "#f4a6a6", "#9fd49f", "#7fb3e6", "#f7d07a"])  # nan, unstable, stable, wobble..
    fig = Figure(figsize=(11, 4.5))
    axes = fig.subplots(1, 2, sharey=True)
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
