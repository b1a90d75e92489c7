"""The post-impact and mid-stance return maps of the exact 3D rimless-wheel reference, at and around the cycle.

Source: 001 = Coleman, Chatterjee & Ruina (1997), "Motions of a rimless spoked wheel: a simple 3D system with
impacts", Sec. 4 (the post-impact map f = s o d on x = (psi, phi, psi_dot, phi_dot, theta_dot) at theta = -pi/n) with
the contact requirements the paper does not print, the planar cycle (001 Table 1, eqs 12-14) on both sections, the
mid-stance map theta = 0 (conjugate to the post-impact map) and the Jacobians of both by central differences (001
Appendix, numerically).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_3d import (
    RimlessWheel3D,
    midstance_pitch_rate,
    planar_bank,
    planar_pitch_rate,
    validate,
)
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_dynamics import (
    ATOL,
    RTOL,
    _impact,
    _integrate,
    _Model,
    _model,
    _pack,
    _rhs,
    _section_state,
    _start,
    _unpack,
)
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler import (
    Matrix,
    Vector,
    angular_velocity,
    euler_angles,
    euler_rates,
    euler_state,
    pose,
)
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

_SCAN = 201


@dataclass(frozen=True)
class StepRecord:
    """One step of the post-impact map (001 Sec. 4), with the contact requirements the paper does not print.

    ``x_next``: next post-impact state (psi, phi, psi_dot, phi_dot, theta_dot); ``time``: step time;
    ``pre_impact``: q- = (psi, phi, theta, psi_dot, phi_dot, theta_dot) at the impact (theta = pi/n to round-off);
    ``theta_after``: the pitch after the reset (-pi/n to round-off); ``min_normal_force``: min N/(m g) over the
    stance (ground force normal to the slope); ``max_friction_ratio``: max |F_t|/N over the stance;
    ``impulse_ratio``: |tangential|/normal impulse at the new foot; ``normal_impulse``: its normal component.
    """

    x_next: Vector
    time: float
    pre_impact: Vector
    theta_after: float
    min_normal_force: float
    max_friction_ratio: float
    impulse_ratio: float
    normal_impulse: float


def _contact_force(md: _Model, y: Vector) -> Vector:
    """Ground force on the wheel at the stance foot (world), F = a_G - g with
    a_G = R (Omega' x e3 + Omega x (Omega x e3))."""
    R, Omega = _unpack(y)
    dOmega = np.asarray(_rhs(md)(0.0, y)[9:])
    e3 = np.array([0.0, 0.0, 1.0])
    acc = R @ (np.cross(dOmega, e3) + np.cross(Omega, np.cross(Omega, e3)))
    return acc - np.array([md.sa, 0.0, -md.ca])


def _scan_extreme(fun: Callable[[float], float], t_end: float) -> float:
    """min of fun over [0, t_end]: scan, then bounded refinement around the best sample."""
    grid = np.linspace(0.0, t_end, _SCAN)
    vals = np.array([fun(float(t)) for t in grid])
    i = int(np.argmin(vals))
    best = float(vals[i])
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, _SCAN - 1)]
    res = minimize_scalar(fun, bounds=(float(lo), float(hi)), method="bounded", options={"xatol": 1e-12})
    return min(best, float(res.fun))


def step_record(w: RimlessWheel3D, x: ArrayLike) -> StepRecord:
    """One post-impact -> post-impact step with the contact diagnostics of :class:`StepRecord`."""
    md = _model(w)
    xs = np.asarray(x, dtype=float)
    leg = _integrate(md, _start(xs[0], xs[1], -md.beta, xs[2:]), midstance=False, dense=True)
    R, Omega = _unpack(leg.y_end)
    q_pre = euler_state(R, R @ Omega)
    R_plus, Omega_plus, impulse = _impact(md, R, Omega)
    x_next, theta_after = _section_state(_pack(R_plus, Omega_plus))
    sol = leg.sol

    def normal(t: float) -> float:
        return float(_contact_force(md, sol.sol(t))[2])  # type: ignore[attr-defined]

    def neg_ratio(t: float) -> float:
        f = _contact_force(md, sol.sol(t))  # type: ignore[attr-defined]
        return -math.hypot(f[0], f[1]) / f[2] if f[2] > 0.0 else math.inf

    nmin = _scan_extreme(normal, leg.time)
    ratio = -_scan_extreme(neg_ratio, leg.time) if nmin > 0.0 else math.inf
    return StepRecord(
        x_next=x_next,
        time=leg.time,
        pre_impact=q_pre,
        theta_after=theta_after,
        min_normal_force=nmin,
        max_friction_ratio=ratio,
        impulse_ratio=float(math.hypot(impulse[0], impulse[1]) / impulse[2]),
        normal_impulse=float(impulse[2]),
    )


def step(w: RimlessWheel3D, x: ArrayLike) -> tuple[Vector, float]:
    """Post-impact map of 001 Sec. 4 (f = s o d): x = (psi, phi, psi_dot, phi_dot, theta_dot) at theta = -pi/n ->
    (next post-impact state, step time). Raises ``RuntimeError`` if the wheel rolls back, falls or stalls."""
    md = _model(w)
    xs = np.asarray(x, dtype=float)
    leg = _integrate(md, _start(xs[0], xs[1], -md.beta, xs[2:]), midstance=False)
    R, Omega = _unpack(leg.y_end)
    R_plus, Omega_plus, _ = _impact(md, R, Omega)
    return _section_state(_pack(R_plus, Omega_plus))[0], leg.time


def impact_rates(w: RimlessWheel3D, psi: float, phi: float, rates: ArrayLike) -> Vector:
    """Euler rates just after an impact at (psi, phi, theta = pi/n) with pre-impact Euler rates ``rates``, by the
    vector angular-momentum law (for checking 001 eq 6 / :func:`rimless_wheel_3d.impact_matrix`)."""
    md = _model(w)
    R = pose(psi, phi, md.beta)
    R_plus, Omega_plus, _ = _impact(md, R, R.T @ angular_velocity(psi, phi, rates))
    psi_p, phi_p, _ = euler_angles(R_plus)
    return euler_rates(psi_p, phi_p, R_plus @ Omega_plus)


def simulate(w: RimlessWheel3D, x0: ArrayLike, impacts: int) -> Matrix:
    """Iterate :func:`step`: array of shape (impacts + 1, 5), row 0 = x0, row k = state just after impact k."""
    out = np.empty((impacts + 1, 5))
    out[0] = np.asarray(x0, dtype=float)
    for k in range(impacts):
        out[k + 1] = step(w, out[k])[0]
    return out


def planar_fixed_point(w: RimlessWheel3D) -> Vector:
    """Planar cycle on the post-impact section, (psi, phi*, 0, 0, theta_dot*) (001 Table 1, eqs 12-14), from the
    closed forms."""
    validate(w)
    return np.array([w.heading, planar_bank(w.slope, w.heading), 0.0, 0.0, planar_pitch_rate(w)])


def jacobian(w: RimlessWheel3D, h: float = 1e-6) -> Matrix:
    """5x5 Jacobian of :func:`step` at :func:`planar_fixed_point` by central differences (001 Appendix J_f = B D E,
    here numerically). Truncation O(h^2) ~ 1e-12, round-off ~ 1e-12/h ~ 1e-6 at most."""
    return central_jacobian(lambda x: step(w, x)[0], planar_fixed_point(w), h)


# --- the mid-stance map ----------------------------------------------------------------------------------------


def midstance_fixed_point(w: RimlessWheel3D) -> Vector:
    """Planar cycle at mid-stance theta = 0: (psi, phi*, 0, 0, theta_dot(0)) (001 eqs 12-14, energy integral)."""
    validate(w)
    return np.array([w.heading, planar_bank(w.slope, w.heading), 0.0, 0.0, midstance_pitch_rate(w)])


def midstance_state(w: RimlessWheel3D, x_post: ArrayLike) -> Vector:
    """Integrate a post-impact state (theta = -pi/n) to the next upward crossing of theta = 0 (same stance):
    returns (psi, phi, psi_dot, phi_dot, theta_dot) there."""
    md = _model(w)
    xs = np.asarray(x_post, dtype=float)
    leg = _integrate(md, _start(xs[0], xs[1], -md.beta, xs[2:]), midstance=True)
    return _section_state(leg.y_end)[0]


def midstance_map(w: RimlessWheel3D, x: ArrayLike, *, rtol: float = RTOL, atol: float = ATOL
                  ) -> tuple[Vector, float]:
    """Return map of the mid-stance section theta = 0 (upward): (psi, phi, psi_dot, phi_dot, theta_dot) -> next
    crossing, and the elapsed time. Conjugate to :func:`step` (same eigenvalues). ``rtol``, ``atol``: DOP853's
    tolerances."""
    md = _model(w)
    xs = np.asarray(x, dtype=float)
    first = _integrate(md, _start(xs[0], xs[1], 0.0, xs[2:]), midstance=False, rtol=rtol, atol=atol)
    R, Omega = _unpack(first.y_end)
    R_plus, Omega_plus, _ = _impact(md, R, Omega)
    second = _integrate(md, _pack(R_plus, Omega_plus), midstance=True, rtol=rtol, atol=atol)
    return _section_state(second.y_end)[0], first.time + second.time


def midstance_jacobian(w: RimlessWheel3D, h: float = 1e-6) -> Matrix:
    """5x5 Jacobian of :func:`midstance_map` at :func:`midstance_fixed_point` (central differences)."""
    return central_jacobian(lambda x: midstance_map(w, x)[0], midstance_fixed_point(w), h)
