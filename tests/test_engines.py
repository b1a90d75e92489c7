"""The Drake backend (:mod:`mjpoincare.engines.backends.drake`) and the engines' page.

- The translation: each wheel's mass matrix in Drake equals MuJoCo's at a random state (the same bodies, inertias,
  joints; the 3D wheel's free joint with its body-frame angular velocity), to rounding.
- The smoke run: the planar wheel with a hub of radius of gyration 0.3 through Drake's SAP, its impact coefficient
  checked against the check's own MuJoCo tolerance (measured 3.1e-4 against 1e-2: well inside; with the default
  near-point-mass hub Drake misses it, a finding of docs/results/engines/README.md).
- Refusals before any simulation: a scenario needing a mechanism Drake lacks, a setting it cannot honour, a model
  feature it cannot translate, each in one line.
- The page re-renders byte for byte from its committed JSON.
"""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest
from conftest import require_module

from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_inputs, run_validation
from mjpoincare.core.params import ParameterError
from mjpoincare.pages import engine_findings_page

PAGE = Path(__file__).resolve().parents[1] / "docs" / "results" / "engines"
#: Mass matrices agree to rounding: entries of order 1 (the hub's mass) down to 1e-4 (its floored inertia).
MASS_TOL = 1e-12


@pytest.fixture
def drake() -> None:
    require_module("pydrake", "drake")


@pytest.mark.usefixtures("drake")
@pytest.mark.parametrize("name", ["rimless-wheel", "rimless-wheel-friction"])
def test_the_translated_mass_matrix_is_mujocos(name: str) -> None:
    """Hinge and slide joints map one to one: the mass matrices agree entry by entry."""
    from mjpoincare.engines.backends.drake_plant import build_scene, to_drake

    _, _, params, settings = resolve_inputs(name, {}, "fast")
    from mjpoincare.scenarios import get

    model = get(name).build(params, settings)
    data = mujoco.MjData(model)
    rng = np.random.default_rng(0)
    data.qpos[:], data.qvel[:] = rng.normal(size=model.nq), rng.normal(size=model.nv)
    mujoco.mj_forward(model, data)
    expected = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, expected)
    state = np.empty((1, mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS)))
    mujoco.mj_getState(model, data, state[0], mujoco.mjtState.mjSTATE_FULLPHYSICS)
    scene = build_scene(model)
    context = scene.plant.CreateDefaultContext()
    scene.plant.SetPositionsAndVelocities(context, to_drake(scene, model, state)[0])
    drake_mass = scene.plant.CalcMassMatrix(context)
    order = np.zeros(model.nv, int)  # Drake's velocity index of each MuJoCo dof
    for j in scene.joints:
        order[j.dof] = j.v
    assert np.max(np.abs(drake_mass[np.ix_(order, order)] - expected)) <= MASS_TOL


@pytest.mark.usefixtures("drake")
@pytest.mark.parametrize("name", ["rimless-wheel-3d"])
def test_the_translated_kinetic_energy_is_mujocos(name: str) -> None:
    """A free joint's state maps through the body's rotation (MuJoCo's angular velocity is in the body frame,
    Drake's in the world's), so its mass matrices differ by it: the kinetic energy of a random state agrees."""
    from mjpoincare.engines.backends.drake_plant import build_scene, to_drake
    from mjpoincare.scenarios import get

    _, _, params, settings = resolve_inputs(name, {}, "fast")
    model = get(name).build(params, settings)
    data = mujoco.MjData(model)
    rng = np.random.default_rng(1)
    quat = rng.normal(size=4)
    data.qpos[:] = np.r_[rng.normal(size=3), quat / np.linalg.norm(quat)]
    data.qvel[:] = rng.normal(size=6)
    mujoco.mj_forward(model, data)
    mujoco.mj_energyVel(model, data)
    state = np.empty((1, mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS)))
    mujoco.mj_getState(model, data, state[0], mujoco.mjtState.mjSTATE_FULLPHYSICS)
    scene = build_scene(model)
    context = scene.plant.CreateDefaultContext()
    scene.plant.SetPositionsAndVelocities(context, to_drake(scene, model, state)[0])
    assert abs(scene.plant.CalcKineticEnergy(context) - data.energy[1]) <= MASS_TOL * max(1.0, data.energy[1])


@pytest.mark.mujoco
@pytest.mark.usefixtures("drake")
def test_the_planar_wheel_with_a_hub_runs_through_drake_within_mujocos_tolerance() -> None:
    result = run_validation("rimless-wheel", {"gyration": "0.3", "backend": "drake"}, "fast")
    check = next(c for c in result.checks if c.name == "impact_coefficient")
    assert check.error <= 0.1 * check.tolerance, result.table()
    assert not result.diverged and not result.warnings, result.table()


@pytest.mark.usefixtures("drake")
@pytest.mark.parametrize(("args", "needle"), [
    (["validate", "compass-biped", "--set", "backend=drake"], "contact release and restore does not work"),
    (["validate", "rimless-wheel-3d", "--set", "backend=drake", "--set", "impact=ideal"], "fractional steps"),
    (["validate", "slotted-skate", "--set", "backend=drake"], "does not work on MuJoCo"),
    (["validate", "rimless-wheel", "--set", "backend=drake", "--set", "diagnostics=1"],
     "backend=drake cannot run diagnostics=1"),
    (["validate", "rimless-wheel", "--set", "backend=drake", "--set", "precision=float32"], "precision must be"),
])
def test_what_drake_cannot_do_is_refused_in_one_line(args: list[str], needle: str,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1, err


@pytest.mark.usefixtures("drake")
def test_a_model_feature_with_no_counterpart_is_refused() -> None:
    from mjpoincare.engines.backends.drake_plant import build_scene

    model = mujoco.MjModel.from_xml_string("""<mujoco><worldbody><geom type="plane" size="1 1 1" friction="1"/>
      <body pos="0 0 1"><freejoint/><geom type="sphere" size="0.1" friction="0.5"/></body></worldbody></mujoco>""")
    with pytest.raises(ParameterError, match="one friction coefficient on every colliding geom"):
        build_scene(model)
    mesh = mujoco.MjModel.from_xml_string("""<mujoco><worldbody><body><joint type="ball"/>
      <geom type="sphere" size="0.1"/></body></worldbody></mujoco>""")
    with pytest.raises(ParameterError, match="ball joint"):
        build_scene(mesh)


def test_the_page_renders_from_its_json() -> None:
    records = engine_findings_page.load(PAGE)
    assert records, "docs/results/engines/json/ holds no records: run make engines"
    assert (PAGE / "README.md").read_text() == engine_findings_page.render(records), "stale: run make engines-render"


def _record(engine: str, case: str, analytic: list[float], passed: bool = True) -> dict[str, object]:
    check = {"name": "planar_pitch_rate", "analytic": analytic, "simulated": analytic, "error": 0.1 if not passed
             else 0.0, "error_kind": "max-abs", "tolerance": 0.005, "passed": passed}
    return {"engine": engine, "case": case, "preset": "fast", "checks": [check], "settings": {"timestep": 1e-3},
            "timing": {"wall_s": 1.0, "steps_per_s": 1.0}, "diverged_trajectories": [], "warnings": []}


def test_the_exact_column_is_mujocos_and_an_engine_with_its_own_says_so() -> None:
    """The exact value shown is MuJoCo C's run's, whatever the records' order; an engine whose run evaluated its
    reference elsewhere quotes it in its cell; the 3D wheel's sentence counts the planar wheel's passes it names."""
    records = [_record("drake-lagged", "rimless-wheel-3d", [2.4, 1.3], passed=False),
               _record("mujoco", "rimless-wheel-3d", [2.4, 2.3])]
    text = engine_findings_page.section(records, ["mujoco", "drake-lagged"])
    assert "| [2.4, 2.3] | 0 | 0.1 FAIL (against its exact [2.4, 1.3]) |" in text, text
    planar = [_record("drake-lagged", "rimless-wheel[gyration=0.3]", [1.0], passed=False)]
    assert "0 of the planar wheel's 1 checks pass on drake-lagged" in "\n".join(
        engine_findings_page.mechanisms(records + planar))
