"""``mjpoincare sweep rimless-wheel-friction --param mu``: the gait type, eigenvalue and edges across friction
(002 Sec. 3.3, Fig. 3.5), simulated in batches of mu values against the reference per mu: the scenario's
:class:`~mjpoincare.scenarios.base.ParamSweep` of mu (:data:`MU_SWEEP`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from mjpoincare.analysis.force_ratio import critical_ratio, ratio_profile
from mjpoincare.analysis.stick_slip_phases import Steps, fit_midstance_map, outcome, settled_rows
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.core.parallel import run_jobs
from mjpoincare.scenarios.base import ParamSweep, Values
from mjpoincare.scenarios.rimless_wheel_friction.rollout import (
    D_SIM_STEPS,
    FIT_OFFSETS,
    FIT_PAIRS,
    SETTLED_STEPS,
    friction_wheel,
    gait_start,
    run_batch,
)

# --- friction sweep (002 Sec. 3.3, Fig. 3.5) ---------------------------------------------------------------------

SWEEP_OFFSETS = FIT_OFFSETS  # theta_dot0 offsets per mu: the middle start classifies, all fit lambda
SWEEP_STEPS = 20
SWEEP_BATCH = 12  # mu values per rollout (memory: every row of the batch is kept); the batch setting overrides it


def mu_per_rollout(settings: Values) -> int:
    """Mu values per rollout: as many as fill the ``batch`` setting's trajectories (SWEEP_OFFSETS starts each; at
    least one), else SWEEP_BATCH."""
    batch = int(settings["batch"])
    return max(1, batch // len(SWEEP_OFFSETS)) if batch else SWEEP_BATCH


def sweep_reference(params: Values, mu: float) -> dict[str, Any]:
    """The reference at one mu: the stable gait (type, post-impact start, multiplier, mid-stance rate) and the type
    :func:`theory.settle` reaches from the simulation's middle start (the gait's start, or eq 16's sticking fixed point
    where no gait exists)."""
    w = friction_wheel({**params, "mu": mu})
    gaits = theory.attractors(w)
    if gaits:
        gait = gaits[0]
        start = gait_start(gait)
        lam = complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])
        row = {"gait": gait.kind, "eigenvalue": lam.real, "midstance_rate": gait.midstance_rate}
    else:
        start = (theory.sticking_fixed_point(w), 0.0)
        row = {"gait": "", "eigenvalue": math.nan, "midstance_rate": math.nan}
    settled = theory.settle(w, start, max_steps=300, tol=1e-9)
    return {"mu": mu, "start": list(start), "reference": settled.outcome, **row}


def _sweep_reference_job(p: dict[str, Any], mus: list[float]) -> list[dict[str, Any]]:
    return [sweep_reference(p, mu) for mu in mus]


def sweep_batch(params: Values, settings: Values, preset: str, refs: list[dict[str, Any]],
                seed: int = 0) -> list[dict[str, Any]]:
    """Simulate every mu of ``refs`` in ONE rollout (a model per trajectory, SWEEP_OFFSETS starts per mu) and
    classify: settled type, the type of the last step before a failure, the fitted multiplier of the gait."""
    n = len(SWEEP_OFFSETS)
    starts = np.array([[r["start"][0] * (1 + d), r["start"][1]] for r in refs for d in SWEEP_OFFSETS])
    mus = np.repeat([r["mu"] for r in refs], n)
    steps_n = D_SIM_STEPS if all(r["gait"].startswith("D") for r in refs) else SWEEP_STEPS
    run = run_batch(params, settings, preset, starts, steps_n, mus=mus)
    rows, steps, report = run.rows, run.steps, run.report
    out = []
    for i, ref in enumerate(refs):
        middle = i * n + n // 2
        sim = outcome(steps, middle)
        before = _type_before_failure(steps, middle)
        lam = math.nan
        if ref["gait"]:
            try:
                mine = np.isin(np.arange(len(starts)), range(i * n, (i + 1) * n))
                fit, _, _ = fit_midstance_map(steps, np.nonzero(mine)[0], ref["gait"], FIT_PAIRS, seed)
                lam = float(np.real(fit.eigenvalues[0]))
            except ValueError:
                lam = math.nan
        ratio = math.nan
        if sim == "A":  # the force ratio the A gait needs along its stance: MuJoCo's mu_c (002 eq 23)
            phi = math.pi / int(params["spokes"])
            pooled = settled_rows(rows, steps, range(i * n, (i + 1) * n), "A", SETTLED_STEPS)
            ratio = critical_ratio(*ratio_profile(rows.theta, rows.force_t, rows.force_n, pooled, phi), phi)
        out.append({**ref, "simulated": sim, "simulated_before_failure": before, "critical_ratio": ratio,
                    "simulated_velocity_only": outcome(steps, middle, velocity_only=True),
                    "agree": sim == ref["reference"], "eigenvalue_simulated": lam,
                    "eigenvalue_error": abs(lam - ref["eigenvalue"]) if ref["gait"] else math.nan,
                    "diverged": int(report.diverged[i * n : (i + 1) * n].sum()), "warnings": report.warnings})
    return out


def _type_before_failure(steps: Steps, b: int) -> str:
    done = np.nonzero(steps.complete[b])[0]
    if steps.failure[b]:
        done = done[done < steps.failure_step[b]]
    return str(steps.kind[b, done[-1]]) if done.size else str(steps.failure[b])


def type_edges(mus: Sequence[float], types: Sequence[str]) -> dict[str, float]:
    """Where the type changes along increasing mu: ``"X/Y"`` -> the midpoint between the last mu of type X and the
    first of type Y (only between neighbouring grid points)."""
    order = np.argsort(mus)
    m = [float(mus[i]) for i in order]
    ty = [types[i] for i in order]
    edges: dict[str, float] = {}
    for k in range(len(m) - 1):
        if ty[k] != ty[k + 1]:
            edges.setdefault(f"{ty[k]}/{ty[k + 1]}", 0.5 * (m[k] + m[k + 1]))
    return edges


def sweep_summary(params: Values, rows: list[dict[str, Any]]) -> dict[str, Any]:
    """Agreement, the located type edges against the reference's (:func:`theory.gait_boundaries` of the wheel ``p``),
    eigenvalue errors per type, over the sweep's ``rows`` (increasing mu)."""
    w = friction_wheel(params)
    boundaries = theory.gait_boundaries(w.kappa, w.spokes, w.slope)
    mus = [r["mu"] for r in rows]
    reference = {"A/B (mu_c)": boundaries.ab, "B/C": boundaries.bc, "C/D+": boundaries.d_sign,
                 "D+/backward": boundaries.d_lower}
    names = {"A/B (mu_c)": ("B", "A"), "B/C": ("C", "B"), "C/D+": ("D+", "C"), "D+/backward": ("backward", "D+")}

    def locate(types: list[str]) -> dict[str, float]:
        found = type_edges(mus, types)
        return {k: found.get(f"{lo}/{hi}", math.nan) for k, (lo, hi) in names.items()}

    sim_edges = locate([r["simulated"] for r in rows])
    before_edges = locate([r["simulated_before_failure"] for r in rows])
    ref_edges_grid = locate([r["reference"] for r in rows])
    eig: dict[str, float] = {}
    for r in rows:
        if r["gait"] and math.isfinite(r["eigenvalue_error"]):
            eig[r["gait"]] = max(eig.get(r["gait"], 0.0), r["eigenvalue_error"])
    ratios = [r["critical_ratio"] for r in rows if math.isfinite(r.get("critical_ratio", math.nan))]
    mu_c_ratio = float(np.median(ratios)) if ratios else math.nan
    agree = sum(r["agree"] for r in rows)
    agree_before = sum(r["simulated_before_failure"] == r["reference"] for r in rows)
    # without the D+ band: MuJoCo's sliding foot lifts off at about mu |v_t| (analysis/soft_contact, eq 2), and a D+
    # gait's slip speed grows every step until it flies
    outside = [r for r in rows if r["reference"] != "D+"]
    agree_outside = sum(r["agree"] for r in outside) / len(outside) if outside else math.nan
    return {"points": len(rows), "agreement": agree / len(rows), "agreement_before_failure": agree_before / len(rows),
            "points_without_d_plus": len(outside), "agreement_without_d_plus": agree_outside,
            "disagreements": [{"mu": r["mu"], "reference": r["reference"], "simulated": r["simulated"],
                               "before_failure": r["simulated_before_failure"]} for r in rows if not r["agree"]],
            "edges_reference": reference, "edges_reference_on_grid": ref_edges_grid, "edges_simulated": sim_edges,
            "edges_simulated_before_failure": before_edges,
            "edge_errors": {k: abs(sim_edges[k] - v) for k, v in reference.items()},
            "mu_c_relative_error": abs(sim_edges["A/B (mu_c)"] - boundaries.ab) / boundaries.ab,
            "mu_c_force_ratio": mu_c_ratio, "mu_c_force_ratio_points": len(ratios),
            "mu_c_force_ratio_relative_error": abs(mu_c_ratio - boundaries.ab) / boundaries.ab,
            "max_eigenvalue_error_per_type": eig}


def plan(params: Values, settings: Values, mus: Sequence[float], *, workers: int) -> list[tuple[list[dict[str, Any]]]]:
    """The reference at each mu (:func:`sweep_reference`), grouped into the rollouts of :func:`sweep_batch`.

    Args:
        p: the wheel's parameters (mu aside).
        s: the simulator settings (``batch``: :func:`mu_per_rollout`).
        mus: the mu values to run, increasing.
        workers: processes for the references, at least two (the mu values interleaved: the D range costs more).

    Returns:
        One job per rollout: ``(refs,)``, :func:`mu_per_rollout` references in increasing mu.
    """
    workers = max(workers, 2)
    parts = max(1, min(workers, len(mus)))
    chunks = [list(mus[i::parts]) for i in range(parts)]
    refs = sorted((r for part in run_jobs(_sweep_reference_job, [(dict(params), c) for c in chunks], workers=workers)
                   for r in part), key=lambda r: r["mu"])
    per_rollout = mu_per_rollout(settings)
    return [(refs[k : k + per_rollout],) for k in range(0, len(refs), per_rollout)]


def sweep_passed(summary: dict[str, Any]) -> bool:
    """The simulated type agrees with the reference's at >= 95 % of the mu values, every located edge is within 0.02
    of the reference's and every type's largest eigenvalue error is within 0.02."""
    return (summary["agreement"] >= 0.95
            and all(e <= 0.02 for e in summary["edge_errors"].values() if math.isfinite(e))
            and all(e <= 0.02 for e in summary["max_eigenvalue_error_per_type"].values()))


def sweep_table(rows: list[dict[str, Any]], summary: dict[str, Any]) -> str:
    """The sweep as a table a person reads, with the summary lines."""
    lines = [markdown_table(
        ("mu", "reference", "simulated", "before failure", "lambda ref", "lambda sim"),
        [(f"{r['mu']:.4g}", r["reference"], f"{r['simulated']}{'' if r['agree'] else ' (!)'}",
          r["simulated_before_failure"], f"{r['eigenvalue']:.4f}", f"{r['eigenvalue_simulated']:.4f}") for r in rows])]
    lines.append(f"\nagreement {summary['agreement']:.1%} of {summary['points']} "
                 f"({summary['agreement_before_failure']:.1%} counting the type before a flight); without the D+ "
                 f"band {summary['agreement_without_d_plus']:.1%} of {summary['points_without_d_plus']}")
    for name, ref in summary["edges_reference"].items():
        lines.append(f"edge {name}: simulated {summary['edges_simulated'][name]:.4f}, reference {ref:.4f} "
                     f"(error {summary['edge_errors'][name]:.4f}; before failure "
                     f"{summary['edges_simulated_before_failure'][name]:.4f})")
    edge = summary["edges_simulated"]["A/B (mu_c)"]
    lines.append(f"mu_c: A/B type edge {edge:.4f} ({summary['mu_c_relative_error']:.2%} off); max |f_t/f_n| along the "
                 f"simulated A gaits (eq 23, median of {summary['mu_c_force_ratio_points']}) "
                 f"{summary['mu_c_force_ratio']:.4f} ({summary['mu_c_force_ratio_relative_error']:.2%} off); "
                 f"reference {summary['edges_reference']['A/B (mu_c)']:.6f}")
    lines.append("largest eigenvalue error per type: " + ", ".join(
        f"{k} {v:.4f}" for k, v in summary["max_eigenvalue_error_per_type"].items()))
    return "\n".join(lines)


MU_SWEEP = ParamSweep(plan=plan, compute=sweep_batch, summarize=sweep_summary, table=sweep_table, passed=sweep_passed)


