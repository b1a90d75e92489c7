"""The figures of ``mjpoincare reproduce -o DIR``: each paper figure's theory curve beside MuJoCo's points, with their
spread as error bars, in the paper's axes and units (one PNG per figure result, named by its id)."""

from __future__ import annotations

import textwrap
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mjpoincare.core.result import write_bytes
from mjpoincare.scenarios.paper_results import Curve, PaperResult, Runner


def plot_figures(chosen: Iterable[tuple[str, PaperResult]], results: Sequence[Mapping[str, Any]], folder: Path, *,
                 runner: Callable[[str, str], Runner]) -> list[str]:
    """Write a PNG per figure result held in ``results`` (``runner(scenario, preset)`` gives each theory curve its
    scenario's parameters); return their paths."""
    rows = {r["id"]: r for r in results if r.get("figure")}
    paths = []
    for scenario, pr in chosen:
        if isinstance(pr.run, Curve) and pr.id in rows:
            path = str(folder / f"{pr.id}.png")
            write_bytes(figure_png(pr, rows[pr.id], runner(scenario, rows[pr.id]["preset"])), path)
            paths.append(path)
    return paths


def figure_png(pr: PaperResult, row: Mapping[str, Any], runner: Runner) -> bytes:
    """One figure: the theory's curve (a line on a dense grid), MuJoCo's points with error bars, and the
    reference lines, titled with the paper's location."""
    import io

    from matplotlib.figure import Figure

    run = pr.run
    assert isinstance(run, Curve)
    fig = row["figure"]
    x = np.asarray(fig["x"], float)
    pad = 0.04 * (x.max() - x.min())
    dense = np.linspace(x.min() - pad, x.max() + pad, run.dense)
    y_theory = run.theory(dense, runner)
    y = np.asarray([np.nan if v is None else v for v in fig["mujoco"]], float)
    err = np.asarray([0.0 if s is None else s for s in fig["spread"]], float)
    ok = np.asarray(fig["passed"], bool)
    f = Figure(figsize=(6.4, 4.2), dpi=110)
    ax = f.add_subplot()
    ax.plot(dense, y_theory, "-", color="0.25", lw=1.4, label="theory (suite's derivation)")
    ax.errorbar(x[ok], y[ok], yerr=err[ok], fmt="o", ms=4.5, color="tab:blue", capsize=3,
                label=f"MuJoCo ({row['preset']} preset), within tolerance")
    if (~ok).any():
        ax.errorbar(x[~ok], y[~ok], yerr=err[~ok], fmt="s", ms=5, color="tab:red", capsize=3,
                    label="MuJoCo, outside tolerance")
    missing = x[~np.isfinite(y)]
    if missing.size:
        ax.annotate("no MuJoCo value at x = " + ", ".join(f"{v:g}" for v in missing), (0.02, 0.02),
                    xycoords="axes fraction", fontsize=8, color="tab:red")
    for label, level in run.lines.items():
        ax.axhline(level, ls="--", lw=0.9, color="0.5")
        ax.annotate(label, (dense[0], level), xytext=(3, 3), textcoords="offset points", fontsize=8, color="0.35")
    ax.set_xlabel(run.x_label)
    ax.set_ylabel(run.y_label)
    ax.set_title(textwrap.fill(f"{pr.paper} {pr.location}: {pr.quantity}", 90), fontsize=8)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    f.tight_layout()
    buf = io.BytesIO()
    f.savefig(buf, format="png")
    return buf.getvalue()
