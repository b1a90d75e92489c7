"""The registry's contract, as dm_control's suite test holds its domains to theirs: every scenario at every preset has
defaults its own input check accepts, tolerances for that preset, a declaration of the checks a run reports, a model
that compiles, validation batches that fit the model, a render frame, and a validation result whose JSON round-trips and
whose checks are the declared ones: the clauses ``mjpoincare check-plugin`` runs, its functions
(:mod:`mjpoincare.commands.check_plugin`), called here (tests/test_gate.py calls the gate's). The validation results are
the gate's cached runs (:func:`mjpoincare.gate.forms.case`), so no validation runs twice in a session; the declarations
of the gate's other runs are held to the checks the committed margins measurement (docs/results/gate/margins.json) saw
them report."""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from mjpoincare.commands import check_plugin as clause
from mjpoincare.commands.validation import resolve_values
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios import REGISTRY, loadable
from mjpoincare.scenarios.base import MissingTolerances, at_preset
from mjpoincare.scenarios.gate_cases import GateCase

CASES = [pytest.param(name, preset, id=f"{name}[{preset}]") for name in loadable() for preset in REGISTRY[name].presets]
MARGINS = Path(__file__).resolve().parent.parent / "docs" / "results" / "gate" / "margins.json"
#: Every key of a run's JSON and of a check's, each in the first column of one of its tables.
RESULT_JSON_DOC = Path(__file__).resolve().parent.parent / "docs" / "result-json.md"


def _measured() -> dict[str, list[str]]:
    """Gate case label -> the checks its run reported when the gate was last measured (``make margins``), in the
    run's order."""
    measured: dict[str, list[str]] = {}
    for row in json.loads(MARGINS.read_text())["rows"]:
        measured.setdefault(row["case"], []).append(row["check"])
    return measured


MEASURED = _measured()
#: The built-in scenarios' gate cases: the runs the committed measurement covers (a plugin's are measured elsewhere).
BUILT_IN_CASES = [pytest.param(case, id=case.label) for case in gate.cases()
                  if REGISTRY.distribution(case.scenario) == "mjpoincare"]


def test_every_registered_scenario_loads() -> None:
    """Every scenario of the registry loads and its declaration holds; one that does not (a plugin's mistake) fails
    here, in the registry's line, and stays out of the other tests, which run for the rest."""
    loadable()
    assert not REGISTRY.broken, "\n".join(REGISTRY.broken.values())


@pytest.mark.parametrize(("name", "preset"), CASES)
def test_defaults_accepted_and_tolerances_with_reasons(name: str, preset: str) -> None:
    clause.defaults_accepted(name, preset)
    clause.tolerances_with_reasons(name, preset)


@pytest.mark.parametrize(("name", "preset"), CASES)
def test_the_defaults_declare_the_checks_a_run_reports(name: str, preset: str) -> None:
    """``checks_for`` at the defaults: check names, each once, in the order of ``checks`` (every check the scenario
    reports somewhere), without the ``stable`` the validation appends; every built-in scenario declares its checks."""
    scenario, _, params, settings = resolve_values(name, {}, preset)
    declared = scenario.checks_for(params, settings)
    assert isinstance(declared, tuple) and all(isinstance(c, str) for c in declared), declared
    assert len(set(declared)) == len(declared) and "stable" not in declared, declared
    assert [c for c in scenario.checks if c in declared] == list(declared), (declared, scenario.checks)
    assert declared or REGISTRY.distribution(name) != "mjpoincare", f"{name}: declares no checks"


@pytest.mark.parametrize("case", BUILT_IN_CASES)
def test_the_declared_checks_of_each_gate_run_are_the_checks_it_reported(case: GateCase) -> None:
    """Each gate case's declaration (``checks_for`` at its parameters and preset, then ``stable``) is the list of
    checks its run reported in the committed margins measurement, in the run's order: a check the run reports and
    the scenario does not declare, or one it declares and the run does not report, is a bug of the declaration (no
    simulation here: the declarations are analytic)."""
    assert case.label in MEASURED, f"{case.label}: not in {MARGINS.name} (run make margins)"
    scenario, _, params, settings = resolve_values(case.scenario, dict(case.values), case.preset)
    assert [*scenario.checks_for(params, settings), "stable"] == MEASURED[case.label]


def test_a_missing_preset_is_an_error_not_a_fallback() -> None:
    with pytest.raises(MissingTolerances, match="scenario 'x' declares no tolerances for preset 'coarse'"):
        at_preset({"fast": {"a": 1.0}}, "x", "coarse")


@pytest.mark.mujoco
@pytest.mark.parametrize(("name", "preset"), CASES)
def test_model_compiles_and_validation_batches_fit_it(name: str, preset: str) -> None:
    clause.model_and_batches(name, preset)


@pytest.mark.mujoco
@pytest.mark.parametrize(("name", "preset"), CASES)
def test_one_render_frame(name: str, preset: str) -> None:
    clause.still_renders(name, preset)


@pytest.mark.mujoco
@pytest.mark.parametrize(("name", "preset"), CASES)
def test_a_validation_reports_the_checks_its_scenario_declares_and_its_json_round_trips(name: str, preset: str) -> None:
    """The defaults' run (the gate's cached one) reports its declared checks, in their order, then ``stable``: none of
    kind ``missing`` (the validation's stand-in for a declared check the run lost) and none undeclared (a scenario
    that declares no checks, a plugin written without them, is held to no order); its JSON round-trips, and every key
    of it is documented."""
    result = gate.run_case(gate.case(f"{name}[{preset}]"))
    clause.reports_declared_checks(name, preset, result)
    payload = result.to_dict()
    first_cells = re.findall(r"^\| ([^|]+) \|", RESULT_JSON_DOC.read_text(), re.M)
    keys = {key for cell in first_cells for key in re.findall(r"`([a-z_]+)`", cell)}
    assert set(payload) <= keys, f"undocumented keys of a run (docs/result-json.md): {set(payload) - keys}"
    assert {k for c in payload["checks"] for k in c} <= keys


def test_looking_up_a_scenario_imports_that_scenario_only() -> None:
    """The registry imports a scenario's module on first lookup: a command that runs one loads no other."""
    code = ("import sys; from mjpoincare import scenarios; scenarios.get('rimless-wheel'); "
            "print(sorted(m for m in sys.modules if m.startswith('mjpoincare.scenarios.')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    loaded = set(ast.literal_eval(out))
    assert "mjpoincare.scenarios.rimless_wheel" in loaded
    assert not loaded & {f"mjpoincare.scenarios.{m}" for m in ("compass_biped", "compass_biped_friction",
                                                               "slotted_skate", "rimless_wheel_3d",
                                                               "rimless_wheel_friction")}
