"""``mjpoincare check-plugin NAME``: the scenario contract and the gate's forms, run against an installed scenario (a
plugin's, or a built-in one), in about the time of its validations at each preset.

The clauses are the ones the suite holds its own scenarios to (tests/test_scenario_contract.py, tests/test_gate.py):
the declaration loads; at every preset the defaults are accepted, the tolerances exist with their reasons, the model
compiles, the validation batches fit it, a validation reports exactly the declared checks and its JSON round-trips, and
a still renders; every stress case is accepted or refused in one line; every gate case's run has each check gated,
watched or a declared miss, and its gated checks pass. One line per clause; exit 0 when every clause holds, else 1.
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


def _tolerances(name: str, preset: str) -> str:
    scenario = scenarios.REGISTRY[name]
    for table in scenario.tolerance_tables:
        tolerances = at_preset(table, name, preset)
        assert isinstance(tolerances, Tolerances) and tolerances.bounds, "no bounds"
        assert tolerances.why or tolerances.reasons, "no reason given for the tolerances"
    return ""


def _probe(name: str, preset: str) -> str:
    scenario, _, params, settings = resolve_inputs(name, {}, preset)
    assert isinstance(scenario.build(params, settings), mujoco.MjModel), "build returned no MjModel"
    model, batches = scenario.validation_batches(params, settings)
    assert batches, "validation_batches returned no batch"
    size = mujoco.mj_stateSize(model, STATE_SPEC)
    for states, nstep in batches:
        assert states.ndim == 2 and states.shape[1] == size, f"a batch of shape {states.shape}, state size {size}"
        assert np.all(np.isfinite(states)) and nstep > 0, "a batch with non-finite states or no steps"
    return f"{sum(len(s) for s, _ in batches)} starts"


def _validation(name: str, preset: str, runs: dict[str, Result]) -> str:
    scenario, _, params, settings = resolve_values(name, {}, preset)
    result = runs[preset] = run_validation(name, {}, preset)
    reported = [c.name for c in result.checks]
    missing = [c.name for c in result.checks if c.kind == "missing"]
    assert not missing, f"declared but not reported: {', '.join(missing)}"
    if scenario.checks:
        assert reported == [*scenario.checks_for(params, settings), "stable"], f"reported {reported}"
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / "result.json")
        write_json(result.to_dict(), path)
        assert json.loads(Path(path).read_text()) == result.to_dict(), "the JSON does not round-trip"
    failed = [c.name for c in result.checks if not c.passed]
    return f"{len(reported)} checks, {result.timing['wall_s']:.1f} s" + (f"; failing: {', '.join(failed)}"
                                                                          if failed else "")


def _still(name: str, preset: str) -> str:
    from mjpoincare.commands.render import render_frames

    frames, _ = render_frames(name, {}, preset, 0.02, 50, (32, 24), last_only=True)
    assert frames.shape == (1, 24, 32, 3) and frames.std() > 0, "a blank frame"
    return ""


def _stress(name: str) -> str:
    scenario = scenarios.REGISTRY[name]
    refused = 0
    for case in scenario.stress_cases:
        try:
            resolve_values(name, dict(case.values), None)
        except ParameterError:
            refused += 1
    return f"{len(scenario.stress_cases)} cases, {refused} refused in one line"


def _gate_presets(name: str) -> str:
    scenario = scenarios.REGISTRY[name]
    missing = sorted(set(scenario.presets) - {c.preset for c in scenario.gate_cases if not c.values})
    assert not missing, f"no gate case on the defaults at {', '.join(missing)}"
    return ""


def _gate_case(case: GateCase, runs: dict[str, Result]) -> str:
    result = runs[case.preset] if not case.values and case.preset in runs else run_validation(
        case.scenario, dict(case.values), case.preset)
    forms = {*case.gated, *(w.check for w in case.watched), *(m.check for m in case.misses)}
    loose = [c.name for c in result.checks if c.name not in forms]
    assert not loose, f"checks in no form (gated, watched or a declared miss): {', '.join(loose)}"
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
        clauses.check(f"{name}[{preset}] defaults accepted", lambda p=preset: (resolve_inputs(name, {}, p), "")[1])
        clauses.check(f"{name}[{preset}] tolerances with reasons", lambda p=preset: _tolerances(name, p))
        clauses.check(f"{name}[{preset}] model compiles, validation batches fit it", lambda p=preset: _probe(name, p))
        clauses.check(f"{name}[{preset}] validation reports the declared checks",
                      lambda p=preset: _validation(name, p, runs))
        clauses.check(f"{name}[{preset}] a still renders", lambda p=preset: _still(name, p))
    clauses.check(f"{name} stress cases accepted or refused", lambda: _stress(name))
    clauses.check(f"{name} gate runs every preset on its defaults", lambda: _gate_presets(name))
    for case in scenario.gate_cases:
        clauses.check(f"gate case {case.label}", lambda c=case: _gate_case(c, runs))
    print(f"{name}: {clauses.failed} of the clauses failed" if clauses.failed else f"{name}: every clause holds")
    return 1 if clauses.failed else 0
