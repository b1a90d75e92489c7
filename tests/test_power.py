"""The gate's power (:mod:`mjpoincare.gate.power`, :mod:`mjpoincare.gate.effects`): a planted change reaches every
model a run compiles and nothing else; a slope plant rotates gravity in the plane of motion and moves the checks the
theory says it moves; a change the theory and the model cannot see is a control, run once and never listed blind;
the unplanted control is caught by nothing; a change of 1e-2 of the timestep is caught by the baseline; the page
renders from a payload; the committed page is rendered from its JSON, its controls hold, and it says plainly what
nothing caught."""

from __future__ import annotations

import json
import math
from pathlib import Path

import mujoco
import pytest

from mjpoincare import scenarios
from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_values
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.mjcf_loader import compile_spec, load_spec, planted
from mjpoincare.gate import effects, power
from mjpoincare.pages import gate_power_page

ROOT = Path(__file__).parents[1]


def test_a_planted_edit_reaches_the_models_compiled_within_its_block_only() -> None:
    spec = load_spec("rimless_wheel_2d.xml")
    before = compile_spec(spec).opt.gravity.copy()
    edit = power.model_edit(power.Plant("gravity", 1e-2), "hub")
    assert edit is not None
    with planted(edit):
        inside = compile_spec(load_spec("rimless_wheel_2d.xml")).opt.gravity.copy()
    after = compile_spec(load_spec("rimless_wheel_2d.xml")).opt.gravity
    assert inside == pytest.approx(1.01 * before) and after == pytest.approx(before)


def test_dropping_a_contact_pair_leaves_a_moving_body_geom_colliding_with_nothing() -> None:
    model = compile_spec(load_spec("rimless_wheel_2d.xml"))
    edit = power.model_edit(power.Plant("contact_pair"), "hub")
    assert edit is not None
    colliding = sum(bool(model.geom_contype[g] or model.geom_conaffinity[g]) for g in range(model.ngeom))
    what = edit(model)
    assert sum(bool(model.geom_contype[g] or model.geom_conaffinity[g]) for g in range(model.ngeom)) == colliding - 1
    assert "of body" in what and mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "hub") >= 0


@pytest.mark.mujoco
def test_the_control_is_caught_by_nothing_and_a_timestep_one_percent_off_by_the_baseline() -> None:
    control = power.run_plant("rimless-wheel[fast]", power.Plant("none"))
    assert power.verdict(control) == "-", control
    moved = power.run_plant("rimless-wheel[fast]", power.Plant("timestep", 1e-2))
    assert moved["baseline"] and moved["settings"]["timestep"] > 0, moved


def test_a_slope_plant_rotates_gravity_by_the_slope_change_at_its_magnitude() -> None:
    model = compile_spec(load_spec("rimless_wheel_2d.xml"))
    model.opt.gravity[:] = [9.81 * math.sin(0.08), 0.0, -9.81 * math.cos(0.08)]
    edit = power.model_edit(power.Plant("slope", 1e-2), "hub")
    assert edit is not None
    edit(model)
    assert model.opt.gravity == pytest.approx([9.81 * math.sin(0.0808), 0.0, -9.81 * math.cos(0.0808)], rel=1e-12)


def test_a_gyration_plant_scales_the_rotational_inertia_alone() -> None:
    model = compile_spec(load_spec("rimless_wheel_2d.xml"))
    hub = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "hub")
    mass, inertia = float(model.body_mass[hub]), model.body_inertia[hub].copy()
    edit = power.model_edit(power.Plant("gyration", 1e-2), "hub")
    assert edit is not None
    edit(model)
    assert model.body_mass[hub] == mass and model.body_inertia[hub] == pytest.approx(1.01**2 * inertia)


@pytest.mark.parametrize(("scenario", "moved", "still"), [
    ("rimless-wheel", {"omega_post_impact", "step_period"}, {"eigenvalue", "impact_coefficient"}),
    ("compass-biped", {"fixed_point", "eigenvalues", "step_period", "step_length"}, {"trailing_foot_release"}),
    ("rimless-wheel-3d", {"pitch_rate", "bank", "wobble_angle", "planar_bank"}, {"heading_eigenvalue"}),
])
def test_a_slope_plant_moves_the_checks_the_theory_says_it_moves(scenario: str, moved: set[str],
                                                                   still: set[str]) -> None:
    """003 eq 3.11: the planar wheel's impact coefficient (and so its multiplier beta^2) does not depend on the slope;
    its fixed point and period do. 001 Table 1: the 3D wheel's heading stays neutral on any slope."""
    _, _, params, _ = resolve_values(scenario, {}, None)
    effect = effects.effects(scenario, "slope", params, 1e-2)
    assert effects.kind(scenario, "slope") == "theory"
    assert all(effect[c] is not None and effect[c] > 1e-5 for c in moved), effect
    assert all(effect[c] == pytest.approx(0.0, abs=1e-9) for c in still), effect
    smaller = effects.effects(scenario, "slope", params, 1e-3)
    assert all(0.0 < smaller[c] < effect[c] for c in moved), smaller  # type: ignore[operator]


@pytest.mark.parametrize(("scenario", "change"), [
    ("rimless-wheel", "mass_inertia"), ("rimless-wheel-3d", "mass_inertia"), ("rimless-wheel", "friction"),
    ("compass-biped", "friction"), ("slotted-skate", "gravity"), ("slotted-skate", "contact_pair")])
def test_a_change_the_theory_cannot_see_is_a_control_run_once_and_never_blind(scenario: str, change: str) -> None:
    assert effects.kind(scenario, change) == "control"
    sizes = [p.size for p in power.plants(scenario) if p.change == change]
    assert len(sizes) == 1
    row = {"case": f"{scenario}[fast]", "change": change, "size": sizes[0], "kind": "control", "raised": None,
           "tolerance": [], "baseline": []}
    assert power.is_control(row) and power.blind([row]) == [] and power.holds([row])
    assert not power.holds([{**row, "baseline": ["x"]}])


def test_friction_is_a_control_only_where_the_gate_cases_cone_is_elliptic() -> None:
    """A sticking foot's mu is invisible to MuJoCo's elliptic cone, not to its pyramidal one (the friction biped's
    fast preset), whose rows mix the normal with mu times the tangent."""
    for scenario, controls in effects.CONTROLS.items():
        cone = {**sim_settings.DEFAULTS, **scenarios.get(scenario).presets["fast"]}["cone"]
        contact = "no contact" not in controls.get("friction", "")
        assert ("friction" in controls) <= (cone == "elliptic" or not contact), scenario
    assert effects.kind("compass-biped-friction", "friction") == "simulator"


def test_the_friction_wheels_friction_is_a_parameter_of_its_theory_not_a_control() -> None:
    assert effects.kind("rimless-wheel-friction", "friction") == "theory"
    assert [p.size for p in power.plants("rimless-wheel-friction") if p.change == "friction"] == list(power.SIZES)


def _row(case: str, change: str, size: float | None, kind: str, *, must_fail: list[str], tolerance: list[str],
         baseline: list[str]) -> dict[str, object]:
    return {"case": case, "change": change, "size": size, "kind": kind, "raised": None, "settings": {},
            "edited": ["gravity's direction (slope 0.08 rad)"], "effects": {"step_period": 0.02 if must_fail else 0.0,
                                                                           "basins": None},
            "must_fail": must_fail, "tolerance": tolerance, "baseline": baseline, "largest_move": [0.5, "x"],
            "wall_s": 1.0}


def test_the_page_renders_from_a_payload_with_the_smallest_detected_size_and_no_control_blind() -> None:
    case = "rimless-wheel[fast]"
    rows = [_row(case, "none", None, "control", must_fail=[], tolerance=[], baseline=[]),
            _row(case, "slope", 1e-4, "theory", must_fail=[], tolerance=[], baseline=[]),
            _row(case, "slope", 1e-3, "theory", must_fail=[], tolerance=[], baseline=["step_period"]),
            _row(case, "slope", 1e-2, "theory", must_fail=["step_period"], tolerance=["step_period"],
                 baseline=["step_period"]),
            _row(case, "timestep", 1e-2, "simulator", must_fail=[], tolerance=[], baseline=[]),
            _row(case, "mass_inertia", 1e-2, "control", must_fail=[], tolerance=[], baseline=[])]
    stamp = {"mujoco": "4.0.0", "numpy": "2", "scipy": "1", "python": "3.11", "git_sha": "0" * 40,
             "git_dirty": False, "cpu": "test", "logical_cpus": 2, "platform": "test", "date": "2026-12-07T00:00:00Z"}
    page = gate_power_page.render({"stamp": stamp, "multiple": 3.0, "floor": 1e-6, "rows": rows})
    assert "they do." in page
    assert f"| {case} | slope | theory | 0.01 | 0.01 | 0.001 |" in page
    assert f"| {case} | timestep | simulator | - | not at 0.01 | not at 0.01 |" in page
    blind = page.split("## Caught by neither")[1].split("## Which checks")[0]
    assert "slope x(1+0.0001)" in blind and "timestep x(1+0.01)" in blind and "mass_inertia" not in blind
    assert "step_period (0.02), ? basins" in page


def test_power_refuses_an_unknown_change_before_any_simulation(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["power", "--change", "viscosity"]) == 2
    assert "--change must be among" in capsys.readouterr().err


def test_the_committed_page_renders_from_its_json_and_its_control_holds() -> None:
    payload = json.loads((ROOT / gate_power_page.POWER).read_text())
    assert (ROOT / gate_power_page.PAGE).read_text() == gate_power_page.render(payload), "stale: make power"
    assert power.holds(payload["rows"])
    assert {r["case"] for r in payload["rows"]} == {c.label for c in power.default_cases()}
    assert {(r["case"], r["change"], r["size"]) for r in payload["rows"]} == {
        (label, p.change, p.size) for label, p in power.jobs(power.default_cases(), power.plants())}
