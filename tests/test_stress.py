"""The stress command: case verdicts, the timestep ladder's summary, the soak, and a refused edge."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import pytest

from mjpoincare import scenarios
from mjpoincare.cli import main
from mjpoincare.commands.check_plugin import stress_cases_answered
from mjpoincare.commands.stress import (
    LADDER,
    generic_cases,
    largest_timesteps,
    run_case,
    soak_steps,
    soak_summary,
)
from mjpoincare.scenarios.base import StressCase


def test_generic_cases_cover_the_ladder_integrators_solvers_and_contact() -> None:
    names = [c.name for c in generic_cases(scenarios.get("rimless-wheel"))]
    assert [n for n in names if n.startswith("timestep")] == [f"timestep x{k}" for k in LADDER]
    assert {"integrator euler", "integrator rk4", "solver cg", "solver pgs", "cone pyramidal", "stiff contact",
            "soft contact"} <= set(names)


def test_largest_timesteps_stop_at_the_first_failure() -> None:
    verdicts = ["accurate", "accurate", "inaccurate", "diverged", "inaccurate", "inaccurate"]
    rows = [{"case": f"timestep x{k}", "verdict": v} for k, v in zip(LADDER, verdicts, strict=True)]
    assert largest_timesteps(rows, 1e-4) == pytest.approx((4e-4, 2e-4))


def test_every_scenario_declares_edges_that_must_be_refused() -> None:
    for name in scenarios.default_scenarios():
        cases = scenarios.get(name).stress_cases
        assert any(c.expect == "refused" for c in cases), name
        assert any(c.expect == "run" for c in cases), name


def test_check_plugin_answers_each_stress_case_accepted_or_refused() -> None:
    """``mjpoincare check-plugin``'s stress clause: every case of the 3-D wheel accepted or refused in one line, the
    refused ones those it declares refused."""
    cases = scenarios.get("rimless-wheel-3d").stress_cases
    refused = sum(c.expect == "refused" for c in cases)
    assert stress_cases_answered("rimless-wheel-3d") == f"{len(cases)} cases, {refused} refused in one line"


def test_refused_case_is_reported_not_raised() -> None:
    row = run_case("rimless-wheel", StressCase("two spokes", {"spokes": "2"}, "", expect="refused"))
    assert row["verdict"] == "refused" and "spokes" in row["message"]


@pytest.mark.mujoco
def test_case_runs_with_diagnostics() -> None:
    # a 2 ms step (the peg's time constant at 2 steps): the diagnostics' mechanism in a quarter of the preset's time
    row = run_case("slotted-skate", StressCase("rk4", {"integrator": "rk4", "timestep": "2e-3",
                                                      "solref_timeconst": "4e-3"}, "integrator"))
    assert row["verdict"] == "accurate"
    assert row["max_penetration_m"] == 0.0  # contact is disabled in the skate: only the peg constraint acts
    assert row["max_kinetic_energy_J"] == pytest.approx(0.5 * (1.0 + 1.5**2 * 0.1**2 * (1 + 1.0)), rel=0.1)


@pytest.mark.mujoco
def test_a_soak_past_a_billion_steps_is_refused_before_it_starts(capsys: pytest.CaptureFixture[str]) -> None:
    """A 20-impact pilot costs the soak: rimless-wheel's million impacts at the fast preset, about 1.1e9 steps."""
    assert main(["stress", "rimless-wheel", "--soak", "1000000"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "stress rimless-wheel --soak 1000000 (a 20-impact pilot, scaled) would take" in err
    steps = soak_steps("rimless-wheel", 1_000_000)
    assert 1e9 < steps < 1.3e9
    assert soak_steps("rimless-wheel", 1000) == pytest.approx(steps / 1000)
    assert soak_steps("slotted-skate", 1_000_000) == 0.0  # no soak: nothing to cost


def test_soak_of_the_wheel_stays_on_the_cycle() -> None:
    summary = soak_summary("rimless-wheel", 40)
    assert summary["impacts_seen"] >= 40 and summary["diverged"] == 0
    assert summary["relative_error_last_tenth"] < 1e-2  # the fast preset's omega_post_impact tolerance
    assert abs(summary["drift"]) < 1e-2 * summary["analytic"]
    assert "defines no soak" in soak_summary("slotted-skate", 40)["skipped"]  # no limit cycle to soak on
    assert soak_summary("rimless-wheel", 0) == {"skipped": "--soak 0 asked for none"}


def test_stress_cli_refuses_unknown_scenario(tmp_path: Path) -> None:
    assert main(["stress", "no-such-scenario", "--soak", "0"]) == 2
    assert not any(tmp_path.iterdir())


def test_stress_json_is_strict(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The report is written whole, as strict JSON (NaN becomes null). Of the edges the skate declares, it keeps the
    two that run in half a second together and the two it must refuse (its other edges take 15 s)."""
    from mjpoincare.commands import stress

    monkeypatch.setattr(stress, "generic_cases", lambda scenario: [])
    skate = scenarios.get("slotted-skate")
    cases = tuple(c for c in skate.stress_cases if c.expect == "refused" or c.name in ("fast slide", "short slot"))
    assert len(cases) == 4 and {c.expect for c in cases} == {"run", "refused"}
    monkeypatch.setitem(scenarios.REGISTRY, skate.name, replace(skate, stress_cases=cases))
    out = tmp_path / "stress.json"
    monkeypatch.setattr(stress, "LADDER", ())
    assert main(["stress", "slotted-skate", "--soak", "0", "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    assert {r["case"] for r in report["cases"]} == {c.name for c in cases}
    assert {r["verdict"] == "refused" for r in report["cases"]} == {True, False}
    assert report["largest_stable_timestep"] is None or math.isnan(report["largest_stable_timestep"])
