"""analysis.stick_slip_reference: runs of the friction wheel's reference (002 Sec. 3.3) from given starts."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis import stick_slip_reference as reference
from mjpoincare.analysis.stick_slip_phases import Rows
from mjpoincare.analysis.theory import rimless_wheel_friction as theory

WHEEL = theory.FrictionWheel(10, 1.0 / 3.0, math.radians(13.0), 0.3)  # 002's set at its stick-slip mu: Type B
SLOW = (0.05, 0.0)  # rolls back within the first step


def b_gait() -> theory.Gait:
    gait = theory.attractors(WHEEL)[0]
    assert gait.kind == "B"
    return gait


def test_step_records_stop_at_a_failure() -> None:
    records = reference.step_records(WHEEL, SLOW, 5)
    assert len(records) == 1 and records[0].failure == "backward"
    start = (float(b_gait().fixed_point[0]), 0.0)
    records = reference.step_records(WHEEL, start, 4)
    assert len(records) == 4 and all(r.failure is None for r in records)
    assert records[1].theta_dot0 == records[0].theta_dot  # each step starts where the last one ended


def test_labelled_steps() -> None:
    label, mids, kinds = reference.labelled_steps(WHEEL, SLOW, 5)
    assert label == "backward" and mids.size == 0 and kinds.size == 0
    gait = b_gait()
    label, mids, kinds = reference.labelled_steps(WHEEL, (gait.fixed_point[0], 0.0), 3)
    assert label == "B" and list(kinds) == ["B"] * 3
    assert mids == pytest.approx([gait.midstance_rate] * 3, rel=1e-6)
    assert reference.labelled_steps(WHEEL, SLOW, 0)[0] == ""


def test_reference_run_continues_past_the_settled_steps() -> None:
    gait = b_gait()
    start = (float(gait.fixed_point[0]) * 1.1, 0.0)
    settled = theory.settle(WHEEL, start)
    steps = settled.steps + 3
    run = reference.reference_run(WHEEL, start, steps)
    assert run.outcome == "B" and run.settle_steps == settled.steps
    assert run.mid_rate.size == run.kinds.size == steps
    assert run.mid_rate[-1] == pytest.approx(gait.midstance_rate, rel=1e-6) and run.kinds[-1] == "B"
    assert reference.reference_run(WHEEL, start, 2).mid_rate.size == 2
    failed = reference.reference_run(WHEEL, SLOW, 10)
    assert failed.outcome == "backward" and failed.kinds.tolist() == [""]


def test_gait_values() -> None:
    values = reference.gait_values(WHEEL, b_gait())
    assert values["gait"] == "B" and values["phases"] == ["stick", "slip+"]
    assert values["mu_c"] == pytest.approx(0.914121, abs=1e-6)  # 002 eq 23 for the paper's set
    assert values["sticking_impulse_ratio"] == pytest.approx(theory.impulse_ratio(10, 1.0 / 3.0))


def test_generic_bench_agrees_with_the_fast_method() -> None:
    gait = b_gait()
    starts = np.array([[gait.fixed_point[0] * (1 + d), 0.0] for d in (-0.1, 0.0, 0.1)])
    bench = reference.generic_bench(WHEEL, gait, starts, 6, 1e-11)
    assert bench["rtol"] == theory.RTOL and bench["wall_s"] > 0
    assert bench["midstance_rate_error"] < 1e-5 and bench["eigenvalue_error"] < 1e-4  # measured 8e-7 and 1.1e-5


def test_force_ratio_comparison_of_the_exact_profile() -> None:
    """Rows whose force ratio is the no-slip wheel's (002 eq 19-22) give its critical friction (eq 23)."""
    rigid = theory.FrictionWheel(WHEEL.spokes, WHEEL.kappa, WHEEL.slope, math.inf)
    theta = np.linspace(-WHEEL.phi, WHEEL.phi, 40001)[None]
    ones = np.ones(theta.shape)
    rows = Rows(time=ones, theta=theta, rate=ones, slip=ones, clearance=ones, ratio=ones,
                force_t=np.asarray(theory.force_ratio(rigid, theta), float), force_n=ones, stance=ones.astype(int),
                since=ones, wrap=ones.astype(bool), mode=ones, vmode=ones)
    mu_c, measured, profile = reference.force_ratio_comparison(WHEEL, rows, np.ones(theta.shape, bool))
    assert mu_c == pytest.approx(theory.critical_friction(rigid)[0])
    assert measured == pytest.approx(mu_c, rel=2e-3)  # the 2 mrad bins' mean near theta = phi
    assert profile["max_abs_error"] < 5e-3  # bin means against the centres' values
