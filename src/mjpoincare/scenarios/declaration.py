"""A scenario's declaration checked when the registry loads it, before anything runs: each mistake a system author
can make in the :class:`~mjpoincare.scenarios.base.Scenario` record, as one line naming the field and the fix
(:class:`~mjpoincare.scenarios.base.DeclarationError`).

What is checked here is what the record itself shows: the fields it was built with, its presets' setting names, its
seam mechanisms, its parameters' bounds, its name against its entry point, its tolerances (each
:class:`~mjpoincare.scenarios.base.Tolerances` refuses a bound that is not finite and positive when it is built; the
tables, against the presets and the declared checks: :func:`check_tolerances`).
What ``evaluate`` returns is checked on its first return (:func:`check_evaluation`).
"""

from __future__ import annotations

import dataclasses
import re

from mjpoincare.analysis.checks import Check
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.params import did_you_mean
from mjpoincare.scenarios.base import RENAMED_FIELDS, DeclarationError, Evaluation, Scenario, Tolerances
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
    check_tolerances(scenario)


def declared_checks(scenario: Scenario) -> tuple[str, ...]:
    """The checks a run may report: ``checks``, or where the scenario declares none its ``bench_checks``."""
    return scenario.checks or scenario.bench_checks


def _bounds_a_check(key: str, declared: tuple[str, ...]) -> bool:
    """Whether tolerance key ``key`` names a declared check or begins a word of one's name: a quantity the checks
    named after it share (slotted-skate's ``sigma4``: ``sigma4_forward``, ``sigma4_fit_backward``, ...; the 3-D
    wheel's ``eigenvalue``: ``heading_eigenvalue`` and the multipliers without their own bound)."""
    return any(re.search(rf"(?:^|_){re.escape(key)}", name) for name in declared)


def check_tolerances(scenario: Scenario) -> None:
    """Refuse a tolerance table whose presets are not the scenario's, a bound that names no declared check (nor
    begins a word of one's name: :func:`_bounds_a_check`), or a check bounded at one preset and not at another.

    A declared check that no preset bounds is not refused here: a category or a count is judged without a bound,
    and which checks those are shows only when ``evaluate`` runs (asking a :class:`Tolerances` for a bound it does not
    have is then a :class:`DeclarationError`)."""
    declared = declared_checks(scenario)
    presets = list(scenario.presets)
    if not set(scenario.tolerances) & set(presets):
        stray = [key for key, table in scenario.tolerances.items() if isinstance(table, Tolerances)]
        if stray:
            raise DeclarationError(f"tolerances names {stray[0]!r}, which is not a preset"
                                   f"{did_you_mean(stray[0], presets)} (presets: {', '.join(presets)})")
    for mode, table in scenario.tolerance_modes.items():
        where = f"tolerances[{mode!r}]" if mode else "tolerances"
        for preset in table:
            if preset not in presets:
                raise DeclarationError(f"{where} names {preset!r}, which is not a preset"
                                       f"{did_you_mean(preset, presets)} (presets: {', '.join(presets)})")
        for preset in presets:
            if preset not in table:
                raise DeclarationError(f"{where} has no Tolerances for preset {preset!r}: a run at every preset is "
                                       "judged against its own")
        for preset, tolerances in table.items():
            if not isinstance(tolerances, Tolerances):
                raise DeclarationError(f"{where}[{preset!r}] is a {type(tolerances).__name__}, not a Tolerances "
                                       "(its bounds, and why)")
            for key in tolerances.bounds:
                if not _bounds_a_check(key, declared):
                    raise DeclarationError(f"{where}[{preset!r}] bounds {key!r}, which names no declared check"
                                           f"{did_you_mean(key, declared)} (declared: {', '.join(declared)})")
        for key in dict.fromkeys(key for tolerances in table.values() for key in tolerances.bounds):
            bounded = [preset for preset, tolerances in table.items() if key in tolerances.bounds]
            unbounded = [preset for preset in table if preset not in bounded]
            if unbounded:
                raise DeclarationError(f"{where}[{unbounded[0]!r}] has no bound for {key!r}, which "
                                       f"{where}[{bounded[0]!r}] bounds: give it a bound at every preset")


def check_evaluation(scenario: Scenario, evaluation: object) -> None:
    """Refuse what ``evaluate`` returned when it is not an :class:`Evaluation`, reports no check, or reports one the
    scenario does not declare (its ``checks``, or where it declares none its ``bench_checks``)."""
    if not isinstance(evaluation, Evaluation):
        raise DeclarationError(f"evaluate returned {type(evaluation).__name__}, not an Evaluation")
    names = [c.name for c in evaluation.checks if isinstance(c, Check)]
    if not names:
        raise DeclarationError("evaluate reported no check: a run must be judged on something (report the checks "
                               "checks= declares)")
    declared = declared_checks(scenario)
    field = "checks=" if scenario.checks else "bench_checks= (checks= is empty)"
    for name in names:
        if name not in declared:
            raise DeclarationError(f"evaluate reported check {name!r}, which {field} does not declare"
                                   f"{did_you_mean(name, declared)} (declared: {', '.join(declared)})")
