"""The regression gate (:data:`mjpoincare.gate.GATE`): every gated check passes, every expected miss misses (strict
xfail carrying its measured number), and every scenario's defaults are in the gate at every preset it offers.

Which checks are gated, and the margin each holds by, comes from ``mjpoincare margins`` (error + spread under seed,
thread count and starts x(1 + 1e-12), and against the oldest numpy/scipy allowed, within half the tolerance).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mjpoincare import scenarios
from mjpoincare.cli import main
from mjpoincare.gate import GATE, MARGIN, GateCase, margin_rows

pytestmark = pytest.mark.mujoco


def _params() -> list[object]:
    out: list[object] = []
    for case in GATE:
        out += [pytest.param(case, name, id=f"{case.label}::{name}") for name in case.gated]
        out += [pytest.param(case, name, id=f"{case.label}::{name}", marks=pytest.mark.xfail(strict=True, reason=why))
                for name, why in case.misses]
    return out


@pytest.mark.parametrize(("case", "name"), _params())
def test_gated_check(case: GateCase, name: str) -> None:
    result = case.run()
    check = next(c for c in result.checks if c.name == name)
    assert check.passed, result.table()


@pytest.mark.parametrize("name", list(scenarios.REGISTRY))
def test_every_preset_of_every_scenario_is_gated_on_its_defaults(name: str) -> None:
    """Each preset's default run is a gate case whose every check is gated, an expected miss, or reported because
    it passes here without the margin (named in the case, with its number in the margins table)."""
    for preset in scenarios.get(name).presets:
        case = next((c for c in GATE if c.scenario == name and c.preset == preset and not c.values), None)
        assert case is not None, f"{name} --preset {preset} is not in the gate"
        covered = set(case.gated) | {m for m, _ in case.misses} | set(case.reported)
        assert {c.name for c in case.run().checks} <= covered, f"{case.label}: ungated checks"


def test_margin_rows_measure_the_spread() -> None:
    """The margins command's rows on the cheapest case: one row per check, the spread measured under every
    perturbation, and the gated checks within the margin."""
    case = next(c for c in GATE if c.label == "slotted-skate[fast]")
    rows = margin_rows([case])
    assert [r["check"] for r in rows] == [c.name for c in case.run().checks]
    assert all(r["spread"] >= 0 for r in rows)
    assert all(r["ratio"] <= MARGIN for r in rows if r["status"] == "gated")


def test_margins_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``mjpoincare margins`` on one case: the table, the JSON whole, exit 0 when every gated check holds its margin;
    a --case that matches nothing and a bad --compare file are refused with exit 2 before any simulation."""
    out = tmp_path / "margins.json"
    assert main(["margins", "--case", "slotted-skate[fast]", "--json", str(out)]) == 0
    table = capsys.readouterr().out
    assert "(err+spread)/tol" in table and "sigma4_forward" in table
    payload = json.loads(out.read_text())
    assert payload["margin"] == MARGIN and {r["case"] for r in payload["rows"]} == {"slotted-skate[fast]"}
    assert main(["margins", "--case", "no-such-case"]) == 2
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    assert main(["margins", "--case", "slotted-skate[fast]", "--compare", str(bad)]) == 2
    assert capsys.readouterr().err.count("\n") == 2
