"""The 3D rimless wheel's checks: the fitted 5-D mid-stance map's cycle and eigenvalues against the exact hybrid
reference (001 Sec. 8.1, Table 2; eqs 12, 14), and the planar cycles at several headings (001 eqs 6, 11, 12)."""

from __future__ import annotations

import math

import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.returnmap import sample_pairs
from mjpoincare.analysis.theory import rimless_wheel_3d as theory
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid
from mjpoincare.analysis.theory.rimless_wheel_3d.section import MapFit, planar_tails
from mjpoincare.core.params import Values
from mjpoincare.scenarios.base import ReturnMapPlot, Tolerances
from mjpoincare.scenarios.rimless_wheel_3d import runs

EIGEN_DOCS = {
    "heading_eigenvalue": "lambda1 = 1: the neutral heading (family of planar cycles, 001 Table 1)",
    "wobble_modulus": "|lambda3,4| of the wobble pair (001 Sec. 8.1, Table 2)",
    "wobble_angle": "arg lambda3 of the wobble pair, rad per impact (001 Table 2)",
    "lambda5": "lambda5, the real transverse eigenvalue (001 Table 2, eq 32)",
    "lambda2": "lambda2 = mu^2, the planar pitch-rate multiplier (001 eqs 6, 11)",
}


def _tolerance(tol: Tolerances, name: str) -> float:
    return tol.bounds.get(name, tol["eigenvalue"])


def _reason(tol: Tolerances, name: str) -> str:
    """``"; "`` and the reason of check ``name``'s bound, where the tolerances give one."""
    return f"; bound: {tol.reasons[name]}" if name in tol.reasons else ""


def fit_checks(w: theory.RimlessWheel3D, fitted: MapFit | None, ref: hybrid.Eigen3D, unit: float,
                tol: Tolerances, why: str) -> list[checks.Check]:
    x_ref = hybrid.midstance_fixed_point(w)
    point = fitted.cycle.fixed_point if fitted is not None else np.full(5, math.nan)
    out = [
        checks.relative("pitch_rate", x_ref[4] * unit, point[4] * unit, tol["pitch_rate"], "rad/s",
                        "mid-stance pitch rate of the planar cycle at the heading (001 eq 14 + the stance energy "
                        "integral), from the fitted map's fixed point at psi = heading; " + why),
        checks.absolute("bank", x_ref[1], point[1], tol["bank"], "rad",
                        "bank of the planar cycle, phi* = -atan(sin psi tan alpha) (001 eq 12), fitted fixed point"),
    ]
    simulated = fitted.eigen.named() if fitted is not None and fitted.eigen is not None else {}
    for name, analytic in ref.named().items():
        out.append(checks.absolute(name, analytic, simulated.get(name, math.nan), _tolerance(tol, name), "",
                                   EIGEN_DOCS[name] + ": exact hybrid reference (DOP853 1e-12, central "
                                   "differences) vs the Jacobian of the quadratic least-squares fit of the 5-D "
                                   "mid-stance map at its cycle" + _reason(tol, "eigenvalue")))
    return out


def planar_checks(params: Values, headings: list[float], run: runs.Run, tol: Tolerances
                   ) -> tuple[list[checks.Check], dict[str, object]]:
    """Planar cycles started on the analytic fixed point at each commanded heading, read against the cycle at that
    heading (:func:`planar_tails`), and the heading's drift per impact against its exact value, 0."""
    t = planar_tails(runs.wheel(params), headings, run.sequences, runs.PLANAR_TAIL, runs.rate_unit(params))
    where = (f"headings {', '.join(f'{h:.4g}' for h in headings)}, last {runs.PLANAR_TAIL} of "
             f"{runs.PLANAR_IMPACTS} samples")
    worst = max(t.drift_per_100.values(), key=abs, default=math.nan) / 100.0
    out = [
        checks.Check(name="planar_pitch_rate", analytic=t.rate_analytic, simulated=t.rate_simulated, error=t.rate_error,
                     tolerance=tol["planar_pitch_rate"], kind="max-relative", unit="rad/s",
                     why=f"planar cycle at several headings: mid-stance pitch rate against eq 14 + energy "
                     f"integral at the commanded heading ({where})"),
        checks.Check(name="planar_bank", analytic=t.bank_analytic, simulated=t.bank_simulated, error=t.bank_error,
                     tolerance=tol["planar_bank"], kind="max-abs", unit="rad",
                     why=f"planar cycle at several headings: bank against eq 12 at the commanded heading ({where})"
                     + ("; impact=ideal: the controller applies the reference's own impact law (001 eqs 4-6, Sec. "
                        "3.2.2), so this agreement tests MuJoCo's integration of the stance only, not its impacts"
                        if runs.is_ideal(params) else "")),
        checks.Check(name="heading_drift", analytic=0.0, simulated=worst, error=t.drift_error,
                     tolerance=tol["heading_drift"], kind="absolute", unit="rad/impact",
                     why=f"(psi_last - psi_first) / impacts of the planar runs, the largest over the headings "
                     f"({', '.join(f'{h:.4g}' for h in headings)}; {runs.PLANAR_IMPACTS} impacts): every planar "
                     "cycle keeps its heading (001 Table 1: lambda1 = 1, a neutral family), so the exact drift is 0"
                     + _reason(tol, "heading_drift")),
    ]
    return out, {"planar_headings": headings, "heading_drift_per_100_impacts_planar": t.drift_per_100,
                 "heading_drift_planar_note": f"(psi_last - psi_first) per 100 impacts over the {runs.PLANAR_IMPACTS}-"
                                              "impact planar runs, start transient included (the fitted steady "
                                              "drift is 'heading_drift' of the 5-D fit)"}


def return_map_plot(w: theory.RimlessWheel3D, sequences: list[np.ndarray], unit: float, ref: hybrid.Eigen3D
                     ) -> ReturnMapPlot:
    """theta_dot(0)_k -> theta_dot(0)_k+1 of the samples, with the planar map (eq 11 moved to mid-stance)."""
    x, x_next = sample_pairs(sequences)
    grid = np.linspace(float(x[:, 4].min()), float(x[:, 4].max()), 40)
    planar = theory.midstance_return_map(w, grid)
    return ReturnMapPlot(label="mid-stance pitch rate theta_dot (rad/s); line: planar map", x=x[:, 4] * unit,
                         x_next=x_next[:, 4] * unit, analytic_x=grid * unit, analytic_y=planar * unit,
                         analytic_eigenvalues=[complex(v) for v in ref.all])
