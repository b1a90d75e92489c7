"""Equations of motion and heel-strike impact law of the compass-gait biped (003 eqs 4.1-4.19).

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4: the swing EoM of eq 4.5 (M,
C, G and the hip torque's B = (-1, 1), plus the ankle torque), its closed-form solve, the energy, the swing-foot
height of eqs 4.1-4.3, and the impact of eqs 4.7 and 4.15-4.18 (angular momenta of the whole biped about the new
contact and of the trailing leg about the hip); re-derived, both agree with the thesis.
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped
from numpy.typing import ArrayLike, NDArray


def mass_matrix(bp: CompassBiped, q: ArrayLike) -> NDArray[np.float64]:
    """Inertia matrix M(q) of 003 eq 4.5:
    [[m_l a^2 + (m_h + m_l) l^2, -m_l b l cos(theta_st - theta_sw)], [., m_l b^2]]."""
    th_st, th_sw = np.asarray(q, dtype=float)
    off = -bp.m_l * bp.b * bp.l * math.cos(th_st - th_sw)
    return np.array([[bp.m_l * bp.a**2 + (bp.m_h + bp.m_l) * bp.l**2, off], [off, bp.m_l * bp.b**2]])


def coriolis(bp: CompassBiped, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
    """Coriolis/centrifugal matrix C(q, qd) of 003 eq 4.5:
    [[0, -m_l b l sin(Delta) dtheta_sw], [m_l b l sin(Delta) dtheta_st, 0]], Delta = theta_st - theta_sw."""
    th_st, th_sw = np.asarray(q, dtype=float)
    om_st, om_sw = np.asarray(qd, dtype=float)
    k = bp.m_l * bp.b * bp.l * math.sin(th_st - th_sw)
    return np.array([[0.0, -k * om_sw], [k * om_st, 0.0]])


def gravity_vector(bp: CompassBiped, q: ArrayLike) -> NDArray[np.float64]:
    """Gravity term G(q) of 003 eq 4.5 (on the right-hand side, G = -dU/dq):
    (g sin(theta_st) (m_l a + m_h l + m_l l), -g m_l b sin(theta_sw))."""
    th_st, th_sw = np.asarray(q, dtype=float)
    g = bp.gravity
    return np.array(
        [g * math.sin(th_st) * (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l), -g * bp.m_l * bp.b * math.sin(th_sw)]
    )


def _qdd(bp: CompassBiped, th_st: float, th_sw: float, om_st: float, om_sw: float, tau: float) -> tuple[float, float]:
    """Scalar solve of M qdd = G + B (tau_hip + tau) + (tau_ankle, 0) - C qd (003 eq 4.5) by the closed-form 2x2
    inverse (``tau`` is an extra hip torque on top of the model's constant ones)."""
    s, c = math.sin(th_st - th_sw), math.cos(th_st - th_sw)
    mbl = bp.m_l * bp.b * bp.l
    m11 = bp.m_l * bp.a**2 + (bp.m_h + bp.m_l) * bp.l**2
    m12 = -mbl * c
    m22 = bp.m_l * bp.b**2
    g = bp.gravity
    hip = bp.tau_hip + tau
    r1 = g * math.sin(th_st) * (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l) - hip + bp.tau_ankle + mbl * s * om_sw**2
    r2 = -g * bp.m_l * bp.b * math.sin(th_sw) + hip - mbl * s * om_st**2
    det = m11 * m22 - m12 * m12
    return (m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det


def swing_dynamics(bp: CompassBiped, q: ArrayLike, qd: ArrayLike, tau_hip: float = 0.0) -> NDArray[np.float64]:
    """Accelerations qdd = M^-1 (G + B tau - C qd) of 003 eq 4.5 with B = (-1, 1) (tau > 0 counter-clockwise
    on the swing leg), tau = the model's tau_hip + ``tau_hip``, plus the model's ankle torque; passive swing 003
    eq 4.19 when all torques are 0."""
    th_st, th_sw = np.asarray(q, dtype=float)
    om_st, om_sw = np.asarray(qd, dtype=float)
    return np.array(_qdd(bp, th_st, th_sw, om_st, om_sw, tau_hip))


def energy(bp: CompassBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """Total energy T + U (J), T = qd^T M qd / 2 and U = g[(m_l a + (m_h + m_l) l) cos theta_st
    - m_l b cos theta_sw] with the height measured from the stance foot along the TRUE vertical (003 Sec. 4.1)."""
    th_st, th_sw = np.asarray(q, dtype=float)
    qd_arr = np.asarray(qd, dtype=float)
    kinetic = 0.5 * float(qd_arr @ mass_matrix(bp, (th_st, th_sw)) @ qd_arr)
    potential = bp.gravity * (
        (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l) * math.cos(th_st) - bp.m_l * bp.b * math.cos(th_sw)
    )
    return kinetic + potential


def swing_foot_height(bp: CompassBiped, q: ArrayLike) -> float:
    """Swing-foot height above the slope along its normal (003 eqs 4.1-4.3):
    h = l [cos(theta_st - gamma) - cos(theta_sw - gamma)]
      = -2 l sin((theta_st + theta_sw - 2 gamma)/2) sin((theta_st - theta_sw)/2)."""
    th_st, th_sw = np.asarray(q, dtype=float)
    return bp.l * (math.cos(th_st - bp.slope) - math.cos(th_sw - bp.slope))


def impact_matrices(bp: CompassBiped, half_angle: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Q+, Q-) of 003 eqs 4.15/4.16 for the half inter-leg angle alpha = (theta_st- - theta_sw-)/2.

    Row 1: angular momentum of the whole biped about the new contact point; row 2: of the trailing leg about the
    hip (003 eqs 4.9-4.14). Re-derived: identical to the thesis.
    """
    c2 = math.cos(2.0 * half_angle)
    m_h, m_l, a, b, l = bp.m_h, bp.m_l, bp.a, bp.b, bp.l
    q_plus = np.array(
        [
            [m_l * (b * l * c2 - l**2 - a**2) - m_h * l**2, m_l * (b * l * c2 - b**2)],
            [m_l * b * l * c2, -m_l * b**2],
        ]
    )
    q_minus = np.array([[m_l * (a * b - 2.0 * a * l * c2) - m_h * l**2 * c2, m_l * a * b], [m_l * a * b, 0.0]])
    return q_plus, q_minus


def impact_map(bp: CompassBiped, x_minus: ArrayLike) -> NDArray[np.float64]:
    """Heel-strike map x- -> x+ (003 eq 4.18): q+ = R q- with R = [[0, 1], [1, 0]] (003 eqs 4.7/4.8) and
    qd+ = Q+^-1 Q- qd- (003 eq 4.17)."""
    x = np.asarray(x_minus, dtype=float)
    q_plus, q_minus = impact_matrices(bp, 0.5 * (x[0] - x[1]))
    return np.concatenate([x[1::-1], np.linalg.solve(q_plus, q_minus @ x[2:])])
