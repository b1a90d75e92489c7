"""Regression: the peg-switched MuJoCo skate against Coleman & Holmes' exact return map."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mjpoincare.cli import main
from mjpoincare.commands.validation import run_validation
from mjpoincare.gate import forms as gate

pytestmark = pytest.mark.mujoco


def test_fast_validation_passes() -> None:
    result = gate.run_case(gate.case("slotted-skate[fast]"))
    assert result.extras["impacts"] > 60
    collisions = next(c for c in result.checks if c.name == "collisions_before_reversal")
    # P1 backward starts (B.6; docs/theory/slotted-skate.md Sec. 3.4: 11 at Omega0 = 0.1)
    assert collisions.analytic == [15, 11, 8]


@pytest.mark.parametrize("l0", [1.0, -1.0])
def test_accurate_preset_meets_targets(l0: float) -> None:
    """Acceptance (P1, P2 = Figs 4-6): sigma4 within 1e-6 and the energy per impact within 1e-5, both directions
    (the run's full verdict is the gate's: tests/test_gate.py)."""
    label = "slotted-skate[accurate]" if l0 > 0 else f"slotted-skate[accurate,l0={l0},delta={1 / 3}]"
    result = gate.run_case(gate.case(label))
    by_name = {c.name: c for c in result.checks}
    for name in ("sigma4_forward", "sigma4_backward"):
        assert by_name[name].error <= 1e-6, result.table()
    assert by_name["energy_loss"].error <= 1e-5, result.table()


def test_reversals_follow_the_map() -> None:
    """P4 (Fig 8, L0 = -sqrt 2, Delta = sqrt 2 / 2): forward starts reverse within a stance (B.5); every stance's
    reversal matches the map."""
    result = gate.run_case(gate.case("slotted-skate[fast,l0=-1.4142135623730951,delta=0.7071067811865476]"))
    by_name = {c.name: c for c in result.checks}
    assert result.extras["reversals_seen"] > 0
    assert by_name["reversals"].error == 0


def test_error_is_first_order_in_the_step() -> None:
    """Semi-implicit Euler with a dead-beat peg (the fast preset before the search) halves sigma4's error with the
    step."""
    errors = []
    for dt in ("1e-3", "5e-4"):
        result = run_validation("slotted-skate", {"integrator": "euler", "solref_dampratio": "1", "tolerance": "1e-14",
                                                  "timestep": dt, "solref_timeconst": str(2 * float(dt))}, "fast")
        errors.append(next(c.error for c in result.checks if c.name == "sigma4_backward"))
    assert 1.6 < errors[0] / errors[1] < 2.5, errors


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [("delta=0", "delta must be in (0, 1000]"), ("rho=-1", "rho must be in (0, 1000]"),
     ("V0=0", "V0 must be non-zero"), ("peg=2", "unknown parameter 'peg'")],
)
def test_bad_input(assignment: str, needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "slotted-skate", "--set", assignment]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_stability_region_map_matches_the_analytic_regions(tmp_path: Path) -> None:
    """A 5x4 (l0/delta, 1/delta^2) grid in one batched rollout: simulated classes equal (3.11-3.12) off the
    boundaries, and the PNG and JSON are written."""
    png, out = tmp_path / "regions.png", tmp_path / "regions.json"
    code = main(["sweep", "slotted-skate", "--grid", "x=-1.5:0.5:5,y=0.1:1:4", "--preset", "accurate",
                 "--set", "timestep=1e-2", "--set", "solref_timeconst=2e-2", "-o", str(png), "--json", str(out)])
    payload = json.loads(out.read_text())
    assert code == 0 and payload["mismatches"] == 0
    assert png.stat().st_size > 10_000
    measured, analytic = np.array(payload["sigma4_measured"]), np.array(payload["sigma4_analytic"])
    assert np.nanmax(np.abs(measured - analytic)) < 1e-4


def test_grid_input_is_checked(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sweep", "slotted-skate", "--grid", "x=0:1:3"]) == 2
    assert "--grid expects x=START:STOP:N,y=START:STOP:N" in capsys.readouterr().err


def test_final_state_and_smooth_limit() -> None:
    """P4 reverses once and ends at V_f = -0.88307 (B.12); a small slot approaches the sleigh's rate -1/2."""
    result = gate.run_case(gate.case("slotted-skate[fast,l0=-1.4142135623730951,delta=0.7071067811865476]"))
    by_name = {c.name: c for c in result.checks}
    assert by_name["final_speed"].analytic == pytest.approx(-0.8830719, abs=1e-6)
    assert by_name["final_speed"].passed and by_name["final_reversals"].simulated == 1
    small = run_validation("slotted-skate", {"delta": "0.02"}, "fast").extras["smooth_limit"]
    assert small["discrete_rate_simulated"] == pytest.approx(small["discrete_rate_exact"], abs=1e-4)
    assert abs(small["discrete_rate_exact"] - small["sleigh_rate"]) < 0.01
