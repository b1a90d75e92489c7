"""Regression: MuJoCo's rimless wheel with Coulomb friction against the stick-slip reference (Gamus & Or 2015,
Sec. 3 and Appendix A; :mod:`mjpoincare.analysis.theory.rimless_wheel_friction`).

The checks and their tolerances are the scenario's own (:mod:`mjpoincare.scenarios.rimless_wheel_friction`); nothing
here loosens them. The Type D+ test pins a measured MuJoCo limitation (a sliding foot lifts off), so that a change
of it shows.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_inputs, run_validation
from mjpoincare.core.params import ParameterError
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios.rimless_wheel_friction import basins
from mjpoincare.scenarios.rimless_wheel_friction import sweep as mu_sweep

pytestmark = pytest.mark.mujoco


@pytest.fixture(scope="module")
def type_b() -> dict:
    return gate.run_case(gate.case("rimless-wheel-friction[fast]")).to_dict()


def _checks(result: dict) -> dict[str, dict]:
    return {c["name"]: c for c in result["checks"]}


def test_default_type_b(type_b: dict) -> None:
    """mu = 0.3 (the paper's stick-slip case): Type B, slip onset, impact kind, multiplier, mid-stance rate (their
    verdicts are the gate's: tests/test_gate.py); every start is Type B in both the simulation and the reference."""
    checks = _checks(type_b)
    assert {"gait_type", "midstance_rate", "eigenvalue", "impact_kind", "phase_sequence", "slip_onset",
            "stable"} <= set(checks)
    assert type_b["analytic"]["gait"] == "B"
    assert all(s["simulated"] == s["reference"] == "B" for s in type_b["extras"]["starts"])
    json.dumps(type_b, allow_nan=False)


def test_type_a_and_critical_friction() -> None:
    """mu = 2: no slip (Type A); the run's verdict is the gate's (tests/test_gate.py)."""
    result = gate.run_case(gate.case("rimless-wheel-friction[fast,mu=2.0]")).to_dict()
    assert result["analytic"]["gait"] == "A"
    assert "critical_friction" in _checks(result)


def test_type_c() -> None:
    """mu = 0.24: slipping impact, slip -> stick -> slip (Type C); the run's verdict is the gate's."""
    result = gate.run_case(gate.case("rimless-wheel-friction[fast,mu=0.24]")).to_dict()
    assert result["analytic"]["gait"] == "C"


def test_type_d_plus_flight_is_reported() -> None:
    """mu = 0.2 (Type D+): MuJoCo's sliding foot lifts off at normal speed ~ mu x_dot, and D+'s slip speed grows each
    step, so every start flies within a few steps. The run must say so (gait_type fails with 'detached'), while the
    steps before the flight are still D+ steps with the reference's mid-stance rate."""
    result = run_validation("rimless-wheel-friction", {"mu": "0.2"}, "fast").to_dict()
    checks = _checks(result)
    assert not result["passed"]
    assert not checks["gait_type"]["passed"]
    assert {s["simulated"] for s in result["extras"]["starts"]} == {"detached"}
    assert {s["reference"] for s in result["extras"]["starts"]} == {"D+"}
    assert checks["midstance_rate"]["passed"]
    assert any(step["kind"] == "D+" for step in result["extras"]["steps"])


@pytest.mark.parametrize(("assignments", "name"), [
    ({"mu": "-1"}, "mu"),
    ({"mu": "0.05"}, "mu"),
    ({"kappa": "0"}, "kappa"),
    ({"kappa": "1.5"}, "kappa"),
    ({"slope": "0.3"}, "slope"),
    ({"spokes": "2"}, "spokes"),
])
def test_bad_input_names_the_parameter(assignments: dict[str, str], name: str) -> None:
    with pytest.raises(ParameterError, match=name):
        resolve_inputs("rimless-wheel-friction", assignments, "fast")


def test_type_edges() -> None:
    edges = mu_sweep.type_edges([0.1, 0.2, 0.3, 0.9, 1.0], ["D+", "C", "B", "B", "A"])
    assert edges == pytest.approx({"D+/C": 0.15, "C/B": 0.25, "B/A": 0.95})


def test_mu_sweep_batches_and_resumes(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Two mu values in one rollout, then a resumed run that only simulates the new value."""
    target = tmp_path / "sweep.json"
    args = ["sweep", "rimless-wheel-friction", "--param", "mu", "--preset", "fast", "--json", str(target)]
    main([*args, "--values", "0.3,1.1"])
    first = json.loads(target.read_text())
    assert [r["simulated"] for r in first["rows"]] == ["B", "A"]
    assert all(r["eigenvalue_error"] <= 0.02 for r in first["rows"])
    main([*args, "--values", "0.3,1.1,0.24", "--resume"])
    out = capsys.readouterr().out
    assert "1 mu values run" in out
    rows = json.loads(target.read_text())["rows"]
    assert [r["mu"] for r in rows] == [0.24, 0.3, 1.1]
    assert rows[0]["simulated"] == "C"


def test_mu_values_per_rollout_fill_the_batch_setting() -> None:
    offsets = len(mu_sweep.SWEEP_OFFSETS)
    assert mu_sweep.mu_per_rollout({"batch": 0}) == mu_sweep.SWEEP_BATCH
    assert mu_sweep.mu_per_rollout({"batch": 4096}) == 4096 // offsets
    assert mu_sweep.mu_per_rollout({"batch": 1}) == 1


def test_sliding_law_cannot_be_read_from_float32_states(monkeypatch: pytest.MonkeyPatch) -> None:
    """MuJoCo C's own recorded rows of the fast preset, rounded to float32 as MJX float32 and MuJoCo Warp record them:
    the law's residual goes from ~1e-11 to order 1 (measured 1.0 of its largest possible 1), as the foot's depth and
    velocities are differences of hub coordinates of order 1 that float32 resolves to ~1e-7. The float32 backends'
    misses of ``sliding_contact_law`` are their records' precision, not their contact."""
    from mjpoincare.core.seam import Chunk
    from mjpoincare.scenarios import rimless_wheel_friction as scenario

    measured: dict[str, float] = {}
    law = scenario.sliding_contact

    def both(rec: Chunk, *args: object) -> object:
        single = Chunk(**{k: getattr(rec, k).astype(np.float32).astype(float) for k in ("time", "qpos", "qvel")})
        measured["float32"] = law(single, *args).residual
        found = law(rec, *args)
        measured["float64"] = found.residual
        return found

    monkeypatch.setattr(scenario, "sliding_contact", both)
    run_validation("rimless-wheel-friction", {}, "fast")
    assert measured["float64"] < 1e-9
    assert measured["float32"] > 0.1


def test_basin_map_small(tmp_path: Path) -> None:
    """An 8 x 5 map and the x_dot0 = 0 lines, in rollouts of 16 starts (the batch setting; 3 for the map): the region
    of attraction agrees with the reference (exit 0: measured 0 % of the reference points differ, against the 5 % the
    exit code allows), the sticking starts inside the window converge, the slowest rolls back; the PNG and JSON are
    written."""
    png, js = tmp_path / "basins.png", tmp_path / "basins.json"
    code = main(["sweep", "rimless-wheel-friction", "--grid", "theta_dot0=0.05:1.2:8,x_dot0=0:0.04:5", "--set",
                 "batch=16", "--preset", "coarse", "--json", str(js), "-o", str(png)])
    result = json.loads(js.read_text())
    assert png.stat().st_size > 10_000
    assert code == 0 and result["diverged"] == 0
    line = result["lines"]["slip"]
    assert line["simulated"][0] == line["reference"][0] == "backward"
    assert all(s not in basins.FAILURES for s in line["simulated"][1:6])
    steps = np.array(line["simulated_steps"][1:6])
    assert (steps > 0).all()
