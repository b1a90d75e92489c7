"""The mid-stance section of the 3D rimless wheel and the fit of its 5-D return map, for samples of any simulator
(and of the exact reference :mod:`mjpoincare.analysis.theory.rimless_wheel_3d.hybrid`, through the same fit).

Section (001 = Coleman, Chatterjee & Ruina 1997, Sec. 2 angles): the stance spoke's pitch theta of the 3-1-2 angles
R = Rz(psi) Rx(phi) Ry(theta) crossing 0 upwards; the state there is (psi, phi, psi_dot, phi_dot, theta_dot). Its map
is conjugate to the paper's post-impact map (same eigenvalues, Sec. 8.1). The planar cycles form a family neutral in
psi (eigenvalue 1, 001 Table 1), so the map has no isolated fixed point: the fit reads it at its cycle at a given
heading, drifting along the family (:func:`mjpoincare.analysis.returnmap.fit_drifting_cycle`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.returnmap import DriftingCycleFit, fit_drifting_cycle, replicate_list, sample_pairs
from mjpoincare.analysis.rigid_body_kinematics import euler_state
from mjpoincare.analysis.theory.rimless_wheel_3d import RimlessWheel3D, midstance_pitch_rate, planar_bank
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid import Eigen3D, identify_eigenvalues

FIT_DEGREE = 2
BOOTSTRAP = 100


def section_state(quat: np.ndarray, omega_body: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pitch theta ``(...)`` and section state (psi, phi, psi_dot, phi_dot, theta_dot) ``(..., 5)`` of orientations
    ``(..., 4)`` and body-axis angular velocities ``(..., 3)`` of spoke 0's frame.

    Every other spoke's frame differs from spoke 0's by a rotation about the axle, so psi, phi and the rates are the
    same for all spokes and the stance spoke's pitch is theta wrapped to [-pi/n, pi/n).
    """
    q = euler_state(quat, omega_body)
    return q[..., 2], q[..., [0, 1, 3, 4, 5]]


@dataclass(frozen=True)
class MapFit:
    """The fitted 5-D mid-stance map (nondimensional) read at its cycle at psi = heading, the named eigenvalues of its
    Jacobian there (001 Sec. 8.1; None if they cannot be told apart) and the report's ``fit`` entry.

    The planar cycles form a family neutral in psi (eigenvalue 1, 001 Table 1), so the map has no isolated fixed
    point; a biased map makes the cycle drift along the family (``cycle.drift``, per impact).
    """

    cycle: DriftingCycleFit
    eigen: Eigen3D | None
    fit: dict[str, object]


def fit_map(sequences: list[np.ndarray], heading: float, tangent: np.ndarray, seed: int = 0) -> MapFit:
    """Least-squares polynomial map (degree 2: the curvature of the map would otherwise bias the slopes by ~size^2
    times the quadratic terms, which is what limits an affine fit near lambda5 = 1 and at few spokes), its drifting
    cycle at ``heading`` along the family with tangent ``tangent`` (d x*/d psi), its Jacobian there and the named
    eigenvalues (001 Sec. 8.1), with bootstrap standard deviations over the pairs (seed ``seed``)."""
    x, x_next = sample_pairs(sequences)
    cycle = fit_drifting_cycle(x, x_next, tangent, heading, degree=FIT_DEGREE, bootstrap=BOOTSTRAP, seed=seed,
                               label=lambda jac: identify_eigenvalues(jac, tangent).named())
    try:
        eigen: Eigen3D | None = identify_eigenvalues(cycle.jacobian, tangent)
    except ValueError:
        eigen = None
    out: dict[str, object] = {
        "fixed_point": cycle.fixed_point, "fixed_point_std": cycle.fixed_point_std,
        "drift_per_impact": cycle.drift, "drift_std": cycle.drift_std, "jacobian": cycle.jacobian,
        "eigenvalues": cycle.eigenvalues, "eigenvalue_std": cycle.eigenvalue_std,
        "named_eigenvalues": eigen.named() if eigen is not None else None,
        "named_eigenvalue_std": {name: cycle.label_std.get(name, math.nan) for name in Eigen3D.NAMES},
        "residual_rms": cycle.residual_rms, "n_pairs": cycle.n_pairs, "degree": cycle.degree,
        "bootstrap_replicas": cycle.replicates,
        "eigenvalue_replicates": replicate_list(cycle.eigenvalue_replicates),
        "note": "state (psi, phi, psi_dot, phi_dot, theta_dot) at mid-stance, rates in sqrt(g/l); fixed_point is the "
                "fitted map's cycle at psi = heading, drifting along the family of planar cycles by drift_per_impact",
    }
    return MapFit(cycle, eigen, out)


@dataclass(frozen=True)
class PlanarTails:
    """Planar cycles started on the cycle at a commanded heading: per run, the last ``tail`` mid-stance samples
    against the planar cycle at that heading (001 eq 12 bank, eq 14 + the stance energy integral for the pitch rate),
    and the heading's drift per impact, whose exact value is 0 (the heading is neutral: a bias per impact accumulates
    along the family of planar cycles, and moves the bank and the pitch rate away from the commanded cycle).

    Attributes:
        rate_error: the largest relative pitch-rate error over the tails of every run (NaN if a run is too short or
            not finite).
        bank_error: the largest bank error, rad (NaN likewise).
        drift_error: the largest |psi_last - psi_first| / impacts over the runs, rad per impact (NaN likewise).
        rate_analytic, rate_simulated, bank_analytic, bank_simulated: per usable run, its last sample's values.
        drift_per_100: per run heading (``f"{h:.6g}"``), (psi_last - psi_first) per 100 impacts over the whole run.
    """

    rate_error: float
    bank_error: float
    drift_error: float
    rate_analytic: list[float]
    rate_simulated: list[float]
    bank_analytic: list[float]
    bank_simulated: list[float]
    drift_per_100: dict[str, float]


def planar_tails(w: RimlessWheel3D, headings: list[float], sequences: list[np.ndarray], tail: int, rate_unit: float
                 ) -> PlanarTails:
    """:class:`PlanarTails` of runs started on the planar cycles of wheel ``w`` at the commanded ``headings``;
    ``sequences`` (one (K, 5) array per run, rates in rad/s = the paper's rates times ``rate_unit``)."""
    rate_a, rate_s, bank_a, bank_s, drift = [], [], [], [], {}
    rate_err, bank_err, drift_err = 0.0, 0.0, 0.0
    for h, seq in zip(headings, sequences, strict=True):
        if len(seq) < tail + 1 or not np.isfinite(seq).all():
            rate_err = bank_err = drift_err = math.nan
            continue
        last = seq[-tail:]
        ref_rate = midstance_pitch_rate(RimlessWheel3D(w.spokes, w.slope, w.J, float(h))) * rate_unit
        ref_bank = planar_bank(w.slope, float(h))
        per_impact = float(seq[-1, 0] - seq[0, 0]) / (len(seq) - 1)
        rate_err = max(rate_err, float(np.max(np.abs(last[:, 4] - ref_rate) / ref_rate)))
        bank_err = max(bank_err, float(np.max(np.abs(last[:, 1] - ref_bank))))
        drift_err = max(drift_err, abs(per_impact))
        rate_a.append(float(ref_rate))
        rate_s.append(float(last[-1, 4]))
        bank_a.append(float(ref_bank))
        bank_s.append(float(last[-1, 1]))
        drift[f"{h:.6g}"] = 100.0 * per_impact
    return PlanarTails(rate_error=rate_err, bank_error=bank_err, drift_error=drift_err, rate_analytic=rate_a,
                       rate_simulated=rate_s, bank_analytic=bank_a, bank_simulated=bank_s, drift_per_100=drift)
