"""Compass biped with Coulomb friction by complementarity time-stepping: a second, independent computation of the
stick-slip gaits of 002 (Gamus & Or) Secs. 4-5.

:mod:`.compass_biped_friction` is event-driven: eq 27's matrices in the stance-foot coordinates (theta1, theta2, x,
y), a stick / slip+ / slip- mode per phase with its own force law (002 eqs 31-35), event functions for every mode
switch, and the impact law split into its sticking and slipping cases (eqs 37-40). Nothing of that is used here.

* **Coordinates and equations.** Floating base q = (x_h, y_h, phi1, phi2): the hip in the slope frame (x downhill,
  y along the slope normal) and the absolute angle of each leg, hip -> foot direction (sin phi, -cos phi) from the
  slope normal. The Lagrangian of the three point masses (hip ``m_h``; leg masses ``m`` at ``b = l - d`` from the
  hip), L = 1/2 sum m |p_dot|^2 - sum m g (p_y cos alpha - p_x sin alpha), gives
  M = [[M_tot, 0, m b cos phi1, m b cos phi2], [0, M_tot, m b sin phi1, m b sin phi2],
       [., ., m b^2, 0], [., ., 0, m b^2]],
  M q_ddot = F(q, q_dot) + J^T lambda with F = (M_tot g sin alpha + m b (sin phi1 phi1_dot^2 + sin phi2 phi2_dot^2),
  -M_tot g cos alpha - m b (cos phi1 phi1_dot^2 + cos phi2 phi2_dot^2), -m g b sin(phi1 - alpha),
  -m g b sin(phi2 - alpha)) plus the actuation, and each foot r_i = (x_h + l sin phi_i, y_h - l cos phi_i) with
  the Jacobian rows (t, n) = ([1, 0, l cos phi_i], [0, 1, l sin phi_i]) in its columns (x_h, y_h, phi_i).
* **Actuation** as physical couples (002 Sec. 5): an ankle torque ``ankle`` on the stance leg, reacted by the
  ground, and a hip torque ``hip`` on the inter-leg angle phi2 - phi1, reacted by the stance leg; their generalised
  forces follow from virtual work: Q_phi1 = -ankle - hip, Q_phi2 = hip (the stance leg is leg 1; its 002 angle is
  theta1 = -phi1, the swing leg's theta2 = phi2).
* **Contact** by the Stewart-Trinkle / Anitescu-Potra time-stepping scheme (see docs/references.md): per step h,
  M (v+ - v) = h F(q, v, t) + J^T P, q+ = q + h v+, with the stance foot's impulse P = (P_t, P_n) solving the
  Signorini-Coulomb complementarity problem 0 <= P_n _|_ g/h + v_n+ >= 0, |P_t| <= mu P_n, P_t = -mu P_n sgn(v_t+)
  while sliding (maximal dissipation), enumerated over its four cases (free, stick, slide+, slide-). The stick/slip
  phases are whatever case each step's problem takes; no mode logic and no force law per mode. A step in which the
  case changes is shortened to end where the case it leaves stops being valid (its complementarity margin crosses
  0, :func:`case_margin`), so that the switch does not leave an O(h) error that depends on where it falls in the
  step grid (which would make the map's central differences noisy).
* **Heel strike.** The swing foot's contact is armed once the foot is ahead of the stance foot and above the slope
  (002 Sec. 4.1 ignores the scuffing before that); the step in which the armed foot would pass the slope is
  shortened so that it lands exactly (secant on the step fraction), and the plastic frictional impact is the same
  complementarity problem with h = 0 for both feet at once (inelastic: v_n+ >= 0 _|_ P_n >= 0 at each foot, Coulomb
  cone), 16 cases enumerated. Before it, the stance foot's velocity is made consistent at the landing configuration
  (:func:`_consistent`), for the same reason. Whether the impact sticks or slips, and whether the old stance foot
  lifts off, are outputs of that problem, not assumptions.

The scheme is first order in h (:func:`stride` at several h; :func:`richardson`), so this module checks the
event-driven gaits' fixed points, multipliers, step lengths, work and phase times to the accuracy its step allows.
It imports no MuJoCo and nothing of :mod:`.compass_biped_friction` but the parameter record and, for Gait III, the
reference trajectory that defines the controller.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction import FrictionBiped, ReferenceTrajectory
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike, NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]

#: (theta1, theta2, theta1_dot, theta2_dot, phase) -> (ankle, hip) torques (N m), angles and rates in 002's
#: stance-foot convention (theta1 = -phi1, theta2 = phi2), phase = time since the last heel strike.
Controller = Callable[[float, float, float, float, float], tuple[float, float]]
#: Longest stride (s) before the step counts as failed (002's periods are ~0.75 s).
T_MAX = 3.0
#: |phi1| (rad) at which the biped counts as fallen.
FALL_ANGLE = 1.2
#: Root iterations that shorten a step to end at a heel strike (swing-foot height below LANDING_TOL, m) or at a
#: stick/slip switch (the left case's margin below SWITCH_TOL, N s or m/s).
ROOT_ITERATIONS = 60
LANDING_TOL = 1e-13
SWITCH_TOL = 1e-13
#: Relative tolerance of the complementarity conditions (case selection of the enumeration).
LCP_TOL = 1e-10
#: Case labels of one contact: ("free", "stick", "slip+", "slip-"); slip+ is forward (downhill) sliding.
CASES = ("free", "stick", "slip+", "slip-")


def constant_torques(ankle: float, hip: float) -> Controller:
    """Open-loop constant ankle and hip torques (N m), 002 Sec. 5 (Gaits I, II)."""
    return lambda *_args: (ankle, hip)


def pd_tracking(reference: ReferenceTrajectory, kp: float = 15.0, kd: float = 15.0) -> Controller:
    """002 eq 30 with phase reset: tau_i = -kp (theta_i - theta_i^r(phi)) - kd (theta_i_dot - theta_i_dot^r(phi))
    as the generalised force on each of 002's angles (Q_theta = (tau1, tau2)); as physical couples that is
    hip = tau2 and ankle = tau1 - tau2 (Q_theta1 = ankle + hip, Q_theta2 = hip by virtual work)."""

    def control(th1: float, th2: float, w1: float, w2: float, phase: float) -> tuple[float, float]:
        r1, r2, v1, v2 = reference.evaluate(phase)
        tau1 = -kp * (th1 - r1) - kd * (w1 - v1)
        tau2 = -kp * (th2 - r2) - kd * (w2 - v2)
        return tau1 - tau2, tau2

    return control


# --- the floating-base model ------------------------------------------------------------------------------------


def mass_matrix(bp: FrictionBiped, q: ArrayLike) -> Matrix:
    """M(q) of the floating-base Lagrangian (module docstring), (4, 4)."""
    p1, p2 = float(np.asarray(q)[2]), float(np.asarray(q)[3])
    mt, mb = bp.total_mass, bp.m * bp.b
    c1, s1, c2, s2 = math.cos(p1), math.sin(p1), math.cos(p2), math.sin(p2)
    return np.array([[mt, 0.0, mb * c1, mb * c2], [0.0, mt, mb * s1, mb * s2],
                     [mb * c1, mb * s1, mb * bp.b, 0.0], [mb * c2, mb * s2, 0.0, mb * bp.b]])


def free_force(bp: FrictionBiped, q: ArrayLike, v: ArrayLike, ankle: float = 0.0, hip: float = 0.0) -> Vector:
    """F(q, q_dot): gravity, the velocity terms and the couples' generalised force (module docstring), (4,)."""
    p1, p2 = float(np.asarray(q)[2]), float(np.asarray(q)[3])
    w1, w2 = float(np.asarray(v)[2]), float(np.asarray(v)[3])
    mt, mb, g, a = bp.total_mass, bp.m * bp.b, bp.g, bp.slope
    return np.array([
        mt * g * math.sin(a) + mb * (math.sin(p1) * w1 * w1 + math.sin(p2) * w2 * w2),
        -mt * g * math.cos(a) - mb * (math.cos(p1) * w1 * w1 + math.cos(p2) * w2 * w2),
        -mb * g * math.sin(p1 - a) - ankle - hip,
        -mb * g * math.sin(p2 - a) + hip,
    ])


def foot(bp: FrictionBiped, q: ArrayLike, leg: int) -> Vector:
    """Slope-frame position (x, y) of foot ``leg`` (0 or 1), y its height above the slope."""
    x_h, y_h = float(np.asarray(q)[0]), float(np.asarray(q)[1])
    phi = float(np.asarray(q)[2 + leg])
    return np.array([x_h + bp.l * math.sin(phi), y_h - bp.l * math.cos(phi)])


def foot_jacobian(bp: FrictionBiped, q: ArrayLike, leg: int) -> Matrix:
    """d(foot)/dq, rows (tangential, normal), (2, 4)."""
    phi = float(np.asarray(q)[2 + leg])
    jac = np.zeros((2, 4))
    jac[0, 0] = jac[1, 1] = 1.0
    jac[0, 2 + leg] = bp.l * math.cos(phi)
    jac[1, 2 + leg] = bp.l * math.sin(phi)
    return jac


def energy(bp: FrictionBiped, q: ArrayLike, v: ArrayLike) -> float:
    """Kinetic plus potential energy (J), potential 0 at the slope-frame origin."""
    vv = np.asarray(v, dtype=float)
    x_h, y_h, p1, p2 = (float(c) for c in np.asarray(q))
    ca, sa = math.cos(bp.slope), math.sin(bp.slope)

    def height(x: float, y: float) -> float:
        return y * ca - x * sa

    b = bp.b
    pot = bp.m_h * height(x_h, y_h) + sum(bp.m * height(x_h + b * math.sin(p), y_h - b * math.cos(p)) for p in (p1, p2))
    return 0.5 * float(vv @ mass_matrix(bp, q) @ vv) + bp.g * pot


# --- complementarity ------------------------------------------------------------------------------------------


def coulomb_contacts(delassus: Matrix, v0: Vector, mu: float, floor: Vector) -> tuple[Vector, tuple[str, ...]]:
    """Impulses P (2k,) = (P_t, P_n) per contact solving, with v+ = v0 + W P (contact velocities, rows (t, n) per
    contact; W the Delassus matrix J M^-1 J^T): 0 <= P_n _|_ v_n+ - floor >= 0, |P_t| <= mu P_n, v_t+ = 0 while
    |P_t| < mu P_n, P_t = -mu P_n sgn(v_t+) while sliding. Every combination of the cases :data:`CASES` is tried
    and the solutions are compared; ValueError if none or two different ones exist (no consistent contact state:
    Painleve's paradox, not expected here)."""
    k = v0.size // 2
    if k == 1:
        return _one_contact(delassus, v0, mu, float(floor[0]))
    eye = np.eye(2 * k)
    found: list[tuple[Vector, tuple[str, ...]]] = []
    cases_allowed = CASES if math.isfinite(mu) else CASES[:2]
    for cases in itertools.product(cases_allowed, repeat=k):
        rows: list[Vector] = []
        rhs: list[float] = []
        for i, case in enumerate(cases):
            t, n = 2 * i, 2 * i + 1
            if case == "free":
                rows += [eye[t], eye[n]]
                rhs += [0.0, 0.0]
            elif case == "stick":
                rows += [delassus[t], delassus[n]]
                rhs += [-v0[t], floor[i] - v0[n]]
            else:
                rows += [eye[t] + (mu if case == "slip+" else -mu) * eye[n], delassus[n]]
                rhs += [0.0, floor[i] - v0[n]]
        try:
            p = np.linalg.solve(np.array(rows), np.array(rhs))
        except np.linalg.LinAlgError:
            continue
        v = v0 + delassus @ p
        tol_v = LCP_TOL * (1.0 + float(np.max(np.abs(v0))))
        tol_p = LCP_TOL * (1.0 + float(np.max(np.abs(p))))
        ok = True
        for i, case in enumerate(cases):
            pt, pn, vt, vn = p[2 * i], p[2 * i + 1], v[2 * i], v[2 * i + 1]
            if case == "free":
                ok = ok and vn >= floor[i] - tol_v
            elif case == "stick":
                ok = ok and pn >= -tol_p and (math.isinf(mu) or abs(pt) <= mu * pn + tol_p)
            else:
                ok = ok and pn >= -tol_p and (1.0 if case == "slip+" else -1.0) * vt >= -tol_v
        if ok:
            found.append((p, cases))
    if not found:
        raise ValueError("no consistent contact state (Signorini-Coulomb problem without solution)")
    p, cases = found[0]
    for other, _ in found[1:]:
        if not np.allclose(other, p, rtol=1e-8, atol=1e-12):
            raise ValueError("two contact states solve the Signorini-Coulomb problem (non-unique)")
    return p, cases


def _one_contact(delassus: Matrix, v0: Vector, mu: float, floor: float) -> tuple[Vector, tuple[str, ...]]:
    """:func:`coulomb_contacts` for one contact, the cases in closed form (the stance steps' fast path)."""
    (wtt, wtn), (wnt, wnn) = (float(x) for x in delassus[0]), (float(x) for x in delassus[1])
    vt0, vn0 = float(v0[0]), float(v0[1])
    tol_v = LCP_TOL * (1.0 + max(abs(vt0), abs(vn0)))
    found: list[tuple[float, float, str]] = []
    if vn0 >= floor - tol_v:
        found.append((0.0, 0.0, "free"))
    det = wtt * wnn - wtn * wnt
    pt = (-vt0 * wnn - wtn * (floor - vn0)) / det
    pn = (wtt * (floor - vn0) + wnt * vt0) / det
    tol_p = LCP_TOL * (1.0 + max(abs(pt), abs(pn)))
    if pn >= -tol_p and (math.isinf(mu) or abs(pt) <= mu * pn + tol_p):
        found.append((pt, pn, "stick"))
    if math.isfinite(mu):
        for case, s in (("slip+", 1.0), ("slip-", -1.0)):
            pn = (floor - vn0) / (wnn - s * mu * wnt)
            vt = vt0 + (wtn - s * mu * wtt) * pn
            if pn >= -LCP_TOL * (1.0 + abs(pn)) and s * vt >= -tol_v:
                found.append((-s * mu * pn, pn, case))
    if not found:
        raise ValueError("no consistent contact state (Signorini-Coulomb problem without solution)")
    pt, pn, case = found[0]
    for other_t, other_n, _ in found[1:]:
        if not (math.isclose(other_t, pt, rel_tol=1e-8, abs_tol=1e-12)
                and math.isclose(other_n, pn, rel_tol=1e-8, abs_tol=1e-12)):
            raise ValueError("two contact states solve the Signorini-Coulomb problem (non-unique)")
    return np.array([pt, pn]), (case,)


def case_margin(delassus: Matrix, v0: Vector, mu: float, floor: float, case: str) -> float:
    """How far one contact forced into ``case`` is from leaving it (>= 0 inside; the zero is the switch): v_n+ -
    floor when free, min(P_n, mu P_n - |P_t|) when sticking, the sliding speed s v_t+ when slipping."""
    (wtt, wtn), (wnt, wnn) = (float(x) for x in delassus[0]), (float(x) for x in delassus[1])
    vt0, vn0 = float(v0[0]), float(v0[1])
    if case == "free":
        return vn0 - floor
    if case == "stick":
        det = wtt * wnn - wtn * wnt
        pt = (-vt0 * wnn - wtn * (floor - vn0)) / det
        pn = (wtt * (floor - vn0) + wnt * vt0) / det
        return min(pn, mu * pn - abs(pt))
    s = 1.0 if case == "slip+" else -1.0
    pn = (floor - vn0) / (wnn - s * mu * wnt)
    return s * (vt0 + (wtn - s * mu * wtt) * pn)


# --- the stride -------------------------------------------------------------------------------------------------


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
    """One stride of the time-stepping scheme (module docstring) from the post-impact section state z of 002 Sec.
    4.2 to the next one, with step ``h`` (s). ValueError if the stance foot lifts off, the biped falls or stalls
    (no heel strike within :data:`T_MAX`)."""
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
