"""One stride of the compass biped with Coulomb friction by complementarity time-stepping, and its return map.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", Secs. 4-5 (the post-impact
section z of Sec. 4.2): per step h the Stewart-Trinkle / Anitescu-Potra update with the stance foot's complementarity
problem, steps shortened to end exactly at a stick/slip switch or at the heel strike, the plastic frictional heel
strike for both feet at once, the section map, its Jacobian and the Richardson extrapolation of the first-order scheme
(:mod:`mjpoincare.analysis.theory.compass_biped_friction.time_stepping`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped
from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_contacts import case_margin, coulomb_contacts
from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_model import (
    Controller,
    Matrix,
    Vector,
    energy,
    foot,
    foot_jacobian,
    free_force,
    mass_matrix,
)
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike, NDArray

#: Longest stride (s) before the step counts as failed (002's periods are ~0.75 s).
T_MAX = 3.0
#: |phi1| (rad) at which the biped counts as fallen.
FALL_ANGLE = 1.2
#: Root iterations that shorten a step to end at a heel strike (swing-foot height below LANDING_TOL, m) or at a
#: stick/slip switch (the left case's margin below SWITCH_TOL, N s or m/s).
ROOT_ITERATIONS = 60
LANDING_TOL = 1e-13
SWITCH_TOL = 1e-13


def from_section(bp: FrictionBiped, z: ArrayLike) -> tuple[Vector, Vector]:
    """Floating-base (q, v) just after a heel strike from 002's section z = (theta*, theta1_dot+, theta2_dot+[,
    x_dot+]): stance foot (leg 1) at the origin with theta1 = theta2 = -theta*, i.e. phi1 = theta*, phi2 = -theta*,
    sliding at x_dot+ along the slope."""
    zz = np.zeros(4)
    zin = np.asarray(z, dtype=float)
    zz[: zin.size] = zin
    th, w1, w2, xd = zz
    q = np.array([-bp.l * math.sin(th), bp.l * math.cos(th), th, -th])
    v = np.array([xd + bp.l * math.cos(th) * w1, bp.l * math.sin(th) * w1, -w1, w2])
    return q, v


@dataclass(frozen=True)
class Stride:
    """One stride from a post-impact section state (:func:`stride`).

    ``z`` the next post-impact section state (theta*, theta1_dot+, theta2_dot+, x_dot+) in 002's convention (theta*
    half the inter-leg angle at the heel strike; the new stance leg is the old swing leg); ``period`` (s);
    ``step_length`` the new stance foot's distance from the old one's start (m); ``slip_distance`` the old stance
    foot's displacement over the stride (m); ``phases`` the stance foot's cases in order ("stick", "slip+",
    "slip-", "free") and ``phase_times`` the start of each (s); ``impact`` the new foot's case at the heel strike
    ("stick" or "slip+"/"slip-") and ``impulse`` its (P_t, P_n) (N s); ``old_foot`` the old stance foot's case at the
    heel strike ("free" = it lifts off, as 002 assumes); ``actuator_work`` sum Q . v+ h (J); ``energy_change``
    E(before the heel strike) - E(start) (J); ``impact_loss`` the kinetic energy the heel strike removes (J);
    ``max_drift`` the largest |height| of the stance foot over the stride (m): the scheme's constraint drift;
    ``max_ratio`` the largest |P_t|/P_n of the stance foot's step impulses (= mu while it slides; with mu = inf, the
    friction a sticking gait needs, 002 Sec. 4.1's mu_c).
    """

    z: Vector
    period: float
    step_length: float
    slip_distance: float
    phases: tuple[str, ...]
    phase_times: tuple[float, ...]
    impact: str
    impulse: Vector
    old_foot: str
    actuator_work: float
    energy_change: float
    impact_loss: float
    max_drift: float
    max_ratio: float

    @property
    def impulse_ratio(self) -> float:
        """P_t / P_n of the heel strike (002's sigma~)."""
        return float(self.impulse[0] / self.impulse[1])

    @property
    def friction_work(self) -> float:
        """Work of the stance foot's friction over the stride (J): the energy balance's remainder."""
        return self.energy_change - self.actuator_work


def _torques(control: Controller | None, q: Vector, v: Vector, t: float) -> tuple[float, float]:
    if control is None:
        return 0.0, 0.0
    return control(-float(q[2]), float(q[3]), -float(v[2]), float(v[3]), t)


def _contact_problem(bp: FrictionBiped, q: Vector, v: Vector, t: float, h: float, control: Controller | None,
                     gap_time: float) -> tuple[Matrix, Vector, Matrix, Vector, float, float, float]:
    """The stance foot's problem for one step of size h, its height closed over ``gap_time`` (the nominal step; a
    shortened step keeps it): (M^-1 J^T, free velocity, Delassus matrix, free contact velocity, floor, ankle, hip)."""
    ankle, hip = _torques(control, q, v, t)
    minv = np.linalg.inv(mass_matrix(bp, q))
    jac = foot_jacobian(bp, q, 0)
    minv_jt = minv @ jac.T
    v_free = v + h * (minv @ free_force(bp, q, v, ankle, hip))
    gap = float(foot(bp, q, 0)[1])
    return minv_jt, v_free, jac @ minv_jt, jac @ v_free, -gap / gap_time, ankle, hip


def _advance(bp: FrictionBiped, q: Vector, v: Vector, t: float, h: float, control: Controller | None,
             gap_time: float) -> tuple[Vector, Vector, str, float, float]:
    """One time step of size h with the stance foot (leg 1) in the complementarity problem: (q+, v+, its case,
    actuator work, |P_t|/P_n)."""
    minv_jt, v_free, delassus, v0, floor, ankle, hip = _contact_problem(bp, q, v, t, h, control, gap_time)
    p, (case,) = coulomb_contacts(delassus, v0, bp.mu, np.array([floor]))
    v_new = v_free + minv_jt @ p
    work = h * (-(ankle + hip) * float(v_new[2]) + hip * float(v_new[3]))
    ratio = abs(float(p[0])) / float(p[1]) if p[1] > 0.0 else 0.0
    return q + h * v_new, v_new, case, work, ratio


def _consistent(bp: FrictionBiped, q: Vector, v: Vector, case: str) -> Vector:
    """The velocity with the stance foot's impulse of ``case`` that makes its contact velocity consistent at q
    (stick: J v+ = 0; slip: v_n+ = 0 with P_t = -+mu P_n). A step leaves J(q+) v+ = O(h) off, by an amount that
    depends on where the step ends; the heel strike reads the state after this projection, which depends on no step
    boundary (impulses along M^-1 J^T of the same case do not change it)."""
    minv_jt = np.linalg.solve(mass_matrix(bp, q), foot_jacobian(bp, q, 0).T)
    delassus = foot_jacobian(bp, q, 0) @ minv_jt
    vt, vn = foot_jacobian(bp, q, 0) @ v
    if case == "stick":
        p = np.linalg.solve(delassus, [-vt, -vn])
    else:
        tie = np.array([-(1.0 if case == "slip+" else -1.0) * bp.mu, 1.0])
        p = tie * (-vn / float(delassus[1] @ tie))
    return v + minv_jt @ p


def _fraction(fun: Callable[[float], float], f0: float, f1: float, tol: float) -> float:
    """Root s in (0, 1] of fun with fun(0) = f0 >= 0 > fun(1) = f1: regula falsi (Illinois)."""
    lo, hi, f_lo, f_hi = 0.0, 1.0, f0, f1
    s, side = 1.0, 0
    for _ in range(ROOT_ITERATIONS):
        s = lo - f_lo * (hi - lo) / (f_hi - f_lo)
        f = fun(s)
        if abs(f) < tol:
            break
        if f > 0.0:
            lo, f_lo = s, f
            if side == 1:
                f_hi *= 0.5
            side = 1
        else:
            hi, f_hi = s, f
            if side == -1:
                f_lo *= 0.5
            side = -1
    return s


def stride(bp: FrictionBiped, z: ArrayLike, h: float, control: Controller | None = None) -> Stride:
    """One stride of the time-stepping scheme (:mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping`)
    from the post-impact section state z of 002 Sec. 4.2 to the next one, with step ``h`` (s). ValueError if the stance
    foot lifts off, the biped falls or stalls (no heel strike within :data:`T_MAX`)."""
    q, v = from_section(bp, z)
    e0 = energy(bp, q, v)
    t, work, drift, max_ratio = 0.0, 0.0, 0.0, 0.0
    phases: list[str] = []
    times: list[float] = []
    armed = located = False
    while True:
        if t > T_MAX:
            raise ValueError(f"no heel strike within {T_MAX} s")
        q1, v1, case, w, ratio = _advance(bp, q, v, t, h, control, h)
        sw = foot(bp, q1, 1)
        landing = armed and sw[1] < 0.0
        if landing:  # shorten the step to end on the slope

            def height(frac: float, q: Vector = q, v: Vector = v, t: float = t) -> float:
                return float(foot(bp, _advance(bp, q, v, t, frac * h, control, h)[0], 1)[1])

            frac = _fraction(height, float(foot(bp, q, 1)[1]), float(sw[1]), LANDING_TOL)
            q1, v1, _, w, ratio = _advance(bp, q, v, t, frac * h, control, h)
            v1 = _consistent(bp, q1, v1, phases[-1])
        elif phases and case != phases[-1] and not located:  # shorten the step to end at the case switch
            left = phases[-1]

            def margin(frac: float, left: str = left, q: Vector = q, v: Vector = v, t: float = t) -> float:
                _, _, delassus, v0, floor, _, _ = _contact_problem(bp, q, v, t, frac * h, control, h)
                return case_margin(delassus, v0, bp.mu, floor, left)

            frac = _fraction(margin, margin(0.0), margin(1.0), SWITCH_TOL)
            q1, v1, _, w, ratio = _advance(bp, q, v, t, frac * h, control, h)
            case = left
        else:
            frac = 1.0
        full = frac == 1.0 and not located and t > 0.0
        located = frac < 1.0 and not landing
        if case == "free":
            raise ValueError(f"the stance foot lifts off at t = {t:.4f} s")
        if abs(float(q1[2])) > FALL_ANGLE:
            raise ValueError(f"the biped falls (stance leg at {float(q1[2]):.2f} rad)")
        if not landing and (not phases or phases[-1] != case):
            phases.append(case)
            times.append(t)
        work += w
        if full:  # a full step after a full step: its impulse carries the J_dot q_dot term like the exact force
            max_ratio = max(max_ratio, ratio)
        drift = max(drift, abs(float(foot(bp, q1, 0)[1])))
        q, v, t = q1, v1, t + frac * h
        if landing:
            break
        armed = armed or (sw[0] > foot(bp, q1, 0)[0] and sw[1] > 0.0)
    e_pre = energy(bp, q, v)
    jac = np.vstack([foot_jacobian(bp, q, 0), foot_jacobian(bp, q, 1)])
    mass = mass_matrix(bp, q)
    minv_jt = np.linalg.solve(mass, jac.T)
    p, (old, new) = coulomb_contacts(jac @ minv_jt, jac @ v, bp.mu, np.zeros(2))
    v_plus = v + minv_jt @ p
    start = 0.0
    half = 0.5 * (float(q[3]) - float(q[2]))  # half the inter-leg angle: theta* of 002
    new_foot_v = foot_jacobian(bp, q, 1) @ v_plus
    return Stride(
        z=np.array([half, -float(v_plus[3]), float(v_plus[2]), float(new_foot_v[0])]),
        period=t,
        step_length=float(foot(bp, q, 1)[0]) - start,
        slip_distance=float(foot(bp, q, 0)[0]) - start,
        phases=tuple(phases),
        phase_times=tuple(times),
        impact=new,
        impulse=p[2:].copy(),
        old_foot=old,
        actuator_work=work,
        energy_change=e_pre - e0,
        impact_loss=0.5 * float(v @ mass @ v - v_plus @ mass @ v_plus),
        max_drift=drift,
        max_ratio=max_ratio,
    )


def return_map(bp: FrictionBiped, z: ArrayLike, h: float, control: Controller | None = None) -> Vector:
    """z -> z' of :func:`stride`, with the input's length (3: a sticking gait's section, x_dot+ = 0)."""
    zz = np.asarray(z, dtype=float)
    return stride(bp, zz, h, control).z[: zz.size]


def map_jacobian(bp: FrictionBiped, z: ArrayLike, h: float, delta: float, control: Controller | None = None
                 ) -> Matrix:
    """dP/dz of :func:`return_map` by central differences of size ``delta`` (rad, rad/s, m/s)."""
    return central_jacobian(lambda zz: return_map(bp, zz, h, control), np.asarray(z, dtype=float), delta)


def richardson(coarse: ArrayLike, fine: ArrayLike) -> NDArray[np.float64]:
    """Richardson extrapolation of a first-order scheme from steps h (``coarse``) and h/2 (``fine``):
    2 fine - coarse, whose error is O(h^2)."""
    return 2.0 * np.asarray(fine, dtype=float) - np.asarray(coarse, dtype=float)
