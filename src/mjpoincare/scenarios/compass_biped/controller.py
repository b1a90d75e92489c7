"""The compass bipeds' gait controller: the contact protocol of the exact hybrid model, run through the rollout
seam (:class:`mjpoincare.core.seam.Batch`, per trajectory) between MuJoCo's native chunks.

The swing foot's contact is off from heel strike until the foot is ahead of the stance foot and clear of the
ground (it passes through the slope mid-swing, as the exact model's foot does, Kiša 2020 Sec. 4.1), and the
trailing foot's contact is switched off just before the next heel strike, so the impact impulse acts at the new
foot only (Kiša 2020 eqs 4.15-4.17; Gamus & Or 2015 Sec. 4). :class:`GaitController` serves ``compass-biped``;
:class:`FrictionGaitController` adds the actuator work and Gait III's PD reference for ``compass-biped-friction``.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.analysis.sections import level_crossings
from mjpoincare.analysis.theory import compass_biped_friction as friction
from mjpoincare.analysis.theory.compass_biped import CompassBiped
from mjpoincare.analysis.theory.compass_biped_friction.stance_measurements import reference_at
from mjpoincare.core.seam import Batch, Chunk
from mjpoincare.scenarios.base import JointIndex

ENABLE_AHEAD = 0.05  # swing-foot contact switches on once the foot is this far (x l) ahead of the stance foot
ENABLE_CLEAR = 2e-3  # ... and this high (x l) above the slope
RELEASE_WINDOW = 0.02  # s: the released trailing foot is followed this long after heel strike
#: Where in its step each heel strike's touchdown is put (:meth:`GaitController._landing`): half a step after the
#: landed state, so the contact starts at the next step's start with the foot half a step's travel deep, for every
#: strike alike; not at a step boundary, where the contact's presence in a step would be decided by roundoff.
ONSET_PHASE = 0.5


class GaitController:
    """Switches foot contacts at the gait's events and records legs-parallel samples and heel strikes."""

    def __init__(self, model: mujoco.MjModel, bp: CompassBiped, batch: int, foot_radius: float) -> None:
        self.bp, self.radius = bp, foot_radius
        self.feet = [model.geom("foot0").id, model.geom("foot1").id]
        self.ankles = [model.actuator("ankle0").id, model.actuator("ankle1").id]
        self.hip = model.actuator("hip").id
        self.hip_x, self.hip_z = JointIndex.of(model, "x"), JointIndex.of(model, "z")
        legs = [JointIndex.of(model, "leg0"), JointIndex.of(model, "leg1")]
        self.angle, self.rate = [leg.qpos for leg in legs], [leg.dof for leg in legs]  # the leg hinges, by leg
        self.stance = np.zeros(batch, int)
        self.swing_enabled = np.zeros(batch, bool)
        self.samples: list[list[np.ndarray]] = [[] for _ in range(batch)]
        self.sample_times: list[list[float]] = [[] for _ in range(batch)]
        #: per heel strike: (time, new stance foot x): the touchdown's, where it was landed
        self.strikes: list[list[tuple[float, float]]] = [[] for _ in range(batch)]
        # per swing, while the swing foot's contact is off: its lowest height above the slope (m, along the normal;
        # < 0: below the slope) and the stance foot's height at that row (< 0: sunk into the slope)
        self._lowest = np.full((batch, 2), np.inf)
        self.swing_low: list[list[tuple[float, float]]] = [[] for _ in range(batch)]
        # the released trailing foot: (release time, height then, lowest height since), and per strike the depth it
        # went below its release height within RELEASE_WINDOW and its upward speed at the end of the window
        self._release: list[tuple[float, float, float] | None] = [None] * batch
        self.release_depth: list[float] = []
        self.release_speed: list[float] = []
        #: swing-foot contact switch-on thresholds (x l); FrictionGaitController takes its own
        self.enable_ahead, self.enable_clear = ENABLE_AHEAD, ENABLE_CLEAR

    def configure(self, batch: Batch) -> None:
        """Initial contacts: leg 0 stands, leg 1 swings with its contact off; the torques act accordingly."""
        for b in range(self.stance.size):
            batch.set_contact(b, self.feet[1], False)
            self._actuate(batch, b, 0)

    def _actuate(self, batch: Batch, b: int, stance: int) -> None:
        """Trajectory ``b``'s ankle torque on leg ``stance``'s hinge only; the hip tendon (leg1 - leg0) geared so that
        +tau_hip acts on the swing leg (003 eq 4.5, B = (-1, 1))."""
        for leg, actuator in enumerate(self.ankles):
            batch.set_actuator(b, actuator, bias=self.bp.tau_ankle if leg == stance else 0.0)
        batch.set_actuator(b, self.hip, bias=self.bp.tau_hip, gear=1.0 if stance == 0 else -1.0)

    def _feet(self, chunk: Chunk, b: int, leg: int) -> tuple[np.ndarray, np.ndarray]:
        lever = self.bp.l - self.radius
        q = chunk.qpos[b, :, self.angle[leg]]
        x = chunk.qpos[b, :, self.hip_x.qpos] - lever * np.sin(q)
        h = chunk.qpos[b, :, self.hip_z.qpos] - lever * np.cos(q) - self.radius
        return x, h

    def __call__(self, chunk: Chunk, batch: Batch) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        steps = chunk.time.shape[1] - 1
        restart = np.full(chunk.time.shape[0], steps)
        overrides: dict[int, np.ndarray] = {}
        for b in range(chunk.time.shape[0]):
            if np.isnan(chunk.time[b, 1]):
                continue
            st, sw = self.stance[b], 1 - self.stance[b]
            x_st, h_st = self._feet(chunk, b, st)
            x_sw, h_sw = self._feet(chunk, b, sw)
            length = self.bp.l
            if self._release[b] is not None:
                self._watch_release(chunk, b, sw, h_sw)
            strike = False
            if not self.swing_enabled[b]:
                ready = np.nonzero((x_sw[1:] > x_st[1:] + self.enable_ahead * length)
                                   & (h_sw[1:] > self.enable_clear * length))[0]
                last = int(ready[0]) + 1 if ready.size else steps
                i = int(np.nanargmin(h_sw[1 : last + 1])) + 1
                if h_sw[i] < self._lowest[b, 0]:
                    self._lowest[b] = h_sw[i], h_st[i]
                if ready.size:
                    restart[b] = last
                    batch.set_contact(b, self.feet[sw], True)
                    self.swing_enabled[b] = True
                    self.swing_low[b].append((float(self._lowest[b, 0]), float(self._lowest[b, 1])))
                    self._lowest[b] = np.inf
            else:
                predicted = h_sw[1:] + 2.0 * (h_sw[1:] - h_sw[:-1])  # two steps ahead: before any contact starts
                hits = np.nonzero(predicted <= 0.0)[0]
                if hits.size:
                    k = int(hits[0]) + 1
                    landing = self._landing(chunk, batch, b, k, x_sw, h_sw)
                    if landing is None:  # too few rows: the strike is read at the detection row
                        restart[b], strike_at = k, (float(chunk.time[b, k]), float(x_sw[k]))
                    else:
                        restart[b], overrides[b], strike_at = landing
                    strike = True
                    j = int(restart[b])
                    batch.set_contact(b, self.feet[st], False)  # release the trailing foot before impact
                    self._actuate(batch, b, sw)
                    self.strikes[b].append(strike_at)
                    self._release[b] = (float(chunk.time[b, j]), float(h_st[j]), float(h_st[j]))
            self._sample(chunk, b, st, sw, int(restart[b]))
            if strike:
                self.stance[b], self.swing_enabled[b] = sw, False
        return restart, overrides

    def _landing(self, chunk: Chunk, batch: Batch, b: int, k: int, x: np.ndarray, height: np.ndarray
                 ) -> tuple[int, np.ndarray, tuple[float, float]] | None:
        """Where trajectory ``b``'s heel strike, detected at row ``k``, is landed on the step grid: the swing foot's
        touchdown (its height ``height`` reaching 0, extrapolated by a quadratic through rows k-2..k) is put at
        ONSET_PHASE of a step after the landed state, so that every heel strike's soft contact starts at the same
        phase of the step grid, one step after the trailing foot's release, with the same depth. Returns the row j
        the landing starts from, its state advanced by the fraction of a step (:meth:`Batch.advance`, under the
        stance leg's torques), and the touchdown's time and foot x (``x`` extrapolated alike); None where the rows
        do not allow it."""
        rows = slice(k - 2, k + 1)
        if k < 2 or not (np.all(np.isfinite(height[rows])) and np.all(np.isfinite(x[rows]))):
            return None
        dt = batch.timestep
        t = chunk.time[b, rows] - chunk.time[b, k]
        roots = np.roots(np.polyfit(t, height[rows], 2))
        ahead = [float(r.real) for r in roots if abs(r.imag) < 1e-12 and r.real > 0.0]
        if not ahead:
            return None
        touchdown = min(ahead)
        last = chunk.time.shape[1] - 1
        j = min(k + math.floor(touchdown / dt - ONSET_PHASE), last)
        fraction = touchdown - ONSET_PHASE * dt - (chunk.time[b, j] - chunk.time[b, k])
        if j < 1 or fraction < 0.0:
            return None
        state = np.concatenate([[chunk.time[b, j]], chunk.qpos[b, j], chunk.qvel[b, j]])
        if fraction > 1e-9 * dt:
            state = batch.advance(b, state, fraction, self._landing_ctrl(b, float(chunk.time[b, j])))
        x_touch = float(np.polyval(np.polyfit(t, x[rows], 2), touchdown))
        return j, state, (float(chunk.time[b, k]) + touchdown, x_touch)

    def _landing_ctrl(self, b: int, time: float) -> np.ndarray | None:
        """The control of trajectory ``b``'s fractional landing step from ``time`` (None: zero; the torques here are
        actuator biases)."""
        del b, time
        return None

    def _watch_release(self, chunk: Chunk, b: int, leg: int, height: np.ndarray) -> None:
        """Follow the released trailing foot for RELEASE_WINDOW: it must rise (no impulse was needed there)."""
        t_release, h_release, lowest = self._release[b]  # type: ignore[misc]
        inside = chunk.time[b] <= t_release + RELEASE_WINDOW
        lowest = min(lowest, float(np.nanmin(np.where(inside, height, np.inf))))
        after = np.nonzero(~inside & np.isfinite(chunk.time[b]))[0]
        if after.size == 0:
            self._release[b] = (t_release, h_release, lowest)
            return
        i = int(after[0])
        q, qd = chunk.qpos[b, i, self.angle[leg]], chunk.qvel[b, i, self.rate[leg]]
        lever = self.bp.l - self.radius
        self.release_speed.append(float(chunk.qvel[b, i, self.hip_z.dof] + lever * math.sin(q) * qd))
        self.release_depth.append(max(0.0, h_release - lowest))
        self._release[b] = None

    def _sample(self, chunk: Chunk, b: int, st: int, sw: int, last: int) -> None:
        """Legs-parallel crossings (theta_st - theta_sw rising through 0, 003 eq 4.20) in rows 0..last."""
        rows = slice(0, last + 1)
        q = chunk.qpos[b, rows]
        qd = chunk.qvel[b, rows]
        q_st, q_sw = q[:, self.angle[st]], q[:, self.angle[sw]]
        gap = (q_st - q_sw)[None, :]
        values = np.stack([0.5 * (q_st + q_sw) + self.bp.slope, qd[:, self.rate[st]], qd[:, self.rate[sw]]], 1)
        found = level_crossings(chunk.time[b : b + 1, rows], gap, values[None])
        self.samples[b].extend(found.values)
        self.sample_times[b].extend(found.time.tolist())


class FrictionGaitController(GaitController):
    """compass-biped's contact switching for the biped of Gamus & Or (2015, eq 27), plus the per-step actuator work,
    trajectory 0's recorded rows (for the stance measurements) and (Gait III) the PD reference as native control;
    ``enable`` replaces the swing-foot switch-on thresholds (ahead, clear), x l."""

    def __init__(self, model: mujoco.MjModel, g: friction.Gait, batch: int, foot_radius: float,
                 actuated: tuple[float, float], pd: tuple[float, float] | None, enable: tuple[float, float]
                 ) -> None:
        bp = g.biped
        shim = CompassBiped(m_h=bp.m_h, m_l=bp.m, a=bp.d, b=bp.b, slope=0.0, gravity=bp.g,
                                      tau_ankle=actuated[0], tau_hip=actuated[1])
        super().__init__(model, shim, batch, foot_radius)
        self.fb, self.pd, self.dt = bp, pd, model.opt.timestep
        self.ref = friction.gait_c_reference() if pd is not None else None
        self.last_strike = np.zeros(batch)
        self.work = np.zeros(batch)
        self.step_work: list[list[float]] = [[] for _ in range(batch)]
        self.rows0: list[np.ndarray] = []  # trajectory 0: (time, stance, qpos, qvel) of kept rows
        self.nu = model.nu
        self.enable_ahead, self.enable_clear = enable

    def configure(self, batch: Batch) -> None:
        """As compass-biped, but Gait III's PD bias stays on both ankles (the stance leg is chosen by ctrl)."""
        if self.pd is None:
            super().configure(batch)
            return
        for b in range(self.stance.size):
            batch.set_contact(b, self.feet[1], False)

    def _actuate(self, batch: Batch, b: int, stance: int) -> None:
        if self.pd is None:
            super()._actuate(batch, b, stance)

    def control(self, t0: np.ndarray, steps: int) -> np.ndarray:
        """ctrl (B, steps, nu): Gait III's reference term kp theta^r + kd theta_dot^r per hinge (002 eq 30)."""
        phase = (t0 - self.last_strike)[:, None] + self.dt * np.arange(steps)[None, :]
        return self._reference_ctrl(phase, self.stance)

    def _reference_ctrl(self, phase: np.ndarray, stance: np.ndarray) -> np.ndarray:
        """ctrl (B, steps, nu) at the times ``phase`` (B, steps) since the last heel strike, with ``stance`` (B,)."""
        out = np.zeros((*phase.shape, self.nu))
        if self.pd is None or self.ref is None:
            return out
        kp, kd = self.pd
        th1, th2, w1, w2 = reference_at(self.ref, np.nan_to_num(phase))
        out[:, :, self.ankles[0]] = np.where((stance == 0)[:, None], kp * th1 + kd * w1, -(kp * th2 + kd * w2))
        out[:, :, self.ankles[1]] = np.where((stance == 1)[:, None], kp * th1 + kd * w1, -(kp * th2 + kd * w2))
        return out

    def _landing_ctrl(self, b: int, time: float) -> np.ndarray | None:
        """Gait III: the stance leg's reference at ``time`` (the landing step is the stance's last)."""
        if self.pd is None:
            return None
        phase = np.array([[time - self.last_strike[b]]])
        return self._reference_ctrl(phase, self.stance[b : b + 1])[0, 0]

    def __call__(self, chunk: Chunk, batch: Batch) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        stance_before = self.stance.copy()
        strikes_before = [len(s) for s in self.strikes]
        restart, overrides = super().__call__(chunk, batch)
        for b in range(chunk.time.shape[0]):
            if np.isnan(chunk.time[b, 1]):
                continue
            k = int(restart[b])
            st = int(stance_before[b])
            self.work[b] += float(np.sum(self._power(chunk, b, st, slice(0, k)))) * self.dt
            if b in overrides:  # the fractional landing step from row k, the stance's last
                self.work[b] += float(self._power(chunk, b, st, slice(k, k + 1))[0]) * float(overrides[b][0]
                                                                                            - chunk.time[b, k])
            if b == 0:
                self.rows0.append(np.column_stack([chunk.time[0, 1 : k + 1], np.full(k, st), chunk.qpos[0, 1 : k + 1],
                                                   chunk.qvel[0, 1 : k + 1]]))
            if len(self.strikes[b]) > strikes_before[b]:
                self.step_work[b].append(self.work[b])
                self.work[b] = 0.0
                self.last_strike[b] = self.strikes[b][-1][0]
        return restart, overrides

    def _power(self, chunk: Chunk, b: int, st: int, rows: slice) -> np.ndarray:
        """Actuator power (actuator force . actuator velocity) at ``rows`` with stance leg ``st`` (002 eq 29), from
        the recorded hinge rates: constant torques (tau_ankle - tau_hip) on the stance hinge and tau_hip on the swing
        hinge; Gait III: the PD force with the same reference as the control."""
        qd = chunk.qvel[b, rows]
        sw = 1 - st
        if self.pd is None:
            ta, th = self.bp.tau_ankle, self.bp.tau_hip
            return (ta - th) * qd[:, self.rate[st]] + th * qd[:, self.rate[sw]]
        kp, kd = self.pd
        q = chunk.qpos[b, rows]
        phase = chunk.time[b, rows] - self.last_strike[b]
        r1, r2, w1, w2 = reference_at(self.ref, phase)  # type: ignore[arg-type]
        f_st = kp * (r1 - q[:, self.angle[st]]) + kd * (w1 - qd[:, self.rate[st]])
        f_sw = kp * (-r2 - q[:, self.angle[sw]]) + kd * (-w2 - qd[:, self.rate[sw]])
        return f_st * qd[:, self.rate[st]] + f_sw * qd[:, self.rate[sw]]
