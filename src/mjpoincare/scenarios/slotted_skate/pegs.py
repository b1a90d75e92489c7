"""The slotted skate's MJCF model (:func:`build`) and its peg protocol, a chunk controller for
:func:`mjpoincare.simulation.simulate.event_rollout` (:class:`PegController`).

Coleman & Holmes (1999): each stance ends where the peg reaches a slot end (3.5), the peg is retracted and a new
one inserted at the other slot end, and the next constraint solve is the plastic impact (3.6)-(3.7). The model is
the "peg chart" of models/slotted_skate.xml (hinge = heading about the peg, slide s along the slot, slide n held
at 0 by the peg's joint equality); a new peg is a change of chart (derivation page docs/theory/slotted-skate.md,
Sec. 4.2 step 5).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.core import settings as sim_settings
from mjpoincare.core.mjcf_loader import compile_spec, load_spec
from mjpoincare.core.seam import Batch, Chunk
from mjpoincare.scenarios.base import JointIndex, Values


def build(params: Values, settings: Values) -> mujoco.MjModel:
    """The MJCF skate with mass, inertia, slot geometry and the peg constraint's solver settings."""
    spec = load_spec("slotted_skate.xml")
    sim_settings.apply_options(spec, settings)
    body = spec.body("skate")
    mass, rho = float(params["mass"]), float(params["rho"])
    body.mass = mass
    body.inertia = [mass * rho**2] * 3
    l0, delta = float(params["l0"]), float(params["delta"])
    spec.geom("slot").size = [0.5 * delta, 0.02 * rho, 0.021 * rho]
    spec.geom("slot").pos = [-(l0 + 0.5 * delta), 0, 0.05 * rho]
    spec.geom("body").size = [0.5 * abs(l0 + delta) + 0.3 * rho, 0.25 * rho, 0.02 * rho]
    spec.geom("body").pos = [-0.5 * (l0 + delta), 0, 0.05 * rho]
    slot = spec.equality("slot")
    slot.solref = sim_settings.solref(settings)
    slot.solimp = sim_settings.solimp(settings)
    return compile_spec(spec, settings)


class PegController:
    """Ends each stance exactly at a slot end, samples it and inserts the next peg.

    Each sample is one stance as a point of the map's section (3.5): the end where its peg went in (D+),
    E and H about that peg read at the stance's end (stance invariants, so the impact's duration does not
    matter), the heading and time when the peg went in."""

    def __init__(self, model: mujoco.MjModel, params: Values, entry: np.ndarray,
                 slot: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        self.slide = JointIndex.of(model, "s").qpos  # the chart coordinate s along the slot
        # the slot's ends in the chart coordinate s, per trajectory (a region map gives each its own l0, delta)
        lo, hi = slot if slot is not None else (float(params["l0"]), float(params["l0"]) + float(params["delta"]))
        self.lo = np.broadcast_to(np.asarray(lo, float), (len(entry),))
        self.hi = np.broadcast_to(np.asarray(hi, float), (len(entry),))
        self.mass, self.rho = float(params["mass"]), float(params["rho"])
        self.entry = np.array(entry, float)  # slot end (s value) where each trajectory's current peg went in
        self.start_heading = np.full(len(entry), float(params["heading0"]))  # heading when the current peg went in
        self.start_time = np.zeros(len(entry))
        self.peg = np.zeros((len(entry), 2))  # the current peg's position in the plane (the chart's origin)
        self.samples: list[list[tuple[float, ...]]] = [[] for _ in entry]

    def invariants(self, state: np.ndarray) -> tuple[float, float]:
        """Energy and angular momentum about the peg (SI), from a state (t, theta, s, n, w, sdot, ndot)."""
        _, _, s, n, w, sd, nd = state
        vx, vy = sd - w * n, nd + w * s  # mass-centre velocity in the body frame
        energy = 0.5 * self.mass * (vx * vx + vy * vy) + 0.5 * self.mass * self.rho**2 * w * w
        momentum = self.mass * self.rho**2 * w + self.mass * (s * vy - n * vx)
        return energy, momentum

    def __call__(self, chunk: Chunk, batch: Batch) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        steps = chunk.time.shape[1] - 1
        restart = np.full(chunk.time.shape[0], steps)
        overrides: dict[int, np.ndarray] = {}
        s = chunk.qpos[:, :, self.slide]
        outside = (s > self.hi[:, None]) | (s < self.lo[:, None])
        for b in np.nonzero(outside[:, 1:].any(axis=1))[0]:
            k = int(np.argmax(outside[b, 1:])) + 1
            state = np.concatenate([[chunk.time[b, k - 1]], chunk.qpos[b, k - 1], chunk.qvel[b, k - 1]])
            end = self.hi[b] if s[b, k] > self.hi[b] else self.lo[b]
            state = self._step_to(batch, int(b), state, end)
            energy, momentum = self.invariants(state)
            # the stance that just ended, as a section state (D+, E+, theta+, H+) of the map (3.5) plus its start time
            self.samples[b].append((self.entry[b], energy, self.start_heading[b], momentum, self.start_time[b]))
            overrides[int(b)] = self._insert_peg(state, end, int(b))
            self.entry[b], self.start_heading[b], self.start_time[b] = overrides[int(b)][2], state[1], state[0]
            heading, s_old, n_old, s_new = state[1], state[2], state[3], overrides[int(b)][2]
            along, normal = np.array([math.cos(heading), math.sin(heading)]), np.array([-math.sin(heading),
                                                                                      math.cos(heading)])
            self.peg[b] = self.peg[b] + (s_old - s_new) * along + n_old * normal
            restart[b] = k - 1 if k > 1 else 1
        return restart, overrides

    def _step_to(self, batch: Batch, b: int, state: np.ndarray, end: float) -> np.ndarray:
        """One fractional step of trajectory ``b``'s own integrator that lands on the slot end (no overshoot)."""
        speed = state[5]
        dt = batch.timestep
        return batch.advance(b, state, min(dt, max(0.0, (end - state[2]) / speed)) if speed else dt)

    def _insert_peg(self, state: np.ndarray, end: float, b: int) -> np.ndarray:
        """Retract the old peg and insert one at the other slot end: a change of chart (docs/theory/slotted-skate.md,
        Sec. 4.2 step 5).

        The new chart's n-velocity is the normal velocity of the material point over the new peg; the
        next constraint solve removes it (the plastic impact)."""
        out = state.copy()
        s_new = self.lo[b] if end == self.hi[b] else self.hi[b]
        w, s, nd = state[4], state[2], state[6]
        out[2], out[3] = s_new, 0.0
        out[6] = nd + w * (s - s_new)
        return out
