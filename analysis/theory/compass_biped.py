"""Passive compass-gait biped on a slope: swing dynamics, heel-strike impact and the period-1 gait.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4,
eqs (4.2)-(4.20) and Fig. 18; the same model as Goswami, Thuilot & Espiau (1996/1998), "A study of the
passive gait of a compass-like biped robot" (benchmark parameters m_h/m = 2, a = b, l = 1, slope 3 deg).

Conventions (SI units, 003's): q = (theta_st, theta_sw), each the foot->hip direction of a leg measured from the
TRUE vertical, clockwise positive; +x is downhill and the slope falls from left to right. Point masses m_l on each
leg at distance a from the foot (b from the hip), m_h at the hip, l = a + b. Positions with the origin at the
stance foot and u(theta) = (sin theta, cos theta): stance-leg mass a u(theta_st), hip l u(theta_st), swing-leg
mass l u(theta_st) - b u(theta_sw), swing foot l u(theta_st) - l u(theta_sw). The hip torque tau is positive
counter-clockwise on the swing leg with work tau (theta_sw - theta_st), so B = (-1, 1). A state is
x = (theta_st, theta_sw, dtheta_st, dtheta_sw).

Actuation (for the actuated biped; 0 = the passive walker of 003): constant torques, ``tau_hip`` between the legs
as in 003 eq 4.5 (generalised forces (-tau_hip, +tau_hip)) and ``tau_ankle``, the ground's torque on the stance leg,
clockwise positive (generalised force (+tau_ankle, 0): it pushes the hip downhill). Both act in the EoM only; the
impact law is unchanged (finite torques give no impulse).

Heel strike (003 eq 4.6): theta_st + theta_sw = 2 gamma with theta_st > theta_sw (swing foot in front); the
mid-stance crossing theta_st = theta_sw, where the swing foot scuffs, is ignored (003 Sec. 4.1: the swing leg
"retracts" without moving its mass). At impact the legs are relabelled (003 eq 4.7) and
Q+ qd+ = Q- qd- (003 eqs 4.15-4.17) with alpha = (theta_st- - theta_sw-)/2, the half inter-leg angle.

Re-derived here: the EoM (4.5) from the Lagrangian, and Q+/Q- (4.15)/(4.16) from the two conserved angular
momenta (whole biped about the new contact point, trailing leg about the hip); both agree with the thesis.
The thesis finds its gait by grid search plus forward simulation (Sec. 4.4.2) with first-order event location,
so its Fig. 18 state is ~3e-4 off the true fixed point; here the fixed point is found by Newton shooting.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import OptimizeResult, brentq, fsolve, minimize_scalar

RTOL = 1e-12
ATOL = 1e-12
#: Longest swing integrated before a step is declared a fall (no heel strike), in units of sqrt(l/g).
MAX_SWING = 10.0
#: Slope of the built-in fixed point, from which :func:`fixed_point` continues in the slope (003 Fig. 18).
_REF_SLOPE = 0.04
#: Post-impact section state (theta_st+, dtheta_st+ sqrt(l/g), dtheta_sw+ sqrt(l/g)) of the Kisa gait at 0.04.
_REF_Z = (-0.2073985186, 1.0406442919 / math.sqrt(9.81), 0.4810330477 / math.sqrt(9.81))
#: Largest slope increment of one continuation stage in :func:`fixed_point`.
_CONT_STEP = 0.005
_TORQUE_STEP = 0.05  # N m per continuation stage in the constant torques
_FORCE_SAMPLES = 401


@dataclass(frozen=True)
class CompassBiped:
    """Compass-gait biped parameters (003 Sec. 4.1, Fig. 15; defaults = 003 Fig. 18).

    ``m_h`` hip mass > 0 (kg), ``m_l`` leg point mass > 0 (kg), ``a`` foot-to-leg-mass and ``b`` leg-mass-to-hip
    distances > 0 (m), ``slope`` gamma in (0, pi/2) rad, ``gravity`` g > 0 (m/s^2), constant ``tau_ankle`` and
    ``tau_hip`` (N m; module docstring for their senses).
    """

    m_h: float = 10.0
    m_l: float = 5.0
    a: float = 0.5
    b: float = 0.5
    slope: float = 0.04
    gravity: float = 9.81
    tau_ankle: float = 0.0
    tau_hip: float = 0.0

    @property
    def l(self) -> float:  # noqa: E743 (the papers' leg length)
        """Leg length l = a + b (003 Sec. 4.1)."""
        return self.a + self.b

    @property
    def total_mass(self) -> float:
        """m_h + 2 m_l (kg)."""
        return self.m_h + 2.0 * self.m_l


@dataclass(frozen=True)
class StepResult:
    """One step of the passive biped from a state just after an impact (see :func:`step`).

    ``x_plus_next`` post-impact state after the next heel strike (003 eq 4.18), ``x_minus`` the state just before
    it, ``period`` the swing duration (s). Over the swing, with the stance-foot force f = sum m_i a_i - m g
    from Newton's law for the whole biped, split into its slope-normal part N and tangential part F:
    ``min_normal_force_ratio`` = min N/((m_h + 2 m_l) g) and ``required_friction`` = max |F|/N.
    ``liftoff_velocity`` is the slope-normal velocity (m/s) of the trailing (old stance) foot just after the heel
    strike; > 0 means it leaves the ground, as the impact model assumes.
    """

    x_plus_next: NDArray[np.float64]
    x_minus: NDArray[np.float64]
    period: float
    min_normal_force_ratio: float
    required_friction: float
    liftoff_velocity: float


def validate(bp: CompassBiped) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range (003 Sec. 4.1; slope range of 003 eq 4.2,
    endpoint 0 excluded because no passive gait exists there)."""
    for name, unit in (("m_h", "kg"), ("m_l", "kg"), ("a", "m"), ("b", "m")):
        value = getattr(bp, name)
        if not value > 0.0:
            raise ValueError(f"{name} must be > 0 {unit} (got {value!r})")
    if not 0.0 < bp.slope < math.pi / 2:
        raise ValueError(f"slope must be in (0, pi/2) rad (got {bp.slope!r})")
    if not bp.gravity > 0.0:
        raise ValueError(f"gravity must be > 0 m/s^2 (got {bp.gravity!r})")


def mass_matrix(bp: CompassBiped, q: ArrayLike) -> NDArray[np.float64]:
    """Inertia matrix M(q) of 003 eq 4.5:
    [[m_l a^2 + (m_h + m_l) l^2, -m_l b l cos(theta_st - theta_sw)], [., m_l b^2]]."""
    th_st, th_sw = np.asarray(q, dtype=float)
    off = -bp.m_l * bp.b * bp.l * math.cos(th_st - th_sw)
    return np.array([[bp.m_l * bp.a**2 + (bp.m_h + bp.m_l) * bp.l**2, off], [off, bp.m_l * bp.b**2]])


def coriolis(bp: CompassBiped, q: ArrayLike, qd: ArrayLike) -> NDArray[np.float64]:
    """Coriolis/centrifugal matrix C(q, qd) of 003 eq 4.5:
    [[0, -m_l b l sin(Delta) dtheta_sw], [m_l b l sin(Delta) dtheta_st, 0]], Delta = theta_st - theta_sw."""
    th_st, th_sw = np.asarray(q, dtype=float)
    om_st, om_sw = np.asarray(qd, dtype=float)
    k = bp.m_l * bp.b * bp.l * math.sin(th_st - th_sw)
    return np.array([[0.0, -k * om_sw], [k * om_st, 0.0]])


def gravity_vector(bp: CompassBiped, q: ArrayLike) -> NDArray[np.float64]:
    """Gravity term G(q) of 003 eq 4.5 (on the right-hand side, G = -dU/dq):
    (g sin(theta_st) (m_l a + m_h l + m_l l), -g m_l b sin(theta_sw))."""
    th_st, th_sw = np.asarray(q, dtype=float)
    g = bp.gravity
    return np.array(
        [g * math.sin(th_st) * (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l), -g * bp.m_l * bp.b * math.sin(th_sw)]
    )


def _qdd(bp: CompassBiped, th_st: float, th_sw: float, om_st: float, om_sw: float, tau: float) -> tuple[float, float]:
    """Scalar solve of M qdd = G + B (tau_hip + tau) + (tau_ankle, 0) - C qd (003 eq 4.5) by the closed-form 2x2
    inverse (``tau`` is an extra hip torque on top of the model's constant ones)."""
    s, c = math.sin(th_st - th_sw), math.cos(th_st - th_sw)
    mbl = bp.m_l * bp.b * bp.l
    m11 = bp.m_l * bp.a**2 + (bp.m_h + bp.m_l) * bp.l**2
    m12 = -mbl * c
    m22 = bp.m_l * bp.b**2
    g = bp.gravity
    hip = bp.tau_hip + tau
    r1 = g * math.sin(th_st) * (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l) - hip + bp.tau_ankle + mbl * s * om_sw**2
    r2 = -g * bp.m_l * bp.b * math.sin(th_sw) + hip - mbl * s * om_st**2
    det = m11 * m22 - m12 * m12
    return (m22 * r1 - m12 * r2) / det, (m11 * r2 - m12 * r1) / det


def swing_dynamics(bp: CompassBiped, q: ArrayLike, qd: ArrayLike, tau_hip: float = 0.0) -> NDArray[np.float64]:
    """Accelerations qdd = M^-1 (G + B tau - C qd) of 003 eq 4.5 with B = (-1, 1) (tau > 0 counter-clockwise
    on the swing leg), tau = the model's tau_hip + ``tau_hip``, plus the model's ankle torque; passive swing 003
    eq 4.19 when all torques are 0."""
    th_st, th_sw = np.asarray(q, dtype=float)
    om_st, om_sw = np.asarray(qd, dtype=float)
    return np.array(_qdd(bp, th_st, th_sw, om_st, om_sw, tau_hip))


def energy(bp: CompassBiped, q: ArrayLike, qd: ArrayLike) -> float:
    """Total energy T + U (J), T = qd^T M qd / 2 and U = g[(m_l a + (m_h + m_l) l) cos theta_st
    - m_l b cos theta_sw] with the height measured from the stance foot along the TRUE vertical (003 Sec. 4.1)."""
    th_st, th_sw = np.asarray(q, dtype=float)
    qd_arr = np.asarray(qd, dtype=float)
    kinetic = 0.5 * float(qd_arr @ mass_matrix(bp, (th_st, th_sw)) @ qd_arr)
    potential = bp.gravity * (
        (bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l) * math.cos(th_st) - bp.m_l * bp.b * math.cos(th_sw)
    )
    return kinetic + potential


def swing_foot_height(bp: CompassBiped, q: ArrayLike) -> float:
    """Swing-foot height above the slope along its normal (003 eqs 4.1-4.3):
    h = l [cos(theta_st - gamma) - cos(theta_sw - gamma)]
      = -2 l sin((theta_st + theta_sw - 2 gamma)/2) sin((theta_st - theta_sw)/2)."""
    th_st, th_sw = np.asarray(q, dtype=float)
    return bp.l * (math.cos(th_st - bp.slope) - math.cos(th_sw - bp.slope))


def impact_matrices(bp: CompassBiped, half_angle: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Q+, Q-) of 003 eqs 4.15/4.16 for the half inter-leg angle alpha = (theta_st- - theta_sw-)/2.

    Row 1: angular momentum of the whole biped about the new contact point; row 2: of the trailing leg about the
    hip (003 eqs 4.9-4.14). Re-derived: identical to the thesis.
    """
    c2 = math.cos(2.0 * half_angle)
    m_h, m_l, a, b, l = bp.m_h, bp.m_l, bp.a, bp.b, bp.l
    q_plus = np.array(
        [
            [m_l * (b * l * c2 - l**2 - a**2) - m_h * l**2, m_l * (b * l * c2 - b**2)],
            [m_l * b * l * c2, -m_l * b**2],
        ]
    )
    q_minus = np.array([[m_l * (a * b - 2.0 * a * l * c2) - m_h * l**2 * c2, m_l * a * b], [m_l * a * b, 0.0]])
    return q_plus, q_minus


def impact_map(bp: CompassBiped, x_minus: ArrayLike) -> NDArray[np.float64]:
    """Heel-strike map x- -> x+ (003 eq 4.18): q+ = R q- with R = [[0, 1], [1, 0]] (003 eqs 4.7/4.8) and
    qd+ = Q+^-1 Q- qd- (003 eq 4.17)."""
    x = np.asarray(x_minus, dtype=float)
    q_plus, q_minus = impact_matrices(bp, 0.5 * (x[0] - x[1]))
    return np.concatenate([x[1::-1], np.linalg.solve(q_plus, q_minus @ x[2:])])


def _rhs(bp: CompassBiped) -> Callable[[float, NDArray[np.float64]], list[float]]:
    def rhs(_t: float, y: NDArray[np.float64]) -> list[float]:
        return [y[2], y[3], *_qdd(bp, y[0], y[1], y[2], y[3], 0.0)]

    return rhs


def _heel_strike(bp: CompassBiped) -> Callable[[float, NDArray[np.float64]], float]:
    """Continuous guard max(2 gamma - theta_st - theta_sw, theta_sw - theta_st) (003 eq 4.6): > 0 after an impact
    and at the mid-stance scuffing crossing, crossing 0 downwards only at a heel strike with theta_st > theta_sw."""

    def event(_t: float, y: NDArray[np.float64]) -> float:
        return max(2.0 * bp.slope - y[0] - y[1], y[1] - y[0])

    event.terminal = True  # type: ignore[attr-defined]
    event.direction = -1.0  # type: ignore[attr-defined]
    return event


def _foot_force(bp: CompassBiped, y: NDArray[np.float64]) -> tuple[float, float]:
    """Stance-foot force from Newton's law on the whole biped, f = sum m_i a_i + (m_h + 2 m_l) g e_z, split into
    (tangential downhill, normal) components; accelerations from the passive EoM (003 eq 4.19)."""
    th_st, th_sw, om_st, om_sw = y
    al_st, al_sw = _qdd(bp, th_st, th_sw, om_st, om_sw, 0.0)
    # acceleration of r u(theta): r (alpha u'(theta) - omega^2 u(theta)), u = (sin, cos), u' = (cos, -sin)
    acc_st = np.array(
        [al_st * math.cos(th_st) - om_st**2 * math.sin(th_st), -al_st * math.sin(th_st) - om_st**2 * math.cos(th_st)]
    )
    acc_sw = np.array(
        [al_sw * math.cos(th_sw) - om_sw**2 * math.sin(th_sw), -al_sw * math.sin(th_sw) - om_sw**2 * math.cos(th_sw)]
    )
    weight_lever = bp.m_l * bp.a + (bp.m_h + bp.m_l) * bp.l
    force = weight_lever * acc_st - bp.m_l * bp.b * acc_sw + np.array([0.0, bp.total_mass * bp.gravity])
    sg, cg = math.sin(bp.slope), math.cos(bp.slope)
    return float(force[0] * cg - force[1] * sg), float(force[0] * sg + force[1] * cg)


def _minimum(fun: Callable[[float], float], t1: float) -> float:
    """min of fun over [0, t1]: dense sampling, then bounded refinement around the best sample."""
    t = np.linspace(0.0, t1, _FORCE_SAMPLES)
    v = np.array([fun(s) for s in t])
    i = int(np.argmin(v))
    if 0 < i < _FORCE_SAMPLES - 1:
        res = minimize_scalar(fun, bounds=(t[i - 1], t[i + 1]), method="bounded", options={"xatol": 1e-10})
        return float(min(res.fun, v[i]))
    return float(v[i])


def _liftoff_velocity(bp: CompassBiped, x_plus: NDArray[np.float64]) -> float:
    """Slope-normal velocity of the new swing foot l u(theta_st) - l u(theta_sw), origin at the stance foot."""
    th_st, th_sw, om_st, om_sw = x_plus
    vx = bp.l * (om_st * math.cos(th_st) - om_sw * math.cos(th_sw))
    vz = bp.l * (-om_st * math.sin(th_st) + om_sw * math.sin(th_sw))
    return vx * math.sin(bp.slope) + vz * math.cos(bp.slope)


def _swing(bp: CompassBiped, x0: ArrayLike, rtol: float, atol: float, dense: bool = False) -> OptimizeResult:
    """Integrate the passive swing (003 eq 4.19) from x0 to the heel strike (003 eq 4.6); RuntimeError on a fall."""
    sol = _integrate_swing(bp, x0, (_heel_strike(bp),), rtol, atol, dense=dense)
    if sol.status != 1:
        raise RuntimeError(f"no heel strike within {sol.t[-1]:.3g} s from x = {np.asarray(x0)!r} (the biped falls)")
    return sol


def _integrate_swing(bp: CompassBiped, x0: ArrayLike, events: tuple[Callable[..., float], ...], rtol: float,
                     atol: float, *, dense: bool = False, backward: bool = False) -> OptimizeResult:
    """The passive swing (003 eq 4.19) from x0 with DOP853 until the first terminal event, for at most
    MAX_SWING sqrt(l/g) seconds (backward in time if ``backward``)."""
    validate(bp)
    t_max = MAX_SWING * math.sqrt(bp.l / bp.gravity)
    return solve_ivp(_rhs(bp), (0.0, -t_max if backward else t_max), np.asarray(x0, dtype=float), method="DOP853",
                     rtol=rtol, atol=atol, events=events, dense_output=dense)


def step(bp: CompassBiped, x_plus: ArrayLike, *, rtol: float = RTOL, atol: float = ATOL) -> StepResult:
    """One passive step (003 eq 4.18): swing (003 eq 4.19, DOP853, event 003 eq 4.6 located to solver accuracy)
    from x_plus to the heel strike, then the impact map (003 eqs 4.7, 4.17). Also reports the contact-validity
    quantities of :class:`StepResult` (not in 003, which assumes a bilateral, non-slipping stance foot)."""
    sol = _swing(bp, x_plus, rtol, atol, dense=True)
    period = float(sol.t_events[0][0])
    x_minus = np.asarray(sol.y_events[0][0], dtype=float)
    x_next = impact_map(bp, x_minus)

    def normal(t: float) -> float:
        return _foot_force(bp, sol.sol(t))[1]

    def neg_friction(t: float) -> float:
        tangential, norm = _foot_force(bp, sol.sol(t))
        return -abs(tangential / norm)

    return StepResult(
        x_plus_next=x_next,
        x_minus=x_minus,
        period=period,
        min_normal_force_ratio=_minimum(normal, period) / (bp.total_mass * bp.gravity),
        required_friction=-_minimum(neg_friction, period),
        liftoff_velocity=float(_liftoff_velocity(bp, x_next)),
    )


def _section_state(bp: CompassBiped, z: ArrayLike) -> NDArray[np.float64]:
    th_st, om_st, om_sw = np.asarray(z, dtype=float)
    return np.array([th_st, 2.0 * bp.slope - th_st, om_st, om_sw])


def return_map(bp: CompassBiped, z: ArrayLike) -> NDArray[np.float64]:
    """Poincaré map (003 eq 4.18) restricted to the post-impact section z = (theta_st+, dtheta_st+, dtheta_sw+),
    theta_sw+ = 2 gamma - theta_st+ (003 eq 4.6 after relabelling, 003 eq 4.7)."""
    sol = _swing(bp, _section_state(bp, z), RTOL, ATOL)
    x_next = impact_map(bp, sol.y_events[0][0])
    return x_next[[0, 2, 3]]


def _solve_fixed(bp: CompassBiped, guess: NDArray[np.float64]) -> NDArray[np.float64]:
    """Newton-type shooting (MINPACK hybrd) on P(z) - z = 0; ValueError if it does not converge."""

    def gap(z: NDArray[np.float64]) -> NDArray[np.float64]:
        try:
            return return_map(bp, z) - z
        except RuntimeError:
            return np.full(3, 1e3)

    z, _, _, msg = fsolve(gap, guess, full_output=True, xtol=1e-13)
    # judged by the residual: from a guess already at the root (continuation) hybrd stalls at the integration noise
    # floor (~1e-12) and reports "not making good progress" although the gait is found
    if np.max(np.abs(gap(z))) > 1e-9:
        raise ValueError(f"fixed-point shooting failed at slope {bp.slope!r}: {msg}")
    return z


def _continue(bp: CompassBiped, z0: NDArray[np.float64], slope0: float) -> NDArray[np.float64]:
    """Natural-parameter continuation in the slope from a fixed point z0 at slope0 to bp.slope, stages of at most
    ``_CONT_STEP`` rad, each Newton guess linearly extrapolated from the previous two fixed points."""
    stages = max(1, math.ceil(abs(bp.slope - slope0) / _CONT_STEP))
    zs = [np.asarray(z0, dtype=float)]
    for slope in np.linspace(slope0, bp.slope, stages + 1)[1:]:
        guess = zs[-1] if len(zs) == 1 else 2.0 * zs[-1] - zs[-2]
        zs.append(_solve_fixed(replace(bp, slope=float(slope)), guess))
    return zs[-1]


def _continue_torques(bp: CompassBiped, z0: NDArray[np.float64]) -> NDArray[np.float64]:
    """Continuation from the passive fixed point z0 of bp's geometry to bp's constant torques, stages of at most
    ``_TORQUE_STEP`` N m, guesses extrapolated as in :func:`_continue`."""
    stages = math.ceil(max(abs(bp.tau_ankle), abs(bp.tau_hip)) / _TORQUE_STEP)
    zs = [np.asarray(z0, dtype=float)]
    for frac in np.linspace(0.0, 1.0, stages + 1)[1:]:
        guess = zs[-1] if len(zs) == 1 else 2.0 * zs[-1] - zs[-2]
        zs.append(_solve_fixed(replace(bp, tau_ankle=frac * bp.tau_ankle, tau_hip=frac * bp.tau_hip), guess))
    return zs[-1]


@lru_cache(maxsize=256)
def _fixed_point_cached(bp: CompassBiped, guess: tuple[float, float, float] | None) -> tuple[float, ...]:
    if guess is not None:
        return tuple(_solve_fixed(bp, np.array(guess)))
    rate = math.sqrt(bp.gravity / bp.l)
    ref_guess = np.array([_REF_Z[0], _REF_Z[1] * rate, _REF_Z[2] * rate])
    passive = replace(bp, tau_ankle=0.0, tau_hip=0.0)
    ref = _solve_fixed(replace(passive, slope=_REF_SLOPE), ref_guess)
    return tuple(_continue_torques(bp, _continue(passive, ref, _REF_SLOPE)))


def fixed_point(bp: CompassBiped, guess: ArrayLike | None = None) -> NDArray[np.float64]:
    """Period-1 gait x* = (theta_st+, theta_sw+, dtheta_st+, dtheta_sw+) just after the impact: a fixed point
    of the Poincaré map 003 eq 4.18 (passive, 003 eq 4.19, unless bp has constant torques), found by Newton
    shooting on the 3-D post-impact section (:func:`return_map`), not by 003's grid search (Sec. 4.4.2).

    ``guess``: a 3-vector z on the section or a 4-vector x. Default: the 003 Fig. 18 gait (slope 0.04, rates scaled
    by sqrt(g/l)), solved for bp's masses and lengths, continued in the slope to bp.slope, then in the torques from 0
    to bp's (:func:`_continue_torques`); this reaches the
    stable (long-step) gait for m_h/m_l = 2, a = b (003 and Goswami et al. 1996/98) over slopes 0.005..0.0766.
    ValueError if the shooting does not converge.
    """
    validate(bp)
    if guess is not None:
        g = np.asarray(guess, dtype=float)
        g = g[[0, 2, 3]] if g.size == 4 else g
        z = _fixed_point_cached(bp, (float(g[0]), float(g[1]), float(g[2])))
    else:
        z = _fixed_point_cached(bp, None)
    return _section_state(bp, z)


def _jacobian(bp: CompassBiped, z: NDArray[np.float64], eps: float) -> NDArray[np.float64]:
    """dP/dz of :func:`return_map` by central differences with step eps."""
    return central_jacobian(lambda zz: return_map(bp, zz), z, eps)


def eigenvalues(bp: CompassBiped, x_star: ArrayLike | None = None, eps: float = 1e-6) -> NDArray[np.complex128]:
    """The 3 eigenvalues (Floquet multipliers) of the post-impact section map at the gait x* (default
    :func:`fixed_point`), by central finite differences with step eps; sorted by modulus, descending (conjugate
    pairs: positive imaginary part first). Stability of the gait of 003 eq 4.18 (003 gives no multipliers;
    Goswami et al. 1996/98 do)."""
    x = fixed_point(bp) if x_star is None else np.asarray(x_star, dtype=float)
    return sort_eigenvalues(np.linalg.eigvals(_jacobian(bp, x[[0, 2, 3]], eps)).astype(complex))


def step_period(bp: CompassBiped, x_star: ArrayLike) -> float:
    """Swing duration (s) from the post-impact state x* to the next heel strike (003 eqs 4.6, 4.19)."""
    return float(_swing(bp, x_star, RTOL, ATOL).t_events[0][0])


def step_length(bp: CompassBiped, x_star: ArrayLike) -> float:
    """Distance between the feet at heel strike, 2 l sin(alpha*) with alpha* = (theta_sw+ - theta_st+)/2 the half
    inter-leg angle of 003 eqs 4.15-4.17 (after relabelling, 003 eq 4.7)."""
    x = np.asarray(x_star, dtype=float)
    return 2.0 * bp.l * math.sin(0.5 * (x[1] - x[0]))


def period_doubling_slope(m_h: float, m_l: float, a: float, b: float, lo: float, hi: float) -> float:
    """Slope (rad) in (lo, hi) at which a multiplier of the passive gait crosses -1 (first period doubling of the
    Goswami et al. 1998 bifurcation cascade; g = 9.81).

    The gait is continued in the slope (see :func:`fixed_point`) and the root of det(J + I) = prod(lambda_i + 1)
    (J = the post-impact section Jacobian; a complex pair contributes |lambda + 1|^2 > 0) is bracketed on a grid
    of spacing <= 0.005 rad and refined by Brent's method. ValueError if det(J + I) keeps its sign on [lo, hi].
    """
    base = CompassBiped(m_h, m_l, a, b, lo)
    validate(base)
    known: dict[float, NDArray[np.float64]] = {}

    def flip(slope: float) -> float:
        bp = replace(base, slope=slope)
        nearest = min(known, key=lambda s: abs(s - slope)) if known else None
        z = np.asarray(_fixed_point_cached(bp, None)) if nearest is None else _continue(bp, known[nearest], nearest)
        known[slope] = z
        return float(np.linalg.det(_jacobian(bp, z, 1e-6) + np.eye(3)))

    grid = np.linspace(lo, hi, max(2, math.ceil((hi - lo) / _CONT_STEP) + 1))
    values = [flip(float(s)) for s in grid]
    for k in range(len(grid) - 1):
        if values[k] * values[k + 1] < 0.0:
            return float(brentq(flip, grid[k], grid[k + 1], xtol=1e-9))
    raise ValueError(f"no multiplier crosses -1 for slopes in [{lo!r}, {hi!r}]")


def _legs_parallel(_t: float, y: NDArray[np.float64]) -> float:
    return y[1] - y[0]


_legs_parallel.terminal = True  # type: ignore[attr-defined]
_legs_parallel.direction = -1.0  # type: ignore[attr-defined]


def legs_parallel_state(bp: CompassBiped, x_plus: ArrayLike) -> tuple[NDArray[np.float64], float]:
    """Mid-swing section theta_st = theta_sw (003 eq 4.20, the thesis' own search section): integrate the passive
    swing (003 eq 4.19) from a post-impact state to the legs-parallel crossing. Returns
    (y, t) with y = (theta, dtheta_st, dtheta_sw) and t the time after the impact; RuntimeError if a heel strike
    or a fall comes first."""
    sol = _integrate_swing(bp, x_plus, (_legs_parallel, _heel_strike(bp)), RTOL, ATOL)
    if sol.t_events[0].size == 0:
        raise RuntimeError(f"the legs do not pass parallel from x = {np.asarray(x_plus)!r}")
    y = sol.y_events[0][0]
    return np.array([0.5 * (y[0] + y[1]), y[2], y[3]]), float(sol.t_events[0][0])


def parallel_return_map(bp: CompassBiped, y: ArrayLike) -> NDArray[np.float64]:
    """Poincaré map on the legs-parallel section y = (theta, dtheta_st, dtheta_sw), theta_st = theta_sw = theta
    (003 eq 4.20): swing to the heel strike, impact (003 eq 4.18), swing to the next legs-parallel crossing.
    Conjugate to :func:`return_map`, so it has the same multipliers. Needs theta < gamma (swing foot below the
    slope, as at the mid-stance scuffing crossing)."""
    th, om_st, om_sw = np.asarray(y, dtype=float)
    x_plus = impact_map(bp, _swing(bp, (th, th, om_st, om_sw), RTOL, ATOL).y_events[0][0])
    return legs_parallel_state(bp, x_plus)[0]


def goswami(slope: float = 0.0523599, g: float = 9.81) -> CompassBiped:
    """Goswami, Thuilot & Espiau (1996/98) benchmark: m_h/m_l = 2, b/a = 1, l = 1, slope 3 deg by default
    (m_l = 5, m_h = 10; the gait and its multipliers do not depend on the mass scale)."""
    return CompassBiped(m_h=10.0, m_l=5.0, a=0.5, b=0.5, slope=slope, gravity=g)


def kisa() -> CompassBiped:
    """The 003 Fig. 18 parameters: m_h = 10, m_l = 5, a = b = 0.5, g = 9.81, gamma = 0.04."""
    return CompassBiped()


def post_impact_from_parallel(bp: CompassBiped, y: ArrayLike) -> NDArray[np.float64]:
    """Pull a legs-parallel section state y = (theta, dtheta_st, dtheta_sw) (003 eq 4.20) back along the passive
    swing (003 eq 4.19, integrated backward in time) to the post-impact section theta_st + theta_sw = 2 gamma
    (003 eq 4.6). The inverse of :func:`legs_parallel_state`: it maps a simulator's mid-swing sample to the
    post-impact state it came from, under the exact swing dynamics."""
    th, om_st, om_sw = np.asarray(y, dtype=float)

    def after_impact(_t: float, x: NDArray[np.float64]) -> float:
        return x[0] + x[1] - 2.0 * bp.slope

    after_impact.terminal = True  # type: ignore[attr-defined]
    # backward in time the sum first rises through 2 gamma where the swing foot scuffs (h = 0 mid-swing), then
    # falls to 2 gamma at the heel strike that began the swing: only the falling crossing counts
    after_impact.direction = -1.0  # type: ignore[attr-defined]
    sol = _integrate_swing(bp, [th, th, om_st, om_sw], (after_impact,), RTOL, ATOL, backward=True)
    if sol.t_events[0].size == 0:
        raise RuntimeError(f"no post-impact state before the legs-parallel state {np.asarray(y)!r}")
    return np.asarray(sol.y_events[0][0], dtype=float)


def lowest_swing_height(bp: CompassBiped, x_plus: np.ndarray) -> float:
    """The exact model's lowest swing-foot height above the slope (m, along its normal; < 0: below it, the mid-swing
    scuffing that 003 Sec. 4.1 ignores) over the passive swing (003 eq 4.19) from the post-impact state ``x_plus``
    to the heel strike: 003 eqs 4.1-4.3 on 401 samples, the lowest refined by a bounded scalar search."""
    period = step_period(bp, x_plus)
    sol = solve_ivp(lambda _t, y: [y[2], y[3], *swing_dynamics(bp, y[:2], y[2:])], (0.0, period),
                    np.asarray(x_plus, dtype=float), method="DOP853", rtol=RTOL, atol=ATOL,
                    dense_output=True)

    def height(t: float) -> float:
        return swing_foot_height(bp, sol.sol(t)[:2])

    grid = np.linspace(0.0, period, 401)
    i = int(np.argmin([height(t) for t in grid]))
    found = minimize_scalar(height, bounds=(grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]), method="bounded",
                            options={"xatol": 1e-10})
    return float(min(found.fun, height(grid[i])))
