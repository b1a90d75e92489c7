"""The backends' findings page (docs/results/backends/) is generated: it re-renders byte for byte from its committed
JSON, covers every scenario on every backend at the fast preset, and the renderer reports what the records say (no
backend package needed)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mjpoincare import scenarios
from mjpoincare.pages import backend_findings as findings
from mjpoincare.pages import backend_findings_page as findings_page

BACKENDS = Path(__file__).resolve().parent.parent / "docs" / "results" / "backends"
RECORDS = findings_page.load(BACKENDS)
ENV = {"mujoco": "9.9.9", "cpu": "CPU X", "logical_cpus": 2, "git_sha": "abc123", "git_dirty": False,
       "date": "2026-01-01T00:00:00Z", "backend_packages": {"jax": "1.0"}}


def test_committed_page_reproduces_from_its_json() -> None:
    assert (BACKENDS / "README.md").read_text() == findings_page.render(RECORDS), "stale: python -m " \
        "mjpoincare.pages.backend_findings render docs/results/backends"


def test_every_scenario_ran_or_was_refused_on_every_backend_at_the_fast_preset() -> None:
    """And MuJoCo C ran again from each rounding-sized change of the starts (the spread column)."""
    done = {(r["scenario"], r["backend"], r["precision"], r.get("start_perturbation", 0.0)) for r in RECORDS
            if r["kind"] == "validate" and r["preset"] == "fast"}
    built_in = [s for s in scenarios.REGISTRY if scenarios.REGISTRY.distribution(s) == "mjpoincare"]
    expected = {(s, b, p, 0.0) for s in built_in for b, p in findings_page.COLUMNS}
    expected |= {(s, "mujoco", "float64", x) for s in built_in for x in findings_page.PERTURBATIONS}
    assert expected <= done, sorted(expected - done)
    for r in RECORDS:
        if r["kind"] == "validate":
            compiled = r.get("compile_s", 0.0) > 0  # MJX and Warp compile their chunks; MuJoCo C compiles nothing
            assert "refused" in r or ("checks" in r and compiled == (r["backend"] != "mujoco")), findings._key(r)


def _run(backend: str, precision: str, error: float, **timing: float) -> dict[str, Any]:
    check = {"name": "eigenvalue", "error": error, "tolerance": 0.02, "passed": error <= 0.02}
    return {"kind": "validate", "scenario": "toy", "preset": "fast", "backend": backend, "precision": precision,
            "batch": 8, "environment": ENV, "wall_s": 3.0, "compile_s": timing.get("compile_s", 0.0),
            "device": "cpu", "checks": [check],
            "timing": {"rollout_steps_per_s": 1e5, "batch_steps": timing.get("batch_steps", 1e4)}}


def test_page_puts_each_backend_beside_mujoco_c_and_says_what_a_gpu_needs() -> None:
    records = [_run("mujoco", "float64", 1e-4), _run("mjx", "float32", 0.25, compile_s=100.0, batch_steps=5e4),
               {**_run("mujoco", "float64", 3e-4), "start_perturbation": 1e-12},
               {"kind": "validate", "scenario": "toy", "preset": "fast", "backend": "warp", "precision": "float32",
                "batch": 8, "environment": ENV, "refused": "no sensor"},
               {"kind": "scaling", "scenario": "toy", "backend": "mjx", "precision": "float64", "steps": 10,
                "environment": ENV, "device": "cpu", "latency_s": 2e-3, "per_trajectory_s": 1e-5,
                "sizes": [{"batch": 1, "seconds_per_step": 2e-3, "steps_per_s": 500.0, "compile_s": 9.0},
                          {"batch": 9, "seconds_per_step": 1e-2, "steps_per_s": 900.0, "compile_s": 9.0}]},
               {"kind": "map", "map": "mu", "backend": "mujoco", "precision": "float64", "batch": 8, "size": 4,
                "environment": ENV, "exit_code": 1, "wall_s": 20.0, "starts": 4, "agreement": 0.75,
                "agreement_without_d_plus": 1.0, "max_eigenvalue_error": None}]
    lines = findings_page.render(records).splitlines()
    assert "| toy | fast | eigenvalue | 0.02 | 0.0001 | 0.0001 to 0.0003 |  | 0.25 ✗ |  |" in lines
    assert "| toy | fast | compile s | | 0 |  | not run | 100 | refused: no sensor |" in lines
    # 600 s less 100 s of compile over 5e4 batched steps: 1e4 µs per batched step at most
    assert "| fast | mjx | float32 | 1 | 5e+04 | 100 | 1e+04 µs |" in lines
    assert "| toy | mjx | float64 | fit | latency 1 ms + 1e+03 µs per trajectory | |" in lines
    assert any(line.startswith("| mu | mujoco | float64 | 4 | 8 | gait type agrees on 75.0% (100.0% without")
               for line in lines)
    assert "| git commit | abc123 |" in lines


@pytest.mark.parametrize("record", [r for r in RECORDS if r["kind"] == "validate" and "checks" in r],
                         ids=findings._key)
def test_each_record_is_its_backends_own(record: dict[str, Any]) -> None:
    """A record's settings name the backend and precision it claims (a run cannot fall back to MuJoCo C)."""
    assert record["settings"]["backend"] == record["backend"]
    assert record["settings"]["precision"] == record["precision"]


@pytest.mark.parametrize("argv", [["run", "nope", "mjx", "float64"], ["run", "rimless-wheel", "cuda", "float64"],
                                  ["scaling", "rimless-wheel", "mjx", "float64", "--sizes", "0"],
                                  ["all", "--workers", "0"], ["all", "--batch", "-1"]])
def test_bad_input_exits_2_before_any_simulation(argv: list[str], tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        findings.main([*argv, "--out", str(tmp_path)])
    assert exit_.value.code == 2
    assert "error:" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_a_float32_clock_ticks_long() -> None:
    """MJX float32 and MuJoCo Warp keep the time in float32 and add the timestep each step: at the compass biped's
    accurate timestep (2e-5 s), every tick from 2 s to 8 s is 1.36e-3 longer than the timestep. That is the float32
    backends' step_period error on the findings page (1.24e-3 on both, against MuJoCo C's 1.06e-4): their clock, not
    their gait."""
    clock = np.cumsum(np.full(400_000, np.float32(2e-5), dtype=np.float32), dtype=np.float32)
    tick = np.diff(clock[100_000:].astype(float)).mean() / 2e-5 - 1.0
    assert 1.3e-3 < tick < 1.4e-3
