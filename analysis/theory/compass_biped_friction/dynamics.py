"""Equations of motion of the compass biped with Coulomb friction (002 eq 27) as a stick-slip contact model.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 4 eq 27 (M, B, G, W, W~ in the stance-foot coordinates (theta1, theta2, x, y)), eq 2 (in the sign of
:mod:`mjpoincare.analysis.theory.stick_slip`) with the actuation of eqs 28/30, and Sec. 4.2 (the post-impact section
state); re-derivation on the derivation page docs/theory/stick-slip.md, Sec. 3. Also the heel-strike guards (002 Sec.
4) and the kinematics (point masses, swing foot) from which eq 27 follows.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.actuation import PASSIVE, Actuation, ConstantTorque
from mjpoincare.analysis.theory.compass_biped_friction.params import NQ, FrictionBiped, Matrix, Vector, validate
from numpy.typing import ArrayLike

#: |theta1| (rad) at which the biped counts as fallen.
FALL_ANGLE = 1.2


def mass_matrix(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """M(q) of 002 eq 27 (4 x 4, physical coordinates)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    k, b, m = bp.k, bp.b, bp.m
    c1, s1, c2, s2, c12 = math.cos(th1), math.sin(th1), math.cos(th2), math.sin(th2), math.cos(th1 + th2)
    return np.array(
        [
            [bp.d**2 * m + bp.l**2 * (m + bp.m_h), bp.l * m * b * c12, k * c1, -k * s1],
            [bp.l * m * b * c12, m * b * b, m * b * c2, m * b * s2],
            [k * c1, m * b * c2, bp.total_mass, 0.0],
            [-k * s1, m * b * s2, 0.0, bp.total_mass],
        ]
    )


def coriolis_vector(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> Vector:
    """B(q, qd) of 002 eq 27 (velocity terms on the left-hand side of eq 2)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    w1, w2 = float(np.asarray(qd)[0]) ** 2, float(np.asarray(qd)[1]) ** 2
    k, mb, s12 = bp.k, bp.m * bp.b, math.sin(th1 + th2)
    return np.array(
        [
            -bp.l * mb * s12 * w2,
            -bp.l * mb * s12 * w1,
            -mb * math.sin(th2) * w2 - k * math.sin(th1) * w1,
            -k * math.cos(th1) * w1 + mb * math.cos(th2) * w2,
        ]
    )


def gravity_vector(bp: FrictionBiped, q: ArrayLike) -> Vector:
    """G(q) = dV/dq of 002 eq 27 (left-hand side of eq 2)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    a, g, mt = bp.slope, bp.g, bp.total_mass
    return g * np.array(
        [-bp.k * math.sin(th1 + a), -bp.m * bp.b * math.sin(a - th2), -mt * math.sin(a), mt * math.cos(a)]
    )


def potential_energy(bp: FrictionBiped, q: ArrayLike) -> float:
    """V = g [M_tot (y cos(alpha) - x sin(alpha)) + K cos(theta1 + alpha) - m b cos(theta2 - alpha)] (J), height
    along the true vertical from the slope line through the origin; dV/dq = G of 002 eq 27."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    a = bp.slope
    return bp.g * (
        bp.total_mass * (y * math.cos(a) - x * math.sin(a)) + bp.k * math.cos(th1 + a) - bp.m * bp.b * math.cos(th2 - a)
    )


def kinetic_energy(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """T = qd^T M qd / 2 (J) with M of 002 eq 27."""
    v = np.asarray(qd, dtype=float)[:NQ]
    return 0.5 * float(v @ mass_matrix(bp, q) @ v)


def energy(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """Total mechanical energy T + V (J)."""
    return kinetic_energy(bp, q, qd) + potential_energy(bp, q)


def point_masses(bp: FrictionBiped, q: ArrayLike) -> tuple[tuple[float, Vector], ...]:
    """(mass, slope-frame position) of the stance-leg mass, the hip and the swing-leg mass (002 Sec. 4, Fig. 4.1a):
    the kinematics from which M, B, G of eq 27 follow."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    u1 = np.array([math.sin(th1), math.cos(th1)])
    u2 = np.array([math.sin(th2), -math.cos(th2)])
    foot = np.array([x, y])
    hip = foot + bp.l * u1
    return (bp.m, foot + bp.d * u1), (bp.m_h, hip), (bp.m, hip + bp.b * u2)


def swing_foot(bp: FrictionBiped, q: ArrayLike) -> Vector:
    """Swing-foot position r~ = (x + l(sin theta1 + sin theta2), y + l(cos theta1 - cos theta2)) (002 eq 27)."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    return np.array([x + bp.l * (math.sin(th1) + math.sin(th2)), y + bp.l * (math.cos(th1) - math.cos(th2))])


def swing_jacobian(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """W~(q) = d r~/dq = [[l C1, l C2, 1, 0], [-l S1, l S2, 0, 1]] (002 eq 27)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    l = bp.l
    return np.array(
        [[l * math.cos(th1), l * math.cos(th2), 1.0, 0.0], [-l * math.sin(th1), l * math.sin(th2), 0.0, 1.0]]
    )


def heel_strike_guard(q: ArrayLike) -> float:
    """max(theta2 - theta1, -(theta1 + theta2)): > 0 just after an impact (theta1 = theta2 = -theta*) and while the
    swing foot is behind the stance foot, crossing 0 downwards at the heel strike theta1 = theta2 > 0 (002 Sec. 4;
    the same guard as :mod:`~mjpoincare.analysis.theory.compass_biped` in its angles). It also crosses 0 when the legs
    pass parallel (theta1 + theta2 = 0) with theta1 > theta2, i.e. with the stance leg already past the normal; the
    stance is then continued with :func:`heel_strike_after_scuff` (:func:`step`, ``late_swing``)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    return max(th2 - th1, -(th1 + th2))


def heel_strike_after_scuff(q: ArrayLike) -> float:
    """theta2 - theta1: the guard that continues a stance after the legs passed parallel with theta1 > 0 (see
    :func:`heel_strike_guard`); with direction -1 it ignores the upward crossing where the swing foot, which then
    travels below the ground (ignored like the scuffing of 002 Sec. 4.1), emerges ahead of the stance foot, and
    stops at the heel strike theta1 = theta2 with the foot descending."""
    return float(np.asarray(q)[1] - np.asarray(q)[0])


_JAC = np.zeros((2, NQ + 2))
_JAC[0, 2] = 1.0
_JAC[1, 3] = 1.0


def contact_model(bp: FrictionBiped, actuation: Actuation | None = None) -> ss.ContactModel:
    """The biped as a :class:`.stick_slip.ContactModel` (002 eq 27 with eq 28 or 30) on the
    augmented q = (theta1, theta2, x, y, phi, w): phi the phase clock, w_dot the actuator work
    (:mod:`~mjpoincare.analysis.theory.compass_biped_friction`).

    h = B + G - Q (002 eq 2), W and W~ of eq 27 (zero columns for the clock and accumulator), guard
    :func:`heel_strike_guard`; failure events ``"fell"`` (|theta1| = FALL_ANGLE) and ``"backward"`` (the stance leg
    stops and turns back, theta1_dot -> 0 from above; as for the rimless wheel of 002 Sec. 3.4, no step follows).
    """
    validate(bp)
    act = PASSIVE if actuation is None else actuation
    l, k, mb, mt, g, a = bp.l, bp.k, bp.m * bp.b, bp.total_mass, bp.g, bp.slope
    m11 = bp.d**2 * bp.m + l**2 * (bp.m + bp.m_h)
    mbb = mb * bp.b
    sin_a, cos_a = math.sin(a), math.cos(a)
    passive = isinstance(act, ConstantTorque) and act.tau1 == 0.0 and act.tau2 == 0.0

    def mass(q: Vector) -> Matrix:
        s1, c1, s2, c2 = math.sin(q[0]), math.cos(q[0]), math.sin(q[1]), math.cos(q[1])
        c12 = c1 * c2 - s1 * s2
        return np.array(
            [
                [m11, l * mb * c12, k * c1, -k * s1, 0.0, 0.0],
                [l * mb * c12, mbb, mb * c2, mb * s2, 0.0, 0.0],
                [k * c1, mb * c2, mt, 0.0, 0.0, 0.0],
                [-k * s1, mb * s2, 0.0, mt, 0.0, 0.0],
                [0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            ]
        )

    def bias(q: Vector, qd: Vector) -> Vector:
        s1, c1, s2, c2 = math.sin(q[0]), math.cos(q[0]), math.sin(q[1]), math.cos(q[1])
        s12 = s1 * c2 + c1 * s2
        w1, w2 = qd[0] * qd[0], qd[1] * qd[1]
        q1, q2 = (0.0, 0.0) if passive else act.generalised_force(q[:NQ], qd[:NQ], float(q[4]))
        return np.array(
            [
                -l * mb * s12 * w2 - g * k * (s1 * cos_a + c1 * sin_a) - q1,
                -l * mb * s12 * w1 - g * mb * (sin_a * c2 - cos_a * s2) - q2,
                -mb * s2 * w2 - k * s1 * w1 - mt * g * sin_a,
                -k * c1 * w1 + mb * c2 * w2 + mt * g * cos_a,
                0.0,
                -(q1 * qd[0] + q2 * qd[1]),
            ]
        )

    def swing(q: Vector) -> Matrix:
        return np.array(
            [
                [l * math.cos(q[0]), l * math.cos(q[1]), 1.0, 0.0, 0.0, 0.0],
                [-l * math.sin(q[0]), l * math.sin(q[1]), 0.0, 1.0, 0.0, 0.0],
            ]
        )

    return ss.ContactModel(
        mass_matrix=mass,
        bias=bias,
        contact_jacobian=lambda _q: _JAC,
        contact_jacobian_rate=lambda _q, _qd: np.zeros(2),
        swing_jacobian=swing,
        impact_guard=lambda q, _qd: heel_strike_guard(q),
        guard_direction=-1.0,
        failure_events=(
            ("fell", lambda q, _qd: FALL_ANGLE - abs(float(q[0])), -1.0),
            ("backward", lambda _q, qd: float(qd[0]), -1.0),
        ),
    )


@lru_cache(maxsize=64)
def _model(bp: FrictionBiped, actuation: Actuation) -> ss.ContactModel:
    return contact_model(bp, actuation)


def section_state(z: ArrayLike) -> tuple[Vector, Vector]:
    """Augmented (q, qd) just after an impact from the section z = (theta*, theta1_dot+, theta2_dot+[, x_dot+]):
    theta1 = theta2 = -theta*, x = y = 0, y_dot = 0, clock 0 with rate 1, work 0 (002 Sec. 4.2)."""
    zz = np.asarray(z, dtype=float)
    x_dot = float(zz[3]) if zz.size > 3 else 0.0
    q = np.array([-zz[0], -zz[0], 0.0, 0.0, 0.0, 0.0])
    qd = np.array([zz[1], zz[2], x_dot, 0.0, 1.0, 0.0])
    return q, qd
