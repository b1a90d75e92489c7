"""Actuation of the compass biped with Coulomb friction: the generalised force Q on the angles (002 Sec. 5).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 5: constant ankle/hip torques (eq 28, Gaits I and II; the printed actuation matrix E and the effective one that
reproduces Gait I, derivation page docs/theory/stick-slip.md, Sec. 3.3) and PD tracking of a stored joint trajectory
with phase reset (eq 30, Gait III). The conventions are discussed in
:mod:`mjpoincare.analysis.theory.compass_biped_friction`.
"""

from __future__ import annotations

import bisect
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.params import Matrix, Vector

#: Printed actuation matrix of 002 eq 28 (rows theta1, theta2, x, y; columns tau1, tau2).
E_PRINTED = np.array([[1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [0.0, 0.0]])
#: Effective actuation matrix that reproduces 002's Gait I (derivation page docs/theory/stick-slip.md, Sec. 3.3).
E_EFFECTIVE = np.array([[-1.0, 0.0], [-1.0, 1.0], [0.0, 0.0], [0.0, 0.0]])


class Actuation(Protocol):
    """Generalised actuation force Q = (Q_theta1, Q_theta2) on the angles (002 eq 2's E u; Q_x = Q_y = 0) as a
    function of the physical state (theta1, theta2, x, y), its rates and the phase phi = time since the last impact
    (002 eq 30)."""

    def generalised_force(self, q: Vector, qd: Vector, phase: float) -> tuple[float, float]: ...


@dataclass(frozen=True)
class ConstantTorque:
    """Open-loop constant ankle/hip torques (tau1, tau2) (N m) of 002 Sec. 5 (Gaits I, II), eq 28.

    ``convention="effective"`` (default): Q = E_eff u = (-tau1 - tau2, tau2), the convention that reproduces
    002's Gait I (see :mod:`~mjpoincare.analysis.theory.compass_biped_friction`); ``"printed"``: Q = E u with 002's
    printed E, (tau1 + tau2, tau2)."""

    tau1: float = 0.0
    tau2: float = 0.0
    convention: str = "effective"

    def __post_init__(self) -> None:
        if self.convention not in ("effective", "printed"):
            raise ValueError(f"convention must be 'effective' or 'printed' (got {self.convention!r})")

    def generalised_force(self, q: Vector, qd: Vector, phase: float) -> tuple[float, float]:
        """Q = (-tau1 - tau2, tau2) (effective) or (tau1 + tau2, tau2) (printed 002 eq 28)."""
        if self.convention == "effective":
            return -self.tau1 - self.tau2, self.tau2
        return self.tau1 + self.tau2, self.tau2


@dataclass(frozen=True, eq=False)
class ReferenceTrajectory:
    """Joint reference theta^r(phi), theta_dot^r(phi) of 002 eq 30, sampled on ``times`` (s, from 0 = the impact
    that started the step to ``times[-1]`` = the next impact), with ``theta``, ``theta_dot``, ``theta_ddot`` of
    shape (n, 2). Evaluation: cubic Hermite interpolation of theta (slopes theta_dot) and of theta_dot (slopes
    theta_ddot) between samples; beyond the last sample the reference continues at its final velocity
    (theta^r = theta(T) + theta_dot(T)(phi - T), theta_dot^r = theta_dot(T)); before 0 it is held at the first
    sample. Built by :func:`reference_trajectory`."""

    times: Vector
    theta: Matrix
    theta_dot: Matrix
    theta_ddot: Matrix
    _t: list[float] = field(init=False, repr=False)
    _rows: list[tuple[float, ...]] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_t", [float(t) for t in self.times])
        rows = np.column_stack([self.theta, self.theta_dot, self.theta_ddot])
        object.__setattr__(self, "_rows", [tuple(float(v) for v in r) for r in rows])

    @property
    def period(self) -> float:
        """Duration of the reference step (s)."""
        return self._t[-1]

    def evaluate(self, phase: float) -> tuple[float, float, float, float]:
        """(theta1^r, theta2^r, theta1_dot^r, theta2_dot^r) at phi = ``phase`` as floats (the fast path of
        :meth:`__call__`)."""
        t = self._t
        if phase <= t[0]:
            r = self._rows[0]
            return r[0], r[1], r[2], r[3]
        if phase >= t[-1]:
            r = self._rows[-1]
            dt = phase - t[-1]
            return r[0] + r[2] * dt, r[1] + r[3] * dt, r[2], r[3]
        i = bisect.bisect_right(t, phase) - 1
        h = t[i + 1] - t[i]
        s = (phase - t[i]) / h
        s2, s3 = s * s, s * s * s
        h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, (s3 - 2 * s2 + s) * h, -2 * s3 + 3 * s2, (s3 - s2) * h
        a, b = self._rows[i], self._rows[i + 1]
        return (
            h00 * a[0] + h10 * a[2] + h01 * b[0] + h11 * b[2],
            h00 * a[1] + h10 * a[3] + h01 * b[1] + h11 * b[3],
            h00 * a[2] + h10 * a[4] + h01 * b[2] + h11 * b[4],
            h00 * a[3] + h10 * a[5] + h01 * b[3] + h11 * b[5],
        )

    def __call__(self, phase: float) -> tuple[Vector, Vector]:
        """(theta^r(phi), theta_dot^r(phi)), each of shape (2,)."""
        v = self.evaluate(phase)
        return np.array(v[:2]), np.array(v[2:])


@dataclass(frozen=True)
class PDTracking:
    """PD tracking with phase reset (002 eq 30, Gait III): tau_i = -kp (theta_i - theta_i^r(phi))
    - kd (theta_i_dot - theta_i_dot^r(phi)), phi = time since the last impact. 002 uses kp = kd = 15 (N m/rad,
    N m s/rad) and does not say how tau enters eq 2 for this gait. ``convention="direct"`` (default): Q = (tau1,
    tau2), the generalised force on each angle (decoupled PD); ``"effective"``: Q = E_eff tau = (-tau1 - tau2, tau2)
    (the Gait I convention: positive feedback on theta1); ``"printed"``: Q = (tau1 + tau2, tau2) (002 eq 28).
    ``feedforward`` (not in 002, default none): constant torques added to Q (e.g. Gait I's, so that the PD tracks
    a passive slope gait on level ground around an open-loop gait that already walks)."""

    reference: ReferenceTrajectory
    kp: float = 15.0
    kd: float = 15.0
    convention: str = "direct"
    feedforward: ConstantTorque | None = None

    def __post_init__(self) -> None:
        if self.convention not in ("direct", "effective", "printed"):
            raise ValueError(f"convention must be 'direct', 'effective' or 'printed' (got {self.convention!r})")

    def torques(self, q: Vector, qd: Vector, phase: float) -> tuple[float, float]:
        """(tau1, tau2) of 002 eq 30."""
        r1, r2, w1, w2 = self.reference.evaluate(phase)
        return (
            -self.kp * (float(q[0]) - r1) - self.kd * (float(qd[0]) - w1),
            -self.kp * (float(q[1]) - r2) - self.kd * (float(qd[1]) - w2),
        )

    def generalised_force(self, q: Vector, qd: Vector, phase: float) -> tuple[float, float]:
        """Q of :meth:`torques` in the chosen convention, plus the feedforward's Q."""
        t1, t2 = self.torques(q, qd, phase)
        if self.convention == "direct":
            q1, q2 = t1, t2
        elif self.convention == "effective":
            q1, q2 = -t1 - t2, t2
        else:
            q1, q2 = t1 + t2, t2
        if self.feedforward is not None:
            f1, f2 = self.feedforward.generalised_force(q, qd, phase)
            q1, q2 = q1 + f1, q2 + f2
        return q1, q2


PASSIVE = ConstantTorque(0.0, 0.0)
