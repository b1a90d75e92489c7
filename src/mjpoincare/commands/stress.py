"""``mjpoincare stress``: push each scenario's settings and parameters to the edges and report what survives.

Every case is a full validation (fast preset, diagnostics on) with a few ``--set`` overrides:

* the **timestep ladder**: the preset's step times 1, 2, 4, ..., 32 with the contact time constant left at
  the preset's value (MuJoCo then clamps it to 2 steps) -- the largest step that still runs stable, and the
  largest that still passes the accuracy checks;
* every **integrator**, **solver** and **cone**, the Jacobian storage, noslip iterations, ``impratio``;
* **stiff** (time constant = 2 steps) and **soft** (10x) contact, and an under-damped one (damping ratio 1);
* the scenario's own **extreme parameters** (:attr:`Scenario.stress_cases`), including inputs the theory
  excludes, which must be refused with exit 2;
* a **soak** of 10^4 impacts from the fixed point (:attr:`Scenario.soak`): the drift of the section
  coordinate between the first and the last tenth, and its distance from the analytic fixed point.

A case's verdict: ``accurate`` (every check passed), ``inaccurate`` (ran stable, some check beyond
tolerance), ``left cycle`` (no return map: the gait was lost), ``energy blow-up`` (kinetic energy above
10x the largest initial one), ``diverged`` (NaN or MuJoCo's silent reset, reported per trajectory), ``warnings``
(MuJoCo warnings), ``refused`` (bad input, exit 2) or ``crashed`` (an exception: always a failure).
"""

from __future__ import annotations

import math
import sys
import time
import traceback
from collections.abc import Sequence
from typing import Any

import numpy as np

from mjpoincare import scenarios
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_inputs, run_validation
from mjpoincare.core import progress
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.parallel import run_jobs
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import write_json
from mjpoincare.scenarios.base import Scenario, StressCase

LADDER = (1, 2, 4, 8, 16, 32)
BLOWUP = 10.0  # kinetic energy above this multiple of the largest initial one = blow-up
SOAK_IMPACTS = 10_000
#: The longest soak ``--soak`` takes, impacts (100 x the default: minutes of MuJoCo at the fast presets).
MAX_SOAK = 1_000_000
STABLE = ("accurate", "inaccurate")


def generic_cases(scenario: Scenario) -> list[StressCase]:
    """The simulator-setting edges, relative to the scenario's fast preset."""
    _, preset = scenario.preset("fast")
    base = {**sim_settings.DEFAULTS, **preset}
    dt, tc = float(base["timestep"]), float(base["solref_timeconst"])
    cases = [StressCase(f"timestep x{k}", {"timestep": f"{k * dt:.6g}"},
                        f"step {k * dt:.3g} s (contact time constant {tc:.3g} s, clamped to >= 2 steps)")
             for k in LADDER]
    cases += [StressCase(f"integrator {name}", {"integrator": name}, "integrator choice")
              for name in sim_settings.INTEGRATORS if name != base["integrator"]]
    cases += [StressCase(f"solver {name}", {"solver": name}, "constraint solver choice")
              for name in sim_settings.SOLVERS if name != base["solver"]]
    cases += [StressCase("cone pyramidal", {"cone": "pyramidal"}, "pyramidal friction cone"),
              StressCase("jacobian dense", {"jacobian": "dense"}, "dense constraint Jacobian"),
              StressCase("jacobian sparse", {"jacobian": "sparse"}, "sparse constraint Jacobian"),
              StressCase("noslip 10", {"noslip_iterations": "10"}, "noslip post-processing"),
              StressCase("impratio 1", {"impratio": "1"}, "soft friction (impratio 1)"),
              StressCase("impratio 100", {"impratio": "100"}, "hard friction (impratio 100)"),
              StressCase("stiff contact", {"solref_timeconst": f"{2 * dt:.6g}"}, "time constant = 2 steps"),
              StressCase("soft contact", {"solref_timeconst": f"{10 * tc:.6g}"}, "time constant x10"),
              StressCase("damping ratio 1", {"solref_dampratio": "1"}, "critically damped contact"),
              StressCase("solver 10 iterations", {"iterations": "10", "tolerance": "1e-6"},
                         "a cheap solver budget")]
    return cases


def run_case(name: str, case: StressCase) -> dict[str, Any]:
    """Validate ``name`` under ``case`` (fast preset, diagnostics on) and classify what happened."""
    row: dict[str, Any] = {"case": case.name, "assignments": dict(case.assignments), "why": case.why,
                           "expect": case.expect}
    start = time.perf_counter()
    try:
        result = run_validation(name, {**case.assignments, "diagnostics": "1"}, "fast")
    except ParameterError as err:
        return {**row, "verdict": "refused", "message": str(err), "wall_s": time.perf_counter() - start}
    except Exception as err:  # a crash is a finding: reported in the table, never raised past it
        return {**row, "verdict": "crashed", "message": f"{type(err).__name__}: {err}",
                "traceback": traceback.format_exc(limit=4), "wall_s": time.perf_counter() - start}
    scenario = scenarios.get(name)
    by_name = {c.name: c for c in result.checks}
    first = by_name.get(scenario.bench_checks[0])
    diag = result.diagnostics or {}
    lost = [n for n in scenario.bench_checks if n in by_name and not np.all(np.isfinite(by_name[n].simulated))]
    if result.diverged:
        verdict = "diverged"
    elif result.warnings:
        verdict = "warnings"
    elif lost:
        verdict = "left cycle"
    elif diag.get("max_kinetic_energy_J", 0.0) > BLOWUP * diag.get("initial_kinetic_energy_J", math.inf):
        verdict = "energy blow-up"
    else:
        verdict = "accurate" if result.passed else "inaccurate"
    failed = [c.name for c in result.checks if not c.passed]
    return {**row, "verdict": verdict, "failed_checks": failed,
            "error": first.error if first else math.nan, "tolerance": first.tolerance if first else math.nan,
            "check": first.name if first else "", "diverged": len(result.diverged), "warnings": result.warnings,
            "max_penetration_m": diag.get("max_penetration_m", math.nan),
            "max_kinetic_energy_J": diag.get("max_kinetic_energy_J", math.nan),
            "wall_s": time.perf_counter() - start}


def largest_timesteps(rows: list[dict[str, Any]], base_dt: float) -> tuple[float, float]:
    """The largest ladder step up to which every step ran stable, and up to which every step passed."""
    stable = accurate = math.nan
    stable_run = accurate_run = True
    for k in LADDER:
        r = next((r for r in rows if r["case"] == f"timestep x{k}"), None)
        if r is None:
            break
        stable_run = stable_run and r["verdict"] in STABLE
        accurate_run = accurate_run and r["verdict"] == "accurate"
        stable = k * base_dt if stable_run else stable
        accurate = k * base_dt if accurate_run else accurate
    return stable, accurate


def soak_summary(name: str, impacts: int) -> dict[str, Any]:
    """``impacts`` impacts from the fixed point (fast preset): drift and distance from the analytic value; a soak not
    run is ``{"skipped": why}`` (the scenario defines none, or ``impacts`` is 0)."""
    scenario = scenarios.get(name)
    if scenario.soak is None:
        return {"skipped": f"{name} defines no soak (no limit cycle of impacts to repeat: Scenario.soak is None)"}
    if impacts <= 0:
        return {"skipped": "--soak 0 asked for none"}
    _, _, params, settings = resolve_inputs(name, {}, "fast")
    start = time.perf_counter()
    soak = scenario.soak(params, settings, impacts)
    wall = time.perf_counter() - start
    x = np.asarray(soak.samples, float)
    finite = x[np.isfinite(x)]
    tenth = max(1, len(finite) // 10)
    first, last = finite[10 : 10 + tenth], finite[-tenth:]
    drift = float(last.mean() - first.mean()) if len(first) and len(last) else math.nan
    error = abs(float(last.mean()) - soak.analytic) / abs(soak.analytic) if len(last) else math.nan
    return {"impacts_requested": impacts, "impacts_seen": len(finite), "label": soak.label,
            "analytic": soak.analytic, "first_tenth_mean": float(first.mean()) if len(first) else math.nan,
            "last_tenth_mean": float(last.mean()) if len(last) else math.nan, "drift": drift,
            "relative_error_last_tenth": error, "diverged": int(soak.rollout.diverged.sum()),
            "warnings": soak.rollout.warnings, "steps": soak.rollout.steps, "wall_s": wall}


def _ok(row: dict[str, Any]) -> bool:
    if row["expect"] == "refused":
        return row["verdict"] == "refused"
    return row["verdict"] not in ("crashed", "refused")


def stress_scenario(name: str, *, soak: int = SOAK_IMPACTS, workers: int = 1) -> dict[str, Any]:
    """All of a scenario's stress cases (run ``workers`` at a time) and its soak."""
    scenario = scenarios.get(name)
    cases = generic_cases(scenario) + list(scenario.stress_cases)
    rows = []
    with progress.bar(len(cases), f"stress {name}", unit="case") as bar:
        for row in run_jobs(run_case, [(name, c) for c in cases], workers=workers):
            rows.append(row)
            bar.set_postfix_str(str(row["case"]))
            bar.update(1)
    order = {c.name: i for i, c in enumerate(cases)}
    rows.sort(key=lambda r: order[r["case"]])
    _, preset = scenario.preset("fast")
    base_dt = float({**sim_settings.DEFAULTS, **preset}["timestep"])
    stable, accurate = largest_timesteps(rows, base_dt)
    return {"scenario": name, "preset": "fast", "cases": rows, "largest_stable_timestep": stable,
            "largest_accurate_timestep": accurate, "soak": soak_summary(name, soak),
            "ok": all(_ok(r) for r in rows)}


def table(report: dict[str, Any]) -> str:
    """The stress table a person reads."""
    stable, accurate = report["largest_stable_timestep"], report["largest_accurate_timestep"]
    ladder = [float(r["assignments"]["timestep"]) for r in report["cases"] if r["case"].startswith("timestep x")]
    at_top = bool(ladder) and stable == max(ladder)
    lines = [f"{report['scenario']} (fast preset): largest stable timestep "
             f"{'>= ' if at_top else ''}{stable:.3g} s, largest accurate {accurate:.3g} s"]
    rows = []
    for r in report["cases"]:
        err = (f"{r['error']:.2e} / {r['tolerance']:.0e}" if r.get("check") and np.isfinite(r.get("error", math.nan))
               else "—")
        note = "" if _ok(r) else " (UNEXPECTED)"
        if r["verdict"] in ("refused", "crashed"):
            err = r["message"][:70]
        failed = ", ".join(c for c in r.get("failed_checks", []) if c != "stable") or "—"
        rows.append((r["case"], f"{r['verdict']}{note}", err, failed,
                     f"{1e3 * r.get('max_penetration_m', math.nan):.3g}",
                     f"{r.get('max_kinetic_energy_J', math.nan):.3g}", f"{r['wall_s']:.1f}"))
    lines.append(markdown_table(("case", "verdict", "first check error / tol", "failed checks", "max penetration (mm)",
                                 "max KE (J)", "wall (s)"), rows))
    s = report["soak"]
    if "skipped" in s:
        lines.append(f"soak: skipped, {s['skipped']}")
    else:
        lines.append(f"soak: {s['impacts_seen']} impacts ({s['label']}), analytic {s['analytic']:.6g}, first tenth "
                     f"{s['first_tenth_mean']:.6g}, last tenth {s['last_tenth_mean']:.6g}: drift {s['drift']:.2e}, "
                     f"relative error {s['relative_error_last_tenth']:.2e}; {s['diverged']} diverged, "
                     f"{len(s['warnings'])} warnings; {s['steps']:.3g} steps in {s['wall_s']:.1f} s")
    return "\n".join(lines)


#: Impacts of the pilot soak that estimates a longer soak's cost.
PILOT_IMPACTS = 20


def soak_steps(name: str, impacts: int) -> float:
    """The MuJoCo steps a soak of ``impacts`` impacts of scenario ``name`` would take (fast preset): a pilot soak of
    :data:`PILOT_IMPACTS` impacts, scaled; 0 when the scenario defines no soak."""
    scenario = scenarios.get(name)
    if scenario.soak is None or impacts <= 0:
        return 0.0
    _, _, params, settings = resolve_inputs(name, {}, "fast")
    pilot = scenario.soak(params, settings, PILOT_IMPACTS)
    seen = int(np.isfinite(np.asarray(pilot.samples, float)).sum()) or 1
    return float(pilot.rollout.steps) / seen * impacts


def run_stress(names: Sequence[str], json_path: str | None, *, soak: int, workers: int,
               allow_long: bool = False) -> int:
    """Stress each scenario; print the tables; exit 0 unless a case crashed or an expectation failed. A soak longer
    than the default is first costed by a pilot soak (:func:`soak_steps`) and refused past
    :data:`mjpoincare.core.cost.LONG_STEPS` steps unless ``allow_long``."""
    names = list(names) or list(scenarios.default_scenarios())
    if not 0 <= soak <= MAX_SOAK:
        raise ParameterError(f"--soak must be in [0, {MAX_SOAK}] impacts (got {soak})")
    for name in names:
        scenarios.get(name)
    if soak > SOAK_IMPACTS:
        for name in names:
            steps = soak_steps(name, soak)
            refuse_long(steps, f"stress {name} --soak {soak} (a {PILOT_IMPACTS}-impact pilot, scaled)",
                        allow=allow_long, remedy="give a smaller --soak, or --allow-long")
            if steps:
                print(f"stress {name}: the soak of {soak} impacts will take about {steps:.2g} MuJoCo steps "
                      f"(about {steps / 3e5 / 60:.2g} min at 3e5 steps/s)", file=sys.stderr, flush=True)
    reports = [stress_scenario(name, soak=soak, workers=workers) for name in names]
    if json_path != "-":
        print("\n\n".join(table(r) for r in reports))
    if json_path:
        write_json(jsonable(reports[0] if len(reports) == 1 else reports), json_path)
    return 0 if all(r["ok"] for r in reports) else 1
