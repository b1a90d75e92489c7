"""The Python API's contract: typed values, the Result record, one exception type, the CLI as a thin layer over it,
and a library call that leaves its caller's process alone (working directory, stdout, MuJoCo's warning handler)."""

from __future__ import annotations

import json
import os
import re
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import mujoco
import pytest

import mjpoincare
from mjpoincare.cli import main
from mjpoincare.core.result import RESULTS_SCHEMA


def test_bad_values_raise_one_exception_type_naming_the_bound() -> None:
    with pytest.raises(mjpoincare.ParameterError, match=r"spokes must be in \[3, 64\] \(got 2\)"):
        mjpoincare.validate("rimless-wheel", spokes=2)
    with pytest.raises(mjpoincare.ParameterError, match="unknown parameter 'spoke'"):
        mjpoincare.validate("rimless-wheel", spoke=8)
    with pytest.raises(mjpoincare.ParameterError, match="unknown scenario"):
        mjpoincare.validate("no-such-system")
    with pytest.raises(mjpoincare.ParameterError, match="seed must be"):
        mjpoincare.validate("rimless-wheel", seed=-1)
    assert issubclass(mjpoincare.ParameterError, ValueError)


@pytest.mark.mujoco
def test_typed_values_and_the_result_record(capsys: pytest.CaptureFixture[str]) -> None:
    """Typed values give the same run as the CLI's text; ``to_dict`` is the CLI's JSON. The run is the gate's
    ``rimless-wheel-friction[fast]`` (its defaults and its preset's settings given as typed values), every check of
    which is gated: it passes, and the CLI exits 0."""
    result = mjpoincare.validate("rimless-wheel-friction", "fast", spokes=10, mu=0.3, timestep=2e-4,
                                 solref_timeconst=4e-4)
    assert result.params["spokes"] == 10 and result.settings["timestep"] == 2e-4
    for check in result.checks:
        for field in ("name", "analytic", "simulated", "error", "tolerance", "passed", "why"):
            assert hasattr(check, field)
    assert result.passed, result.table()
    code = main(["validate", "rimless-wheel-friction", "--set", "spokes=10", "--set", "mu=0.3", "--set",
                 "timestep=2e-4", "--set", "solref_timeconst=4e-4", "--json", "-"])
    document = json.loads(capsys.readouterr().out)
    assert code == 0
    assert document["schema"] == RESULTS_SCHEMA and document["mjpoincare"] == mjpoincare.__version__
    mine = result.to_document()
    for volatile in ("timing",):  # wall-clock times differ between two runs
        mine["results"][0].pop(volatile), document["results"][0].pop(volatile)
    assert mine == document


@pytest.mark.mujoco
def test_the_readmes_api_example_runs_as_written_and_passes(capsys: pytest.CaptureFixture[str]) -> None:
    """The README's Python API block, executed as it is written: its run passes, and its table is printed."""
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    [block] = [b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "mjpoincare.validate(" in b]
    namespace: dict[str, object] = {}
    exec(compile(block, "README.md", "exec"), namespace)  # the README's own example
    result = namespace["result"]
    assert isinstance(result, mjpoincare.Result) and result.passed, result.table()
    assert "verdict" in capsys.readouterr().out


@pytest.mark.mujoco
def test_threads_give_the_serial_results_and_leave_cwd_and_stdout_alone(capfd: pytest.CaptureFixture[str]) -> None:
    """Two validations in two threads of one process: the same checks as serial runs, while the caller's working
    directory never changes and its prints (on file descriptor 1) still arrive. The runs take a coarse step (contact
    time constant 2 steps; every check finite): a tenth of their time at the fast preset, still half a second each."""
    coarse = {"timestep": 8e-4, "solref_timeconst": 1.6e-3}
    cases = [("rimless-wheel", coarse), ("rimless-wheel", {**coarse, "spokes": 10, "slope": 0.1})]
    serial = [mjpoincare.validate(name, **values).to_dict()["checks"] for name, values in cases]
    cwd = os.getcwd()
    seen_cwd: set[str] = set()
    done = threading.Event()

    def watch() -> None:
        while not done.is_set():
            seen_cwd.add(os.getcwd())
            print("caller still prints", flush=True)
            time.sleep(0.01)

    watcher = threading.Thread(target=watch)
    watcher.start()
    try:
        with ThreadPoolExecutor(2) as pool:
            threaded = list(pool.map(lambda case: mjpoincare.validate(case[0], **case[1]).to_dict()["checks"], cases))
    finally:
        done.set()
        watcher.join()
    assert threaded == serial
    assert seen_cwd == {cwd}
    out = capfd.readouterr().out
    assert out.count("caller still prints") >= 10


@pytest.mark.mujoco
def test_warnings_go_into_the_result_not_a_file_or_stdout(tmp_path: Path, capfd: pytest.CaptureFixture[str]) -> None:
    """A diverging start: MuJoCo's warning text is in the result, nothing is printed or written to the working
    directory, and MuJoCo's warning handler is the caller's again afterwards."""
    import numpy as np

    from mjpoincare.commands.validation import resolve_inputs
    from mjpoincare.scenarios import rimless_wheel as rw
    from mjpoincare.simulation.simulate import initial_states, rollout_batch

    _, _, params, settings = resolve_inputs("rimless-wheel", {}, "fast")
    model = rw.build(params, settings)
    bad = initial_states(model, np.array([[0.0, 1.0, 0.0]]), np.array([[1e12, 0.0, 1e12]]))
    before = mujoco.get_mju_user_warning()
    report = rollout_batch(model, bad, 50, lambda _: None, threads=2, chunk_steps=25)
    assert mujoco.get_mju_user_warning() is before
    assert report.diverged.tolist() == [True]
    assert any("WARNING: Nan, Inf or huge value" in line for line in report.warnings), report.warnings
    captured = capfd.readouterr()
    assert "WARNING" not in captured.out + captured.err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.mujoco
def test_a_foreign_warning_handler_is_kept_and_not_called_from_worker_threads() -> None:
    """dm_control installs a ctypes warning handler at import (it raises when called with a Python str): a diverging
    rollout with it installed neither aborts nor calls it, and it is MuJoCo's handler again afterwards."""
    import dm_control.mujoco  # noqa: F401  (installs dm_control's handler)
    import numpy as np

    from mjpoincare.commands.validation import resolve_inputs
    from mjpoincare.scenarios import rimless_wheel as rw
    from mjpoincare.simulation.simulate import initial_states, rollout_batch

    foreign = mujoco.get_mju_user_warning()
    assert foreign is not None
    _, _, params, settings = resolve_inputs("rimless-wheel", {}, "fast")
    model = rw.build(params, settings)
    bad = initial_states(model, np.array([[0.0, 1.0, 0.0]]), np.array([[1e12, 0.0, 1e12]]))
    report = rollout_batch(model, np.repeat(bad, 3, axis=0), 50, lambda _: None, threads=2, chunk_steps=25)
    assert report.diverged.all() and report.warnings
    assert mujoco.get_mju_user_warning() is foreign


@pytest.mark.mujoco
def test_a_check_that_disappears_fails_the_api_and_the_cli(monkeypatch: pytest.MonkeyPatch,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    """A scenario whose evaluate stops reporting a check it declares: the API's result fails on that check alone,
    named and of kind ``missing``, and ``mjpoincare validate`` exits 1 with it failing in the table. The run is
    rimless-wheel on a coarse step (every check passes: a tenth of the fast preset's time) without its eigenvalue."""
    from dataclasses import replace

    from mjpoincare.core.params import Values
    from mjpoincare.scenarios import REGISTRY, Evaluation

    real = REGISTRY["rimless-wheel"]

    def evaluate(params: Values, settings: Values, preset: str, seed: int) -> Evaluation:
        run = real.evaluate(params, settings, preset, seed)
        return replace(run, checks=[c for c in run.checks if c.name != "eigenvalue"])

    monkeypatch.setitem(REGISTRY, "rimless-wheel", replace(real, evaluate=evaluate))
    result = mjpoincare.validate("rimless-wheel", timestep=8e-4, solref_timeconst=1.6e-3)
    assert not result.passed
    assert [(c.name, c.kind) for c in result.checks if not c.passed] == [("eigenvalue", "missing")], result.table()
    assert "did not report it" in next(c.why for c in result.checks if c.name == "eigenvalue")
    assert f"1 of {len(result.checks)} checks failed:\n  eigenvalue: not measured; " in result.table()
    code = main(["validate", "rimless-wheel", "--set", "timestep=8e-4", "--set", "solref_timeconst=1.6e-3"])
    out = capsys.readouterr().out
    assert code == 1
    assert re.search(r"^eigenvalue\s.*\bmissing\s.*FAIL$", out, re.M), out


def test_a_scenarios_input_check_runs_once_per_process_for_the_same_values(monkeypatch: pytest.MonkeyPatch) -> None:
    """The command's check before any simulation, the cost check and the validation resolve the same inputs: the
    scenario's own check (the compass biped's shooting, for one) runs for the first only, again for other values,
    and a refused input is refused every time."""
    from dataclasses import replace

    from mjpoincare import scenarios
    from mjpoincare.commands.validation import resolve_inputs, run_steps
    from mjpoincare.core.params import ParameterError

    scenario = scenarios.get("rimless-wheel")
    calls: list[object] = []

    def counted(params: dict[str, object]) -> None:
        calls.append(params["slope"])
        scenario.check_params(params)

    monkeypatch.setitem(scenarios.REGISTRY, scenario.name, replace(scenario, check_params=counted))
    for _ in range(2):
        resolve_inputs("rimless-wheel", {"slope": "0.0812"}, "fast")
        run_steps("rimless-wheel", {"slope": "0.0812"}, "fast")
    assert calls == [0.0812]
    resolve_inputs("rimless-wheel", {"slope": "0.0813"}, "fast")
    assert calls == [0.0812, 0.0813]
    for _ in range(2):
        with pytest.raises(ParameterError, match="slope"):
            resolve_inputs("rimless-wheel", {"slope": "0.01"}, "fast")
    assert calls == [0.0812, 0.0813, 0.01, 0.01]
