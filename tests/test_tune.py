"""The preset search (``mjpoincare tune``): how a trial is judged, how the preset is read off the front, that the
scenarios' presets are the ones their committed studies chose, and one real study through the command line."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest
from conftest import require_module
from mjpoincare.analysis.checks import Check

from mjpoincare import scenarios
from mjpoincare.cli import main
from mjpoincare.commands import tune, tune_pages
from mjpoincare.commands.validation import resolve_inputs

TUNE = Path(__file__).resolve().parent.parent / "docs" / "results" / "tune"
STUDIES = [json.loads(p.read_text()) for p in sorted((TUNE / "json").glob("*.json"))]


def _check(error: float, tolerance: float) -> Check:
    return Check(name="c", analytic=0.0, simulated=error, error=error, tolerance=tolerance, kind="absolute", unit="",
                 why="")


def test_a_check_ratio_is_error_over_tolerance_and_a_failed_zero_tolerance_check_is_the_cap() -> None:
    assert tune.check_ratio(_check(2e-3, 1e-2)) == pytest.approx(0.2)
    assert tune.check_ratio(_check(0.0, 0.0)) == 0.0
    assert tune.check_ratio(_check(1.0, 0.0)) == tune.RATIO_CAP
    assert tune.check_ratio(_check(math.nan, 1e-2)) == tune.RATIO_CAP
    assert tune.check_ratio(_check(1e9, 1e-2)) == tune.RATIO_CAP


def _front_row(number: int, cpu: float, ratio: float | None) -> dict[str, Any]:
    return {"number": number, "cpu_s": cpu, "worst_ratio": ratio, "settings": {"timestep": 1e-4}}


def test_the_preset_is_the_cheapest_front_point_within_half_its_tolerances() -> None:
    front = [_front_row(0, 1.0, 3.0), _front_row(1, 2.0, 0.6), _front_row(2, 4.0, 0.5), _front_row(3, 8.0, 0.1)]
    chosen, holds = tune.choose(front)
    assert chosen is not None and chosen["number"] == 2 and holds == "margin"


def test_a_trial_outside_the_targets_timestep_range_is_never_chosen() -> None:
    """The fast preset, enqueued into the accurate study and within half the accurate tolerances at its 0.5 ms, is
    the cheapest such trial, yet not the accurate preset: the 0.2 ms trial is."""
    space = [{"name": "timestep", "low": 1e-5, "high": 2e-4}, {"name": "solref_dampratio", "low": 0.5, "high": 10.0}]
    fast, finer = {**_front_row(0, 11.3, 0.28), "settings": {"timestep": 5e-4}}, _front_row(1, 23.2, 0.19)
    chosen, holds = tune.choose(tune.in_timestep_range([fast, finer], space))
    assert chosen is finer and holds == "margin"
    assert tune.choose([fast, finer])[0] is fast


def test_without_such_a_point_the_preset_is_the_cheapest_passing_one_or_none() -> None:
    chosen, holds = tune.choose([_front_row(0, 1.0, 3.0), _front_row(1, 2.0, 0.9), _front_row(2, 4.0, 0.6)])
    assert chosen is not None and chosen["number"] == 1 and holds == "no margin"
    assert tune.choose([_front_row(0, 1.0, 3.0), _front_row(1, 2.0, 1.2)]) == (None, "none")
    assert tune.choose([_front_row(0, 1.0, None)]) == (None, "none")


@pytest.mark.parametrize("name", list(scenarios.REGISTRY))
def test_every_preset_is_a_point_of_its_search_space(name: str) -> None:
    """A preset enqueued as a trial gives back the preset's settings (the time constant is searched in timesteps)."""
    require_module("optuna", "optuna")
    import optuna
    scenario = scenarios.get(name)
    for preset in scenario.presets:
        if preset not in tune.TARGETS:
            continue
        settings = tune.suggest_settings(optuna.trial.FixedTrial(tune.preset_params(scenario, preset)),
                                         scenario.search_dimensions)
        full = {**tune.sim_settings.DEFAULTS, **scenario.presets[preset]}
        for key, value in settings.items():
            expected = full[key]
            assert value == (expected if isinstance(expected, str) else pytest.approx(expected, rel=1e-12)), key


def test_enqueued_settings_become_trial_parameters_and_bad_ones_are_refused() -> None:
    wheel = scenarios.get("rimless-wheel")
    params = tune.enqueued_params(wheel, {"timestep": "2.5e-5", "solref_timeconst": "2.5e-4", "foot_radius": "1e-4"})
    assert params == {"timestep": 2.5e-5, "solref_timeconst_steps": pytest.approx(10.0), "foot_radius": 1e-4}
    with pytest.raises(tune.ParameterError, match="cone not searched for rimless-wheel"):
        tune.enqueued_params(wheel, {"cone": "pyramidal"})
    with pytest.raises(tune.ParameterError, match="solref_timeconst needs timestep"):
        tune.enqueued_params(wheel, {"solref_timeconst": "1e-3"})
    with pytest.raises(tune.ParameterError, match="timestep must be"):
        tune.enqueued_params(wheel, {"timestep": "-1"})


@pytest.mark.parametrize("name", list(scenarios.REGISTRY))
def test_every_coverage_point_is_a_valid_input(name: str) -> None:
    for point in scenarios.get(name).coverage:
        resolve_inputs(name, dict(point.assignments), None)


@pytest.mark.parametrize("study", STUDIES, ids=[s["study"] for s in STUDIES])
def test_the_scenarios_presets_are_the_ones_their_studies_chose(study: dict[str, Any]) -> None:
    """A committed study that found a preset: the scenario declares exactly that preset for every setting of the
    study's (the searched ones and those it held), and adds only settings the study neither searched nor held (the
    bipeds' foot impedance, set after their searches: docs/scenarios/compass-biped.md); one that found none says so,
    and the scenario keeps its own."""
    rule = tune.choose(tune.in_timestep_range(study["trials"], study["space"]))
    assert rule == (study["chosen"], study["holds"]), "the study's choice is not the rule's"
    declared = scenarios.get(study["scenario"]).presets[study["target"]]
    if study["preset"] is None:
        assert study["chosen"] is None and study["holds"] == "none" and declared
        return
    added = set(declared) - set(study["preset"])
    assert set(study["preset"]) <= set(declared) and not added & {d["name"] for d in study["space"]}, added
    for key, value in study["preset"].items():
        if isinstance(value, float):
            assert float(declared[key]) == pytest.approx(value, rel=1e-9), key
        else:
            assert declared[key] == value, key


def test_the_tune_pages_reproduce_from_their_json() -> None:
    by_scenario: dict[str, list[dict[str, Any]]] = {}
    for study in STUDIES:
        by_scenario.setdefault(study["scenario"], []).append(study)
    assert {p.stem for p in TUNE.glob("*.md")} == set(by_scenario), "a page without its JSON, or JSON without a page"
    for name, studies in by_scenario.items():
        studies.sort(key=lambda s: s["target"])
        assert (TUNE / f"{name}.md").read_text() == tune_pages.render_page(studies), f"{name}.md is stale"


def test_a_study_runs_in_worker_processes_resumes_and_writes_its_front(tmp_path: Path,
                                                                        capsys: pytest.CaptureFixture[str]) -> None:
    """One trial (the enqueued fast preset, judged at the fast tolerances) in two spawned workers; resuming to the
    same count runs nothing more and reports the same front. The study is the friction wheel's, whose trial (its
    three coverage points at its fast preset) takes a fifth of the time of the rigid wheel's."""
    require_module("optuna", "optuna")
    name = "rimless-wheel-friction"
    db, out = tmp_path / "study.db", tmp_path / "front.json"
    args = ["tune", name, "--target", "fast", "--trials", "1", "--study", str(db), "--json", str(out)]
    assert main([*args, "--workers", "2"]) == 0
    first = json.loads(out.read_text())
    assert [r["origin"] for r in first["trials"]] == ["preset fast"]
    assert len(first["front"]) == 1 and first["front"][0]["cpu_s"] > 0
    assert first["front"][0]["worst_check"].split("/")[0] in {p.name for p in scenarios.get(name).coverage}
    assert main([*args, "--workers", "1", "--resume"]) == 0
    again = json.loads(out.read_text())
    assert [r["number"] for r in again["trials"]] == [0]
    assert again["front"] == first["front"]
    assert "Pareto front of 1" in capsys.readouterr().out


def test_bad_tune_input_is_refused_before_any_trial(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    db = tmp_path / "study.db"
    assert main(["tune", "rimless-wheel", "--target", "coarse", "--study", str(db)]) == 2
    assert "--target must be one of accurate, fast" in capsys.readouterr().err
    assert main(["tune", "rimless-wheel", "--trials", "0", "--study", str(db)]) == 2
    assert not db.exists()


def test_a_study_too_long_to_run_is_refused_before_it_starts(tmp_path: Path,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    """``--trials`` whose estimated steps (each trial the target preset's validations over the coverage points) pass
    the cost check's bound: one line with the estimate and the remedy, exit 2, no study written."""
    study = tmp_path / "study.db"
    assert main(["tune", "rimless-wheel", "--target", "fast", "--trials", "100000000", "--study", str(study)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "tune rimless-wheel --trials 100000000" in err[0] and "give fewer --trials" in err[0]
    assert not study.exists()
