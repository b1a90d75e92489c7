"""One step of the compass-gait biped: swing to the heel strike, impact, and the post-impact Poincaré map.

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4: the swing of eq 4.19
integrated with DOP853 to the heel strike of eq 4.6 (located to solver accuracy), the impact map of eqs 4.7 and 4.17,
the map of eq 4.18 on the 3-D post-impact section, the step period and length, and the contact-validity quantities 003
does not give (it assumes a bilateral, non-slipping stance foot).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory.compass_biped.dynamics import _qdd, impact_map
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped, validate
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import OptimizeResult, minimize_scalar

RTOL = 1e-12
ATOL = 1e-12
#: Longest swing integrated before a step is declared a fall (no heel strike), in units of sqrt(l/g).
MAX_SWING = 10.0
_FORCE_SAMPLES = 401


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
    quantities of :class:`StepResult` (not in 003, which assumes a bilateral, non-slipping stance foot). Computed
    once per (model, state, tolerances) and process; the arrays are new at each call."""
    x = tuple(float(v) for v in np.asarray(x_plus, dtype=float))
    once = _step_cached(bp, x, float(rtol), float(atol))
    return replace(once, x_plus_next=once.x_plus_next.copy(), x_minus=once.x_minus.copy())


@lru_cache(maxsize=256)
def _step_cached(bp: CompassBiped, x_plus: tuple[float, ...], rtol: float, atol: float) -> StepResult:
    sol = _swing(bp, np.array(x_plus), rtol, atol, dense=True)
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


def step_period(bp: CompassBiped, x_star: ArrayLike) -> float:
    """Swing duration (s) from the post-impact state x* to the next heel strike (003 eqs 4.6, 4.19)."""
    return float(_swing(bp, x_star, RTOL, ATOL).t_events[0][0])


def step_length(bp: CompassBiped, x_star: ArrayLike) -> float:
    """Distance between the feet at heel strike, 2 l sin(alpha*) with alpha* = (theta_sw+ - theta_st+)/2 the half
    inter-leg angle of 003 eqs 4.15-4.17 (after relabelling, 003 eq 4.7)."""
    x = np.asarray(x_star, dtype=float)
    return 2.0 * bp.l * math.sin(0.5 * (x[1] - x[0]))
