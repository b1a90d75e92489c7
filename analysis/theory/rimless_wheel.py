"""Closed-form theory of the planar rimless wheel on a slope (sticking contact, plastic impacts).

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3,
eqs (3.2)-(3.18); 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions",
SIAM J. Appl. Dyn. Syst., Sec. 3.1, eqs (12)-(26).

Conventions (SI units): ``theta`` is the stance spoke's angle from the true vertical, clockwise positive, so
that a downhill lean is positive (003's convention); ``omega`` = d(theta)/dt, positive when rolling downhill.
The slope is ``gamma``; ``alpha`` = pi/n is half the inter-spoke angle. A forward step runs
theta: gamma - alpha -> gamma + alpha. The Poincaré section is "just after an impact"; the sign of omega
fixes the configuration (omega > 0: theta = gamma - alpha, pivot on the downhill foot;
omega < 0: theta = gamma + alpha, pivot on the uphill foot).

Hub inertia (002): radius of gyration ``gyration``, kappa = (gyration/l)^2. Every formula of 003 generalises
with g/l -> rate2 = g/(l(1+kappa)) (stance dynamics, 002 eq 12) and
cos 2alpha -> beta = (cos 2alpha + kappa)/(1+kappa) (impact, 002 eq 14): the stance equation keeps the form
theta'' = rate2 sin theta and the impact keeps the form omega+ = beta omega-, so the derivations of 003 carry
over symbol for symbol.

Corrections to the sources (re-derived here): for gamma > alpha the backward-step threshold of 003 (3.14)
must be -sqrt(K) instead of omega_b (3.7), because a backward step then never passes the vertical; the
rolling multiplier is beta^2 (003 gives no number).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar

#: Tolerance of the equalities gamma == alpha (region Ω2) and (3.16) with equality (region Ω4).
REGION_TOL = 1e-12
#: Distance (rad/s) from a basin edge within which :func:`predicted_outcome` answers "boundary".
BOUNDARY_TOL = 1e-9
_SCAN_POINTS = 401


@dataclass(frozen=True)
class RimlessWheel:
    """Rimless wheel parameters (003 Sec. 3.1; hub inertia as in 002 Sec. 3.1).

    ``spokes`` n >= 3, ``slope`` gamma in (0, pi/2) rad, ``leg_length`` l > 0 (m),
    ``gyration`` hub radius of gyration in [0, l] (m), ``gravity`` g > 0 (m/s^2),
    ``mass`` m > 0 (kg; it drops out of every speed).
    """

    spokes: int
    slope: float
    leg_length: float = 1.0
    gyration: float = 0.0
    gravity: float = 9.81
    mass: float = 1.0

    @property
    def alpha(self) -> float:
        """Half the inter-spoke angle, alpha = pi/n (003 Sec. 3.1; phi in 002)."""
        return math.pi / self.spokes

    @property
    def kappa(self) -> float:
        """Nondimensional hub inertia kappa = I_c/(m l^2) = (gyration/l)^2 (002 Sec. 3.1)."""
        return (self.gyration / self.leg_length) ** 2

    @property
    def rate2(self) -> float:
        """Stance rate squared g/(l(1+kappa)), 1/s^2: theta'' = rate2 sin theta (003 eq 3.2, 002 eq 12)."""
        return self.gravity / (self.leg_length * (1.0 + self.kappa))

    @property
    def beta(self) -> float:
        """Sticking impact coefficient beta = (cos 2alpha + kappa)/(1+kappa)
        (002 eq 14; 003 eq 3.11 for kappa=0)."""
        return (math.cos(2.0 * self.alpha) + self.kappa) / (1.0 + self.kappa)

    @property
    def impact_coefficient(self) -> float:
        """Alias of :attr:`beta` (002 eq 14, 003 eq 3.11)."""
        return self.beta

    @property
    def K(self) -> float:
        """K = 4 rate2 sin(gamma) sin(alpha): kinetic-energy gain of a full step (003 eq 3.5, 002 eq 13)."""
        return 4.0 * self.rate2 * math.sin(self.slope) * math.sin(self.alpha)


def validate(w: RimlessWheel) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range
    (003 eq 3.1 admissible set, 002 kappa <= 1)."""
    if not isinstance(w.spokes, (int, np.integer)) or w.spokes < 3:
        raise ValueError(f"spokes must be an integer >= 3 (got {w.spokes!r})")
    if not 0.0 < w.slope < math.pi / 2:
        raise ValueError(f"slope must be in (0, pi/2) rad (got {w.slope!r})")
    if not w.leg_length > 0.0:
        raise ValueError(f"leg_length must be > 0 m (got {w.leg_length!r})")
    if not 0.0 <= w.gyration <= w.leg_length:
        raise ValueError(f"gyration must be >= 0 and <= leg_length (got {w.gyration!r})")
    if not w.gravity > 0.0:
        raise ValueError(f"gravity must be > 0 m/s^2 (got {w.gravity!r})")
    if not w.mass > 0.0:
        raise ValueError(f"mass must be > 0 kg (got {w.mass!r})")


def _beta_positive(w: RimlessWheel) -> bool:
    """beta > 0 beyond round-off (n = 4, kappa = 0 gives beta = cos(pi/2) = 6e-17: a dead stop)."""
    return w.beta > REGION_TOL


def _steep(w: RimlessWheel) -> bool:
    """gamma > alpha beyond the Ω2 tolerance (003 Sec. 3.3.5, region Ω1)."""
    return w.slope > w.alpha + REGION_TOL


def _level(w: RimlessWheel) -> bool:
    """gamma == alpha within the tolerance (003 Sec. 3.3.5, region Ω2)."""
    return abs(w.slope - w.alpha) <= REGION_TOL


def forward_threshold(w: RimlessWheel) -> float:
    """omega_f = sqrt(2 rate2 (1 - cos(gamma - alpha))),
    the least post-impact speed completing a forward step.

    003 eq 3.4 (g/l -> rate2); 002 eq 26 (theta_dot_min).
    For gamma >= alpha the hub starts on or past the vertical, no threshold is needed and 0.0 is returned.
    """
    if w.slope >= w.alpha - REGION_TOL:
        return 0.0
    return math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope - w.alpha)))


def backward_threshold(w: RimlessWheel) -> float:
    """Largest (negative) post-impact speed that completes a backward (uphill) step.

    003 eq 3.7 for gamma <= alpha: omega_b = -sqrt(2 rate2 (1 - cos(gamma + alpha)))
    (the step must pass the vertical). Corrected for gamma > alpha (003 eq 3.14 is wrong there): the step stays
    on theta > 0 and only has to reach gamma - alpha, where omega^2 = omega0^2 - K, so the threshold is
    -sqrt(K). Both agree at gamma = alpha.
    """
    if w.slope >= w.alpha:
        return -math.sqrt(w.K)
    return -math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope + w.alpha)))


def _branches(w: RimlessWheel, omega: NDArray[np.float64]) -> tuple[NDArray[np.bool_], ...]:
    """Masks (forward, rocking, backward) of the return map 003 eqs 3.13/3.14 (corrected);
    thresholds excluded."""
    hi = forward_threshold(w)
    lo = backward_threshold(w)
    if _steep(w):
        return omega >= hi, (omega > lo) & (omega < hi), omega <= lo
    return omega > hi, (omega > lo) & (omega < hi), omega < lo


def return_map(w: RimlessWheel, omega: ArrayLike) -> NDArray[np.float64] | float:
    """Post-impact speed -> next post-impact speed,
    003 eqs 3.13 (gamma <= alpha) and 3.14 (gamma > alpha, corrected).

    Forward step beta sqrt(omega^2 + K) (003 3.5 + 3.11), rocking -beta omega (3.10 + 3.11),
    backward step -beta sqrt(omega^2 - K) (3.8 + 3.11), with cos 2alpha -> beta (002 eq 14) and
    g/l -> rate2 (002 eq 12). For gamma > alpha the backward threshold is -sqrt(K)
    (see :func:`backward_threshold`). NaN on the heteroclinic thresholds (gamma <= alpha).
    """
    om = np.asarray(omega, dtype=float)
    fwd, rock, back = _branches(w, om)
    with np.errstate(invalid="ignore"):
        out = np.select(
            [fwd, rock, back],
            [w.beta * np.sqrt(om**2 + w.K), -w.beta * om, -w.beta * np.sqrt(np.maximum(om**2 - w.K, 0.0))],
            default=np.nan,
        )
    return float(out) if out.ndim == 0 else out


def return_map_derivative(w: RimlessWheel, omega: ArrayLike) -> NDArray[np.float64] | float:
    """dP/domega of :func:`return_map` (derivative of 003 eqs 3.13/3.14 corrected, c -> beta of 002 eq 14).

    Forward beta omega/sqrt(omega^2 + K), rocking -beta, backward -beta omega/sqrt(omega^2 - K)
    (infinite at omega = -sqrt(K) for gamma > alpha). NaN on the heteroclinic thresholds.
    """
    om = np.asarray(omega, dtype=float)
    fwd, rock, back = _branches(w, om)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.select(
            [fwd, rock, back],
            [
                w.beta * om / np.sqrt(om**2 + w.K),
                np.full_like(om, -w.beta),
                -w.beta * om / np.sqrt(np.maximum(om**2 - w.K, 0.0)),
            ],
            default=np.nan,
        )
    return float(out) if out.ndim == 0 else out


def _rolling_formula(w: RimlessWheel) -> float:
    """beta sqrt(K/(1 - beta^2)), the root of P(omega) = omega on the forward branch
    (003 Sec. 3.3.2, 002 eq 16)."""
    return w.beta * math.sqrt(w.K / (1.0 - w.beta**2))


def rolling_exists(w: RimlessWheel) -> bool:
    """Whether the rolling fixed point exists: 0 < beta and (gamma >= alpha or (3.16) holds strictly).

    003 eq 3.16 generalised: beta sqrt(K/(1 - beta^2)) > omega_f; equivalently 002 eq 18.
    With beta <= 0 (n = 3, or n = 4 and kappa = 0) a forward step never returns to the forward branch.
    """
    if not _beta_positive(w):
        return False
    if w.slope >= w.alpha - REGION_TOL:
        return True
    return _rolling_formula(w) > forward_threshold(w)


def rolling_fixed_point(w: RimlessWheel) -> float:
    """omega*_roll = beta sqrt(K/(1 - beta^2))
    (003 Sec. 3.3.2: 2 cot 2alpha sqrt((g/l) sin gamma sin alpha) for kappa = 0; 002 eq 16 in SI units).
    NaN when it does not exist (see :func:`rolling_exists`)."""
    return _rolling_formula(w) if rolling_exists(w) else math.nan


def rolling_multiplier(w: RimlessWheel) -> float:
    """P'(omega*_roll) = beta^2 (002 eq 17; for 003 Thm 3.13 it is cos^2 2alpha, re-derived):
    with P = beta sqrt(omega^2 + K), P' = beta omega*/sqrt(omega*^2 + K) = beta omega*/(omega*/beta).
    NaN if no rolling gait."""
    return w.beta**2 if rolling_exists(w) else math.nan


def standing_exists(w: RimlessWheel) -> bool:
    """Whether omega*_stop = 0 exists: gamma <= alpha (003 Sec. 3.3.2, Table 1; unstable at gamma = alpha)."""
    return w.slope <= w.alpha + REGION_TOL


def standing_multiplier(w: RimlessWheel) -> float:
    """P'(0) = -beta on the rocking branch (003 eq 3.13 with 3.10-3.11, Thm 3.10; c -> beta of 002 eq 14).

    NaN where the standing point does not exist or is not on the rocking branch (gamma >= alpha).
    """
    return -w.beta if w.slope < w.alpha - REGION_TOL else math.nan


def region(w: RimlessWheel) -> int:
    """Parameter region 1..5 of 003 Sec. 3.3.5 / Table 1 / Fig. 14.

    Ω1 gamma > alpha; Ω2 gamma == alpha (tolerance 1e-12); for gamma < alpha the generalised (3.16),
    beta^2 K/(1 - beta^2) vs omega_f^2 (compared in units of rate2, tolerance 1e-12): Ω3 "<", Ω4 "=", Ω5 ">".
    """
    if _steep(w):
        return 1
    if _level(w):
        return 2
    lhs = w.beta * abs(w.beta) * w.K / (1.0 - w.beta**2) / w.rate2
    rhs = forward_threshold(w) ** 2 / w.rate2
    if abs(lhs - rhs) <= REGION_TOL:
        return 4
    return 5 if lhs > rhs else 3


def existence_bound(
    spokes: int, gyration: float = 0.0, leg_length: float = 1.0, gravity: float = 9.81
) -> float:
    """gamma*(alpha): slope where the generalised 003 eq 3.16 (002 eq 18) holds with equality,
    omega*_roll = omega_f.

    A rolling gait exists for slope > gamma* (003 Fig. 14; alpha_min of 002).
    Independent of g and l at fixed kappa. NaN when beta <= 0 (no rolling gait at any slope).
    """

    def gap(slope: float) -> float:
        w = RimlessWheel(spokes, slope, leg_length, gyration, gravity)
        return (_rolling_formula(w) ** 2 - forward_threshold(w) ** 2) / w.rate2

    w0 = RimlessWheel(spokes, math.pi / (2 * spokes), leg_length, gyration, gravity)
    validate(w0)
    if not _beta_positive(w0):
        return math.nan
    return float(brentq(gap, 1e-14, w0.alpha * (1.0 - 1e-12), xtol=1e-15, rtol=1e-15))


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


def _require_basin_parameters(w: RimlessWheel) -> None:
    if not _beta_positive(w):
        raise ValueError(
            f"basins need 0 < beta < 1 (got beta = {w.beta!r}; spokes must be >= 4, kappa > 0 for n=4)"
        )


def basin_band_edges(w: RimlessWheel, m_max: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Edges of the Ω5 basin bands, 003 Def. 3.20 (c -> beta, g/l -> rate2).

    Returns (omega1, omega2) with omega1[m] = omega_1^m for m = 0..m_max and
    omega2[m] = omega_2^m for m = 0..m_max+1, where
    omega_1^m = -sqrt(2 rate2 [beta^-2m (1 - cos(gamma+alpha))
      + 2 sin gamma sin alpha (1 - beta^-2m)/(1 - beta^-2)])
    and omega_2^m is the same with beta^-2(m+1) (1 - cos(gamma - alpha)).
    Then I^m_roll = (omega1[m], omega2[m]) and I^m_stop = (omega2[m+1], omega1[m]) (003 eqs 3.17-3.18).
    """
    _require_basin_parameters(w)
    s = math.sin(w.slope) * math.sin(w.alpha)
    b2 = w.beta**-2

    def geometric(m: NDArray[np.float64]) -> NDArray[np.float64]:
        return (1.0 - b2**m) / (1.0 - b2)

    m1 = np.arange(m_max + 1, dtype=float)
    m2 = np.arange(m_max + 2, dtype=float)
    omega1 = -np.sqrt(
        2.0 * w.rate2 * (b2**m1 * (1.0 - math.cos(w.slope + w.alpha)) + 2.0 * s * geometric(m1))
    )
    omega2 = -np.sqrt(
        2.0 * w.rate2 * (b2 ** (m2 + 1) * (1.0 - math.cos(w.slope - w.alpha)) + 2.0 * s * geometric(m2))
    )
    return omega1, omega2


def _forward_preimages(w: RimlessWheel, target: float, upto: float) -> list[float]:
    """Forward-branch preimages target_{-m} <= upto:
    omega^2 = beta^-2m target^2 - K (1 - beta^-2m)/(1 - beta^-2) (inverse of 003 Lemma 3.1 with c -> beta);
    only grows when target > omega*_roll (region Ω3)."""
    out = [target]
    while out[-1] <= upto and len(out) < 10_000:
        nxt = math.sqrt((out[-1] / w.beta) ** 2 - w.K)
        if nxt <= out[-1]:
            break
        out.append(nxt)
    return out


def _bands_below(w: RimlessWheel, omega0: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Band edges of :func:`basin_band_edges` with enough bands that omega_1^m_max < omega0 - 1."""
    m_max = 4
    while True:
        omega1, omega2 = basin_band_edges(w, m_max)
        if omega1[-1] < omega0 - 1.0:
            return omega1, omega2
        m_max *= 2


def predicted_outcome(w: RimlessWheel, omega0: float) -> str:
    """Long-term outcome from post-impact speed omega0 by the basin formulas, not by iterating the map.

    003 Table 1 and Thms 3.14-3.21 (Ω5: eqs 3.17-3.18 with the bands of :func:`basin_band_edges`).
    Returns "rolling", "standing" or "boundary" (within 1e-9 rad/s of a basin edge, i.e. of the set H of speeds
    that reach omega_f or omega_b). Ω1: always rolling; Ω2: rolling except omega0 = 0 and H;
    Ω3: standing except H; Ω4: rolling above omega_f (the semistable ghost), standing below;
    Ω5: the band table. Requires 0 < beta < 1.
    """
    _require_basin_parameters(w)
    reg = region(w)
    if reg == 1:
        return "rolling"
    omega_f = forward_threshold(w)
    omega1, omega2 = _bands_below(w, min(omega0, 0.0))
    edges = [omega_f, *omega1]
    if reg == 5:
        edges.extend(omega2)
    if reg == 3:
        edges.extend(_forward_preimages(w, omega_f, omega0 + 1.0))
    if min(abs(omega0 - e) for e in edges) <= BOUNDARY_TOL:
        return "boundary"
    if reg == 2 or (reg in (4, 5) and omega0 > omega_f):
        return "rolling"
    if reg in (3, 4) or omega0 > omega2[0]:
        return "standing"
    m = int(np.argmax(omega1 < omega0))  # first band index with omega_1^m < omega0
    return "rolling" if omega0 < omega2[m] else "standing"


def flight_free(w: RimlessWheel, omega0: float, steps: int) -> bool:
    """Whether iterating the return map (003 eqs 3.13/3.14 corrected) from omega0 for ``steps`` impacts keeps
    f_n >= 0 (002 eq 19) during every stance: forward steps, rocking excursions and backward steps are all
    checked (see :func:`excursion_min_normal_force`). Iteration stops early on a heteroclinic threshold (NaN).
    """
    omega = float(omega0)
    for _ in range(steps):
        if not math.isfinite(omega):
            break
        if not step_stays_in_contact(w, omega):
            return False
        omega = float(return_map(w, omega))
    return True


def fit_initial_speeds(w: RimlessWheel, count: int) -> NDArray[np.float64]:
    """``count`` post-impact speeds around the rolling fixed point (003 eq 3.13), inside its basin (above
    omega_f) and flight-free on the first step (:func:`step_stays_in_contact`): from
    max(0.85 omega*, omega_f + 0.3 (omega* - omega_f)) to at most 1.15 omega*."""
    star = rolling_fixed_point(w)
    low = max(0.85 * star, forward_threshold(w) + 0.3 * (star - forward_threshold(w)))
    high = 1.15 * star
    while not step_stays_in_contact(w, high) and high > 1.01 * star:
        high = star + 0.5 * (high - star)
    return np.linspace(low, high, count)


def basin_initial_speeds(w: RimlessWheel, bands: int = 3) -> NDArray[np.float64]:
    """Post-impact speeds probing every basin of 003 Table 1 / Def. 3.20 (region Ω5), sorted.

    The midpoint of each rolling band I^m_roll and standing band I^m_stop for m < ``bands``, two
    speeds in (omega_2^0, 0) and in (0, omega_f) (standing), two above omega_f (rolling).
    """
    omega1, omega2 = basin_band_edges(w, bands)
    roll = 0.5 * (omega1[:bands] + omega2[:bands])
    stop = 0.5 * (omega2[1 : bands + 1] + omega1[:bands])
    omega_f, star = forward_threshold(w), rolling_fixed_point(w)
    near_zero = [omega2[0] * 2 / 3, omega2[0] / 3, omega_f / 3, omega_f * 2 / 3]
    forward = [omega_f + 0.5 * (star - omega_f), 1.2 * star]
    return np.sort(np.concatenate([roll, stop, near_zero, forward]))


def basin_edges(w: RimlessWheel, bands: int = 8) -> NDArray[np.float64]:
    """Every basin edge down to band ``bands`` (003 Def. 3.20): omega_f, 0 and the band edges omega_1^m, omega_2^m."""
    omega1, omega2 = basin_band_edges(w, bands)
    return np.concatenate([[forward_threshold(w), 0.0], omega1, omega2])


def basin_bands(w: RimlessWheel, bands: int = 3) -> list[list[float | str]]:
    """[low, high, outcome] of the bands I^m_roll and I^m_stop for m < ``bands`` (003 eqs 3.17-3.18), then the
    standing band (omega_2^0, omega_f) and the rolling band (omega_f, 1.3 omega*)."""
    omega1, omega2 = basin_band_edges(w, bands)
    out: list[list[float | str]] = [[float(omega1[m]), float(omega2[m]), "rolling"] for m in range(bands)]
    out += [[float(omega2[m + 1]), float(omega1[m]), "standing"] for m in range(bands)]
    out += [[float(omega2[0]), float(forward_threshold(w)), "standing"],
            [float(forward_threshold(w)), float(1.3 * rolling_fixed_point(w)), "rolling"]]
    return out
