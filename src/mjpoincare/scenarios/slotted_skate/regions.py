"""``mjpoincare sweep slotted-skate --grid x=START:STOP:N,y=START:STOP:N``: stability regions of straight motion over
(L0/Delta, 1/Delta^2), the axes of Coleman & Holmes 1999 Fig. 2, simulated against the analytic sigma4 (3.10): the
scenario's :class:`~mjpoincare.scenarios.base.RegionMap` (:data:`REGION_MAP`)."""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from mjpoincare.analysis.stability_classes import boundary_cells, region_classes
from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.core.params import Param
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import RegionMap, Values
from mjpoincare.scenarios.slotted_skate.pegs import PegController, build
from mjpoincare.simulation.simulate import event_rollout, initial_states

#: The grid's axes (Coleman & Holmes 1999 Fig. 2; rho = 1).
AXES = (Param("x", 0.0, "l0/delta", float), Param("y", 1.0, "1/delta^2", float, 0.0, low_open=True))


def region_map(params: Values, settings: Values, x: np.ndarray, y: np.ndarray, impacts: int = 3,
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
    base = {**params, "rho": 1.0, "mass": 1.0, "V0": 1.0, "heading0": 0.0}
    model = build(base, settings)
    entry = np.where(V > 0, l0_all, l0_all + delta_all)
    controller = PegController(model, base, entry, (l0_all, l0_all + delta_all))
    start = initial_states(model, np.stack([np.zeros_like(V), entry, np.zeros_like(V)], 1),
                           np.stack([np.full_like(V, omega0), V, np.zeros_like(V)], 1))
    seconds = 1.2 * (impacts + 1) * float(delta_all.max())
    nstep = math.ceil(seconds / model.opt.timestep)
    report = event_rollout(model, start, nstep, controller, **rollout_options(settings),
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


def compute(params: Values, settings: Values, preset: str, x: np.ndarray, y: np.ndarray, *, workers: int) -> dict[str,
                                                                                                                  Any]:
    """The stability classes of straight motion on the grid, simulated (:func:`region_map`) and analytic (3.11-3.12).

    Args:
        p: the scenario's parameters (rho, mass, V0 and heading0 are replaced: rho = 1, the paper's Fig. 2).
        s: the simulator settings.
        preset: not used (the classes are judged against the analytic ones, not a preset's tolerance).
        x: l0/delta, shape (nx,).
        y: 1/delta^2, shape (ny,).
        workers: not used (the whole grid is one batched rollout).

    Returns:
        ``x``, ``y``; ``simulated`` and ``analytic`` classes (:func:`region_classes`), ``boundary`` (cells on an
        analytic boundary, not judged), ``sigma4_measured`` and ``sigma4_analytic``, each shape (2, ny, nx) with
        index 0 forward and 1 backward; ``mismatches`` (judged cells whose classes differ), and the rollout's
        ``steps``, ``rollout_wall_s`` and ``diverged`` trajectories.
    """
    result = region_map(params, settings, x, y)
    simulated, analytic = region_classes(result["measured"]), region_classes(result["analytic"])
    edge = boundary_cells(analytic, result["analytic"])
    return {"x": x, "y": y, "simulated": simulated, "analytic": analytic, "boundary": edge,
            "sigma4_measured": result["measured"], "sigma4_analytic": result["analytic"],
            "mismatches": int(((simulated != analytic) & ~edge).sum()), "steps": result["steps"],
            "rollout_wall_s": result["wall_s"], "diverged": result["diverged"]}


def summary(data: dict[str, Any]) -> str:
    """Per direction: the mismatches off the analytic boundaries and in all cells, and the largest sigma4 error."""
    x, y, simulated, analytic = data["x"], data["y"], data["simulated"], data["analytic"]
    judged = ~data["boundary"]
    mismatch = (simulated != analytic) & judged
    lines = [f"slotted-skate: {x.size}x{y.size} grid (l0/delta, 1/delta^2), forward and backward, "
             f"{data['steps']:.3g} steps in {data['rollout_wall_s']:.1f} s of rollout"]
    for i, label in enumerate(("forward", "backward")):
        error = np.nanmax(np.abs(data["sigma4_measured"][i] - data["sigma4_analytic"][i]))
        lines.append(f"  {label}: {int(mismatch[i].sum())} mismatches in {int(judged[i].sum())} cells off the analytic "
                     f"boundaries ({int((simulated[i] != analytic[i]).sum())} in all {x.size * y.size}); "
                     f"max |sigma4 error| {error:.2e}")
    return "\n".join(lines)


def passed(data: dict[str, Any]) -> bool:
    """Every cell off the analytic boundaries has the analytic class, and no trajectory diverged."""
    return data["mismatches"] == 0 and data["diverged"] == 0


def plot(data: dict[str, Any], path: str) -> None:
    """Both directions' simulated classes under the analytic boundaries |sigma4| = 1 and sigma4 = 0, mismatches
    marked."""
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure

    cmap = ListedColormap(["#d9d9d9", "#f4a6a6", "#9fd49f", "#7fb3e6", "#f7d07a"])  # nan, unstable, stable, wobble..
    fig = Figure(figsize=(11, 4.5))
    axes = fig.subplots(1, 2, sharey=True)
    x, y, simulated, analytic = data["x"], data["y"], data["simulated"], data["analytic"]
    for i, (ax, label) in enumerate(zip(axes, ("V > 0 (forward)", "V < 0 (backward)"), strict=True)):
        ax.pcolormesh(x, y, simulated[i] + 1, cmap=cmap, vmin=0, vmax=4, shading="nearest")
        sig = data["sigma4_analytic"][i]
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
    fig.savefig(path, dpi=110)


REGION_MAP = RegionMap(axes=AXES, output="renders/regions-{scenario}.png", compute=compute, summary=summary,
                       plot=plot, passed=passed)
