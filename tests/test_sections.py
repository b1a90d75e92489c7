"""Vectorised section detection on synthetic trajectories with known crossings."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.outcomes import classify_outcomes
from mjpoincare.analysis.sections import level_crossings, wrap_events, wrap_phase


def test_level_crossings_interpolate_time_and_values() -> None:
    t = np.linspace(0.0, 10.0, 2001)[None, :].repeat(2, axis=0)
    phase = np.sin(t)
    phase[1] = np.sin(t[1] - 0.5)
    values = np.stack([np.cos(t), t], axis=2)
    up = level_crossings(t, phase, values, direction=+1)
    # upward zero crossings of sin(t) at 0 (excluded: starts at 0), 2 pi; of sin(t - 0.5) at 0.5, 0.5 + 2 pi
    seqs = up.times(2)
    np.testing.assert_allclose(seqs[0], [2 * np.pi], atol=1e-5)
    np.testing.assert_allclose(seqs[1], [0.5, 0.5 + 2 * np.pi], atol=1e-5)
    np.testing.assert_allclose(up.sequences(2)[0][:, 0], [1.0], atol=1e-4)
    down = level_crossings(t, phase, values, direction=-1)
    np.testing.assert_allclose(down.times(2)[0], [np.pi, 3 * np.pi], atol=1e-5)


def test_wrap_jumps_are_not_crossings_but_impacts() -> None:
    alpha = 0.4
    t = np.linspace(0.0, 3.0, 3001)[None, :]
    angle = 1.0 * t  # rolling forward at 1 rad/s from 0: wraps at alpha, 3 alpha, 5 alpha, 7 alpha
    psi = wrap_phase(angle, alpha)
    assert psi.min() >= -alpha - 1e-12 and psi.max() < alpha
    mid = level_crossings(t, psi, angle[..., None], max_jump=alpha)
    np.testing.assert_allclose(mid.times(1)[0], [2 * alpha, 4 * alpha, 6 * alpha], atol=1e-9)
    impacts = wrap_events(t, psi, alpha)
    np.testing.assert_allclose(impacts.times(1)[0], [alpha, 3 * alpha, 5 * alpha, 7 * alpha], atol=1e-3)
    assert (impacts.values[:, 0] == 1).all()
    back = wrap_events(t, wrap_phase(-angle, alpha), alpha)
    assert (back.values[:, 0] == -1).all()


def test_nan_rows_give_no_samples() -> None:
    t = np.linspace(0.0, 10.0, 1001)[None, :]
    phase = np.sin(t)
    phase[0, 500:] = np.nan
    assert len(level_crossings(t, phase, t[..., None]).time) == 0


def test_outcome_classes() -> None:
    n = 100
    omega = np.stack([np.full(n, 1e-4), np.full(n, 20.0), np.full(n, 1.0), np.linspace(-1, 1, n),
                      np.full(n, 1.0)])
    clearance = np.zeros_like(omega)
    clearance[4, 50] = 0.1
    out = classify_outcomes(omega, clearance, rest_speed=0.05, runaway_speed=5.0, flight_clearance=0.01)
    assert list(out) == ["standing", "runaway", "rolling", "undetermined", "flight"]
