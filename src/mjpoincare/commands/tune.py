"""``mjpoincare tune``: the cheapest simulator settings that pass, found by a multi-objective search.

A study searches a scenario's :attr:`~mjpoincare.scenarios.base.Scenario.search_space` for one target preset
(``fast`` or ``accurate``: the tolerances a trial is judged at). Each trial runs the scenario's validation at every
one of its coverage points (:attr:`~mjpoincare.scenarios.base.Scenario.coverage`) with the trial's settings and
reports two objectives, both minimised:

- **cost**: the CPU seconds of those validations (``time.process_time`` of the worker process, over all its threads).
  CPU time is the work done: it does not change with the thread count, and a busy machine stretches wall time far
  more than it changes CPU time, so trials run side by side stay comparable. Each trial runs its rollouts on one
  thread. Wall time is recorded beside it.
- **worst ratio**: the largest ``error / tolerance`` over every check of every coverage point (the ``stable`` check
  included). A failed check whose tolerance is 0 (a count or a category), a missing value and a diverged run count
  as :data:`RATIO_CAP`, so the sampler still ranks them behind every finite ratio.

A trial gives up at the first coverage point where a check fails (a worst ratio above 1): such settings cannot be a
preset, whatever the other points give. It is recorded as pruned, with the point and check that failed it and the CPU
seconds spent until then, and the sampler ranks it behind every finished trial. The points run in the order of their
mean ratio over the study's finished trials (a pruned trial counts at the points it ran), the hardest first, so
that a failing trial fails early.

The study is Optuna's (multi-objective TPE sampler with constant liar for parallel workers) in an SQLite file: a
study can be resumed (``--resume``), shared and run by ``--workers`` processes at once. The first trials are the
scenario's current presets, so that the front shows where they stand. The Pareto front is Optuna's
(``study.best_trials``). The preset for the target is the cheapest front point whose worst ratio is at most
:data:`PRESET_RATIO`. If none is, the study says so: the preset is then the cheapest front point that passes every
check (within the tolerances, without the margin), else none is chosen; the front shows the best that was found.
Only a trial inside the target's timestep range (:data:`TARGET_TIMESTEPS`) can be chosen: the other preset, enqueued
as a trial, is shown on the front where it stands, and an accurate preset never becomes the fast one's settings.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, wait
from dataclasses import dataclass, field, replace
from multiprocessing import get_context
from pathlib import Path
from typing import Any

from mjpoincare import scenarios
from mjpoincare.analysis.checks import Check
from mjpoincare.commands.validation import resolve_inputs, run_steps, run_validation
from mjpoincare.core import progress
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.params import ParameterError, Value, resolve
from mjpoincare.scenarios.base import CoveragePoint

TARGETS = ("accurate", "fast")
#: The ratio a failed zero-tolerance check, a missing value or a diverged run counts as.
RATIO_CAP = 1e3
#: A preset's worst ratio over every check and coverage point: its tolerances held with a factor 2 to spare.
PRESET_RATIO = 0.5
STUDY_DIR = Path("renders/tune")
#: The timestep range each target searches (within the scenario's own): an accurate preset is not looked for at steps
#: the fast presets already take, nor a fast one at steps that cost more than the accurate presets.
TARGET_TIMESTEPS = {"accurate": (1e-5, 2e-4), "fast": (5e-5, 1e-3)}
_FINISHED = ("COMPLETE", "FAIL", "PRUNED")


def _optuna() -> Any:
    try:
        import optuna
    except ImportError:
        raise ParameterError("tune needs the optional extra: pip install 'mjpoincare[tune]'") from None
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    return optuna


def check_ratio(check: Check) -> float:
    """``error / tolerance`` of one check; :data:`RATIO_CAP` for a missing value or a failed zero-tolerance check."""
    if not math.isfinite(check.error):
        return RATIO_CAP
    if check.tolerance <= 0.0:
        return 0.0 if check.error <= 0.0 else RATIO_CAP
    return min(check.error / check.tolerance, RATIO_CAP)


@dataclass(frozen=True)
class TrialOutcome:
    """One trial's verdict over the coverage points.

    Attributes:
        cpu_s: CPU seconds of the validations (the cost objective).
        wall_s: their wall seconds.
        worst_ratio: the largest ``error / tolerance`` (the accuracy objective).
        worst_check: where it is, ``point/check``.
        point_ratios: each judged coverage point's worst ratio and its check, for the points that ran.
        gave_up: the trial stopped at a point that failed (``worst_ratio`` > ``give_up``), before the others ran.
        miss_ratios: the same at the points declared misses at the target (outside both objectives).
    """

    cpu_s: float
    wall_s: float
    worst_ratio: float
    worst_check: str
    point_ratios: Mapping[str, tuple[float, str]]
    gave_up: bool = False
    miss_ratios: Mapping[str, tuple[float, str]] = field(default_factory=dict)


def setting_text(value: Value) -> str:
    """A setting as ``--set`` text (numbers to 12 significant digits)."""
    return f"{value:.12g}" if isinstance(value, float) else str(value)


def as_run(settings: Mapping[str, Value]) -> dict[str, Value]:
    """The settings as a trial runs them: through their ``--set`` text (floats to 12 significant digits)."""
    return {k: float(setting_text(v)) if isinstance(v, float) else v for k, v in settings.items()}


def _ratio_at(name: str, point: CoveragePoint, overrides: Mapping[str, str], target: str
              ) -> tuple[float, str, float, float]:
    """(worst ratio, its check, CPU s, wall s) of the validation of ``name`` at coverage ``point``."""
    cpu0, wall0 = time.process_time(), time.perf_counter()
    result = run_validation(name, {**point.assignments, **overrides}, preset=target)
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    ratio, check = max((check_ratio(c), c.name) for c in result.checks)
    return ratio, check, cpu, wall


def run_trial(name: str, target: str, settings: Mapping[str, Value], *, order: Sequence[str] = (),
              give_up: float = math.inf) -> TrialOutcome:
    """Validate scenario ``name`` with ``settings`` at each of its coverage points judged at ``target`` (those named
    in ``order`` first, in that order), at ``target``'s tolerances, on one rollout thread; stop after the first
    point whose worst ratio exceeds ``give_up``. The points that are declared misses at ``target`` run after the
    others (unless the trial gave up): their ratios are recorded, outside both objectives."""
    scenario = scenarios.get(name)
    overrides = {k: setting_text(v) for k, v in settings.items()} | {"threads": "1"}
    rank = {point: k for k, point in enumerate(order)}
    judged = sorted((p for p in scenario.coverage if target not in p.miss_at),
                    key=lambda point: rank.get(point.name, len(rank)))
    cpu = wall = 0.0
    point_ratios: dict[str, tuple[float, str]] = {}
    for point in judged:
        ratio, check, point_cpu, point_wall = _ratio_at(name, point, overrides, target)
        cpu, wall = cpu + point_cpu, wall + point_wall
        point_ratios[point.name] = (ratio, check)
        if ratio > give_up:
            break
    worst_point = max(point_ratios, key=lambda k: point_ratios[k][0])
    ratio, check = point_ratios[worst_point]
    gave_up = len(point_ratios) < len(judged)
    misses: dict[str, tuple[float, str]] = {}
    for point in () if gave_up else (p for p in scenario.coverage if target in p.miss_at):
        miss_ratio, miss_check, *_ = _ratio_at(name, point, overrides, target)
        misses[point.name] = (miss_ratio, miss_check)
    return TrialOutcome(cpu_s=cpu, wall_s=wall, worst_ratio=ratio, worst_check=f"{worst_point}/{check}",
                        point_ratios=point_ratios, gave_up=gave_up, miss_ratios=misses)


def hardest_first(trials: Sequence[Any]) -> list[str]:
    """Coverage point names by their mean worst ratio (capped at 10) over ``trials`` (Optuna trials with
    ``point_ratios``), the largest first."""
    ratios: dict[str, list[float]] = {}
    for trial in trials:
        for point, (ratio, _) in trial.user_attrs.get("point_ratios", {}).items():
            ratios.setdefault(point, []).append(min(float(ratio), 10.0))
    return sorted(ratios, key=lambda point: -sum(ratios[point]) / len(ratios[point]))


def target_space(scenario: scenarios.Scenario, target: str) -> tuple[sim_settings.Dimension, ...]:
    """The scenario's search space with the timestep range narrowed to the target's (:data:`TARGET_TIMESTEPS`)."""
    low, high = TARGET_TIMESTEPS[target]
    return tuple(replace(d, low=max(d.low, low), high=min(d.high, high)) if d.name == "timestep" else d
                 for d in scenario.search_dimensions)


def _param_name(dim: sim_settings.Dimension) -> str:
    return f"{dim.name}_steps" if dim.per_timestep else dim.name


def suggest_settings(trial: Any, space: Sequence[sim_settings.Dimension]) -> dict[str, Value]:
    """The settings an Optuna ``trial`` proposes over ``space`` (a ``per_timestep`` value times the timestep)."""
    values: dict[str, Value] = {}
    for dim in space:
        if dim.choices:
            values[dim.name] = trial.suggest_categorical(_param_name(dim), list(dim.choices))
        else:
            values[dim.name] = trial.suggest_float(_param_name(dim), dim.low, dim.high, log=dim.log)
    for dim in space:
        if dim.per_timestep:
            values[dim.name] = float(values[dim.name]) * float(values["timestep"])
    return values


def preset_params(scenario: scenarios.Scenario, preset: str) -> dict[str, Value]:
    """A scenario preset as the search's trial parameters (to enqueue it as a trial; it may lie outside a target's
    timestep range)."""
    full = {**sim_settings.DEFAULTS, **scenario.presets[preset]}
    params: dict[str, Value] = {}
    for dim in scenario.search_dimensions:
        value = full[dim.name]
        params[_param_name(dim)] = float(value) / float(full["timestep"]) if dim.per_timestep else value
    return params


def study_name(name: str, target: str) -> str:
    """The study of scenario ``name`` for ``target`` in its storage."""
    return f"{name}-{target}"


def storage_url(path: Path) -> str:
    """The SQLite URL of a study file."""
    return f"sqlite:///{path.resolve()}"


def _storage(url: str) -> Any:
    storage = _optuna().storages.RDBStorage(url, engine_kwargs={"connect_args": {"timeout": 120}})
    _write_locked_transactions(storage.engine)
    return storage


def _write_locked_transactions(engine: Any) -> None:
    """Make every transaction on the SQLite ``engine`` take the database's write lock when it begins.

    Optuna hands an enqueued trial to a worker by reading it as WAITING and then writing RUNNING, relying on a row
    lock (``SELECT ... FOR UPDATE``) that SQLite lacks; and Python's sqlite3 runs the read outside any transaction.
    Two workers could then both take one enqueued trial, and the second fails when it reports it. ``BEGIN
    IMMEDIATE`` (SQLAlchemy's documented pysqlite recipe) serialises the read and the write; a worker waits up to
    the connection timeout for the lock.
    """
    from sqlalchemy import event

    def no_implicit_transactions(dbapi_connection: Any, _record: Any) -> None:
        dbapi_connection.isolation_level = None

    def begin_immediate(connection: Any) -> None:
        connection.exec_driver_sql("BEGIN IMMEDIATE")

    event.listen(engine, "connect", no_implicit_transactions)
    event.listen(engine, "begin", begin_immediate)
    engine.dispose()  # connections opened before the listeners would keep the old behaviour


def _sampler(seed: int) -> Any:
    return _optuna().samplers.TPESampler(seed=seed, multivariate=True, constant_liar=True, n_startup_trials=6)


def _objective(name: str, target: str) -> Any:
    space = target_space(scenarios.get(name), target)

    def objective(trial: Any) -> tuple[float, float]:
        settings = suggest_settings(trial, space)
        state = _optuna().trial.TrialState
        order = hardest_first(trial.study.get_trials(deepcopy=False, states=(state.COMPLETE, state.PRUNED)))
        try:
            outcome = run_trial(name, target, settings, order=order, give_up=1.0)
        except ParameterError as err:  # settings the scenario refuses (e.g. a time constant MuJoCo would clamp)
            trial.set_user_attr("refused", str(err))
            return math.inf, RATIO_CAP
        trial.set_user_attr("settings", settings)
        trial.set_user_attr("wall_s", outcome.wall_s)
        trial.set_user_attr("worst_check", outcome.worst_check)
        trial.set_user_attr("point_ratios", {k: list(v) for k, v in outcome.point_ratios.items()})
        trial.set_user_attr("miss_ratios", {k: list(v) for k, v in outcome.miss_ratios.items()})
        if outcome.gave_up:
            trial.set_user_attr("cpu_s_until_failure", outcome.cpu_s)
            trial.set_user_attr("ratio_at_failure", outcome.worst_ratio)
            raise _optuna().TrialPruned(f"fails at {outcome.worst_check} (ratio {outcome.worst_ratio:.3g})")
        return outcome.cpu_s, outcome.worst_ratio

    return objective


def _work(url: str, name: str, target: str, count: int, seed: int) -> None:
    """One worker: ``count`` trials of the study (module level: run in a spawned process)."""
    optuna = _optuna()
    # a preset enqueued outside the target's timestep range is meant: it shows where the old preset stands
    warnings.filterwarnings("ignore", message="Fixed parameter .* is out of range", category=UserWarning)
    resolve_inputs(name, {"threads": "1"}, target)  # the seam's self-tests, once, outside every trial's cost
    study = optuna.load_study(study_name=study_name(name, target), storage=_storage(url), sampler=_sampler(seed))
    study.optimize(_objective(name, target), n_trials=count, catch=(Exception,))


def _finished(study: Any) -> int:
    states = tuple(getattr(_optuna().trial.TrialState, s) for s in _FINISHED)
    return len(study.get_trials(deepcopy=False, states=states))


def enqueued_params(scenario: scenarios.Scenario, assignments: Mapping[str, str]) -> dict[str, Value]:
    """``--enqueue``'s settings as trial parameters (checked as settings; the settings it leaves out are sampled)."""
    space = {d.name: d for d in scenario.search_dimensions}
    outside = set(assignments) - set(space)
    if outside:
        raise ParameterError(f"--enqueue: {', '.join(sorted(outside))} not searched for {scenario.name} "
                             f"(searched: {', '.join(space)})")
    values = resolve(sim_settings.SETTINGS, sim_settings.DEFAULTS, assignments)
    params: dict[str, Value] = {}
    for key in assignments:
        dim = space[key]
        if dim.per_timestep and "timestep" not in assignments:
            raise ParameterError(f"--enqueue: {key} needs timestep beside it (it is searched in timesteps)")
        params[_param_name(dim)] = float(values[key]) / float(values["timestep"]) if dim.per_timestep else values[key]
    return params


def run_study(name: str, target: str, *, trials: int, workers: int, path: Path, resume: bool, seed: int = 0,
              enqueue: Sequence[Mapping[str, str]] = (), command: str = "") -> Any:
    """Run (or, with ``resume``, continue) the study of scenario ``name`` for ``target`` in the SQLite file ``path``
    until it holds ``trials`` finished trials, shared out over ``workers`` processes; returns the study. The
    scenario's presets are its first trials when it starts anew; ``enqueue`` adds settings to try next (partial
    ones: the rest is sampled). ``command`` is recorded in the study when this call adds trials."""
    optuna = _optuna()
    scenario = scenarios.get(name)
    if target not in TARGETS or target not in scenario.presets:
        raise ParameterError(f"--target must be one of {', '.join(TARGETS)} (got {target!r})")
    if trials < 1 or workers < 1:
        raise ParameterError(f"--trials and --workers must be >= 1 (got {trials}, {workers})")
    resolve_inputs(name, {}, target)
    per_trial = sum(run_steps(name, dict(point.assignments), target) for point in scenario.coverage) or run_steps(
        name, {}, target)
    refuse_long(trials * per_trial, f"tune {name} --trials {trials} (each trial about the {target} preset's "
                f"{per_trial:.3g} steps over the coverage points)", allow=False, remedy="give fewer --trials")
    extra = [enqueued_params(scenario, a) for a in enqueue]
    path.parent.mkdir(parents=True, exist_ok=True)
    url, label = storage_url(path), study_name(name, target)
    storage = _storage(url)
    exists = label in [s.study_name for s in optuna.get_all_study_summaries(storage)]
    if exists and not resume:
        optuna.delete_study(study_name=label, storage=storage)
    study = optuna.create_study(study_name=label, storage=storage, directions=["minimize", "minimize"],
                                sampler=_sampler(seed), load_if_exists=True)
    if not exists or not resume:
        study.set_user_attr("scenario", name)
        study.set_user_attr("target", target)
        for preset in scenario.presets:
            if preset in TARGETS:
                study.enqueue_trial(preset_params(scenario, preset), user_attrs={"origin": f"preset {preset}"})
    for params in extra:
        study.enqueue_trial(params, user_attrs={"origin": "enqueued"})
    remaining = max(0, trials - _finished(study))
    if remaining and command:
        study.set_user_attr("commands", [*study.user_attrs.get("commands", []), command])
    shares = [remaining // workers + (k < remaining % workers) for k in range(workers)]
    with progress.bar(trials, label, unit="trial", initial=trials - remaining) as bar:
        if workers == 1:
            _work(url, name, target, remaining, seed)
        elif remaining:
            with ProcessPoolExecutor(max_workers=workers, mp_context=get_context("spawn")) as pool:
                futures = [pool.submit(_work, url, name, target, share, seed + k)
                           for k, share in enumerate(shares) if share]
                pending = set(futures)
                while pending:
                    _, pending = wait(pending, timeout=2.0)
                    bar.update(min(_finished(study), trials) - bar.n)
                for future in futures:
                    future.result()
        bar.update(min(_finished(study), trials) - bar.n)
    return study


def _row(trial: Any) -> dict[str, Any]:
    attrs = trial.user_attrs
    cost, ratio = trial.values if trial.values is not None else (math.nan, attrs.get("ratio_at_failure", math.nan))
    settings = attrs.get("settings")
    return {"number": trial.number, "state": trial.state.name, "origin": attrs.get("origin", "search"),
            "settings": None if settings is None else as_run(settings), "cpu_s": cost if math.isfinite(cost) else None,
            "cpu_s_until_failure": attrs.get("cpu_s_until_failure"),
            "wall_s": attrs.get("wall_s"), "worst_ratio": ratio if math.isfinite(ratio) else None,
            "worst_check": attrs.get("worst_check"), "point_ratios": attrs.get("point_ratios"),
            "miss_ratios": attrs.get("miss_ratios"), "refused": attrs.get("refused")}


def in_timestep_range(rows: Sequence[Mapping[str, Any]], space: Sequence[Mapping[str, Any]]
                      ) -> list[Mapping[str, Any]]:
    """The trial rows whose timestep lies in the searched range (``space``: the JSON form of
    :func:`target_space`), the ones :func:`choose` may pick from."""
    bounds = [(d["low"], d["high"]) for d in space if d["name"] == "timestep"]
    if not bounds:
        return list(rows)
    low, high = bounds[0]
    return [r for r in rows if r["settings"] is not None and low <= float(r["settings"]["timestep"]) <= high]


def choose(trials: Sequence[Mapping[str, Any]], limit: float = PRESET_RATIO
           ) -> tuple[Mapping[str, Any] | None, str]:
    """The preset's trial and how it holds: the cheapest of ``trials`` whose worst ratio is at most ``limit``
    (``"margin"``); else the cheapest that passes every check (``"no margin"``: within the tolerances, but not by
    the factor ``1 / limit``; a more expensive one would buy accuracy the target does not ask for without reaching
    the margin either); else None (``"none"``). Either is a point of the trials' Pareto front, so ``trials`` may be
    the front or every finished trial."""
    rated = [r for r in trials if r["worst_ratio"] is not None and r["cpu_s"]]
    for bound, holds in ((limit, "margin"), (1.0, "no margin")):
        passing = [r for r in rated if r["worst_ratio"] <= bound]
        if passing:
            return min(passing, key=lambda r: r["cpu_s"]), holds
    return None, "none"


def summary(study: Any) -> dict[str, Any]:
    """The study as JSON data: every trial, the Pareto front (cheapest first) and the chosen preset."""
    scenario = scenarios.get(study.user_attrs["scenario"])
    target = study.user_attrs["target"]
    rows = [_row(t) for t in study.trials if t.state.is_finished()]
    front = sorted((_row(t) for t in study.best_trials if t.values and math.isfinite(t.values[0])),
                   key=lambda r: r["cpu_s"])
    space = [{"name": d.name, "low": d.low, "high": d.high, "log": d.log, "choices": list(d.choices),
              "per_timestep": d.per_timestep} for d in target_space(scenario, target)]
    chosen, holds = choose(in_timestep_range(rows, space))
    preset = None if chosen is None else {**scenario.presets[target], **chosen["settings"]}
    return {"scenario": scenario.name, "target": target, "study": study.study_name,
            "commands": study.user_attrs.get("commands", []),
            "objectives": ["cpu_s", "worst_ratio"], "preset_ratio": PRESET_RATIO, "ratio_cap": RATIO_CAP,
            "coverage": [{"name": p.name, "assignments": dict(p.assignments), "why": p.why,
                          "miss": target in p.miss_at} for p in scenario.coverage],
            "space": space, "trials": rows, "front": front, "chosen": chosen, "holds": holds, "preset": preset}
