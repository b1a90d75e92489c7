"""The harness checks itself: each mechanism of the rollout seam (:class:`mjpoincare.seam.Batch`) run on a tiny
model, on the MuJoCo release and the backend actually loaded, before a scenario that uses it runs.

A scenario declares the mechanisms its event controllers use (``Scenario.mechanisms``). :func:`require` runs their
self-tests once per process, backend and precision; a mechanism that does not do what the seam promises raises
:class:`MechanismFailed` (a :class:`~mjpoincare.params.ParameterError`, so the command line exits 2 with one line
naming the mechanism and the release), and no physics is reported from a harness that did not work.

Each self-test is a physical observation with a margin of an order of magnitude, not a reading of the fields it
wrote: a ball of 1 kg resting on a plane (its contact, friction and fields) and a bob on a vertical slide held by a
joint equality and pushed by an affine actuator. Free fall over ``T = 0.05 s`` drops ``g T^2 / 2 = 12.3 mm``; a
held body moves less than 1 mm in that time.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import mujoco
import numpy as np

from mjpoincare.backends import open_batch
from mjpoincare.mjcompat import efc_diag_inverse_inertia
from mjpoincare.params import ParameterError
from mjpoincare.seam import STATE_SPEC, Batch
from mjpoincare.simulate import initial_states

GRAVITY = 9.81
#: Steps of each observation, at the model's timestep of 1 ms.
STEPS = 50
TIMESTEP = 1e-3
#: Free fall over the observation, m.
FREE_FALL = 0.5 * GRAVITY * (STEPS * TIMESTEP) ** 2
#: A body the seam holds (contact, equality on) moves less than this, m (a tenth of the free fall).
HELD = 0.1 * FREE_FALL
#: What agrees exactly agrees to this many machine epsilons of the backend's precision (times of at most 1 s, speeds
#: of at most 1 m/s, a 1 kg body's inverse inertia): rounding, never a missing or wrong mechanism.
EXACT = 64.0
#: Radius of the ball, m.
RADIUS = 0.1

_MODEL = f"""
<mujoco model="seam self-test">
  <option timestep="{TIMESTEP}" gravity="0 0 -{GRAVITY}" cone="elliptic"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" contype="0" conaffinity="1" condim="3"/>
    <body name="ball" pos="0 0 {RADIUS}">
      <joint name="ball_x" type="slide" axis="1 0 0"/>
      <joint name="ball_z" type="slide" axis="0 0 1"/>
      <geom name="ball" type="sphere" size="{RADIUS}" mass="1" contype="1" conaffinity="0" condim="3"
            friction="1 0 0"/>
    </body>
    <body name="bob" pos="2 0 1">
      <joint name="bob_z" type="slide" axis="0 0 1"/>
      <geom name="bob" type="sphere" size="0.05" mass="1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <equality>
    <joint name="hold" joint1="bob_z"/>
  </equality>
  <actuator>
    <general name="push" joint="bob_z" gaintype="fixed" gainprm="0" biastype="affine" biasprm="0 0 0"/>
  </actuator>
</mujoco>
"""


class MechanismFailed(ParameterError):
    """A seam mechanism failed its self-test on the loaded MuJoCo and backend: the run is refused."""


@dataclass(frozen=True)
class Mechanism:
    """One mechanism of the seam and its self-test.

    Attributes:
        name: what the mechanism is, as the refusal names it.
        test: ``(batch opener, eps) -> None`` when it works, or what went wrong, in a few words with the numbers
            (``eps``: the machine epsilon of the backend's precision, which scales the exact comparisons).
        c_only: the mechanism reads MuJoCo C's ``mjData`` whatever the backend (a check's field), so it is tested on
            MuJoCo C.
    """

    name: str
    test: Callable[[Callable[[np.ndarray], Batch], float], str | None]
    c_only: bool = False


def self_test_model() -> mujoco.MjModel:
    """The self-tests' model (ball on a plane, a held bob with an actuator)."""
    return mujoco.MjModel.from_xml_string(_MODEL)


def _starts(model: mujoco.MjModel, count: int = 2, *, ball_z: float = RADIUS - 1e-4, ball_vx: float = 0.0
            ) -> np.ndarray:
    """``count`` identical starts (every test steps two trajectories for the same number of steps, so that MJX and
    MuJoCo Warp compile one chunk for them all): the ball pressed 0.1 mm into the plane (sliding at ``ball_vx``),
    the bob held."""
    qpos = np.tile([0.0, ball_z - RADIUS, 0.0], (count, 1))  # slide joints measure from the body's position
    qvel = np.tile([ball_vx, 0.0, 0.0], (count, 1))
    return initial_states(model, qpos, qvel)


def _drop(batch: Batch, qpos: int) -> np.ndarray:
    """How far each trajectory's coordinate ``qpos`` falls over one observation, m (B,)."""
    chunk = batch.run_chunk(STEPS)
    return chunk[:, 0, 1 + qpos] - chunk[:, -1, 1 + qpos]


def _rollout(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    model = self_test_model()
    start = _starts(model, 2, ball_z=1.0)  # in the air
    with opener(start) as batch:
        first = batch.run_chunk(STEPS)
        batch.set_states(np.array([1]), start[1:])  # trajectory 1 starts again, trajectory 0 goes on
        second = batch.run_chunk(STEPS)
    ticks = np.diff(np.concatenate([first[:, :, 0], second[:, 1:, 0]], axis=1), axis=1)
    if not (np.abs(ticks[0] - TIMESTEP) < EXACT * eps).all():  # rounding of times near 0.1 s
        return f"recorded times advance by {ticks[0].min():.6g}-{ticks[0].max():.6g} s per step, not the timestep"
    drop = first[0, 0, 2] - first[0, -1, 2]
    again = second[1, 0, 2] - second[1, -1, 2]
    if not (abs(drop - FREE_FALL) < 0.05 * FREE_FALL and abs(again - drop) < EXACT * eps
            and second[0, 0, 2] == first[0, -1, 2]):
        return (f"a falling ball dropped {drop * 1e3:.4g} mm (free fall {FREE_FALL * 1e3:.4g}), "
                f"{again * 1e3:.4g} mm after its state was set back")
    return None


def _release_and_restore(opener: Callable[[np.ndarray], Batch], switch: Callable[[Batch, bool], None], qpos: int,
                         what: str) -> str | None:
    """Trajectory 1's ``switch`` off: its body (coordinate ``qpos``) falls freely while trajectory 0's stays held;
    switched on again and both set back to the start, both stay held."""
    with opener(_starts(self_test_model())) as batch:
        start = batch.states()
        switch(batch, False)
        released = _drop(batch, qpos)
        switch(batch, True)
        batch.set_states(np.arange(2), start)
        restored = _drop(batch, qpos)
    if not abs(released[1] - FREE_FALL) < 0.1 * FREE_FALL:
        return (f"a released {what} fell {released[1] * 1e3:.3g} mm in {STEPS * TIMESTEP:g} s "
                f"(free fall {FREE_FALL * 1e3:.3g})")
    if not (abs(released[0]) < HELD and abs(restored).max() < HELD):
        return f"a held (or restored) {what} moved {max(abs(released[0]), abs(restored).max()) * 1e3:.3g} mm"
    return None


def _contact_release(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    ball = self_test_model().geom("ball").id
    return _release_and_restore(opener, lambda batch, on: batch.set_contact(1, ball, on), 1,
                                "ball resting on a plane (its contact)")


def _equality_toggle(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    hold = self_test_model().equality("hold").id
    return _release_and_restore(opener, lambda batch, on: batch.set_eq_active(1, hold, on), 2,
                                "bob held by a joint equality")


def _friction(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    model = self_test_model()
    mus = (0.1, 0.5)
    with opener(_starts(model, 2, ball_vx=1.0)) as batch:
        for index, mu in enumerate(mus):
            batch.set_friction(index, mu)
        chunk = batch.run_chunk(STEPS)
    lost = chunk[:, 0, 1 + model.nq] - chunk[:, -1, 1 + model.nq]  # the ball's x speed lost to friction, m/s
    expected = np.array(mus) * GRAVITY * STEPS * TIMESTEP
    if not (np.abs(lost - expected) < 0.25 * expected).all():
        return (f"balls sliding at mu {mus} lost {np.round(lost, 4).tolist()} m/s in {STEPS * TIMESTEP:g} s "
                f"(Coulomb: {np.round(expected, 4).tolist()})")
    return None


def _fractional_step(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    model = self_test_model()
    start = _starts(model, 2, ball_z=1.0)  # in the air
    with opener(start) as batch:
        fraction = 0.3 * batch.timestep
        after = batch.advance(0, start[0], fraction)
        full = batch.run_chunk(STEPS)
    dt, vz = after[0] - start[0, 0], after[1 + model.nq + 1] - start[0, 1 + model.nq + 1]
    if not (abs(dt - fraction) < EXACT * eps and abs(vz + GRAVITY * fraction) < EXACT * eps):
        return (f"a step of {fraction:g} s advanced the time by {dt:.6g} s and the falling ball's speed by "
                f"{vz:.6g} m/s (expected {-GRAVITY * fraction:.6g})")
    if not abs(full[0, 1, 0] - full[0, 0, 0] - TIMESTEP) < EXACT * eps:
        return f"the step after a fractional step lasted {full[0, 1, 0] - full[0, 0, 0]:.6g} s, not the timestep"
    return None


def _actuator(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    model = self_test_model()
    hold, push = model.equality("hold").id, model.actuator("push").id
    with opener(_starts(model, 2)) as batch:
        for index in range(2):
            batch.set_eq_active(index, hold, False)
        batch.set_actuator(1, push, bias=GRAVITY, gear=1.0)  # trajectory 1's bob is held up by its actuator
        drops = _drop(batch, 2)
    if not (abs(drops[0] - FREE_FALL) < 0.1 * FREE_FALL and abs(drops[1]) < HELD):
        return (f"a bob with a bias force of its weight fell {drops[1] * 1e3:.3g} mm, one without "
                f"{drops[0] * 1e3:.3g} mm (free fall {FREE_FALL * 1e3:.3g})")
    return None


def _contact_fields(opener: Callable[[np.ndarray], Batch], eps: float) -> str | None:
    del opener, eps  # read from MuJoCo C's mjData in float64, whatever the backend
    model = self_test_model()
    data = mujoco.MjData(model)
    mujoco.mj_setState(model, data, _starts(model)[0], STATE_SPEC)
    mujoco.mj_forward(model, data)
    if data.ncon != 1:
        return f"a ball pressed into a plane has {data.ncon} contacts, not 1"
    diag = float(efc_diag_inverse_inertia(data)[data.contact[0].efc_address])
    expected = float(model.body_invweight0[model.body("ball").id, 0])  # MuJoCo's translational inverse weight
    if not abs(diag - expected) <= EXACT * np.finfo(float).eps * expected:
        return f"the contact's diagonal inverse inertia reads {diag:.6g} 1/kg, not the body's {expected:.6g}"
    return None


#: Every mechanism of the seam, by the name a scenario declares.
MECHANISMS: dict[str, Mechanism] = {
    "rollout": Mechanism(name="chunked rollout and state setting", test=_rollout),
    "contact": Mechanism(name="contact release and restore", test=_contact_release),
    "equality": Mechanism(name="equality toggling", test=_equality_toggle),
    "friction": Mechanism(name="per-trajectory friction", test=_friction),
    "fractional_step": Mechanism(name="fractional steps", test=_fractional_step),
    "actuator": Mechanism(name="per-trajectory actuator force", test=_actuator),
    "contact_fields": Mechanism(name="contact fields (diagonal inverse inertia)", test=_contact_fields, c_only=True),
}


@cache
def failure(key: str, backend: str = "mujoco", precision: str = "float64") -> str | None:
    """What went wrong in mechanism ``key``'s self-test on ``backend`` at ``precision`` (None: it works), run once
    per process."""
    mechanism = MECHANISMS[key]
    if mechanism.c_only:
        backend, precision = "mujoco", "float64"
    eps = float(np.finfo(np.float32 if precision == "float32" else np.float64).eps)

    def opener(state0: np.ndarray) -> Batch:
        return open_batch(self_test_model(), state0, threads=1, backend=backend, precision=precision)

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
