"""``mjpoincare reproduce``: every result of the papers a scenario covers, run in MuJoCo.

Each scenario declares its papers' results (:mod:`mjpoincare.scenarios.paper_results`); this command runs them as jobs
on the local or Dask engine (:func:`mjpoincare.core.parallel.run_jobs`), keeps every finished job's rows in the
resumable results file, and prints one row per result: the paper's value, the suite's analytic value, MuJoCo's, the
error, the tolerance and the verdict (``pass``, ``miss`` with a declared mechanism, ``FAIL``, ``refused`` with a
physical reason). Results read off one validation at the same parameters share its run; a figure's points run one job
each; a bracket's bisection is one job.
"""

from __future__ import annotations

import functools
import math
import sys
import time
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import mujoco

from mjpoincare import scenarios
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_values, run_validation
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.parallel import ResumableRows, check_engine
from mjpoincare.core.params import ParameterError, Values, resolve, unknown
from mjpoincare.core.result import Result, write_json
from mjpoincare.core.stamp import environment
from mjpoincare.core.version import VERSION
from mjpoincare.scenarios.base import at_preset
from mjpoincare.scenarios.paper_results import (
    PAPERS,
    AtValidation,
    Bracket,
    Curve,
    Experiment,
    PaperResult,
    Reading,
    Refusal,
    bisect,
    unique_ids,
    verdict,
)

SCHEMA = "mjpoincare.reproduce/1"


@functools.lru_cache(maxsize=16)
def _validation(scenario: str, assignments: tuple[tuple[str, str], ...], preset: str) -> Result:
    return run_validation(scenario, dict(assignments), preset)


class ScenarioRunner:
    """The :class:`~mjpoincare.scenarios.paper_results.Runner` of one scenario at one preset."""

    def __init__(self, scenario: str, preset: str) -> None:
        self.scenario = scenario
        self.preset = preset

    def validate(self, assignments: Mapping[str, str]) -> Result:
        """The scenario's validation at ``assignments`` (:func:`run_validation`), run once per process for the same
        inputs: a figure's curves of several quantities at one value (a gait's multiplier, speed and cost) share it."""
        return _validation(self.scenario, tuple(sorted(assignments.items())), self.preset)

    def inputs(self, assignments: Mapping[str, str], *, checked: bool = True) -> tuple[Values, Values]:
        """Resolved parameters and settings (:func:`resolve_values`; unchecked: the declared bounds only)."""
        if checked:
            _, _, params, settings = resolve_values(self.scenario, assignments, self.preset)
            return params, settings
        scenario = scenarios.get(self.scenario)
        unknown(assignments, scenario.params, sim_settings.SETTINGS)
        _, overrides = scenario.preset(self.preset)
        params = resolve(scenario.params, {p.name: p.default for p in scenario.params}, assignments)
        settings = resolve(sim_settings.SETTINGS, {**sim_settings.DEFAULTS, **overrides}, assignments)
        return params, settings

    def build(self, params: Values, settings: Values) -> mujoco.MjModel:
        """The scenario's ``build``."""
        return scenarios.get(self.scenario).build(params, settings)

    def tolerance(self, check: str, mode: str | None = None) -> float:
        """The scenario's bound of ``check`` at this preset (:func:`at_preset`), in ``mode``'s table where given."""
        scenario = scenarios.get(self.scenario)
        table = scenario.tolerances if mode is None else scenario.tolerances[mode]  # type: ignore[index]
        return float(at_preset(table, self.scenario, self.preset)[check])  # type: ignore[arg-type]


def declared() -> dict[str, tuple[str, PaperResult]]:
    """Every registered scenario's paper results by id: ``id -> (scenario, result)``, in registry order."""
    pairs = [(name, r) for name in scenarios.loadable() for r in scenarios.get(name).paper_results]
    unique_ids([r for _, r in pairs])
    return {r.id: (name, r) for name, r in pairs}


def select(ids: Sequence[str], paper: str | None) -> list[tuple[str, PaperResult]]:
    """The results named by ``ids`` (all when none) of ``paper`` (all papers when None); unknown ones refused."""
    table = declared()
    if paper is not None and paper not in PAPERS:
        raise ParameterError(f"--paper must be one of {', '.join(PAPERS)} (got {paper!r})")
    unknown = [i for i in ids if i not in table]
    if unknown:
        raise ParameterError(f"unknown result id {unknown[0]!r} (mjpoincare reproduce --list shows the ids)")
    chosen = [table[i] for i in ids] if ids else list(table.values())
    return [(s, r) for s, r in chosen if paper is None or r.paper == paper]


def describe(result: PaperResult, scenario: str) -> dict[str, Any]:
    """A result's declaration (``--list``): no simulation, no analytic value computed."""
    run = result.run
    how = {AtValidation: lambda: f"validate {scenario} " + " ".join(f"--set {k}={v}" for k, v in
                                                                      run.assignments.items()),  # type: ignore[union-attr]
           Experiment: lambda: f"{scenario}: a dedicated MuJoCo experiment",
           Curve: lambda: f"{scenario}: one validation per value of {run.x_label}",  # type: ignore[union-attr]
           Bracket: lambda: f"{scenario}: bisection on [{run.low:g}, {run.high:g}]",  # type: ignore[union-attr]
           Refusal: lambda: f"not runnable: {run.reason}"}[type(run)]()  # type: ignore[union-attr]
    return {"id": result.id, "paper": result.paper, "location": result.location, "quantity": result.quantity,
            "paper_value": result.paper_value, "scenario": scenario, "kind": result.kind, "mujoco_run": how.strip(),
            "independent": result.independent, "presets": list(result.presets), "miss": result.miss,
            "disagreement": result.disagreement, "why": result.why, "gate": result.gate}


def _reading_row(result: PaperResult, scenario: str, preset: str, reading: Reading | None, wall: float,
                 **extra: Any) -> dict[str, Any]:
    base = describe(result, scenario)
    row = {"key": f"{result.id}@{preset}", **base, "preset": preset, "wall_s": wall,
           "verdict": verdict(reading, result)}
    if reading is not None:
        row |= {"analytic": jsonable(reading.analytic), "mujoco": jsonable(reading.mujoco),
                "error": jsonable(reading.error), "tolerance": jsonable(reading.tolerance),
                "error_kind": reading.kind, "spread": jsonable(reading.spread), "detail": reading.detail}
    else:
        row |= {"analytic": None, "mujoco": None, "error": None, "tolerance": None, "error_kind": "refused",
                "spread": None, "detail": result.run.reason}  # type: ignore[union-attr]
    return jsonable(row | extra)


def validation_job(scenario: str, assignments: Mapping[str, str], preset: str, ids: Sequence[str]
                   ) -> list[dict[str, Any]]:
    """One validation, read for every result in ``ids`` (module level: worker processes and Dask run it)."""
    table = declared()
    start = time.perf_counter()
    result = run_validation(scenario, dict(assignments), preset)
    wall = (time.perf_counter() - start) / len(ids)
    rows = []
    for rid in ids:
        pr = table[rid][1]
        assert isinstance(pr.run, AtValidation)
        rows.append(_reading_row(pr, scenario, preset, pr.run.read(result), wall,
                                 warnings=len(result.warnings), diverged=len(result.diverged)))
    return rows


def experiment_job(rid: str, preset: str) -> dict[str, Any]:
    """One dedicated experiment."""
    scenario, pr = declared()[rid]
    assert isinstance(pr.run, Experiment)
    start = time.perf_counter()
    reading = pr.run.run(ScenarioRunner(scenario, preset))
    return _reading_row(pr, scenario, preset, reading, time.perf_counter() - start)


def curve_point_job(rid: str, preset: str, index: int) -> dict[str, Any]:
    """One point of a figure's curve (a partial row, key ``id@preset#index``)."""
    scenario, pr = declared()[rid]
    assert isinstance(pr.run, Curve)
    start = time.perf_counter()
    x = pr.run.x[index]
    reading = pr.run.point(x, ScenarioRunner(scenario, preset))
    return jsonable({"key": f"{rid}@{preset}#{index}", "x": x, "analytic": reading.analytic,
                     "mujoco": reading.mujoco, "error": reading.error, "tolerance": reading.tolerance,
                     "spread": reading.spread, "passed": reading.passed, "detail": reading.detail,
                     "wall_s": time.perf_counter() - start})


def bracket_job(rid: str, preset: str) -> dict[str, Any]:
    """A bisection in MuJoCo for one bracket."""
    scenario, pr = declared()[rid]
    run = pr.run
    assert isinstance(run, Bracket)
    start = time.perf_counter()
    runner = ScenarioRunner(scenario, preset)
    theory = run.theory(runner)
    try:
        low, high, runs = bisect(lambda v: run.below(v, runner), run.low, run.high, run.tolerance / 4)
    except ValueError:  # MuJoCo reads both ends on one side: no crossing located, and the result fails
        reading = Reading(analytic=theory, mujoco=None, error=math.nan, tolerance=run.tolerance,
                          detail=f"MuJoCo reads both ends of [{run.low:g}, {run.high:g}] {run.unit} on one side")
        return _reading_row(pr, scenario, preset, reading, time.perf_counter() - start,
                            bracket={"low": run.low, "high": run.high, "runs": 2})
    located = (low + high) / 2
    reading = Reading(analytic=theory, mujoco=located, error=abs(located - theory), tolerance=run.tolerance,
                      spread=abs(high - low) / 2, detail=f"bracket [{low:.6g}, {high:.6g}] {run.unit} after "
                      f"{runs} runs")
    return _reading_row(pr, scenario, preset, reading, time.perf_counter() - start,
                        bracket={"low": low, "high": high, "runs": runs})


def _curve_row(pr: PaperResult, scenario: str, preset: str, points: list[dict[str, Any]]) -> dict[str, Any]:
    """A figure's row from its points: the largest error over the points, judged against the tolerance."""
    errors = [p["error"] for p in points]
    worst = max(range(len(points)), key=lambda i: math.inf if errors[i] is None else errors[i])
    wp = points[worst]
    reading = Reading(analytic=wp["analytic"], mujoco=wp["mujoco"],
                      error=math.inf if wp["error"] is None else wp["error"], tolerance=wp["tolerance"],
                      spread=math.nan if wp["spread"] is None else wp["spread"],
                      detail=f"largest gap of {len(points)} points, at x = {wp['x']:g}")
    return _reading_row(pr, scenario, preset, reading, sum(p["wall_s"] for p in points),
                        figure={"x": [p["x"] for p in points], "mujoco": [p["mujoco"] for p in points],
                                "analytic": [p["analytic"] for p in points], "spread": [p["spread"] for p in points],
                                "error": errors, "passed": [p["passed"] for p in points]})


def plan(chosen: Iterable[tuple[str, PaperResult]], preset: str) -> tuple[list[str], list[tuple[Any, ...]]]:
    """The rows' keys and the jobs that make them, at ``preset`` (results not run at it are left out)."""
    keys: list[str] = []
    groups: dict[tuple[str, tuple[tuple[str, str], ...]], list[str]] = {}
    jobs: list[tuple[Any, ...]] = []
    for scenario, pr in chosen:
        if preset not in pr.presets:
            continue
        run = pr.run
        if isinstance(run, Curve):
            keys += [f"{pr.id}@{preset}#{i}" for i in range(len(run.x))]
            jobs += [(curve_point_job, pr.id, preset, i) for i in range(len(run.x))]
            continue
        keys.append(f"{pr.id}@{preset}")
        if isinstance(run, AtValidation):
            groups.setdefault((scenario, tuple(sorted(run.assignments.items()))), []).append(pr.id)
        elif isinstance(run, Experiment):
            jobs.append((experiment_job, pr.id, preset))
        elif isinstance(run, Bracket):
            jobs.append((bracket_job, pr.id, preset))
        else:
            jobs.append((refusal_job, pr.id, preset))
    jobs += [(validation_job, s, dict(a), preset, ids) for (s, a), ids in groups.items()]
    return keys, jobs


def refusal_job(rid: str, preset: str) -> dict[str, Any]:
    """A result not runnable in MuJoCo: its row, with the reason."""
    scenario, pr = declared()[rid]
    return _reading_row(pr, scenario, preset, None, 0.0)


def dispatch(job: tuple[Any, ...]) -> Any:
    """Run one planned job (module level: the engines call it with the job's tuple)."""
    fn, *args = job
    return fn(*args)


def assemble(chosen: Iterable[tuple[str, PaperResult]], preset: str, rows: Mapping[str, dict[str, Any]]
             ) -> list[dict[str, Any]]:
    """The results' rows at ``preset``, a figure's made from its points (only results whose rows are all held)."""
    out = []
    for scenario, pr in chosen:
        if preset not in pr.presets:
            continue
        if isinstance(pr.run, Curve):
            points = [rows.get(f"{pr.id}@{preset}#{i}") for i in range(len(pr.run.x))]
            if all(p is not None for p in points):
                out.append(_curve_row(pr, scenario, preset, points))  # type: ignore[arg-type]
        elif f"{pr.id}@{preset}" in rows:
            out.append(rows[f"{pr.id}@{preset}"])
    return out


def run_reproduce(ids: Sequence[str], paper: str | None, preset: str, json_path: str | None, plots: str | None,
                  *, workers: int = 1, engine: str = "local", scheduler: str | None = None,
                  resume: bool = False) -> int:
    """Run the chosen results at ``preset``; print the table; exit 0 unless a result FAILs (a declared miss and a
    refusal are not failures)."""
    check_engine(workers, engine, scheduler)
    if preset not in ("fast", "accurate"):
        raise ParameterError(f"--preset must be fast or accurate (got {preset!r})")
    chosen = select(ids, paper)
    keys, jobs = plan(chosen, preset)
    header = {"schema": SCHEMA, "preset": preset, "ids": sorted(r.id for _, r in chosen)}
    held = ResumableRows.open(header, json_path, "key", keys, resume=resume)
    todo = set(held.todo)
    start = time.perf_counter()
    pending = [j for j in jobs if _job_keys(j, chosen) & todo]
    held.run(dispatch, [(j,) for j in pending], label="reproduce", unit="row",
             describe=lambda new: f"{new[0]['key']}: {new[0].get('verdict', 'point')}", workers=workers,
             engine=engine, scheduler=scheduler)
    wall = time.perf_counter() - start
    results = assemble(chosen, preset, held.rows)
    out = sys.stderr if json_path == "-" else sys.stdout  # stdout carries the JSON alone
    print(summary_table(results), file=out)
    counts = {v: sum(r["verdict"] == v for r in results) for v in ("pass", "miss", "FAIL", "refused")}
    print(f"\n{len(results)} results at the {preset} preset: " + ", ".join(f"{n} {v}" for v, n in counts.items())
          + f"; {len(pending)} jobs run in {wall:.1f} s wall ({engine} engine, {workers} worker(s))", file=out)
    if json_path:
        write_json(jsonable({**header, "mjpoincare": VERSION, "environment": environment(), "wall_s": wall,
                             "workers": workers, "rows": held.ordered(), "results": results}), json_path)
    if plots:
        from mjpoincare.commands.reproduce_plots import plot_figures

        for path in plot_figures(chosen, results, Path(plots), runner=ScenarioRunner):
            print(f"wrote {path}", file=out)
    return 1 if counts["FAIL"] else 0


def _job_keys(job: tuple[Any, ...], chosen: Sequence[tuple[str, PaperResult]]) -> set[str]:
    fn, *args = job
    if fn is validation_job:
        return {f"{rid}@{args[2]}" for rid in args[3]}
    if fn is curve_point_job:
        return {f"{args[0]}@{args[1]}#{args[2]}"}
    return {f"{args[0]}@{args[1]}"}


def _cell(value: Any) -> str:
    if value is None:
        return "—"
    if isinstance(value, float):
        return f"{value:.4g}"
    if isinstance(value, list):
        return "[" + ", ".join(_cell(v) for v in value) + "]"
    return str(value)


def summary_table(results: Sequence[Mapping[str, Any]]) -> str:
    """One line per result: id, paper value, analytic, MuJoCo, error, tolerance, verdict."""
    return markdown_table(("id", "paper", "analytic", "MuJoCo", "error", "tolerance", "verdict"),
                          [(r["id"], r["paper_value"] or "—", _cell(r["analytic"]), _cell(r["mujoco"]),
                            _cell(r["error"]), _cell(r["tolerance"]), r["verdict"]) for r in results])


def list_results(ids: Sequence[str], paper: str | None, json_path: str | None) -> int:
    """``--list``: the ids and their declarations, without simulating."""
    rows = [describe(r, s) for s, r in select(ids, paper)]
    if json_path:
        write_json({"schema": SCHEMA, "results": rows}, json_path)
        if json_path == "-":
            return 0
    print(markdown_table(("id", "paper", "location", "quantity", "paper value", "run"),
                         [(r["id"], r["paper"], r["location"], r["quantity"], r["paper_value"] or "—",
                           r["kind"]) for r in rows]))
    return 0
