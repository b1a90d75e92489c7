"""analysis.force_ratio on synthetic stance forces whose ratio profile and maximum are known."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.force_ratio import critical_ratio, ratio_profile

PHI, WIDTH, SLOPE = 0.3, 2e-3, -2.0  # half step (rad), bin width (rad), f_t/f_n = SLOPE theta


def stance(rows: int = 30_000) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(1, rows) theta uniform over [-phi, phi), a varying normal force and f_t = SLOPE theta f_n."""
    theta = np.linspace(-PHI, PHI, rows, endpoint=False)[None]
    f_n = 1.0 + 0.5 * np.cos(40 * theta)
    return theta, SLOPE * theta * f_n, f_n


def test_profile_is_the_impulse_ratio_per_bin() -> None:
    theta, f_t, f_n = stance()
    centres, ratio = ratio_profile(theta, f_t, f_n, np.ones(theta.shape, bool), PHI, WIDTH)
    assert centres.size == round(2 * PHI / WIDTH)
    np.testing.assert_allclose(centres[[0, -1]], [-PHI + WIDTH / 2, PHI - WIDTH / 2])
    np.testing.assert_allclose(ratio, SLOPE * centres, atol=abs(SLOPE) * WIDTH / 20)


def test_profile_leaves_out_unselected_sparse_and_unloaded_bins() -> None:
    theta, f_t, f_n = stance()
    select = np.ones(theta.shape, bool)
    select[0, :1000] = False  # the rows of the first 10 bins
    f_t[0, :1000] = 1e6  # would spoil them if they counted
    select[0, 4990:5110] = False  # 100 rows per bin
    select[0, [5030, 5060]] = True  # two rows left in bin 50: too few
    f_n[0, 7990:8110] = 1e-3  # bin 80 almost unloaded (a chattering contact's gap)
    f_t[0, 7990:8110] = SLOPE * theta[0, 7990:8110] * 1e-3
    centres, ratio = ratio_profile(theta, f_t, f_n, select, PHI, WIDTH)
    assert np.isnan(ratio[:10]).all() and np.isnan(ratio[50]) and np.isnan(ratio[80])
    ok = np.isfinite(ratio)
    assert ok.sum() == centres.size - 12
    np.testing.assert_allclose(ratio[ok], SLOPE * centres[ok], atol=abs(SLOPE) * WIDTH / 4)


def test_critical_ratio_extrapolates_to_the_stance_ends() -> None:
    centres = np.arange(-PHI + WIDTH / 2, PHI, WIDTH)
    ratio = 0.5 + SLOPE * centres - 3.0 * centres**2
    assert critical_ratio(centres, ratio, PHI) == pytest.approx(abs(0.5 - SLOPE * PHI - 3.0 * PHI**2), rel=1e-9)
    gap = centres > -PHI + 0.01  # -phi is 10 mrad from the first bin: more than a quarter span, no extrapolation
    assert critical_ratio(centres[gap], ratio[gap], PHI) == pytest.approx(float(np.max(np.abs(ratio[gap]))))
    few = np.full(centres.shape, np.nan)
    few[:5] = 1.0
    assert math.isnan(critical_ratio(centres, few, PHI))
