"""analysis.stability_classes: the four classes of straight motion by sigma4 (Coleman & Holmes 1999, 3.11-3.12)
and the cells an analytic class boundary crosses, on hand-made grids."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.stability_classes import boundary_cells, region_classes


def test_classes_of_each_region_and_nan() -> None:
    sigma = np.array([1.5, 0.5, -0.5, -1.5, np.nan, 1.0, -1.0, 0.0])
    assert region_classes(sigma).tolist() == [0, 1, 2, 3, -1, 0, 3, 1]


def test_boundary_cells_mark_class_changes_and_near_critical_values() -> None:
    sigma = np.array([[[0.5, 0.5, 1.5], [0.5, 0.5, 1.5], [0.5, 0.5, 0.5]]])  # (direction, y, x)
    edge = boundary_cells(region_classes(sigma), sigma)
    assert edge.tolist() == [[[False, True, True], [False, True, True], [False, False, True]]]
    near = np.full((1, 2, 2), 0.5)
    near[0, 1, 1] = 1.0 - 5e-4  # within tol of |sigma4| = 1: its class is decided by round-off
    assert boundary_cells(region_classes(near), near).tolist() == [[[False, False], [False, True]]]
    zero = np.full((1, 2, 2), 0.5)
    zero[0, 0, 0] = 1e-4  # within tol of sigma4 = 0
    assert boundary_cells(region_classes(zero), zero, tol=1e-3)[0, 0, 0]
    assert not boundary_cells(region_classes(zero), zero, tol=1e-5).any()
