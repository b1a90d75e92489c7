"""Exact event-driven reference of the 3D rimless wheel, independent of the closed forms of
:mod:`mjpoincare.analysis.theory.rimless_wheel_3d`.

Model (the physics of 001 = Coleman, Chatterjee & Ruina 1997, Sec. 3, solved generically; m = l = g = 1):

* Stance (001 eq 3, replaced by Newton-Euler): the stance foot P is a frictional ball joint (no slip, no torsional
  friction). The state is the rotation matrix R (body -> slope frame, 9 entries) and the body angular velocity
  Omega; R' = R [Omega]x and, about P in body axes, I_P Omega' + Omega x I_P Omega = e3 x (R^T g) with
  I_P = diag(J/2 + 1, J + 1, J/2), g = (sin alpha, 0, -cos alpha), hub = P + R e3, body e2 = axle.
* Impact (001 eqs 4-6, NOT via the Euler-rate matrix T): the event is the height of the next foot,
  hub_z + (R d)_z with d = (sin 2beta, 0, -cos 2beta) the next spoke in body axes, crossing zero downwards (that
  it happens at pitch +pi/n is a result, not an input). The rates jump by conservation of angular momentum about
  the new foot P': (I_C + |r'|^2 1 - r' r'^T) omega+ = I_C omega- + r' x (omega- x r), r = G - P, r' = G - P'
  (world frame, I_C = R diag(J/2, J, J/2) R^T); then R -> R Ry(-2 beta) (the new stance spoke becomes body -e3).
  The impulse at the new foot is v_G+ - v_G-; the trailing foot gets none.
* Integration: ``solve_ivp(method="DOP853", rtol=1e-12, atol=1e-12)`` with terminal events (impact; the trailing
  foot touching again = rolled back; hub height below 0.05 = fallen). Unilateral contact and friction are not
  enforced; :class:`StepRecord` reports the minimum normal force and the friction the stance needs.

Euler angles are only used at the section: R = Rz(psi) Rx(phi) Ry(theta) (phi = asin R[2,1],
theta = atan2(-R[2,0], R[2,2]), psi = atan2(-R[0,1], R[1,1])) and omega = psi_dot e_z + phi_dot x' + theta_dot y''.
The post-impact section state is x = (psi, phi, psi_dot, phi_dot, theta_dot) at theta = -pi/n (5-D; 001 uses the
6-D q with one extra eigenvalue 0). The mid-stance section is the upward crossing theta = 0, the section a soft-
contact simulator should use; its map is conjugate to the post-impact map (same eigenvalues).
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
    planar_bank,
    planar_pitch_rate,
    stability_thresholds,
    step_period,
    validate,
)
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

RTOL = 1e-12
ATOL = 1e-12
#: A stance longer than this (time units sqrt(l/g)) is declared stalled.
MAX_STANCE_TIME = 200.0
#: Hub height below which the wheel is declared fallen.
FALLEN_HEIGHT = 0.05
_SCAN = 201

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]


# --- kinematics ------------------------------------------------------------------------------------------------


def _rx(a: float) -> Matrix:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _ry(a: float) -> Matrix:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rz(a: float) -> Matrix:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def pose(psi: float, phi: float, theta: float) -> Matrix:
    """R = Rz(psi) Rx(phi) Ry(theta), the stance-spoke frame in the slope frame (001 Sec. 2, 3-1-2 angles)."""
    return _rz(psi) @ _rx(phi) @ _ry(theta)


def euler_angles(R: ArrayLike) -> tuple[float, float, float]:
    """(psi, phi, theta) of R = Rz(psi) Rx(phi) Ry(theta) (inverse of :func:`pose`, |phi| < pi/2)."""
    m = np.asarray(R, dtype=float)
    phi = math.asin(max(-1.0, min(1.0, float(m[2, 1]))))
    theta = math.atan2(-float(m[2, 0]), float(m[2, 2]))
    psi = math.atan2(-float(m[0, 1]), float(m[1, 1]))
    return psi, phi, theta


def _rate_basis(psi: float, phi: float) -> Matrix:
    """Columns e_z, x' = Rz e_x, y'' = Rz Rx e_y: omega = [e_z, x', y''] (psi_dot, phi_dot, theta_dot)."""
    cp, sp, cf, sf = math.cos(psi), math.sin(psi), math.cos(phi), math.sin(phi)
    return np.array([[0.0, cp, -sp * cf], [0.0, sp, cp * cf], [1.0, 0.0, sf]])


def angular_velocity(psi: float, phi: float, rates: ArrayLike) -> Vector:
    """World angular velocity from Euler rates (psi_dot, phi_dot, theta_dot) (001 Sec. 2)."""
    return _rate_basis(psi, phi) @ np.asarray(rates, dtype=float)


def euler_rates(psi: float, phi: float, omega: ArrayLike) -> Vector:
    """Euler rates (psi_dot, phi_dot, theta_dot) from the world angular velocity (inverse of
    :func:`angular_velocity`; needs cos phi != 0)."""
    return np.linalg.solve(_rate_basis(psi, phi), np.asarray(omega, dtype=float))


def euler_state(R: ArrayLike, omega: ArrayLike) -> Vector:
    """Paper state q = (psi, phi, theta, psi_dot, phi_dot, theta_dot) (001 eq 2) from the stance-spoke frame R and
    the world angular velocity omega (e.g. read from a simulator)."""
    psi, phi, theta = euler_angles(R)
    return np.array([psi, phi, theta, *euler_rates(psi, phi, omega)])


# --- stance dynamics -------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Model:
    beta: float
    sa: float
    ca: float
    i1: float
    i2: float
    i3: float
    s2b: float
    c2b: float
    J: float


def _model(w: RimlessWheel3D) -> _Model:
    validate(w)
    beta = math.pi / w.spokes
    return _Model(
        beta=beta,
        sa=math.sin(w.slope),
        ca=math.cos(w.slope),
        i1=w.J / 2.0 + 1.0,
        i2=w.J + 1.0,
        i3=w.J / 2.0,
        s2b=math.sin(2.0 * beta),
        c2b=math.cos(2.0 * beta),
        J=w.J,
    )


def _rhs(md: _Model) -> Callable[[float, Vector], list[float]]:
    """R' = R [Omega]x, I_P Omega' = e3 x R^T g - Omega x I_P Omega (body axes about the stance foot)."""
    sa, ca, i1, i2, i3 = md.sa, md.ca, md.i1, md.i2, md.i3

    def f(_t: float, y: Vector) -> list[float]:
        r00, r01, r02, r10, r11, r12, r20, r21, r22, w1, w2, w3 = y
        g0 = r00 * sa - r20 * ca
        g1 = r01 * sa - r21 * ca
        return [
            r01 * w3 - r02 * w2,
            r02 * w1 - r00 * w3,
            r00 * w2 - r01 * w1,
            r11 * w3 - r12 * w2,
            r12 * w1 - r10 * w3,
            r10 * w2 - r11 * w1,
            r21 * w3 - r22 * w2,
            r22 * w1 - r20 * w3,
            r20 * w2 - r21 * w1,
            (-g1 - (i3 - i2) * w2 * w3) / i1,
            (g0 - (i1 - i3) * w3 * w1) / i2,
            (-(i2 - i1) * w1 * w2) / i3,
        ]

    return f


def _events(md: _Model) -> list[Callable[[float, Vector], float]]:
    s2b, c2b = md.s2b, md.c2b

    def impact(_t: float, y: Vector) -> float:  # height of the next foot, body direction (sin 2b, 0, -cos 2b)
        return y[6] * s2b + y[8] * (1.0 - c2b)

    def rolled_back(_t: float, y: Vector) -> float:  # height of the trailing foot, (-sin 2b, 0, -cos 2b)
        return -y[6] * s2b + y[8] * (1.0 - c2b)

    def fallen(_t: float, y: Vector) -> float:
        return y[8] - FALLEN_HEIGHT

    for ev in (impact, rolled_back, fallen):
        ev.terminal = True  # type: ignore[attr-defined]
        ev.direction = -1.0  # type: ignore[attr-defined]
    return [impact, rolled_back, fallen]


def _midstance_event(_t: float, y: Vector) -> float:
    """theta = atan2(-R[2,0], R[2,2]) crossing 0 upwards."""
    return -y[6]


_midstance_event.terminal = True  # type: ignore[attr-defined]
_midstance_event.direction = 1.0  # type: ignore[attr-defined]


def _pack(R: Matrix, Omega: Vector) -> Vector:
    return np.concatenate([np.asarray(R, dtype=float).ravel(), np.asarray(Omega, dtype=float)])


def _unpack(y: Vector) -> tuple[Matrix, Vector]:
    return np.asarray(y[:9]).reshape(3, 3), np.asarray(y[9:12])


@dataclass(frozen=True)
class _Leg:
    y_end: Vector
    time: float
    sol: object


def _integrate(md: _Model, y0: Vector, midstance: bool, dense: bool = False, *, rtol: float = RTOL,
               atol: float = ATOL) -> _Leg:
    """Integrate a stance from y0 until the impact event (or the mid-stance crossing when ``midstance``)."""
    events = _events(md)
    if midstance:
        events = [_midstance_event, *events[1:]]
    sol = solve_ivp(
        _rhs(md),
        (0.0, MAX_STANCE_TIME),
        y0,
        method="DOP853",
        rtol=rtol,
        atol=atol,
        events=events,
        dense_output=dense,
    )
    if sol.status == -1:
        raise RuntimeError(f"stance integration failed: {sol.message}")
    if sol.t_events[0].size:
        return _Leg(np.asarray(sol.y_events[0][0], dtype=float), float(sol.t_events[0][0]), sol)
    if sol.t_events[1].size:
        raise RuntimeError("the wheel rolled back onto the trailing foot (no forward step)")
    if sol.t_events[2].size:
        raise RuntimeError("the wheel fell over (hub height below 0.05)")
    raise RuntimeError(f"stance stalled for {MAX_STANCE_TIME} time units")


def _inertia_world(md: _Model, R: Matrix) -> Matrix:
    return R @ np.diag([md.J / 2.0, md.J, md.J / 2.0]) @ R.T


def _impact(md: _Model, R: Matrix, Omega: Vector) -> tuple[Matrix, Vector, Vector]:
    """Vector angular-momentum law about the new foot (001 Sec. 3.2.2). Returns (R+, Omega+, impulse on the
    wheel at the new foot, world frame)."""
    omega = R @ Omega
    r = R[:, 2]  # G - P (old foot), l = 1
    d_new = np.array([md.s2b, 0.0, -md.c2b])
    r_new = -(R @ d_new)  # G - P'
    ic = _inertia_world(md, R)
    h = ic @ omega + np.cross(r_new, np.cross(omega, r))
    a = ic + np.dot(r_new, r_new) * np.eye(3) - np.outer(r_new, r_new)
    omega_plus = np.linalg.solve(a, h)
    impulse = np.cross(omega_plus, r_new) - np.cross(omega, r)
    R_plus = R @ _ry(-2.0 * md.beta)
    return R_plus, R_plus.T @ omega_plus, impulse


def _section_state(y: Vector) -> tuple[Vector, float]:
    """(psi, phi, psi_dot, phi_dot, theta_dot) and theta of a full state."""
    R, Omega = _unpack(y)
    psi, phi, theta = euler_angles(R)
    rates = euler_rates(psi, phi, R @ Omega)
    return np.array([psi, phi, *rates]), theta


def _start(psi: float, phi: float, theta: float, rates: ArrayLike) -> Vector:
    R = pose(psi, phi, theta)
    return _pack(R, R.T @ angular_velocity(psi, phi, rates))


# --- the post-impact map ---------------------------------------------------------------------------------------


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


# --- eigenvalues -----------------------------------------------------------------------------------------------


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
    if not real:
        raise ValueError("no real eigenvalue left for lambda2")
    i_two = max(real, key=lambda i: abs(vecs[4, i]) / norms[i])
    rest = [i for i in rest if i != i_two]
    complex_ = [i for i in rest if abs(vals[i].imag) >= _REAL_TOL]
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
