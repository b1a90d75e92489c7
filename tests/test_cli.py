"""The CLI's contract: exit codes, one-line errors naming the parameter, nothing written on bad input."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mjpoincare.cli import main


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [
        ("spokes=2", "spokes must be in [3, 64] (got 2)"),
        ("slope=-0.1", "slope must be in (0, 1.5708) rad (got -0.1)"),
        ("mu=-1", "mu must be in [0, 1000] (got -1)"),
        ("slope=0.3", "slope must be in (0.0682, 0.2621) rad for spokes=8"),
        ("slope=0.05", "above the existence bound"),
        ("mu=0.3", "mu must be >= 0.4142"),
        ("spokes=5", "spokes=5 has no flight-free rolling gait"),
        ("spokez=8", "unknown parameter 'spokez'"),
        ("slope=abc", "slope must be a number"),
        ("timestep=0", "timestep must be in (0, 0.05]"),
        ("integrator=verlet", "integrator must be one of euler, implicit, implicitfast, rk4"),
    ],
)
def test_bad_input_exits_2_with_one_line(assignment: str, needle: str, tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    out_file = tmp_path / "result.json"
    code = main(["validate", "rimless-wheel", "--set", assignment, "--json", str(out_file)])
    captured = capsys.readouterr()
    assert code == 2
    assert needle in captured.err
    assert captured.err.count("\n") == 1 and "Traceback" not in captured.err
    assert not out_file.exists()


def test_unknown_scenario_and_preset(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "no-such-wheel"]) == 2
    assert "unknown scenario 'no-such-wheel'" in capsys.readouterr().err
    assert main(["validate", "rimless-wheel", "--preset", "turbo"]) == 2
    assert "preset must be one of fast, accurate" in capsys.readouterr().err


def test_list_shows_scenarios_and_parameters(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "rimless-wheel" in out and "spokes = 8" in out and "presets: fast, accurate" in out


@pytest.mark.parametrize("command", [
    ["validate", "rimless-wheel", "--json", "/proc/mjpoincare-x.json"],
    ["validate", "rimless-wheel", "--report", "/proc/mjpoincare-report"],
    ["sweep", "rimless-wheel", "--param", "slope", "--values", "0.1,0.12", "--json", "/proc/x.json"],
    ["sweep", "slotted-skate", "--grid", "x=-1:0:2,y=0.1:0.5:2", "-o", "/proc/x.png"],
    ["stress", "rimless-wheel", "--json", "/proc/x.json"],
    ["bench", "rimless-wheel", "--quick", "--json", "/proc/x.json"],
    ["bench", "rimless-wheel", "--quick", "-o", "/proc/x.png"],
    ["render", "rimless-wheel", "-o", "/proc/x.mp4"],
])
def test_unwritable_output_exits_2_before_any_simulation(command: list[str], capsys: pytest.CaptureFixture[str],
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    """An output path that cannot be written is refused first: one line naming the option, exit 2, and no rollout
    (every rollout goes through ``mujoco_c._native_chunk``, which fails this test if reached). The seam's self-test
    (a tiny model, cached per process) runs first, as any earlier validation in the process would have run it."""
    from mjpoincare.engines.backends import mujoco_c
    from mjpoincare.simulation import seam_check

    seam_check.require(tuple(seam_check.MECHANISMS))

    def no_simulation(*_: object, **__: object) -> None:
        raise AssertionError("simulated before checking the output path")

    monkeypatch.setattr(mujoco_c, "_native_chunk", no_simulation)
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot be written" in err and "/proc/" in err, err


def test_interrupt_exits_130_in_one_line(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """Ctrl-C during a command: one line on stderr, no traceback, exit 130 (128 + SIGINT)."""
    from mjpoincare import api

    def interrupted(*_: object, **__: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(api, "run_validation", interrupted)
    assert main(["validate", "rimless-wheel", "--workers", "1"]) == 130
    err = capsys.readouterr().err
    assert err == "mjpoincare: interrupted\n", err



@pytest.mark.mujoco
def test_interrupt_stops_the_worker_processes_at_once(tmp_path: Path) -> None:
    """Ctrl-C (SIGINT to the process group) during a sweep on two worker processes: the command exits 130 within
    seconds with one line on stderr, and no worker is left running (they leave the interrupt to the parent, which
    stops them)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    run = subprocess.Popen([sys.executable, "-m", "mjpoincare", "sweep", "rimless-wheel", "--param", "slope",
                            "--values", "0.08:0.2:200", "--workers", "2", "--json", str(tmp_path / "s.json")],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                           preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    time.sleep(4.0)
    os.killpg(run.pid, signal.SIGINT)
    start = time.perf_counter()
    _, err = run.communicate(timeout=30)
    assert run.returncode == 130 and time.perf_counter() - start < 10, err
    assert err.splitlines()[-1] == "mjpoincare: interrupted" and "Traceback" not in err, err
    time.sleep(0.5)
    with pytest.raises(ProcessLookupError):
        os.killpg(run.pid, 0)  # the group is empty: no worker survived its parent


def test_list_ranges_finds_where_a_scenarios_own_checks_refuse(capsys: pytest.CaptureFixture[str]) -> None:
    """``list NAME --ranges``: rimless-wheel's slope is declared (0, pi/2) but its existence and no-flight bounds
    refuse outside about (0.0682, 0.2621) at the defaults; each reported end is accepted and 0.2 % past it is
    refused."""
    from mjpoincare.commands.validation import resolve_values
    from mjpoincare.core.params import ParameterError

    assert main(["list", "rimless-wheel", "--ranges"]) == 0
    out = capsys.readouterr().out
    line = next(line for line in out.splitlines() if line.startswith("  slope = "))
    match = re.search(r"accepted at the defaults: \[([\d.e+-]+), ([\d.e+-]+)\]", line)
    assert match is not None, line
    low, high = float(match[1]), float(match[2])
    assert 0.068 < low < 0.0685 and 0.261 < high < 0.263
    for inside, outside in ((low, low * (1 - 2e-3)), (high, high * (1 + 2e-3))):
        resolve_values("rimless-wheel", {"slope": repr(inside)}, None)
        with pytest.raises(ParameterError, match="slope must be in"):
            resolve_values("rimless-wheel", {"slope": repr(outside)}, None)
    assert "leg_length = 1.0  (spoke length l, m; in (0, 100])" in out  # nothing refused: the declared range
    assert main(["list", "rimless_wheel"]) == 2
    assert "did you mean 'rimless-wheel'" in capsys.readouterr().err
