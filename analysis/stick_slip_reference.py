"""The friction wheel's reference from given post-impact starts: runs of the event-driven hybrid simulator of
:mod:`mjpoincare.analysis.theory.rimless_wheel_friction` (002 = Gamus & Or 2015, Sec. 3.3 and Appendix A), the
generic integrator's mid-stance map (bench), a gait's analytic values and the measured force ratio against the
no-slip wheel's (numpy/scipy only)."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from mjpoincare.analysis.force_ratio import critical_ratio, ratio_profile
from mjpoincare.analysis.returnmap import fit_return_map, sample_pairs
from mjpoincare.analysis.stick_slip_phases import Rows
from mjpoincare.analysis.theory import rimless_wheel_friction as theory


def step_records(w: theory.FrictionWheel, start: Sequence[float], n: int, **options: Any) -> list[theory.StepRecord]:
    """Up to ``n`` steps of :func:`theory.step` (with ``options``) from the post-impact state ``start`` =
    (theta_dot0, x_dot0); a failed step is the last record."""
    records: list[theory.StepRecord] = []
    z: Sequence[float] | None = start
    while len(records) < n and z is not None:
        rec = theory.step(w, z, **options)
        records.append(rec)
        z = rec.post if rec.failure is None else None
    return records


@dataclass(frozen=True)
class Reference:
    """The reference run from one start: settled outcome and steps (:func:`theory.settle`), and the mid-stance rates
    and types of its first steps, each (S,) (for the convergence count)."""

    outcome: str
    settle_steps: int
    mid_rate: np.ndarray
    kinds: np.ndarray


def reference_run(w: theory.FrictionWheel, start: Sequence[float], steps: int) -> Reference:
    """:func:`theory.settle` from ``start`` (002 Sec. 3.3); its records, continued to ``steps`` unless one failed,
    give the mid-stance rates of the first ``steps`` steps."""
    settled = theory.settle(w, start)
    recs = list(settled.records)
    if recs and recs[-1].failure is None:
        recs += step_records(w, recs[-1].post, steps - len(recs))
    recs = recs[:steps]
    mid = np.array([r.midstance[0] for r in recs])
    kinds = np.array([theory.classify_record(r) or "" for r in recs])
    return Reference(outcome=settled.outcome, settle_steps=settled.steps, mid_rate=mid, kinds=kinds)


def labelled_steps(w: theory.FrictionWheel, start: Sequence[float], n: int) -> tuple[str, np.ndarray, np.ndarray]:
    """``n`` steps from the post-impact state ``start``: (label, mid-stance rates (S,), types (S,)) of the steps
    before any failure; label = the failure, else the type of the last step ("" for n = 0)."""
    recs = step_records(w, (float(start[0]), float(start[1])), n)
    done = [r for r in recs if r.failure is None]
    kinds = [theory.classify_record(r) or "" for r in done]
    label = recs[-1].failure if recs and recs[-1].failure is not None else (kinds[-1] if kinds else "")
    return label, np.array([r.midstance[0] for r in done]), np.array(kinds, dtype=str)


def generic_bench(w: theory.FrictionWheel, gait: theory.Gait, starts: np.ndarray, steps: int, rtol: float
                  ) -> dict[str, float]:
    """The generic Appendix-A integrator (:func:`theory.step` ``method="generic"`` at relative tolerance ``rtol``)
    through a quadratic fit of the mid-stance map theta_dot_k -> theta_dot_k+1 from ``steps`` steps of each start
    of ``starts`` (B, 2): its wall time and the errors of the fitted fixed point (relative) and multiplier (absolute)
    against ``gait`` (the fast method's)."""
    start = time.perf_counter()
    sequences = []
    for z in starts:
        recs = step_records(w, (float(z[0]), float(z[1])), steps, method="generic", max_step=None, rtol=rtol)
        sequences.append(np.array([r.midstance[0] for r in recs if r.failure is None])[:, None])
    fit = fit_return_map(*sample_pairs(sequences), degree=2)
    wall = time.perf_counter() - start
    lam = complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])
    return {"rtol": rtol, "wall_s": wall,
            "midstance_rate_error": abs(float(fit.fixed_point[0]) - gait.midstance_rate) / gait.midstance_rate,
            "eigenvalue_error": abs(complex(fit.eigenvalues[0]) - lam)}


def gait_values(w: theory.FrictionWheel, gait: theory.Gait) -> dict[str, Any]:
    """The gait's analytic values (002 Sec. 3.3), with the rigid wheel's critical friction mu_c (eq 23), the sticking
    impulse ratio (eq 25) and the slope bounds of the sticking gait (eq 18, 21)."""
    rigid = theory.FrictionWheel(w.spokes, w.kappa, w.slope, math.inf)
    return {"gait": gait.kind, "fixed_point": gait.fixed_point, "eigenvalues": [complex(e) for e in gait.eigenvalues],
            "phases": list(gait.phases), "phase_angles": list(gait.phase_angles), "impact": gait.impact,
            "dx_per_step": gait.dx_per_step, "midstance_rate": gait.midstance_rate,
            "midstance_x_dot": gait.midstance_x_dot, "period": gait.period, "impulse_ratio": gait.impulse_ratio,
            "mu_c": theory.critical_friction(rigid)[0],
            "sticking_impulse_ratio": theory.impulse_ratio(w.spokes, w.kappa),
            "slope_bounds": theory.slope_bounds(w.spokes, w.kappa)}


def force_ratio_comparison(w: theory.FrictionWheel, rows: Rows, select: np.ndarray
                           ) -> tuple[float, float, dict[str, Any]]:
    """The no-slip wheel's critical friction mu_c (002 eq 23), the measured max |f_t/f_n| of the rows ``select`` (B, T)
    (:func:`critical_ratio` of their :func:`ratio_profile`) and the profile beside the no-slip wheel's (eq 19-22)."""
    centres, ratio = ratio_profile(rows.theta, rows.force_t, rows.force_n, select, w.phi)
    rigid = theory.FrictionWheel(w.spokes, w.kappa, w.slope, math.inf)
    analytic = np.asarray(theory.force_ratio(rigid, centres), float)
    profile = {"theta": centres, "simulated": ratio, "analytic": analytic,
               "max_abs_error": float(np.nanmax(np.abs(ratio - analytic)))}
    return theory.critical_friction(rigid)[0], critical_ratio(centres, ratio, w.phi), profile
