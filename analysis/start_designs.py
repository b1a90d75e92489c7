"""Start designs around a fixed point on a Poincaré section: offsets in random directions.

Random directions (uniform on the unit sphere, seeded) sample every direction of the section without favouring
the coordinate axes, so that a return map fitted to the steps that follow sees all its multipliers. Only numpy.

A design's size may be chosen from analytic values that carry roundoff (multipliers from a finite-difference
Jacobian agree to about 1e-10 between BLAS kernels); :func:`design_size` rounds it, so that the starts, and every
sample after them, are the same bits on every CPU.
"""

from __future__ import annotations

import numpy as np

__all__ = ["DESIGN_DIGITS", "design_size", "random_directions", "sphere_offsets"]

#: Significant digits a start design's size keeps: a size within 1e-10 relative of a rounding boundary (one in 1e7)
#: is the only one a kernel's roundoff can still move.
DESIGN_DIGITS = 3


def design_size(size: float, digits: int = DESIGN_DIGITS) -> float:
    """``size`` rounded to ``digits`` significant digits (0 stays 0): a perturbation size derived from analytic values
    (a margin to instability, an impact border) without the roundoff of their computation."""
    if size == 0.0 or not np.isfinite(size):
        return size
    return float(f"{size:.{digits - 1}e}")


def random_directions(count: int, dim: int, seed: int = 0) -> np.ndarray:
    """``count`` unit vectors (count, dim), uniform on the sphere: normalised standard normal draws of
    ``np.random.default_rng(seed)``."""
    directions = np.random.default_rng(seed).normal(size=(count, dim))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return directions


def sphere_offsets(center: np.ndarray, scales: np.ndarray, count: int, seed: int = 0) -> np.ndarray:
    """``center`` (d,) and ``count`` starts offset from it (count + 1, d), row 0 the centre itself: start k is
    ``center + scales * u_k`` in the coordinates with a nonzero entry of ``scales`` (d,), u_k from
    :func:`random_directions` in as many dimensions; the other coordinates stay at ``center``."""
    moved = np.flatnonzero(scales)
    directions = random_directions(count, moved.size, seed)
    out = np.repeat(np.asarray(center, dtype=float)[None, :], count + 1, axis=0)
    for j, i in enumerate(moved):
        out[1:, i] += scales[i] * directions[:, j]
    return out
