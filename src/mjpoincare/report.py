"""``validate --report DIR``: a self-contained HTML report (no network: images are embedded).

It shows the check table, the empirical return map (x_k+1 against x_k, analytic map drawn over it),
the fitted eigenvalues in the complex plane with the unit circle and the analytic values, the
basin map over the analytic regions, and the convergence (time against error) plot when a bench
result ``renders/bench-<scenario>.json`` exists. Plots use matplotlib's object API (no pyplot: the caller's
backend is left alone).
"""

from __future__ import annotations

import base64
import html
import io
import json
from pathlib import Path
from typing import Any

from matplotlib.figure import Figure

from mjpoincare.result import write_text

COLORS = {"rolling": "tab:green", "standing": "tab:blue", "runaway": "tab:red", "flight": "tab:orange",
          "undetermined": "tab:gray"}


def _png(fig: Figure) -> str:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110)
    return base64.b64encode(buffer.getvalue()).decode()


def return_map_figure(plot: dict[str, Any]) -> str:
    """x_k+1 against x_k from the simulation, with the analytic map and the diagonal; ``plot`` is the JSON form of a
    :class:`mjpoincare.scenarios.base.ReturnMapPlot`."""
    fig = Figure(figsize=(5, 4))
    ax = fig.subplots()
    ax.plot(plot["analytic_x"], plot["analytic_y"], "k-", lw=1, label="analytic map")
    ax.plot(plot["analytic_x"], plot["analytic_x"], ":", color="gray", lw=1, label="x_k+1 = x_k")
    ax.plot(plot["x"], plot["x_next"], "o", ms=4, color="tab:red", label="MuJoCo samples")
    ax.set_xlabel(f"x_k: {plot['label']}")
    ax.set_ylabel("x_k+1")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _png(fig)


def eigenvalue_figure(fit: dict[str, Any], analytic: list[Any]) -> str:
    """Fitted eigenvalues (with bootstrap error bars) and analytic ones in the complex plane."""
    import numpy as np

    fig = Figure(figsize=(4.5, 4.5))
    ax = fig.subplots()
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(t), np.sin(t), color="gray", lw=1)
    for (re, im), (sre, sim) in zip(fit["eigenvalues"], fit["eigenvalue_std"], strict=True):
        ax.errorbar(re, im, xerr=sre or 0, yerr=sim or 0, fmt="o", color="tab:red")
    for value in analytic:
        re, im = (value, 0.0) if isinstance(value, int | float) else value
        ax.plot(re, im, "kx", ms=9)
    ax.set_aspect("equal")
    ax.set_xlim(-1.2, 1.2)
    ax.set_ylim(-1.2, 1.2)
    ax.set_title("eigenvalues: MuJoCo fit (o), analytic (x)", fontsize=9)
    fig.tight_layout()
    return _png(fig)


def basin_figure(table: list[dict[str, Any]], bands: list[list[Any]]) -> str:
    """Simulated end states over the analytic regions of attraction (shaded bands)."""
    fig = Figure(figsize=(8, 2.2))
    ax = fig.subplots()
    for lo, hi, outcome in bands:
        ax.axvspan(lo, hi, color=COLORS[outcome], alpha=0.15)
    for row in table:
        marker = "o" if row["judged"] else "s"
        ax.plot(row["omega0"], 0, marker, color=COLORS.get(row["simulated"], "k"), ms=8, mfc="none"
                if not row["judged"] else COLORS.get(row["simulated"], "k"))
    ax.set_yticks([])
    ax.set_xlabel("initial post-impact speed (rad/s); shading: analytic basin, marker: MuJoCo end state "
                  "(hollow = not judged)", fontsize=8)
    fig.tight_layout()
    return _png(fig)


def bench_figure(bench: dict[str, Any]) -> str:
    """Wall time against the first accuracy check's error, from a saved bench result."""
    rows = bench["rows"]
    key = next(k for k in rows[0] if k.endswith("_error"))
    fig = Figure(figsize=(6, 4))
    ax = fig.subplots()
    ax.loglog([r["wall_s"] for r in rows], [r[key] for r in rows], "o")
    for r in rows:
        ax.annotate(r["config"], (r["wall_s"], r[key]), fontsize=6)
    ax.set_xlabel("wall time, s")
    ax.set_ylabel(key)
    fig.tight_layout()
    return _png(fig)


def write_report(result: dict[str, Any], directory: str) -> Path:
    """Write ``DIR/<scenario>.html`` and ``DIR/<scenario>.json``; returns the HTML path."""
    out = Path(directory)
    name = result["scenario"]
    rows = "".join(
        f"<tr class={'pass' if c['passed'] else 'fail'}><td>{html.escape(c['name'])}</td><td>{_cell(c['analytic'])}"
        f"</td><td>{_cell(c['simulated'])}</td><td>{_cell(c['error'])}</td><td>{c['tolerance']:.3g}</td>"
        f"<td>{'PASS' if c['passed'] else 'FAIL'}</td><td class=why>{html.escape(c['why'])}</td></tr>"
        for c in result["checks"])
    images = []
    if "return_map" in result:
        images.append(("Empirical return map", return_map_figure(result["return_map"])))
        images.append(("Eigenvalues", eigenvalue_figure(result["fit"], result["return_map"]["analytic_eigenvalues"])))
    if "basins" in result and "basin_bands" in result:
        images.append(("Regions of attraction", basin_figure(result["basins"], result["basin_bands"])))
    bench_path = Path("renders") / f"bench-{name}.json"
    if bench_path.is_file():
        images.append(("Time against error (from mjpoincare bench)", bench_figure(json.loads(bench_path.read_text()))))
    figures = "".join(f"<h2>{html.escape(t)}</h2><img alt='{html.escape(t)}' src='data:image/png;base64,{b}'>"
                      for t, b in images)
    params = ", ".join(f"{k}={v}" for k, v in result["params"].items())
    timing = result["timing"]
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>mjpoincare: {html.escape(name)}</title>
<style>body{{font-family:sans-serif;max-width:1000px;margin:2em auto}}
td,th{{padding:3px 8px;border-bottom:1px solid #ddd}} tr.fail td{{background:#fdd}}
td.why{{font-size:80%;color:#555}}</style></head><body>
<h1>{html.escape(name)}: {'all checks passed' if result['passed'] else 'FAILED'}</h1>
<p>preset {html.escape(result['preset'])}; {html.escape(params)}; MuJoCo {html.escape(result['mujoco_version'])};
wall {timing['wall_s']:.2f} s, {timing['steps_per_s']:.3g} steps/s</p>
<table id=checks><tr><th>check</th><th>analytic</th><th>simulated</th><th>error</th><th>tolerance</th><th>verdict</th>
<th>why this tolerance</th></tr>{rows}</table>
<p>MuJoCo warnings: {html.escape('; '.join(result['warnings']) or 'none')}</p>{figures}</body></html>
"""
    target = out / f"{name}.html"
    write_text(page, str(target))
    write_text(json.dumps(result, indent=2) + "\n", str(out / f"{name}.json"))
    return target


def _cell(value: Any) -> str:
    if isinstance(value, list):
        return html.escape(", ".join(_cell(v) for v in value))
    if isinstance(value, float):
        return f"{value:.6g}"
    return html.escape(str(value))
