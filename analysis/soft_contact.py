"""MuJoCo's soft contact for one frictional point contact with an elliptic friction cone, written from its documented
equations, on quantities a simulator records (numpy only): what a sliding contact does in the normal direction.

Model (MuJoCo documentation, "Computation": the primal problem, "Soft contact model" and "Solver parameters";
Todorov 2014). For contact distance ``r`` (< 0: penetration), contact-frame velocity (v_n, v_t) and the constrained
acceleration J qacc = (a_n, a_t) of one step, the solver works on jar = J qacc - a_ref with the reference
acceleration

    a_ref = -b v - k d(r) r (normal row),   a_ref = -b v_t (friction rows),
    b = 2 / (d_width tau),   k = 1 / (d_width^2 tau^2 zeta^2),   tau >= 2 h ("refsafe"),

d(r) the impedance of ``solimp`` (:func:`impedance`) and regulariser R_n = (1 - d)/d A_nn (A_nn: MuJoCo's diagonal
approximation of the inverse inertia in the normal direction, ``efc_diagA``). The elliptic cone's friction rows get
R_t = R_n / impratio, and the solver's regularised cone the friction mu_r = mu sqrt(R_t / R_n).

A **sliding** contact is the cone's middle zone. There the constraint cost is 0.5 D_n / (mu_r^2 (1 + mu_r^2))
(N - mu_r T)^2 with N = mu_r jar_n, T = mu |jar_t|, whose force is f_t = -mu f_n t_hat (friction on the cone, against
the slide) and

    jar_n - mu |jar_t| = -(1 + mu_r^2) R_n f_n.                                                            (1)

Solved for the normal velocity the step starts with:

    v_n = mu |v_t + a_t / b| - (a_n + k d(r) r + (1 + mu_r^2) R_n f_n) / b.                               (2)

So a sliding contact moves away from the surface at mu |v_t| (the documentation's "the only way to initiate slip is
to generate some motion in the normal direction"), less the step's normal acceleration, the contact's spring and its
regularised force over b; at rest in the normal direction, k d r = -R_n f_n, so those two cancel and the lift is
mu |v_t| - (mu_r^2 R_n f_n + a_n - mu a_t t_hat) / b.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


def impedance(dist: np.ndarray | float, solimp: Sequence[float]) -> np.ndarray:
    """MuJoCo's impedance d(r) of a contact at distance ``dist`` (margin 0) for ``solimp`` (d0, d_width, width,
    midpoint, power): d0 at r = 0 rising to d_width at |r| >= width along two power-law halves meeting at the
    midpoint (MuJoCo documentation, "Solver parameters", solimp)."""
    d0, dw, width, mid, power = (float(v) for v in solimp)
    if d0 == dw or width <= 0:
        return np.full(np.shape(dist), 0.5 * (d0 + dw))
    x = np.clip(np.abs(np.asarray(dist, float)) / width, 0.0, 1.0)
    if power == 1:
        y = x
    else:
        low = x <= mid
        y = np.where(low, x**power / mid ** (power - 1), 1 - (1 - x) ** power / (1 - mid) ** (power - 1))
    return d0 + y * (dw - d0)


@dataclass(frozen=True)
class SoftContact:
    """One contact's MuJoCo parameters.

    Attributes:
        timestep: h, s.
        timeconst: solref tau, s (raised to 2 h as MuJoCo's refsafe does).
        dampratio: solref zeta.
        solimp: (d0, d_width, width, midpoint, power).
        impratio: friction-to-normal impedance ratio of the elliptic cone.
        mu: sliding friction coefficient (an array broadcast against the rows: one per trajectory).
        diag_inverse_inertia: A_nn, MuJoCo's ``efc_diagA`` of the contact's normal row, 1/kg.
    """

    timestep: float
    timeconst: float
    dampratio: float
    solimp: Sequence[float]
    impratio: float
    mu: float | np.ndarray
    diag_inverse_inertia: float

    @property
    def damping(self) -> float:
        """b = 2 / (d_width tau), 1/s."""
        return 2.0 / (self.solimp[1] * max(self.timeconst, 2.0 * self.timestep))

    @property
    def stiffness(self) -> float:
        """k = 1 / (d_width^2 tau^2 zeta^2), 1/s^2 (multiplied by d(r) in a_ref)."""
        tau = max(self.timeconst, 2.0 * self.timestep)
        return 1.0 / (self.solimp[1] ** 2 * tau**2 * self.dampratio**2)

    @property
    def regularised_mu_squared(self) -> float | np.ndarray:
        """mu_r^2 = mu^2 R_t / R_n = mu^2 / impratio."""
        return self.mu**2 / self.impratio

    def sliding_normal_velocity(self, *, dist: np.ndarray, v_t: np.ndarray, a_n: np.ndarray, a_t: np.ndarray,
                                f_n: np.ndarray) -> np.ndarray:
        """Eq (2): the normal velocity (m/s) a step must start with for a contact at ``dist`` (m) sliding at ``v_t``
        (m/s) whose step has constrained accelerations ``a_n``, ``a_t`` (m/s^2, J qacc) and normal force ``f_n``
        (N); all arrays of one shape."""
        d = impedance(dist, self.solimp)
        r_n = (1.0 - d) / d * self.diag_inverse_inertia
        b = self.damping
        return (self.mu * np.abs(v_t + a_t / b)
                - (a_n + self.stiffness * d * dist + (1.0 + self.regularised_mu_squared) * r_n * f_n) / b)

    def sliding_law_residual(self, *, dist: np.ndarray, v_n: np.ndarray, v_t: np.ndarray, a_n: np.ndarray,
                             a_t: np.ndarray, f_n: np.ndarray) -> np.ndarray:
        """Eq (1)'s residual jar_n - mu |jar_t| + (1 + mu_r^2) R_n f_n over the sum of its terms' magnitudes: 0 (to
        the solver's tolerance) on every row of a sliding contact that MuJoCo's documented law governs."""
        d = impedance(dist, self.solimp)
        r_n = (1.0 - d) / d * self.diag_inverse_inertia
        jar_n = a_n + self.damping * v_n + self.stiffness * d * dist
        jar_t = self.mu * np.abs(a_t + self.damping * v_t)
        force = (1.0 + self.regularised_mu_squared) * r_n * f_n
        return np.abs(jar_n - jar_t + force) / (np.abs(jar_n) + jar_t + np.abs(force))

    def in_cone_zone(self, *, dist: np.ndarray, v_n: np.ndarray, v_t: np.ndarray, a_n: np.ndarray, a_t: np.ndarray
                     ) -> np.ndarray:
        """The rows whose jar lies in the elliptic cone's middle zone (sliding): neither separating (jar_n >= mu
        |jar_t|) nor inside the dual of the regularised cone (mu_r^2 jar_n + mu |jar_t| <= 0)."""
        d = impedance(dist, self.solimp)
        b = self.damping
        jar_n = a_n + b * v_n + self.stiffness * d * dist
        jar_t = np.abs(a_t + b * v_t)
        top = jar_n >= self.mu * jar_t
        bottom = self.regularised_mu_squared * jar_n + self.mu * jar_t <= 0
        return ~top & ~bottom & (jar_t > 0)


def lift_ratio(v_n: np.ndarray, v_t: np.ndarray, mu: float) -> np.ndarray:
    """v_n / (mu |v_t|): 1 when a sliding contact separates exactly at mu |v_t|."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.asarray(v_n, float) / (mu * np.abs(np.asarray(v_t, float)))

