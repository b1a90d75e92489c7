"""The sweep command: value parsing, bifurcation location, and a small real sweep."""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from conftest import require_module

from mjpoincare.cli import main
from mjpoincare.commands.sweep import crossing, verdict
from mjpoincare.core.params import ParameterError, parse_values

#: Coarse steps for the sweeps, which test the command rather than accuracy (a tenth to a third of a validation's time
#: at the fast preset; every check passes there): the wheel's contact time constant, and the skate's peg's, at 2 steps.
WHEEL_COARSE = ["--set", "timestep=8e-4", "--set", "solref_timeconst=1.6e-3"]
SKATE_COARSE = ["--set", "timestep=2e-3", "--set", "solref_timeconst=4e-3"]


def test_parse_values() -> None:
    assert parse_values("0.07, 0.072") == ["0.07", "0.072"]
    assert parse_values("0:1:3") == ["0", "0.5", "1"]
    with pytest.raises(ParameterError):
        parse_values("a:b:c")


def test_crossing_interpolates_and_extrapolates() -> None:
    assert crossing([0.0, 1.0, 2.0], [0.0, -0.5, -1.5]) == pytest.approx(1.5)
    assert crossing([0.0, 1.0], [-0.2, -0.6]) == pytest.approx(2.0)
    assert math.isnan(crossing([0.0, 1.0], [-0.5, -0.5]))


def test_verdict_names_the_failed_checks() -> None:
    assert verdict({"passed": True, "failed": []}) == "PASS"
    assert verdict({"passed": False, "failed": ["eigenvalue", "stable"]}) == "FAIL (eigenvalue, stable)"


@pytest.mark.mujoco
def test_wheel_sweep_over_slope(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep.json"
    plot = tmp_path / "sweep.png"
    code = main(["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08,0.12", *WHEEL_COARSE,
                 "--json", str(out), "-o", str(plot)])
    document = json.loads(out.read_text())
    rows = document["rows"]
    assert document["schema"] == "mjpoincare.sweep/1" and set(rows[0]["tolerances"]) == set(rows[0]["errors"])
    assert plot.read_bytes().startswith(b"\x89PNG")
    assert code == (0 if all(r["passed"] for r in rows) else 1)  # each row's verdict is the gate's to assert
    assert [r["slope"] for r in rows] == [0.08, 0.12]
    assert all(abs(r["fitted_lowest"] - 0.5) < 0.02 for r in rows)  # beta^2 = 0.5 for 8 spokes at any slope
    table = capsys.readouterr().out
    assert "lowest Re" in table and "| verdict" in table
    assert [line.rstrip(" |").rsplit("| ", 1)[-1].split()[0] for line in table.splitlines()[2:4]] == [
        "PASS" if r["passed"] else "FAIL" for r in rows]  # each row's verdict, the exit code's reason
    assert main(["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08,0.5"]) == 2  # checked first


@pytest.mark.mujoco
def test_parallel_sweep_resumes_from_its_results_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep.json"
    args = ["sweep", "rimless-wheel", "--param", "slope", *WHEEL_COARSE, "--json", str(out)]
    code = main([*args, "--values", "0.08,0.1", "--workers", "2"])
    first = json.loads(out.read_text())
    assert code == (0 if all(r["passed"] for r in first["rows"]) else 1)
    assert [r["slope"] for r in first["rows"]] == [0.08, 0.1] and first["workers"] == 2
    capsys.readouterr()
    code = main([*args, "--values", "0.08,0.1,0.12", "--resume"])
    assert "1 points run (2 resumed)" in capsys.readouterr().out
    rows = json.loads(out.read_text())["rows"]
    assert code == (0 if all(r["passed"] for r in rows) else 1)
    assert [r["slope"] for r in rows] == [0.08, 0.1, 0.12]
    assert rows[:2] == first["rows"]  # the finished points were not redone
    assert main([*args, "--values", "0.08", "--resume", "--set", "spokes=10"]) == 2  # a different sweep's file


@pytest.mark.mujoco
def test_dask_engine_gives_the_same_rows(tmp_path: Path) -> None:
    require_module("dask.distributed", "dask")
    local, dask = tmp_path / "local.json", tmp_path / "dask.json"
    args = ["sweep", "slotted-skate", "--param", "Omega0", "--values", "0.1,0.2", *SKATE_COARSE]
    code = main([*args, "--json", str(local)])
    assert main([*args, "--json", str(dask), "--engine", "dask", "--workers", "2"]) == code
    strip = [{k: v for k, v in r.items() if k != "wall_s"} for r in json.loads(local.read_text())["rows"]]
    assert [{k: v for k, v in r.items() if k != "wall_s"} for r in json.loads(dask.read_text())["rows"]] == strip


def test_bad_engine_and_resume_without_file_are_refused() -> None:
    base = ["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08"]
    assert main([*base, "--engine", "ray"]) == 2
    assert main([*base, "--workers", "0"]) == 2
    assert main([*base, "--resume"]) == 2


def _no_simulation(monkeypatch: pytest.MonkeyPatch) -> None:
    """Fail the test if a scenario's rollout starts (every rollout goes through ``mujoco_c._native_chunk``; the
    seam's self-test, cached per process, runs first)."""
    from mjpoincare.engines.backends import mujoco_c
    from mjpoincare.simulation import seam_check

    seam_check.require(tuple(seam_check.MECHANISMS))

    def refuse(*_: object, **__: object) -> None:
        raise AssertionError("simulated before refusing")

    monkeypatch.setattr(mujoco_c, "_native_chunk", refuse)


@pytest.mark.parametrize(("command", "needle"), [
    (["sweep", "rimless-wheel", "--grid", "x=0:1:2,y=0.1:1:2"], "--grid: rimless-wheel has no region map"),
    (["sweep", "slotted-skate", "--param", "slope", "--values", "0.1"], "unknown parameter 'slope'"),
])
def test_a_facet_the_scenario_lacks_is_refused(command: list[str], needle: str, monkeypatch: pytest.MonkeyPatch,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    _no_simulation(monkeypatch)
    assert main(command) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err


def _with_facets(monkeypatch: pytest.MonkeyPatch, **facets: object) -> None:
    """The friction wheel, as every lookup of it answers, with ``facets`` (its region map, its own sweeps) replaced."""
    from mjpoincare import scenarios

    wheel = replace(scenarios.get("rimless-wheel-friction"), **facets)
    monkeypatch.setattr(scenarios, "get", lambda name: wheel)


def test_a_region_map_gets_resolved_inputs_and_the_command_writes_its_data(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """``--grid`` over the map's axes and the inputs are checked before the map runs; the map gets the resolved inputs
    and the axes' values, and the command prints its summary, writes the PNG (the map's default path) and the JSON
    (``scenario``, then the map's data, NaN as null) and exits by the map's verdict."""
    from mjpoincare.scenarios.base import RegionMap
    from mjpoincare.scenarios.rimless_wheel_friction import basins

    _no_simulation(monkeypatch)
    calls: list[tuple[object, ...]] = []

    def compute(p: Mapping[str, object], s: Mapping[str, object], preset: str, x: np.ndarray, y: np.ndarray, *,
                workers: int) -> dict[str, object]:
        calls.append((p["mu"], s["timestep"], preset, x.tolist(), y.tolist(), workers))
        return {"cells": np.array([[1.0, math.nan]]), "agrees": False}

    region = RegionMap(axes=basins.AXES, output="maps/{scenario}.png", compute=compute,
                       summary=lambda data: f"{data['cells'].size} cells",
                       plot=lambda data, path: Path(path).write_text("png"), passed=lambda data: bool(data["agrees"]))
    _with_facets(monkeypatch, region_map=region)
    out = tmp_path / "map.json"
    args = ["sweep", "rimless-wheel-friction", "--set", "mu=0.4", "--preset", "coarse", "--workers", "3"]
    assert main([*args, "--grid", "theta_dot0=0.5:1:2,x_dot0=0:0.1:3", "--json", str(out)]) == 1
    assert calls == [(0.4, 4e-4, "coarse", [0.5, 1.0], [0.0, 0.05, 0.1], 3)]
    png = Path("maps/rimless-wheel-friction.png")
    assert capsys.readouterr().out == f"2 cells\nwrote {png}\n" and png.read_text() == "png"
    assert json.loads(out.read_text()) == {"scenario": "rimless-wheel-friction", "cells": [[1.0, None]],
                                           "agrees": False}
    for bad, needle in [(["--grid", "theta_dot0=0:1:2,x_dot0=0:0.1:3"], "--grid theta_dot0 = post-impact"),
                        (["--grid", "theta_dot0=0.5:1:2,x_dot0=0:0.1:3", "--set", "kappa=0"], "kappa must be in")]:
        assert main([*args, *bad]) == 2
        err = capsys.readouterr().err
        assert needle in err and err.count("\n") == 1, err
    assert len(calls) == 1


def test_a_scenario_sweep_gets_resolved_inputs_and_the_command_resumes_its_rows(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    """A scenario's own ``--param`` sweep: the values are checked against the parameter's range before the sweep
    plans; the command runs the planned jobs into the results file, one row per value in increasing order, resumes
    from it (a NaN written as null read back as NaN), prints the sweep's table and the timing, writes the summary and
    exits by the sweep's verdict."""
    from mjpoincare.scenarios.base import ParamSweep

    _no_simulation(monkeypatch)
    planned: list[tuple[list[float], int]] = []
    computed: list[float] = []

    def plan(p: Mapping[str, object], s: Mapping[str, object], values: list[float], *,
             workers: int) -> list[tuple[object, ...]]:
        planned.append((list(values), workers))
        return [([v],) for v in values]

    def compute(p: Mapping[str, object], s: Mapping[str, object], preset: str, mus: list[float]) -> list[dict]:
        computed.extend(mus)
        return [{"mu": mu, "x": math.nan if mu > 1 else mu} for mu in mus]

    def summarize(p: Mapping[str, object], rows: list[dict]) -> dict[str, object]:
        return {"mus": [r["mu"] for r in rows], "nan": sum(math.isnan(r["x"]) for r in rows)}

    sweep = ParamSweep(plan=plan, compute=compute, summarize=summarize, table=lambda rows, _: f"{len(rows)} rows",
                       passed=lambda summary: summary["nan"] == 0)
    _with_facets(monkeypatch, param_sweeps={"mu": sweep})
    out = tmp_path / "mu.json"
    args = ["sweep", "rimless-wheel-friction", "--param", "mu", "--json", str(out)]
    assert main([*args, "--values", "1.1,0.3", "--workers", "3"]) == 1
    first = json.loads(out.read_text())
    assert planned == [([0.3, 1.1], 3)]
    assert first["rows"] == [{"mu": 0.3, "x": 0.3}, {"mu": 1.1, "x": None}]
    assert first["summary"] == {"mus": [0.3, 1.1], "nan": 1} and first["preset"] == "fast"
    assert capsys.readouterr().out.startswith("2 rows\n2 mu values run in ")
    assert main([*args, "--values", "0.3,1.1,0.24", "--resume"]) == 1
    assert planned[-1] == ([0.24], 1) and computed == [0.3, 1.1, 0.24]
    assert json.loads(out.read_text())["summary"] == {"mus": [0.24, 0.3, 1.1], "nan": 1}
    assert capsys.readouterr().out.startswith("3 rows\n1 mu values run in ")
    for bad, needle in [(["--values", "0.3,-1"], "mu must be in [0, 1000] (got -1)"),
                        (["--values", "0.3", "--set", "kappa=0"], "kappa must be in"),
                        (["--values", "0.3", "--resume", "--json", "-"], "--resume needs --json PATH")]:
        assert main([*args, *bad]) == 2
        err = capsys.readouterr().err
        assert needle in err and err.count("\n") == 1, err
    assert len(planned) == 2


def test_the_mu_sweeps_references_run_in_two_processes_at_least(monkeypatch: pytest.MonkeyPatch) -> None:
    """The friction wheel's mu sweep plans its references in two processes or more, the mu values interleaved, and
    groups them in increasing mu into the rollouts the batch setting allows (the processes are replaced)."""
    from mjpoincare.scenarios.rimless_wheel_friction import sweep as mu_sweep

    seen: list[tuple[int, list[list[float]]]] = []

    def jobs(_: object, work: list[tuple[dict, list[float]]], *, workers: int) -> list[list[dict]]:
        seen.append((workers, [mus for _, mus in work]))
        return [[{"mu": mu} for mu in mus] for _, mus in work]

    monkeypatch.setattr(mu_sweep, "run_jobs", jobs)
    plan = mu_sweep.plan({}, {"batch": 2 * len(mu_sweep.SWEEP_OFFSETS)}, [0.2, 0.3, 0.4], workers=1)
    assert seen == [(2, [[0.2, 0.4], [0.3]])]
    assert plan == [([{"mu": 0.2}, {"mu": 0.3}],), ([{"mu": 0.4}],)]


def test_workers_are_spawned_once_a_threaded_library_is_loaded(monkeypatch: pytest.MonkeyPatch) -> None:
    """Forking a process that holds JAX's or Warp's native threads can deadlock the child: then spawn."""
    import sys
    import types

    from mjpoincare.core import parallel

    monkeypatch.delitem(sys.modules, "jax", raising=False)
    monkeypatch.delitem(sys.modules, "jaxlib", raising=False)
    monkeypatch.delitem(sys.modules, "warp", raising=False)
    assert parallel.start_method() == ("fork" if sys.platform.startswith("linux") else "spawn")
    monkeypatch.setitem(sys.modules, "jax", types.ModuleType("jax"))
    assert parallel.start_method() == "spawn"
