"""Eigenvalues of the exact 3D rimless-wheel maps, identified with 001 eq 32 / Table 2, and the analytic summary.

Source: 001 = Coleman, Chatterjee & Ruina (1997), "Motions of a rimless spoked wheel: a simple 3D system with
impacts", Sec. 8.1 and Table 2: the five eigenvalues of a section Jacobian named (heading, lambda2, the wobble pair,
lambda5), the tangent of the planar-cycle family (001 Table 1), the eigenvalues on both sections and the analytic
quantities of a wheel (eqs 6, 10, 12-15, 32-36) next to them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_3d import (
    RimlessWheel3D,
    asymptotic_eigenvalues,
    existence_threshold,
    impact_friction_ratio,
    midstance_pitch_rate,
    minimum_stable_slope_asymptotic,
    planar_pitch_rate,
    stability_thresholds,
    step_period,
)
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler import Matrix, Vector
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_maps import (
    jacobian,
    midstance_fixed_point,
    midstance_jacobian,
    planar_fixed_point,
    step_record,
)
from numpy.typing import NDArray
from scipy.optimize import brentq


@dataclass(frozen=True)
class Eigen3D:
    """Eigenvalues of the 5-D map identified with 001 eq 32 / Table 2 (lambda0 = 0 of the 6-D map omitted).

    ``heading`` lambda1 (= 1: the heading family); ``wobble_modulus``/``wobble_angle`` |lambda3| and
    arg(lambda3) >= 0 of the wobble pair; ``lambda5``; ``lambda2`` (= mu^2, planar); ``wobble`` the pair
    (lambda3, lambda4); ``all`` = [lambda1, lambda2, lambda3, lambda4, lambda5] (complex).

    When the wobble pair is real (f0 > 0: the rolling-disk criterion eq 33/35 fails; e.g. n = 16,
    alpha = 0.9/16), the three transverse eigenvalues are all real: ``lambda5`` is then the middle one (eq 32:
    the pair 1 + f1 eps^2/2 +- eps sqrt(f0) straddles 1 - f2 eps^2 by O(eps)), ``wobble`` = (larger, smaller),
    ``wobble_modulus`` = max(|lambda3|, |lambda4|) and ``wobble_angle`` = 0 (pi if that one is negative).
    """

    heading: complex
    wobble_modulus: float
    wobble_angle: float
    lambda5: float
    lambda2: float
    all: NDArray[np.complex128]
    wobble: tuple[complex, complex]
    #: The keys of :meth:`named`.
    NAMES: ClassVar[tuple[str, ...]] = ("heading_eigenvalue", "wobble_modulus", "wobble_angle", "lambda5", "lambda2")

    def named(self) -> dict[str, float]:
        """The checked eigenvalues by name: lambda1 (real part), |lambda3|, arg lambda3, lambda5, lambda2."""
        return {"heading_eigenvalue": float(self.heading.real), "wobble_modulus": self.wobble_modulus,
                "wobble_angle": self.wobble_angle, "lambda5": self.lambda5, "lambda2": self.lambda2}


#: |Im lambda| below which an eigenvalue counts as real.
_REAL_TOL = 1e-7


def identify_eigenvalues(jac: Matrix, family_tangent: Vector) -> Eigen3D:
    """Identify the eigenvalues of a 5x5 section Jacobian (001 Sec. 8.1, Table 2).

    heading: the eigenvector best aligned with the tangent of the fixed-point family d x*/d psi (mostly e_psi; it
    is an exact eigenvector with eigenvalue 1). lambda2: among the remaining real eigenvalues, the one whose
    eigenvector lies most along e_theta_dot (the planar subspace is invariant, so e_theta_dot is an exact
    eigenvector with eigenvalue mu^2). The other three: a complex pair (wobble) plus lambda5, or, when all are
    real, see :class:`Eigen3D`.
    """
    vals, vecs = np.linalg.eig(jac)
    t = np.asarray(family_tangent, dtype=float)
    t = t / np.linalg.norm(t)
    norms = np.linalg.norm(vecs, axis=0)
    align = np.abs(vecs.conj().T @ t) / norms
    i_head = int(np.argmax(align))
    rest = [i for i in range(vals.size) if i != i_head]
    real = [i for i in rest if abs(vals[i].imag) < _REAL_TOL]
    if abs(vals[i_head].imag) >= _REAL_TOL:
        # at a stability threshold the heading eigenvalue 1 is a double root, which the Jacobian's own error splits
        # into a complex pair (1 +- 1.6e-5 i under one BLAS kernel, two real roots under another): its partner is real
        real.append(min(rest, key=lambda i: abs(vals[i] - np.conj(vals[i_head]))))
    if not real:
        raise ValueError("no real eigenvalue left for lambda2")
    i_two = max(real, key=lambda i: abs(vecs[4, i]) / norms[i])
    rest = [i for i in rest if i != i_two]
    complex_ = [i for i in rest if abs(vals[i].imag) >= _REAL_TOL and i not in real]
    if complex_:
        if len(complex_) != 2:
            raise ValueError(f"unexpected eigenvalue structure {vals}")
        i5 = next(i for i in rest if i not in complex_)
        up = max(complex_, key=lambda i: vals[i].imag)
        pair = (complex(vals[up]), complex(np.conj(vals[up])))
        modulus, angle = abs(pair[0]), float(np.angle(pair[0]))
    else:
        order = sorted(rest, key=lambda i: vals[i].real)
        i5 = order[1]
        pair = (complex(vals[order[2]].real), complex(vals[order[0]].real))
        big = max(pair, key=abs)
        modulus, angle = abs(big), 0.0 if big.real >= 0.0 else math.pi
    lam5 = float(vals[i5].real)
    lam2 = float(vals[i_two].real)
    return Eigen3D(
        heading=complex(vals[i_head]),
        wobble_modulus=float(modulus),
        wobble_angle=angle,
        lambda5=lam5,
        lambda2=lam2,
        all=np.array([vals[i_head], lam2, pair[0], pair[1], lam5], dtype=complex),
        wobble=pair,
    )


def family_tangent(point: Callable[[RimlessWheel3D], Vector], w: RimlessWheel3D, h: float = 1e-6) -> Vector:
    """d x*/d psi of a section's fixed-point family (``point``: :func:`planar_fixed_point` or
    :func:`midstance_fixed_point`; the planar cycles at every heading, 001 Table 1), by central differences."""
    up = RimlessWheel3D(w.spokes, w.slope, w.J, w.heading + h)
    down = RimlessWheel3D(w.spokes, w.slope, w.J, w.heading - h)
    return (point(up) - point(down)) / (2.0 * h)


def eigenvalues_3d(w: RimlessWheel3D, h: float = 1e-6) -> Eigen3D:
    """Eigenvalues of the post-impact map at the planar cycle (001 Sec. 8.1, Table 2 "numerical" row)."""
    return identify_eigenvalues(jacobian(w, h), family_tangent(planar_fixed_point, w))


def midstance_eigenvalues(w: RimlessWheel3D, h: float = 1e-6) -> Eigen3D:
    """Eigenvalues of the mid-stance map at the planar cycle; equal to :func:`eigenvalues_3d` (conjugate maps)."""
    return identify_eigenvalues(midstance_jacobian(w, h), family_tangent(midstance_fixed_point, w))


def analytic_summary(w: RimlessWheel3D, ref: Eigen3D) -> dict[str, object]:
    """The analytic quantities of a wheel (nondimensional, m = l = g = 1): the eigenvalues ``ref`` of the exact map
    and their eq 32 asymptotics, mu (eq 6), the bank (eq 12), gamma (eq 13), the pitch rates (eq 14), the step period
    (eq 15), the thresholds (eqs 10, 33-36) and the friction and normal force the planar cycle needs."""
    record = step_record(w, planar_fixed_point(w))
    return {
        "eigenvalues": [complex(v) for v in ref.all],
        "eigenvalues_named": ref.named(),
        "asymptotic_eigenvalues_eq32": [complex(v) for v in asymptotic_eigenvalues(w)[1:]],
        "collision_coefficient_mu": w.mu, "effective_slope": w.gamma, "bank": w.bank,
        "post_impact_pitch_rate": planar_pitch_rate(w), "midstance_pitch_rate": midstance_pitch_rate(w),
        "step_period": step_period(w), "existence_threshold": existence_threshold(w.spokes, w.J),
        "stability_thresholds": stability_thresholds(w.J)._asdict(), "g1": w.spokes * w.slope * math.cos(
            w.heading), "impact_friction_ratio": impact_friction_ratio(w),
        "stance_max_friction_ratio": record.max_friction_ratio, "min_normal_force": record.min_normal_force,
        "units": "m = l = g = 1: rates in sqrt(g/l), times in sqrt(l/g)",
    }


def transverse_modulus(w: RimlessWheel3D) -> float:
    """The largest modulus of the transverse eigenvalues lambda2, lambda3,4, lambda5 of the exact post-impact map
    (001 Sec. 8.1: the planar cycle is stable in the weak sense iff it is below 1; lambda1 = 1 is the heading)."""
    e = eigenvalues_3d(w)
    return max(abs(e.lambda2), e.wobble_modulus, abs(e.lambda5))


def minimum_stable_slope(spokes: int, J: float, heading: float = 0.0) -> float:
    """The least slope alpha at which the planar cycle at ``heading`` is stable in 3D, exactly at finite n: the root of
    :func:`transverse_modulus` = 1 (001 eqs 33-36 give it for many spokes, alpha ~ pi/((2+J) n cos psi), eq 34).

    Bracketed between the asymptotic slope of eq 34, below which the exact map is unstable at finite n (the
    derivation page: n alpha_crit = 1.48537, 1.30927 at n = 8, 16 against pi/2.5 at psi = 0, J = 1/2), and twice it.

    Raises:
        ValueError: the bracket does not hold the crossing (the asymptotic slope is already stable).
    """
    low = minimum_stable_slope_asymptotic(spokes, J, heading)

    def excess(slope: float) -> float:
        return transverse_modulus(RimlessWheel3D(spokes, slope, J, heading)) - 1.0

    if not excess(low) > 0.0 > excess(2.0 * low):
        raise ValueError(f"no stability crossing in [{low:.6g}, {2.0 * low:.6g}] for spokes={spokes}, J={J:g}, "
                         f"heading={heading:g}")
    return float(brentq(excess, low, 2.0 * low, xtol=1e-9, rtol=1e-12))
