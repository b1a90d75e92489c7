"""The sticking stance of the planar rimless wheel: speeds, ground forces, contact validity, period and friction.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3; 002 = Gamus & Or (2015),
"Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst., Sec. 3.1. The energy integral of 003
eqs 3.3-3.5 / 002 eq 13, the ground forces of 002 eq 19 along it, whether a step keeps f_n >= 0 (002 eqs 20-21, 26;
003 Sec. 3.1 unilateral contact), the largest slope without flight, the step period, the friction the rolling gait
needs (002 eqs 22-23) and the sticking-impulse ratio (002 eq 25).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel.map import (
    _rolling_formula,
    backward_threshold,
    forward_threshold,
    rolling_exists,
)
from mjpoincare.analysis.theory.rimless_wheel.params import RimlessWheel, _beta_positive, validate
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar

_SCAN_POINTS = 401


def normal_force_ratio(w: RimlessWheel, theta: ArrayLike, omega: ArrayLike) -> NDArray[np.float64] | float:
    """f_n/(m g): ground force on the stance foot normal to the slope, sticking stance at (theta, omega).

    002 eq 19 rewritten with the slope-frame angle psi = theta - gamma and theta_dot_nd^2 = omega^2/rate2:
    f_n/(mg) = cos(gamma) - sin(theta) sin(psi)/(1+kappa) - (l omega^2/g) cos(psi).
    For kappa = 0 this is (cos theta - l omega^2/g) cos(theta - gamma)
    (003 Sec. 3.1 pendulum force along the spoke).
    """
    th = np.asarray(theta, dtype=float)
    om = np.asarray(omega, dtype=float)
    psi = th - w.slope
    out = (
        math.cos(w.slope)
        - np.sin(th) * np.sin(psi) / (1.0 + w.kappa)
        - w.leg_length * om**2 / w.gravity * np.cos(psi)
    )
    return float(out) if np.ndim(out) == 0 else out


def tangential_force_ratio(
    w: RimlessWheel, theta: ArrayLike, omega: ArrayLike
) -> NDArray[np.float64] | float:
    """f_t/(m g): ground force on the stance foot along the slope, positive downhill,
    sticking stance at (theta, omega).

    002 eq 19 with psi = theta - gamma:
    f_t/(mg) = sin(theta) cos(psi)/(1+kappa) - (l omega^2/g) sin(psi) - sin(gamma).
    """
    th = np.asarray(theta, dtype=float)
    om = np.asarray(omega, dtype=float)
    psi = th - w.slope
    out = (
        np.sin(th) * np.cos(psi) / (1.0 + w.kappa)
        - w.leg_length * om**2 / w.gravity * np.sin(psi)
        - math.sin(w.slope)
    )
    return float(out) if np.ndim(out) == 0 else out


def phase_speed(w: RimlessWheel, omega_post: ArrayLike, theta: ArrayLike) -> NDArray[np.float64] | float:
    """|omega| at stance angle theta on a step that started at theta = gamma - alpha with speed omega_post.

    Energy integral omega^2 = omega_post^2 + 2 rate2 (cos(gamma - alpha) - cos theta)
    (003 eqs 3.3-3.5, 002 eq 13). NaN where the motion does not reach theta.
    """
    om = np.asarray(omega_post, dtype=float)
    th = np.asarray(theta, dtype=float)
    sq = om**2 + 2.0 * w.rate2 * (math.cos(w.slope - w.alpha) - np.cos(th))
    with np.errstate(invalid="ignore"):
        out = np.sqrt(sq)
    return float(out) if np.ndim(out) == 0 else out


def post_impact_speed(w: RimlessWheel, theta: ArrayLike, omega: ArrayLike) -> NDArray[np.float64] | float:
    """Inverse of :func:`phase_speed`: pull a stance state (theta, omega) back along the sticking flow to the
    post-impact section theta = gamma - alpha of a forward step
    (003 eq 3.5 / 002 eq 13 solved for omega_post >= 0).

    NaN if no motion from the section reaches (theta, omega).
    """
    th = np.asarray(theta, dtype=float)
    om = np.asarray(omega, dtype=float)
    sq = om**2 - 2.0 * w.rate2 * (math.cos(w.slope - w.alpha) - np.cos(th))
    with np.errstate(invalid="ignore"):
        out = np.sqrt(sq)
    return float(out) if np.ndim(out) == 0 else out


def _excursion(w: RimlessWheel, omega_post: float) -> tuple[float, float]:
    """Stance-angle interval swept between an impact with post-impact speed omega_post and the next impact.

    A completed step sweeps [gamma - alpha, gamma + alpha]; a rocking excursion sweeps from the start to the
    turning point where omega = 0 (energy integral 003 eq 3.3/3.6) and back.
    """
    start = w.slope - w.alpha if omega_post >= 0.0 else w.slope + w.alpha
    end = w.slope + w.alpha if omega_post >= 0.0 else w.slope - w.alpha
    cos_turn = math.cos(start) + omega_post**2 / (2.0 * w.rate2)
    completes = omega_post > forward_threshold(w) if omega_post >= 0.0 else omega_post < backward_threshold(w)
    if completes or cos_turn > 1.0:
        return min(start, end), max(start, end)
    turn = math.copysign(math.acos(cos_turn), start)
    return min(start, turn), max(start, turn)


def _minimize_on(
    fun: Callable[[NDArray[np.float64]], NDArray[np.float64]], lo: float, hi: float
) -> tuple[float, float]:
    """Global minimum of a smooth scalar function on [lo, hi]: dense scan, then bounded refinement."""
    grid = np.linspace(lo, hi, _SCAN_POINTS)
    values = fun(grid)
    i = int(np.argmin(values))
    if i in (0, _SCAN_POINTS - 1):
        return float(grid[i]), float(values[i])
    res = minimize_scalar(
        lambda x: float(fun(np.asarray(x))),
        bounds=(grid[i - 1], grid[i + 1]),
        method="bounded",
        options={"xatol": 1e-13},
    )
    return (float(res.x), float(res.fun)) if res.fun < values[i] else (float(grid[i]), float(values[i]))


def _stance_speed(
    w: RimlessWheel, theta_start: float, omega_start: float, theta: ArrayLike
) -> NDArray[np.float64]:
    """omega^2 along a sticking stance from (theta_start, omega_start) (003 eq 3.2 energy integral),
    clipped at 0."""
    sq = omega_start**2 + 2.0 * w.rate2 * (math.cos(theta_start) - np.cos(np.asarray(theta, dtype=float)))
    return np.maximum(sq, 0.0)


def excursion_min_normal_force(w: RimlessWheel, omega_post: float) -> float:
    """min f_n/(m g) over the stance that follows an impact with post-impact speed omega_post (either sign).

    Covers forward steps, backward steps and rocking excursions (forces depend on omega^2 only, so the return
    leg of a rock repeats the outbound one). 002 eq 19 along the energy integral 002 eq 13 / 003 eqs 3.3-3.10.
    """
    lo, hi = _excursion(w, omega_post)
    start = w.slope - w.alpha if omega_post >= 0.0 else w.slope + w.alpha

    def fn(th: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.asarray(normal_force_ratio(w, th, np.sqrt(_stance_speed(w, start, omega_post, th))))

    return _minimize_on(fn, lo, hi)[1]


def step_stays_in_contact(w: RimlessWheel, omega_post: float) -> bool:
    """Whether the sticking stance after an impact with speed omega_post keeps f_n >= 0 throughout.

    For omega_post > omega_f this is one forward step
    (002 eq 26 unnumbered theta_dot_max condition, generalising 002 eq 21 / 003 Sec. 3.1 to any start speed);
    rocking and backward excursions are handled as well.
    """
    return excursion_min_normal_force(w, omega_post) >= 0.0


def _orbit_min_normal_force(w: RimlessWheel) -> float:
    """min f_n/(mg) over theta in [gamma - alpha, gamma + alpha] with the formal fixed-point energy integral
    omega^2 = omega*^2 + 2 rate2 (cos(gamma - alpha) - cos theta) (002 eq 20), used even where (3.16) fails.
    """
    omega_star = _rolling_formula(w)
    lo = w.slope - w.alpha

    def fn(th: NDArray[np.float64]) -> NDArray[np.float64]:
        om2 = omega_star**2 + 2.0 * w.rate2 * (math.cos(lo) - np.cos(th))
        static = np.asarray(normal_force_ratio(w, th, 0.0))
        return static - w.leg_length * om2 / w.gravity * np.cos(th - w.slope)

    return _minimize_on(fn, lo, w.slope + w.alpha)[1]


def no_flight_bound(spokes: int, gyration: float = 0.0, leg_length: float = 1.0) -> float:
    """gamma_fly: largest slope for which the rolling fixed-point orbit keeps f_n >= 0 over the whole step.

    002 eq 21 (alpha_max) / 003 Sec. 3.1 unilateral-contact condition, found by scanning theta over the step
    (no assumption on where the minimum is) and root-finding in the slope.
    Independent of g and l at fixed kappa. The orbit is the formal one of 002 eq 20: for n = 5, kappa = 0
    the result (0.2486) lies below :func:`existence_bound` (0.3397), i.e. no flight-free rolling gait exists.
    """
    validate(RimlessWheel(spokes, 0.1, leg_length, gyration))
    if not _beta_positive(RimlessWheel(spokes, 0.1, leg_length, gyration)):
        return math.nan

    def margin(slope: float) -> float:
        return _orbit_min_normal_force(RimlessWheel(spokes, slope, leg_length, gyration))

    slopes = np.linspace(1e-6, math.pi / 2 - 1e-6, 64)
    values = [margin(s) for s in slopes]
    for a, b, fa, fb in zip(slopes[:-1], slopes[1:], values[:-1], values[1:], strict=True):
        if fa >= 0.0 > fb:
            return float(brentq(margin, a, b, xtol=1e-14, rtol=1e-15))
    return math.nan


def step_period(w: RimlessWheel, omega_post: float) -> float:
    """Duration of a forward step started with post-impact speed omega_post:
    T = int dtheta/omega(theta) over [gamma - alpha, gamma + alpha] with the energy integral
    (003 eq 3.5, 002 eq 13). NaN if the step is not completed (omega_post <= omega_f, or omega_post < 0)."""
    if omega_post < 0.0 or (w.slope < w.alpha and omega_post <= forward_threshold(w)):
        return math.nan
    lo, hi = w.slope - w.alpha, w.slope + w.alpha

    def inv_speed(th: float) -> float:
        return 1.0 / math.sqrt(float(_stance_speed(w, lo, omega_post, th)))

    points = [0.0] if lo < 0.0 < hi else None
    value, _ = quad(inv_speed, lo, hi, points=points, epsabs=1e-13, epsrel=1e-12, limit=200)
    return float(value)


def required_friction(w: RimlessWheel) -> float:
    """mu_c = max |f_t/f_n| over the rolling fixed-point orbit
    (002 eqs 22-23; tan(alpha) for kappa = 0, 003 Sec. 3.1).

    NaN if the rolling gait does not exist; inf if f_n <= 0 somewhere on the orbit.
    """
    if not rolling_exists(w):
        return math.nan
    omega_star = _rolling_formula(w)
    lo = w.slope - w.alpha

    def neg_ratio(th: NDArray[np.float64]) -> NDArray[np.float64]:
        om = np.sqrt(_stance_speed(w, lo, omega_star, th))
        fn = np.asarray(normal_force_ratio(w, th, om))
        ft = np.asarray(tangential_force_ratio(w, th, om))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(fn > 0.0, -np.abs(ft / fn), -np.inf)

    return -_minimize_on(neg_ratio, lo, w.slope + w.alpha)[1]


def impact_impulse_ratio(w: RimlessWheel) -> float:
    """Signed tangential/normal impulse ratio of the sticking impact,
    -sin 2alpha/(2(kappa + cos^2 alpha)) (002 eq 25).

    Re-derived from the hub velocity jump m l ((beta-1) omega- cos alpha, (beta+1) omega- sin alpha);
    negative means the ground pushes uphill. Independent of the slope and of the speed.
    """
    return -math.sin(2.0 * w.alpha) / (2.0 * (w.kappa + math.cos(w.alpha) ** 2))
