"""Compass biped with Coulomb friction: stick-slip stance, frictional heel strike, passive and actuated gaits.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 4 (passive CB on a slope, eq 27, Figs 4.1-4.2), Sec. 5 (actuated CB on level ground, eqs 28-30,
Figs 5.1-5.2) and Appendix A (eqs 31-40); re-derivation with numbers on the derivation page
docs/theory/stick-slip.md, Secs. 3, 4 and 7. The
stance and impact machinery is the model-agnostic :mod:`mjpoincare.analysis.theory.stick_slip`; this module only
supplies the matrices of eq 27, the actuation, the heel-strike guard, the relabelling and the shooting. It never
imports mujoco.

Model (002 eq 27, SI units): legs of length ``l`` with a point mass ``m`` at distance ``d`` from the foot, hip
mass ``m_h``, slope ``slope`` = alpha, friction ``mu`` (static = kinetic). q = (theta1, theta2, x, y): (x, y) is the
stance foot in the slope frame (x downhill = walking direction, y along the slope normal); theta1 is the stance
leg's foot->hip direction (sin theta1, cos theta1) and theta2 the swing leg's hip->foot direction
(sin theta2, -cos theta2), both from the slope normal. Swing foot r~ = (x + l(S1 + S2), y + l(C1 - C2)).
With K = d m + l (m + m_h), b = l - d, M_tot = 2m + m_h:
M = [[d^2 m + l^2 (m + m_h), l m b C12, K C1, -K S1], [., m b^2, m b C2, m b S2], [., ., M_tot, 0], [., ., 0, M_tot]],
B = (-l m b S12 th2d^2, -l m b S12 th1d^2, -m b S2 th2d^2 - K S1 th1d^2, -K C1 th1d^2 + m b C2 th2d^2),
G = g (-K sin(theta1 + alpha), -m b sin(alpha - theta2), -M_tot sin(alpha), M_tot cos(alpha)),
W = [[0, 0, 1, 0], [0, 0, 0, 1]], W~ = [[l C1, l C2, 1, 0], [-l S1, l S2, 0, 1]] (002 eq 27 as printed; the tests
re-derive M, B, G from the point-mass Lagrangian by finite differences). Equations of motion 002 eq 2 in the sign
of :mod:`mjpoincare.analysis.theory.stick_slip`: M qdd = -(B + G - Q) + W^T f, Q the actuation's generalised force.

Step: from the post-impact state theta1 = theta2 = -theta*, (theta1_dot, theta2_dot, x_dot) and y_dot = 0, the
stance is integrated (stick / slip+ / slip-, 002 eq 35) until heel strike theta1 = theta2 > 0 (swing foot ahead and
descending); the scuffing of the swing foot near mid-stance is ignored, as in 002 Sec. 4.1. Then the frictional
plastic impact of 002 eqs 37-40 (sticking if its impulse is in the cone, else slipping) and the relabelling of 002
Sec. 4 (theta1 <-> -theta2, theta1_dot <-> -theta2_dot; the new stance foot is the old swing foot, its post-impact
velocity (x_dot+, 0) the new (x_dot, y_dot)). Poincaré section: post-impact, z = (theta*, theta1_dot+, theta2_dot+)
plus x_dot+ when the impact slips (002 Sec. 4.2; 3-D for Gaits A, B, 4-D for Gait C).

Actuation (002 Sec. 5), stated as the generalised force Q on (theta1, theta2):

* :class:`ConstantTorque` (eq 28, Gaits I/II): 002 prints E = [[1, 0, 0, 0], [1, 1, 0, 0]]^T, i.e.
  Q = (tau1 + tau2, tau2); this is the Jacobian of a physical ankle torque on theta1 and a hip torque on the
  inter-leg angle theta1 + theta2. With the reported Gait I torques tau1 = -2.73, tau2 = 0.54 it gives
  Q1 = -2.19 N m, and the biped falls backwards on its first step (tests; derivation page Sec. 3.3). The torques
  fit the "gravity replacement" Q1 = g K (sin(theta1 + alpha) - sin(theta1)) ~ +2.19 cos(theta1),
  Q2 = g m b (sin(alpha - theta2) + sin(theta2)) ~ +0.547 cos(theta2) of alpha = 1 deg only with the effective
  E_eff = [[-1, 0, 0, 0], [-1, 1, 0, 0]]^T: Q = (-tau1 - tau2, tau2) (default ``convention="effective"``). The same
  Q comes from physical (printed-E) ankle and hip torques (tau_a, tau_h) = (-tau1 - 2 tau2, tau2), e.g. (1.65, 0.54)
  N m for Gait I: a simulator must reproduce Q, not the printed tau.
* :class:`PDTracking` (eq 30, Gait III): tau_i = -kp (theta_i - theta_i^r(phi)) - kd (theta_i_dot -
  theta_i_dot^r(phi)) with phi the time since the last impact (phase reset), applied as Q = (tau1, tau2), the
  generalised force on each angle (``convention="direct"``; with E_eff the stance-leg feedback would have the
  destabilising sign). The reference is a stored gait trajectory (:class:`ReferenceTrajectory`, sampled with
  :func:`reference_trajectory`); 002's is the passive Gait C of its Fig. 4.2a, mu = 0.14 (:func:`gait_c_reference`).

Time dependence: :class:`.stick_slip.ContactModel` has time-free callables, so :func:`contact_model`
appends two decoupled unit-mass coordinates: index 4 is the phase clock phi (phi_dot = 1, phi_ddot = 0) and index 5
an actuator-work accumulator whose velocity is W_act(t) = int Q . qd dt (its acceleration is Q . qd). Neither enters
W, W~ or the coupling of M, so the stick-slip machinery is used unchanged (stick_slip.py is not modified).

Gaits (002 Secs. 4-5; :func:`paper_gait`, seeds in :data:`GAIT_SEEDS`, values in the tests):

* A (sticking throughout) and B (sticking impact, slip+ -> stick -> slip-): the values of the derivation page,
  Sec. 3.2; B loses stability at mu = 0.11035 (linear interpolation of the page's table: 0.1104; 002 "~0.11").
  Gait A equals the passive biped of
  :mod:`.compass_biped` (003 Ch. 4) in that module's angles.
* C (slipping impact with forward slip, slip+ -> stick, stuck before the heel strike) is found here by
  :func:`search_gaits` (grid on the pre-impact section, then Newton): unstable
  (|lambda|max 1.82 at mu = 0.14, 1.53 at 0.2), impact angle 4.53 deg at mu = 0.14 (002: "4 deg" in Fig. 4.2a)
  and 6.52 deg at 0.2, coexisting with B and with A above mu_c, as 002 says. The 4-D map has one multiplier ~0
  (the slip -> stick transition collapses x_dot, like the rimless wheel's Type C). Continued upwards, the branch
  ends at mu = 0.3044, where its post-impact slip vanishes and it joins a second, unstable sticking-impact passive
  gait (theta* = 0.14282, multipliers 2.342, 0.625, 0.273, |sigma~| = 0.3044). Why it is easy to miss: in Gait C
  the legs pass parallel only after the stance leg has passed the normal (theta1 ~ 0.014 rad), so the swing foot
  dips < 0.3 mm below the ground ahead of the stance foot until it emerges at theta1 = theta2 ~ 0.026 rad; a
  heel-strike guard that stops at the legs-parallel crossing rejects the orbit (:func:`heel_strike_guard`,
  :func:`heel_strike_after_scuff`, ``StepRecord.late_swing``). And theta1_dot+ is tiny (0.044 rad/s at mu = 0.14),
  so perturbed orbits roll back.
* I (E_eff, -2.73/0.54): the derivation page's Sec. 3.3 table; stability is lost at mu = 0.10350 (002 "stable
  for mu > 0.11").
* II (-0.69/0.12, E_eff, slipping impact): unstable on [0.09, 0.2], c_mt = 0.0044 as in 002; W = 0.120 J (002
  0.1), S = 0.279 m (002 0.23). The energy split is not 002's: friction work -0.005 J and impact loss 0.116 J at
  mu = 0.2 (002: 0.078 J and 0.022 J). 002 says these torques are the mean inverse-dynamics torques of Gait C on
  level ground, but rows theta1, theta2 of eq 2 carry no contact force (W has zero columns there), so for any
  passive slope trajectory the level-ground inverse dynamics give exactly Q = G(alpha = 0) - G(alpha) on the angles,
  ~ (2.19, 0.55) N m, i.e. Gait I's torques, not (-0.69, 0.12).
* III (PD tracking Gait C of mu = 0.14, direct convention): stable on [0.09, 0.2] with slipping impact and forward
  post-impact slip, also above mu_c; S = 0.24-0.25 m (002 ~0.23); |lambda|max 0.57 (mu = 0.2) to 0.86 (0.09), not
  002's "< 0.5 for all mu". Pure PD tracking of Gait A on level ground (no feedforward) found no gait: the biped
  rolls back after a few steps.

Corrections to 002 found here (also on the derivation page, Sec. 7 items 3-5, 12-14):

* (34) sign, (39) Gamma~ = (s mu, 1)^T, W q_dot = 0 (not W = 0): see :mod:`mjpoincare.analysis.theory.stick_slip`.
* Sec. 5 / (28): E and the reported torques are sign-inconsistent (above).
* Sec. 4.1 says the scuffing collision is "where theta1 = theta2", while the legs pass parallel at
  theta2 = -theta1. The swing foot crosses the ground line twice before the heel strike and is below it in between
  (:func:`scuffing_crossings`): along Gait A first at theta1 = theta2 < 0 (foot behind the stance foot), then at
  theta2 = -theta1 (legs parallel); along Gait C first at theta2 = -theta1 (theta1 > 0), then at
  theta1 = theta2 > 0 (foot ahead, emerging). Both statements name one end of that interval; the heel strike is the
  later, downward crossing theta1 = theta2 > 0.
* Sec. 5 (29): c_mt = W/(M_tot g S) with the total weight M_tot g, W in J (printed "W = 0.1").

Independent confirmation: :mod:`.compass_biped_time_stepping` computes the same gaits by complementarity
time-stepping in floating-base coordinates, sharing no equation, mode logic or impact law with this module; its
Richardson-extrapolated strides reproduce the fixed points of Gaits B, C, I, II, III to 4e-6, the step quantities to
6e-6 and the multipliers to 6e-3 (tests/test_theory_compass_biped_time_stepping.py). Where 002 disagrees (III
|lambda|max < 0.5; II S = 0.23 m, W = 0.1 J), the evidence supports this model's values for the model as printed
(eq 27, the torques and gains of Sec. 5 in the convention that reproduces Gait I); what 002 computed differently is
not recoverable from the paper.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any, NamedTuple, Protocol

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.shooting import central_jacobian, chord_newton
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]

#: Number of physical coordinates (theta1, theta2, x, y); the model carries 2 more (clock, work accumulator).
NQ = 4
#: Printed actuation matrix of 002 eq 28 (rows theta1, theta2, x, y; columns tau1, tau2).
E_PRINTED = np.array([[1.0, 0.0], [1.0, 1.0], [0.0, 0.0], [0.0, 0.0]])
#: Effective actuation matrix that reproduces 002's Gait I (derivation page docs/theory/stick-slip.md, Sec. 3.3).
E_EFFECTIVE = np.array([[-1.0, 0.0], [-1.0, 1.0], [0.0, 0.0], [0.0, 0.0]])
#: Longest stance integrated (s) before a step counts as "stalled" (002's period is ~0.75 s).
T_MAX = 5.0
#: |theta1| (rad) at which the biped counts as fallen.
FALL_ANGLE = 1.2
#: Absolute central-difference step on the section coordinates (rad, rad/s, m/s) for Jacobians. The map is smooth
#: while the phase sequence and impact kind are unchanged; the stance integration error (rtol 1e-11) then puts the
#: Jacobian noise at ~1e-6 and the truncation error at ~1e-10. Where a perturbation of size FD_STEP changes the phase
#: sequence (a stick phase grazing the cone, a slip speed grazing 0) or the impact kind, the map is only piecewise
#: smooth (continuous, with a kink) and the central difference is the mean of the one-sided derivatives.
FD_STEP = 1e-5
#: Newton converges when the largest |P(z) - z| is below this.
NEWTON_TOL = 1e-10


# --- parameters and actuation ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class FrictionBiped:
    """Compass biped of 002 Sec. 4.1 (paper values as defaults): leg length ``l`` (m), leg point mass ``m`` (kg)
    at ``d`` (m) from the foot, hip mass ``m_h`` (kg), gravity ``g`` (m/s^2), slope alpha (rad; 0 = level ground of
    002 Sec. 5), Coulomb coefficient ``mu`` (``math.inf`` = no slip)."""

    l: float = 1.6
    d: float = 0.8
    m: float = 4.0
    m_h: float = 2.0
    g: float = 9.8
    slope: float = math.radians(1.0)
    mu: float = math.inf

    @property
    def k(self) -> float:
        """K = d m + l (m + m_h), the stance-leg mass moment of 002 eq 27 (kg m)."""
        return self.d * self.m + self.l * (self.m + self.m_h)

    @property
    def b(self) -> float:
        """Hip-to-swing-mass distance l - d (m)."""
        return self.l - self.d

    @property
    def total_mass(self) -> float:
        """M_tot = 2 m + m_h (kg)."""
        return 2.0 * self.m + self.m_h


def validate(bp: FrictionBiped) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range (002 Sec. 4.1: l > 0, 0 < d < l,
    m, m_h > 0; g > 0; |alpha| < pi/2; mu >= 0, inf allowed)."""
    if not bp.l > 0.0:
        raise ValueError(f"l must be > 0 m (got {bp.l!r})")
    if not 0.0 < bp.d < bp.l:
        raise ValueError(f"d must be in (0, l) = (0, {bp.l!r}) m (got {bp.d!r})")
    for name in ("m", "m_h"):
        if not getattr(bp, name) > 0.0:
            raise ValueError(f"{name} must be > 0 kg (got {getattr(bp, name)!r})")
    if not bp.g > 0.0:
        raise ValueError(f"g must be > 0 m/s^2 (got {bp.g!r})")
    if not abs(bp.slope) < math.pi / 2:
        raise ValueError(f"slope must be in (-pi/2, pi/2) rad (got {bp.slope!r})")
    if not bp.mu >= 0.0:
        raise ValueError(f"mu must be >= 0 (got {bp.mu!r})")


class Actuation(Protocol):
    """Generalised actuation force Q = (Q_theta1, Q_theta2) on the angles (002 eq 2's E u; Q_x = Q_y = 0) as a
    function of the physical state (theta1, theta2, x, y), its rates and the phase phi = time since the last impact
    (002 eq 30)."""

    def generalised_force(self, q: Vector, qd: Vector, phase: float) -> tuple[float, float]: ...


@dataclass(frozen=True)
class ConstantTorque:
    """Open-loop constant ankle/hip torques (tau1, tau2) (N m) of 002 Sec. 5 (Gaits I, II), eq 28.

    ``convention="effective"`` (default): Q = E_eff u = (-tau1 - tau2, tau2), the convention that reproduces
    002's Gait I (see the module docstring); ``"printed"``: Q = E u with 002's printed E, (tau1 + tau2, tau2)."""

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


# --- model (002 eq 27) ----------------------------------------------------------------------------------------


def mass_matrix(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """M(q) of 002 eq 27 (4 x 4, physical coordinates)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    k, b, m = bp.k, bp.b, bp.m
    c1, s1, c2, s2, c12 = math.cos(th1), math.sin(th1), math.cos(th2), math.sin(th2), math.cos(th1 + th2)
    return np.array(
        [
            [bp.d**2 * m + bp.l**2 * (m + bp.m_h), bp.l * m * b * c12, k * c1, -k * s1],
            [bp.l * m * b * c12, m * b * b, m * b * c2, m * b * s2],
            [k * c1, m * b * c2, bp.total_mass, 0.0],
            [-k * s1, m * b * s2, 0.0, bp.total_mass],
        ]
    )


def coriolis_vector(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> Vector:
    """B(q, qd) of 002 eq 27 (velocity terms on the left-hand side of eq 2)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    w1, w2 = float(np.asarray(qd)[0]) ** 2, float(np.asarray(qd)[1]) ** 2
    k, mb, s12 = bp.k, bp.m * bp.b, math.sin(th1 + th2)
    return np.array(
        [
            -bp.l * mb * s12 * w2,
            -bp.l * mb * s12 * w1,
            -mb * math.sin(th2) * w2 - k * math.sin(th1) * w1,
            -k * math.cos(th1) * w1 + mb * math.cos(th2) * w2,
        ]
    )


def gravity_vector(bp: FrictionBiped, q: ArrayLike) -> Vector:
    """G(q) = dV/dq of 002 eq 27 (left-hand side of eq 2)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    a, g, mt = bp.slope, bp.g, bp.total_mass
    return g * np.array(
        [-bp.k * math.sin(th1 + a), -bp.m * bp.b * math.sin(a - th2), -mt * math.sin(a), mt * math.cos(a)]
    )


def potential_energy(bp: FrictionBiped, q: ArrayLike) -> float:
    """V = g [M_tot (y cos(alpha) - x sin(alpha)) + K cos(theta1 + alpha) - m b cos(theta2 - alpha)] (J), height
    along the true vertical from the slope line through the origin; dV/dq = G of 002 eq 27."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    a = bp.slope
    return bp.g * (
        bp.total_mass * (y * math.cos(a) - x * math.sin(a)) + bp.k * math.cos(th1 + a) - bp.m * bp.b * math.cos(th2 - a)
    )


def kinetic_energy(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """T = qd^T M qd / 2 (J) with M of 002 eq 27."""
    v = np.asarray(qd, dtype=float)[:NQ]
    return 0.5 * float(v @ mass_matrix(bp, q) @ v)


def energy(bp: FrictionBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """Total mechanical energy T + V (J)."""
    return kinetic_energy(bp, q, qd) + potential_energy(bp, q)


def point_masses(bp: FrictionBiped, q: ArrayLike) -> tuple[tuple[float, Vector], ...]:
    """(mass, slope-frame position) of the stance-leg mass, the hip and the swing-leg mass (002 Sec. 4, Fig. 4.1a):
    the kinematics from which M, B, G of eq 27 follow."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    u1 = np.array([math.sin(th1), math.cos(th1)])
    u2 = np.array([math.sin(th2), -math.cos(th2)])
    foot = np.array([x, y])
    hip = foot + bp.l * u1
    return (bp.m, foot + bp.d * u1), (bp.m_h, hip), (bp.m, hip + bp.b * u2)


def swing_foot(bp: FrictionBiped, q: ArrayLike) -> Vector:
    """Swing-foot position r~ = (x + l(sin theta1 + sin theta2), y + l(cos theta1 - cos theta2)) (002 eq 27)."""
    th1, th2, x, y = (float(v) for v in np.asarray(q)[:NQ])
    return np.array([x + bp.l * (math.sin(th1) + math.sin(th2)), y + bp.l * (math.cos(th1) - math.cos(th2))])


def swing_jacobian(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """W~(q) = d r~/dq = [[l C1, l C2, 1, 0], [-l S1, l S2, 0, 1]] (002 eq 27)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    l = bp.l
    return np.array(
        [[l * math.cos(th1), l * math.cos(th2), 1.0, 0.0], [-l * math.sin(th1), l * math.sin(th2), 0.0, 1.0]]
    )


def heel_strike_guard(q: ArrayLike) -> float:
    """max(theta2 - theta1, -(theta1 + theta2)): > 0 just after an impact (theta1 = theta2 = -theta*) and while the
    swing foot is behind the stance foot, crossing 0 downwards at the heel strike theta1 = theta2 > 0 (002 Sec. 4;
    the same guard as :mod:`.compass_biped` in its angles). It also crosses 0 when the legs pass
    parallel (theta1 + theta2 = 0) with theta1 > theta2, i.e. with the stance leg already past the normal; the
    stance is then continued with :func:`heel_strike_after_scuff` (:func:`step`, ``late_swing``)."""
    th1, th2 = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    return max(th2 - th1, -(th1 + th2))


_JAC = np.zeros((2, NQ + 2))
_JAC[0, 2] = 1.0
_JAC[1, 3] = 1.0


def contact_model(bp: FrictionBiped, actuation: Actuation | None = None) -> ss.ContactModel:
    """The biped as a :class:`.stick_slip.ContactModel` (002 eq 27 with eq 28 or 30) on the
    augmented q = (theta1, theta2, x, y, phi, w): phi the phase clock, w_dot the actuator work (module docstring).

    h = B + G - Q (002 eq 2), W and W~ of eq 27 (zero columns for the clock and accumulator), guard
    :func:`heel_strike_guard`; failure events ``"fell"`` (|theta1| = FALL_ANGLE) and ``"backward"`` (the stance leg
    stops and turns back, theta1_dot -> 0 from above; as for the rimless wheel of 002 Sec. 3.4, no step follows).
    """
    validate(bp)
    act = PASSIVE if actuation is None else actuation
    l, k, mb, mt, g, a = bp.l, bp.k, bp.m * bp.b, bp.total_mass, bp.g, bp.slope
    m11 = bp.d**2 * bp.m + l**2 * (bp.m + bp.m_h)
    mbb = mb * bp.b
    sin_a, cos_a = math.sin(a), math.cos(a)
    passive = isinstance(act, ConstantTorque) and act.tau1 == 0.0 and act.tau2 == 0.0

    def mass(q: Vector) -> Matrix:
        s1, c1, s2, c2 = math.sin(q[0]), math.cos(q[0]), math.sin(q[1]), math.cos(q[1])
        c12 = c1 * c2 - s1 * s2
        return np.array(
            [
                [m11, l * mb * c12, k * c1, -k * s1, 0.0, 0.0],
                [l * mb * c12, mbb, mb * c2, mb * s2, 0.0, 0.0],
                [k * c1, mb * c2, mt, 0.0, 0.0, 0.0],
                [-k * s1, mb * s2, 0.0, mt, 0.0, 0.0],
                [0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            ]
        )

    def bias(q: Vector, qd: Vector) -> Vector:
        s1, c1, s2, c2 = math.sin(q[0]), math.cos(q[0]), math.sin(q[1]), math.cos(q[1])
        s12 = s1 * c2 + c1 * s2
        w1, w2 = qd[0] * qd[0], qd[1] * qd[1]
        q1, q2 = (0.0, 0.0) if passive else act.generalised_force(q[:NQ], qd[:NQ], float(q[4]))
        return np.array(
            [
                -l * mb * s12 * w2 - g * k * (s1 * cos_a + c1 * sin_a) - q1,
                -l * mb * s12 * w1 - g * mb * (sin_a * c2 - cos_a * s2) - q2,
                -mb * s2 * w2 - k * s1 * w1 - mt * g * sin_a,
                -k * c1 * w1 + mb * c2 * w2 + mt * g * cos_a,
                0.0,
                -(q1 * qd[0] + q2 * qd[1]),
            ]
        )

    def swing(q: Vector) -> Matrix:
        return np.array(
            [
                [l * math.cos(q[0]), l * math.cos(q[1]), 1.0, 0.0, 0.0, 0.0],
                [-l * math.sin(q[0]), l * math.sin(q[1]), 0.0, 1.0, 0.0, 0.0],
            ]
        )

    return ss.ContactModel(
        mass_matrix=mass,
        bias=bias,
        contact_jacobian=lambda _q: _JAC,
        contact_jacobian_rate=lambda _q, _qd: np.zeros(2),
        swing_jacobian=swing,
        impact_guard=lambda q, _qd: heel_strike_guard(q),
        guard_direction=-1.0,
        failure_events=(
            ("fell", lambda q, _qd: FALL_ANGLE - abs(float(q[0])), -1.0),
            ("backward", lambda _q, qd: float(qd[0]), -1.0),
        ),
    )


@lru_cache(maxsize=64)
def _model(bp: FrictionBiped, actuation: Actuation) -> ss.ContactModel:
    return contact_model(bp, actuation)


def section_state(z: ArrayLike) -> tuple[Vector, Vector]:
    """Augmented (q, qd) just after an impact from the section z = (theta*, theta1_dot+, theta2_dot+[, x_dot+]):
    theta1 = theta2 = -theta*, x = y = 0, y_dot = 0, clock 0 with rate 1, work 0 (002 Sec. 4.2)."""
    zz = np.asarray(z, dtype=float)
    x_dot = float(zz[3]) if zz.size > 3 else 0.0
    q = np.array([-zz[0], -zz[0], 0.0, 0.0, 0.0, 0.0])
    qd = np.array([zz[1], zz[2], x_dot, 0.0, 1.0, 0.0])
    return q, qd


# --- one step -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class StepRecord:
    """One step from a post-impact section state (see :func:`step`).

    ``z0`` the start (theta*, theta1_dot+, theta2_dot+, x_dot+); ``z`` the next post-impact section state (NaN on
    failure); ``failure`` None or the stance outcome ("detached", "painleve", "fell", "backward", "stalled",
    "chatter", "solver"), "scuff" (the stance ended at theta1 = theta2 <= 0, no heel strike ahead) or "impact" (the
    impact law is inconsistent: F~_n <= 0, slip reversal, or the old stance foot pushed into the ground); ``impact``
    "sticking"/"slipping"; ``phases`` the stance modes in order ("stick", "slip+" = forward slip, "slip-", 002
    eq 35) with their start times ``phase_times``; ``period`` T (s); ``step_length`` S = displacement of the stance
    foot over the stance plus the foot separation 2 l sin(theta-) at heel strike (m; the distance the biped advances
    per step); ``slip_distance`` the stance foot's displacement; ``q_pre``, ``qd_pre`` physical state before the
    impact; ``actuator_work`` W_act = int Q . qd dt (J, 002 eq 29); ``friction_work`` int f_t v_t dt (J, <= 0; from
    the energy balance, the normal force does no work); ``impact_loss`` kinetic energy lost at the heel strike (J),
    of which ``impact_loss_tangential`` = -F~_t (v~_t- + v~_t+)/2 by the tangential impulse (the rest,
    -F~_n v~_n-/2, by the normal one); ``impulse`` (F~_t, F~_n) (N s); ``liftoff_velocity`` slope-normal velocity of
    the trailing foot after the impact (m/s); ``min_fn`` min f_n (N); ``late_swing``: the legs passed parallel only
    after the stance leg had passed the normal (theta1 > 0), so the swing foot travelled below the ground ahead of
    the stance foot before emerging (ignored, as the scuffing of 002 Sec. 4.1).

    Only with ``forces=True`` (else NaN): ``max_ratio`` max |f_t/f_n| over the stance (= mu while slipping) at
    ``max_ratio_time`` with the signed value ``max_ratio_sigma``; ``min_swing_height`` the lowest swing-foot height
    inside the stance (m; < 0: the ignored scuffing dip) at ``min_swing_height_time``.
    """

    z0: Vector
    z: Vector
    failure: str | None
    impact: str | None
    phases: tuple[str, ...]
    phase_times: tuple[float, ...]
    period: float
    step_length: float
    slip_distance: float
    q_pre: Vector
    qd_pre: Vector
    actuator_work: float
    friction_work: float
    impact_loss: float
    impact_loss_tangential: float
    impulse: Vector
    liftoff_velocity: float
    min_fn: float
    late_swing: bool
    max_ratio: float = math.nan
    max_ratio_time: float = math.nan
    max_ratio_sigma: float = math.nan
    min_swing_height: float = math.nan
    min_swing_height_time: float = math.nan

    @property
    def impulse_ratio(self) -> float:
        """sigma~ = F~_t/F~_n of the heel-strike impulse (002 Sec. 4.1, Fig. 4.1c 'x')."""
        return float(self.impulse[0] / self.impulse[1])

    @property
    def theta_star(self) -> float:
        """Impact angle theta1 = theta2 at the heel strike (rad)."""
        return float(self.q_pre[0])


def _nan_record(z0: Vector, failure: str, phases: tuple[str, ...], times: tuple[float, ...], t: float,
                q: Vector, qd: Vector, min_fn: float, late: bool) -> StepRecord:
    nan = math.nan
    return StepRecord(z0, np.full(4, nan), failure, None, phases, times, t, nan, nan, q[:NQ].copy(), qd[:NQ].copy(),
                      nan, nan, nan, nan, np.full(2, nan), nan, min_fn, late)


def heel_strike_after_scuff(q: ArrayLike) -> float:
    """theta2 - theta1: the guard that continues a stance after the legs passed parallel with theta1 > 0 (see
    :func:`heel_strike_guard`); with direction -1 it ignores the upward crossing where the swing foot, which then
    travels below the ground (ignored like the scuffing of 002 Sec. 4.1), emerges ahead of the stance foot, and
    stops at the heel strike theta1 = theta2 with the foot descending."""
    return float(np.asarray(q)[1] - np.asarray(q)[0])


@lru_cache(maxsize=64)
def _late_model(bp: FrictionBiped, actuation: Actuation) -> ss.ContactModel:
    return replace(_model(bp, actuation), impact_guard=lambda q, _qd: heel_strike_after_scuff(q))


def _stance(bp: FrictionBiped, act: Actuation, q0: Vector, qd0: Vector, t_max: float, rtol: float = ss.RTOL
            ) -> tuple[ss.StanceResult, bool]:
    """integrate_stance (002 eqs 2, 31-35) to the heel strike theta1 = theta2 > 0, continued once through a late
    legs-parallel crossing (:func:`heel_strike_after_scuff`), at relative tolerance ``rtol`` (absolute rtol x
    ATOL/RTOL). Returns (stance, continued); a continued stance has the phases of both parts (a phase split at the
    crossing appears twice)."""
    tol = {"rtol": rtol, "atol": rtol * ss.ATOL / ss.RTOL}
    first = ss.integrate_stance(_model(bp, act), q0, qd0, bp.mu, t_max=t_max, **tol)
    q = first.q_end
    if not (first.impacted and q[1] - q[0] < -1e-8 and q[0] > 0.0):
        return first, False
    rest = ss.integrate_stance(_late_model(bp, act), q, first.qd_end, bp.mu, t0=first.t_end, t_max=t_max,
                               mode=first.phases[-1].mode, **tol)
    merged = ss.StanceResult(first.phases + rest.phases, rest.outcome, rest.t_end, rest.q_end, rest.qd_end,
                             min(first.min_normal_force, rest.min_normal_force), {**rest.sections, **first.sections})
    return merged, True


def _collapse(phases: Sequence[ss.Phase]) -> tuple[tuple[str, ...], tuple[float, ...]]:
    """Modes and start times with consecutive repeats merged."""
    modes: list[str] = []
    times: list[float] = []
    for p in phases:
        if not modes or modes[-1] != p.mode:
            modes.append(p.mode)
            times.append(p.t_start)
    return tuple(modes), tuple(times)


def _phase_solutions(model: ss.ContactModel, stance: ss.StanceResult, mu: float) -> list[tuple[str, float, float, Any]]:
    """Re-integrate each phase of a stance from its recorded start (same mode, same tolerances) with a dense
    output: (mode, t0, t1, OdeSolution or None for a zero-length phase)."""
    out: list[tuple[str, float, float, Any]] = []
    ends = [p.t_start for p in stance.phases[1:]] + [stance.t_end]
    n = NQ + 2
    for phase, t1 in zip(stance.phases, ends, strict=True):
        if not t1 > phase.t_start:
            out.append((phase.mode, phase.t_start, t1, None))
            continue

        def rhs(_t: float, y: Vector, mode: str = phase.mode) -> Vector:
            return np.concatenate([y[n:], ss.contact_state(model, y[:n], y[n:], mode, mu).qdd])

        sol = solve_ivp(rhs, (phase.t_start, t1), np.concatenate([phase.q_start, phase.qd_start]), method="DOP853",
                        rtol=ss.RTOL, atol=ss.ATOL, dense_output=True,
                        max_step=ss.SLIP_MAX_STEP if phase.mode != "stick" else np.inf)
        out.append((phase.mode, phase.t_start, t1, sol.sol))
    return out


def _refined_max(fun: Callable[[float], float], t0: float, t1: float, samples: int) -> tuple[float, float]:
    """(max of fun on [t0, t1], where): dense samples and a bounded refinement around the best one."""
    ts = np.linspace(t0, t1, samples)
    vals = np.array([fun(t) for t in ts])
    i = int(np.argmax(vals))
    t_best, v_best = float(ts[i]), float(vals[i])
    if 0 < i < samples - 1:
        res = minimize_scalar(lambda t: -fun(t), bounds=(ts[i - 1], ts[i + 1]), method="bounded",
                              options={"xatol": 1e-12})
        if -res.fun > v_best:
            t_best, v_best = float(res.x), float(-res.fun)
    return v_best, t_best


def _diagnostics(bp: FrictionBiped, model: ss.ContactModel, stance: ss.StanceResult) -> tuple[float, ...]:
    """(max |f_t/f_n|, its time, signed f_t/f_n there, min swing-foot height, its time) over the stance, on the
    re-integrated phases (129 samples each plus a bounded refinement); a slip phase contributes |f_t/f_n| = mu."""
    mu, n = bp.mu, NQ + 2
    ratio = (-math.inf, math.nan, math.nan)
    low = (math.inf, math.nan)
    for mode, t0, t1, sol in _phase_solutions(model, stance, mu):
        if sol is None:
            continue

        def height(t: float, sol: Any = sol) -> float:
            y = sol(t)
            return float(bp.l * (math.cos(y[0]) - math.cos(y[1])))

        # the swing foot starts and ends on the ground: only the interior counts
        lo, hi = (t0, t1)
        if t0 == 0.0:
            lo = t0 + 1e-6 * (t1 - t0)
        if t1 == stance.t_end:
            hi = t1 - 1e-6 * (t1 - t0)
        neg_h, t_h = _refined_max(lambda t: -height(t), lo, hi, 129)
        if -neg_h < low[0]:
            low = (-neg_h, t_h)
        if mode != "stick":
            if ratio[0] < mu:
                ratio = (mu, t0, (-1.0 if mode == "slip+" else 1.0) * mu)
            continue

        def sigma(t: float, sol: Any = sol) -> float:
            y = sol(t)
            f = ss.contact_state(model, y[:n], y[n:], "stick", mu).force
            return float(f[0] / f[1])

        v, t = _refined_max(lambda t: abs(sigma(t)), t0, t1, 129)
        if v > ratio[0]:
            ratio = (v, t, sigma(t))
    return (*ratio, *low)


def step(bp: FrictionBiped, z: ArrayLike, actuation: Actuation | None = None, *, forces: bool = False,
         t_max: float = T_MAX, rtol: float = ss.RTOL) -> StepRecord:
    """One step of the (actuated) biped from the post-impact section state z = (theta*, theta1_dot+, theta2_dot+)
    or (..., x_dot+) (002 Secs. 4-5): the stance by :func:`.stick_slip.integrate_stance` (002 eqs 2,
    31-35) until the heel strike theta1 = theta2 > 0 (the swing foot's passages below the ground line are ignored,
    002 Sec. 4.1), the frictional impact :func:`.stick_slip.impact` (002 eqs 37-40, corrected) and
    the relabelling theta1 <-> -theta2, theta1_dot <-> -theta2_dot (002 Sec. 4).
    ``forces``: also compute max |f_t/f_n| and the lowest swing-foot height (re-integrates the phases; slower).
    ``rtol``: the stance integration's relative tolerance (:func:`_stance`).
    """
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    z0 = np.zeros(4)
    zz = np.asarray(z, dtype=float)
    z0[: zz.size] = zz
    q0, qd0 = section_state(z0)
    mu = bp.mu
    stance, late = _stance(bp, act, q0, qd0, t_max, rtol)
    phases, times = _collapse(stance.phases)
    q, qd = stance.q_end, stance.qd_end
    if not stance.impacted:
        return _nan_record(z0, stance.outcome, phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    if abs(q[1] - q[0]) > 1e-8 or not q[0] > 0.0:
        return _nan_record(z0, "scuff", phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    imp = ss.impact(model, q, qd, mu)
    if not imp.consistent:
        return _nan_record(z0, "impact", phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    qd_plus = imp.qd_plus
    e_start = energy(bp, q0, qd0)
    e_pre = energy(bp, q, qd)
    w_act = float(qd[5])
    v_minus = model.swing_jacobian(q) @ qd
    extra = _diagnostics(bp, model, stance) if forces else (math.nan,) * 5
    return StepRecord(
        z0=z0,
        z=np.array([0.5 * (q[0] + q[1]), -qd_plus[1], -qd_plus[0], imp.swing_velocity[0]]),
        failure=None,
        impact=imp.kind,
        phases=phases,
        phase_times=times,
        period=stance.t_end,
        step_length=float(swing_foot(bp, q)[0]),
        slip_distance=float(q[2]),
        q_pre=q[:NQ].copy(),
        qd_pre=qd[:NQ].copy(),
        actuator_work=w_act,
        friction_work=e_pre - e_start - w_act,
        impact_loss=kinetic_energy(bp, q, qd) - kinetic_energy(bp, q, qd_plus),
        impact_loss_tangential=float(-imp.impulse[0] * (v_minus[0] + imp.swing_velocity[0]) / 2.0),
        impulse=imp.impulse.copy(),
        liftoff_velocity=imp.liftoff_velocity,
        min_fn=stance.min_normal_force,
        late_swing=late,
        max_ratio=extra[0],
        max_ratio_time=extra[1],
        max_ratio_sigma=extra[2],
        min_swing_height=extra[3],
        min_swing_height_time=extra[4],
    )


def return_map(bp: FrictionBiped, z: ArrayLike, actuation: Actuation | None = None, rtol: float = ss.RTOL
               ) -> Vector:
    """Poincaré map on the post-impact section (002 Sec. 4.2): z -> z' with z = (theta*, theta1_dot+,
    theta2_dot+) (3-D, x_dot+ = 0: Gaits A, B) or (..., x_dot+) (4-D: Gait C); the output has the input's length.
    NaN on a failed step. ``rtol``: as :func:`step`'s."""
    zz = np.asarray(z, dtype=float)
    return step(bp, zz, actuation, rtol=rtol).z[: zz.size]


def classify(record: StepRecord) -> str:
    """Gait type of a step (002 Sec. 4.2): ``"A"`` sticking impact, stick throughout; ``"B"`` sticking impact with
    slip during the stance; ``"C"`` slipping impact with a stick phase during the stance; ``"D"`` slipping impact,
    slip throughout (the Type-D-like gait 002 did not find for the CB). A failed step gives "failed: <reason>"."""
    if record.failure is not None:
        return f"failed: {record.failure}"
    slips = any(p != "stick" for p in record.phases)
    if record.impact == "sticking":
        return "B" if slips else "A"
    return "C" if "stick" in record.phases else "D"


def describe(record: StepRecord) -> str:
    """Human-readable step pattern, e.g. "sticking impact; slip+ -> stick -> slip-" (slip+ = forward slip)."""
    if record.failure is not None:
        return f"failed: {record.failure} after {' -> '.join(record.phases)}"
    return f"{record.impact} impact; {' -> '.join(record.phases)}"


# --- pre-impact section: the search that finds Gait C ---------------------------------------------------------


def impact_from_pre(bp: FrictionBiped, p: ArrayLike, actuation: Actuation | None = None
                    ) -> tuple[Vector | None, ss.ImpactResult]:
    """Heel strike (002 eqs 37-40) and relabelling from a pre-impact state p = (theta, theta1_dot-, theta2_dot-[,
    x_dot-]) at theta1 = theta2 = theta: (post-impact section state z, impact result); z is None when the impact
    law is inconsistent."""
    pp = np.asarray(p, dtype=float)
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    th = float(pp[0])
    q = np.array([th, th, 0.0, 0.0, 0.0, 0.0])
    qd = np.array([pp[1], pp[2], pp[3] if pp.size > 3 else 0.0, 0.0, 1.0, 0.0])
    imp = ss.impact(model, q, qd, bp.mu)
    if not imp.consistent:
        return None, imp
    return np.array([th, -imp.qd_plus[1], -imp.qd_plus[0], imp.swing_velocity[0]]), imp


def pre_impact_map(bp: FrictionBiped, p: ArrayLike, actuation: Actuation | None = None
                   ) -> tuple[Vector, StepRecord | None, ss.ImpactResult]:
    """Poincaré map on the pre-impact section p = (theta, theta1_dot-, theta2_dot-, x_dot-) (conjugate to the
    post-impact map of 002 Sec. 4.2): impact, relabelling, stance. Returns (next p or NaN, record, impact). When the
    stance ends sticking, x_dot- = 0 whatever the start, so on such steps the map is effectively 3-D (the slip ->
    stick transition of Gait C collapses x_dot; one post-impact multiplier is 0, as for the rimless wheel's Type C)."""
    z, imp = impact_from_pre(bp, p, actuation)
    if z is None:
        return np.full(4, math.nan), None, imp
    rec = step(bp, z, actuation)
    if rec.failure is not None:
        return np.full(4, math.nan), rec, imp
    return np.concatenate([rec.q_pre[:1], rec.qd_pre[:3]]), rec, imp


def search_gaits(bp: FrictionBiped, thetas: Sequence[float], rates1: Sequence[float], rates2: Sequence[float],
                 actuation: Actuation | None = None, impact: str = "slipping", candidates: int = 8) -> list[Vector]:
    """Search for period-1 gaits with the given impact kind (default slipping: 002's Gait C, II) on a grid of
    pre-impact states (theta, theta1_dot-, theta2_dot-) with x_dot- = 0 (stuck before the impact): the
    ``candidates`` grid points with the smallest scaled one-step residual max |(p' - p)/(0.05, 0.5, 0.5)| seed a
    Newton shooting on the 3-D pre-impact map (:func:`pre_impact_map`); each converged orbit is returned as its
    post-impact section state z* (4 components), duplicates removed. Cost: one step per grid point."""
    scale = np.array([0.05, 0.5, 0.5])
    scored: list[tuple[float, Vector]] = []
    for th in thetas:
        for w1 in rates1:
            for w2 in rates2:
                p = np.array([th, w1, w2])
                nxt, rec, imp = pre_impact_map(bp, np.append(p, 0.0), actuation)
                if rec is None or imp.kind != impact or not np.all(np.isfinite(nxt)):
                    continue
                scored.append((float(np.max(np.abs((nxt[:3] - p) / scale))), p))
    scored.sort(key=lambda item: item[0])

    def gap(p: Vector) -> Vector:
        nxt, rec, imp = pre_impact_map(bp, np.append(p, 0.0), actuation)
        if rec is None or imp.kind != impact or abs(nxt[3]) > 1e-9:
            return np.full(3, math.nan)
        return nxt[:3] - p

    found: list[Vector] = []
    for _, p in scored[:candidates]:
        p_star = chord_newton(gap, p, tol=NEWTON_TOL)
        if p_star is None:
            continue
        z, _ = impact_from_pre(bp, np.append(p_star, 0.0), actuation)
        if z is not None and not any(np.allclose(z, f, atol=1e-6) for f in found):
            found.append(z)
    return found


# --- fixed points and eigenvalues -----------------------------------------------------------------------------


def _gap(bp: FrictionBiped, actuation: Actuation | None, dim: int, kind: str | None) -> Callable[[Vector], Vector]:
    """P(z) - z restricted to ``dim`` section coordinates; NaN when the step fails or (``kind``) has the wrong
    impact kind."""

    def gap(z: Vector) -> Vector:
        rec = step(bp, z, actuation)
        if rec.failure is not None or (kind is not None and rec.impact != kind):
            return np.full(dim, math.nan)
        return rec.z[:dim] - z

    return gap


def fixed_point(bp: FrictionBiped, guess: ArrayLike, actuation: Actuation | None = None,
                jacobian: ArrayLike | None = None) -> Vector:
    """Period-1 gait z* = (theta*, theta1_dot+, theta2_dot+, x_dot+) by Newton shooting on the post-impact section
    (002 Secs. 4-5): a 3-vector guess shoots on the 3-D map with x_dot+ = 0 (sticking impact: Gaits A, B, I), a
    4-vector on the 4-D map (slipping impact: Gaits C, II, III). ``jacobian``: a map Jacobian dP/dz (e.g. of a
    nearby gait) to start Newton with. ValueError if Newton does not converge or the converged step has the other
    impact kind."""
    g = np.asarray(guess, dtype=float)
    if g.size not in (3, 4):
        raise ValueError(f"guess must have 3 or 4 components (got {g.size})")
    kind = "sticking" if g.size == 3 else "slipping"
    jac0 = None if jacobian is None else np.asarray(jacobian, dtype=float) - np.eye(g.size)
    z = chord_newton(_gap(bp, actuation, g.size, kind), g, tol=NEWTON_TOL, jac0=jac0)
    if z is None:
        raise ValueError(f"fixed-point shooting from {g!r} did not converge to a {kind}-impact gait (mu = {bp.mu!r})")
    out = np.zeros(4)
    out[: g.size] = z
    return out


def map_jacobian(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                 h: float = FD_STEP) -> Matrix:
    """dP/dz of the post-impact map at z* by central differences (step ``h``, see FD_STEP): 3 x 3 when the step's
    impact sticks (then x_dot+ = 0 for every nearby state, so the 4-D map only adds an exact multiplier 0), 4 x 4
    when it slips (002 Sec. 4.2)."""
    z = np.asarray(z_star, dtype=float)
    rec = step(bp, z, actuation)
    if rec.failure is not None:
        raise ValueError(f"the step from {z!r} fails ({rec.failure})")
    dim = 3 if rec.impact == "sticking" else 4
    return central_jacobian(lambda v: return_map(bp, v, actuation), z[:dim], h)


def eigenvalues(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                h: float = FD_STEP) -> NDArray[np.complex128]:
    """Eigenvalues of the linearised Poincaré map at the gait z* (:func:`map_jacobian`), sorted by modulus,
    descending (002 Figs 4.2b, 5.2a plot the largest modulus)."""
    return sort_eigenvalues(np.linalg.eigvals(map_jacobian(bp, z_star, actuation, h)).astype(complex))


def spectral_radius(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None) -> float:
    """|lambda|max of :func:`eigenvalues`."""
    return float(np.max(np.abs(eigenvalues(bp, z_star, actuation))))


@dataclass(frozen=True)
class Gait:
    """A period-1 gait: the biped, its actuation, the fixed point z* (4 components), the map Jacobian and its
    eigenvalues (sorted by modulus, descending: :func:`~mjpoincare.analysis.eigenvalues.sort_eigenvalues`), the step
    record (with forces) and its :func:`classify` label."""

    biped: FrictionBiped
    actuation: Actuation
    z: Vector
    jacobian: Matrix
    eigenvalues: NDArray[np.complex128]
    record: StepRecord
    kind: str

    @property
    def spectral_radius(self) -> float:
        """|lambda|max."""
        return float(np.max(np.abs(self.eigenvalues)))


def find_gait(bp: FrictionBiped, guess: ArrayLike, actuation: Actuation | None = None,
              jacobian: ArrayLike | None = None) -> Gait:
    """:func:`fixed_point`, :func:`map_jacobian` with its eigenvalues and the step record (with forces) in one
    (002 Secs. 4-5)."""
    act = PASSIVE if actuation is None else actuation
    z = fixed_point(bp, guess, act, jacobian)
    jac = map_jacobian(bp, z, act)
    rec = step(bp, z, act, forces=True)
    return Gait(bp, act, z, jac, sort_eigenvalues(np.linalg.eigvals(jac).astype(complex)), rec, classify(rec))


class _Solved(NamedTuple):
    z: Vector
    jacobian: Matrix


def continuation(bp: FrictionBiped, mus: Sequence[float], z_start: ArrayLike,
                 actuation: Actuation | None = None, max_halvings: int = 4, mu_start: float | None = None
                 ) -> list[Gait]:
    """Natural-parameter continuation of a gait in mu (002 Figs 4.2b, 5.2): the gait at each mu of ``mus`` (in
    order), Newton started from a predictor with the previous map Jacobian. ``z_start`` is the gait at ``mu_start``
    (refined there first), or a guess for the first mu when ``mu_start`` is None. Predictor: the secant through the
    last two gaits, or after the first one the tangent dz/dmu = (I - J)^-1 dP/dmu (dP/dmu by a central difference
    of 1e-5). Where Newton fails the mu step is halved (intermediate gaits are not returned), up to
    ``max_halvings`` times; then the continuation stops (the list is shorter than ``mus``). The length of
    ``z_start`` (3 or 4) fixes the impact kind, as in :func:`fixed_point`."""
    dim = np.asarray(z_start).size
    z_first = np.asarray(z_start, dtype=float)[:dim]
    act = PASSIVE if actuation is None else actuation
    path: list[tuple[float, Vector]] = []  # (mu, z) of every gait found, for the predictor
    jac: Matrix | None = None

    def solve(mu: float, guess: Vector) -> _Solved | None:
        b = replace(bp, mu=mu)
        try:
            z = fixed_point(b, guess, act, jac if jac is not None and jac.shape == (dim, dim) else None)
            return _Solved(z, map_jacobian(b, z, act))
        except ValueError:
            return None

    def predict(mu: float) -> Vector:
        if not path:
            return z_first
        m1, z1 = path[-1]
        if len(path) >= 2:
            m0, z0 = path[-2]
            return z1 + (z1 - z0) / (m1 - m0) * (mu - m1)
        if jac is None or jac.shape != (dim, dim):
            return z1
        d = 1e-5
        dp = (return_map(replace(bp, mu=m1 + d), z1, act) - return_map(replace(bp, mu=m1 - d), z1, act)) / (2 * d)
        if not np.all(np.isfinite(dp)):
            return z1
        return z1 + np.linalg.solve(np.eye(dim) - jac, dp) * (mu - m1)

    if mu_start is not None:
        first = solve(mu_start, z_first)
        path.append((mu_start, first.z[:dim] if first is not None else z_first))
        jac = first.jacobian if first is not None else None
    out: list[Gait] = []
    for target in (float(m) for m in mus):
        gait = solve(target, predict(target)) if not (path and path[-1][0] == target and jac is not None) else None
        if gait is None and path and path[-1][0] == target and jac is not None:
            gait = _Solved(np.concatenate([path[-1][1], np.zeros(4 - dim)]), jac)
        if gait is None and path:
            start = path[-1][0]
            for k in range(1, max_halvings + 1):
                sub = np.linspace(start, target, 2**k + 1)[1:]
                saved = (list(path), jac)
                for mu in sub:
                    gait = solve(float(mu), predict(float(mu)))
                    if gait is None:
                        break
                    path.append((float(mu), gait.z[:dim]))
                    jac = gait.jacobian
                if gait is not None:
                    break
                path, jac = saved
        if gait is None:
            break
        if not path or path[-1][0] != target:
            path.append((target, gait.z[:dim]))
        jac = gait.jacobian
        b = replace(bp, mu=target)
        rec = step(b, gait.z, act, forces=True)
        lam = sort_eigenvalues(np.linalg.eigvals(gait.jacobian).astype(complex))
        out.append(Gait(b, act, gait.z, gait.jacobian, lam, rec, classify(rec)))
    return out


def stability_loss_mu(bp: FrictionBiped, z_start: ArrayLike, mu_start: float, mu_stop: float,
                      actuation: Actuation | None = None, mu_step: float = 0.01, tol: float = 1e-5) -> float:
    """mu at which |lambda|max of a gait continued from (z_start, mu_start) towards mu_stop crosses 1 (002 Sec. 4.2:
    Gait B "loses stability at mu ~ 0.11"; Sec. 5: Gait I "stable for mu > 0.11"): :func:`continuation` on a grid of
    at most ``mu_step``, then regula falsi (Illinois) on |lambda|max(mu) - 1 inside the bracketing grid interval to
    |lambda|max - 1 < 1e-6 (the finite-difference noise) or a bracket below ``tol``, each Newton started from the
    linear interpolation of the bracketing gaits with their map Jacobian. ValueError if it does not cross on
    [mu_stop, mu_start] or the branch ends first."""
    n = max(1, math.ceil(abs(mu_start - mu_stop) / mu_step - 1e-9))
    grid = np.linspace(mu_start, mu_stop, n + 1)
    gaits = continuation(bp, grid, z_start, actuation, mu_start=mu_start)
    dim = np.asarray(z_start).size
    rho = [g.spectral_radius - 1.0 for g in gaits]
    for i in range(len(gaits) - 1):
        if rho[i] * rho[i + 1] <= 0.0:
            lo, hi = gaits[i], gaits[i + 1]

            def f(mu: float, lo: Gait = lo, hi: Gait = hi) -> float:
                w = (mu - lo.biped.mu) / (hi.biped.mu - lo.biped.mu)
                guess = (1 - w) * lo.z[:dim] + w * hi.z[:dim]
                b = replace(bp, mu=mu)
                z = fixed_point(b, guess, actuation, lo.jacobian)
                return spectral_radius(b, z, actuation) - 1.0

            # Illinois regula falsi: |lambda|max(mu) is smooth and nearly linear inside one grid interval
            a, fa, b, fb = lo.biped.mu, rho[i], hi.biped.mu, rho[i + 1]
            for _ in range(40):
                if fb == fa:
                    break
                c = b - fb * (b - a) / (fb - fa)
                fc = f(c)
                if fc * fb < 0.0:
                    a, fa = b, fb
                else:
                    fa *= 0.5
                b, fb = c, fc
                if abs(fc) < 1e-6 or abs(b - a) < tol:
                    break
            return float(b)
    raise ValueError(f"|lambda|max does not cross 1 on the continued branch ({len(gaits)} of {grid.size} gaits)")


# --- the gaits of 002 Secs. 4-5 -------------------------------------------------------------------------------

_AB_SEEDS = (
    (0.2, (0.1478369, 0.7327968, -0.5006679)),
    (0.14, (0.1408071, 0.7102088, -0.5168477)),
    (0.11, (0.1227550, 0.6475338, -0.5131655)),
)
#: (mu, section state z*) pairs of each named gait of 002 from which :func:`paper_gait` continues (computed here;
#: see the module docstring). "A" and "B" are one branch (sticking impact): Gait A for mu >= mu_c = 0.1749, Gait B
#: below. Gait C's post-impact theta1_dot+ is small at low mu (0.044 rad/s at 0.14), so it has seeds at both ends.
GAIT_SEEDS: dict[str, tuple[tuple[float, tuple[float, ...]], ...]] = {
    "A": _AB_SEEDS,
    "B": _AB_SEEDS,
    "C": ((0.14, (0.0790379, 0.0437766, -0.4317612, 0.6341740)), (0.2, (0.1137971, 0.2499297, -0.5764132, 0.5770183))),
    "I": ((0.2, (0.1480151, 0.7340354, -0.5026890)), (0.11, (0.1259916, 0.6483977, -0.6059526))),
    "II": ((0.2, (0.0871665, 0.4447162, -0.4921641, 0.0839298)),),
    "III": (
        (0.2, (0.0744951, 0.2627163, -0.4256346, 0.2531528)),
        (0.09, (0.0720499, 0.2311505, -0.3868293, 0.2788256)),
    ),
}
#: Gait I and II torques (tau1, tau2) of 002 Sec. 5 (effective convention, see the module docstring).
GAIT_I_TORQUES = (-2.73, 0.54)
GAIT_II_TORQUES = (-0.69, 0.12)
#: mu of the passive Gait C whose joint trajectory Gait III tracks (002 Sec. 5: "Gait C ... in Figure 4.2(a)",
#: which is drawn for mu = 0.14).
GAIT_III_REFERENCE_MU = 0.14


@lru_cache(maxsize=4)
def gait_c_reference(mu: float = GAIT_III_REFERENCE_MU, samples: int = 401) -> ReferenceTrajectory:
    """Joint trajectory of the passive Gait C (slope 1 deg) at ``mu``: Gait III's reference (002 eq 30)."""
    gait = paper_gait("C", mu)
    return reference_trajectory(gait.biped, gait.z, samples=samples)


def paper_setup(name: str, mu: float) -> tuple[FrictionBiped, Actuation]:
    """Biped and actuation of a named gait of 002: "A"/"B"/"C" passive on the 1 deg slope (Sec. 4), "I"/"II"
    constant torques (E_eff) and "III" PD (kp = kd = 15, direct, tracking :func:`gait_c_reference`) on level
    ground (Sec. 5)."""
    if name in ("A", "B", "C"):
        return FrictionBiped(mu=mu), PASSIVE
    level = FrictionBiped(slope=0.0, mu=mu)
    if name == "I":
        return level, ConstantTorque(*GAIT_I_TORQUES)
    if name == "II":
        return level, ConstantTorque(*GAIT_II_TORQUES)
    if name == "III":
        return level, PDTracking(gait_c_reference())
    raise ValueError(f"unknown gait {name!r}; one of A, B, C, I, II, III")


@lru_cache(maxsize=64)
def paper_gait(name: str, mu: float, max_step: float = 0.01) -> Gait:
    """The named gait of 002 ("A" and "B" are one branch, see :data:`GAIT_SEEDS`) at friction ``mu``, continued
    from the seed nearest in mu in steps of at most ``max_step`` (for mu = inf: Newton from the largest-mu seed).
    ValueError if the branch does not reach mu."""
    if name not in GAIT_SEEDS:
        raise ValueError(f"unknown gait {name!r}; one of {', '.join(GAIT_SEEDS)}")
    bp, act = paper_setup(name, mu)
    seeds = GAIT_SEEDS[name]
    seed_mu, seed_z = max(seeds) if math.isinf(mu) else min(seeds, key=lambda s: abs(s[0] - mu))
    if math.isinf(mu) or mu == seed_mu:
        return find_gait(bp, seed_z, act)
    n = math.ceil(abs(mu - seed_mu) / max_step - 1e-9)
    mus = [float(m) for m in np.linspace(seed_mu, mu, n + 1)[1:]]
    gaits = continuation(bp, mus, seed_z, act, mu_start=seed_mu)
    if len(gaits) < len(mus):
        raise ValueError(f"gait {name} could not be continued from mu = {seed_mu} to {mu}")
    return gaits[-1]


# --- friction demand, cost and speed (002 Secs. 4.1, 5) ------------------------------------------------------


class FrictionDemand(NamedTuple):
    """Friction needed by a sticking gait (002 Sec. 4.1, Fig. 4.1c): ``stance`` mu_c = max |f_t/f_n| over the
    stance, reached at ``time`` (s after the impact) with signed ratio ``sigma``; ``impulse`` |sigma~| =
    |F~_t/F~_n| of the heel strike. Stick throughout needs mu >= max(stance, impulse)."""

    stance: float
    time: float
    sigma: float
    impulse: float


def critical_friction(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None) -> FrictionDemand:
    """mu_c and |sigma~| of the gait z* computed with mu = inf (002 Sec. 4.1: mu_c = 0.175, |sigma~| = 0.145 for
    Gait A)."""
    rec = step(replace(bp, mu=math.inf), z_star, actuation, forces=True)
    if rec.failure is not None:
        raise ValueError(f"the step from {np.asarray(z_star)!r} fails ({rec.failure})")
    return FrictionDemand(rec.max_ratio, rec.max_ratio_time, rec.max_ratio_sigma, abs(rec.impulse_ratio))


def cost_of_transport(bp: FrictionBiped, record: StepRecord) -> float:
    """Specific cost c_mt = W_act/(M_tot g S) (002 eq 29 with the total weight; docs/theory/stick-slip.md, Sec. 7
    item 14)."""
    return record.actuator_work / (bp.total_mass * bp.g * record.step_length)


def average_speed(record: StepRecord) -> float:
    """v = S/T (m/s) (002 Sec. 5, below eq 29)."""
    return record.step_length / record.period


# --- reference trajectories for PD tracking (002 eq 30) -------------------------------------------------------


def reference_trajectory(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                         samples: int = 401) -> ReferenceTrajectory:
    """The joint trajectory theta^r(phi), theta_dot^r(phi) (and theta_ddot) of the step from z* (a gait of 002
    Secs. 4-5, e.g. passive Gait C), on ``samples`` equally spaced phases from 0 to the step period plus the phase
    switches (values from the re-integrated phases). This is the reference of 002 eq 30 and the control sequence a
    simulator's PD tracker needs."""
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    q0, qd0 = section_state(np.asarray(z_star, dtype=float))
    stance, _ = _stance(bp, act, q0, qd0, T_MAX)
    if not stance.impacted:
        raise ValueError(f"the step from {np.asarray(z_star)!r} fails ({stance.outcome})")
    sols = [s for s in _phase_solutions(model, stance, bp.mu) if s[3] is not None]
    grid = np.linspace(0.0, stance.t_end, samples)
    n = NQ + 2
    times: list[float] = []
    th: list[Vector] = []
    om: list[Vector] = []
    al: list[Vector] = []
    for k, (mode, t0, t1, sol) in enumerate(sols):
        inner = grid[(grid > t0) & (grid < t1)]
        ts = np.concatenate([[t0], inner, [t1]] if k == len(sols) - 1 else [[t0], inner])
        for t in ts:
            y = sol(t)
            times.append(float(t))
            th.append(y[0:2].copy())
            om.append(y[n : n + 2].copy())
            al.append(ss.contact_state(model, y[:n], y[n:], mode, bp.mu).qdd[0:2].copy())
    return ReferenceTrajectory(np.array(times), np.array(th), np.array(om), np.array(al))


def stance_foot_motion(bp: FrictionBiped, z_star: ArrayLike, times: ArrayLike, actuation: Actuation | None = None
                       ) -> tuple[Vector, Vector]:
    """(x, x_dot) of the stance foot along the slope at ``times`` after the impact of the step from z (002 Secs.
    4-5: the foot's coordinate x of eq 27, 0 at the impact; x_dot > 0 is forward slip), from the re-integrated
    phases; NaN past the heel strike. A simulator's stance-foot speed can then be classified with the same
    threshold as the exact one (a stick -> slip switch shows in the speed only once it has grown)."""
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    q0, qd0 = section_state(np.asarray(z_star, dtype=float))
    stance, _ = _stance(bp, act, q0, qd0, T_MAX)
    ts = np.asarray(times, dtype=float)
    x, v = np.full(ts.shape, np.nan), np.full(ts.shape, np.nan)
    for _mode, t0, t1, sol in _phase_solutions(model, stance, bp.mu):
        sel = (ts >= t0) & (ts <= t1)
        if sol is not None and sel.any():
            y = sol(ts[sel])
            x[sel], v[sel] = y[2], y[NQ + 2 + 2]
    return x, v


def scuffing_crossings(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                       samples: int = 2001) -> list[tuple[float, float, float]]:
    """Zero crossings of the swing-foot height l(cos theta1 - cos theta2) strictly inside the stance of the step
    from z* (002 Sec. 4.1 "scuffing"): (t, theta1, theta2) of each, from a dense sample of the stance (exact zeros
    on the sample grid, e.g. at a continued legs-parallel crossing, count as crossings)."""
    ref = reference_trajectory(bp, z_star, actuation, samples)

    def height(t: float) -> float:
        r = ref.evaluate(t)
        return math.cos(r[0]) - math.cos(r[1])

    h = np.cos(ref.theta[:, 0]) - np.cos(ref.theta[:, 1])
    out: list[tuple[float, float, float]] = []
    for i in range(1, len(h) - 1):
        t: float | None = None
        if h[i] == 0.0 and h[i - 1] * h[i + 1] < 0.0:
            t = float(ref.times[i])
        elif h[i] * h[i + 1] < 0.0 and i + 1 < len(h) - 1:
            t = float(brentq(height, ref.times[i], ref.times[i + 1], xtol=1e-13))
        if t is not None:
            r = ref.evaluate(t)
            out.append((t, r[0], r[1]))
    return out


def legs_parallel(g: Gait) -> tuple[np.ndarray, float]:
    """Analytic legs-parallel state (theta1, theta1_dot, -theta2_dot) where theta1 + theta2 = 0 rises through 0
    along the step from z* (the MuJoCo hinges are then equal), and the time of it after the impact."""
    ref = reference_trajectory(g.biped, g.z, g.actuation, samples=2001)
    gap = ref.theta[:, 0] + ref.theta[:, 1]
    i = int(np.nonzero((gap[:-1] < 0) & (gap[1:] >= 0))[0][0])
    t = float(brentq(lambda s: sum(ref.evaluate(s)[:2]), ref.times[i], ref.times[i + 1], xtol=1e-13))
    r = ref.evaluate(t)
    return np.array([r[0], r[2], -r[3]]), t
