"""Tests of analysis.start_designs: seeded random directions and offsets around a fixed point."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.start_designs import random_directions, sphere_offsets


def test_random_directions_unit_seeded_and_spread() -> None:
    d = random_directions(400, 3)
    assert d.shape == (400, 3)
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 1.0, rtol=1e-12)
    np.testing.assert_array_equal(d, random_directions(400, 3, seed=0))
    assert not np.array_equal(d, random_directions(400, 3, seed=1))
    assert np.all(np.abs(d.mean(axis=0)) < 0.15)  # no preferred direction
    assert np.all(d.min(axis=0) < -0.9) and np.all(d.max(axis=0) > 0.9)


def test_sphere_offsets_centre_first_and_scaled_per_coordinate() -> None:
    center = np.array([1.0, 2.0, 3.0, 4.0])
    scales = np.array([0.1, 0.0, 1.0, 1.0])
    out = sphere_offsets(center, scales, 50, seed=3)
    assert out.shape == (51, 4)
    np.testing.assert_array_equal(out[0], center)
    np.testing.assert_array_equal(out[:, 1], 2.0)  # zero scale: not moved
    u = (out[1:] - center)[:, [0, 2, 3]] / scales[[0, 2, 3]]
    np.testing.assert_allclose(u, random_directions(50, 3, seed=3), rtol=0, atol=1e-12)


def test_sphere_offsets_leaves_center_unchanged() -> None:
    center = np.array([0.5, -0.5])
    sphere_offsets(center, np.array([1.0, 1.0]), 4)
    np.testing.assert_array_equal(center, [0.5, -0.5])
