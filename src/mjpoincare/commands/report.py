"""``validate --report DIR``: a self-contained HTML report (no network: images are embedded).

Each scenario page shows the check table, a still of the model (rendered by the caller: this module only draws
data), the empirical return map (x_k+1 against x_k, analytic map drawn over it) or, for a map with no 1-D analytic
form, each section coordinate's distance to the analytic fixed point against the step, the fitted eigenvalues in the
complex plane with their bootstrap clouds, the unit circle and the analytic values, the basin map over the analytic
regions, and the convergence (time against error) plot when a bench result ``renders/bench-<scenario>.json``
exists. Every report also gets ``DIR/index.html`` (one scenario or several): each scenario's verdict and its checks'
verdicts.
Plots use matplotlib's object API (no pyplot: the caller's backend is left alone).
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from mjpoincare.core.result import write_text

COLORS = {"rolling": "tab:green", "standing": "tab:blue", "runaway": "tab:red", "flight": "tab:orange",
          "undetermined": "tab:gray"}
STYLE = """body{font-family:sans-serif;max-width:1000px;margin:2em auto}
td,th{padding:3px 8px;border-bottom:1px solid #ddd} tr.fail td{background:#fdd}
td.why{font-size:80%;color:#555} img.still{border:1px solid #ccc}
span.v{display:inline-block;margin:1px 2px;padding:0 4px;border-radius:3px;font-size:85%}
span.pass{background:#dfd} span.fail{background:#fbb}"""


def _png(fig: Figure) -> str:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110)
    return base64.b64encode(buffer.getvalue()).decode()


def _floats(values: Any) -> np.ndarray:
    """A JSON array (None for NaN) as floats."""
    return np.array(values if values is not None else [], dtype=float)


def _complex(value: Any) -> complex:
    """A JSON number or ``[re, im]`` (None: NaN) as a complex number."""
    if isinstance(value, list):
        re, im = (np.nan if v is None else v for v in value)
        return complex(re, im)
    return complex(np.nan if value is None else value, 0.0)


def has_analytic_map(plot: dict[str, Any]) -> bool:
    """The return map has a 1-D analytic map to draw (not all NaN)."""
    return bool(np.isfinite(_floats(plot["analytic_y"])).any())


def return_map_figure(plot: dict[str, Any]) -> str:
    """x_k+1 against x_k from the simulation, with the analytic map (where it has one) and the diagonal; ``plot`` is
    the JSON form of a :class:`mjpoincare.scenarios.base.ReturnMapPlot`."""
    fig = Figure(figsize=(5, 4))
    ax = fig.subplots()
    if has_analytic_map(plot):
        ax.plot(plot["analytic_x"], _floats(plot["analytic_y"]), "k-", lw=1, label="analytic map")
    ax.plot(plot["analytic_x"], plot["analytic_x"], ":", color="gray", lw=1, label="x_k+1 = x_k")
    ax.plot(plot["x"], plot["x_next"], "o", ms=4, color="tab:red", label="MuJoCo samples")
    ax.set_xlabel(f"x_k: {plot['label']}")
    ax.set_ylabel("x_k+1")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _png(fig)


def section_convergence_figure(conv: dict[str, Any], fitted: list[Any] | None, analytic_eigenvalues: list[Any]
                               ) -> str:
    """Per section coordinate, |x_k - x*| against the step k (log scale) of each sampled trajectory, x* the analytic
    fixed point; with the fitted fixed point's distance from x* (dashed) and the analytic rate |lambda|max^k.

    ``conv``: ``labels`` (one per coordinate), ``fixed_point`` (analytic x*) and ``sequences`` (per trajectory, its
    consecutive section samples); ``fitted``: the fit's fixed point (None: not drawn).
    """
    star = _floats(conv["fixed_point"])
    sequences = [np.abs(_floats(seq).reshape(-1, star.size) - star) for seq in conv["sequences"]]
    rate = max((abs(_complex(v)) for v in analytic_eigenvalues), default=np.nan)
    fig = Figure(figsize=(3.3 * star.size, 3.4))
    axes = fig.subplots(1, star.size, squeeze=False)[0]
    for i, (ax, label) in enumerate(zip(axes, conv["labels"], strict=True)):
        for n, distance in enumerate(sequences):
            ax.semilogy(np.arange(len(distance)), np.where(distance[:, i] > 0, distance[:, i], np.nan), "-",
                        color="tab:red", alpha=0.35, lw=0.8, label="MuJoCo trajectories" if n == 0 else None)
        _draw_guides(ax, i, sequences, star, fitted, rate)
        ax.set_xlabel("step k")
        ax.set_title(f"|x_k - x*|: {label}", fontsize=9)
    handles = {line.get_label(): line for ax in axes for line in ax.get_lines() if not line.get_label().startswith("_")}
    fig.legend(list(handles.values()), list(handles), loc="lower center", ncol=len(handles), fontsize=8)
    fig.tight_layout(rect=(0, 0.09, 1, 1))
    return _png(fig)


def _draw_guides(ax: Axes, i: int, sequences: list[np.ndarray], star: np.ndarray, fitted: list[Any] | None,
                 rate: float) -> None:
    """Coordinate ``i``'s fitted fixed point's distance from x* and the analytic rate from the median first
    distance."""
    offset = abs(_floats(fitted)[i] - star[i]) if fitted is not None else np.nan
    if np.isfinite(offset) and offset > 0:
        ax.axhline(offset, color="k", ls="--", lw=1, label="|fitted fixed point - x*|")
    firsts = [d[0, i] for d in sequences if len(d) and np.isfinite(d[0, i]) and d[0, i] > 0]
    steps = max((len(d) for d in sequences), default=0)
    if firsts and np.isfinite(rate) and rate > 0 and steps > 1:
        k = np.arange(steps)
        ax.semilogy(k, float(np.median(firsts)) * rate**k, ":", color="tab:blue", lw=1.5,
                    label=f"analytic rate |lambda|max^k = {rate:.3g}^k")


def eigenvalue_figure(fit: dict[str, Any], analytic: list[Any]) -> str:
    """Fitted eigenvalues, the bootstrap replicates' eigenvalues as a faint cloud behind them (``fit``'s
    ``eigenvalue_replicates``, when present) and the analytic ones, in the complex plane with the unit circle; beside
    it a zoom on each fitted eigenvalue (one of a conjugate pair; up to four), where the cloud is resolved."""
    fitted = np.array([_complex(v) for v in fit["eigenvalues"]])
    cloud = np.array([[_complex(v) for v in row] for row in fit.get("eigenvalue_replicates") or []], dtype=complex)
    exact = np.array([_complex(v) for v in analytic if v is not None], dtype=complex)
    zooms = [i for i, z in enumerate(fitted) if np.isfinite(z) and z.imag >= 0][:4]
    rows, cols = min(len(zooms), 2), (len(zooms) + 1) // 2
    fig = Figure(figsize=(4.5 + 2.6 * cols, 4.5))
    grid = fig.add_gridspec(max(rows, 1), 1 + cols, width_ratios=[4.5] + [2.6] * cols)
    ax = fig.add_subplot(grid[:, 0])
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(t), np.sin(t), color="gray", lw=1)
    _draw_eigenvalues(ax, fitted, cloud, exact, legend=True)
    ax.set_aspect("equal")
    ax.set_xlim(-1.2, 1.2)
    ax.set_ylim(-1.2, 1.2)
    ax.set_xlabel("Re")
    ax.set_ylabel("Im")
    ax.legend(fontsize=7, loc="lower left")
    for n, i in enumerate(zooms):
        zoom = fig.add_subplot(grid[n % rows, 1 + n // rows])
        _draw_eigenvalues(zoom, fitted[i : i + 1], cloud[:, i : i + 1] if cloud.size else cloud, exact, legend=False)
        _frame(zoom, fitted[i], cloud[:, i] if cloud.size else cloud, exact)
    fig.tight_layout()
    return _png(fig)


def _draw_eigenvalues(ax: Axes, fitted: np.ndarray, cloud: np.ndarray, exact: np.ndarray, legend: bool) -> None:
    """The cloud (faint, behind), the fitted values (red dots) and the analytic values (black crosses)."""
    if cloud.size:
        ax.plot(cloud.real.ravel(), cloud.imag.ravel(), ".", ms=2.5, color="tab:red", alpha=0.15, zorder=1,
                label=f"bootstrap replicates ({len(cloud)})" if legend else None)
    ax.plot(fitted.real, fitted.imag, "o", ms=5, color="tab:red", zorder=3, label="MuJoCo fit" if legend else None)
    if exact.size:
        ax.plot(exact.real, exact.imag, "kx", ms=9, mew=1.5, zorder=4, label="analytic" if legend else None)


def _frame(ax: Axes, value: complex, cloud: np.ndarray, exact: np.ndarray) -> None:
    """Square limits around ``value``, its cloud (1st to 99th percentile) and the nearest analytic value."""
    points = [value]
    if exact.size:
        points.append(exact[np.argmin(np.abs(exact - value))])
    finite = cloud[np.isfinite(cloud)]
    if finite.size:
        points += [complex(np.percentile(finite.real, q), np.percentile(finite.imag, q)) for q in (1, 99)]
    pts = np.array(points)
    center = complex(pts.real.min() + pts.real.max(), pts.imag.min() + pts.imag.max()) / 2
    half = 0.6 * max(np.ptp(pts.real), np.ptp(pts.imag), 1e-6)
    ax.set_xlim(center.real - half, center.real + half)
    ax.set_ylim(center.imag - half, center.imag + half)
    ax.set_aspect("equal")
    ax.tick_params(labelsize=6)
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.xaxis.set_major_locator(MaxNLocator(4))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.set_title(f"lambda = {value.real:.4g}{value.imag:+.4g}j", fontsize=7)


def basin_figure(table: list[dict[str, Any]], bands: list[list[Any]]) -> str:
    """Simulated end states over the analytic regions of attraction (shaded bands), with a legend of the outcomes'
    colours (band: analytic, marker: MuJoCo) and of the hollow marker (a start not judged)."""
    fig = Figure(figsize=(8, 2.6))
    ax = fig.subplots()
    for lo, hi, outcome in bands:
        ax.axvspan(lo, hi, color=COLORS[outcome], alpha=0.15)
    for row in table:
        marker = "o" if row["judged"] else "s"
        ax.plot(row["omega0"], 0, marker, color=COLORS.get(row["simulated"], "k"), ms=8, mfc="none"
                if not row["judged"] else COLORS.get(row["simulated"], "k"))
    outcomes = list(dict.fromkeys([*(b[2] for b in bands), *(r["simulated"] for r in table)]))
    handles = [Patch(color=COLORS.get(o, "k"), alpha=0.5, label=o) for o in outcomes]
    handles.append(Line2D([], [], marker="s", ls="", color="k", mfc="none", label="not judged"))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.45), ncol=len(handles), fontsize=7,
              frameon=False)
    ax.set_yticks([])
    ax.set_xlabel("initial post-impact speed (rad/s); shading: analytic basin, marker: MuJoCo end state", fontsize=8)
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


def _figures(result: dict[str, Any]) -> list[tuple[str, str]]:
    """(title, base64 PNG) of each figure the result has data for."""
    images = []
    plot = result.get("return_map")
    if plot is not None and not has_analytic_map(plot) and "section_convergence" in result:
        images.append(("Convergence toward the analytic fixed point, per section coordinate",
                       section_convergence_figure(result["section_convergence"], result["fit"].get("fixed_point"),
                                                  plot["analytic_eigenvalues"])))
    elif plot is not None:
        images.append(("Empirical return map", return_map_figure(plot)))
    if "fit" in result:
        analytic = plot["analytic_eigenvalues"] if plot is not None else result.get("analytic", {}).get("eigenvalues")
        images.append(("Eigenvalues of the fitted return map", eigenvalue_figure(result["fit"], analytic or [])))
    if "basins" in result and "basin_bands" in result:
        images.append(("Regions of attraction", basin_figure(result["basins"], result["basin_bands"])))
    bench_path = Path("renders") / f"bench-{result['scenario']}.json"
    if bench_path.is_file():
        images.append(("Time against error (from mjpoincare bench)", bench_figure(json.loads(bench_path.read_text()))))
    return images


def _still(name: str, still: bytes | str | None) -> str:
    """The still's section: the PNG, or the one line saying why there is none."""
    if still is None:
        return ""
    if isinstance(still, str):
        return f"<p class=still>No still of the model: {html.escape(still)}</p>"
    return (f"<img class=still alt='still of {html.escape(name)}' "
            f"src='data:image/png;base64,{base64.b64encode(still).decode()}'>")


def write_report(result: dict[str, Any], directory: str, still: bytes | str | None = None) -> Path:
    """Write ``DIR/<scenario>.html`` and ``DIR/<scenario>.json``; returns the HTML path.

    ``still``: a PNG of the model (bytes), or why it could not be rendered (one line on the page); None: no still.
    """
    out = Path(directory)
    name = result["scenario"]
    rows = "".join(
        f"<tr class={'pass' if c['passed'] else 'fail'}><td>{html.escape(c['name'])}</td>"
        f"<td>{_cell(c['analytic'], c.get('complex', False))}</td><td>{_cell(c['simulated'], c.get('complex', False))}"
        f"</td><td>{_cell(c['error'])}</td><td>{c['tolerance']:.3g}</td>"
        f"<td>{'PASS' if c['passed'] else 'FAIL'}</td><td class=why>{html.escape(c['why'])}</td></tr>"
        for c in result["checks"])
    figures = "".join(f"<h2>{html.escape(t)}</h2><img alt='{html.escape(t)}' src='data:image/png;base64,{b}'>"
                      for t, b in _figures(result))
    params = ", ".join(f"{k}={v}" for k, v in result["params"].items())
    timing = result["timing"]
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>mjpoincare: {html.escape(name)}</title>
<style>{STYLE}</style></head><body>
<h1>{html.escape(name)}: {'all checks passed' if result['passed'] else 'FAILED'}</h1>
<p>preset {html.escape(result['preset'])}; {html.escape(params)}; MuJoCo {html.escape(result['mujoco_version'])};
wall {timing['wall_s']:.2f} s, {timing['steps_per_s']:.3g} steps/s</p>{_still(name, still)}
<table id=checks><tr><th>check</th><th>analytic</th><th>simulated</th><th>error</th><th>tolerance</th><th>verdict</th>
<th>why this tolerance</th></tr>{rows}</table>
<p>MuJoCo warnings: {html.escape('; '.join(result['warnings']) or 'none')}</p>{figures}</body></html>
"""
    target = out / f"{name}.html"
    write_text(page, str(target))
    write_text(json.dumps(result, indent=2) + "\n", str(out / f"{name}.json"))
    return target


def write_index(results: list[dict[str, Any]], directory: str) -> Path:
    """Write ``DIR/index.html``: per scenario a link to its page (:func:`write_report`), its verdict and each check's
    verdict (hover: error and tolerance); returns its path."""
    rows = "".join(
        f"<tr class={'pass' if r['passed'] else 'fail'}><td><a href='{html.escape(r['scenario'])}.html'>"
        f"{html.escape(r['scenario'])}</a></td><td>{'PASS' if r['passed'] else 'FAIL'}</td>"
        f"<td>{html.escape(r['preset'])}</td><td>{r['timing']['wall_s']:.1f}</td><td>"
        + "".join(f"<span class='v {'pass' if c['passed'] else 'fail'}' title='error {_cell(c['error'])}, tolerance "
                  f"{c['tolerance']:.3g}'>{html.escape(c['name'])}</span>" for c in r["checks"])
        + "</td></tr>" for r in results)
    failed = sum(not r["passed"] for r in results)
    versions = ", ".join(sorted({r["mujoco_version"] for r in results}))
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>mjpoincare validation</title>
<style>{STYLE}</style></head><body>
<h1>mjpoincare validation: {f'{failed} of {len(results)} scenarios FAILED' if failed else
                            f'all {len(results)} scenarios passed'}</h1>
<p>MuJoCo {html.escape(versions)}; each check is green (passed) or red (failed); hover for its error.</p>
<table id=scenarios><tr><th>scenario</th><th>verdict</th><th>preset</th><th>wall, s</th><th>checks</th></tr>
{rows}</table></body></html>
"""
    target = Path(directory) / "index.html"
    write_text(page, str(target))
    return target


def _cell(value: Any, complex_values: bool = False) -> str:
    """A check's value as table text; with ``complex_values``, each ``[re, im]`` pair (how the JSON writes a complex
    number) as ``re+imj``."""
    if complex_values and isinstance(value, list) and len(value) == 2 and all(
            v is None or isinstance(v, int | float) for v in value):
        re_, im = (math.nan if v is None else float(v) for v in value)
        return html.escape(f"{re_:.6g}{im:+.6g}j")
    if isinstance(value, list):
        return html.escape(", ".join(_cell(v, complex_values) for v in value))
    if isinstance(value, float):
        return f"{value:.6g}"
    return html.escape(str(value))
