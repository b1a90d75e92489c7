"""The ``impact=ideal`` mode of ``rimless-wheel-3d``: MuJoCo integrates the stance only, the impacts are exact.

The stance foot is a ball joint under a mocap "pivot" body and contact is disabled
(:func:`mjpoincare.scenarios.rimless_wheel_3d.build`); :class:`IdealImpactController`, run by
:func:`mjpoincare.simulation.simulate.event_rollout`, lands each trajectory on the guard theta = pi/n, applies the
impact law of 001 = Coleman, Chatterjee & Ruina (1997), Sec. 3.2.2 (angular momentum about the new foot) and moves the
pivot.
"""

from __future__ import annotations

import math

import numpy as np

from mjpoincare.analysis.rigid_body_kinematics import euler_state, matrix_to_quat, quat_to_matrix
from mjpoincare.analysis.sections import Crossings, level_crossings
from mjpoincare.analysis.theory.rimless_wheel_3d import RimlessWheel3D, hybrid
from mjpoincare.analysis.theory.rimless_wheel_3d.section import section_state
from mjpoincare.core.seam import Batch, Chunk


class IdealImpactController:
    """Event controller of the ideal mode: exact guard, exact impact law, pivot moved to the new foot.

    For each trajectory whose pitch passes theta = pi/n inside a chunk, the state is restarted from the last row
    before the guard with two fractional steps of the model's own integrator (secant on the step fraction), so the
    impact happens on the guard (measured within 1e-12 rad); the Euler rates jump by the vector law of 001 Sec. 3.2.2
    (:func:`hybrid.impact_rates`), the orientation is relabelled to the new stance
    spoke (R -> R Ry(-2 pi/n), theta -> theta - 2 pi/n) and the pivot moves to the new foot (spoke length
    ``length``, m). Mid-stance crossings are sampled on the kept rows.
    """

    def __init__(self, w: RimlessWheel3D, length: float, batch: int) -> None:
        self.w = w
        self.beta = w.beta
        self.length = length
        self.mid = Crossings.empty(5)
        self.pivot = np.zeros((batch, 3))
        self.impacts = np.zeros(batch, int)
        self.guard_error = 0.0  # largest |theta - pi/n| at an applied impact

    def __call__(self, chunk: Chunk, batch: Batch) -> tuple[np.ndarray, dict[int, np.ndarray]]:
        steps = chunk.time.shape[1] - 1
        theta, values = section_state(chunk.qpos, chunk.qvel)
        with np.errstate(invalid="ignore"):
            over = theta[:, 1:] >= self.beta
        restart = np.full(chunk.time.shape[0], steps)
        overrides: dict[int, np.ndarray] = {}
        for b in np.nonzero(over.any(axis=1))[0]:
            k = int(np.argmax(over[b])) + 1  # the guard lies between rows k-1 and k
            overrides[int(b)] = self._impact(batch, chunk, theta, int(b), k)
            restart[b] = max(k - 1, 1)
        kept = np.arange(steps + 1)[None, :] <= restart[:, None]
        phase = np.where(kept, theta, np.nan)
        self.mid = self.mid.concat(level_crossings(chunk.time, phase, values, max_jump=self.beta))
        return restart, overrides

    def _impact(self, batch: Batch, chunk: Chunk, theta: np.ndarray, b: int, k: int) -> np.ndarray:
        """Trajectory ``b``'s state just after the impact whose guard lies between rows k-1 and k (full physics: time,
        qpos, qvel, the ideal model's whole state)."""
        beta, nq = self.beta, chunk.qpos.shape[2]
        row = np.concatenate([chunk.time[b, k - 1 : k], chunk.qpos[b, k - 1], chunk.qvel[b, k - 1]])
        rise = theta[b, k] - theta[b, k - 1]
        frac = (beta - theta[b, k - 1]) / rise
        for _ in range(2):  # secant on the step fraction
            state = batch.advance(b, row, frac * batch.timestep)
            qpos, qvel = state[1 : 1 + nq], state[1 + nq :]
            miss = float(euler_state(qpos, qvel)[2]) - beta
            frac -= miss / rise
        self.guard_error = max(self.guard_error, abs(miss))
        R = quat_to_matrix(np.array(qpos))
        psi, phi, pitch = hybrid.euler_angles(R)
        rates = hybrid.euler_rates(psi, phi, R @ qvel)
        rates_plus = hybrid.impact_rates(self.w, psi, phi, rates)
        R_plus = hybrid.pose(psi, phi, pitch - 2.0 * beta)
        l = self.length
        next_spoke = np.array([math.sin(2.0 * beta), 0.0, -math.cos(2.0 * beta)])
        self.pivot[b] += l * (R[:, 2] + R @ next_spoke)
        self.impacts[b] += 1
        state[1 : 1 + nq] = matrix_to_quat(R_plus)
        state[1 + nq :] = R_plus.T @ hybrid.angular_velocity(psi, phi, rates_plus)
        return state
