"""``mjpoincare sweep rimless-wheel-friction --grid theta_dot0=..,x_dot0=..``: regions of attraction with finite
friction (002 Sec. 3.4, eq 26, Fig. 3.8), simulated against the reference on a coarser grid: the scenario's
:class:`~mjpoincare.scenarios.base.RegionMap` (:data:`REGION_MAP`)."""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from mjpoincare.analysis.stick_slip_phases import outcome, steps_to_converge
from mjpoincare.analysis.stick_slip_reference import labelled_steps
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.core.parallel import run_jobs
from mjpoincare.core.params import Param
from mjpoincare.core.seam import RolloutReport
from mjpoincare.scenarios.base import RegionMap, Values
from mjpoincare.scenarios.rimless_wheel_friction.rollout import (
    friction_wheel,
    gait_start,
    period_seconds,
    rate_unit,
    reference_gait,
    run_batch,
)

# --- regions of attraction (002 Sec. 3.4, eq 26, Fig. 3.8) --------------------------------------------------------

BASIN_STEPS = 4  # steps per trajectory of the 2-D map: label = a failure, else the type of the last complete step
CONVERGE_STEPS = 30  # steps along the theta_dot0 lines, for the convergence counts
CONVERGE_TOL = 0.01  # converged: mid-stance theta_dot within 1 % of its last value and every step of the final type
BASIN_CHUNK = 250  # trajectories per rollout (every row of a rollout is kept); the batch setting overrides it
REFERENCE_STRIDE = 4  # the reference map is evaluated on every 4th grid point in each direction
FAILURES = ("backward", "detached", "painleve", "impact", "chatter", "unsettled", "")
MU_NO_SLIP = 10.0  # "unbounded" friction in simulation: far above mu_c; the reference uses the same finite mu
#: The map's axes: the post-impact state (002's nondimensional units).
AXES = (Param("theta_dot0", 1.0, "post-impact theta_dot (nondimensional)", float, 0.0, low_open=True),
        Param("x_dot0", 0.0, "post-impact slip speed (nondimensional)", float, 0.0))


def _basin_reference_job(p: dict[str, Any], mu: float, theta_dot0: list[float], x_dot0: float, n: int,
                         eventual: bool) -> list[dict[str, Any]]:
    w = friction_wheel({**p, "mu": mu})
    out = []
    for th in theta_dot0:
        label, mids, kinds = labelled_steps(w, (th, x_dot0), n)
        row: dict[str, Any] = {"mu": mu, "theta_dot0": th, "x_dot0": x_dot0, "label": label,
                               "converge_steps": steps_to_converge(mids, kinds, label, CONVERGE_TOL)}
        if eventual:
            lab, st = theory.basin_outcome(w, th, x_dot0)
            row["eventual"], row["eventual_steps"] = str(lab), int(st)
        out.append(row)
    return out


def simulate_starts(params: Values, settings: Values, preset: str, starts: np.ndarray, nsteps: int, mu: float
                    ) -> tuple[list[str], list[int], list[np.ndarray], RolloutReport]:
    """Simulate ``starts`` in rollouts of BASIN_CHUNK trajectories, or of the ``batch`` setting's (sorted by
    theta_dot0, so that only the slowest chunk waits for a slow first step); per start: the label (failure, else the
    type of the last complete step), the steps to converge (CONVERGE_TOL) and the mid-stance rates."""
    order = np.argsort(starts[:, 0], kind="stable")
    labels: list[str] = [""] * len(starts)
    conv: list[int] = [-1] * len(starts)
    mids: list[np.ndarray] = [np.zeros(0)] * len(starts)
    total = RolloutReport()
    per_rollout = int(settings["batch"]) or BASIN_CHUNK
    for k in range(0, len(starts), per_rollout):
        idx = order[k : k + per_rollout]
        part = starts[idx]
        extra = _first_step_seconds({**params, "mu": mu}, part)
        run = run_batch({**params, "mu": mu}, settings, preset, part, nsteps, extra=extra)
        steps, report = run.steps, run.report
        total = report if not total.steps else total.merge(report)
        for b, i in enumerate(idx):
            label = outcome(steps, b)
            done = np.nonzero(steps.complete[b])[0]
            rate, kinds = steps.mid_rate[b, done], steps.kind[b, done]
            labels[i], mids[i] = label, rate
            conv[i] = steps_to_converge(rate, kinds, label, CONVERGE_TOL) if label not in FAILURES else -1
    return labels, conv, mids, total


def _first_step_seconds(params: Values, starts: np.ndarray) -> float:
    """Extra time for a slow first step (a start near the backward edge crawls over the top), from the reference's
    first step of the slowest start that does not roll back, at most 1 s."""
    w = friction_wheel(params)
    period = period_seconds(params, np.array([w.mu]))
    for th, xd in starts[np.argsort(starts[:, 0])]:
        rec = theory.step(w, (float(th), float(xd)))
        if rec.failure != "backward":
            return float(np.clip(rec.duration / rate_unit(params) - period, 0.0, 1.0))
    return 0.0


def basin_map(params: Values, settings: Values, preset: str, theta_dot0: np.ndarray, x_dot0: np.ndarray, *,
              workers: int) -> dict[str, Any]:
    """Regions of attraction (002 Sec. 3.4, eq 26, Fig. 3.8) from simulation, against the reference.

    * The map: every (theta_dot0, x_dot0) post-impact start at the scenario's mu, BASIN_STEPS steps, batched
      (BASIN_CHUNK trajectories per rollout); the reference on every REFERENCE_STRIDE-th point: the label after the
      same steps and the eventual outcome (:func:`theory.basin_outcome`), run in ``workers`` processes, at least two.
    * The lines: theta_dot0 alone (x_dot0 = 0) at mu and at MU_NO_SLIP (no slip along the gait: the paper's
      unbounded friction), CONVERGE_STEPS steps: the window edges and the steps to converge, simulated and reference.

    Args:
        p: the scenario's parameters (the map is at their mu).
        s: the simulator settings (``batch``: trajectories per rollout, else BASIN_CHUNK).
        preset: the preset (the classifier's thresholds).
        theta_dot0: post-impact theta_dot of the map's columns, shape (nx,).
        x_dot0: post-impact slip speed of its rows, shape (ny,).
        workers: processes for the reference.

    Returns:
        ``params`` and ``preset``; ``mu``, the axes, ``simulated`` labels (ny, nx); the reference's axes (every
        REFERENCE_STRIDE-th point), its labels after BASIN_STEPS steps and eventual outcomes; the ``lines``; the
        disagreements (region, type, region by x_dot0), ``windows`` and ``convergence``; the timings, ``steps``,
        ``diverged`` trajectories and MuJoCo ``warnings``.
    """
    workers = max(workers, 2)
    mu = float(params["mu"])
    start = time.perf_counter()
    grid = np.array([(th, xd) for xd in x_dot0 for th in theta_dot0])
    labels, _, _, report = simulate_starts(params, settings, preset, grid, BASIN_STEPS, mu)
    sim_map = np.array(labels, dtype=object).reshape(len(x_dot0), len(theta_dot0)).astype(str)
    map_wall = time.perf_counter() - start
    line = np.column_stack([theta_dot0, np.zeros_like(theta_dot0)])
    lines: dict[str, Any] = {}
    for name, m in (("slip", mu), ("no_slip", MU_NO_SLIP)):
        lab, conv, _, rep = simulate_starts(params, settings, preset, line, CONVERGE_STEPS, m)
        report = report.merge(rep)
        lines[name] = {"mu": m, "simulated": lab, "simulated_steps": conv}
    sim_wall = time.perf_counter() - start
    ref_th = theta_dot0[::REFERENCE_STRIDE]
    ref_xd = x_dot0[::REFERENCE_STRIDE]
    jobs: list[tuple[Any, ...]] = [(dict(params), mu, list(map(float, ref_th)), float(xd), BASIN_STEPS, True)
                                   for xd in ref_xd]
    jobs += [(dict(params), m, [float(th)], 0.0, CONVERGE_STEPS, False) for m in (mu, MU_NO_SLIP) for th in theta_dot0]
    results = list(run_jobs(_basin_reference_job, jobs, workers=workers))
    ref_rows = [r for part in results for r in part if "eventual" in r]
    line_rows = {(round(r["theta_dot0"], 12), r["mu"]): r for part in results for r in part if "eventual" not in r}
    ref_wall = time.perf_counter() - start - sim_wall
    ref_label = np.full((len(ref_xd), len(ref_th)), "", dtype=object)
    ref_eventual = np.full((len(ref_xd), len(ref_th)), "", dtype=object)
    for r in ref_rows:
        i = int(np.argmin(np.abs(ref_xd - r["x_dot0"])))
        j = int(np.argmin(np.abs(ref_th - r["theta_dot0"])))
        ref_label[i, j], ref_eventual[i, j] = r["label"], r["eventual"]
    for name, m in (("slip", mu), ("no_slip", MU_NO_SLIP)):
        rows = [line_rows.get((round(float(th), 12), m), {}) for th in theta_dot0]
        lines[name]["reference"] = [r.get("label", "") for r in rows]
        lines[name]["reference_steps"] = [r.get("converge_steps", -1) for r in rows]
    sub = sim_map[::REFERENCE_STRIDE, ::REFERENCE_STRIDE]
    inside_sim = ~np.isin(sub, FAILURES)
    inside_ref = ~np.isin(ref_eventual.astype(str), FAILURES)
    result = {"params": dict(params), "preset": preset, "mu": mu, "theta_dot0": theta_dot0, "x_dot0": x_dot0,
              "simulated": sim_map,
              "reference_theta_dot0": ref_th, "reference_x_dot0": ref_xd,
              "reference_after_steps": ref_label.astype(str),
              "reference_eventual": ref_eventual.astype(str), "lines": lines,
              "type_disagreement": float(np.mean(sub != ref_label.astype(str))),
              "region_disagreement": float(np.mean(inside_sim != inside_ref)),
              "region_disagreement_by_x_dot0": np.mean(inside_sim != inside_ref, axis=1),
              "windows": _windows(params, theta_dot0, lines), "steps": float(report.steps),
              "rollout_wall_s": report.wall_s, "map_wall_s": map_wall, "simulation_wall_s": sim_wall,
              "reference_wall_s": ref_wall, "wall_s": time.perf_counter() - start,
              "diverged": int(report.diverged.sum()), "warnings": report.warnings}
    result["convergence"] = _convergence_summary(lines)
    return result


def _windows(params: Values, theta_dot0: np.ndarray, lines: dict[str, Any]) -> dict[str, Any]:
    """Attraction windows in theta_dot0 (x_dot0 = 0): reference (:func:`theory.attraction_window`, eq 26 for
    mu = inf) and simulated (the outermost converging starts of each line)."""
    rigid = friction_wheel({**params, "mu": math.inf})
    out: dict[str, Any] = {"eq26_unbounded": list(theory.attraction_window_rigid(rigid))}
    for name, line in lines.items():
        w = friction_wheel({**params, "mu": line["mu"]})
        inside = np.array([lab not in FAILURES for lab in line["simulated"]])
        centre = int(np.argmin(np.abs(theta_dot0 - gait_start(reference_gait(w))[0])))
        sim = [math.nan, math.nan]
        if inside[centre]:  # the unbroken run of converging starts around the gait's own speed
            lo = centre
            while lo > 0 and inside[lo - 1]:
                lo -= 1
            hi = centre
            while hi < inside.size - 1 and inside[hi + 1]:
                hi += 1
            sim = [float(theta_dot0[lo]), float(theta_dot0[hi])]
        out[name] = {"mu": line["mu"], "reference": list(theory.attraction_window(w, tol=1e-6)), "simulated": sim,
                     "simulated_outside_converging": [float(x) for x, ok in zip(theta_dot0, inside, strict=True)
                                                      if ok and not sim[0] <= x <= sim[1]]}
    return out


def _convergence_summary(lines: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for name, line in lines.items():
        sim = np.array(line["simulated_steps"], float)
        ref = np.array(line["reference_steps"], float)
        both = (sim >= 0) & (ref >= 0)
        inside_sim = np.array([lab not in FAILURES for lab in line["simulated"]])
        inside_ref = np.array([lab not in FAILURES for lab in line["reference"]])
        out[name] = {"mu": line["mu"], "points": int(both.sum()),
                     "region_disagreement": float(np.mean(inside_sim != inside_ref)),
                     "median_steps_simulated": float(np.median(sim[both])) if both.any() else math.nan,
                     "median_steps_reference": float(np.median(ref[both])) if both.any() else math.nan,
                     "mean_abs_difference": float(np.mean(np.abs(sim[both] - ref[both]))) if both.any() else math.nan}
    return out


BASIN_COLORS = {"A": "#4c9be8", "B": "#6cc36c", "C": "#f2c14e", "D+": "#e8864c", "D-": "#c77dd6",
                "backward": "#9e9e9e", "detached": "#d9534f", "": "#ffffff"}


def plot_basins(result: dict[str, Any], path: str) -> None:
    """The map (simulated labels) over the reference's eventual-outcome boundaries, and the convergence lines."""
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    names = list(BASIN_COLORS)
    th, xd = np.asarray(result["theta_dot0"]), np.asarray(result["x_dot0"])
    sim = np.asarray(result["simulated"])
    codes = np.vectorize(lambda s: names.index(s) if s in names else names.index(""))(sim)
    fig = Figure(figsize=(13, 5))
    ax, bx = fig.subplots(1, 2)
    ax.pcolormesh(th, xd, codes, cmap=ListedColormap(list(BASIN_COLORS.values())), vmin=-0.5,
                  vmax=len(names) - 0.5, shading="nearest")
    rth, rxd = np.asarray(result["reference_theta_dot0"]), np.asarray(result["reference_x_dot0"])
    ev = np.asarray(result["reference_eventual"])
    inside = (~np.isin(ev, FAILURES)).astype(float)
    back = (ev == "backward").astype(float)
    if min(ev.shape) >= 2:  # a contour needs a 2 x 2 reference grid at least
        if 0 < inside.mean() < 1:
            ax.contour(rth, rxd, inside, levels=[0.5], colors="k", linewidths=1.5)
        if 0 < back.mean() < 1:
            ax.contour(rth, rxd, back, levels=[0.5], colors="k", linestyles="--", linewidths=1.0)
    after = np.asarray(result["reference_after_steps"])
    sub = sim[:: REFERENCE_STRIDE, :: REFERENCE_STRIDE]
    yy, xx = np.nonzero(sub != after)
    ax.plot(rth[xx], rxd[yy], "kx", ms=3)
    ax.set_xlabel("post-impact theta_dot0 (nondimensional)")
    ax.set_ylabel("post-impact slip speed x_dot0 (nondimensional)")
    ax.set_title(f"mu = {result['mu']:g}: simulated outcome after {BASIN_STEPS} steps\nblack: reference region of "
                 "attraction (solid), backward roll (dashed); x: type differs from the reference", fontsize=8)
    handles = [Rectangle((0, 0), 1, 1, color=c) for k, c in BASIN_COLORS.items() if k]
    ax.legend(handles, [k for k in BASIN_COLORS if k], fontsize=7, loc="upper right")
    for name, style in (("slip", "tab:green"), ("no_slip", "tab:blue")):
        line = result["lines"][name]
        sim_steps = np.array(line["simulated_steps"], float)
        ref_steps = np.array(line["reference_steps"], float)
        bx.plot(th[sim_steps >= 0], sim_steps[sim_steps >= 0], "o", ms=3, color=style,
                label=f"MuJoCo, mu = {line['mu']:g}")
        bx.plot(th[ref_steps >= 0], ref_steps[ref_steps >= 0], "-", color=style,
                label=f"reference, mu = {line['mu']:g}")
    lo, hi = result["windows"]["eq26_unbounded"]
    bx.axvline(lo, color="k", ls=":", lw=1)
    bx.axvline(hi, color="k", ls=":", lw=1, label="eq 26 window (mu = inf)")
    for name, style in (("slip", "tab:green"), ("no_slip", "tab:blue")):
        for edge in result["windows"][name]["reference"]:
            if math.isfinite(edge):
                bx.axvline(edge, color=style, ls="--", lw=1)
    bx.set_xlabel("theta_dot0 (x_dot0 = 0)")
    bx.set_ylabel(f"steps to converge (mid-stance rate within {CONVERGE_TOL:.0%})")
    bx.set_title("steps to converge with slip (mu finite) and without (mu = 10), x_dot0 = 0\n"
                 "dashed: reference windows (Fig. 3.8a)", fontsize=8)
    bx.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def summary(result: dict[str, Any]) -> str:
    """The map's disagreements with the reference, and per line its window and steps to converge against the
    reference's."""
    w = result["windows"]
    c = result["convergence"]
    lines = [f"rimless-wheel-friction basins, mu = {result['mu']:g}: {result['theta_dot0'].size}x"
             f"{result['x_dot0'].size} map in {result['map_wall_s']:.1f} s ({result['steps']:.3g} steps in all, "
             f"{result['rollout_wall_s']:.1f} s in MuJoCo), reference {result['reference_wall_s']:.1f} s, total "
             f"{result['wall_s']:.1f} s",
             f"  region of attraction differs on {result['region_disagreement']:.1%} of the reference points, the type "
             f"after {BASIN_STEPS} steps on {result['type_disagreement']:.1%}; by x_dot0: " + ", ".join(
                 f"{x:.3g}: {d:.0%}" for x, d in zip(result["reference_x_dot0"],
                                                      result["region_disagreement_by_x_dot0"], strict=True))]
    for name in ("slip", "no_slip"):
        lines.append(f"  mu = {w[name]['mu']:g}: window simulated {w[name]['simulated'][0]:.4f}.."
                     f"{w[name]['simulated'][1]:.4f}, reference {w[name]['reference'][0]:.4f}.."
                     f"{w[name]['reference'][1]:.4f} (region differs on {c[name]['region_disagreement']:.1%} of the "
                     f"line); steps to converge (median over {c[name]['points']}) simulated "
                     f"{c[name]['median_steps_simulated']:.1f}, reference {c[name]['median_steps_reference']:.1f}, "
                     f"mean |difference| {c[name]['mean_abs_difference']:.2f}")
    lines.append(f"  eq 26 (mu = inf): {w['eq26_unbounded'][0]:.4f}..{w['eq26_unbounded'][1]:.4f}")
    return "\n".join(lines)


def passed(result: dict[str, Any]) -> bool:
    """The simulated region of attraction differs from the reference's on at most 5 % of the reference points, and no
    trajectory diverged."""
    return result["region_disagreement"] <= 0.05 and result["diverged"] == 0


REGION_MAP = RegionMap(axes=AXES, output="renders/basins-{scenario}.png", compute=basin_map, summary=summary,
                       plot=plot_basins, passed=passed)
