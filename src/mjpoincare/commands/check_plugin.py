"""``mjpoincare check-plugin NAME``: the scenario contract and the gate's forms, run against an installed scenario (a
plugin's, or a built-in one), in about the time of its validations at each preset.

The clauses are the ones the suite holds its own scenarios to: tests/test_scenario_contract.py and tests/test_gate.py
run the public functions of this module, one per clause, on every registered scenario. The declaration loads; at every
preset the defaults are accepted, the tolerances exist with their reasons, the model compiles, the validation batches
fit it, a validation reports exactly the declared checks and its JSON round-trips, and a still renders; every stress
case is accepted or refused in one line; every gate case names each check of its run once, gated, watched or a
declared miss, and its gated checks pass. One line per clause; exit 0 when every clause holds, else 1.
"""

from __future__ import annotations

import json
import math
import tempfile
from collections.abc import Callable
from pathlib import Path

import mujoco
import numpy as np

from mjpoincare import scenarios
from mjpoincare.commands.validation import resolve_inputs, resolve_values, run_validation
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import Result, write_json
from mjpoincare.core.seam import STATE_SPEC
from mjpoincare.scenarios import GateCase, Tolerances, at_preset


class _Clauses:
    """The clauses' verdicts, printed as they come."""

    def __init__(self) -> None:
        self.failed = 0

    def check(self, clause: str, test: Callable[[], str | None]) -> None:
        """Run ``test`` (None or a note: holds; an assertion or any error: fails) and print one line."""
        try:
            note = test()
        except Exception as err:  # a clause that raises fails, in one line
            self.failed += 1
            text = str(err).splitlines()[0] if str(err) else ""
            print(f"FAIL  {clause}: {type(err).__name__}{': ' + text if text else ''}")
            return
        print(f"ok    {clause}" + (f" ({note})" if note else ""))


def defaults_accepted(name: str, preset: str) -> str:
    """The defaults at ``preset`` pass the scenario's own input checks and the seam self-test."""
    resolve_inputs(name, {}, preset)
    return ""


def tolerances_with_reasons(name: str, preset: str) -> str:
    """Every tolerance table of the scenario has bounds at ``preset``, each finite and > 0, and says why."""
    for table in scenarios.REGISTRY[name].tolerance_tables:
        tolerances = at_preset(table, name, preset)
        assert isinstance(tolerances, Tolerances) and tolerances.bounds, f"no bounds at {preset}"
        assert all(math.isfinite(v) and v > 0 for v in tolerances.bounds.values()), tolerances.bounds
        assert tolerances.why or tolerances.reasons, "no reason given for the tolerances"
    return ""


def model_and_batches(name: str, preset: str) -> str:
    """The model compiles at ``preset``'s defaults, and every batch of ``validation_batches`` fits it: full-physics
    states of the model's size, at least one start, all finite, a positive number of steps."""
    scenario, _, params, settings = resolve_inputs(name, {}, preset)
    assert isinstance(scenario.build(params, settings), mujoco.MjModel), "build returned no MjModel"
    model, batches = scenario.validation_batches(params, settings)
    assert batches, "validation_batches returned no batch"
    size = mujoco.mj_stateSize(model, STATE_SPEC)
    for states, nstep in batches:
        assert states.ndim == 2 and states.shape[0] >= 1 and states.shape[1] == size, (
            f"a batch of shape {states.shape}, state size {size}")
        assert np.all(np.isfinite(states)) and nstep > 0, "a batch with non-finite states or no steps"
    return f"{sum(len(s) for s, _ in batches)} starts"


def reports_declared_checks(name: str, preset: str, result: Result) -> str:
    """``result``, the validation at ``preset``'s defaults, is of that scenario and preset, reports every declared
    check (none of kind ``missing``) and, where the scenario declares its checks, exactly those in their order, then
    ``stable``; its JSON round-trips."""
    scenario, _, params, settings = resolve_values(name, {}, preset)
    assert result.scenario == name and result.preset == preset, (result.scenario, result.preset)
    reported = [c.name for c in result.checks]
    missing = [c.name for c in result.checks if c.kind == "missing"]
    assert not missing, f"declared but not reported: {', '.join(missing)}"
    if scenario.checks:
        assert reported == [*scenario.checks_for(params, settings), "stable"], f"reported {reported}"
    payload = result.to_dict()
    assert [c["name"] for c in payload["checks"]] == reported, "the JSON's checks are not the run's"
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / "result.json")
        write_json(payload, path)
        assert json.loads(Path(path).read_text()) == payload, "the JSON does not round-trip"
    failed = [c.name for c in result.checks if not c.passed]
    return f"{len(reported)} checks, {result.timing['wall_s']:.1f} s" + (f"; failing: {', '.join(failed)}"
                                                                          if failed else "")


def still_renders(name: str, preset: str) -> str:
    """One frame of the scenario's video at ``preset`` renders, not blank."""
    from mjpoincare.commands.render import render_frames

    frames, _ = render_frames(name, {}, preset, 0.02, 50, (32, 24), last_only=True)
    assert frames.shape == (1, 24, 32, 3) and frames.std() > 0, "a blank frame"
    return ""


def stress_cases_answered(name: str) -> str:
    """Every stress case's values are accepted or refused in one line (a :class:`ParameterError`), never crash."""
    scenario = scenarios.REGISTRY[name]
    refused = 0
    for case in scenario.stress_cases:
        try:
            resolve_values(name, dict(case.assignments), None)
        except ParameterError:
            refused += 1
    return f"{len(scenario.stress_cases)} cases, {refused} refused in one line"


def gate_covers_every_preset(name: str) -> str:
    """The scenario's gate cases run every preset on its defaults."""
    scenario = scenarios.REGISTRY[name]
    missing = [p for p in scenario.presets
               if not any(c.scenario == name and c.preset == p and not c.values for c in scenario.gate_cases)]
    assert not missing, f"no gate case on the defaults at {', '.join(missing)}"
    return ""


def gate_case_names_every_check(case: GateCase, result: Result) -> str:
    """The case names each check of its run ``result`` once, in one form (gated, watched or a declared miss), and
    no check the run does not report."""
    forms = [*case.gated, *(w.check for w in case.watched), *(m.check for m in case.misses)]
    twice = sorted({c for c in forms if forms.count(c) > 1})
    assert not twice, f"checks in two forms: {', '.join(twice)}"
    loose = [c.name for c in result.checks if c.name not in forms]
    assert not loose, f"checks in no form (gated, watched or a declared miss): {', '.join(loose)}"
    stray = sorted(set(forms) - {c.name for c in result.checks})
    assert not stray, f"checks in a form that the run does not report: {', '.join(stray)}"
    return ""


def _defaults_run(name: str, preset: str, runs: dict[str, Result]) -> str:
    """:func:`reports_declared_checks` on the validation at ``preset``'s defaults, kept in ``runs`` for the gate's
    case on them."""
    runs[preset] = run_validation(name, {}, preset)
    return reports_declared_checks(name, preset, runs[preset])


def _gate_case(case: GateCase, runs: dict[str, Result]) -> str:
    """:func:`gate_case_names_every_check`, and the gated checks pass (the gate's assertion on them)."""
    result = runs[case.preset] if not case.values and case.preset in runs else run_validation(
        case.scenario, dict(case.values), case.preset)
    gate_case_names_every_check(case, result)
    failing = [c.name for c in result.checks if c.name in case.gated and not c.passed]
    assert not failing, f"gated checks failing: {', '.join(failing)}"
    worst = max((c.error / c.tolerance for c in result.checks if c.name in case.gated and c.tolerance > 0
                 and math.isfinite(c.error)), default=0.0)
    return f"largest gated error {worst:.2f} of its tolerance"


def check_plugin(name: str) -> int:
    """Run every clause on scenario ``name``; exit 0 when all hold, 1 otherwise (2: not a scenario, or its declaration
    is broken: the registry's one line)."""
    scenario = scenarios.get(name)
    clauses = _Clauses()
    runs: dict[str, Result] = {}
    for preset in scenario.presets:
        clauses.check(f"{name}[{preset}] defaults accepted", lambda p=preset: defaults_accepted(name, p))
        clauses.check(f"{name}[{preset}] tolerances with reasons", lambda p=preset: tolerances_with_reasons(name, p))
        clauses.check(f"{name}[{preset}] model compiles, validation batches fit it",
                      lambda p=preset: model_and_batches(name, p))
        clauses.check(f"{name}[{preset}] validation reports the declared checks",
                      lambda p=preset: _defaults_run(name, p, runs))
        clauses.check(f"{name}[{preset}] a still renders", lambda p=preset: still_renders(name, p))
    clauses.check(f"{name} stress cases accepted or refused", lambda: stress_cases_answered(name))
    clauses.check(f"{name} gate runs every preset on its defaults", lambda: gate_covers_every_preset(name))
    for case in scenario.gate_cases:
        clauses.check(f"gate case {case.label}", lambda c=case: _gate_case(c, runs))
    print(f"{name}: {clauses.failed} of the clauses failed" if clauses.failed else f"{name}: every clause holds")
    return 1 if clauses.failed else 0
