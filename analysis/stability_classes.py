"""Stability classes of a map's multiplier over a parameter grid, and the cells an analytic class boundary crosses
(numpy only): the four regions of straight motion of the discrete Chaplygin sleigh, Coleman & Holmes (1999)
(3.11)-(3.12) and Fig. 2, from sigma4 (3.10), measured or exact."""

from __future__ import annotations

import numpy as np


def region_classes(sigma: np.ndarray) -> np.ndarray:
    """0 unstable, 1 stable, 2 stable wobble (-1 < sigma4 < 0), 3 unstable wobble (sigma4 < -1); NaN -> -1."""
    stable, wobble = np.abs(sigma) < 1, sigma < 0
    out = np.where(wobble, np.where(stable, 2, 3), np.where(stable, 1, 0))
    return np.where(np.isfinite(sigma), out, -1)


def boundary_cells(classes: np.ndarray, sigma: np.ndarray, tol: float = 1e-3) -> np.ndarray:
    """Cells the analytic boundary crosses: a neighbour has another class, or |sigma4| is within ``tol`` of 1
    or sigma4 of 0 (the class there is decided by round-off)."""
    edge = (np.abs(np.abs(sigma) - 1.0) < tol) | (np.abs(sigma) < tol)
    for axis in (-1, -2):
        diff = np.diff(classes, axis=axis) != 0
        pad_lo = [(0, 0)] * classes.ndim
        pad_hi = [(0, 0)] * classes.ndim
        pad_lo[axis], pad_hi[axis] = (1, 0), (0, 1)
        edge |= np.pad(diff, pad_lo) | np.pad(diff, pad_hi)
    return edge
