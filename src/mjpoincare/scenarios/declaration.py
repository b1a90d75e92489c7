"""A scenario's declaration checked when the registry loads it, before anything runs: each mistake a system author
can make in the :class:`~mjpoincare.scenarios.base.Scenario` record, as one line naming the field and the fix
(:class:`~mjpoincare.scenarios.base.DeclarationError`).

What is checked here is what the record itself shows: the fields it was built with, its presets' setting names, its
seam mechanisms, its parameters' bounds, its name against its entry point, its tolerances (each
:class:`~mjpoincare.scenarios.base.Tolerances` refuses a bound that is not finite and positive when it is built).
What ``evaluate`` returns is checked on its first return (:func:`check_evaluation`).
"""

from __future__ import annotations

import dataclasses
import re

from mjpoincare.analysis.checks import Check
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.params import did_you_mean
from mjpoincare.scenarios.base import RENAMED_FIELDS, DeclarationError, Evaluation, Scenario
from mjpoincare.simulation.seam_check import MECHANISMS


def load_error(error: BaseException) -> str:
    """What went wrong while a scenario's module was imported or its record built, in one line: an unknown field of
    a record gets the closest field's name (the new name where the closest is a renamed field's old one, which is
    still accepted: :data:`~mjpoincare.scenarios.base.RENAMED_FIELDS`)."""
    text = str(error).splitlines()[0] if str(error) else type(error).__name__
    unknown = re.search(r"(\w+)\.__init__\(\) got an unexpected keyword argument '(\w+)'", text)
    if unknown and unknown.group(1) == "Scenario":
        fields = [f.name for f in dataclasses.fields(Scenario)]
        return f"Scenario has no field {unknown.group(2)!r}{did_you_mean(unknown.group(2), fields, RENAMED_FIELDS)}"
    return text if isinstance(error, DeclarationError) else f"{type(error).__name__}: {text}"


def check_declaration(scenario: Scenario, entry_name: str) -> None:
    """Refuse, in one line naming the field and the fix, a declaration the commands would trip over later."""
    if scenario.name != entry_name:
        raise DeclarationError(f"name={scenario.name!r} differs from its entry point {entry_name!r}: make them the "
                               "same")
    settings = [p.name for p in sim_settings.SETTINGS]
    for preset, values in scenario.presets.items():
        for key in values:
            if key not in settings:
                raise DeclarationError(f"presets[{preset!r}] sets {key!r}, which is not a simulator setting"
                                       f"{did_you_mean(key, settings)} (mjpoincare list shows them)")
    for key in scenario.seam_mechanisms:
        if key not in MECHANISMS:
            raise DeclarationError(f"seam_mechanisms= names {key!r}, not a seam mechanism"
                                   f"{did_you_mean(key, MECHANISMS)} (known: {', '.join(MECHANISMS)})")
    for param in scenario.params:
        if param.choices is None and param.kind in (int, float) and (param.low is None or param.high is None):
            raise DeclarationError(f"Param {param.name!r} has no bounds: give low= and high= (the values the "
                                   "theory holds for), so that a value outside is refused before any simulation")
    if scenario.default_preset not in scenario.presets:
        raise DeclarationError(f"default_preset={scenario.default_preset!r} is not one of presets= "
                               f"({', '.join(scenario.presets)})")


def check_evaluation(scenario: Scenario, evaluation: object) -> None:
    """Refuse what ``evaluate`` returned when it is not an :class:`Evaluation`, reports no check, or reports one the
    scenario does not declare (its ``checks``, or where it declares none its ``bench_checks``)."""
    if not isinstance(evaluation, Evaluation):
        raise DeclarationError(f"evaluate returned {type(evaluation).__name__}, not an Evaluation")
    names = [c.name for c in evaluation.checks if isinstance(c, Check)]
    if not names:
        raise DeclarationError("evaluate reported no check: a run must be judged on something (report the checks "
                               "checks= declares)")
    declared = scenario.checks or scenario.bench_checks
    field = "checks=" if scenario.checks else "bench_checks= (checks= is empty)"
    for name in names:
        if name not in declared:
            raise DeclarationError(f"evaluate reported check {name!r}, which {field} does not declare"
                                   f"{did_you_mean(name, declared)} (declared: {', '.join(declared)})")
