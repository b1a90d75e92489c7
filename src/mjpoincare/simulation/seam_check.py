"""The harness checks itself: each mechanism of the rollout seam (:class:`mjpoincare.core.seam.Batch`) run on a tiny
model, on the MuJoCo release and the backend actually loaded, before a scenario that uses it runs.

A scenario declares the mechanisms its event controllers use (``Scenario.seam_mechanisms``). :func:`require` runs their
self-tests once per process, backend and precision; a mechanism that does not do what the seam promises raises
:class:`MechanismFailed` (a :class:`~mjpoincare.core.params.ParameterError`, so the command line exits 2 with one line
naming the mechanism and the release), and no physics is reported from a harness that did not work.

Each self-test is a physical observation with a margin of an order of magnitude, not a reading of the fields it
wrote. The model: two balls resting on a plane, a 1 kg ball and a 0.1 kg pebble (two colliding pairs: their contacts,
friction and fields), a bob on a vertical slide held by a joint equality, and a free 0.5 kg lift on a vertical slide
with an affine actuator (its bias force and gear) and a motor (native control). Free fall over ``T = 0.05 s`` drops
``g T^2 / 2 = 12.3 mm``; a held body moves less than 1 mm in that time. Every self-test steps
:data:`TRAJECTORIES` trajectories that its events set apart (which ball is released, the friction coefficient, the
fraction of a step, the gear, the control), so that a mechanism that acts on the wrong trajectory or geom, or drops
an argument, is seen.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import mujoco
import numpy as np

from mjpoincare.core.mjcompat import efc_diag_inverse_inertia
from mjpoincare.core.params import ParameterError
from mjpoincare.core.seam import STATE_SPEC, Batch
from mjpoincare.engines.backends import open_batch
from mjpoincare.simulation.simulate import initial_states

GRAVITY = 9.81
#: Steps of each observation, at the model's timestep of 1 ms.
STEPS = 50
TIMESTEP = 1e-3
#: Free fall over the observation, m.
FREE_FALL = 0.5 * GRAVITY * (STEPS * TIMESTEP) ** 2
#: A body the seam holds (contact, equality, actuator on) moves less than this, m (a tenth of the free fall).
HELD = 0.1 * FREE_FALL
#: What agrees exactly agrees to this many machine epsilons of the backend's precision (times of at most 1 s, speeds
#: of at most 1 m/s): rounding, never a missing or wrong mechanism.
EXACT = 64.0
#: Radius of both balls, m.
RADIUS = 0.1
#: Masses of the ball and the pebble, kg: a decade apart, so that a contact field read at the other contact's rows
#: is off by a factor of ten.
BALL, PEBBLE = 1.0, 0.1
#: How deep a resting ball starts pressed into the plane, m.
PRESS = 1e-4
#: Masses of the bob and the lift, kg, so that the bodies add up to 2 kg: Drake's contact stiffness is built on the
#: moving mass (:mod:`mjpoincare.engines.backends.drake_plant`), and its contact release is measured at that
#: (docs/engines.md).
BOB, LIFT = 0.4, 0.5
#: The lift's weight, N.
WEIGHT = LIFT * GRAVITY
#: Trajectories of every self-test: one shape, so that MJX and MuJoCo Warp compile one chunk for them all.
TRAJECTORIES = 3

_MODEL = f"""
<mujoco model="seam self-test">
  <option timestep="{TIMESTEP}" gravity="0 0 -{GRAVITY}" cone="elliptic"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" contype="0" conaffinity="1" condim="3"/>
    <body name="ball" pos="0 0 {RADIUS}">
      <joint name="ball_x" type="slide" axis="1 0 0"/>
      <joint name="ball_z" type="slide" axis="0 0 1"/>
      <geom name="ball" type="sphere" size="{RADIUS}" mass="{BALL}" contype="1" conaffinity="0" condim="3"
            friction="1 0 0"/>
    </body>
    <body name="pebble" pos="1 0 {RADIUS}">
      <joint name="pebble_x" type="slide" axis="1 0 0"/>
      <joint name="pebble_z" type="slide" axis="0 0 1"/>
      <geom name="pebble" type="sphere" size="{RADIUS}" mass="{PEBBLE}" contype="1" conaffinity="0" condim="3"
            friction="1 0 0"/>
    </body>
    <body name="bob" pos="2 0 1">
      <joint name="bob_z" type="slide" axis="0 0 1"/>
      <geom name="bob" type="sphere" size="0.05" mass="{BOB}" contype="0" conaffinity="0"/>
    </body>
    <body name="lift" pos="3 0 1">
      <joint name="lift_z" type="slide" axis="0 0 1"/>
      <geom name="lift" type="sphere" size="0.05" mass="{LIFT}" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <equality>
    <joint name="hold" joint1="bob_z"/>
  </equality>
  <actuator>
    <general name="push" joint="lift_z" gaintype="fixed" gainprm="0" biastype="affine" biasprm="0 0 0"/>
    <general name="drive" joint="lift_z" gaintype="fixed" gainprm="0"/>
  </actuator>
</mujoco>
"""


#: Opens a batch of the backend under test over a model and its starts (B, nstate).
Opener = Callable[[mujoco.MjModel, np.ndarray], Batch]


class MechanismFailed(ParameterError):
    """A seam mechanism failed its self-test on the loaded MuJoCo and backend: the run is refused."""


@dataclass(frozen=True)
class Mechanism:
    """One mechanism of the seam and its self-test.

    Attributes:
        name: what the mechanism is, as the refusal names it.
        test: ``(opener, eps) -> None`` when it works, or what went wrong, in a few words with the numbers
            (``eps``: the machine epsilon of the backend's precision, which scales the exact comparisons).
        c_only: the mechanism reads MuJoCo C's ``mjData`` whatever the backend (a check's field), so it is tested on
            MuJoCo C.
    """

    name: str
    test: Callable[[Opener, float], str | None]
    c_only: bool = False


def self_test_model() -> mujoco.MjModel:
    """The self-tests' model (a ball and a pebble on a plane, a held bob, a lift with an affine actuator and a
    motor whose gain is 0: Drake refuses a model with an actuator that makes a force, and the control self-test
    sets it)."""
    return mujoco.MjModel.from_xml_string(_MODEL)


def _starts(model: mujoco.MjModel, *, height: float = -PRESS, speed: float = 0.0) -> np.ndarray:
    """:data:`TRAJECTORIES` identical starts: both balls' lowest points ``height`` above the plane (pressed
    :data:`PRESS` into it by default), sliding along it at ``speed``; the bob and the lift at rest."""
    qpos = np.zeros((TRAJECTORIES, model.nq))
    qvel = np.zeros((TRAJECTORIES, model.nv))
    for ball in ("ball", "pebble"):  # slide joints measure from the body's position
        qpos[:, model.joint(f"{ball}_z").qposadr[0]] = height
        qvel[:, model.joint(f"{ball}_x").dofadr[0]] = speed
    return initial_states(model, qpos, qvel)


def _coordinate(model: mujoco.MjModel, joint: str) -> int:
    """Column of joint ``joint``'s coordinate in a recorded state (time first)."""
    return 1 + int(model.joint(joint).qposadr[0])


def _speed(model: mujoco.MjModel, joint: str) -> int:
    """Column of joint ``joint``'s speed in a recorded state."""
    return 1 + model.nq + int(model.joint(joint).dofadr[0])


def _drops(batch: Batch, columns: list[int]) -> np.ndarray:
    """How far each trajectory's coordinates ``columns`` fall over one observation, m (B, k)."""
    chunk = batch.run_chunk(STEPS)
    return chunk[:, 0, columns] - chunk[:, -1, columns]


def _mm(values: np.ndarray) -> list:
    """Lengths ``values``, m, in mm to the micrometre (for a message)."""
    return np.round(np.asarray(values) * 1e3, 3).tolist()


def _rollout(opener: Opener, eps: float) -> str | None:
    model = self_test_model()
    z = _coordinate(model, "ball_z")
    start = _starts(model, height=1.0)  # in the air
    with opener(model, start) as batch:
        first = batch.run_chunk(STEPS)
        batch.set_states(np.array([1]), start[1:2])  # trajectory 1 starts again, trajectories 0 and 2 go on
        second = batch.run_chunk(STEPS)
        third = batch.run_chunk(STEPS, rows=np.array([0, 2]))  # trajectory 1 waits
        waited = (bool(np.isnan(third[1]).all()) and bool((batch.states()[1] == second[1, -1]).all())
                  and not batch.report.diverged.any() and bool((third[[0, 2], 0] == second[[0, 2], -1]).all()))
    if not waited:
        return ("a chunk of trajectories 0 and 2 did not leave trajectory 1 where it was (its rows NaN, its state "
                "kept, not flagged) or did not continue the others")
    ticks = np.concatenate([np.diff(first[:, :, 0]), np.diff(second[:, :, 0])], axis=1)
    if not (np.abs(ticks - TIMESTEP) < EXACT * eps).all():  # rounding of times near 0.1 s
        return f"recorded times advance by {ticks.min():.6g}-{ticks.max():.6g} s per step, not the timestep"
    drop = first[:, 0, z] - first[:, -1, z]
    again = second[1, 0, z] - second[1, -1, z]
    went_on = (second[[0, 2], 0] == first[[0, 2], -1]).all()
    if not ((np.abs(drop - FREE_FALL) < 0.05 * FREE_FALL).all() and abs(again - drop[1]) < EXACT * eps and went_on):
        return (f"falling balls dropped {_mm(drop)} mm (free fall {FREE_FALL * 1e3:.4g}), the one set back to its "
                f"start {again * 1e3:.4g} mm, the others {'went on' if went_on else 'were moved'}")
    return None


def _release_and_restore(opener: Opener, release: Callable[[Batch], None], restore: Callable[[Batch], None],
                         joints: tuple[str, ...], falls: np.ndarray, still_falls: np.ndarray, what: str
                         ) -> str | None:
    """``release`` frees, in each trajectory, the bodies (on the vertical slides ``joints``) that ``falls`` (B, k)
    marks: each of them falls freely over an observation while every other stays held. Then ``restore`` holds some
    of them again and every trajectory is set back to its start: those ``still_falls`` marks fall freely again, every
    other body stays held."""
    model = self_test_model()
    columns = [_coordinate(model, joint) for joint in joints]
    with opener(model, _starts(model)) as batch:
        start = batch.states()
        release(batch)
        released = _drops(batch, columns)
        restore(batch)
        batch.set_states(np.arange(TRAJECTORIES), start)
        restored = _drops(batch, columns)
    fell = np.concatenate([released[falls], restored[still_falls]])
    if not (np.abs(fell - FREE_FALL) < 0.1 * FREE_FALL).all():
        return (f"{what}: the released ones fell {_mm(released[falls])} mm, then {_mm(restored[still_falls])} mm, in "
                f"{STEPS * TIMESTEP:g} s (free fall {FREE_FALL * 1e3:.3g})")
    moved = max(np.abs(released[~falls]).max(initial=0.0), np.abs(restored[~still_falls]).max(initial=0.0))
    if not moved < HELD:
        return (f"{what}: a held (or restored) one moved {moved * 1e3:.3g} mm (drops by trajectory and body "
                f"{_mm(released)}, after the restore {_mm(restored)})")
    return None


def _contact_release(opener: Opener, eps: float) -> str | None:
    """Trajectory 1 releases the ball's contact, trajectory 2 the ball's and the pebble's (one geom released in two
    trajectories, as a biped releases the same foot in many); then trajectory 2 alone restores both, and trajectory
    1's ball must stay released (a release kept per geom, not per trajectory and geom, fails either half)."""
    model = self_test_model()
    ball, pebble = model.geom("ball").id, model.geom("pebble").id

    def release(batch: Batch) -> None:
        batch.set_contact(1, ball, False)
        batch.set_contact(2, ball, False)
        batch.set_contact(2, pebble, False)

    def restore(batch: Batch) -> None:
        batch.set_contact(2, ball, True)
        batch.set_contact(2, pebble, True)

    falls = np.array([[False, False], [True, False], [True, True]])
    still_falls = np.array([[False, False], [True, False], [False, False]])
    return _release_and_restore(opener, release, restore, ("ball_z", "pebble_z"), falls, still_falls,
                                "balls resting on a plane (trajectory 1 releases the ball's contact, 2 the ball's and "
                                "the pebble's, then 2 restores both)")


def _equality_toggle(opener: Opener, eps: float) -> str | None:
    hold = self_test_model().equality("hold").id
    return _release_and_restore(opener, lambda batch: batch.set_eq_active(1, hold, False),
                                lambda batch: batch.set_eq_active(1, hold, True), ("bob_z",),
                                np.array([[False], [True], [False]]), np.zeros((TRAJECTORIES, 1), bool),
                                "bobs held by a joint equality (trajectory 1 releases it, then restores it)")


def _friction(opener: Opener, eps: float) -> str | None:
    model = self_test_model()
    mus = np.array([0.05, 0.2, 0.8])  # a factor of 4 apart: a coefficient set in another trajectory is seen
    columns = [_speed(model, "ball_x"), _speed(model, "pebble_x")]
    with opener(model, _starts(model, speed=1.0)) as batch:
        for index, mu in enumerate(mus):
            batch.set_friction(index, float(mu))
        chunk = batch.run_chunk(STEPS)
    lost = chunk[:, 0, columns] - chunk[:, -1, columns]  # each ball's speed lost to friction, m/s (B, 2)
    expected = mus[:, None] * GRAVITY * STEPS * TIMESTEP
    if not (np.abs(lost - expected) < 0.25 * expected).all():
        return (f"a ball and a pebble sliding at mu {mus.tolist()} lost {np.round(lost, 4).tolist()} m/s in "
                f"{STEPS * TIMESTEP:g} s (Coulomb: {np.round(expected[:, 0], 4).tolist()})")
    return None


def _fractional_step(opener: Opener, eps: float) -> str | None:
    """Each trajectory's own fraction of a step with its own model, from the state it is given: trajectory k's lift is
    pushed up by a bias force of k/2 its weight (through the actuator: a broken actuator fails this too), so over a
    step of ``h`` its speed changes by exactly ``(k/2 - 1) g h``. Each step starts from a state of its own, moving at
    a speed of its own, that is not the batch's current state (a step from the current state gains a speed off by
    the given one)."""
    model = self_test_model()
    push, vz = model.actuator("push").id, _speed(model, "lift_z")
    support = np.arange(TRAJECTORIES) / 2.0  # of the weight
    start = _starts(model)
    given = start.copy()
    given[:, 0] = [0.1, 0.2, 0.3]  # s
    given[:, vz] = [0.5, -0.25, 1.0]  # m/s
    with opener(model, start) as batch:
        for index in range(1, TRAJECTORIES):
            batch.set_actuator(index, push, bias=float(support[index]) * WEIGHT)
        fractions = np.array([0.2, 0.5, 0.8]) * batch.timestep
        after = np.array([batch.advance(index, given[index], float(fractions[index]))
                          for index in range(TRAJECTORIES)])
        full = batch.run_chunk(STEPS)
    dt, gained = after[:, 0] - given[:, 0], after[:, vz] - given[:, vz]
    expected = (support - 1.0) * GRAVITY * fractions
    if not ((np.abs(dt - fractions) < EXACT * eps).all() and (np.abs(gained - expected) < EXACT * eps).all()):
        return (f"steps of {np.round(fractions, 6).tolist()} s advanced the times by {np.round(dt, 6).tolist()} s "
                f"and the speeds of lifts held up by (0, 1/2, 1) x their weight by {np.round(gained, 6).tolist()} m/s "
                f"(expected {np.round(expected, 6).tolist()})")
    ticks = full[:, 1, 0] - full[:, 0, 0]
    if not (np.abs(ticks - TIMESTEP) < EXACT * eps).all():
        return f"the steps after fractional steps lasted {ticks.tolist()} s, not the timestep"
    return None


def _actuator(opener: Opener, eps: float) -> str | None:
    """Trajectory 1's lift is held up by a bias force of minus its weight through a gear of -1, trajectory 2's by half
    its weight through a gear of 2 (set before the bias, which must keep it); trajectory 0's falls freely."""
    model = self_test_model()
    push = model.actuator("push").id
    with opener(model, _starts(model)) as batch:
        batch.set_actuator(1, push, bias=-WEIGHT, gear=-1.0)
        batch.set_actuator(2, push, gear=2.0)
        batch.set_actuator(2, push, bias=0.5 * WEIGHT)
        drops = _drops(batch, [_coordinate(model, "lift_z")])[:, 0]
    if not (abs(drops[0] - FREE_FALL) < 0.1 * FREE_FALL and (np.abs(drops[1:]) < HELD).all()):
        return (f"lifts with bias forces (-1, 1/2) x their weight through gears (-1, 2) fell {_mm(drops[1:])} mm, "
                f"one without {drops[0] * 1e3:.3g} mm (free fall {FREE_FALL * 1e3:.3g})")
    return None


def _control(opener: Opener, eps: float) -> str | None:
    """Native control, per trajectory and per step: trajectory 0's lift gets no force and falls freely, trajectory
    1's its weight throughout and stays held, trajectory 2's twice its weight for the first half of the steps and
    none for the second, so it rises by half the free fall and comes to rest."""
    model = self_test_model()
    control = np.zeros((TRAJECTORIES, STEPS, model.nu))
    drive = model.actuator("drive").id
    model.actuator_gainprm[drive, 0] = 1.0  # 1 N per unit of ctrl
    control[1, :, drive] = WEIGHT
    control[2, : STEPS // 2, drive] = 2.0 * WEIGHT
    z, vz = _coordinate(model, "lift_z"), _speed(model, "lift_z")
    with opener(model, _starts(model)) as batch:
        chunk = batch.run_chunk(STEPS, control)
    drops, speed = chunk[:, 0, z] - chunk[:, -1, z], chunk[2, -1, vz]
    if not (abs(drops[0] - FREE_FALL) < 0.1 * FREE_FALL and abs(drops[1]) < HELD
            and abs(drops[2] + 0.5 * FREE_FALL) < HELD and abs(speed) < 0.1 * GRAVITY * STEPS * TIMESTEP):
        return (f"lifts driven by (0, 1, 2 then 0) x their weight fell {_mm(drops)} mm (free fall "
                f"{FREE_FALL * 1e3:.3g}, held, rising {0.5 * FREE_FALL * 1e3:.3g}), the last ending at {speed:.3g} m/s "
                "(at rest)")
    return None


def _contact_fields(opener: Opener, eps: float) -> str | None:
    """The ball and the pebble settled on the plane: each contact's normal force (``efc_force`` at its
    ``efc_address``) is its body's weight, and the diagonal inverse inertia of that row times that force is the
    acceleration it gives the body, g (a translating body's inverse inertia is 1/m in every direction)."""
    del opener, eps  # read from MuJoCo C's mjData in float64, whatever the backend
    model = self_test_model()
    data = mujoco.MjData(model)
    mujoco.mj_setState(model, data, _starts(model)[0], STATE_SPEC)
    for _ in range(STEPS):
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)
    diag = efc_diag_inverse_inertia(data)
    for name, mass in (("ball", BALL), ("pebble", PEBBLE)):
        touching = np.flatnonzero((data.contact.geom == model.geom(name).id).any(axis=1))
        if touching.size != 1:
            return f"the resting {name} has {touching.size} contacts with the plane, not 1"
        address = int(data.contact.efc_address[touching[0]])
        force, inverse = float(data.efc_force[address]), float(diag[address])
        if not (abs(force / (mass * GRAVITY) - 1.0) < 0.1 and abs(inverse * force / GRAVITY - 1.0) < 0.1):
            return (f"the resting {name}'s ({mass:g} kg) contact pushes with {force:.4g} N (its weight "
                    f"{mass * GRAVITY:.4g}), and its diagonal inverse inertia {inverse:.4g} 1/kg gives that force an "
                    f"acceleration of {inverse * force:.4g} m/s^2 (g {GRAVITY:g})")
    return None


#: Every mechanism of the seam, by the name a scenario declares.
MECHANISMS: dict[str, Mechanism] = {
    "rollout": Mechanism(name="chunked rollout, state setting and chunks of chosen trajectories", test=_rollout),
    "contact": Mechanism(name="contact release and restore", test=_contact_release),
    "equality": Mechanism(name="equality toggling", test=_equality_toggle),
    "friction": Mechanism(name="per-trajectory friction", test=_friction),
    "fractional_step": Mechanism(name="fractional steps", test=_fractional_step),
    "actuator": Mechanism(name="per-trajectory actuator force", test=_actuator),
    "control": Mechanism(name="native control", test=_control),
    "contact_fields": Mechanism(name="contact fields (normal force, diagonal inverse inertia)", test=_contact_fields,
                                c_only=True),
}


@cache
def failure(key: str, backend: str = "mujoco", precision: str = "float64") -> str | None:
    """What went wrong in mechanism ``key``'s self-test on ``backend`` at ``precision`` (None: it works), run once
    per process."""
    mechanism = MECHANISMS[key]
    if mechanism.c_only:
        backend, precision = "mujoco", "float64"
    eps = float(np.finfo(np.float32 if precision == "float32" else np.float64).eps)

    def opener(model: mujoco.MjModel, state0: np.ndarray) -> Batch:
        return open_batch(model, state0, threads=1, backend=backend, precision=precision)

    try:
        return mechanism.test(opener, eps)
    except Exception as err:  # a missing attribute or API on this release is a failed mechanism, not a crash
        return f"{type(err).__name__}: {err}"


def require(keys: tuple[str, ...], backend: str = "mujoco", precision: str = "float64") -> None:
    """Refuse, with :class:`MechanismFailed`, the first of the mechanisms ``keys`` that fails its self-test on the
    loaded MuJoCo and ``backend`` (one line: the mechanism, the release, the backend and what was observed)."""
    for key in keys:
        problem = failure(key, backend, precision)
        if problem is not None:
            raise MechanismFailed(f"harness: {MECHANISMS[key].name} does not work on MuJoCo {mujoco.__version__} "
                                  f"(backend={backend}): {problem}; no physics is reported from it")
