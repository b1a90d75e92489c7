"""The polynomial basis of the fitted return maps: monomials, their values and gradients, and a per-step regression.

The regression matrix of all monomials of total degree <= 1, 2 or 3 in the section coordinates, its derivative at a
point (the Jacobian of a fitted map), the shape checks of a set of pairs, and :func:`regress_at`, which reads a
per-step quantity at a fixed point by the same least squares. Only numpy is used.
"""

from __future__ import annotations

from functools import lru_cache
from itertools import combinations_with_replacement

import numpy as np

_SUPPORTED_DEGREES = (1, 2, 3)


def _monomials(dim: int, degree: int) -> list[tuple[int, ...]]:
    """Index tuples of all monomials of total degree ``<= degree`` (``()`` is the constant)."""
    terms: list[tuple[int, ...]] = []
    for order in range(degree + 1):
        terms.extend(combinations_with_replacement(range(dim), order))
    return terms


@lru_cache(maxsize=64)
def _exponents(terms: tuple[tuple[int, ...], ...], dim: int) -> np.ndarray:
    """``(p, d)`` integer exponents of the monomials ``terms`` (read-only)."""
    out = np.zeros((len(terms), dim), dtype=int)
    for row, term in enumerate(terms):
        for var in term:
            out[row, var] += 1
    out.setflags(write=False)
    return out


def _features(z: np.ndarray, terms: list[tuple[int, ...]]) -> np.ndarray:
    """Regression matrix ``(N, p)`` of the monomials evaluated at the rows of ``z`` ``(N, d)``."""
    powers = _exponents(tuple(terms), z.shape[1])
    return np.prod(z[:, None, :] ** powers[None, :, :], axis=2)


def _feature_gradient(z: np.ndarray, terms: list[tuple[int, ...]]) -> np.ndarray:
    """Derivative ``(p, d)`` of the monomials with respect to ``z`` at the single point ``z``: column j is
    e_j z_j^(e_j - 1) times the other factors, for each monomial with exponents e."""
    powers = _exponents(tuple(terms), z.size)
    grad = np.zeros(powers.shape)
    for j in range(z.size):
        has = powers[:, j] > 0
        lowered = powers[has].copy()
        lowered[:, j] -= 1
        grad[has, j] = powers[has, j] * np.prod(z[None, :] ** lowered, axis=1)
    return grad


def _as_2d(array: np.ndarray, name: str) -> np.ndarray:
    """Return ``array`` as float ``(N, d)``, promoting ``(N,)`` to ``(N, 1)``."""
    out = np.asarray(array, dtype=float)
    if out.ndim == 1:
        out = out[:, None]
    if out.ndim != 2:
        raise ValueError(f"{name} must have shape (N,) or (N, d), got {np.shape(array)}")
    return out


def _pairs(x: np.ndarray, x_next: np.ndarray, degree: int) -> tuple[np.ndarray, np.ndarray]:
    """``(x, x_next)`` as float ``(N, d)`` arrays of one shape; raise on mismatched shapes or a bad degree."""
    xs = _as_2d(x, "x")
    ys = _as_2d(x_next, "x_next")
    if xs.shape != ys.shape:
        raise ValueError(f"x and x_next must have the same shape, got {xs.shape} and {ys.shape}")
    if degree not in _SUPPORTED_DEGREES:
        raise ValueError(f"degree must be one of {_SUPPORTED_DEGREES}, got {degree}")
    return xs, ys


def regress_at(point: np.ndarray, samples: np.ndarray, values: np.ndarray, degree: int = 1) -> float:
    """A per-step quantity read at the fixed point: polynomial least squares (total degree ``degree``; 1: affine)
    of ``values`` (n,) on the section samples ``samples`` (n, d), evaluated at ``point`` (d,): e.g. a gait's step
    period and length from the steps of starts around its fixed point. An affine fit of a curved quantity is biased
    by the samples' spread about ``point``; degree 2 removes that bias at first order. NaN unless there are more
    samples than the polynomial has terms."""
    samples = np.asarray(samples, float).reshape(len(values), -1)
    terms = _monomials(samples.shape[1], degree)
    if len(values) <= len(terms):
        return float("nan")
    design = _features(samples - point, terms)
    coef, *_ = np.linalg.lstsq(design, values, rcond=None)
    return float(coef[0])
