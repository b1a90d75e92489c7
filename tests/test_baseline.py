"""The regression baseline (:mod:`mjpoincare.baseline`): what a change beyond a check's resolution is, on records
built by hand; ``validate --baseline`` refuses a missing file before any simulation; the gate's committed baseline
(``docs/results/gate/baseline.json``, ``make baseline``) holds every gate check, and every gate run stays within it."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from mjpoincare.analysis.checks import Check

from mjpoincare import baseline, gate
from mjpoincare.cli import main
from mjpoincare.reports.gate_baseline import BASELINE
from mjpoincare.result import Result
from mjpoincare.scenarios.gate_cases import GateCase

ROOT = Path(__file__).parents[1]


def _result(errors: dict[str, float], **settings: object) -> Result:
    checks = [Check(name=n, analytic=1.0, simulated=1.0 + e, error=e, tolerance=0.1, kind="relative", unit="",
                    why="") for n, e in errors.items()]
    return Result(scenario="rimless-wheel", preset="fast", seed=0, params={"spokes": 8, "slope": 0.08},
                  settings={"timestep": 1e-3, **settings}, mujoco_version="x", checks=checks, timing={}, warnings=[],
                  diverged=[])


def _baseline(result: Result, resolutions: dict[str, float]) -> dict[str, object]:
    return baseline.updated(None, [(baseline.run_key(result), baseline.entry(result, resolutions))], {})


def test_a_change_beyond_its_multiple_of_the_resolution_fails_naming_old_new_and_resolution() -> None:
    recorded = _baseline(_result({"a": 0.01, "b": 0.02}), {"a": 1e-4, "b": 1e-4})
    assert baseline.deviations(_result({"a": 0.01 + 2.9e-4, "b": 0.02 - 2.9e-4}), recorded) == []
    moved = baseline.deviations(_result({"a": 0.01 + 3.1e-4, "b": 0.02}, timestep=1.01e-3), recorded)
    assert [d.check for d in moved] == ["a"]
    assert moved[0].message() == (
        "rimless-wheel[fast]::a: error 0.01 -> 0.01031: changed 0.00031, 3.1 x its resolution 0.0001 (at most 3 x); "
        "settings differ from the recorded run: timestep 0.001 -> 0.00101")


def test_the_resolution_never_falls_below_roundoff_and_nan_matches_only_nan() -> None:
    recorded = _baseline(_result({"a": 0.5, "b": math.nan}), {"a": 0.0})
    assert baseline.deviations(_result({"a": 0.5 + 2e-12, "b": math.nan}), recorded) == []
    assert [d.check for d in baseline.deviations(_result({"a": 0.5 + 4e-12, "b": 0.0}), recorded)] == ["a", "b"]


def test_a_missing_or_new_check_and_an_unrecorded_run_are_changes() -> None:
    recorded = _baseline(_result({"a": 0.01, "b": 0.02}), {})
    notes = [d.message() for d in baseline.deviations(_result({"a": 0.01, "c": 0.0}), recorded)]
    assert notes == ["rimless-wheel[fast]::b: the check is missing from this run",
                     "rimless-wheel[fast]::c: the check is new: the baseline lacks it"]
    other = _result({"a": 0.01})
    other.params["spokes"] = 10
    assert baseline.run_key(other) == "rimless-wheel[fast,spokes=10]"
    assert "has no run rimless-wheel[fast,spokes=10]" in baseline.deviations(other, recorded)[0].message()


@pytest.mark.parametrize(("args", "message"), [
    (["--baseline", "absent.json"], "--baseline absent.json does not exist"),
    (["--update-baseline"], "--update-baseline needs --baseline PATH"),
    (["--baseline", "not-a-baseline.json"], "is not an mjpoincare baseline"),
])
def test_validate_refuses_a_baseline_it_cannot_use_before_any_simulation(
        args: list[str], message: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "not-a-baseline.json").write_text("{}")
    monkeypatch.setattr("mjpoincare.api.run_validation", lambda *a, **k: pytest.fail("simulated"))
    assert main(["validate", "rimless-wheel", *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["not-a-baseline.json"]


def test_the_committed_baseline_holds_every_gate_check_with_a_resolution() -> None:
    """One record per gate case (keyed by its non-default parameters), every check of the committed ensemble
    measurement in it, each resolution at least roundoff and below the check's tolerance except where the gate
    declares the check unresolved (its spread exceeds half its tolerance: no baseline resolves it either)."""
    payload = baseline.load(str(ROOT / BASELINE))
    assert payload["stamp"]["git_sha"] and payload["multiple"] == baseline.MULTIPLE
    rows = json.loads((ROOT / "docs/results/gate/margins.json").read_text())["rows"]
    keys = {c.label: baseline.key_of(c.scenario, c.preset, dict(c.values)) for c in gate.cases()}
    assert set(payload["runs"]) == set(keys.values()) and len(keys) == len(set(keys.values()))
    for row in rows:
        entry = payload["runs"][keys[row["case"]]]["checks"][row["check"]]
        assert entry["resolution"] >= baseline.floor(entry["error"]), (row["case"], row["check"])
        if row["tolerance"] > 0 and row["status"] != "declared miss, unresolved":
            assert entry["resolution"] < row["tolerance"], (row["case"], row["check"])


@pytest.mark.mujoco
@pytest.mark.parametrize("case", [pytest.param(c, id=c.label) for c in gate.cases()])
def test_every_gate_run_stays_within_the_committed_baseline(case: GateCase) -> None:
    """No check of the gate's run moved from the committed baseline by more than its multiple of the resolution."""
    moved = baseline.deviations(gate.run_case(case), baseline.load(str(ROOT / BASELINE)))
    assert not moved, "\n".join([*(d.message() for d in moved),
                                 "a real change: re-measure with make margins, then make baseline, and read its diff"])
