"""The compass biped with Coulomb friction in floating-base coordinates, for the time-stepping scheme.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", Secs. 4-5: the biped of eq 27
re-derived from the Lagrangian of its three point masses with the hip and the absolute leg angles as coordinates (M, F
and the feet's Jacobians, :mod:`mjpoincare.analysis.theory.compass_biped_friction.time_stepping`), and the actuation of
Sec. 5 as physical couples: constant torques (eq 28, Gaits I and II) and PD tracking with phase reset (eq 30, Gait III).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.actuation import ReferenceTrajectory
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped
from numpy.typing import ArrayLike, NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]

#: (theta1, theta2, theta1_dot, theta2_dot, phase) -> (ankle, hip) torques (N m), angles and rates in 002's
#: stance-foot convention (theta1 = -phi1, theta2 = phi2), phase = time since the last heel strike.
Controller = Callable[[float, float, float, float, float], tuple[float, float]]


def constant_torques(ankle: float, hip: float) -> Controller:
    """Open-loop constant ankle and hip torques (N m), 002 Sec. 5 (Gaits I, II)."""
    return lambda *_args: (ankle, hip)


def pd_tracking(reference: ReferenceTrajectory, kp: float = 15.0, kd: float = 15.0) -> Controller:
    """002 eq 30 with phase reset: tau_i = -kp (theta_i - theta_i^r(phi)) - kd (theta_i_dot - theta_i_dot^r(phi))
    as the generalised force on each of 002's angles (Q_theta = (tau1, tau2)); as physical couples that is
    hip = tau2 and ankle = tau1 - tau2 (Q_theta1 = ankle + hip, Q_theta2 = hip by virtual work)."""

    def control(th1: float, th2: float, w1: float, w2: float, phase: float) -> tuple[float, float]:
        r1, r2, v1, v2 = reference.evaluate(phase)
        tau1 = -kp * (th1 - r1) - kd * (w1 - v1)
        tau2 = -kp * (th2 - r2) - kd * (w2 - v2)
        return tau1 - tau2, tau2

    return control


def mass_matrix(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """M(q) of the floating-base Lagrangian (:mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping`),
    (4, 4)."""
    p1, p2 = float(np.asarray(q)[2]), float(np.asarray(q)[3])
    mt, mb = bp.total_mass, bp.m * bp.b
    c1, s1, c2, s2 = math.cos(p1), math.sin(p1), math.cos(p2), math.sin(p2)
    return np.array([[mt, 0.0, mb * c1, mb * c2], [0.0, mt, mb * s1, mb * s2],
                     [mb * c1, mb * s1, mb * bp.b, 0.0], [mb * c2, mb * s2, 0.0, mb * bp.b]])


def free_force(bp: FrictionBiped, q: ArrayLike, v: ArrayLike, ankle: float = 0.0, hip: float = 0.0) -> Vector:
    """F(q, q_dot): gravity, the velocity terms and the couples' generalised force
    (:mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping`), (4,)."""
    p1, p2 = float(np.asarray(q)[2]), float(np.asarray(q)[3])
    w1, w2 = float(np.asarray(v)[2]), float(np.asarray(v)[3])
    mt, mb, g, a = bp.total_mass, bp.m * bp.b, bp.g, bp.slope
    return np.array([
        mt * g * math.sin(a) + mb * (math.sin(p1) * w1 * w1 + math.sin(p2) * w2 * w2),
        -mt * g * math.cos(a) - mb * (math.cos(p1) * w1 * w1 + math.cos(p2) * w2 * w2),
        -mb * g * math.sin(p1 - a) - ankle - hip,
        -mb * g * math.sin(p2 - a) + hip,
    ])


def foot(bp: FrictionBiped, q: ArrayLike, leg: int) -> Vector:
    """Slope-frame position (x, y) of foot ``leg`` (0 or 1), y its height above the slope."""
    x_h, y_h = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    phi = float(np.asarray(q)[2 + leg])
    return np.array([x_h + bp.l * math.sin(phi), y_h - bp.l * math.cos(phi)])


def foot_jacobian(bp: FrictionBiped, q: ArrayLike, leg: int) -> Matrix:
    """d(foot)/dq, rows (tangential, normal), (2, 4)."""
    phi = float(np.asarray(q)[2 + leg])
    jac = np.zeros((2, 4))
    jac[0, 0] = jac[1, 1] = 1.0
    jac[0, 2 + leg] = bp.l * math.cos(phi)
    jac[1, 2 + leg] = bp.l * math.sin(phi)
    return jac


def energy(bp: FrictionBiped, q: ArrayLike, v: ArrayLike) -> float:
    """Kinetic plus potential energy (J), potential 0 at the slope-frame origin."""
    vv = np.asarray(v, dtype=float)
    x_h, y_h, p1, p2 = (float(c) for c in np.asarray(q))
    ca, sa = math.cos(bp.slope), math.sin(bp.slope)

    def height(x: float, y: float) -> float:
        return y * ca - x * sa

    b = bp.b
    pot = bp.m_h * height(x_h, y_h) + sum(bp.m * height(x_h + b * math.sin(p), y_h - b * math.cos(p)) for p in (p1, p2))
    return 0.5 * float(vv @ mass_matrix(bp, q) @ vv) + bp.g * pot
