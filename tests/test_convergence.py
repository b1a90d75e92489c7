"""Observed order, Richardson extrapolation, GCI and verdicts on manufactured ladders (no MuJoCo)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.convergence import FS_NOISY, Verdict, analyze, solve_order, three_grid

H = 0.1 * 2.0 ** -np.arange(5)  # a ratio-2 ladder, coarsest first as a command builds it


def test_celik_2008_table_1_first_column() -> None:
    # Celik et al. 2008 Table 1, phi = reattachment length: 2-D grids of 18000, 8000, 4500 cells (h = N^-1/2),
    # phi = 6.063, 5.972, 5.863 -> p = 1.53, phi_ext = 6.1685, GCI_fine = 2.2 % (relative to phi1).
    h = [n**-0.5 for n in (18000, 8000, 4500)]
    tg = three_grid(h, [6.063, 5.972, 5.863])
    assert tg.ratio_fine == pytest.approx(1.5) and tg.ratio_coarse == pytest.approx(4 / 3)
    assert tg.observed_order == pytest.approx(1.53, abs=0.005)
    assert tg.extrapolated == pytest.approx(6.1685, abs=5e-5)
    assert tg.gci / 6.063 == pytest.approx(0.022, abs=5e-4)
    assert tg.safety_factor == 1.25


def test_constant_ratio_order_is_the_log_ratio() -> None:
    assert solve_order(1.0, 2.0, 4.0, 0.25 / 0.125) == pytest.approx(1.0)
    assert solve_order(1.0, 2.0, 4.0, 4.0) == pytest.approx(2.0)
    assert solve_order(1.0, 2.0, 4.0, 0.5) == pytest.approx(-1.0)


@pytest.mark.parametrize("p", [0.7, 1.0, 2.0, 3.5])
def test_exact_power_law_converges_to_its_limit(p: float) -> None:
    r = analyze(H, 2.0 + 5.0 * H**p, 2.0)
    assert r.three_grid.observed_order == pytest.approx(p, rel=1e-6)
    assert r.fit.order == pytest.approx(p, rel=1e-4)
    assert r.error_slope == pytest.approx(p, rel=1e-6)
    assert abs(r.bias) < 1e-10 and r.verdict is Verdict.ANALYTIC
    assert r.h == tuple(sorted(H))  # finest first whatever the input order


def test_non_constant_ratio() -> None:
    h = np.array([1.0, 1.7, 2.3, 4.1]) * 1e-3
    r = analyze(h, 1.0 - 3.0 * h**1.3, 1.0)
    assert r.three_grid.observed_order == pytest.approx(1.3, rel=1e-8)
    assert r.three_grid.extrapolated == pytest.approx(1.0, abs=1e-12)


def test_bias_is_another_value_with_its_band() -> None:
    rng = np.random.default_rng(1)
    values = 1.01 + 0.4 * H + 1e-7 * rng.standard_normal(H.size)
    r = analyze(H, values, 1.0)
    assert r.verdict is Verdict.OTHER
    assert r.bias == pytest.approx(0.01, abs=1e-5)
    assert r.band == pytest.approx(1.25 * 0.4 * H[-1], rel=1e-3)  # Fs |eps21| / (2 - 1), eps21 = 0.4 h1
    assert r.fit.order == pytest.approx(1.0, abs=3 * r.fit.order_stderr + 0.05)
    assert r.fit.extrapolated == pytest.approx(1.01, abs=1e-5)


def test_noise_dominated_ladder_does_not_converge() -> None:
    rng = np.random.default_rng(3)
    h = 1e-3 * 2.0 ** -np.arange(6)
    sd = 1e-4 * np.sqrt(h / h[0])  # noise shrinking like sqrt(h) on top of a small first-order error
    values = 1.0 + 0.01 * h + sd * np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0]) * (1 + 0.1 * rng.random(6))
    r = analyze(h, values, 1.0)
    assert r.three_grid.pattern == "oscillatory" and r.verdict is Verdict.NONE
    assert 1e-5 < r.noise_floor < 1e-4
    assert r.noise_exponent == pytest.approx(0.5, abs=0.25)  # six residuals about a fitted line: a rough scaling
    assert math.isnan(r.three_grid.gci)


def test_order_outside_the_sane_range_uses_the_conservative_band() -> None:
    r = analyze(H, 1.0 + 1e3 * H**6, 1.0)
    tg = r.three_grid
    assert tg.observed_order == pytest.approx(6.0, rel=1e-6) and tg.order == 1.0 and tg.safety_factor == FS_NOISY
    assert tg.gci == pytest.approx(FS_NOISY * abs(r.values[1] - r.values[0]) / (2.0**1 - 1))
    assert "outside" in tg.note and r.verdict is Verdict.ANALYTIC


def test_divergent_and_constant_ladders() -> None:
    assert analyze(H, 1.0 + 1e-3 / H, 1.0).three_grid.pattern == "divergent"
    assert analyze(H, 1.0 + 1e-3 / H, 1.0).verdict is Verdict.NONE
    flat = analyze(H, np.full(H.size, 0.5), 0.5)
    assert flat.three_grid.pattern == "constant" and flat.verdict is Verdict.ANALYTIC
    assert analyze(H, np.full(H.size, 0.5), 0.6).verdict is Verdict.OTHER


def test_bad_ladders_are_refused() -> None:
    with pytest.raises(ValueError, match=">= 3"):
        analyze([1e-3, 2e-3], [1.0, 1.1], 1.0)
    with pytest.raises(ValueError, match="distinct"):
        analyze([1e-3, 1e-3, 2e-3], [1.0, 1.0, 1.1], 1.0)
    with pytest.raises(ValueError, match="finite"):
        analyze([1e-3, 2e-3, 4e-3], [1.0, math.nan, 1.1], 1.0)
