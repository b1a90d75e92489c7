"""``mjpoincare sweep slotted-skate --grid x=START:STOP:N,y=START:STOP:N``: stability regions of straight motion over
(L0/Delta, 1/Delta^2), the axes of Coleman & Holmes 1999 Fig. 2, simulated against the analytic sigma4 (3.10)
(PNG + JSON)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.stability_classes import boundary_cells, region_classes
from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.params import ParameterError, parse_values
from mjpoincare.result import write_json
from mjpoincare.scenarios import slotted_skate as skate
from mjpoincare.scenarios.base import Values
from mjpoincare.scenarios.slotted_skate_pegs import PegController
from mjpoincare.settings import rollout_options
from mjpoincare.simulate import event_rollout, initial_states
from mjpoincare.validation import resolve_inputs


def parse_grid(text: str) -> tuple[np.ndarray, np.ndarray]:
    """``x=-1.5:0.5:30,y=0.05:1:30`` -> the two axes (x = l0/delta, y = 1/delta^2)."""
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


def region_map(p: Values, s: Values, x: np.ndarray, y: np.ndarray, impacts: int = 3,
               omega0: float = 0.01) -> dict[str, np.ndarray]:
    """Stability of straight motion over a grid of (L0/Delta, 1/Delta^2) (the paper's Fig. 2 axes), simulated.

    Every grid point runs forward and backward (V0 = +-1, Omega0 = ``omega0``, rho = 1) in ONE batched
    event rollout (each trajectory with its own slot ends); sigma4 is measured as H_k+1/H_k of the first two
    stances that keep the initial direction (an unstable motion may later reverse and settle the other way).
    Returns the measured and analytic (3.10) sigma4 arrays, shape (2, len(y), len(x)),
    index 0 forward and 1 backward.
    """
    X, Y = np.meshgrid(x, y)
    delta = 1.0 / np.sqrt(Y.ravel())
    l0 = X.ravel() * delta
    cells = l0.size
    V = np.concatenate([np.ones(cells), -np.ones(cells)])
    l0_all, delta_all = np.tile(l0, 2), np.tile(delta, 2)
    base = {**p, "rho": 1.0, "mass": 1.0, "V0": 1.0, "heading0": 0.0}
    model = skate.build(base, s)
    entry = np.where(V > 0, l0_all, l0_all + delta_all)
    controller = PegController(model, base, entry, (l0_all, l0_all + delta_all))
    start = initial_states(model, np.stack([np.zeros_like(V), entry, np.zeros_like(V)], 1),
                           np.stack([np.full_like(V, omega0), V, np.zeros_like(V)], 1))
    seconds = 1.2 * (impacts + 1) * float(delta_all.max())
    nstep = math.ceil(seconds / model.opt.timestep)
    report = event_rollout(model, start, nstep, controller, **rollout_options(s),
                           chunk_steps=max(10, min(500, nstep // 10)))
    measured = np.full(2 * cells, np.nan)
    for b, samples in enumerate(controller.samples):
        ok = [(a[3], c[3]) for a, c in itertools.pairwise(samples)
              if a[0] == c[0] == entry[b] and abs(a[3]) > 1e-12]
        if ok:
            measured[b] = ok[0][1] / ok[0][0]
    analytic = np.array([[theory.sigma4(theory.SlottedSkate(L0=a, Delta=d), forward) for a, d in zip(l0, delta,
                                                                                                      strict=True)]
                         for forward in (True, False)])
    return {"x": x, "y": y, "measured": measured.reshape(2, len(y), len(x)),
            "analytic": analytic.reshape(2, len(y), len(x)), "steps": float(report.steps),
            "wall_s": report.wall_s, "diverged": int(report.diverged.sum())}


def run_regions(grid: str, assignments: Mapping[str, str], preset: str | None, json_path: str | None,
                output: str) -> int:
    """Stability regions on a grid from simulation against the analytic ones, with a PNG; exit 0 when every cell off
    the analytic boundaries has the analytic class and no trajectory diverged."""
    name = skate.SLOTTED_SKATE.name
    x, y = parse_grid(grid)
    _, _, params, settings = resolve_inputs(name, assignments, preset)
    result = region_map(params, settings, x, y)
    simulated, analytic = region_classes(result["measured"]), region_classes(result["analytic"])
    edge = boundary_cells(analytic, result["analytic"])
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
