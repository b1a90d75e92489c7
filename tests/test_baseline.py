"""The regression baseline (:mod:`mjpoincare.gate.baseline`): what a change beyond a check's allowance is, on records
built by hand and planted into a gate run; ``validate --baseline`` refuses a missing file before any simulation; the
gate's committed baseline (``docs/results/gate/baseline.json``, ``make baseline``) holds every gate check, and every
gate run stays within it."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import pytest
from mjpoincare.analysis.checks import Check

from mjpoincare.cli import main
from mjpoincare.core.allowance import FLOOR, MULTIPLE, allowance, floor
from mjpoincare.core.result import Result
from mjpoincare.gate import baseline
from mjpoincare.gate import forms as gate
from mjpoincare.pages.gate_baseline import BASELINE
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


def test_a_change_beyond_its_multiple_of_the_resolution_fails_naming_old_new_and_allowance() -> None:
    recorded = _baseline(_result({"a": 0.01, "b": 0.02}), {"a": 1e-4, "b": 1e-4})
    assert baseline.deviations(_result({"a": 0.01 + 2.9e-4, "b": 0.02 - 2.9e-4}), recorded) == []
    moved = baseline.deviations(_result({"a": 0.01 + 3.1e-4, "b": 0.02}, timestep=1.01e-3), recorded)
    assert [d.check for d in moved] == ["a"]
    assert moved[0].message() == (
        "rimless-wheel[fast]::a: error 0.01 -> 0.01031: changed 0.00031, 1.03 x its allowance 0.0003 (the larger of "
        "3 x its resolution 0.0001 and 1e-06 x its tolerance); settings differ from the recorded run: timestep 0.001 "
        "-> 0.00101")


def test_below_the_floor_a_change_passes_however_small_the_resolution_and_nan_matches_only_nan() -> None:
    """The tolerance is 0.1: a resolution at roundoff (or none measured) still allows 1e-7, a millionth of it."""
    recorded = _baseline(_result({"a": 0.5, "b": math.nan, "c": 0.3}), {"a": 0.0, "c": 1e-14})
    assert baseline.deviations(_result({"a": 0.5 + 9e-8, "b": math.nan, "c": 0.3 - 9e-8}), recorded) == []
    moved = baseline.deviations(_result({"a": 0.5 + 1.1e-7, "b": 0.0, "c": 0.3}), recorded)
    assert [d.check for d in moved] == ["a", "b"]


def test_a_re_record_that_changes_no_run_keeps_the_stamp() -> None:
    result = _result({"a": 0.01})
    record = [(baseline.run_key(result), baseline.entry(result, {"a": 1e-4}))]
    first = baseline.updated(None, record, {"date": "then"})
    assert baseline.updated(first, record, {"date": "now"})["stamp"] == {"date": "then"}
    moved = _result({"a": 0.02})
    changed = [(baseline.run_key(moved), baseline.entry(moved, {"a": 1e-4}))]
    assert baseline.updated(first, changed, {"date": "now"})["stamp"] == {"date": "now"}


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
    measurement in it, each resolution finite and at least 0 and below the check's tolerance except where the gate
    declares the check unresolved (its spread exceeds half its tolerance: no baseline resolves it either), recorded
    under the allowance's rule of today."""
    payload = baseline.load(str(ROOT / BASELINE))
    assert payload["stamp"]["git_sha"] and (payload["multiple"], payload["floor"]) == (MULTIPLE, FLOOR)
    rows = json.loads((ROOT / "docs/results/gate/margins.json").read_text())["rows"]
    keys = {c.label: baseline.key_of(c.scenario, c.preset, dict(c.values)) for c in gate.cases()}
    assert set(payload["runs"]) == set(keys.values()) and len(keys) == len(set(keys.values()))
    for row in rows:
        entry = payload["runs"][keys[row["case"]]]["checks"][row["check"]]
        assert entry["resolution"] is not None and entry["resolution"] >= 0, (row["case"], row["check"])
        if row["tolerance"] > 0 and row["status"] != "declared miss, unresolved":
            assert entry["resolution"] < row["tolerance"], (row["case"], row["check"])


@pytest.mark.mujoco
def test_a_planted_change_below_the_floor_passes_and_beyond_the_allowance_fails_the_committed_baseline() -> None:
    """The skate's gate run with its heading error moved by half its floor (a millionth of its tolerance, far above
    its recorded resolution) passes the committed baseline; moved by 1.1 x its allowance, it fails, naming the check
    alone."""
    run = gate.run_case(gate.case("slotted-skate[fast]"))
    committed = baseline.load(str(ROOT / BASELINE))
    entry = committed["runs"][baseline.run_key(run)]["checks"]["heading"]
    assert entry["resolution"] < 0.5 * floor(entry["tolerance"]), "the heading's resolution reached the floor"

    def moved(shift: float) -> list[baseline.Deviation]:
        checks = [dataclasses.replace(c, error=c.error + shift) if c.name == "heading" else c for c in run.checks]
        return baseline.deviations(dataclasses.replace(run, checks=checks), committed)

    assert moved(0.0) == [] and moved(0.5 * floor(entry["tolerance"])) == []
    beyond = moved(1.1 * allowance(entry["resolution"], entry["tolerance"], entry["error"]))
    assert [d.check for d in beyond] == ["heading"] and "1.1 x its allowance" in beyond[0].message()


@pytest.mark.mujoco
@pytest.mark.parametrize("case", [pytest.param(c, id=c.label) for c in gate.cases()])
def test_every_gate_run_stays_within_the_committed_baseline(case: GateCase) -> None:
    """No check of the gate's run moved from the committed baseline by more than its multiple of the resolution."""
    moved = baseline.deviations(gate.run_case(case), baseline.load(str(ROOT / BASELINE)))
    assert not moved, "\n".join([*(d.message() for d in moved),
                                 "a real change: re-measure with make margins, then make baseline, and read its diff"])
