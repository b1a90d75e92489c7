"""Tests of analysis.rigid_body_kinematics on rotations whose quaternions and 3-1-2 Euler angles (001 Sec. 2) are
known, and against the scalar forms of the exact reference (analysis.theory.rimless_wheel_3d_hybrid)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.rigid_body_kinematics import euler_state, matrix_to_quat, quat_to_matrix
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid

#: Rotations about x, y and z by ``angle``: (unit axis index, expected matrix).
AXES = {0: lambda c, s: [[1, 0, 0], [0, c, -s], [0, s, c]],
        1: lambda c, s: [[c, 0, s], [0, 1, 0], [-s, 0, c]],
        2: lambda c, s: [[c, -s, 0], [s, c, 0], [0, 0, 1]]}


def axis_quat(axis: int, angle: float) -> np.ndarray:
    """(cos(angle/2), sin(angle/2) e_axis)."""
    q = np.zeros(4)
    q[0], q[1 + axis] = math.cos(angle / 2), math.sin(angle / 2)
    return q


@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("angle", [0.3, -1.1, 3.0])
def test_quat_to_matrix_of_axis_rotations(axis: int, angle: float) -> None:
    """A quaternion about one axis is the right-handed rotation about it (not its transpose), normalised first."""
    expected = np.array(AXES[axis](math.cos(angle), math.sin(angle)))
    np.testing.assert_allclose(quat_to_matrix(axis_quat(axis, angle)), expected, atol=1e-15)
    np.testing.assert_allclose(quat_to_matrix(2.5 * axis_quat(axis, angle)), expected, atol=1e-15)


@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("angle", [0.3, 2.9, math.pi])
def test_matrix_to_quat_every_branch(axis: int, angle: float) -> None:
    """Small angles take the trace branch, angles near pi the branch of the rotation axis: each returns the axis
    quaternion with its largest component positive."""
    R = np.array(AXES[axis](math.cos(angle), math.sin(angle)))
    np.testing.assert_allclose(matrix_to_quat(R), axis_quat(axis, angle), atol=1e-15)


def test_round_trips() -> None:
    """matrix -> quaternion -> matrix is the identity; quaternion -> matrix -> quaternion up to the sign of q."""
    rng = np.random.default_rng(0)
    quats = rng.normal(size=(200, 4))
    quats /= np.linalg.norm(quats, axis=1, keepdims=True)
    mats = quat_to_matrix(quats)
    np.testing.assert_allclose(mats @ np.swapaxes(mats, -1, -2), np.broadcast_to(np.eye(3), mats.shape), atol=1e-14)
    for q, R in zip(quats, mats, strict=True):
        back = matrix_to_quat(R)
        np.testing.assert_allclose(back * np.sign(back @ q), q, atol=1e-14)
        np.testing.assert_allclose(quat_to_matrix(back), R, atol=1e-14)


def test_euler_state_of_the_reference_pose() -> None:
    """The pose R = Rz(psi) Rx(phi) Ry(theta) and the body-axis rate R^T omega of the reference read back as
    (psi, phi, theta, psi_dot, phi_dot, theta_dot), one state or a batch of them."""
    rng = np.random.default_rng(1)
    q = np.column_stack([rng.uniform(-3.0, 3.0, 6), rng.uniform(-1.4, 1.4, 6), rng.uniform(-3.0, 3.0, 6),
                         rng.normal(size=(6, 3))])
    quats, omegas = [], []
    for psi, phi, theta, *rates in q:
        R = hybrid.pose(psi, phi, theta)
        quats.append(matrix_to_quat(R))
        omegas.append(R.T @ hybrid.angular_velocity(psi, phi, rates))
    batch = euler_state(np.reshape(quats, (2, 3, 4)), np.reshape(omegas, (2, 3, 3)))
    assert batch.shape == (2, 3, 6)
    np.testing.assert_allclose(batch.reshape(6, 6), q, atol=1e-12)
    np.testing.assert_allclose(euler_state(quats[0], omegas[0]), q[0], atol=1e-12)


def test_euler_rates_of_known_motions() -> None:
    """Spinning about the axle (body y) is pure pitch rate; turning about the slope normal is pure heading rate
    whatever the pitch; a lean rate about the heading's x' axis shows as phi_dot."""
    pitched = matrix_to_quat(hybrid.pose(0.0, 0.0, 0.4))
    np.testing.assert_allclose(euler_state(pitched, np.array([0.0, 2.0, 0.0])), [0, 0, 0.4, 0, 0, 2.0], atol=1e-15)
    R = hybrid.pose(0.5, 0.0, 0.4)
    turning = euler_state(matrix_to_quat(R), R.T @ np.array([0.0, 0.0, 1.5]))
    np.testing.assert_allclose(turning, [0.5, 0, 0.4, 1.5, 0, 0], atol=1e-15)
    leaning = euler_state(matrix_to_quat(R), R.T @ (0.7 * np.array([math.cos(0.5), math.sin(0.5), 0.0])))
    np.testing.assert_allclose(leaning, [0.5, 0, 0.4, 0, 0.7, 0], atol=1e-15)
