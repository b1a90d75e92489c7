"""Ordering and pairing of return-map multipliers (eigenvalues of the linearised Poincaré map).

One convention for every analytic and fitted spectrum, so that the k-th multiplier of a simulation is compared with
the k-th of the theory: modulus descending (002 Figs 4.2b, 5.2a plot the largest modulus), a complex-conjugate
pair with the positive angle first. Only numpy and scipy are used.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = ["match_eigenvalues", "sort_eigenvalues"]

#: moduli within this relative difference count as equal, and are ordered by angle
TIE_RTOL = 1e-9


def sort_eigenvalues(values: np.ndarray) -> np.ndarray:
    """``values`` (d,) by modulus descending; equal moduli (relative ``TIE_RTOL``) by angle descending."""
    modulus = np.abs(values)
    order = np.argsort(-modulus, kind="stable")
    group_modulus = modulus[order].copy()
    for k in range(1, group_modulus.size):
        if np.isclose(group_modulus[k], group_modulus[k - 1], rtol=TIE_RTOL, atol=0.0):
            group_modulus[k] = group_modulus[k - 1]
    resorted = np.lexsort((-np.angle(values[order]), -group_modulus))
    return values[order][resorted]


def match_eigenvalues(reference: np.ndarray, values: np.ndarray) -> np.ndarray:
    """``values`` (d,) reordered to pair with ``reference`` (m,), m <= d: the m entries of ``values`` that minimise
    the total |difference| to ``reference`` (optimal assignment), in the order of ``reference``; shape (m,)."""
    cost = np.abs(reference[:, None] - values[None, :])
    _, cols = linear_sum_assignment(cost)
    return values[cols]


def eigenvalue_error(reference: np.ndarray, values: np.ndarray) -> float:
    """max |lambda - lambda_ref| over ``values`` matched to ``reference`` (:func:`match_eigenvalues`): the max-abs
    error of an eigenvalue check."""
    reference = np.asarray(reference)
    return float(np.max(np.abs(match_eigenvalues(reference, np.asarray(values)) - reference)))
