"""A regression baseline: each check's error and simulated value from a recorded run, with its resolution, so that a
change far below the check's tolerance but beyond jitter fails.

A tolerance says how far MuJoCo may be from the analytic value; a baseline says how far this run may be from the
last one. Each check of a recorded run holds its error, its simulated value (for the reader of the file's diff) and
its **resolution**: the largest change of the error that jitter gives, that is, the spread of the error

- for the gate's own baseline (``docs/results/gate/baseline.json``, ``make baseline``): over the ensemble of
  environments ``mjpoincare margins`` measured (every OpenBLAS kernel the CPU runs, numpy at its baseline, the
  oldest numpy/scipy allowed) and the rounding perturbations (:data:`ROUNDING`);
- for a user's baseline (``validate --update-baseline``, the plugin's ``--mjpoincare-update-baseline``): over the
  rounding perturbations (:data:`ROUNDING`), run beside the recorded run;

A later run's check fails when its error moves from the recorded one by more than its allowance
(:func:`mjpoincare.core.allowance.allowance`: :data:`~mjpoincare.core.allowance.MULTIPLE` resolutions, never below
:data:`~mjpoincare.core.allowance.FLOOR` of the check's tolerance), or when it is missing or new.

Runs are keyed by scenario, preset and the parameters that differ from the scenario's defaults
(``rimless-wheel[accurate,spokes=10,slope=0.1]``, the gate cases' labels), never by the simulator settings: a
baseline recorded at a preset's settings is what a run at changed settings is compared with. The conventions follow
pytest-regressions and syrupy (a file per suite, an update flag that records and passes, a missing file a usage
error).
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mjpoincare.analysis.checks import jsonable
from mjpoincare.core.allowance import FLOOR, MULTIPLE, allowance
from mjpoincare.core.params import ParameterError, Value
from mjpoincare.core.result import Result

#: Format of the baseline file (its ``schema`` field).
SCHEMA = "mjpoincare-baseline/1"
#: The gate's perturbations that change a run's rounding only (:data:`mjpoincare.gate.forms.PERTURBATIONS`): threads and
#: starts x(1 + 1e-12) and x(1 + 1e-9). A baseline compares runs at one seed, so another seed's experiment design (a
#: different set of starts, not jitter) is not part of its resolution.
ROUNDING = ("threads 1", "starts x(1+1e-12)", "starts x(1+1e-9)")


@dataclass(frozen=True)
class Deviation:
    """A check whose error moved beyond its allowance from its recorded value, or that one of the two runs lacks.

    Attributes:
        run: the run's key (:func:`run_key`).
        check: the check's name.
        old: the recorded error (NaN: the baseline lacks the check).
        new: this run's error (NaN: this run lacks the check).
        resolution: the recorded resolution (NaN where the baseline lacks the check).
        allowed: the change the check is allowed (:func:`mjpoincare.core.allowance.allowance` of the resolution and the
            recorded tolerance; NaN where the baseline lacks the check).
        note: what else differs from the recorded run (its settings), or why there is nothing to compare.
    """

    run: str
    check: str
    old: float
    new: float
    resolution: float
    allowed: float = math.nan
    note: str = ""

    def message(self) -> str:
        """One line naming the check, the old and the new error and the resolution."""
        head = f"{self.run}::{self.check}: "
        if self.note and not (math.isfinite(self.old) and math.isfinite(self.new)) and math.isnan(self.resolution):
            return head + self.note
        change = abs(self.new - self.old)
        return (head + f"error {self.old:.6g} -> {self.new:.6g}: changed {change:.3g}, {change / self.allowed:.3g} x "
                f"its allowance {self.allowed:.3g} (the larger of {MULTIPLE:g} x its resolution {self.resolution:.3g} "
                f"and {FLOOR:g} x its tolerance)" + (f"; {self.note}" if self.note else ""))


def run_key(result: Result) -> str:
    """The key of ``result``'s run (:func:`key_of` its scenario, preset and parameters)."""
    return key_of(result.scenario, result.preset, result.params)


def key_of(scenario: str, preset: str, params: Mapping[str, Value]) -> str:
    """``scenario[preset,name=value,...]``: the parameters that differ from the scenario's defaults, in its order."""
    from mjpoincare import scenarios

    declared = scenarios.get(scenario).params
    changed = [f"{p.name}={params[p.name]}" for p in declared if p.name in params and params[p.name] != p.default]
    return f"{scenario}[{','.join([preset, *changed])}]"


def entry(result: Result, resolutions: Mapping[str, float]) -> dict[str, Any]:
    """The baseline record of ``result``: seed, settings, MuJoCo version, and per check its error, simulated value,
    tolerance, kind and resolution (the measured spread; ``None`` where jitter made the error non-finite)."""
    checks = {}
    for c in result.checks:
        resolution = resolutions.get(c.name, 0.0)
        checks[c.name] = {"error": c.error, "simulated": c.simulated, "tolerance": c.tolerance, "kind": c.kind,
                          "resolution": resolution if math.isfinite(resolution) else None}
    return jsonable({"seed": result.seed, "settings": result.settings, "mujoco_version": result.mujoco_version,
                     "checks": checks})


def perturbation_spreads(result: Result, assignments: Mapping[str, Value]) -> dict[str, float]:
    """The largest change of each check's error over the rounding perturbations (:data:`ROUNDING`) of ``result``'s
    run (re-run with ``assignments``, the ``--set`` values it was run with): check name -> spread."""
    from mjpoincare.commands.validation import run_validation
    from mjpoincare.gate.forms import PERTURBATIONS

    varied = [run_validation(result.scenario, {**assignments, **extra}, result.preset, result.seed + seed)
              for label, seed, extra in PERTURBATIONS if label in ROUNDING]
    return spreads(result, [{c.name: c.error for c in run.checks} for run in varied])


def spreads(result: Result, others: Iterable[Mapping[str, float]]) -> dict[str, float]:
    """The largest change of each check's error from ``result``'s over ``others`` (check name -> error, one mapping
    per environment or perturbation): inf where one error is finite and the other is not, or one is missing."""
    out = dict.fromkeys((c.name for c in result.checks), 0.0)
    for errors in others:
        for check in result.checks:
            other = errors.get(check.name, math.nan)
            if math.isfinite(check.error) and math.isfinite(other):
                change = abs(other - check.error)
            else:
                change = 0.0 if math.isnan(check.error) and math.isnan(other) else math.inf
            out[check.name] = max(out[check.name], change)
    return out


def load(path: str, option: str = "--baseline") -> dict[str, Any]:
    """The baseline file at ``path``; a usage error (:class:`ParameterError`) naming ``option`` and ``path`` when it
    does not exist or is not a baseline."""
    try:
        payload = json.loads(Path(path).read_text())
    except FileNotFoundError:
        raise ParameterError(f"{option} {path} does not exist (record it first with the update flag)") from None
    except (OSError, ValueError) as err:
        raise ParameterError(f"{option} {path} cannot be read ({err})") from None
    if not isinstance(payload, dict) or payload.get("schema") != SCHEMA or not isinstance(payload.get("runs"), dict):
        raise ParameterError(f"{option} {path} is not an mjpoincare baseline (schema {SCHEMA})")
    return payload


def check_path(path: str, update: bool, option: str = "--baseline") -> None:
    """Before any simulation: a baseline to compare with must exist and be one; one to update must be writable (and,
    where it exists, be a baseline: its other runs are kept)."""
    from mjpoincare.core.result import check_output_path

    if update:
        check_output_path(path, option)
    if not update or Path(path).exists():
        load(path, option)


def deviations(result: Result, baseline: Mapping[str, Any], key: str | None = None, *,
               record_flag: str = "--update-baseline") -> list[Deviation]:
    """Every check of ``result`` that moved beyond its allowance (:func:`mjpoincare.core.allowance.allowance` of its
    recorded resolution and tolerance) from ``baseline``'s record of the
    same run (``key``: of the run recorded under that key instead, e.g. the unchanged run of a planted change of
    a parameter), or that one of the two lacks; the run missing from the baseline is one deviation, whose note names
    ``record_flag``, the flag that records it where the comparison runs (the CLI's, or the pytest plugin's)."""
    key = key or run_key(result)
    recorded = baseline["runs"].get(key)
    if recorded is None:
        return [Deviation(run=key, check="*", old=math.nan, new=math.nan, resolution=math.nan,
                          note=f"the baseline has no run {key} (record it with {record_flag})")]
    changed = sorted(k for k, v in result.settings.items() if recorded["settings"].get(k) != v)
    note = ("settings differ from the recorded run: "
            + ", ".join(f"{k} {recorded['settings'].get(k)} -> {result.settings[k]}" for k in changed)
            if changed else "")
    out = []
    checks = {c.name: c for c in result.checks}
    for name in [*recorded["checks"], *(n for n in checks if n not in recorded["checks"])]:
        old_entry, check = recorded["checks"].get(name), checks.get(name)
        if old_entry is None or check is None:
            what = "is new: the baseline lacks it" if old_entry is None else "is missing from this run"
            out.append(Deviation(run=key, check=name, old=math.nan, new=math.nan, resolution=math.nan,
                                 note=f"the check {what}"))
            continue
        old = math.nan if old_entry["error"] is None else float(old_entry["error"])
        resolution = math.inf if old_entry["resolution"] is None else float(old_entry["resolution"])
        tolerance = old_entry.get("tolerance")
        allowed = allowance(resolution, math.nan if tolerance is None else float(tolerance), old)
        new = check.error
        if math.isfinite(old) and math.isfinite(new):
            moved = abs(new - old) > allowed
        else:
            moved = not (math.isnan(old) and math.isnan(new))
        if moved:
            out.append(Deviation(run=key, check=name, old=old, new=new, resolution=resolution, allowed=allowed,
                                 note=note))
    return out


def updated(baseline: Mapping[str, Any] | None, records: Iterable[tuple[str, dict[str, Any]]],
            stamp: Mapping[str, Any]) -> dict[str, Any]:
    """``baseline`` (None: a new one) with ``records`` ((run key, :func:`entry`)) put in, stamped with ``stamp``
    (:func:`mjpoincare.core.stamp.environment`); runs sorted by key so that its diff is what changed. A re-record
    that changes no run keeps the old stamp: the file stays byte for byte, and a reviewer's diff shows only real
    changes."""
    runs = dict(baseline["runs"]) if baseline else {}
    runs.update(records)
    runs = dict(sorted(runs.items()))
    if baseline and runs == baseline["runs"] and "stamp" in baseline:
        stamp = baseline["stamp"]
    return {"schema": SCHEMA, "multiple": MULTIPLE, "floor": FLOOR, "stamp": dict(stamp), "runs": runs}
