"""The rollout seam (:class:`mjpoincare.core.seam.Batch` on MuJoCo C): restarts, state rewrites and per-trajectory
contact, equality and actuator switches."""

from __future__ import annotations

import copy
import itertools

import mujoco
import numpy as np
import pytest
from mujoco import rollout as mj_rollout

from mjpoincare.core.seam import RELEASED_MARGIN, STATE_SPEC, Batch, Chunk, switch_contact
from mjpoincare.engines.backends.mujoco_c import MujocoBatch
from mjpoincare.simulation.simulate import event_rollout, initial_states

#: A ball on a slide joint above a plane (contact margin 1 mm), a pendulum, a bob held by a weld, and a slider pushed
#: by a motor with a constant bias force.
XML = """
<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="ball" pos="0 0 0.1">
      <joint name="drop" type="slide" axis="0 0 1"/>
      <geom name="ball" type="sphere" size="0.1" mass="1" margin="0.001"/>
    </body>
    <body name="arm" pos="2 0 2">
      <joint name="swing" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02" mass="1" contype="0" conaffinity="0"/>
    </body>
    <body name="bob" pos="-2 0 2">
      <joint name="hang" type="slide" axis="0 0 1"/>
      <geom type="sphere" size="0.05" mass="1" contype="0" conaffinity="0"/>
    </body>
    <body name="cart" pos="0 2 2">
      <joint name="push" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.1 0.1 0.1" mass="2" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <equality><weld name="hold" body1="bob"/></equality>
  <actuator>
    <general name="motor" joint="push" gainprm="0" biastype="affine" biasprm="0 0 0"/>
  </actuator>
</mujoco>
"""


@pytest.fixture(scope="module")
def model() -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(XML)


@pytest.fixture(scope="module")
def free(model: mujoco.MjModel) -> mujoco.MjModel:
    """The model without constraints: restarting from a recorded state then repeats MuJoCo's step bit for bit (no
    solver warmstart to lose)."""
    out = copy.copy(model)
    out.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
    return out


def _states(model: mujoco.MjModel, batch: int, swing: float = 0.3) -> np.ndarray:
    """``batch`` states at rest, the ball touching the floor, the pendulum at ``swing`` (rad)."""
    qpos = np.tile(model.qpos0, (batch, 1))
    qpos[:, model.joint("swing").qposadr[0]] = swing
    return initial_states(model, qpos, np.zeros((batch, model.nv)))


def _copies(model: mujoco.MjModel, batch: int) -> list[mujoco.MjModel]:
    return [copy.copy(model) for _ in range(batch)]


def _column(model: mujoco.MjModel, joint: str, velocity: bool = False) -> int:
    """The full-physics state column of ``joint``'s position (or velocity)."""
    return 1 + (model.nq + model.joint(joint).dofadr[0] if velocity else model.joint(joint).qposadr[0])


def test_chunk_restarts_continue_one_long_rollout(free: mujoco.MjModel) -> None:
    """Three chunks of 40 steps, each from the last state of the one before, are the 120-step rollout."""
    start = _states(free, 2, swing=0.7)
    start[1, _column(free, "swing", velocity=True)] = -1.0
    long, _ = mj_rollout.rollout(free, mujoco.MjData(free), start, nstep=120)
    with MujocoBatch(_copies(free, 2), start, threads=2) as batch:
        rows = [batch.run_chunk(40) for _ in range(3)]
    np.testing.assert_array_equal(rows[0][:, 0], start)
    for i, chunk in enumerate(rows):
        np.testing.assert_array_equal(chunk[:, 1:], long[:, 40 * i : 40 * (i + 1)])
    np.testing.assert_array_equal(batch.report.final_state, long[:, -1])
    assert batch.report.steps == 240


def test_set_states_rewrites_the_chosen_trajectories_only(model: mujoco.MjModel) -> None:
    start = _states(model, 3)
    with MujocoBatch(_copies(model, 3), start) as batch:
        first = batch.run_chunk(30)
        new = _states(model, 1, swing=-0.4)
        batch.set_states(np.array([1]), new)
        second = batch.run_chunk(30)
    np.testing.assert_array_equal(second[1, 0], new[0])
    np.testing.assert_array_equal(second[[0, 2], 0], first[[0, 2], -1])


def test_event_rollout_restarts_at_the_returned_row_and_takes_overrides(free: mujoco.MjModel) -> None:
    """Trajectory 0 restarts from row 5 of each chunk, trajectory 1 from an override, trajectory 2 runs on: every
    chunk's row 0 is the state it was told to continue from, and 2's final state is the plain rollout's."""
    start = _states(free, 3)
    override = _states(free, 1, swing=-0.2)[0]
    seen: list[np.ndarray] = []

    def on_chunk(chunk: Chunk, _batch: Batch) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        seen.append(np.concatenate([chunk.time[:, :, None], chunk.qpos, chunk.qvel], axis=2))
        return np.array([5, 20, 20]), {1: override}

    report = event_rollout(free, start, 40, on_chunk, chunk_steps=20)
    for before, after in itertools.pairwise(seen):
        np.testing.assert_array_equal(after[0, 0], before[0, 5])
        np.testing.assert_array_equal(after[1, 0], override)
    assert len(seen) == 8  # trajectory 0 keeps 5 steps per chunk
    long, _ = mj_rollout.rollout(free, mujoco.MjData(free), start[2:], nstep=40)
    np.testing.assert_array_equal(report.final_state[2], long[0, -1])  # done after 2 chunks, then idle
    np.testing.assert_array_equal(report.final_state[1], override)


def test_contact_released_and_restored_per_trajectory(model: mujoco.MjModel) -> None:
    """A released ball falls through the floor while the other rests on it; restored, its own collision filter is
    back."""
    ball, drop = model.geom("ball").id, _column(model, "drop")
    models = _copies(model, 2)
    with MujocoBatch(models, _states(model, 2)) as batch:
        batch.set_contact(1, ball, False)
        fell = batch.run_chunk(200)
        assert models[1].geom_contype[ball] == models[1].geom_conaffinity[ball] == 0
        np.testing.assert_array_equal(models[0].geom_contype, model.geom_contype)
        batch.set_contact(1, ball, True)
        batch.set_contact(1, ball, True)  # restoring twice keeps the model's own filter
    assert fell[0, -1, drop] > -0.01  # resting, up to the soft contact's penetration
    assert fell[1, -1, drop] < -0.5 * 9.81 * 0.4**2 * 0.9  # free fall over 0.4 s
    np.testing.assert_array_equal(models[1].geom_contype, model.geom_contype)
    np.testing.assert_array_equal(models[1].geom_conaffinity, model.geom_conaffinity)


@pytest.mark.skipif(tuple(int(v) for v in mujoco.__version__.split(".")[:2]) < (3, 5),
                    reason="before 3.5 MuJoCo C still generates a contact below a negative margin (MJX and MuJoCo "
                           "Warp, the backends that release through the margin, need 3.17)")
def test_a_contact_released_through_the_margin_is_bitwise_a_filtered_one(model: mujoco.MjModel) -> None:
    """Switching a geom's contact off through its margin (MJX, MuJoCo Warp) gives the very states of removing it
    from collision (contype 0, MuJoCo C), so the backends keep every number."""
    ball = model.geom("ball").id
    through_margin = copy.copy(model)
    switch_contact({}, through_margin.geom_margin, 0, ball, False)
    assert through_margin.geom_margin[ball] == RELEASED_MARGIN
    start = _states(model, 1)
    expected, _ = mj_rollout.rollout(through_margin, mujoco.MjData(through_margin), start, nstep=300)
    with MujocoBatch(_copies(model, 1), start) as batch:
        batch.set_contact(0, ball, False)
        got = batch.run_chunk(300)
    np.testing.assert_array_equal(got[:, 1:], expected)


def test_setup_switches_before_the_first_chunk(model: mujoco.MjModel) -> None:
    ball, drop = model.geom("ball").id, _column(model, "drop")
    first: list[np.ndarray] = []

    def on_chunk(chunk: Chunk, _batch: Batch) -> np.ndarray:
        first.append(chunk.qpos[:, 1, drop - 1])
        return np.full(2, 10)

    event_rollout(model, _states(model, 2), 10, on_chunk, chunk_steps=10,
                  setup=lambda batch: batch.set_contact(0, ball, False))
    assert first[0][0] < first[0][1]  # the released ball drops from the first step on


@pytest.mark.parametrize("released", [0, 1])
def test_equality_switched_per_trajectory(model: mujoco.MjModel, released: int) -> None:
    """With one thread both trajectories share an mjData: a switch must not leak to the other one."""
    hang = _column(model, "hang")
    start = _states(model, 2)
    with MujocoBatch(_copies(model, 2), start, threads=1) as batch:
        batch.set_eq_active(released, model.equality("hold").id, False)
        loose = batch.run_chunk(100)
        batch.set_eq_active(released, model.equality("hold").id, True)
        batch.set_states(np.arange(2), start)
        held = batch.run_chunk(100)
    assert loose[released, -1, hang] < -0.15 and abs(loose[1 - released, -1, hang]) < 1e-3
    np.testing.assert_array_equal(held[released], held[1 - released])


def test_actuator_bias_and_gear_per_trajectory(model: mujoco.MjModel) -> None:
    """A constant bias force of 3 N on the 2 kg cart of trajectory 1 (then geared -1); trajectory 0 stays."""
    motor, push = model.actuator("motor").id, _column(model, "push", velocity=True)
    with MujocoBatch(_copies(model, 2), _states(model, 2)) as batch:
        batch.set_actuator(1, motor, bias=3.0)
        pushed = batch.run_chunk(50)
        batch.set_actuator(1, motor, gear=-1.0)
        back = batch.run_chunk(50)
    assert pushed[0, -1, push] == 0.0
    assert pushed[1, -1, push] == pytest.approx(1.5 * 0.1)
    assert back[1, -1, push] == pytest.approx(0.0, abs=1e-12)


def fractional_step_of(model: mujoco.MjModel, start: np.ndarray, seconds: float) -> np.ndarray:
    """The state after one MuJoCo C step of ``seconds`` from ``start`` on a copy of ``model`` with that timestep."""
    data = mujoco.MjData(model)
    mujoco.mj_setState(model, data, start, STATE_SPEC)
    short = copy.copy(model)
    short.opt.timestep = seconds
    mujoco.mj_step(short, data)
    out = np.empty_like(start)
    mujoco.mj_getState(model, data, out, STATE_SPEC)
    return out


def test_advance_steps_a_fraction_of_the_timestep(model: mujoco.MjModel) -> None:
    start = _states(model, 1, swing=0.5)[0]
    models = _copies(model, 1)
    with MujocoBatch(models, start[None, :]) as batch:
        state = batch.advance(0, start, 0.0005)
    np.testing.assert_array_equal(state, fractional_step_of(model, start, 0.0005))
    assert state[0] == pytest.approx(0.0005) and models[0].opt.timestep == 0.002


def test_a_shared_model_is_copied_for_the_trajectory_an_event_changes(model: mujoco.MjModel) -> None:
    """Events on one trajectory of a shared model change that trajectory's own copy: the caller's model and the
    other trajectories keep theirs, and the released ball falls through as with a model of its own."""
    ball, drop = model.geom("ball").id, _column(model, "drop")
    filters, frictions = model.geom_contype.copy(), model.geom_friction.copy()
    with MujocoBatch(model, _states(model, 3)) as batch:
        batch.set_contact(1, ball, False)
        batch.set_friction(2, 0.25)
        rows = batch.run_chunk(200)
        assert batch.models[0] is model and batch.models[1] is not model and batch.models[2] is not model
        assert batch.models[1].geom_contype[ball] == 0 and batch.models[2].geom_friction[ball, 0] == 0.25
    np.testing.assert_array_equal(model.geom_contype, filters)
    np.testing.assert_array_equal(model.geom_friction, frictions)
    assert rows[0, -1, drop] > -0.01 and rows[2, -1, drop] > -0.01 and rows[1, -1, drop] < -0.5


def test_friction_set_per_trajectory_only(model: mujoco.MjModel) -> None:
    """Every geom's sliding friction in the changed trajectory's copy, and nowhere else."""
    with MujocoBatch(model, _states(model, 2)) as batch:
        batch.set_friction(1, 0.5)
        assert batch.models[1].geom_friction[:, 0].tolist() == [0.5] * model.ngeom
        np.testing.assert_array_equal(batch.models[1].geom_friction[:, 1:], model.geom_friction[:, 1:])
        assert batch.models[0] is model and model.geom_friction[0, 0] == 1.0
