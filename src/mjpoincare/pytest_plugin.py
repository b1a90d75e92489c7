"""pytest plugin: gate CI on mjpoincare's analytic checks, one test item per check.

Usage (the plugin is registered through the ``pytest11`` entry point ``mjpoincare``; no test files needed)::

    pytest --mjpoincare rimless-wheel,compass-biped [--mjpoincare-preset fast]
           [--mjpoincare-set timestep=2e-4 ...] [--mjpoincare-seed 0]
           [--mjpoincare-baseline PATH [--mjpoincare-update-baseline]]

Each scenario gives one item per check of its :class:`~mjpoincare.core.result.Result`, node id
``mjpoincare::<scenario>::<check>`` (the ``stable`` check, divergence + MuJoCo warnings, included; such a node id on
the command line, ``pytest mjpoincare::rimless-wheel::eigenvalue``, runs that item alone); every item
carries the ``mjpoincare`` marker, so ``-m mjpoincare`` selects only these and ``-m "not mjpoincare"`` skips them.
A failing item prints the check's analytic and simulated values, error (and its kind), tolerance, unit and why,
then the scenario / preset / seed / settings. Exit status is pytest's: 0 all passed, 1 a check failed,
4 bad input (unknown scenario, preset or ``--mjpoincare-set`` value: a one-line usage error naming the parameter
and its bound, raised in ``pytest_configure`` before any simulation). Without ``--mjpoincare`` the plugin adds
nothing and imports nothing beyond pytest (no MuJoCo, numpy or scipy); ``-p no:mjpoincare`` disables it.

With ``--mjpoincare-baseline PATH`` (:mod:`mjpoincare.gate.baseline`) an item also fails when its check's error moved
from the one recorded in ``PATH`` for the same scenario, preset and parameters by more than its allowance
(:func:`mjpoincare.core.allowance.allowance`: 3 x its resolution, never below 1e-6 x its tolerance; naming the old
and new errors, the resolution and the allowance), or when the check is missing from the run or from the baseline;
a ``PATH`` that does not exist is created from this session's runs, and every item fails saying so (as
pytest-regressions does: run again to compare). With ``--mjpoincare-update-baseline`` the runs are recorded into
``PATH`` instead (whole, at the end of the session; its other runs kept), each check's resolution measured by
re-running the scenario under the rounding perturbations, and the items judge the tolerances only (as
syrupy's ``--snapshot-update``).

How the items get into the session (pytest 8 and 9): a ``pytest_make_collect_report`` wrapper adds one collector
per scenario to the *session's* collect report. pytest then expands those collectors exactly as it expands files:
collect reports, ``pytest_itemcollected``, the "collected N items" count, then ``pytest_collection_modifyitems``
(``-k``, ``-m``, ``--deselect``, ``--lf``) and ``session.testscollected``. So the run exits 0 (not 5, "no tests")
in an empty directory and the items sit beside a project's own tests. The alternatives are weaker: items appended
in ``pytest_collection_modifyitems`` skip the collect reports (wrong count) and race the plugins that deselect
in that same hook; a ``pytest_collect_directory`` collector is only reached for directories on the collection
path, so ``pytest tests/test_x.py --mjpoincare ...`` would silently drop the checks.

When the simulation runs: never at collection. The items are the checks the scenario declares at the requested
parameters and settings (:meth:`~mjpoincare.scenarios.base.Scenario.checks_for`, checked inputs only) and
``stable``; the scenario is validated when its first item runs, once per process, the result cached on the config.
So ``--collect-only`` simulates nothing, a ``-k`` that deselects every check of a scenario skips its run, and under
pytest-xdist ``--dist loadscope`` sends each scenario's items (the scope ``mjpoincare::<scenario>`` of their node
ids) to one worker, which runs the scenario once; with plain ``-n``, xdist's ``load`` spreads the items and each
worker that gets one runs the scenario again (the header says so). (``--dist loadgroup`` with ``xdist_group`` marks
would not do: pytest-xdist 3.8 renames the node ids through an attribute pytest 9.2 no longer reads, so its groups
are ignored.) A check the run reports but does not declare, and a baseline complaint about a check the run lacks,
fail the ``stable`` item, naming it. A run that raises (a crash, not a failed check)
fails each of its items with the traceback, so the other scenarios and the project's tests still run. A scenario
whose module or declaration does not load (a plugin author's mistake) is one failing item,
``mjpoincare::<scenario>::declaration``, with the registry's one line, and the other scenarios run.

Settings in ``pytest.ini``, ``pyproject.toml`` (``[tool.pytest.ini_options]``) or ``tox.ini``, each used where its
option is not given on the command line: ``mjpoincare`` (scenario names, comma- or space-separated),
``mjpoincare_preset``, ``mjpoincare_set`` (``NAME=VALUE`` items, space-separated) and ``mjpoincare_seed``. The ini's
scenarios join a plain ``pytest`` run (its testpaths or the invocation folder); a run of named files or tests
(``pytest test_mine.py::test_x``) collects only those, unless ``--mjpoincare`` names scenarios too.
"""

from __future__ import annotations

import math
from collections.abc import Generator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import pytest

if TYPE_CHECKING:
    from mjpoincare.analysis.checks import Check
    from mjpoincare.core.result import Result

MARKER = "mjpoincare"


@dataclass(frozen=True)
class Request:
    """What ``--mjpoincare*`` asked for, checked: scenarios, preset, seed and ``name=value`` settings."""

    scenarios: tuple[str, ...]
    preset: str | None
    seed: int
    assignments: dict[str, str]
    baseline: str | None = None
    update_baseline: bool = False
    #: The scenarios came from the ini file (``mjpoincare = ...``), not from ``--mjpoincare``.
    from_ini: bool = False
    #: The baseline to compare with did not exist: this session records it, and every item fails saying so.
    creating_baseline: bool = False
    #: Node ids named on the command line (``mjpoincare::<scenario>[::<check>]``): only those items run.
    selected: tuple[str, ...] = ()

    def describe(self, scenario: str | None = None) -> str:
        """One line: scenario(s), preset, seed and the ``--mjpoincare-set`` values."""
        names = scenario or ", ".join(self.scenarios)
        sets = " ".join(f"{k}={v}" for k, v in self.assignments.items()) or "(none)"
        return f"mjpoincare {names}  preset={self.preset or '(scenario default)'}  seed={self.seed}  set: {sets}"


_REQUEST = pytest.StashKey[Request]()
_RESULTS = pytest.StashKey["dict[str, Result | Exception]"]()
#: Per scenario: check name -> the baseline's complaint (compare mode), or the run's record (update mode).
_CHANGES = pytest.StashKey["dict[str, dict[str, str]]"]()
_RECORDS = pytest.StashKey["dict[str, dict[str, Any]]"]()


def pytest_addoption(parser: pytest.Parser) -> None:
    """The ``--mjpoincare*`` options (cheap: no mjpoincare module is imported)."""
    group = parser.getgroup("mjpoincare", "mjpoincare analytic checks (one test item per check)")
    group.addoption("--mjpoincare", action="append", default=[], metavar="SCENARIOS",
                    help="validate these scenarios (comma-separated, repeatable), one test item per check")
    group.addoption("--mjpoincare-preset", default=None, metavar="PRESET",
                    help="simulator preset, e.g. fast or accurate (default: each scenario's own)")
    group.addoption("--mjpoincare-set", action="append", default=[], metavar="NAME=VALUE",
                    help="set a parameter or simulator setting for every scenario (repeatable)")
    group.addoption("--mjpoincare-seed", type=int, default=None, metavar="SEED",
                    help="seed of the experiment design's random parts (default 0)")
    group.addoption("--mjpoincare-baseline", default=None, metavar="PATH",
                    help="also fail a check whose error moved beyond its allowance from this baseline's")
    group.addoption("--mjpoincare-update-baseline", action="store_true", default=False,
                    help="record the runs into --mjpoincare-baseline instead (resolution measured by re-running)")
    parser.addini("mjpoincare", "scenarios to validate when --mjpoincare is not given (comma- or space-separated)",
                  type="args", default=[])
    parser.addini("mjpoincare_preset", "simulator preset when --mjpoincare-preset is not given", default="")
    parser.addini("mjpoincare_set", "NAME=VALUE settings (space-separated) when no --mjpoincare-set is given",
                  type="args", default=[])
    parser.addini("mjpoincare_seed", "seed when --mjpoincare-seed is not given", default="")


def pytest_configure(config: pytest.Config) -> None:
    """Check the ``--mjpoincare*`` input before any collection; bad input is a one-line usage error."""
    request = _parse_request(config)
    if request is None:
        return
    config.stash[_REQUEST] = request
    config.stash[_RESULTS] = {}
    config.stash[_CHANGES] = {}
    config.stash[_RECORDS] = {}
    config.addinivalue_line("markers", f"{MARKER}: an mjpoincare analytic check (added by --mjpoincare)")


def _take_node_ids(config: pytest.Config) -> list[tuple[str, str]]:
    """The ``mjpoincare::<scenario>[::<check>]`` node ids among the command line's arguments, as (scenario, check)
    pairs; they are taken out of ``config.args``, where pytest would look for a file of that name."""
    ids = [a for a in config.args if a.startswith(f"{MARKER}::")]
    if not ids:
        return []
    config.args[:] = [a for a in config.args if a not in ids]
    out = []
    for node in ids:
        parts = node.split("::")
        if len(parts) not in (2, 3) or not parts[1]:
            raise pytest.UsageError(f"{node}: a node id of the plugin is mjpoincare::<scenario>[::<check>]")
        out.append((parts[1], parts[2] if len(parts) == 3 else ""))
    return out


def _parse_request(config: pytest.Config) -> Request | None:
    """The checked request, None without ``--mjpoincare``; raises :class:`pytest.UsageError` on bad input."""
    named = _take_node_ids(config)
    given: list[str] = (config.getoption("mjpoincare") or [",".join(dict.fromkeys(s for s, _ in named))] if named
                        else config.getoption("mjpoincare") or list(config.getini("mjpoincare")))
    preset: str | None = config.getoption("mjpoincare_preset") or str(config.getini("mjpoincare_preset")) or None
    sets: list[str] = config.getoption("mjpoincare_set") or list(config.getini("mjpoincare_set"))
    seed: int | None = config.getoption("mjpoincare_seed")
    if seed is None and str(config.getini("mjpoincare_seed")).strip():
        text = str(config.getini("mjpoincare_seed")).strip()
        try:
            seed = int(text)
        except ValueError:
            raise pytest.UsageError(f"mjpoincare_seed (ini) must be an integer >= 0 (got {text!r})") from None
    baseline: str | None = config.getoption("mjpoincare_baseline")
    update: bool = config.getoption("mjpoincare_update_baseline")
    if not given:
        extra = [flag for flag, value in (("--mjpoincare-preset", preset), ("--mjpoincare-set", sets),
                                          ("--mjpoincare-seed", seed), ("--mjpoincare-baseline", baseline),
                                          ("--mjpoincare-update-baseline", update or None))
                 if value is not None and value != []]
        if extra:
            raise pytest.UsageError(f"{', '.join(extra)} given without --mjpoincare SCENARIOS "
                                    "(nothing would be validated)")
        return None
    names = tuple(dict.fromkeys(n.strip() for item in given for n in item.split(",") if n.strip()))
    if not names:
        raise pytest.UsageError("--mjpoincare expects scenario names, e.g. --mjpoincare rimless-wheel,compass-biped")
    if seed is not None and seed < 0:
        raise pytest.UsageError(f"--mjpoincare-seed must be an integer >= 0 (got {seed})")
    for item in sets:
        if "=" not in item or not item.partition("=")[0].strip():
            raise pytest.UsageError(f"--mjpoincare-set expects NAME=VALUE (got {item!r})")

    if update and not baseline:
        raise pytest.UsageError("--mjpoincare-update-baseline needs --mjpoincare-baseline PATH (the file to record "
                                "into)")

    from mjpoincare.commands.validation import resolve_inputs
    from mjpoincare.core.params import ParameterError, parse_assignments
    from mjpoincare.scenarios import DeclarationError

    creating = False
    if baseline:
        from pathlib import Path

        from mjpoincare.gate.baseline import check_path

        creating = not update and not Path(baseline).exists()  # as pytest-regressions: record it, and fail
        try:
            check_path(baseline, update or creating, option="--mjpoincare-baseline")
        except ParameterError as err:
            raise pytest.UsageError(str(err)) from None

    try:
        assignments = parse_assignments(sets)
    except ParameterError as err:
        raise pytest.UsageError(f"--mjpoincare-set: {err}") from None
    for name in names:
        try:
            resolve_inputs(name, assignments, preset)
        except DeclarationError:
            continue  # a plugin that does not load is its author's mistake, not the request's: one failing item
        except ParameterError as err:
            raise pytest.UsageError(f"--mjpoincare {name}: {err}") from None
    return Request(names, preset, 0 if seed is None else seed, assignments, baseline, update or creating,
                   from_ini=not (config.getoption("mjpoincare") or named), creating_baseline=creating,
                   selected=tuple(f"{MARKER}::{s}::{c}" if c else f"{MARKER}::{s}" for s, c in named))


def pytest_report_header(config: pytest.Config) -> list[str] | None:
    """The request in the session header; under pytest-xdist without ``--dist loadscope``, that each worker runs
    every scenario it has an item of."""
    request = config.stash.get(_REQUEST, None)
    if request is None:
        return None
    lines = [request.describe()]
    if getattr(config.option, "dist", "no") not in ("no", "loadscope"):
        lines.append(f"mjpoincare: --dist {config.option.dist} spreads a scenario's checks over the workers, and "
                     "each worker runs the scenario again; --dist loadscope runs each scenario once")
    if getattr(config.option, "dist", "no") != "no":
        lines.append("mjpoincare: each validation already steps its rollouts on every core (threads); workers split "
                     "the cores and each starts its own processes, so on a machine with few cores a serial run "
                     "(no -n) is the fastest for these items")
    return lines


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """With node ids of the plugin named on the command line, only those of its items run (the others are
    deselected, as pytest does for a file's tests not named)."""
    request = config.stash.get(_REQUEST, None)
    if request is None or not request.selected:
        return
    keep = [i for i in items if not i.nodeid.startswith(f"{MARKER}::")
            or any(i.nodeid == s or i.nodeid.startswith(f"{s}::") for s in request.selected)
            or isinstance(i, BrokenScenarioItem)]  # what stands for every item of a scenario that did not load
    dropped = [i for i in items if i not in keep]
    if dropped:
        config.hook.pytest_deselected(items=dropped)
        items[:] = keep


@pytest.hookimpl(wrapper=True)
def pytest_make_collect_report(
    collector: pytest.Collector,
) -> Generator[None, pytest.CollectReport, pytest.CollectReport]:
    """Add one :class:`ScenarioCollector` per requested scenario to the session's collect report.

    The node id is given (``mjpoincare::<scenario>``): a child of the session that is not a file would otherwise
    get ``::<scenario>`` (pytest 8 and 9 alike); the items below get ``mjpoincare::<scenario>::<check>``.
    """
    report = yield
    request = collector.config.stash.get(_REQUEST, None)
    if request is not None and request.from_ini and collector.config.args_source == pytest.Config.ArgsSource.ARGS:
        return report  # the ini's scenarios join a plain ``pytest`` run, not one of named files or tests
    if request is not None and isinstance(collector, pytest.Session) and report.passed:
        report.result.extend(
            ScenarioCollector.from_parent(collector, name=name, nodeid=f"{MARKER}::{name}")
            for name in request.scenarios
        )
    return report


def _result(config: pytest.Config, scenario: str) -> Result | Exception:
    """The scenario's result (or the exception its run raised), run once and cached on the config."""
    cache = config.stash[_RESULTS]
    if scenario not in cache:
        import mjpoincare
        from mjpoincare.commands.validation import typed_values

        request = config.stash[_REQUEST]
        try:
            cache[scenario] = mjpoincare.validate(scenario, request.preset, request.seed,
                                                  **typed_values(scenario, request.assignments))
        except Exception as err:  # a crash becomes a failing item, not a collection error that stops the session
            cache[scenario] = err
        else:
            _against_baseline(config, scenario, cache[scenario])
    return cache[scenario]


def _against_baseline(config: pytest.Config, scenario: str, result: Result) -> None:
    """Compare ``result`` with the baseline (its complaints per check), or measure its record (update mode)."""
    request = config.stash[_REQUEST]
    if request.baseline is None:
        return
    from mjpoincare.gate import baseline

    if request.update_baseline:
        config.stash[_RECORDS][baseline.run_key(result)] = baseline.entry(
            result, baseline.perturbation_spreads(result, request.assignments))
        if request.creating_baseline:
            config.stash[_CHANGES][scenario] = {
                c.name: f"baseline {request.baseline} did not exist: this run is recorded into it; run again to "
                        "compare" for c in result.checks}
        return
    changes = config.stash[_CHANGES].setdefault(scenario, {})
    for deviation in baseline.deviations(result, baseline.load(request.baseline),
                                         record_flag="--mjpoincare-update-baseline"):
        names = [c.name for c in result.checks] if deviation.check == "*" else [deviation.check]
        for name in names:
            changes[name] = f"baseline {request.baseline}: {deviation.message()}"


def pytest_sessionfinish(session: pytest.Session) -> None:
    """In update mode, write the recorded runs into the baseline, whole (its other runs kept)."""
    records = session.config.stash.get(_RECORDS, None)
    if not records:
        return
    from pathlib import Path

    from mjpoincare.core.result import write_json
    from mjpoincare.core.stamp import environment
    from mjpoincare.gate import baseline

    path = session.config.stash[_REQUEST].baseline
    assert path is not None
    previous = baseline.load(path) if Path(path).exists() else None
    write_json(baseline.updated(previous, records.items(), environment()), path)
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is not None:
        reporter.write_line(f"mjpoincare: recorded {len(records)} run(s) into the baseline {path}: "
                            + ", ".join(sorted(records)))


class ScenarioCollector(pytest.Collector):
    """One scenario: an item per check it declares at the requested inputs, and ``stable``; nothing is simulated."""

    def collect(self) -> list[pytest.Item]:
        """A :class:`CheckItem` per declared check, then ``stable`` (the scenario runs when the first one does); a
        scenario whose module or declaration does not load: one :class:`BrokenScenarioItem`."""
        from mjpoincare.commands.validation import resolve_values
        from mjpoincare.scenarios import DeclarationError

        request = self.config.stash[_REQUEST]
        try:
            scenario, _, params, settings = resolve_values(self.name, request.assignments, request.preset)
        except DeclarationError as err:
            return [BrokenScenarioItem.from_parent(self, name="declaration", error=str(err))]
        self.declared = tuple(dict.fromkeys([*scenario.checks_for(params, settings), "stable"]))
        return [CheckItem.from_parent(self, name=name) for name in self.declared]


class _MjpoincareItem(pytest.Item):
    """Shared parts: the marker, the scenario name and the report location."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.add_marker(MARKER)

    @property
    def scenario(self) -> str:
        """The scenario this item belongs to."""
        assert self.parent is not None
        return self.parent.name

    def reportinfo(self) -> tuple[Any, int | None, str]:
        """Location shown in headers: ``mjpoincare <scenario>::<name>``."""
        return self.path, None, f"{MARKER} {self.scenario}::{self.name}"


class BrokenDeclaration(Exception):
    """A scenario's module or declaration does not load (the registry's one line naming the plugin and the fix)."""


class BrokenScenarioItem(_MjpoincareItem):
    """The one item of a scenario whose module or declaration does not load (a plugin author's mistake, in the
    registry's one line): it fails, and the other scenarios' items and the project's tests run."""

    def __init__(self, *, error: str, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.error = error

    def runtest(self) -> None:
        """Fail with the registry's line."""
        raise BrokenDeclaration(self.error)

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> Any:
        """The registry's line, no traceback."""
        if not isinstance(excinfo.value, BrokenDeclaration):
            return super().repr_failure(excinfo, style)
        return CheckFailureRepr((self.error,), _Crash(self.error))


class ScenarioCrashed(Exception):
    """A scenario's validation raised (its ``__cause__``) instead of returning a result."""


class CheckFailed(AssertionError):
    """A check's error is not finite or exceeds its tolerance."""

    def __init__(self, check: Check) -> None:
        super().__init__(_summary(check))
        self.check = check


class BaselineChanged(AssertionError):
    """A check's error moved beyond its allowance from the baseline's, or one of the two lacks the check."""


class UndeclaredCheck(AssertionError):
    """The run reported a check its scenario does not declare at these inputs (the declaration is stale)."""


class CheckItem(_MjpoincareItem):
    """One check of a scenario's cached result (the scenario runs at the first of its items): passes when the check
    passed and, against a baseline, did not move beyond its allowance."""

    def runtest(self) -> None:
        """Read the check from the cached result; raise :class:`ScenarioCrashed` if the run raised,
        :class:`CheckFailed` if the check failed, then :class:`BaselineChanged` if it moved from the baseline; the
        ``stable`` item also fails on a reported check no item stands for (:class:`UndeclaredCheck`) and on a
        baseline complaint about a check the run lacks."""
        result = _result(self.config, self.scenario)
        if isinstance(result, Exception):
            raise ScenarioCrashed(f"validation raised {type(result).__name__}: {result}") from result
        changes = self.config.stash[_CHANGES].get(self.scenario, {})
        change = changes.get(self.name)
        check = next((c for c in result.checks if c.name == self.name), None)
        if check is None:
            raise BaselineChanged(change or f"{self.scenario} reported no check {self.name}")
        if self.name == "stable":
            siblings = set(getattr(self.parent, "declared", ()))
            stray = [c.name for c in result.checks if c.name not in siblings]
            if stray:
                raise UndeclaredCheck(f"{self.scenario} reported checks it does not declare at these inputs: "
                                      f"{', '.join(stray)}")
            others = [text for name, text in changes.items() if name not in siblings]
            if others:
                raise BaselineChanged("; ".join(others))
        self.user_properties.extend([("analytic", _fmt(check.analytic)), ("simulated", _fmt(check.simulated)),
                                     ("error", f"{_fmt(check.error)} {check.kind}"),
                                     ("tolerance", _fmt(check.tolerance)), ("unit", check.unit)])
        if not check.passed:
            raise CheckFailed(check)
        if change is not None:
            raise BaselineChanged(change)

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> Any:
        """A failed check as its values, tolerance and reason, a baseline change as its one line (no traceback), a
        crashed run as its own exception and traceback; other errors as usual."""
        error = excinfo.value.__cause__ if isinstance(excinfo.value, ScenarioCrashed) else None
        if error is not None:
            tbstyle = self.config.getoption("tbstyle", "auto")
            return pytest.ExceptionInfo.from_exception(error).getrepr(
                style="long" if tbstyle == "auto" else tbstyle, showlocals=bool(self.config.getoption("showlocals")))
        if isinstance(excinfo.value, (BaselineChanged, UndeclaredCheck)):
            return CheckFailureRepr((str(excinfo.value),), _Crash(str(excinfo.value)))
        if not isinstance(excinfo.value, CheckFailed):
            return super().repr_failure(excinfo, style)
        result = _result(self.config, self.scenario)
        assert not isinstance(result, Exception)
        return CheckFailureRepr(_failure_lines(excinfo.value.check, result, self.config.stash[_REQUEST]),
                                _Crash(_summary(excinfo.value.check)))


@dataclass(frozen=True)
class _Crash:
    """The one-line message pytest's short summary and JUnit XML read (``longrepr.reprcrash.message``)."""

    message: str

    def __str__(self) -> str:
        return self.message


@dataclass(frozen=True)
class CheckFailureRepr:
    """A failed check's report (pytest calls ``toterminal``; xdist and JUnit XML use ``str``)."""

    lines: tuple[str, ...]
    reprcrash: _Crash

    def toterminal(self, tw: Any) -> None:
        """Write the lines to pytest's terminal writer."""
        for line in self.lines:
            tw.line(line)

    def __str__(self) -> str:
        return "\n".join(self.lines)


def _summary(check: Check) -> str:
    """One line: the error against the tolerance, and the two values (the node id names the check)."""
    unit = f" {check.unit}" if check.unit else ""
    if not math.isfinite(check.error):
        why = f"error {_fmt(check.error)} (simulated value missing or not finite)"
    else:
        why = f"{check.kind} error {_fmt(check.error)} > tolerance {_fmt(check.tolerance)}"
    return f"{why}; analytic {_fmt(check.analytic)}{unit}, simulated {_fmt(check.simulated)}{unit}"


def _failure_lines(check: Check, result: Result, request: Request) -> tuple[str, ...]:
    """The failing check's values and reason, then what was run."""
    unit = check.unit or "(dimensionless)"
    lines = [
        f"mjpoincare check {result.scenario}::{check.name} FAILED",
        f"  analytic   {_fmt(check.analytic)}",
        f"  simulated  {_fmt(check.simulated)}",
        f"  error      {_fmt(check.error)} ({check.kind})",
        f"  tolerance  {_fmt(check.tolerance)} ({check.kind})",
        f"  unit       {unit}",
        f"  why        {check.why}",
    ]
    if check.name == "stable":
        lines += [f"  diverged trajectories: {result.diverged}"] if result.diverged else []
        lines += [f"  mujoco warning: {w}" for w in result.warnings]
    lines += [
        request.describe(result.scenario),
        f"  resolved preset={result.preset}  MuJoCo {result.mujoco_version}",
        "  params:   " + " ".join(f"{k}={_fmt(v)}" for k, v in result.params.items()),
        "  settings: " + " ".join(f"{k}={_fmt(v)}" for k, v in result.settings.items()),
    ]
    return tuple(lines)


def _fmt(value: Any) -> str:
    from mjpoincare.core.result import format_value  # loaded with the results it formats, never without --mjpoincare

    return format_value(value)


def pytest_terminal_summary(terminalreporter: Any, config: pytest.Config) -> None:
    """Each validated scenario's check table at the end of the run (not with ``-q``)."""
    results = config.stash.get(_RESULTS, None)
    if not results or terminalreporter.verbosity < 0:
        return
    terminalreporter.write_sep("=", "mjpoincare")
    for name, result in results.items():
        if isinstance(result, Exception):
            terminalreporter.write_line(f"{name}: validation raised {type(result).__name__}: {result}")
        else:
            terminalreporter.write_line(result.table())
