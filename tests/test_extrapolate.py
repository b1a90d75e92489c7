"""``validate --extrapolate``: Richardson values from the timestep grids h, 2h, 4h, reported only where the order is
clean (:mod:`mjpoincare.commands.extrapolate`)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mjpoincare.cli import main
from mjpoincare.commands.extrapolate import _component

pytestmark = pytest.mark.mujoco


def test_a_clean_first_order_ladder_is_extrapolated_to_its_limit() -> None:
    """f = 1 + 0.01 h on h = 1, 2, 4: order 1, the Richardson value the limit 1, the error gone."""
    rows = [{"failed": None, "diverged": 0}] * 2
    out = _component("x", 1.0, [1.01, 1.02, 1.04], [1.0, 2.0, 4.0], rows)
    assert out.note == "" and out.order == pytest.approx(1.0)
    assert out.extrapolated == pytest.approx(1.0, abs=1e-12) and out.error_plain == pytest.approx(0.01)


def test_an_oscillating_ladder_gets_no_extrapolated_value() -> None:
    rows = [{"failed": None, "diverged": 0}] * 2
    out = _component("x", 1.0, [1.01, 0.98, 1.04], [1.0, 2.0, 4.0], rows)
    assert math.isnan(out.extrapolated) and "oscillatory" in out.note


def test_skate_extrapolates_first_order_checks(tmp_path: Path) -> None:
    """Semi-implicit Euler at 5e-4 s with a dead-beat peg (the skate's fast preset before the search) is a clean first
    order in the step: sigma4's Richardson value from h, 2h, 4h lies within its GCI band of the analytic value.
    Measured: order 0.99-1.01, extrapolated errors 4e-8 to 9e-7 against plain ones of 1e-5 to 4e-4."""
    target = tmp_path / "skate.json"
    euler = ["--set=integrator=euler", "--set=timestep=5e-4", "--set=solref_timeconst=1e-3", "--set=solref_dampratio=1",
             "--set=tolerance=1e-14"]
    code = main(["validate", "slotted-skate", *euler, "--extrapolate", "--json", str(target)])
    [payload] = json.loads(target.read_text())["results"]
    assert code == (0 if payload["passed"] else 1)  # the checks' verdicts are the gate's to assert
    entry = payload["extrapolated"]
    sigma4 = [c for c in entry["components"] if c["component"].startswith("sigma4")]
    assert len(sigma4) == 4
    for c in sigma4:
        assert c["note"] == "", c
        assert c["order"] == pytest.approx(1.0, abs=0.1), c
        assert c["error_extrapolated"] <= c["band"] and c["error_extrapolated"] < 0.1 * c["error_plain"], c


def test_a_coarser_grid_out_of_bounds_is_refused_before_any_simulation(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "slotted-skate", "--extrapolate", "--set", "timestep=0.02"]) == 2
    assert "timestep" in capsys.readouterr().err
