"""The pytest plugin (``pytest --mjpoincare ...``), run in a subprocess so the ``pytest11`` entry point loads it."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest
from conftest import all_gated

# imported here, before any pytester test: pytester restores sys.modules after each test, and scipy's extensions,
# once dropped from it, cannot be loaded again in the same process
from mjpoincare.commands.validation import resolve_values

pytest_plugins = ["pytester"]

NODE = re.compile(r"^mjpoincare::rimless-wheel::(\w+) (PASSED|FAILED)", re.MULTILINE)


def nodes(scenario: str) -> re.Pattern[str]:
    """The verbose report line of each of ``scenario``'s items: (check, verdict)."""
    return re.compile(rf"^mjpoincare::{re.escape(scenario)}::(\w+) (PASSED|FAILED)", re.MULTILINE)


#: A conftest that records each scenario a process validates (one line per run, in runs.txt) and then crashes it.
COUNTING_CRASH = """
    import os
    import mjpoincare.api

    def crash(scenario, *args, **kwargs):
        with open(os.path.join(os.path.dirname(__file__), "runs.txt"), "a") as log:
            log.write(scenario + "\\n")
        raise RuntimeError(f"simulated crash in {scenario}")

    mjpoincare.api.validate = crash
"""


@pytest.fixture
def pytester(pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch) -> pytest.Pytester:
    """pytester with plugin autoloading on (as in a user's CI job) and the CI env vars off (stable summary)."""
    for name in ("PYTEST_DISABLE_PLUGIN_AUTOLOAD", "PYTEST_PLUGINS", "CI", "BUILD_NUMBER"):
        monkeypatch.delenv(name, raising=False)
    return pytester


def run(pytester: pytest.Pytester, *args: str) -> pytest.RunResult:
    """``pytest *args`` in a fresh interpreter, in pytester's directory."""
    result = pytester.runpytest_subprocess(*args, timeout=120)
    assert not (pytester.path / "MUJOCO_LOG.TXT").exists()
    return result


@pytest.mark.mujoco
def test_empty_dir_passes_with_one_item_per_check(pytester: pytest.Pytester) -> None:
    import mjpoincare

    scenario = all_gated("rimless-wheel-friction[fast]")  # every check gated: the run passes with margin
    result = run(pytester, "--mjpoincare", scenario, "--mjpoincare-preset", "fast", "-v")
    assert result.ret == pytest.ExitCode.OK, result.stdout.str()
    expected = [c.name for c in mjpoincare.validate(scenario, preset="fast").checks]
    assert nodes(scenario).findall(result.stdout.str()) == [(name, "PASSED") for name in expected]
    assert {"eigenvalue", "stable"} <= set(expected)
    result.assert_outcomes(passed=len(expected))


@pytest.mark.mujoco
def test_failing_check_reports_values_beside_project_tests(pytester: pytest.Pytester) -> None:
    pytester.makepyfile(test_project="def test_project():\n    assert True\n")
    result = run(pytester, "--mjpoincare", "rimless-wheel", "--mjpoincare-set", "timestep=0.01", "-v")
    out = result.stdout.str()
    assert result.ret == pytest.ExitCode.TESTS_FAILED, out
    assert "test_project.py::test_project PASSED" in out
    failed = [name for name, verdict in NODE.findall(out) if verdict == "FAILED"]
    assert failed
    report = out.split("= FAILURES =")[1]
    for field in ("analytic", "simulated", "error", "tolerance", "unit", "why"):
        assert re.search(rf"^  {field} +\S", report, re.MULTILINE), field
    assert f"mjpoincare check rimless-wheel::{failed[0]} FAILED" in report
    assert "set: timestep=0.01" in report
    assert re.search(rf"^FAILED mjpoincare::rimless-wheel::{failed[0]} - \w+ error \d", out, re.MULTILINE)


@pytest.mark.parametrize(("args", "message"), [
    (["--mjpoincare", "rimless-wheel,no-such-wheel"], "unknown scenario 'no-such-wheel' (known: compass-biped"),
    (["--mjpoincare", "rimless-wheel", "--mjpoincare-set", "timestep=1"], "timestep must be in (0, 0.05] s (got 1)"),
    (["--mjpoincare", "rimless-wheel", "--mjpoincare-set", "timestep"], "--mjpoincare-set expects NAME=VALUE"),
    (["--mjpoincare-set", "timestep=2e-4"], "--mjpoincare-set given without --mjpoincare"),
    (["--mjpoincare", "rimless-wheel", "--mjpoincare-baseline", "/proc/b.json"], "--mjpoincare-baseline /proc/b.json"),
    (["--mjpoincare", "rimless-wheel", "--mjpoincare-update-baseline"],
     "--mjpoincare-update-baseline needs --mjpoincare-baseline PATH"),
])
def test_bad_input_is_a_one_line_usage_error(pytester: pytest.Pytester, args: list[str], message: str) -> None:
    result = run(pytester, *args)
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    lines = [line for line in result.stderr.lines if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("ERROR: ") and message in lines[0], lines
    assert "collected" not in result.stdout.str()


def test_a_crash_fails_the_scenarios_items_and_the_run_goes_on(pytester: pytest.Pytester) -> None:
    pytester.makeconftest(COUNTING_CRASH)
    pytester.makepyfile(test_project="def test_project():\n    assert True\n")
    result = run(pytester, "--mjpoincare", "rimless-wheel", "-rf")
    assert result.ret == pytest.ExitCode.TESTS_FAILED
    outcomes = result.parseoutcomes()
    assert outcomes["passed"] == 1 and outcomes["failed"] >= 2, outcomes
    result.stdout.fnmatch_lines(["FAILED mjpoincare::rimless-wheel::stable - RuntimeError: simulated crash*"])
    assert (pytester.path / "runs.txt").read_text().split() == ["rimless-wheel"]  # run once for all its items
    assert "runtest" not in result.stdout.str()  # the run's own traceback, not pytest's runner frames


@pytest.mark.mujoco
def test_a_broken_plugin_is_one_failing_item_and_the_rest_run(pytester: pytest.Pytester,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    """A plugin whose declaration does not load, named in the ini beside a built-in scenario: its one item fails with
    the registry's one line, and the built-in scenario's checks and the project's test run and pass."""
    plugin = pytester.path / "plugin"
    shutil.copytree(Path(__file__).parent / "plugin_example", plugin, ignore=shutil.ignore_patterns("__pycache__"))
    source = plugin / "toy_ball.py"
    source.write_text(source.read_text().replace('"fast": {"timestep": 1e-4,', '"fast": {"timestpe": 1e-4,'))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(plugin), os.environ.get("PYTHONPATH", "")]))
    pytester.makeini("[pytest]\nmjpoincare = bouncing-ball rimless-wheel\nmjpoincare_preset = fast\n")
    pytester.makepyfile(test_project="def test_project():\n    assert True\n")
    result = run(pytester, "-v", "-p", "no:cacheprovider")
    declared = resolve_values("rimless-wheel", {}, "fast")[0].checks
    assert result.ret == pytest.ExitCode.TESTS_FAILED and "INTERNALERROR" not in result.stdout.str()
    assert result.parseoutcomes() == {"failed": 1, "passed": len(declared) + 2}, result.stdout.str()
    result.stdout.fnmatch_lines(["mjpoincare::bouncing-ball::declaration FAILED*"])
    assert "\nplugin toy-ball (toy_ball:BOUNCING_BALL): presets['fast'] sets 'timestpe'" in result.stdout.str()
    assert sorted(nodes("rimless-wheel").findall(result.stdout.str())) == sorted(
        (check, "PASSED") for check in (*declared, "stable"))


def test_without_option_the_plugin_adds_nothing(pytester: pytest.Pytester) -> None:
    assert run(pytester).ret == pytest.ExitCode.NO_TESTS_COLLECTED
    pytester.makepyfile(test_project="""
        import sys

        def test_plugin_loaded_but_light():
            assert "mjpoincare.pytest_plugin" in sys.modules
            assert not {"mujoco", "numpy", "mjpoincare.commands.validation"} & set(sys.modules)
    """)
    result = run(pytester, "-v")
    result.assert_outcomes(passed=1)
    assert "mjpoincare::" not in result.stdout.str()


def test_a_node_id_of_the_plugin_selects_its_item(pytester: pytest.Pytester) -> None:
    """``pytest mjpoincare::<scenario>::<check>`` (as a node id is passed for a file's test) collects the scenario and
    selects that item; the project's named tests run beside it."""
    pytester.makeconftest(COUNTING_CRASH)
    pytester.makepyfile(test_mine="def test_x():\n    pass\n")
    result = run(pytester, "--collect-only", "-q", "test_mine.py::test_x", "mjpoincare::rimless-wheel::eigenvalue")
    assert result.ret == pytest.ExitCode.OK, result.stdout.str()
    assert [line for line in result.stdout.lines if "::" in line] == ["test_mine.py::test_x",
                                                                       "mjpoincare::rimless-wheel::eigenvalue"]
    refused = run(pytester, "mjpoincare::")
    assert refused.ret == pytest.ExitCode.USAGE_ERROR and "mjpoincare::<scenario>[::<check>]" in refused.stderr.str()


@pytest.mark.mujoco
def test_a_missing_baseline_is_recorded_and_every_item_fails_saying_so(pytester: pytest.Pytester) -> None:
    """As pytest-regressions: a baseline that does not exist is created from the session's runs, each item fails
    naming it, and the next session compares with it and passes."""
    base = ("--mjpoincare", "rimless-wheel", "--mjpoincare-baseline", "new.json", "-rf")
    first = run(pytester, *base)
    assert first.ret == pytest.ExitCode.TESTS_FAILED and (pytester.path / "new.json").is_file(), first.stdout.str()
    assert "baseline new.json did not exist: this run is recorded into it; run again to compare" in first.stdout.str()
    assert run(pytester, *base).ret == pytest.ExitCode.OK


@pytest.mark.mujoco
def test_a_baseline_catches_a_timestep_one_percent_off_that_every_tolerance_passes(pytester: pytest.Pytester) -> None:
    """Recorded with ``--mjpoincare-update-baseline``, the same run passes against it; at a timestep 1 % off the
    preset's, every check still passes its tolerance and at least one item fails on the baseline, naming the check,
    the old and new errors, the resolution and the allowance."""
    from mjpoincare import scenarios

    scenario = all_gated("rimless-wheel[fast]")
    timestep = 1.01 * float(scenarios.get(scenario).presets["fast"]["timestep"])
    base = ("--mjpoincare", scenario, "--mjpoincare-preset", "fast", "--mjpoincare-baseline", "b.json", "-v")
    recorded = run(pytester, *base, "--mjpoincare-update-baseline")
    assert recorded.ret == pytest.ExitCode.OK and (pytester.path / "b.json").is_file(), recorded.stdout.str()
    assert "mjpoincare: recorded 1 run(s) into the baseline b.json: rimless-wheel" in recorded.stdout.str()
    again = run(pytester, *base)
    assert again.ret == pytest.ExitCode.OK, again.stdout.str()
    moved = run(pytester, *base, "--mjpoincare-set", f"timestep={timestep!r}")
    out = moved.stdout.str()
    assert moved.ret == pytest.ExitCode.TESTS_FAILED, out
    assert "mjpoincare check" not in out, "a tolerance failed: the change is not below the tolerance"
    failed = [name for name, verdict in nodes(scenario).findall(out) if verdict == "FAILED"]
    assert failed, out
    assert re.search(rf"rimless-wheel\[fast\]::{failed[0]}: error \S+ -> \S+: changed \S+, \S+ x its allowance \S+ "
                     r"\(the larger of 3 x its resolution \S+ and 1e-06 x its tolerance\)",
                     out), out


def test_collect_only_simulates_nothing(pytester: pytest.Pytester) -> None:
    """The items are the declared checks and ``stable``: collected without a run (the validation would crash)."""
    pytester.makeconftest(COUNTING_CRASH)
    result = run(pytester, "--collect-only", "-q", "--mjpoincare", "rimless-wheel")
    assert result.ret == pytest.ExitCode.OK, result.stdout.str()
    scenario, _, params, settings = resolve_values("rimless-wheel", {}, None)
    expected = [f"mjpoincare::rimless-wheel::{name}" for name in (*scenario.checks_for(params, settings), "stable")]
    assert [line for line in result.stdout.lines if line.startswith("mjpoincare::")] == expected
    assert not (pytester.path / "runs.txt").exists()


def test_ini_options_are_read_and_checked(pytester: pytest.Pytester) -> None:
    """``mjpoincare``, ``mjpoincare_preset`` and ``mjpoincare_set`` from pytest.ini: the scenario is collected, and a
    bad value there is the same one-line usage error as on the command line."""
    pytester.makeconftest(COUNTING_CRASH)
    pytester.makeini("[pytest]\nmjpoincare = rimless-wheel\nmjpoincare_preset = fast\n")
    collected = run(pytester, "--collect-only", "-q")
    assert collected.ret == pytest.ExitCode.OK, collected.stdout.str()
    assert "mjpoincare::rimless-wheel::stable" in collected.stdout.str()
    assert "preset=fast" in run(pytester, "--collect-only").stdout.str()
    pytester.makepyfile(test_mine="def test_x():\n    pass\n")
    named = run(pytester, "--collect-only", "-q", "test_mine.py::test_x")
    assert named.ret == pytest.ExitCode.OK and "mjpoincare::" not in named.stdout.str(), named.stdout.str()
    assert "mjpoincare::rimless-wheel::stable" in run(pytester, "--collect-only", "-q", "test_mine.py",
                                                      "--mjpoincare", "rimless-wheel").stdout.str()
    pytester.makeini("[pytest]\nmjpoincare = rimless-wheel\nmjpoincare_set = timestep=1\n")
    refused = run(pytester)
    assert refused.ret == pytest.ExitCode.USAGE_ERROR
    assert "timestep must be in (0, 0.05] s (got 1)" in refused.stderr.str()


def test_under_xdist_loadscope_each_scenario_runs_once(pytester: pytest.Pytester) -> None:
    """With ``-n 2 --dist loadscope`` each scenario's items share a worker, so each scenario is validated once; every
    item of a crashed run fails with the crash."""
    pytester.makeconftest(COUNTING_CRASH)
    result = run(pytester, "-n", "2", "--dist", "loadscope", "--mjpoincare", "rimless-wheel,compass-biped", "-rf")
    assert result.ret == pytest.ExitCode.TESTS_FAILED
    runs = (pytester.path / "runs.txt").read_text().split()
    assert sorted(runs) == ["compass-biped", "rimless-wheel"], runs
    failed = [line for line in result.stdout.lines if line.startswith("FAILED mjpoincare::")]
    assert failed and all(" - RuntimeError: simul" in line for line in failed)
