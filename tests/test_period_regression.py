"""analysis.period_regression: the crossing-to-crossing time at a fixed point from a quadratic regression on the
speeds the return spans (the rimless wheel's step period, Kiša 2020 Sec. 3), on synthetic samples."""

from __future__ import annotations

import numpy as np
import pytest
from mjpoincare.analysis.period_regression import period_at


def test_exact_quadratic_gives_the_period_at_the_fixed_point() -> None:
    rng = np.random.default_rng(0)
    star = 1.3
    before = [star + 0.1 * rng.standard_normal(5) for _ in range(3)]
    after = [star + 0.8 * (b - star) for b in before]
    after = [a + 0.01 * rng.standard_normal(a.size) for a in after]  # off the map: both regressors informative

    def dt(u: np.ndarray, v: np.ndarray) -> np.ndarray:
        x, y = u - star, v - star
        return 0.7 - 0.2 * x + 0.1 * y + 0.05 * x * x - 0.03 * x * y + 0.02 * y * y

    assert period_at(star, before, after, [dt(u, v) for u, v in zip(before, after, strict=True)]) == pytest.approx(
        0.7, abs=1e-12)


def test_noise_averages_out() -> None:
    rng = np.random.default_rng(1)
    star = 2.0
    before = [star + 0.05 * rng.standard_normal(40) for _ in range(4)]
    after = [star + 0.05 * rng.standard_normal(40) for _ in range(4)]
    dts = [0.5 + 0.3 * (u - star) + 1e-4 * rng.standard_normal(u.size) for u in before]
    assert period_at(star, before, after, dts) == pytest.approx(0.5, abs=1e-4)
