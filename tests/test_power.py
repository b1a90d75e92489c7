"""The gate's power (:mod:`mjpoincare.gate.power`): a planted change reaches every model a run compiles and nothing
else; the unplanted control is caught by nothing; a change of 1e-2 of the timestep is caught by the baseline; the
committed page is rendered from its JSON, its control holds, and it says plainly what nothing caught."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import pytest

from mjpoincare.cli import main
from mjpoincare.core.mjcf_loader import compile_spec, load_spec, planted
from mjpoincare.gate import power
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


def test_power_refuses_an_unknown_change_before_any_simulation(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["power", "--change", "viscosity"]) == 2
    assert "--change must be among" in capsys.readouterr().err


def test_the_committed_page_renders_from_its_json_and_its_control_holds() -> None:
    payload = json.loads((ROOT / gate_power_page.POWER).read_text())
    assert (ROOT / gate_power_page.PAGE).read_text() == gate_power_page.render(payload), "stale: make power"
    assert power.holds(payload["rows"])
    assert {r["case"] for r in payload["rows"]} == {c.label for c in power.default_cases()}
    assert {(r["change"], r["size"]) for r in payload["rows"]} == {(p.change, p.size) for p in power.plants()}
