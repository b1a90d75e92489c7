"""The benchmark command produces its table, Pareto marks, reference rows and PNG (quick sweep)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mjpoincare.cli import main
from mjpoincare.commands import bench, bench_paths
from mjpoincare.commands.bench import pareto_front

#: A coarse step (contact time constant 2 steps) for the tests of the command's output: a wheel validation takes about
#: a tenth of its time at the fast preset.
COARSE = {"timestep": "8e-4", "solref_timeconst": "1.6e-3"}


def test_pareto_front() -> None:
    walls = [1.0, 2.0, 3.0, 2.5]
    errors = [1e-2, 1e-3, 1e-4, 1e-2]
    assert pareto_front(walls, errors) == [True, True, True, False]


@pytest.mark.mujoco
def test_quick_bench_writes_table_plot_and_json(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    """The table, the Pareto marks, the reference rows, the PNG and the JSON of a quick bench. The ``mujoco.rollout``
    reference (a rollout and a validation) is measured for real, at :data:`COARSE` instead of the default preset's
    step, which made it two thirds of the test's time."""
    real_rate = bench.raw_rollout_rate
    monkeypatch.setattr(bench, "raw_rollout_rate",
                        lambda name, assignments: real_rate(name, {**COARSE, **assignments}))
    png, out = tmp_path / "bench.png", tmp_path / "bench.json"
    assert main(["bench", "rimless-wheel", "--quick", "-o", str(png), "--json", str(out)]) == 0
    table = capsys.readouterr().out
    assert "omega_post_impact error" in table and "solve_ivp reference" in table
    assert png.stat().st_size > 10_000
    payload = json.loads(out.read_text())
    assert len(payload["rows"]) == 2 and any(r["pareto"] for r in payload["rows"])
    assert payload["raw_rollout"]["steps_per_s"] > 0
    # refining the step (0.8 ms -> 0.4 ms, contact time constant 10 steps) reduces the error
    errors = [r["omega_post_impact_error"] for r in payload["rows"]]
    assert errors[1] < errors[0]


def test_unskip_collisions_makes_every_geom_collide() -> None:
    from mjpoincare.commands.validation import resolve_inputs

    scenario, _, params, settings = resolve_inputs("rimless-wheel", {"unskip": "collisions"}, None)
    model = scenario.build(params, settings)
    assert (model.geom_contype == 1).all() and (model.geom_conaffinity == 1).all()
    scenario, _, params, settings = resolve_inputs("rimless-wheel", {}, None)
    model = scenario.build(params, settings)
    assert (model.geom_contype == 0).sum() > 0  # spokes and hub are filtered out by default
    scenario, _, params, settings = resolve_inputs("slotted-skate", {"unskip": "contact"}, None)
    import mujoco

    assert not scenario.build(params, settings).opt.disableflags & int(mujoco.mjtDisableBit.mjDSBL_CONTACT)


@pytest.mark.mujoco
def test_scaling_reports_ceiling_and_speedup(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "scaling.json"
    assert main(["bench", "rimless-wheel", "--scaling", "--param", "slope", "--values", "0.1,0.15", "--repeats", "1",
                 *(f"--set={k}={v}" for k, v in COARSE.items()), "--json", str(out)]) == 0
    assert "machine ceiling" in capsys.readouterr().out
    payload = json.loads(out.read_text())
    assert payload["workers"] == 2 and payload["ceiling"] > 0 and payload["speedup"] > 0
    assert payload["efficiency"] == pytest.approx(payload["speedup"] / payload["ceiling"])


def test_scaling_refuses_one_worker() -> None:
    assert main(["bench", "rimless-wheel", "--scaling", "--param", "slope", "--workers", "1"]) == 2


@pytest.mark.parametrize(("command", "needle"), [
    (["bench", "slotted-skate", "--scaling"], "bench --scaling needs --param NAME"),
    (["bench", "slotted-skate", "--param", "Omega0"], "--param Omega0 is for bench --scaling only"),
    (["bench", "slotted-skate", "--scaling", "--param", "slope"], "unknown parameter 'slope'"),
])
def test_scaling_param_has_no_default(command: list[str], needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(command) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err


@pytest.mark.mujoco
def test_paths_bench_puts_fast_accurate_and_richardson_on_one_plot(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    """``bench --paths`` on the friction wheel (its presets the cheapest): the three paths' table, PNG and JSON; the
    Richardson path costs the fast run and more (its coarser grids), and a component without a clean order keeps the
    fast path's error exactly."""
    png, out = tmp_path / "paths.png", tmp_path / "paths.json"
    assert main(["bench", "rimless-wheel-friction", "--paths", "-o", str(png), "--json", str(out)]) == 0
    table = capsys.readouterr().out
    assert all(f"| {path} |" in table for path in ("fast", "accurate", "fast + Richardson"))
    assert png.stat().st_size > 10_000
    fast, accurate, richardson = json.loads(out.read_text())["paths"]
    assert [fast["path"], accurate["path"], richardson["path"]] == ["fast", "accurate", "fast + Richardson"]
    assert fast["errors"] and set(fast["errors"]) == set(accurate["errors"]) == set(richardson["errors"])
    assert richardson["wall_s"] > fast["wall_s"]
    for component in richardson["not_clean"]:
        assert richardson["errors"][component] == fast["errors"][component]
    data = json.loads(out.read_text())
    assert data["build"]  # the commit the paths were measured at, the label --compare draws
    beside = tmp_path / "beside.png"
    bench_paths.plot(data, str(beside), compare={**data, "build": "earlier"})  # another build's, dashed
    assert beside.stat().st_size > png.stat().st_size


@pytest.mark.parametrize(("content", "needle"), [
    (None, "not a readable bench --paths JSON"),
    ('{"scenario": "rimless-wheel"}', "not a bench --paths JSON (no 'paths')"),
    ('{"scenario": "slotted-skate", "paths": []}', "is of 'slotted-skate', not 'rimless-wheel'"),
])
def test_paths_compare_refuses_what_is_not_the_scenarios_paths(content: str | None, needle: str, tmp_path: Path,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    """``--compare`` takes another build's ``bench --paths --json`` of the same scenario; anything else is refused in
    one line before any run, as is ``--compare`` without ``--paths``."""
    other = tmp_path / "other.json"
    if content is not None:
        other.write_text(content)
    assert main(["bench", "rimless-wheel", "--paths", "--compare", str(other), "-o", str(tmp_path / "p.png"),
                 "--json", str(tmp_path / "p.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0] and not (tmp_path / "p.png").exists()
    assert main(["bench", "rimless-wheel", "--compare", str(other)]) == 2
    assert "is for bench --paths only" in capsys.readouterr().err


@pytest.mark.parametrize("flags", [["--paths", "--skips"], ["--quick", "--paths"]])
def test_bench_takes_one_mode(flags: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["bench", "rimless-wheel", *flags]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bench takes one of --quick, --skips, --scaling, --paths" in err[0]
