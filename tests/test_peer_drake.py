"""The suite's theory against Drake's hybrid simulation (``pydrake.examples`` RimlessWheel and CompassGait), an
implementation nobody here wrote: fixed points, multipliers, periods and step lengths at the defaults and at other
parameter sets, and the ``--peer drake`` / bench wiring.

Drake's RimlessWheel has a point-mass hub: it has no kappa parameter, so the rimless wheel is compared with the
theory at kappa = 0 (003 Sec. 3), and the scenario's floored kappa = 1e-4 (MIN_GYRATION) shows as a difference
of the size the theory predicts (:func:`test_rimless_wheel_kappa_floor_is_the_whole_difference`).

Without pydrake these tests skip, except in CI (CI=true) on a platform where the ``peers`` extra installs drake: there
a missing pydrake fails, so that a broken install cannot hide behind a skip.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
from conftest import skip_unless_required
from mjpoincare.analysis.checks import Check
from mjpoincare.analysis.eigenvalues import match_eigenvalues
from mjpoincare.analysis.theory import compass_biped as compass_theory
from mjpoincare.analysis.theory import rimless_wheel as rimless_theory

from mjpoincare import scenarios
from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.engines.peers import compare, drake
from mjpoincare.scenarios.compass_biped import biped
from mjpoincare.scenarios.compass_biped import drake as compass_biped_drake
from mjpoincare.scenarios.rimless_wheel import drake as rimless_wheel_drake
from mjpoincare.scenarios.rimless_wheel import wheel
from mjpoincare.scenarios.rimless_wheel.drake import point_mass_wheel

ACCURACY = drake.REFERENCE_ACCURACY  # runge_kutta5 at target accuracy 1e-12
# Post-impact state, period, step length: Drake's error control keeps each step's error near the accuracy, and the
# witness isolates the impact to 0.01 x accuracy x 1 s, so the gait is good to a small multiple of 1e-12. 100 x the
# accuracy; measured at most 2.1e-12 (omega+, n = 32) over the 9 cases below, a margin of 48.
STATE_TOL = 100 * ACCURACY
# Multipliers by central differences with step h = difference_step(1e-12) = 1e-5 on both sides: the map's noise
# (~accuracy) gives accuracy/h = 1e-7; 10 x that. Measured at most 3.5e-9 (rimless wheel) and 8.9e-9 (compass gait,
# against the theory at the same h).
MULTIPLIER_TOL = 10 * ACCURACY / drake.difference_step(ACCURACY)
# omega+/omega- across the impact: cos(2 alpha) in closed form on both sides (Drake's reset, 003 eq 3.11); rounding
# only (measured 0).
IMPACT_TOL = 1e-14

RIMLESS_CASES = rimless_wheel_drake.AGREEMENT_CASES
COMPASS_CASES = compass_biped_drake.AGREEMENT_CASES


@pytest.fixture
def needs_drake() -> None:
    """Skip without pydrake, except in CI on a platform the peers extra installs drake on, where its absence is a
    failure (on the others the extra installs nothing, and the tests skip)."""
    if not drake.available():
        skip_unless_required(f"pydrake not installed: {drake.INSTALL}", "drake")


def _params(scenario: str, assignments: dict[str, str]) -> dict:
    return resolve_inputs(scenario, assignments, None)[2]


@functools.cache
def _rimless(items: tuple[tuple[str, str], ...]) -> drake.RimlessWheelGait:
    return drake.rimless_wheel(point_mass_wheel(_params("rimless-wheel", dict(items))))


@pytest.mark.usefixtures("needs_drake")
@pytest.mark.parametrize("assignments", RIMLESS_CASES, ids=lambda a: ",".join(f"{k}={v}" for k, v in a.items()) or
                         "defaults")
def test_rimless_wheel_matches_theory_at_kappa_zero(assignments: dict[str, str]) -> None:
    gait = _rimless(tuple(assignments.items()))
    w = point_mass_wheel(_params("rimless-wheel", assignments))
    star = rimless_theory.rolling_fixed_point(w)
    assert gait.accuracy == ACCURACY
    assert abs(gait.omega_post_impact - star) / star <= STATE_TOL
    assert abs(gait.multiplier - rimless_theory.rolling_multiplier(w)) <= MULTIPLIER_TOL
    assert abs(gait.impact_coefficient - w.beta) / w.beta <= IMPACT_TOL
    period = rimless_theory.step_period(w, star)
    assert abs(gait.step_period - period) / period <= STATE_TOL


@pytest.mark.usefixtures("needs_drake")
def test_rimless_wheel_kappa_floor_is_the_whole_difference() -> None:
    """Drake's omega+ minus the scenario's analytic one (kappa = 1e-4) is the theory's own kappa shift."""
    p = _params("rimless-wheel", {})
    floored = rimless_theory.rolling_fixed_point(wheel(p))
    predicted = rimless_theory.rolling_fixed_point(point_mass_wheel(p)) - floored
    assert abs(predicted) > 1e4 * STATE_TOL  # a difference the check must name, far above the agreement
    assert abs((_rimless(()).omega_post_impact - floored) - predicted) <= STATE_TOL * floored


@pytest.mark.usefixtures("needs_drake")
@pytest.mark.parametrize("assignments", COMPASS_CASES, ids=lambda a: ",".join(f"{k}={v}" for k, v in a.items()) or
                         "defaults")
def test_compass_gait_matches_theory(assignments: dict[str, str]) -> None:
    p = _params("compass-biped", assignments)
    bp = biped(p)
    cycle = drake.compass_gait(bp)
    x_star = compass_theory.fixed_point(bp)
    assert np.max(np.abs(np.array(cycle.fixed_point) - x_star)) <= STATE_TOL
    lam = compass_theory.eigenvalues(bp, x_star, eps=drake.difference_step(ACCURACY))
    assert np.max(np.abs(match_eigenvalues(lam, np.array(cycle.eigenvalues)) - lam)) <= MULTIPLIER_TOL
    period, length = compass_theory.step_period(bp, x_star), compass_theory.step_length(bp, x_star)
    assert abs(cycle.step_period - period) / period <= STATE_TOL
    assert abs(cycle.step_length - length) / length <= STATE_TOL


@pytest.mark.mujoco
@pytest.mark.usefixtures("needs_drake")
def test_validate_json_carries_drake_values(capsys: pytest.CaptureFixture[str]) -> None:
    main(["validate", "rimless-wheel", "--peer", "drake", "--json", "-"])
    [payload] = json.loads(capsys.readouterr().out)["results"]
    peer = payload["peer"]
    assert peer["name"] == "drake" and peer["version"] == drake.version() and peer["accuracy"] == ACCURACY
    assert set(peer["checks"]) == {"omega_post_impact", "eigenvalue", "impact_coefficient", "step_period"}
    omega = peer["checks"]["omega_post_impact"]
    assert omega["difference_peer_model"] <= STATE_TOL
    analytic = next(c["analytic"] for c in payload["checks"] if c["name"] == "omega_post_impact")
    assert omega["difference"] == pytest.approx(abs(omega["value"] - analytic) / analytic)


@pytest.mark.usefixtures("needs_drake")
def test_compare_block_and_table_for_the_compass_gait() -> None:
    p = _params("compass-biped", {})
    bp = biped(p)
    x_star = compass_theory.fixed_point(bp)
    lam = compass_theory.eigenvalues(bp, x_star)
    checks = [Check(name="fixed_point", analytic=x_star, simulated=x_star, error=0.0, tolerance=1.0,
                    kind="max-abs", unit="", why=""),
              Check(name="eigenvalues", analytic=lam, simulated=lam, error=0.0, tolerance=1.0, kind="max-abs",
                    unit="", why=""),
              Check(name="stable", analytic=0.0, simulated=0.0, error=0.0, tolerance=0.0, kind="count", unit="",
                    why="")]
    block = compare.compare(scenarios.get("compass-biped").peers[0], p, checks)
    assert set(block["checks"]) == {"fixed_point", "eigenvalues"}
    assert block["checks"]["fixed_point"]["difference"] <= STATE_TOL
    # the analytic eigenvalues use the theory's own step 1e-6: its truncation (measured 2.6e-8) adds to the tolerance
    assert block["checks"]["eigenvalues"]["difference"] <= MULTIPLIER_TOL
    table = compare.format_peer(block)
    assert table.startswith(f"peer drake {drake.version()}") and "fixed_point" in table and "eigenvalues" in table


@pytest.mark.usefixtures("needs_drake")
@pytest.mark.parametrize(("scenario", "metric"), [("rimless-wheel", "omega_post_impact_error"),
                                                  ("compass-biped", "fixed_point_error")])
def test_bench_rows_tighten_with_accuracy(scenario: str, metric: str) -> None:
    peers = scenarios.get(scenario).peers
    text, block = compare.bench_block(peers, _params(scenario, {}))
    assert block is not None and "Drake" in text and f"accuracy={peers[0].bench_accuracies[0]:g}" in text
    errors = [row[metric] for row in block["rows"]]
    assert errors[-1] < errors[0]


def test_peer_refuses_other_scenarios(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "slotted-skate", "--peer", "drake"]) == 2
    err = capsys.readouterr().err
    assert "--peer drake is for compass-biped, rimless-wheel only" in err and err.count("\n") == 1, err


@pytest.mark.usefixtures("needs_drake")
@pytest.mark.parametrize(("setting", "needle"), [("gyration=0.1", "gyration must be 0 with --peer drake"),
                                                 ("tau_ankle=0.1", "tau_ankle must be 0 with --peer drake")])
def test_peer_refuses_what_drake_cannot_represent(setting: str, needle: str,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    scenario = "rimless-wheel" if setting.startswith("gyration") else "compass-biped"
    assert main(["validate", scenario, "--peer", "drake", "--set", setting]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err


def test_missing_pydrake_names_the_extra(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(drake, "available", lambda: False)
    assert main(["validate", "compass-biped", "--peer", "drake", "--json", "-"]) == 2
    err = capsys.readouterr().err
    assert "mjpoincare[peers]" in err and err.count("\n") == 1, err
    text, block = compare.bench_block(scenarios.get("rimless-wheel").peers, _params("rimless-wheel", {}))
    assert block is None and "mjpoincare[peers]" in text and text.strip().count("\n") == 0
