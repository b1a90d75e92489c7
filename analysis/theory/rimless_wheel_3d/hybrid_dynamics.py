"""Stance and impact of the exact 3D rimless-wheel reference: Newton-Euler about the foot, angular-momentum impact.

Source: 001 = Coleman, Chatterjee & Ruina (1997), "Motions of a rimless spoked wheel: a simple 3D system with
impacts", Sec. 3, solved generically (m = l = g = 1): the stance about a frictional ball-joint foot (001 eq 3 replaced
by Newton-Euler) integrated with DOP853 to the next foot's touchdown (or rolling back, falling, the mid-stance
crossing), and the impact by conservation of angular momentum about the new foot (001 Sec. 3.2.2, eqs 4-6, not via the
Euler-rate matrix); model in :mod:`mjpoincare.analysis.theory.rimless_wheel_3d.hybrid`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_3d import RimlessWheel3D, validate
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler import (
    Matrix,
    Vector,
    _ry,
    angular_velocity,
    euler_angles,
    euler_rates,
    pose,
)
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

RTOL = 1e-12
ATOL = 1e-12
#: A stance longer than this (time units sqrt(l/g)) is declared stalled.
MAX_STANCE_TIME = 200.0
#: Hub height below which the wheel is declared fallen.
FALLEN_HEIGHT = 0.05


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
