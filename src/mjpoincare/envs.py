"""The validated systems as dm_control environments: ``load(domain_name, task_name=None, task_kwargs=None,
environment_kwargs=None, visualize_reward=False, *, preset=None, **values)``, ``dm_control.suite.load``'s shape.

The domain is a scenario (:data:`ALL`); its tasks are the behaviours the suite validates it on, its coverage points
(:data:`ALL_TASKS`): ``defaults`` and ``steep`` for ``rimless-wheel``, ``gait_a`` to ``gait_iii`` for
``compass-biped-friction``, ``type_a`` to ``type_d_plus`` for ``rimless-wheel-friction``...; each task sets the
parameters of its point, and ``**values`` set more on top. The simulator preset is the keyword ``preset``.

Each registered scenario (:data:`ALL`) loads as a :class:`dm_control.rl.control.Environment`, in the manner of
``dm_control.suite``: a :class:`Physics` over the scenario's compiled model with the given physical parameters and
simulator settings applied (``scenario.build``, through MjSpec, not the raw MJCF file), and a :class:`SystemTask`
that starts each episode from a full-physics start state the validation itself starts from
(``scenario.validation_batches``'s first batch, around the analytic fixed point or gait of the paper in
``scenario.source``, kept as ``task.source``): its first row by default, ``task_kwargs={"start": i}`` row ``i``,
``{"start": None}`` a random row per episode.

* Observations: ``position`` (qpos), ``velocity`` (qvel), ``com_velocity`` (world-frame velocity of the centre of
  mass of ``scenario.track_body``'s subtree: the whole wheel, walker or skate).
* Reward: the down-slope speed of that centre of mass, m/s (the slope is tilted gravity, so down-slope is the
  horizontal part of ``model.opt.gravity``: model +x); with no slope (``slotted-skate``, gravity off) its
  horizontal speed. With ``visualize_reward=True`` the tracked body's geoms turn from their own colour to
  :data:`REWARD_HIGHLIGHT` as the reward rises from 0 to the start state's speed (dm_control's suite blends its
  ``self`` materials the same way; these models have no such materials).
* Actions: one per model actuator. Only the compass bipeds have any: ``ankle0``, ``ankle1`` on the leg hinges and
  ``hip`` on the ``leg1 - leg0`` tendon. The MJCF builds them with zero gain (the validation drives them through
  their biases), so the environment sets a unit gain: an action is a torque, N m, within +-:func:`weight_torque`
  (the system's weight times its extent; MuJoCo clamps to it) (with ``gait=iii`` of
  ``compass-biped-friction`` the ankles keep the PD bias ``-kp q - kd q_dot`` the scenario builds in, and an ankle
  action is the PD's reference term ``kp q_ref + kd q_ref_dot``). The others have an empty action.

What the environment does NOT do: it steps plain MuJoCo physics, without the validation's event controllers. The
planar rimless wheels (``rimless-wheel``, ``rimless-wheel-friction``) and ``rimless-wheel-3d`` with
``impact=contact`` (the default) need none: their environments are the validated simulation. For the others a user
gets the validated model and start, and their own controller acts through ``physics`` and the actions:

* ``compass-biped``, ``compass-biped-friction``: no contact switching (the swing foot's contact is not switched off
  after heel strike nor back on once ahead and clear, the trailing foot is not released at heel strike; the
  validation switches the contacts of ``foot0`` / ``foot1`` per trajectory through the seam). The swing foot
  catches the slope near legs-parallel (t = 0.24 s on the default ``compass-biped``) and the walker falls forward,
  legs together. No constant or PD torques either (``tau_ankle``, ``tau_hip``, gaits ``i`` / ``iii``), and no phase
  reset.
* ``slotted-skate``: no peg switching at the slot ends: the one peg stays in and the slot acts as if unbounded.
* ``rimless-wheel-3d`` with ``impact=ideal``: no impact law and no pivot moves: the wheel swings about one foot
  (through the slope: contact is off in that mode).
"""

from __future__ import annotations

import collections
import contextlib
import re
import warnings
from collections.abc import Iterator, Mapping
from typing import Any

import mujoco
import numpy as np
from dm_control import mujoco as dm_mujoco
from dm_control.mujoco import wrapper
from dm_control.mujoco.wrapper.mjbindings import sizes
from dm_control.rl import control
from dm_control.suite import base

from mjpoincare import scenarios
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.params import ParameterError, Value, did_you_mean, typed
from mjpoincare.scenarios.base import CoveragePoint

#: The loadable names: every scenario of the registry whose module and declaration load.
ALL: tuple[str, ...] = tuple(scenarios.loadable())
#: Default episode length, s (``environment_kwargs={"time_limit": ...}`` overrides it).
DEFAULT_TIME_LIMIT = 10.0
#: Default control timestep, s, as in dm_control's suite (10-25 ms); rounded to whole physics steps
#: (:func:`sub_steps`).
DEFAULT_CONTROL_TIMESTEP = 0.01
#: The colour a tracked body's geoms blend to as the reward reaches the start state's speed (visualize_reward).
REWARD_HIGHLIGHT = (1.0, 0.55, 0.1, 1.0)


def task_name_of(point: str) -> str:
    """A coverage point's name as a task name: ``"Gait A"`` -> ``"gait_a"``, ``"Type D+"`` -> ``"type_d_plus"``."""
    return re.sub(r"[^a-z0-9]+", "_", point.lower().replace("+", " plus")).strip("_")


def tasks(domain_name: str) -> dict[str, CoveragePoint]:
    """The tasks of a domain: its scenario's coverage points (the behaviours the suite validates), by task name."""
    return {task_name_of(point.name): point for point in scenarios.get(domain_name).coverage}


#: ``(domain, task)`` pairs, as ``dm_control.suite.ALL_TASKS``: each scenario with each of its coverage points.
ALL_TASKS: tuple[tuple[str, str], ...] = tuple((name, task) for name in ALL for task in tasks(name))
_FULLPHYSICS = mujoco.mjtState.mjSTATE_FULLPHYSICS


@contextlib.contextmanager
def _known_fields(model: mujoco.MjModel, data: mujoco.MjData) -> Iterator[None]:
    """dm_control's named-index table without the fields the installed ``mujoco`` no longer has.

    dm_control 1.0.50 lists flex fields that mujoco 4.0 removed (``flex_vertedge``, ``flexvert_J``...) and its
    named indexing fails on the first one it cannot read, for every model (its own suite included). Only while
    a :class:`Physics` sets up its indexing, and only when a field is missing, the table is swapped for a copy
    without those fields; nothing that exists is touched.
    """
    table = sizes.array_sizes
    kept = {struct: {f: dims for f, dims in fields.items() if hasattr(obj, f)}
            for struct, fields, obj in (("mjmodel", table["mjmodel"], model), ("mjdata", table["mjdata"], data))}
    if all(len(kept[s]) == len(table[s]) for s in kept):
        yield
        return
    sizes.array_sizes = {**table, **kept}
    try:
        yield
    finally:
        sizes.array_sizes = table


class Physics(dm_mujoco.Physics):
    """dm_control physics of a validated system, with the centre-of-mass velocity the reward reads."""

    def _reload_from_data(self, data: wrapper.MjData) -> None:
        with _known_fields(data.model.ptr, data.ptr):
            super()._reload_from_data(data)

    def subtree_velocity(self, body: str) -> np.ndarray:
        """World-frame linear velocity of the centre of mass of ``body``'s subtree.

        MuJoCo fills ``subtree_linvel`` only on demand, so this calls ``mj_subtreeVel`` first.
        """
        mujoco.mj_subtreeVel(self.model.ptr, self.data.ptr)
        return np.array(self.named.data.subtree_linvel[body])

    def downhill(self) -> np.ndarray | None:
        """Unit down-slope direction: the horizontal part of gravity (the slope is tilted gravity); None if level."""
        g = np.array(self.model.opt.gravity, float)
        g[2] = 0.0
        norm = float(np.linalg.norm(g))
        return g / norm if norm > 0.0 else None


class SystemTask(base.Task):
    """Start from the validation's start state, observe the state, reward down-slope speed."""

    def __init__(self, track_body: str, starts: np.ndarray, start: int | None = 0,
                 random: int | np.random.RandomState | None = None, source: str = "") -> None:
        """
        Args:
            track_body: body whose subtree's centre of mass the reward and ``com_velocity`` follow.
            starts: full-physics start states, (batch, nstate).
            start: row of ``starts`` each episode starts from; None draws one per episode with ``self.random``.
            random: seed or ``RandomState`` of that draw.
            source: the analytic reference the start comes from (the scenario's ``source``).
        """
        starts = np.atleast_2d(np.asarray(starts, float))
        if start is not None and (isinstance(start, bool) or not isinstance(start, int)
                                  or not 0 <= start < len(starts)):
            raise ParameterError(f"start must be None or an integer in [0, {len(starts)}) (got {start!r})")
        self.track_body, self.starts, self.start, self.source = track_body, starts, start, source
        self._reward_scale = 1.0
        self._shown: tuple[np.ndarray, np.ndarray] | None = None  # the tracked geoms and their own colours
        super().__init__(random=random)

    def initialize_episode(self, physics: Physics) -> None:
        """Set the chosen start state (time, qpos, qvel, act, mocap, active equalities...)."""
        row = self.random.randint(len(self.starts)) if self.start is None else self.start
        mujoco.mj_setState(physics.model.ptr, physics.data.ptr, self.starts[row], _FULLPHYSICS)
        mujoco.mj_forward(physics.model.ptr, physics.data.ptr)
        self._reward_scale = abs(self.get_reward(physics)) or 1.0
        super().initialize_episode(physics)

    def after_step(self, physics: Physics) -> None:
        """With ``visualize_reward``: blend the tracked body's geoms from their own colour to
        :data:`REWARD_HIGHLIGHT` by the reward over the start state's speed, clipped to [0, 1]."""
        if not self.visualize_reward:
            return
        model = physics.model.ptr
        if self._shown is None:  # found once: the control loop then only blends
            geoms = _subtree_geoms(model, model.body(self.track_body).id)
            self._shown = geoms, model.geom_rgba[geoms].copy()
        geoms, colours = self._shown
        blend = float(np.clip(self.get_reward(physics) / self._reward_scale, 0.0, 1.0))
        model.geom_rgba[geoms] = (1.0 - blend) * colours + blend * np.asarray(REWARD_HIGHLIGHT)

    def get_observation(self, physics: Physics) -> collections.OrderedDict[str, np.ndarray]:
        """``position`` (qpos), ``velocity`` (qvel), ``com_velocity`` (tracked subtree's centre of mass, world)."""
        obs: collections.OrderedDict[str, np.ndarray] = collections.OrderedDict()
        obs["position"] = physics.data.qpos.copy()
        obs["velocity"] = physics.data.qvel.copy()
        obs["com_velocity"] = physics.subtree_velocity(self.track_body)
        return obs

    def get_reward(self, physics: Physics) -> float:
        """Down-slope speed of the tracked centre of mass, m/s (horizontal speed when there is no slope)."""
        velocity = physics.subtree_velocity(self.track_body)
        direction = physics.downhill()
        if direction is None:
            return float(np.linalg.norm(velocity[:2]))
        return float(velocity @ direction)


def _subtree_geoms(model: mujoco.MjModel, body: int) -> np.ndarray:
    """The geoms of ``body`` and of every body below it."""
    inside = np.zeros(model.nbody, bool)
    for b in range(model.nbody):  # a parent's id is below its children's
        inside[b] = b == body or (b > 0 and inside[model.body_parentid[b]])
    return np.flatnonzero(inside[model.geom_bodyid])


def _unit_gains(model: mujoco.MjModel) -> None:
    """Give fixed-gain actuators built with zero gain a unit gain, so that ``ctrl`` is the force or torque."""
    for i in range(model.nu):
        if model.actuator_gaintype[i] == mujoco.mjtGain.mjGAIN_FIXED and model.actuator_gainprm[i, 0] == 0.0:
            model.actuator_gainprm[i, 0] = 1.0


def weight_torque(model: mujoco.MjModel) -> float:
    """The system's weight times its extent, N m: the largest torque its own weight can exert about a point within
    its size (for the compass bipeds, holding the whole walker on one horizontal leg: 196 N m at the defaults)."""
    return float(model.body_subtreemass[0] * np.linalg.norm(model.opt.gravity) * model.stat.extent)


def _limit_controls(model: mujoco.MjModel) -> None:
    """Bound every actuator without a control range to +-:func:`weight_torque` (MuJoCo clamps ``ctrl`` to it).

    The papers' torques lie far inside: the actuated compass gait's 0.5 and 0.2 N m (Kiša 2020 Sec. 4), Gait I's
    constant torques and Gait III's PD reference terms, tens of N m at most (Gamus & Or 2015 eqs 29-30).
    """
    limit = weight_torque(model)
    for i in range(model.nu):
        if not model.actuator_ctrllimited[i]:
            model.actuator_ctrllimited[i] = 1
            model.actuator_ctrlrange[i] = (-limit, limit)


def sub_steps(control_timestep: float, physics_timestep: float) -> int:
    """Whole physics steps per control step: ``control_timestep / physics_timestep`` rounded to the nearest integer,
    at least 1 (the environment's ``control_timestep()`` is then that many physics steps, which is what dm_control
    requires; the requested and the rounded value differ by at most half a physics step)."""
    if not control_timestep > 0:
        raise ParameterError(f"control_timestep must be > 0 s (got {control_timestep!r})")
    return max(1, round(control_timestep / physics_timestep))


def load(domain_name: str, task_name: str | None = None, task_kwargs: Mapping[str, Any] | None = None,
         environment_kwargs: Mapping[str, Any] | None = None, visualize_reward: bool = False, *,
         preset: str | None = None, **values: Value) -> control.Environment:
    """The dm_control environment of scenario ``domain_name`` doing task ``task_name``, as
    ``dm_control.suite.load(domain_name, task_name, task_kwargs, environment_kwargs, visualize_reward)``.

    Args:
        domain_name: a registered scenario (:data:`ALL`), e.g. ``"rimless-wheel"``.
        task_name: one of the scenario's validated behaviours (:func:`tasks`, :data:`ALL_TASKS`), e.g. ``"steep"``
            or ``"gait_b"``; None is its first (the scenario's defaults, or its first gait).
        task_kwargs: passed to :class:`SystemTask`: ``start`` (row of the start batch, None: random) and ``random``.
        environment_kwargs: passed to :class:`dm_control.rl.control.Environment` (``time_limit``, default
            :data:`DEFAULT_TIME_LIMIT`; ``n_sub_steps``, or ``control_timestep`` in s, default
            :data:`DEFAULT_CONTROL_TIMESTEP`, rounded to whole physics steps by :func:`sub_steps`: the environment's
            ``control_timestep()`` returns the rounded value).
        visualize_reward: colour the tracked body by the reward in rendered frames (:meth:`SystemTask.after_step`).
        preset: simulator preset (``"fast"``, ``"accurate"``, ...); None is the scenario's default.
        **values: physical parameters and simulator settings on top of the task's, typed (``spokes=8``; text for a
            number is refused), as for :func:`mjpoincare.validate`.

    Raises:
        ParameterError: any bad input (unknown scenario, task, preset or parameter, value out of range), one line.
    """
    scenario = scenarios.get(domain_name)
    known = tasks(domain_name)
    if task_name in scenario.presets and task_name not in known:
        warnings.warn(f"envs.load({domain_name!r}, {task_name!r}): the second argument is the task now, as in "
                      f"dm_control.suite.load; pass preset={task_name!r}", DeprecationWarning, stacklevel=2)
        task_name, preset = None, task_name
    if task_name is None:
        task_name = next(iter(known))
    if task_name not in known:
        raise ParameterError(f"unknown task {task_name!r} of domain {domain_name}{did_you_mean(task_name, known)}; "
                             f"known: {', '.join(known)}")
    if preset is not None and preset not in scenario.presets:
        raise ParameterError(f"preset must be one of {', '.join(scenario.presets)} (got {preset!r})")
    if not isinstance(visualize_reward, bool):
        raise ParameterError(f"visualize_reward must be True or False (got {visualize_reward!r})")
    typed([*scenario.params, *sim_settings.SETTINGS], values)
    point: dict[str, Value] = dict(known[task_name].assignments)  # --set text, as the coverage point declares it
    scenario, _, params, settings = resolve_inputs(domain_name, {**point, **values}, preset)
    model, batches = scenario.validation_batches(params, settings)
    _unit_gains(model)
    _limit_controls(model)
    physics = Physics.from_model(wrapper.MjModel(model))
    task = SystemTask(scenario.track_body, batches[0][0], source=scenario.source, **dict(task_kwargs or {}))
    task.visualize_reward = visualize_reward
    kwargs = {"time_limit": DEFAULT_TIME_LIMIT, **dict(environment_kwargs or {})}
    if "n_sub_steps" not in kwargs:
        requested = kwargs.pop("control_timestep", DEFAULT_CONTROL_TIMESTEP)
        kwargs["n_sub_steps"] = sub_steps(requested, model.opt.timestep)
    return control.Environment(physics, task, **kwargs)


def suite_load(domain_name: str, task_name: str, task_kwargs: Mapping[str, Any] | None = None,
               environment_kwargs: Mapping[str, Any] | None = None, visualize_reward: bool = False,
               **values: Value) -> control.Environment:
    """Deprecated: :func:`load` has ``dm_control.suite.load``'s shape now (its tasks are behaviours, the preset a
    keyword); a preset as the task still works, with a warning."""
    warnings.warn("envs.suite_load is envs.load now", DeprecationWarning, stacklevel=2)
    return load(domain_name, task_name, task_kwargs, environment_kwargs, visualize_reward, **values)


__all__ = ["ALL", "ALL_TASKS", "DEFAULT_CONTROL_TIMESTEP", "DEFAULT_TIME_LIMIT", "REWARD_HIGHLIGHT", "Physics",
           "SystemTask", "load", "sub_steps", "suite_load", "tasks"]
