"""The adaptive stopping rule of a fitting batch (mjpoincare.analysis.adaptive_stopping): when it looks, when it
stops and why, from the fit's own spread only."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.adaptive_stopping import FitSettling, StoppingRule, fit_spread
from mjpoincare.analysis.returnmap import fit_return_map, sample_pairs


def _sequences(k: int, batch: int = 3) -> list[np.ndarray]:
    return [np.zeros((k, 2)) for _ in range(batch)]


def _settling(spreads: dict[int, float], **rule: float) -> FitSettling:
    """A stop test whose fit spread at k samples per trajectory is ``spreads[k]``."""
    return FitSettling(StoppingRule(min_samples=3, **rule), lambda seqs: spreads[len(seqs[0])])


def test_no_look_before_min_samples_nor_twice_at_the_same_count() -> None:
    settle = _settling({3: 2.0, 4: 1.0})
    assert not settle(_sequences(2))
    assert not settle(_sequences(3))
    assert not settle(_sequences(3))
    assert settle.history == [(3, 2.0)]
    assert not settle([np.zeros((4, 2)), np.zeros((3, 2))])  # the shortest trajectory decides
    assert settle.reason == "full design"


def test_stops_once_the_interval_is_well_inside_every_tolerance() -> None:
    settle = _settling({3: 2.0, 4: 0.2})
    assert not settle(_sequences(3))
    assert settle(_sequences(4))
    assert settle.reason == "settled"


def test_stops_once_a_round_of_samples_no_longer_narrows_the_interval() -> None:
    settle = _settling({3: 2.0, 4: 1.0, 5: 0.95})
    assert not settle(_sequences(3))
    assert not settle(_sequences(4))  # halved: go on
    assert settle(_sequences(5))  # 5 % narrower: no gain
    assert settle.reason == "no gain"
    assert settle.to_dict()["looks"] == [{"samples": 3, "spread": 2.0}, {"samples": 4, "spread": 1.0},
                                         {"samples": 5, "spread": 0.95}]


def test_a_fit_that_fails_counts_as_no_information_and_never_stops_the_batch() -> None:
    def failing(_: list[np.ndarray]) -> float:
        raise ValueError("too few pairs")

    settle = FitSettling(StoppingRule(min_samples=1), failing)
    assert not settle(_sequences(1)) and not settle(_sequences(2))
    assert settle.to_dict()["looks"] == [{"samples": 1, "spread": None}, {"samples": 2, "spread": None}]


def test_the_spread_is_the_largest_95_percent_half_width_in_tolerances() -> None:
    rng = np.random.default_rng(0)
    sequences = []
    for _ in range(20):
        x = rng.normal(size=2)
        seq = [x]
        for _ in range(5):
            x = 0.5 * x + 1e-3 * rng.normal(size=2)
            seq.append(x)
        sequences.append(np.array(seq))
    fit = fit_return_map(*sample_pairs(sequences), degree=1, seed=0)
    u = fit_spread(fit, 1e-3, 1e-2)
    expected = max(2 * np.max(fit.fixed_point_std) / 1e-3, 2 * np.max(np.abs(fit.eigenvalue_std)) / 1e-2)
    assert u == pytest.approx(expected) and math.isfinite(u)


def test_a_relative_fixed_point_tolerance_scales_with_the_fitted_fixed_point() -> None:
    rng = np.random.default_rng(1)
    x = rng.uniform(1.0, 3.0, size=(40, 1))
    fit = fit_return_map(x, 2.0 + 0.5 * (x - 2.0) + 1e-3 * rng.normal(size=x.shape), degree=1, seed=0)
    absolute = fit_spread(fit, 1e-3 * abs(float(fit.fixed_point[0])), 1e-2)
    assert fit_spread(fit, 1e-3, 1e-2, relative=True) == pytest.approx(absolute)
