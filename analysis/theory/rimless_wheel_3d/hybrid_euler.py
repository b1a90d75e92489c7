"""The 3-1-2 Euler angles of the 3D rimless wheel in scalar form: pose, angles and rates (001 Sec. 2).

Source: 001 = Coleman, Chatterjee & Ruina (1997), "Motions of a rimless spoked wheel: a simple 3D system with
impacts", Sec. 2 and eq 2: the stance-spoke frame R = Rz(psi) Rx(phi) Ry(theta) in the slope frame, its angles, the
world angular velocity omega = psi_dot e_z + phi_dot x' + theta_dot y'' and the paper's state q. The exact reference
:mod:`mjpoincare.analysis.theory.rimless_wheel_3d.hybrid` uses them only at its sections; the array forms for
simulator output are in :mod:`mjpoincare.analysis.rigid_body_kinematics`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]


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
