"""The measured-results pages under docs/results/ are generated: each re-renders byte for byte from its committed
JSON (no simulation here), and the renderer reports what the JSON says."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest

from mjpoincare import scenarios
from mjpoincare.gate import releases
from mjpoincare.pages import discrimination_page, gate_power_page
from mjpoincare.pages import results_pages as results

RESULTS = Path(__file__).resolve().parent.parent / "docs" / "results"
PAYLOADS = results.load_payloads(RESULTS)
#: The scenarios this distribution declares (a plugin installed beside it has no committed pages here).
BUILT_IN = [s for s in scenarios.REGISTRY if scenarios.REGISTRY.distribution(s) == "mjpoincare"]


def test_every_scenario_has_committed_results() -> None:
    assert sorted(p["scenario"] for p in PAYLOADS) == sorted(BUILT_IN)
    for payload in PAYLOADS:
        assert [r["preset"] for r in payload["runs"]] == list(scenarios.get(payload["scenario"]).presets)
        assert payload["schema"] == results.SCHEMA


@pytest.mark.parametrize("payload", PAYLOADS, ids=[p["scenario"] for p in PAYLOADS])
def test_committed_page_reproduces_from_its_json(payload: dict[str, Any]) -> None:
    page = RESULTS / f"{payload['scenario']}.md"
    assert page.read_text() == results.render_scenario(payload), f"{page} is stale: run make results-render"


def test_committed_index_reproduces_from_the_json() -> None:
    assert (RESULTS / "README.md").read_text() == results.render_index(PAYLOADS)
    pages = {p.name for p in RESULTS.glob("*.md")}
    # the release history (from releases/json, mjpoincare.gate.releases), the gate's power (from gate/power.json) and
    # the discrimination of its checks (from gate/margins.json)
    others = {releases.PAGE.name, gate_power_page.PAGE.name, discrimination_page.PAGE.name}
    assert pages == {"README.md", *others} | {f"{p['scenario']}.md" for p in PAYLOADS}, "a page without its JSON"


def _synthetic() -> dict[str, Any]:
    check = {"name": "eigenvalue", "analytic": 0.5, "simulated": 0.52, "error": 0.02, "error_kind": "absolute",
             "tolerance": 0.01, "unit": "", "passed": False, "why": "|lambda| from the fit\nof 3 starts"}
    other = {"name": "period", "analytic": [1.0, 2.0], "simulated": None, "error": None, "error_kind": "relative",
             "tolerance": 1e-3, "unit": "s", "passed": False, "why": "timing"}
    good = {**check, "name": "fixed_point", "error": 1e-4, "passed": True}
    run = {"preset": "fast", "passed": False, "params": {"spokes": 8, "slope": 0.08},
           "settings": {"timestep": 4e-4, "integrator": "rk4"}, "checks": [good, check, other],
           "timing": {"wall_s": 1.234, "steps": 2.85e5, "steps_per_s": 2e5, "rollout_steps_per_s": 2.5e5},
           "warnings": ["Nan, Inf or huge value in QACC"], "diverged_trajectories": [3],
           "reported": {"depth": {"value": 0.002, "unit": "m", "note": "no verdict"}}}
    env = {"mujoco": "9.9.9", "numpy": "1.0", "scipy": "2.0", "python": "3.11.0", "platform": "Linux-x", "cpu": "CPU X",
           "logical_cpus": 2, "git_sha": "abc123", "git_dirty": True, "date": "2026-01-01T00:00:00Z"}
    return {"schema": results.SCHEMA, "scenario": "toy", "summary": "a toy", "source": "Paper 2000 eq 1", "seed": 0,
            "environment": env, "runs": [run, {**copy.deepcopy(run), "preset": "accurate", "passed": True,
                                                 "checks": [good]}]}


def _rows(page: str) -> list[list[str]]:
    """The check-table rows of ``page``, split on unescaped pipes."""
    rows = []
    for line in page.splitlines():
        if line.startswith("| ") and not line.startswith(("| check ", "| run ", "| MuJoCo", "| numpy", "| git",
                                                            "| CPU", "| date")):
            rows.append([c.strip() for c in line.replace("\\|", "\0").strip("|").split("|")])
    return rows


def test_renderer_reports_the_json() -> None:
    payload = _synthetic()
    page = results.render_scenario(payload)
    assert payload == _synthetic()  # rendering leaves its input alone
    rows = _rows(page)
    assert all(len(r) == 7 for r in rows), "a pipe or newline in a cell broke the table"
    fast = {r[0]: r for r in rows[:3]}
    assert fast["fixed_point"][5] == "PASS" and fast["eigenvalue"][5] == "FAIL"
    assert fast["eigenvalue"][1:5] == ["0.5", "0.52", "0.02 absolute", "0.01"]
    assert fast["period"][2:4] == ["nan s", "nan relative"]
    assert fast["period"][1] == "[1, 2] s"
    assert "## preset `fast`: FAIL (1 of 3 checks)" in page
    assert "## preset `accurate`: PASS (1 of 1 checks)" in page
    assert page.index("## preset `fast`") < page.index("## preset `accurate`")
    for text in ("MuJoCo | 9.9.9", "abc123 (with uncommitted changes)", "CPU X (2 logical CPUs)",
                 "2026-01-01T00:00:00Z", "1.0 / 2.0 / 3.11.0", "Diverged trajectories: [3]", "MuJoCo warning: Nan, Inf",
                 "depth = 0.002 m", "`timestep=0.0004`", "`spokes=8`"):
        assert text in page, text


def test_index_lists_every_run() -> None:
    index = results.render_index([_synthetic()])
    assert "| [toy](toy.md) | fast | FAIL (1 of 3 checks) | eigenvalue, period | 1.23 |" in index
    assert "| [toy](toy.md) | accurate | PASS (1 of 1 checks) | none |" in index
    assert "abc123+" in index
