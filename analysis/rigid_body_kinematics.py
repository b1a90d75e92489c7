"""Orientation of a rigid body: unit quaternions, rotation matrices and the 3-1-2 Euler angles of 001.

001 = Coleman, Chatterjee & Ruina (1997), Sec. 2: the stance-spoke frame in the slope frame is
R = Rz(psi) Rx(phi) Ry(theta) (heading psi, bank phi, pitch theta) and the world angular velocity is
omega = psi_dot e_z + phi_dot x' + theta_dot y''; q = (psi, phi, theta, psi_dot, phi_dot, theta_dot) is the paper's
state (eq 2). Quaternions are (w, x, y, z), scalar first, as a simulator stores them; angular velocities given in
body axes are Omega = R^T omega. Arrays and formulas only (numpy); the scalar forms of the same angles, used by the
exact reference, are in :mod:`mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["euler_state", "matrix_to_quat", "quat_to_matrix"]


def quat_to_matrix(quat: np.ndarray) -> np.ndarray:
    """Rotation matrices ``(..., 3, 3)`` of quaternions ``(..., 4)`` (w, x, y, z), normalised first."""
    q = quat / np.linalg.norm(quat, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=-2)


def matrix_to_quat(R: np.ndarray) -> np.ndarray:
    """Unit quaternion ``(4,)`` (w, x, y, z) of one rotation matrix ``(3, 3)``.

    Shepperd's method: the component of largest magnitude is taken from the trace or a diagonal entry, the others
    from the off-diagonal sums and differences (the branches and operation order of MuJoCo's ``mju_mat2Quat``, so
    the two agree to the last bit); the result is renormalised only if its norm is off 1 by more than 1e-15.
    """
    m = np.asarray(R, dtype=float).ravel()
    q = np.empty(4)
    if m[0] + m[4] + m[8] > 0:
        q[0] = 0.5 * np.sqrt(1 + m[0] + m[4] + m[8])
        q[1:] = 0.25 * np.array([m[7] - m[5], m[2] - m[6], m[3] - m[1]]) / q[0]
    elif m[0] > m[4] and m[0] > m[8]:
        q[1] = 0.5 * np.sqrt(1 + m[0] - m[4] - m[8])
        q[[0, 2, 3]] = 0.25 * np.array([m[7] - m[5], m[1] + m[3], m[2] + m[6]]) / q[1]
    elif m[4] > m[8]:
        q[2] = 0.5 * np.sqrt(1 - m[0] + m[4] - m[8])
        q[[0, 1, 3]] = 0.25 * np.array([m[2] - m[6], m[1] + m[3], m[5] + m[7]]) / q[2]
    else:
        q[3] = 0.5 * np.sqrt(1 - m[0] - m[4] + m[8])
        q[:3] = 0.25 * np.array([m[3] - m[1], m[2] + m[6], m[5] + m[7]]) / q[3]
    norm = np.sqrt((q[0] * q[0] + q[1] * q[1]) + (q[2] * q[2] + q[3] * q[3]))
    if abs(norm - 1.0) > 1e-15:
        q *= 1.0 / norm
    return q


def euler_state(quat: np.ndarray, omega_body: np.ndarray) -> np.ndarray:
    """The paper's state q = (psi, phi, theta, psi_dot, phi_dot, theta_dot) ``(..., 6)`` (001 eq 2) of orientations
    ``(..., 4)`` and body-axis angular velocities ``(..., 3)``, in R = Rz(psi) Rx(phi) Ry(theta) (001 Sec. 2).

    phi = asin R21, theta = atan2(-R20, R22), psi = atan2(-R01, R11) (|phi| < pi/2); with omega = R Omega:
    phi_dot = omega . x', theta_dot cos(phi) = omega . (-sin psi, cos psi, 0), psi_dot = omega_z - theta_dot sin(phi).
    """
    R = quat_to_matrix(quat)
    phi = np.arcsin(np.clip(R[..., 2, 1], -1.0, 1.0))
    theta = np.arctan2(-R[..., 2, 0], R[..., 2, 2])
    psi = np.arctan2(-R[..., 0, 1], R[..., 1, 1])
    omega = np.einsum("...ij,...j->...i", R, omega_body)
    cpsi, spsi = np.cos(psi), np.sin(psi)
    phi_dot = omega[..., 0] * cpsi + omega[..., 1] * spsi
    theta_dot = (-omega[..., 0] * spsi + omega[..., 1] * cpsi) / np.cos(phi)
    psi_dot = omega[..., 2] - theta_dot * np.sin(phi)
    return np.stack([psi, phi, theta, psi_dot, phi_dot, theta_dot], axis=-1)
