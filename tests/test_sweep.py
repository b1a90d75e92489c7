"""The sweep command: value parsing, bifurcation location, and a small real sweep."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mjpoincare.cli import main
from mjpoincare.params import ParameterError
from mjpoincare.sweep import crossing, parse_values


def test_parse_values() -> None:
    assert parse_values("0.07, 0.072") == ["0.07", "0.072"]
    assert parse_values("0:1:3") == ["0", "0.5", "1"]
    with pytest.raises(ParameterError):
        parse_values("a:b:c")


def test_crossing_interpolates_and_extrapolates() -> None:
    assert crossing([0.0, 1.0, 2.0], [0.0, -0.5, -1.5]) == pytest.approx(1.5)
    assert crossing([0.0, 1.0], [-0.2, -0.6]) == pytest.approx(2.0)
    assert math.isnan(crossing([0.0, 1.0], [-0.5, -0.5]))


@pytest.mark.mujoco
def test_wheel_sweep_over_slope(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep.json"
    assert main(["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08,0.12", "--json", str(out)]) == 0
    rows = json.loads(out.read_text())["rows"]
    assert [r["slope"] for r in rows] == [0.08, 0.12]
    assert all(abs(r["fitted_lowest"] - 0.5) < 0.02 for r in rows)  # beta^2 = 0.5 for 8 spokes at any slope
    assert "lowest Re" in capsys.readouterr().out
    assert main(["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08,0.5"]) == 2  # checked first
