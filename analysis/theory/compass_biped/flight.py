"""The compass-gait biped with neither foot on the ground: its 4-DOF dynamics in MuJoCo's coordinates, and the
released trailing foot's slope-normal acceleration at heel strike.

Source: the point-mass biped of 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4,
Sec. 4.1 and Fig. 15 (the model of Goswami, Thuilot & Espiau 1998): hip mass m_h, each leg's mass m_l at a from its
foot (b from the hip), l = a + b, with the constant torques of eq 4.5 (hip torque between the legs, B = (-1, 1);
ground's ankle torque on the stance leg; senses in :mod:`~mjpoincare.analysis.theory.compass_biped`). 003 writes the
swing with the stance foot pinned (eq 4.5); at a heel strike the trailing foot is released, and with the stance contact
gone the hip is free to translate. Derived here from the Lagrangian of the point masses.

Coordinates (MuJoCo's: ``models/compass_biped.xml``): q = (x, z, phi_0, phi_1), the hip's position in the slope
frame (+x downhill along the slope, +z along its normal) and the two legs' hinge angles phi_i = theta_i - gamma
(foot -> hip direction from the slope normal, clockwise positive); gravity is tilted, g_vec = g (sin gamma,
-cos gamma). With u(phi) = (sin phi, cos phi), c_i = cos phi_i, s_i = sin phi_i and M_t = m_h + 2 m_l:

* positions: hip p_h = (x, z), leg i's mass p_i = p_h - b u(phi_i), its foot sphere's centre p_h - (l - r) u(phi_i)
  (MuJoCo's point foot is a sphere of radius r whose surface is at the leg's end, so its centre is at l - r);
* T = M_t (xd^2 + zd^2)/2 + sum_i m_l [b^2 phid_i^2 - 2 b phid_i (xd c_i - zd s_i)]/2, U = -sum_k m_k g_vec . p_k
  = -M_t g (x sin gamma - z cos gamma) - m_l b g sum_i cos(phi_i + gamma);
* Lagrange's equations M(q) qdd + h(q, qd) = G(q) + Q with
  M = [[M_t, 0, -m_l b c_0, -m_l b c_1], [0, M_t, m_l b s_0, m_l b s_1], [., ., m_l b^2, 0], [., ., 0, m_l b^2]]
  (symmetric), the velocity terms h = (m_l b sum_i s_i phid_i^2, m_l b sum_i c_i phid_i^2, 0, 0) (a leg's own rows
  have none: its d/dt dT/dphid_i and dT/dphi_i both hold m_l b phid_i (xd s_i + zd c_i)), gravity G = -dU/dq =
  (M_t g sin gamma, -M_t g cos gamma, -m_l b g sin(phi_0 + gamma), -m_l b g sin(phi_1 + gamma)) and the hinge
  torques Q = (0, 0, Q_0, Q_1).

M, h and G depend on the legs' angles and rates only (the dynamics are invariant under translation of the hip).
Pinning a foot (x = l sin phi_st, z = l cos phi_st about the stance foot) projects M and G onto 003 eq 4.5's mass
matrix and gravity term; the hip's x and z rows are the whole biped's momentum balance, M_t times its centre of
mass's acceleration = M_t g_vec (the torques are couples).
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped
from numpy.typing import ArrayLike, NDArray


def mass_matrix(bp: CompassBiped, angles: ArrayLike) -> NDArray[np.float64]:
    """M(q) of the free biped in q = (x, z, phi_0, phi_1) at hinge angles ``angles`` = (phi_0, phi_1) (module
    docstring)."""
    (c0, c1), (s0, s1) = np.cos(angles), np.sin(angles)
    mb, total = bp.m_l * bp.b, bp.m_h + 2.0 * bp.m_l
    return np.array([[total, 0.0, -mb * c0, -mb * c1],
                     [0.0, total, mb * s0, mb * s1],
                     [-mb * c0, mb * s0, mb * bp.b, 0.0],
                     [-mb * c1, mb * s1, 0.0, mb * bp.b]])


def velocity_terms(bp: CompassBiped, angles: ArrayLike, rates: ArrayLike) -> NDArray[np.float64]:
    """h(q, qd) = C(q, qd) qd: (m_l b sum s_i phid_i^2, m_l b sum c_i phid_i^2, 0, 0) (module docstring)."""
    phi, w2 = np.asarray(angles, dtype=float), np.asarray(rates, dtype=float) ** 2
    mb = bp.m_l * bp.b
    return np.array([mb * float(np.sin(phi) @ w2), mb * float(np.cos(phi) @ w2), 0.0, 0.0])


def gravity_forces(bp: CompassBiped, angles: ArrayLike) -> NDArray[np.float64]:
    """G(q) = -dU/dq: (M_t g sin gamma, -M_t g cos gamma, -m_l b g sin(phi_i + gamma)) (module docstring)."""
    phi = np.asarray(angles, dtype=float)
    g, total = bp.gravity, bp.m_h + 2.0 * bp.m_l
    legs = -bp.m_l * bp.b * g * np.sin(phi + bp.slope)
    return np.array([total * g * math.sin(bp.slope), -total * g * math.cos(bp.slope), *legs])


def accelerations(bp: CompassBiped, angles: ArrayLike, rates: ArrayLike, hinge_torques: ArrayLike
                  ) -> NDArray[np.float64]:
    """qdd = (xdd, zdd, phidd_0, phidd_1) = M^-1 (G + Q - h) of the free biped, Q = (0, 0, ``hinge_torques``)."""
    forces = gravity_forces(bp, angles) - velocity_terms(bp, angles, rates)
    forces[2:] += np.asarray(hinge_torques, dtype=float)
    return np.linalg.solve(mass_matrix(bp, angles), forces)


def release_torques(bp: CompassBiped) -> tuple[float, float]:
    """Hinge torques (Q_trailing, Q_leading) once the trailing foot is released at heel strike: the leading leg is
    the new stance leg (003 eq 4.7's relabelling), so it carries the ground's ankle torque and the hip torque acts
    with B = (-1, 1) from it to the trailing (new swing) leg: (tau_hip, tau_ankle - tau_hip) (003 eq 4.5)."""
    return bp.tau_hip, bp.tau_ankle - bp.tau_hip


def release_acceleration(bp: CompassBiped, x_minus: ArrayLike, foot_radius: float) -> float:
    """Slope-normal acceleration (m/s^2, < 0 downward) of the trailing foot released at the pre-impact state
    ``x_minus`` = (theta_st, theta_sw, dtheta_st, dtheta_sw) (003's frame: the stance leg is the trailing one),
    with :func:`release_torques`: the free biped's accelerations, then the foot sphere's centre at l - r from the hip,
    z - (l - r) cos phi, twice differentiated:
    a = zdd + (l - r) (sin phi phidd + cos phi phid^2), phi = theta_st - gamma."""
    x = np.asarray(x_minus, dtype=float)
    angles, rates = x[:2] - bp.slope, x[2:]
    qdd = accelerations(bp, angles, rates, release_torques(bp))
    phi, rate = float(angles[0]), float(rates[0])
    return float(qdd[1]) + (bp.l - foot_radius) * (math.sin(phi) * float(qdd[2]) + math.cos(phi) * rate * rate)
