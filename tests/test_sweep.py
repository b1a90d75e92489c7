"""The sweep command: value parsing, bifurcation location, and a small real sweep."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from conftest import require_module

from mjpoincare.cli import main
from mjpoincare.params import ParameterError, parse_values
from mjpoincare.sweep import crossing

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


@pytest.mark.mujoco
def test_wheel_sweep_over_slope(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "sweep.json"
    code = main(["sweep", "rimless-wheel", "--param", "slope", "--values", "0.08,0.12", *WHEEL_COARSE,
                 "--json", str(out)])
    rows = json.loads(out.read_text())["rows"]
    assert code == (0 if all(r["passed"] for r in rows) else 1)  # each row's verdict is the gate's to assert
    assert [r["slope"] for r in rows] == [0.08, 0.12]
    assert all(abs(r["fitted_lowest"] - 0.5) < 0.02 for r in rows)  # beta^2 = 0.5 for 8 spokes at any slope
    assert "lowest Re" in capsys.readouterr().out
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
    from mjpoincare import seam_check
    from mjpoincare.backends import mujoco_c

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


def test_the_scenario_facets_are_dispatched(monkeypatch: pytest.MonkeyPatch) -> None:
    """``--grid`` and a scenario's own ``--param`` sweep reach the hooks it declares, with its default PNG path and at
    least two processes for the friction wheel's reference (the hooks are replaced: no simulation)."""
    from mjpoincare.scenarios import rimless_wheel_friction_basins as basins
    from mjpoincare.scenarios import rimless_wheel_friction_sweep as mu_sweep

    _no_simulation(monkeypatch)
    calls: list[tuple[object, ...]] = []
    monkeypatch.setattr(basins, "run_basin_map", lambda *a, **k: calls.append((*a, k)) or 0)
    monkeypatch.setattr(mu_sweep, "run_mu_sweep", lambda *a, **k: calls.append((*a, k)) or 0)
    grid = "theta_dot0=0.05:1.2:8,x_dot0=0:0.04:5"
    assert main(["sweep", "rimless-wheel-friction", "--grid", grid]) == 0
    assert calls.pop() == (grid, {}, None, None, "renders/basins-rimless-wheel-friction.png", {"workers": 2})
    assert main(["sweep", "rimless-wheel-friction", "--param", "mu", "--values", "0.3,1.1", "--workers", "3"]) == 0
    assert calls.pop() == (["0.3", "1.1"], {}, None, None, {"resume": False, "workers": 3})



def test_workers_are_spawned_once_a_threaded_library_is_loaded(monkeypatch: pytest.MonkeyPatch) -> None:
    """Forking a process that holds JAX's or Warp's native threads can deadlock the child: then spawn."""
    import sys
    import types

    from mjpoincare import parallel

    monkeypatch.delitem(sys.modules, "jax", raising=False)
    monkeypatch.delitem(sys.modules, "jaxlib", raising=False)
    monkeypatch.delitem(sys.modules, "warp", raising=False)
    assert parallel.start_method() == ("fork" if sys.platform.startswith("linux") else "spawn")
    monkeypatch.setitem(sys.modules, "jax", types.ModuleType("jax"))
    assert parallel.start_method() == "spawn"
