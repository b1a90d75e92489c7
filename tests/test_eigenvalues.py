"""Tests of analysis.eigenvalues: one ordering and one pairing of multipliers for theory and fits alike."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.eigenvalues import TIE_RTOL, match_eigenvalues, sort_eigenvalues


def test_sort_by_modulus_descending() -> None:
    values = np.array([0.1, -0.9, 0.5 + 0.0j, 0.3j])
    np.testing.assert_array_equal(sort_eigenvalues(values), [-0.9, 0.5, 0.3j, 0.1])


def test_sort_conjugate_pair_positive_angle_first() -> None:
    pair = 0.6 * np.exp(np.array([-0.7j, 0.7j]))
    out = sort_eigenvalues(np.array([0.2, pair[0], pair[1]]))
    assert out[0].imag > 0 and out[1].imag < 0 and out[2] == 0.2


def test_sort_near_equal_moduli_by_angle() -> None:
    """Moduli within TIE_RTOL are one group, ordered by angle; beyond it, by modulus."""
    small = 0.5 * (1 + 0.1 * TIE_RTOL)
    np.testing.assert_array_equal(sort_eigenvalues(np.array([small + 0j, -0.5 + 0j])), [-0.5, small])
    large = 0.5 * (1 + 10 * TIE_RTOL)
    np.testing.assert_array_equal(sort_eigenvalues(np.array([-0.5 + 0j, large + 0j])), [large, -0.5])


def test_match_pairs_each_reference_with_its_nearest() -> None:
    reference = np.array([0.8 + 0.1j, 0.8 - 0.1j, -0.3])
    values = np.array([-0.29, 0.81 - 0.09j, 0.79 + 0.11j])
    np.testing.assert_array_equal(match_eigenvalues(reference, values), values[[2, 1, 0]])


def test_match_optimal_assignment_not_greedy() -> None:
    """Nearest-first pairs 0.5 with 0.45 (then 0.0 with 1.0: total 1.05); the least total (0.95) pairs crosswise."""
    reference = np.array([0.5, 0.0])
    values = np.array([0.45, 1.0])
    np.testing.assert_array_equal(match_eigenvalues(reference, values), [1.0, 0.45])


def test_match_fewer_references_keeps_their_length_and_order() -> None:
    reference = np.array([0.9, 0.1])
    values = np.array([0.12, 0.5, 0.88, -0.4])
    np.testing.assert_array_equal(match_eigenvalues(reference, values), [0.88, 0.12])
