"""The dm_control environments (:mod:`mjpoincare.envs`): the suite's contract for every scenario, named access, the
parameterised model, the reward's sign and the input check."""

from __future__ import annotations

import itertools
import unittest

import dm_env
import numpy as np
import pytest
from dm_control.rl import control
from dm_env import test_utils

from mjpoincare import envs, scenarios
from mjpoincare.core.params import ParameterError

pytestmark = pytest.mark.mujoco

STEPS = 50


@pytest.mark.parametrize("name", envs.ALL)
def test_environment_contract(name: str) -> None:
    """Like dm_control's domains_test: reset, specs match, 50 spec-valid steps stay finite and advance time."""
    env = envs.load(name, preset=scenarios.get(name).default_preset)
    assert isinstance(env, control.Environment)
    first = env.reset()
    assert first.first()
    spec = env.observation_spec()
    assert list(spec) == list(first.observation) == ["position", "velocity", "com_velocity"]
    for key, value in first.observation.items():
        spec[key].validate(value)
    action_spec = env.action_spec()
    assert action_spec.shape == (env.physics.model.nu,)
    action = action_spec.generate_value()  # the minimum: the largest torque the spec allows, on every actuator
    action_spec.validate(action)
    t0 = env.physics.data.time
    for _ in range(STEPS):
        step = env.step(action)
        assert step.mid()
        assert np.isfinite(step.reward)
        for key, value in step.observation.items():
            spec[key].validate(value)
            assert np.all(np.isfinite(value)), (key, value)
    n_sub_steps = envs.sub_steps(envs.DEFAULT_CONTROL_TIMESTEP, env.physics.timestep())
    assert env.control_timestep() == pytest.approx(n_sub_steps * env.physics.timestep())
    assert abs(env.control_timestep() - envs.DEFAULT_CONTROL_TIMESTEP) <= env.physics.timestep() / 2
    assert env.physics.data.time == pytest.approx(t0 + STEPS * env.control_timestep(), rel=1e-9)


@pytest.mark.parametrize("requested", [0.01, 0.0123, 0.025])
def test_control_timestep_is_rounded_to_whole_physics_steps(requested: float) -> None:
    """dm_control needs a control step of whole physics steps; the tuned timesteps rarely divide 10 ms, so a requested
    ``control_timestep`` is rounded to the nearest whole number of physics steps (within half a step)."""
    env = envs.load("rimless-wheel", environment_kwargs={"control_timestep": requested})
    h = env.physics.timestep()
    steps = env.control_timestep() / h
    assert steps == pytest.approx(round(steps), abs=1e-9)
    assert abs(env.control_timestep() - requested) <= h / 2
    env.reset()
    t0 = env.physics.data.time
    env.step([])
    assert env.physics.data.time == pytest.approx(t0 + env.control_timestep(), rel=1e-9)


def test_n_sub_steps_is_kept_and_a_bad_control_timestep_is_refused() -> None:
    env = envs.load("rimless-wheel", environment_kwargs={"n_sub_steps": 1})
    assert env.control_timestep() == pytest.approx(env.physics.timestep())
    with pytest.raises(ParameterError, match="control_timestep"):
        envs.load("rimless-wheel", environment_kwargs={"control_timestep": 0.0})


def test_dm_control_suite_shape_tasks_are_the_validated_behaviours() -> None:
    """``load(domain, task, task_kwargs, environment_kwargs, visualize_reward)`` as dm_control's ``suite.load``:
    the tasks are each scenario's coverage points (every pair in ``ALL_TASKS``), each setting its parameters; the
    preset is a keyword; an unknown domain or task is one line with the closest known name."""
    assert {domain for domain, _ in envs.ALL_TASKS} == set(envs.ALL)
    assert [t for d, t in envs.ALL_TASKS if d == "compass-biped-friction"] == [
        "gait_a", "gait_b", "gait_c", "gait_i", "gait_ii", "gait_iii"]
    assert ("rimless-wheel-friction", "type_d_plus") in envs.ALL_TASKS
    a = envs.load("compass-biped-friction", "gait_a", None, {"time_limit": 1.0})
    b = envs.load("compass-biped-friction", "gait_b", environment_kwargs={"time_limit": 1.0})
    friction = {name: env.physics.named.model.geom_friction["foot0"][0] for name, env in (("a", a), ("b", b))}
    assert friction == {"a": pytest.approx(1.0), "b": pytest.approx(0.14)}  # 002's paper values of the two gaits
    steep = envs.load("rimless-wheel", "steep", preset="accurate", environment_kwargs={"time_limit": 1.0})
    accurate = scenarios.get("rimless-wheel").preset("accurate")[1]
    assert steep.physics.timestep() == pytest.approx(float(accurate["timestep"]))
    gravity = steep.physics.model.opt.gravity
    assert np.arctan2(gravity[0], -gravity[2]) == pytest.approx(0.25)  # the task's slope
    with pytest.raises(ParameterError, match="unknown scenario 'rimless_wheel'; did you mean 'rimless-wheel'"):
        envs.load("rimless_wheel", "defaults")
    with pytest.raises(ParameterError, match="unknown task 'stepp' of domain rimless-wheel; did you mean 'steep'"):
        envs.load("rimless-wheel", "stepp")


def test_a_preset_as_the_task_still_loads_with_a_deprecation_warning() -> None:
    with pytest.warns(DeprecationWarning, match="pass preset='accurate'"):
        env = envs.load("rimless-wheel", "accurate", environment_kwargs={"time_limit": 1.0})
    accurate = scenarios.get("rimless-wheel").preset("accurate")[1]
    assert env.physics.timestep() == pytest.approx(float(accurate["timestep"]))
    with pytest.warns(DeprecationWarning, match="suite_load is envs.load"):
        envs.suite_load("rimless-wheel", "steep", environment_kwargs={"time_limit": 1.0})


def test_visualize_reward_colours_the_tracked_body_by_its_reward() -> None:
    """Off: colours never change; on: the tracked body's geoms move toward the highlight as the wheel rolls
    downhill at its gait's speed, and nothing else changes colour."""
    plain = envs.load("rimless-wheel", environment_kwargs={"time_limit": 1.0})
    shown = envs.load("rimless-wheel", visualize_reward=True, environment_kwargs={"time_limit": 1.0})
    before = shown.physics.model.geom_rgba.copy()
    plain_before = plain.physics.model.geom_rgba.copy()
    for env in (plain, shown):
        env.reset()
        for _ in range(5):
            env.step(np.zeros(env.action_spec().shape))
    assert np.array_equal(plain.physics.model.geom_rgba, plain_before)
    changed = np.flatnonzero(np.any(shown.physics.model.geom_rgba != before, axis=1))
    model = shown.physics.model
    tracked = model.body(scenarios.get("rimless-wheel").track_body).id
    assert changed.size and all(model.body_rootid[model.geom_bodyid[g]] == model.body_rootid[tracked]
                                for g in changed)
    toward = np.abs(shown.physics.model.geom_rgba[changed] - np.asarray(envs.REWARD_HIGHLIGHT))
    assert np.all(toward <= np.abs(before[changed] - np.asarray(envs.REWARD_HIGHLIGHT)) + 1e-12)
    with pytest.raises(ParameterError, match="visualize_reward must be True or False"):
        envs.load("rimless-wheel", visualize_reward=1)  # type: ignore[arg-type]


def test_named_access_and_parameterised_model() -> None:
    """Joints and bodies by name, on the model built with the given parameters (not the raw MJCF)."""
    env = envs.load("rimless-wheel", mass=2.5, spokes=10)
    obs = env.reset().observation
    named = env.physics.named
    assert named.data.qpos["pitch"] == obs["position"][2]
    assert named.data.qvel["x"] == obs["velocity"][0]
    assert named.model.body_mass["hub"] == pytest.approx(2.5)
    assert sum(name.startswith("foot") for name in named.model.geom_size.axes.row.names) == 10
    biped = envs.load("compass-biped")
    biped.reset()
    assert biped.physics.named.data.qpos["leg1"] == biped.physics.data.qpos[3]


def test_rimless_wheel_rolls_down_the_slope() -> None:
    """From the validation's start the wheel rolls towards +x (down the tilted-gravity slope): positive reward.

    Measured (fast preset before the search, first start, 0.85 x the rolling fixed point's speed): 0.93 m/s after one
    step, 0.89 after 20 ms, at least 0.27 over the first second; the gait settles near 0.75 m/s.
    """
    env = envs.load("rimless-wheel")
    x0 = env.reset().observation["position"][0]
    rewards = [env.step([]).reward for _ in range(round(0.1 / env.control_timestep()))]  # 0.1 s
    assert min(rewards) > 0.5
    assert env.physics.named.data.qpos["x"] > x0 + 0.1 * min(rewards)


def test_compass_biped_actions_are_torques() -> None:
    """The actuators are built with zero gain; the environment's unit gain makes an action a torque in N m."""
    env = envs.load("compass-biped")
    env.reset()
    physics = env.physics
    assert [physics.model.actuator(i).name for i in range(physics.model.nu)] == ["ankle0", "ankle1", "hip"]
    physics.set_control([0.0, 0.0, 2.0])
    physics.forward()
    assert physics.named.data.qfrc_actuator["leg1"] == pytest.approx(2.0)
    assert physics.named.data.qfrc_actuator["leg0"] == pytest.approx(-2.0)


def test_random_start_and_bad_start() -> None:
    """``start=None`` draws a row of the validation's start batch per episode; a bad row is refused."""
    env = envs.load("rimless-wheel", task_kwargs={"start": None, "random": 0})
    starts = env.task.starts
    for _ in range(3):
        velocity = env.reset().observation["velocity"]
        assert np.any(np.all(np.isclose(starts[:, 4:7], velocity), axis=1))
    with pytest.raises(ParameterError, match="start"):
        envs.load("rimless-wheel", task_kwargs={"start": len(starts)})


@pytest.mark.parametrize(("values", "named"), [({"spokes": 2}, "spokes"), ({"bogus": 1}, "bogus"),
                                               ({"timestep": -1.0}, "timestep")])
def test_bad_parameter_raises(values: dict, named: str) -> None:
    with pytest.raises(ParameterError, match=named):
        envs.load("rimless-wheel", **values)


def test_unknown_scenario_raises() -> None:
    with pytest.raises(ParameterError, match="unknown scenario"):
        envs.load("no-such-system")


#: Random in-spec actions each environment is stepped with, over episodes cut short so that several end.
RANDOM_STEPS = 3000
SHORT_EPISODE = 0.05  # s


@pytest.mark.parametrize("name", envs.ALL)
def test_random_actions_within_the_spec_keep_the_dm_env_contract(name: str) -> None:
    """Thousands of steps under random actions inside ``action_spec()`` raise nothing, stay finite, and each episode
    runs FIRST (no reward, no discount), MID (reward, discount 1), ..., LAST at its time limit, then restarts."""
    env = envs.load(name, environment_kwargs={"time_limit": SHORT_EPISODE})
    spec = env.action_spec()
    assert np.all(np.isfinite(spec.minimum)) and np.all(np.isfinite(spec.maximum))
    rng = np.random.default_rng(0)
    step = env.reset()
    types, episodes = [step.step_type], 0
    assert step.reward is None and step.discount is None
    for _ in range(RANDOM_STEPS):
        action = rng.uniform(spec.minimum, spec.maximum).astype(spec.dtype)
        step = env.step(action)
        types.append(step.step_type)
        if step.first():
            assert step.reward is None and step.discount is None
            continue
        assert np.isfinite(step.reward) and step.discount == 1.0
        assert all(np.all(np.isfinite(v)) for v in step.observation.values())
        episodes += step.last()
    assert episodes >= 2
    first, mid, last = dm_env.StepType.FIRST, dm_env.StepType.MID, dm_env.StepType.LAST
    allowed = {(first, mid), (mid, mid), (mid, last), (last, first)}
    assert all(pair in allowed for pair in itertools.pairwise(types))


def test_biped_actions_are_bounded_by_the_walkers_weight_torque() -> None:
    """The bipeds' actuators have no control range in the validation model; the environment bounds them by the
    walker's weight times its extent and MuJoCo clamps to it."""
    env = envs.load("compass-biped")
    model = env.physics.model.ptr
    limit = envs.weight_torque(model)
    assert limit == pytest.approx(20.0 * 9.81 * model.stat.extent, rel=1e-3)
    assert np.all(env.action_spec().maximum == limit) and np.all(env.action_spec().minimum == -limit)
    env.reset()
    env.physics.set_control([0.0, 0.0, 10 * limit])
    env.physics.forward()
    assert env.physics.named.data.qfrc_actuator["leg1"] == pytest.approx(limit)


def _conformance_case(name: str) -> type:
    """dm_env's own conformance tests (reset, step after reset, a longer action sequence) for one environment."""
    return type(f"TestDmEnvConformance_{name.replace('-', '_')}", (test_utils.EnvironmentTestMixin, unittest.TestCase),
                {"make_object_under_test": lambda self: envs.load(name)})


for _name in envs.ALL:
    _case = _conformance_case(_name)
    globals()[_case.__name__] = _case
