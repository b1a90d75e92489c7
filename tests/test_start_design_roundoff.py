"""The compass bipeds' start designs carry no roundoff of the analytic multipliers: the perturbation size, chosen from
the largest multiplier (a finite-difference Jacobian, which BLAS kernels reproduce to about 2e-10 only), is rounded
(:func:`mjpoincare.analysis.start_designs.design_size`), so the starts are the same bits under every kernel."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from mjpoincare.analysis.start_designs import DESIGN_DIGITS, design_size

from mjpoincare import scenarios
from mjpoincare.scenarios import compass_biped_friction as friction
from mjpoincare.scenarios.compass_biped import runs
from mjpoincare.scenarios.compass_biped_friction.start_design import initial_section_states

#: The relative roundoff the multipliers carry between kernels (measured: 2e-10 SkylakeX against Haswell, 9.5e-10
#: Prescott), with a factor of 10 on it.
MULTIPLIER_ROUNDOFF = 1e-8


def test_design_size_keeps_three_significant_digits() -> None:
    assert DESIGN_DIGITS == 3
    assert design_size(0.018308628868830064) == 0.0183
    assert design_size(0.0183086 * (1 + 1e-10)) == design_size(0.0183086 * (1 - 1e-10))
    assert design_size(123456.0) == 123000.0
    assert design_size(0.0) == 0.0
    assert math.isinf(design_size(math.inf))


@pytest.mark.parametrize("gait", ["a", "b", "c", "i", "ii", "iii"])
def test_friction_biped_starts_are_the_same_bits_under_multiplier_roundoff(gait: str) -> None:
    """Each gait's starts with its multipliers moved by ``MULTIPLIER_ROUNDOFF`` either way are the same bits."""
    g = friction.gait({"gait": gait, "mu": 0.0, "kp": 15.0, "kd": 15.0})
    timestep = float(friction.PRESETS["fast"]["timestep"])
    starts = initial_section_states(g, timestep)
    for factor in (1.0 + MULTIPLIER_ROUNDOFF, 1.0 - MULTIPLIER_ROUNDOFF):
        moved = dataclasses.replace(g, eigenvalues=g.eigenvalues * factor)
        np.testing.assert_array_equal(initial_section_states(moved, timestep), starts)


@pytest.mark.parametrize("preset", ["fast", "accurate"])
def test_compass_biped_starts_are_the_same_bits_under_multiplier_roundoff(preset: str,
                                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """compass-biped's starts with the multipliers its design reads moved by ``MULTIPLIER_ROUNDOFF`` are the same
    bits."""
    bp = runs.theory.CompassBiped()
    timestep = float(scenarios.get("compass-biped").presets[preset]["timestep"])
    starts = runs.initial_section_states(bp, timestep)
    exact = runs.theory.eigenvalues
    for factor in (1.0 + MULTIPLIER_ROUNDOFF, 1.0 - MULTIPLIER_ROUNDOFF):
        monkeypatch.setattr(runs.theory, "eigenvalues", lambda *a, f=factor, **k: exact(*a, **k) * f)
        np.testing.assert_array_equal(runs.initial_section_states(bp, timestep), starts)
