"""The papers' results (``mjpoincare reproduce``): every declaration is well formed and runnable as declared, the list
runs no simulation, the generated pages re-render from their committed JSON, and the regression gate asserts the
cheap results' verdicts at the fast preset."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest

from mjpoincare import cli, scenarios
from mjpoincare.commands import reproduce
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.pages import papers_page
from mjpoincare.scenarios.paper_results import (
    PAPERS,
    AtValidation,
    Bracket,
    Curve,
    PaperResult,
    Reading,
    Refusal,
    _CheckReader,
    bisect,
    verdict,
)

DECLARED = reproduce.declared()
IDS = list(DECLARED)
PAGES = Path(__file__).resolve().parent.parent / "docs" / "results" / "papers"


@pytest.mark.parametrize("rid", IDS)
def test_declaration_is_complete_and_runnable(rid: str) -> None:
    scenario_name, pr = DECLARED[rid]
    scenario = scenarios.get(scenario_name)
    assert pr.location and pr.quantity and pr.independent, rid
    run = pr.run
    if isinstance(run, AtValidation):
        resolve_inputs(scenario_name, dict(run.assignments), "fast")  # the parameters are valid: no ParameterError
        if isinstance(run.read, _CheckReader):
            assert run.read.name in scenario.checks, f"{rid}: {run.read.name} is not a check of {scenario_name}"
    elif isinstance(run, Curve):
        assert len(run.x) >= 8 and run.x_label and run.y_label
    elif isinstance(run, Bracket):
        assert run.low != run.high and run.tolerance > 0
    elif isinstance(run, Refusal):
        assert len(run.reason) > 40, f"{rid}: a refusal states its physical reason"
    if pr.miss:
        assert re.search(r"\d", pr.miss), f"{rid}: a declared miss states its measured mechanism (numbers)"
    if not isinstance(run, AtValidation) and not isinstance(run, Refusal):
        assert pr.why, f"{rid}: a tolerance that is not a check's states why it is what it is"


def test_every_paper_has_results() -> None:
    assert {pr.paper for _, pr in DECLARED.values()} == set(PAPERS)


def test_list_runs_no_simulation(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    def refuse(*_: Any, **__: Any) -> None:
        raise AssertionError("--list simulated")

    monkeypatch.setattr(reproduce, "run_validation", refuse)
    assert cli.main(["reproduce", "--list", "--json", "-"]) == 0
    listed = json.loads(capsys.readouterr().out)["results"]
    assert [r["id"] for r in listed] == IDS
    for row in listed:
        assert {"id", "paper", "location", "quantity", "paper_value", "mujoco_run"} <= row.keys()


def test_unknown_id_and_paper_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["reproduce", "002-no-such-result"]) == 2
    assert "unknown result id '002-no-such-result'" in capsys.readouterr().err
    assert cli.main(["reproduce", "--paper", "004", "--list"]) == 2
    assert "--paper must be one of 000, 001, 002, 003" in capsys.readouterr().err


def test_verdicts_and_bisection() -> None:
    pr = PaperResult(id="002-x", paper="002", location="eq (1)", quantity="q", paper_value="", independent="i",
                     run=Refusal("r"), miss="measured 2x")
    assert verdict(Reading(1.0, 1.1, 0.1, 0.2), pr) == "pass"
    assert verdict(Reading(1.0, 1.5, 0.5, 0.2), pr) == "miss"
    assert verdict(Reading(1.0, float("nan"), float("nan"), 0.2), PaperResult(**{**pr.__dict__, "miss": ""})) == "FAIL"
    assert verdict(None, pr) == "refused"
    low, high, runs = bisect(lambda v: v < 0.3, 0.0, 1.0, 1e-3)
    assert low < 0.3 <= high and high - low <= 1e-3 and runs == 12
    with pytest.raises(ValueError, match="does not bracket"):
        bisect(lambda v: v < 0.3, 0.5, 1.0, 1e-3)


def test_gate_asserts_the_cheap_results(tmp_path: Path) -> None:
    """The results the papers state at the scenarios' defaults, cheap to run (``gate=True``), in one run at the fast
    preset (the results of one validation share it): each verdict is the declared one (pass, or a declared miss)."""
    gated = [rid for rid, (_, pr) in DECLARED.items() if pr.gate]
    out = tmp_path / "r.json"
    reproduce.run_reproduce(gated, None, "fast", str(out), None)
    rows = {row["id"]: row for row in json.loads(out.read_text())["results"]}
    wrong = {rid: (rows[rid]["verdict"], rows[rid]["error"], rows[rid]["tolerance"]) for rid in gated
             if rows[rid]["verdict"] != ("miss" if DECLARED[rid][1].miss else "pass")}
    assert not wrong, f"verdict, error, tolerance of the gated results that changed: {wrong}"


def test_committed_pages_reproduce_from_their_json() -> None:
    runs = papers_page.load(PAGES)
    assert set(runs) == {"fast", "accurate"}, "run make papers"
    for name, text in papers_page.render(runs).items():
        assert (PAGES / name).read_text() == text, f"docs/results/papers/{name} is stale: run make papers-render"


def test_committed_run_covers_every_declared_result() -> None:
    runs = papers_page.load(PAGES)
    held = {row["id"] for run in runs.values() for row in run["results"]}
    assert held == set(IDS), "docs/results/papers/json is stale: run make papers"
    for rid in IDS:
        if DECLARED[rid][1].kind == "figure":
            assert (PAGES / "figures" / f"{rid}.png").exists()
