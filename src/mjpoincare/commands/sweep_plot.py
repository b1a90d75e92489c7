"""The plot of a one-parameter sweep (``mjpoincare sweep SCENARIO --param NAME --values ... -o PNG``): each check's
error over the swept value against its tolerance, and the largest multiplier modulus, fitted beside analytic."""

from __future__ import annotations

import io
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mjpoincare.core.result import write_bytes


def sweep_png(rows: Sequence[Mapping[str, Any]], param: str, scenario: str) -> bytes:
    """Two panels over ``param``: every check's error (log scale, the checks with a positive error somewhere) with
    its tolerance dashed in the same colour, a failing point hollow; and abs(lambda)max fitted (points) beside the
    analytic one (line) where the runs have multipliers."""
    from matplotlib.figure import Figure

    x = np.array([r[param] for r in rows], float)
    names = list(dict.fromkeys(n for r in rows for n in r["errors"]))
    fig = Figure(figsize=(7.0, 6.4), dpi=110)
    ax, bx = fig.subplots(2, 1, sharex=True)
    colors = iter(_palette(len(names)))
    for name in names:
        err = np.array([math.nan if r["errors"].get(name) is None else r["errors"][name] for r in rows], float)
        if not np.any(err > 0):
            continue
        color = next(colors)
        failed = np.array([name in r.get("failed", []) for r in rows])
        ax.plot(x[~failed], err[~failed], "o-", color=color, ms=4, lw=1, label=name)
        if failed.any():
            ax.plot(x[failed], err[failed], "o", mfc="none", color=color, ms=7)
        tol = [r.get("tolerances", {}).get(name) for r in rows]
        if any(t is not None for t in tol):
            ax.plot(x, [math.nan if t is None else t for t in tol], "--", color=color, lw=0.8)
    ax.set_yscale("log")
    ax.set_ylabel("error (each check's own measure)")
    ax.set_title(f"{scenario}: sweep of {param} (dashed: tolerance; hollow: failed)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="best")
    fitted = np.array([r.get("fitted_max_modulus", math.nan) for r in rows], float)
    analytic = np.array([r.get("analytic_max_modulus", math.nan) for r in rows], float)
    bx.plot(x, analytic, "-", color="0.3", label="analytic")
    bx.plot(x, fitted, "o", color="tab:blue", label="fitted (MuJoCo)")
    bx.axhline(1.0, ls=":", color="0.5", lw=0.8)
    bx.set_ylabel("abs(lambda)max")
    bx.set_xlabel(param)
    bx.grid(True, alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


def _palette(n: int) -> list[str]:
    base = [f"C{i}" for i in range(10)]
    return [base[i % 10] for i in range(max(n, 1))]


def write_sweep_plot(rows: Sequence[Mapping[str, Any]], param: str, scenario: str, path: str) -> None:
    """Write :func:`sweep_png` to ``path`` (whole or not at all)."""
    write_bytes(sweep_png(rows, param, scenario), path)
