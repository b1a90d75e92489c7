"""Rimless wheel with hub inertia and Coulomb friction: stick-slip gaits A-D, their maps and basins.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 3 eqs (11)-(26), Figs 3.3-3.8, Appendix A eqs (41)-(45); re-derivation with oracles on the derivation
page docs/theory/stick-slip.md, Secs. 1, 2, 4, 5, 7. The rigid (sticking) closed forms are reused from
:mod:`mjpoincare.analysis.theory.rimless_wheel` (003/002 eqs 12-17, 22-25) through :func:`rigid_wheel`.

Conventions (002's, nondimensional): m = l = 1 and g = 1 + kappa, so the stance rate omega_c =
sqrt(g/(l (1+kappa))) = 1 (002's "tau_c" is this rate; :func:`omega_c` converts: theta_dot_SI = theta_dot omega_c,
x_dot_SI = x_dot l omega_c, t_SI = t/omega_c). q = (x, y, theta): (x, y) is the stance-spoke tip in the slope
frame (x downhill, y normal), theta the stance spoke's angle from the slope normal (> 0: hub downhill of the tip).
A step runs theta: -phi -> +phi with phi = pi/n; the next spoke lands at theta = +phi. The slope is alpha
(``slope``). A post-impact state is (theta_dot, x_dot) at theta = -phi, y = y_dot = 0; x_dot is the slip speed of
the new stance tip, unchanged across the relabelling (both tips lie on the ground line). Forces are reported as
f/(m g), impulses in units of m l omega_c. Contact modes: "stick", "slip+" (x_dot > 0, forward/downhill slip),
"slip-".

Two independent implementations of a step: ``method="fast"`` integrates in theta, with the sticking phases in
closed form (energy integral 002 eq 13, forces eq 19) and the slipping phases from eq 42 (u = theta_dot^2 obeys
a linear ODE in theta); ``method="generic"`` runs the Appendix-A matrix machinery of
:mod:`mjpoincare.analysis.theory.stick_slip` in time on q = (x, y, theta) with M, B, G, W, W~ of eq 11.

Corrections to 002 (re-derived; also on the derivation page, Sec. 7 items 1-8):

* tau_c of 002 is the rate omega_c = sqrt(g/(l(1+kappa))), not a time; every "rad/tau_c" is theta_dot/omega_c.
* (41): the kinetic-energy cross term is -2 y_dot theta_dot l sin(theta) (M_23 = -m l sin theta of eq 11).
* (25) prints |sigma~|; the sticking-impulse ratio is -sin(2phi)/(2(kappa + cos^2 phi)) (the ground pushes uphill).
* (39): Gamma~ = (s mu, 1)^T; (44) needs the factor 2 in 2(kappa + cos^2 phi) l theta_dot^- of the denominator
  (else it contradicts (25) at x_dot^- = 0).
* (45): written with s_F = sgn(F~_t) (-1 for forward slip), theta_dot^+ = (2kappa - 1 + cos2phi - s_F mu sin2phi)
  / D_s theta_dot^- and x_dot^+ = x_dot^- + 2 l sin(phi) (2 s_F mu (kappa + cos^2 phi) + sin 2phi)/D_s theta_dot^-,
  D_s = 2kappa + 1 - cos2phi + s_F mu sin2phi. The printed theta row uses s = -s_F (against the paper's own
  s = -sgn(v~_t^-)), and the printed x row's kappa term 2 s mu kappa sin(phi) should be 4 s mu kappa l sin(phi).
  Only the corrected row reproduces 002's Delta x_dot = -0.0517 (Fig. 3.6).
* (34) has a sign error (see :mod:`mjpoincare.analysis.theory.stick_slip`).

Results of this module that the derivation page docs/theory/stick-slip.md takes from it (the rest of its Secs. 1, 2,
4, 5 reproduces here):

* Sec. 2, slipping-impact gain at mu = 0.2: eq 45 (corrected) gives 0.80158, which is also the ratio
  0.775514/0.967486 of the page's Type D table; 0.9570 at mu = 0.3.
* Sec. 2, upper edge of the attraction window, 1.12050 at mu = 1e6: above mu ~ 1e3 the first step fails by the
  Painleve case (forward slip starting at theta < 0 with D = kappa + sin^2 + mu sin cos < 0), not by f_n -> 0;
  detachment is the failure up to mu ~ 1e3. The edge tends to sqrt((3+kappa) cos(alpha) - 2cos(alpha-phi))
  = 1.120496 as mu -> inf (the sticking f_n reaching 0 exactly at theta = 0).
* Secs. 2 and 5, lower end of the C branch: it ends at mu = tan(alpha) = 0.230868, the D+/D- boundary, in a grazing
  bifurcation: the stick phase shrinks like sqrt(mu - tan(alpha)) and the orbit becomes the D orbit with
  Delta x_dot = 0 (found here down to tan(alpha) + 5e-6).

Additional exact results derived here (not in 002; used as oracles): over a Type D step u = theta_dot^2 is affine,
u(phi) = Phi u(-phi) + Psi (:func:`slip_affine_coefficients`), so theta_dot*^2 = gamma^2 Psi/(1 - gamma^2 Phi) and
lambda_D = gamma^2 Phi with gamma the slipping-impact gain (:func:`type_d_linear`); and momentum balance over a step
gives Delta x_dot = g T (sin(alpha) - mu cos(alpha)) for a D gait of period T, so the D+/D- boundary is
mu = tan(alpha) exactly (:func:`d_sign_boundary`).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory import rimless_wheel as rw
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.shooting import central_jacobian, chord_newton
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import IntegrationWarning, quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar

RTOL = 1e-11
ATOL = 1e-12
#: Largest theta step (rad) of a slipping phase in the fast method (grazing trap, docs/theory/stick-slip.md Sec. 4).
SLIP_MAX_STEP = 0.05
#: Post-impact slip speed used to shoot Type D gaits: x_dot is neutral while it stays > 0 (002 Sec. 3.3).
X_NEUTRAL = 10.0
#: |x_dot| below which a post-impact state counts as not slipping.
X_TOL = 1e-12
_GRID = 65
_GAIT_KINDS = ("A", "B", "C", "D")


@dataclass(frozen=True)
class FrictionWheel:
    """Rimless wheel of 002 Sec. 3 (eq 11), nondimensional: ``spokes`` n, ``kappa`` = I_c/(m l^2), ``slope`` alpha
    (rad), ``mu`` the Coulomb coefficient (static = kinetic; ``math.inf`` = no slip). Paper set: n = 10,
    kappa = 1/3, alpha = 13 deg."""

    spokes: int
    kappa: float
    slope: float
    mu: float

    @property
    def phi(self) -> float:
        """Half the inter-spoke angle phi = pi/n (002 eq 43)."""
        return math.pi / self.spokes

    @property
    def gravity(self) -> float:
        """Nondimensional gravity g = 1 + kappa (m = l = 1, omega_c = 1)."""
        return 1.0 + self.kappa


def omega_c(leg_length: float, gravity: float, kappa: float) -> float:
    """Stance rate omega_c = sqrt(g/(l(1+kappa))) (1/s), 002's "tau_c" below eq 12 (a rate, not a time)."""
    return math.sqrt(gravity / (leg_length * (1.0 + kappa)))


def rigid_wheel(w: FrictionWheel) -> rw.RimlessWheel:
    """The same wheel for :mod:`mjpoincare.analysis.theory.rimless_wheel` (003's slope gamma = 002's alpha), in units
    where its rate2 = g/(l(1+kappa)) = 1: l = 1, gyration = sqrt(kappa), g = 1 + kappa."""
    return rw.RimlessWheel(w.spokes, w.slope, 1.0, math.sqrt(w.kappa), 1.0 + w.kappa)


def beta(spokes: int, kappa: float) -> float:
    """Sticking impact coefficient beta = (cos(2pi/n) + kappa)/(1 + kappa) (002 eq 14)."""
    return (math.cos(2.0 * math.pi / spokes) + kappa) / (1.0 + kappa)


@lru_cache(maxsize=256)
def slope_bounds(spokes: int, kappa: float) -> tuple[float, float]:
    """(alpha_min, alpha_max) (rad): the sticking gait exists (002 eq 18) and keeps f_n > 0 (002 eq 21).

    Computed by :func:`mjpoincare.analysis.theory.rimless_wheel.existence_bound` (eq 18 with equality) and
    :func:`mjpoincare.analysis.theory.rimless_wheel.no_flight_bound`, which scans the whole step instead of assuming the
    minimum of f_n at theta = phi (002 Appendix B proves that only for n >= 6 or 9, depending on the case); for the
    paper set both equal eq 21. (nan, nan) when beta <= 0 (n = 3 with kappa <= 1/2, n = 4 with kappa = 0).
    """
    gyration = math.sqrt(kappa)
    return rw.existence_bound(spokes, gyration, 1.0, 1.0), rw.no_flight_bound(spokes, gyration, 1.0)


def validate(w: FrictionWheel) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range.

    ``spokes``: integer >= 3, the same check as :class:`mjpoincare.analysis.theory.rimless_wheel.RimlessWheel` and the
    MuJoCo scenario. 002 states n >= 4 (its Appendix B); the slope window below enforces that in effect, because it
    rejects every wheel without a contact-preserving sticking gait and n = 3 has none for any kappa in [0, 1] (beta <=
    0 for kappa <= 1/2; alpha_min > alpha_max above, e.g. 38.2 > 28.7 deg at kappa = 1), so the message names the empty
    window rather than a second, redundant spoke bound. ``kappa`` in [0, 1] (002 below eq 11); ``mu`` >= 0 (inf
    allowed); ``slope`` strictly inside (alpha_min, alpha_max) of eqs 18/21 (:func:`slope_bounds`).
    """
    if not isinstance(w.spokes, (int, np.integer)) or isinstance(w.spokes, bool) or w.spokes < 3:
        raise ValueError(f"spokes must be an integer >= 3 (got {w.spokes!r})")
    if not 0.0 <= w.kappa <= 1.0:
        raise ValueError(f"kappa must be in [0, 1] (got {w.kappa!r})")
    if not w.mu >= 0.0:
        raise ValueError(f"mu must be >= 0 (got {w.mu!r})")
    lo, hi = slope_bounds(int(w.spokes), float(w.kappa))
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(
            f"slope: no admissible slope for spokes={w.spokes} and kappa={w.kappa} (beta = "
            f"{beta(w.spokes, w.kappa):.4g}; 002 eqs 18/21 leave an empty window)"
        )
    if not lo < w.slope < hi:
        raise ValueError(f"slope must be in ({lo:.6g}, {hi:.6g}) rad, 002 eqs 18/21 (got {w.slope!r})")


# --- sticking closed forms (002 Sec. 3.1-3.2) -----------------------------------------------------------------


def sticking_fixed_point(w: FrictionWheel) -> float:
    """theta_dot* = 2 beta sqrt(sin(alpha) sin(pi/n)/(1 - beta^2)) (002 eq 16), post-impact, nondimensional."""
    b = beta(w.spokes, w.kappa)
    return 2.0 * b * math.sqrt(math.sin(w.slope) * math.sin(w.phi) / (1.0 - b * b))


def sticking_eigenvalue(w: FrictionWheel) -> float:
    """dPi/dtheta_dot at theta_dot* = beta^2 (002 eq 17), independent of alpha and mu."""
    return beta(w.spokes, w.kappa) ** 2


def sticking_map(w: FrictionWheel, theta_dot: ArrayLike) -> NDArray[np.float64] | float:
    """Pi(theta_dot) = beta sqrt(theta_dot^2 + 4 sin(alpha) sin(pi/n)) (002 eq 15)."""
    out = beta(w.spokes, w.kappa) * np.sqrt(np.asarray(theta_dot, float) ** 2 + 4 * math.sin(w.slope) * math.sin(w.phi))
    return float(out) if np.ndim(out) == 0 else out


def sticking_forces(
    w: FrictionWheel, theta: ArrayLike, theta_dot: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(f_t, f_n)/(m g) under sticking at (theta, theta_dot) (002 eq 19, theta_dot nondimensional):
    f_n = ((cos(alpha+theta) - theta_dot^2) cos(theta) + kappa cos(alpha))/(1+kappa),
    f_t = ((cos(alpha+theta) - theta_dot^2) sin(theta) - kappa sin(alpha))/(1+kappa)."""
    th = np.asarray(theta, dtype=float)
    core = np.cos(w.slope + th) - np.asarray(theta_dot, dtype=float) ** 2
    f_n = (core * np.cos(th) + w.kappa * math.cos(w.slope)) / (1.0 + w.kappa)
    f_t = (core * np.sin(th) - w.kappa * math.sin(w.slope)) / (1.0 + w.kappa)
    return f_t, f_n


def force_ratio(w: FrictionWheel, theta: ArrayLike) -> NDArray[np.float64] | float:
    """sigma(theta) = f_t/f_n along the sticking orbit (002 eq 22, i.e. eq 19 with eq 20's
    cos(alpha+theta) - theta_dot^2 = 3cos(alpha+theta) - theta_dot*^2 - 2cos(alpha - pi/n))."""
    th = np.asarray(theta, dtype=float)
    core = 3 * np.cos(w.slope + th) - sticking_fixed_point(w) ** 2 - 2 * math.cos(w.slope - w.phi)
    out = (core * np.sin(th) - w.kappa * math.sin(w.slope)) / (core * np.cos(th) + w.kappa * math.cos(w.slope))
    return float(out) if np.ndim(out) == 0 else out


def critical_friction(w: FrictionWheel, samples: int = 20001) -> tuple[float, float]:
    """(mu_c, theta at which |sigma| peaks): mu_c = max |sigma(theta)| over [-pi/n, pi/n] (002 eq 23).

    Dense scan of eq 22 plus a bounded refinement; mu_c agrees with
    :func:`mjpoincare.analysis.theory.rimless_wheel.required_friction`. The peak can sit at either end of the step.
    """
    grid = np.linspace(-w.phi, w.phi, samples)
    vals = np.abs(np.asarray(force_ratio(w, grid)))
    i = int(np.argmax(vals))
    best_th, best = float(grid[i]), float(vals[i])
    if 0 < i < samples - 1:
        res = minimize_scalar(
            lambda t: -abs(float(force_ratio(w, t))), bounds=(grid[i - 1], grid[i + 1]), method="bounded",
            options={"xatol": 1e-13},
        )
        if -res.fun > best:
            best_th, best = float(res.x), float(-res.fun)
    return best, best_th


def impulse_ratio(spokes: int, kappa: float) -> float:
    """Signed sticking-impulse ratio F~_t/F~_n = -sin(2pi/n)/(2(kappa + cos^2(pi/n))) (002 eq 25, sign restored:
    the paper prints the magnitude). Independent of alpha and of the speed (at x_dot^- = 0)."""
    phi = math.pi / spokes
    return -math.sin(2.0 * phi) / (2.0 * (kappa + math.cos(phi) ** 2))


def attraction_window_rigid(w: FrictionWheel) -> tuple[float, float]:
    """(theta_dot_min, theta_dot_max) for mu = inf (002 eq 26 and the unnumbered equation after it):
    theta_dot_min = sqrt(2(1 - cos(alpha - pi/n))) (0 for alpha >= pi/n; reuses
    :func:`mjpoincare.analysis.theory.rimless_wheel.forward_threshold`),
    theta_dot_max = sqrt(3cos(alpha+phi) - 2cos(alpha-phi) + kappa cos(alpha)/cos(phi)) (f_n(phi) = 0 on the
    first step; assumes the minimum of f_n at theta = phi, 002 Appendix B)."""
    a, p = w.slope, w.phi
    top = 3 * math.cos(a + p) - 2 * math.cos(a - p) + w.kappa * math.cos(a) / math.cos(p)
    return rw.forward_threshold(rigid_wheel(w)), math.sqrt(top) if top > 0 else math.nan


def attraction_upper_limit(w: FrictionWheel) -> float:
    """Limit of the upper edge of the attraction window as mu -> inf (derived here):
    sqrt((3 + kappa) cos(alpha) - 2 cos(alpha - phi)), the theta_dot0 whose sticking f_n (eq 19 with eq 13) reaches 0
    exactly at theta = 0. Any finite mu lets the wheel slip just before f_n = 0 (|sigma| -> inf); a forward slip that
    starts at theta > 0 keeps contact, one that starts at theta < 0 detaches or, for huge mu, is Painleve-inconsistent.
    Hence the finite-mu edge stays well above theta_dot_max = 0.9595 of eq 26 (002 Sec. 3.4)."""
    return math.sqrt((3.0 + w.kappa) * math.cos(w.slope) - 2.0 * math.cos(w.slope - w.phi))


def start_slip_threshold(w: FrictionWheel) -> float:
    """|f_t/f_n| of the sticking force at theta = -phi on the slowest motion that passes upright,
    theta_dot_0 = theta_dot_min of eq 26 (002 eq 19): below this mu the slowest admissible start slips at once and
    the lower edge of the attraction window rises above theta_dot_min (002 Fig. 3.8a, "mu > 0.29";
    derivation page docs/theory/stick-slip.md, Sec. 2: 0.3008)."""
    f_t, f_n = sticking_forces(w, -w.phi, attraction_window_rigid(w)[0])
    return float(abs(f_t / f_n))


def d_sign_boundary(w: FrictionWheel) -> float:
    """mu at which a Type D gait has Delta x_dot = 0: tan(alpha) exactly (derived here, not in 002).

    Over a D step (slip+ throughout, slipping impact with F~_t = -mu F~_n) the hub velocity returns to itself
    except for Delta x_dot, so the momentum balance reads m Delta x_dot = m g T sin(alpha) - mu (int f_n dt + F~_n)
    along the slope and 0 = int f_n dt + F~_n - m g T cos(alpha) normal to it:
    Delta x_dot = g T (sin(alpha) - mu cos(alpha)).
    """
    return math.tan(w.slope)


# --- slip and impact closed forms (002 Appendix A.3) ------------------------------------------------------------


def slip_dynamics(
    w: FrictionWheel, theta: float, theta_dot: float, sign: float
) -> tuple[float, float, float, float]:
    """Slipping stance (002 eq 42, nondimensional), slip direction sign = sgn(x_dot):
    f_n = kappa (g cos(alpha) - theta_dot^2 cos(theta))/D, D = kappa + sin^2(theta) + sign mu sin(theta) cos(theta),
    theta_ddot = (sign mu f_n cos(theta) + sin(theta)(g cos(alpha) - theta_dot^2 cos(theta)))/(kappa + sin^2 theta),
    x_ddot = ((1+kappa)(theta_dot^2 sin(theta) - sign mu f_n) + g(kappa sin(alpha) - cos(alpha+theta) sin(theta)))
    /(kappa + sin^2 theta).
    Returns (theta_ddot, x_ddot, f_n/(m g), D); D <= 0 is the Painleve case (docs/theory/stick-slip.md, Sec. 4).
    """
    s, c = math.sin(theta), math.cos(theta)
    g, k, smu = w.gravity, w.kappa, sign * w.mu
    den = k + s * s + smu * s * c
    core = g * math.cos(w.slope) - theta_dot**2 * c
    f_n = k * core / den
    thdd = (smu * f_n * c + s * core) / (k + s * s)
    xdd = ((1 + k) * (theta_dot**2 * s - smu * f_n) + g * (k * math.sin(w.slope) - math.cos(w.slope + theta) * s)) / (
        k + s * s
    )
    return thdd, xdd, f_n / g, den


@dataclass(frozen=True)
class ImpactValues:
    """Closed-form impact at theta = phi: post-impact (theta_dot, x_dot) and the impulse (F_t, F_n) at the new tip
    (units m l omega_c); ``admissible``: the sticking impulse lies in the cone (002 eq 44 corrected) or, for a
    slipping impact, F_n > 0 and the new tip slides against the friction impulse."""

    theta_dot: float
    x_dot: float
    impulse_t: float
    impulse_n: float
    admissible: bool


def sticking_impact(w: FrictionWheel, theta_dot_minus: float, x_dot_minus: float) -> ImpactValues:
    """Sticking impact with pre-impact slip (002 eq 43): x_dot^+ = 0,
    theta_dot^+ = beta theta_dot^- + cos(phi) x_dot^-/(l(1+kappa)), with the impulses (docs/theory/stick-slip.md,
    Sec. 4)
    F_t = -m((kappa + sin^2 phi) x_dot^- + l sin(phi) sin(2phi) theta_dot^-)/(1+kappa),
    F_n = m sin(phi)(cos(phi) x_dot^- + 2(kappa + cos^2 phi) l theta_dot^-)/(1+kappa);
    admissible iff F_n > 0 and |F_t| <= mu F_n (002 eq 44 with the factor 2 restored)."""
    p, k = w.phi, w.kappa
    thd = beta(w.spokes, k) * theta_dot_minus + math.cos(p) * x_dot_minus / (1 + k)
    f_t = -((k + math.sin(p) ** 2) * x_dot_minus + math.sin(p) * math.sin(2 * p) * theta_dot_minus) / (1 + k)
    f_n = math.sin(p) * (math.cos(p) * x_dot_minus + 2 * (k + math.cos(p) ** 2) * theta_dot_minus) / (1 + k)
    ok = f_n > 0 and (math.isinf(w.mu) or abs(f_t) <= w.mu * f_n)
    return ImpactValues(thd, 0.0, f_t, f_n, bool(ok))


def slipping_impact(w: FrictionWheel, theta_dot_minus: float, x_dot_minus: float, sign: float) -> ImpactValues:
    """Slipping impact (002 eq 45, corrected; see the module docstring), F_t = sign mu F_n with sign = s_F =
    sgn(F_t of the sticking candidate) (-1 for forward slip): with D_s = 2kappa + 1 - cos2phi + s_F mu sin2phi,
    theta_dot^+ = (2kappa - 1 + cos2phi - s_F mu sin2phi)/D_s theta_dot^-,
    x_dot^+ = x_dot^- + 2 sin(phi)(2 s_F mu (kappa + cos^2 phi) + sin 2phi)/D_s theta_dot^-,
    F_n = 2 kappa sin(phi) theta_dot^-/(kappa + sin^2 phi + s_F mu sin(phi) cos(phi))."""
    p, k, smu = w.phi, w.kappa, sign * w.mu
    c2, s2 = math.cos(2 * p), math.sin(2 * p)
    den = 2 * k + 1 - c2 + smu * s2
    thd = (2 * k - 1 + c2 - smu * s2) / den * theta_dot_minus
    xd = x_dot_minus + 2 * math.sin(p) * (2 * smu * (k + math.cos(p) ** 2) + s2) / den * theta_dot_minus
    denom_n = k + math.sin(p) ** 2 + smu * math.sin(p) * math.cos(p)
    f_n = 2 * k * math.sin(p) * theta_dot_minus / denom_n
    ok = f_n > 0 and denom_n > 0 and -sign * xd >= 0 and thd > 0
    return ImpactValues(thd, xd, smu * f_n, f_n, bool(ok))


def impact_closed_form(w: FrictionWheel, theta_dot_minus: float, x_dot_minus: float) -> tuple[str, ImpactValues]:
    """The frictional impact of 002 Appendix A.2 in closed form: sticking (eq 43) if admissible (eq 44 corrected),
    else slipping (eq 45 corrected) with s_F = sgn(F_t of the sticking candidate)."""
    cand = sticking_impact(w, theta_dot_minus, x_dot_minus)
    if cand.admissible:
        return "sticking", cand
    return "slipping", slipping_impact(w, theta_dot_minus, x_dot_minus, 1.0 if cand.impulse_t > 0 else -1.0)


def slip_affine_coefficients(
    w: FrictionWheel, sign: float = 1.0, theta0: float | None = None, theta1: float | None = None
) -> tuple[float, float]:
    """(Phi, Psi) with u(theta1) = Phi u(theta0) + Psi, u = theta_dot^2, for slipping in one direction
    (derived here from 002 eq 42: theta_ddot = d(u/2)/dtheta = (g cos(alpha) - u cos(theta))
    (sin(theta) + sign mu cos(theta))/D is affine in u, so du/dtheta = A(theta) - B(theta) u).
    Defaults: the whole step [-phi, phi]. Valid while u > 0; (nan, nan) if D <= 0 somewhere on the interval
    (checked on a grid) or mu = inf."""
    lo = -w.phi if theta0 is None else theta0
    hi = w.phi if theta1 is None else theta1
    g, k, smu = w.gravity, w.kappa, sign * w.mu
    grid = np.linspace(lo, hi, 257)
    if math.isinf(w.mu) or np.min(k + np.sin(grid) ** 2 + smu * np.sin(grid) * np.cos(grid)) <= 0.0:
        return math.nan, math.nan  # Painleve (D <= 0) somewhere on the interval: eq 42 does not hold

    def rhs(th: float, y: NDArray[np.float64]) -> list[float]:
        s, c = math.sin(th), math.cos(th)
        p = 2.0 * (s + smu * c) / (k + s * s + smu * s * c)
        return [-p * c * y[0], p * (g * math.cos(w.slope) - c * y[1])]

    sol = solve_ivp(rhs, (lo, hi), [1.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-14)
    return float(sol.y[0, -1]), float(sol.y[1, -1])


def type_d_linear(w: FrictionWheel) -> tuple[float, float]:
    """(theta_dot*, lambda) of the Type D gait from the affine slip map and the slipping impact gain gamma
    (eq 45 corrected with s_F = -1): theta_dot*^2 = gamma^2 Psi/(1 - gamma^2 Phi), lambda = gamma^2 Phi
    (derived here). Formal: it does not check u > 0, f_n > 0 or that the impact slips."""
    phi_c, psi_c = slip_affine_coefficients(w, 1.0)
    gamma = slipping_impact(w, 1.0, X_NEUTRAL, -1.0).theta_dot
    lam = gamma**2 * phi_c
    return math.sqrt(gamma**2 * psi_c / (1.0 - lam)), lam


# --- the generic Appendix-A model (002 eq 11) ------------------------------------------------------------------


def contact_model(w: FrictionWheel) -> ss.ContactModel:
    """The wheel as a :class:`mjpoincare.analysis.theory.stick_slip.ContactModel` on q = (x, y, theta) (002 eq 11,
    nondimensional): M = [[1, 0, cos], [0, 1, -sin], [cos, -sin, 1+kappa]], h = B + G with
    B = (-theta_dot^2 sin, -theta_dot^2 cos, 0), G = g(-sin(alpha), cos(alpha), -sin(alpha+theta)),
    W = [[1, 0, 0], [0, 1, 0]], W~ = d(tip of the spoke ahead)/dq (= eq 11's W~_c at theta = phi), guard: height of
    the spoke ahead y + cos(theta) - cos(theta - 2phi). Failure event "backward" (theta_dot -> 0), section
    "midstance" (theta = 0 upward). Needs kappa > 0 (M is singular at kappa = 0)."""
    if not w.kappa > 0.0:
        raise ValueError(f"kappa must be > 0 for the generic model (M is singular at kappa = 0; got {w.kappa!r})")
    k, g, a, p = w.kappa, w.gravity, w.slope, w.phi
    jac = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])

    def mass(q: NDArray[np.float64]) -> NDArray[np.float64]:
        s, c = math.sin(q[2]), math.cos(q[2])
        return np.array([[1.0, 0.0, c], [0.0, 1.0, -s], [c, -s, 1.0 + k]])

    def bias(q: NDArray[np.float64], qd: NDArray[np.float64]) -> NDArray[np.float64]:
        s, c, om2 = math.sin(q[2]), math.cos(q[2]), qd[2] ** 2
        return np.array([-om2 * s - g * math.sin(a), -om2 * c + g * math.cos(a), -g * math.sin(a + q[2])])

    def swing(q: NDArray[np.float64]) -> NDArray[np.float64]:
        th = q[2]
        return np.array(
            [[1.0, 0.0, math.cos(th) - math.cos(th - 2 * p)], [0.0, 1.0, -math.sin(th) + math.sin(th - 2 * p)]]
        )

    return ss.ContactModel(
        mass_matrix=mass,
        bias=bias,
        contact_jacobian=lambda _q: jac,
        contact_jacobian_rate=lambda _q, _qd: np.zeros(2),
        swing_jacobian=swing,
        impact_guard=lambda q, _qd: q[1] + math.cos(q[2]) - math.cos(q[2] - 2 * p),
        guard_direction=-1.0,
        failure_events=(("backward", lambda _q, qd: qd[2], -1.0),),
        sections=(("midstance", lambda q, _qd: q[2], 1.0),),
    )


# --- one step -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class StepRecord:
    """One step from a post-impact state (theta_dot0, x_dot0) at theta = -phi (see :func:`step`).

    ``phases`` ("stick", "slip+", "slip-") in order with ``phase_angles`` theta at their starts; ``impact``
    "sticking"/"slipping" (None on failure); ``theta_dot_pre``/``x_dot_pre`` just before the impact; ``theta_dot``/
    ``x_dot`` the next post-impact state (NaN on failure); ``impulse_ratio`` F~_t/F~_n applied; ``min_fn`` min f_n/(mg)
    over the stance (sampled); ``failure`` None, "backward" (theta_dot -> 0: rolls back), "detached" (f_n -> 0;
    also any slip at kappa = 0, where eq 42 gives f_n = 0), "painleve" (D of eq 42 <= 0), "impact" (the impact law
    is inconsistent: F~_n <= 0, slip reversal within the impact or theta_dot^+ <= 0) or "chatter";
    ``failure_angle`` theta where it happened; ``duration`` the stance time; ``midstance`` (theta_dot, x_dot) at
    theta = 0 (NaN if not reached).
    """

    theta_dot0: float
    x_dot0: float
    phases: tuple[str, ...]
    phase_angles: tuple[float, ...]
    impact: str | None
    theta_dot_pre: float
    x_dot_pre: float
    theta_dot: float
    x_dot: float
    impulse_ratio: float
    min_fn: float
    failure: str | None
    failure_angle: float
    duration: float
    midstance: tuple[float, float]

    @property
    def dx(self) -> float:
        """x_dot - x_dot0: the change of slip speed over the step (Delta x_dot of 002 Sec. 3.3)."""
        return self.x_dot - self.x_dot0

    @property
    def post(self) -> tuple[float, float]:
        """Next post-impact state (theta_dot, x_dot)."""
        return self.theta_dot, self.x_dot


@dataclass
class _Builder:
    phases: list[str] = field(default_factory=list)
    angles: list[float] = field(default_factory=list)
    min_fn: float = math.inf
    duration: float = 0.0
    mid: tuple[float, float] = (math.nan, math.nan)


def _first_root(fun: Callable[[float], float], grid: NDArray[np.float64], vals: NDArray[np.float64]) -> float:
    """First point of grid[0] < theta <= grid[-1] where fun <= 0 (inf if none): the first non-positive sample,
    or a dip between samples detected from the parabola through three samples and refined by minimize_scalar."""
    if vals[0] < 0.0:
        return float(grid[0])
    neg = np.nonzero(vals[1:] <= 0.0)[0]
    j = int(neg[0]) + 1 if neg.size else len(grid)
    m = max(j - 2, 0)
    v0, v1, v2 = vals[:m], vals[1 : m + 1], vals[2 : m + 2]
    curv = v0 - 2 * v1 + v2
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.where((v1 <= v0) & (v1 <= v2) & (curv > 0), v1 - (v2 - v0) ** 2 / (8 * curv), np.inf)
    for i in np.nonzero(vertex <= 0.05 * (np.abs(v2 - v0) + curv))[0]:
        lo, hi = float(grid[i]), float(grid[i + 2])
        res = minimize_scalar(fun, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        if res.fun <= 0.0:
            return float(brentq(fun, lo, float(res.x), xtol=1e-15, rtol=1e-15))
    if j < len(grid):
        return float(brentq(fun, float(grid[j - 1]), float(grid[j]), xtol=1e-15, rtol=1e-15))
    return math.inf


def _sampled_min(vals: NDArray[np.float64]) -> float:
    """Minimum of equally spaced samples, refined by the parabola through the smallest sample and its neighbours."""
    if vals.size == 0:
        return math.inf
    i = int(np.argmin(vals))
    if 0 < i < vals.size - 1:
        v0, v1, v2 = vals[i - 1], vals[i], vals[i + 1]
        curv = v0 - 2 * v1 + v2
        if curv > 0:
            return float(v1 - (v2 - v0) ** 2 / (8 * curv))
    return float(vals[i])


def _stick_phase(w: FrictionWheel, th0: float, u0: float, b: _Builder) -> tuple[float, float, str]:
    """Sticking phase from (th0, u0 = theta_dot^2) in closed form (002 eqs 12-13, 19): returns (theta_end, u_end,
    reason), reason "impact" (theta = phi), "slip+"/"slip-" (cone edge reached: f_t = -+mu f_n), "detached"
    (f_n = 0) or "backward" (theta_dot = 0)."""
    a, k, p = w.slope, w.kappa, w.phi
    e0 = u0 + 2.0 * math.cos(a + th0)
    cos_a, sin_a = math.cos(a), math.sin(a)

    def u_of(th: float) -> float:
        return e0 - 2.0 * math.cos(a + th)

    def forces(th: float) -> tuple[float, float]:
        core = math.cos(a + th) - u_of(th)
        return (core * math.sin(th) - k * sin_a) / (1 + k), (core * math.cos(th) + k * cos_a) / (1 + k)

    extra = [x for x in (-a, 0.0) if th0 < x < p]
    grid = np.unique(np.concatenate([np.linspace(th0, p, _GRID), extra]))
    u = e0 - 2.0 * np.cos(a + grid)
    core = np.cos(a + grid) - u
    f_n = (core * np.cos(grid) + k * cos_a) / (1 + k)
    f_t = (core * np.sin(grid) - k * sin_a) / (1 + k)
    ends: list[tuple[float, str]] = [
        (_first_root(u_of, grid, u), "backward"),
        (_first_root(lambda th: forces(th)[1], grid, f_n), "detached"),
    ]
    if not math.isinf(w.mu):
        mu = w.mu
        ends.append((_first_root(lambda th: forces(th)[0] + mu * forces(th)[1], grid, f_t + mu * f_n), "slip+"))
        ends.append((_first_root(lambda th: mu * forces(th)[1] - forces(th)[0], grid, mu * f_n - f_t), "slip-"))
    th_end, reason = min(ends)
    if math.isinf(th_end):
        th_end, reason = p, "impact"
    b.min_fn = min(b.min_fn, _sampled_min(f_n[grid <= th_end]), forces(th_end)[1])
    if th0 <= 0.0 <= th_end:
        b.mid = (math.sqrt(max(u_of(0.0), 0.0)), 0.0)
    if th_end > th0:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", IntegrationWarning)
            b.duration += quad(lambda th: 1.0 / math.sqrt(max(u_of(th), 1e-300)), th0, th_end, limit=200)[0]
    return th_end, max(u_of(th_end), 0.0), reason


def _slip_phase(
    w: FrictionWheel, th0: float, u0: float, xd0: float, sign: float, b: _Builder, max_step: float
) -> tuple[float, float, float, str]:
    """Slipping phase from (th0, u0, xd0) integrated in theta (002 eq 42 with u = theta_dot^2:
    du/dtheta = 2 theta_ddot, dx_dot/dtheta = x_ddot/theta_dot, dt/dtheta = 1/theta_dot), DOP853 with events:
    x_dot = 0 ("stop"), D = 0 ("painleve"), f_n = 0 ("detached"), u = 0 ("backward"). f_n and u are also checked
    for dips between steps on the dense solution. Returns (theta_end, u_end, x_dot_end, reason)."""
    a, k, g, p = w.slope, w.kappa, w.gravity, w.phi
    smu = sign * w.mu
    gcos, ksin = g * math.cos(a), k * math.sin(a)

    def rhs(th: float, y: NDArray[np.float64]) -> list[float]:
        u = y[0]
        s, c = math.sin(th), math.cos(th)
        den = k + s * s + smu * s * c
        core = gcos - u * c
        f_n = k * core / den
        xdd = ((1 + k) * (u * s - smu * f_n) + g * (ksin - math.cos(a + th) * s)) / (k + s * s)
        r = 1.0 / math.sqrt(abs(u)) if u != 0.0 else 1e150
        return [2.0 * core * (s + smu * c) / den, xdd * r, r]

    # A slip that starts from x_dot = 0 has x_dot ~ a0 (theta - th0) with a0 >= 0, possibly tiny (the start lies just
    # outside the cone): its stop may come before the first solver step ends, and sign*x_dot alone would put the
    # root at th0 (the grazing trap). sign*x_dot/(theta - th0), which starts at a0, has only the true root.
    a0 = sign * rhs(th0, np.array([u0, xd0, 0.0]))[1] if xd0 == 0.0 else math.nan

    def stop(th: float, y: NDArray[np.float64]) -> float:
        if xd0 != 0.0:
            return sign * y[1]
        return sign * y[1] / (th - th0) if th > th0 else a0

    def painleve(th: float, _y: NDArray[np.float64]) -> float:
        s = math.sin(th)
        return k + s * s + smu * s * math.cos(th)

    def detach(th: float, y: NDArray[np.float64]) -> float:
        return gcos - y[0] * math.cos(th)

    def backward(_th: float, y: NDArray[np.float64]) -> float:
        return y[0]

    if painleve(th0, None) <= 0.0:  # type: ignore[arg-type]
        return th0, u0, xd0, "painleve"
    if detach(th0, np.array([u0])) <= 0.0:
        b.min_fn = min(b.min_fn, float(k * detach(th0, np.array([u0])) / painleve(th0, None) / g))  # type: ignore
        return th0, u0, xd0, "detached"
    events = (stop, painleve, detach, backward)
    names = ("stop", "painleve", "detached", "backward")
    for ev in events:
        ev.terminal = True  # type: ignore[attr-defined]
        ev.direction = -1.0  # type: ignore[attr-defined]
    sol = solve_ivp(
        rhs, (th0, p), [u0, xd0, 0.0], method="DOP853", rtol=RTOL, atol=ATOL, events=events, dense_output=True,
        max_step=max_step, first_step=min(1e-3, max(p - th0, 1e-12)),
    )
    th_end, y_end, reason = float(sol.t[-1]), sol.y[:, -1], "impact"
    hits = [(float(te[0]), i) for i, te in enumerate(sol.t_events) if te.size]
    if sol.status == 1 and hits:
        th_hit, i = min(hits)
        th_end, y_end, reason = th_hit, sol.y_events[i][0], names[i]
    elif sol.status != 0:
        reason = "backward" if sol.y[0, -1] < 1e-6 else "chatter"
    if th_end > th0:
        grid = np.linspace(th0, th_end, _GRID)
        ys = sol.sol(grid)
        for fun_vals, fun, label in (
            (ys[0], lambda t: float(sol.sol(t)[0]), "backward"),
            (gcos - ys[0] * np.cos(grid), lambda t: gcos - float(sol.sol(t)[0]) * math.cos(t), "detached"),
        ):
            th_dip = _first_root(fun, grid, fun_vals)
            if th_dip < th_end and reason != label:
                th_end, y_end, reason = th_dip, sol.sol(th_dip), label
        fn = k * (gcos - ys[0] * np.cos(grid)) / (k + np.sin(grid) ** 2 + smu * np.sin(grid) * np.cos(grid)) / g
        b.min_fn = min(b.min_fn, _sampled_min(fn[grid <= th_end]))
        if th0 <= 0.0 <= th_end:
            ym = sol.sol(0.0)
            b.mid = (math.sqrt(max(ym[0], 0.0)), float(ym[1]))
    s_end = math.sin(th_end)
    den_end = k + s_end**2 + smu * s_end * math.cos(th_end)
    fn_end = float(k * (gcos - y_end[0] * math.cos(th_end)) / den_end / g) if den_end > 0 else -math.inf
    b.min_fn = min(b.min_fn, fn_end)
    b.duration += float(y_end[2])
    return th_end, float(y_end[0]), float(y_end[1]), reason


def _stick_decision(w: FrictionWheel, th: float, u: float) -> str:
    """Mode at x_dot = 0 (002 eq 35): stick if the sticking force (eq 19) is in the cone, else slip against f_t."""
    f_t, f_n = sticking_forces(w, th, math.sqrt(max(u, 0.0)))
    return ss.mode_from_stick_force((float(f_t), float(f_n)), w.mu)


def _record(
    theta_dot0: float, x_dot0: float, b: _Builder, impact: str | None, pre: tuple[float, float],
    post: tuple[float, float], ratio: float, failure: str | None, angle: float,
) -> StepRecord:
    return StepRecord(
        theta_dot0, x_dot0, tuple(b.phases), tuple(b.angles), impact, pre[0], pre[1], post[0], post[1], ratio,
        b.min_fn, failure, angle, b.duration, b.mid,
    )


def _step_fast(w: FrictionWheel, theta_dot0: float, x_dot0: float, max_step: float, max_phases: int) -> StepRecord:
    b = _Builder()
    nan2 = (math.nan, math.nan)
    th, u, xd = -w.phi, theta_dot0**2, x_dot0
    if not theta_dot0 > 0.0:
        return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, "backward", th)
    if abs(xd) <= X_TOL:
        xd = 0.0
        mode = _stick_decision(w, th, u)
    else:
        mode = "slip+" if xd > 0 else "slip-"
    while True:
        if len(b.phases) >= max_phases:
            return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, "chatter", th)
        b.phases.append(mode)
        b.angles.append(th)
        if mode == "stick":
            th, u, reason = _stick_phase(w, th, u, b)
            xd = 0.0
        elif w.kappa == 0.0 or math.isinf(w.mu):
            reason = "detached"  # kappa = 0: eq 42 gives f_n = 0 while slipping; mu = inf: f_n < 0 under sticking
            b.min_fn = min(b.min_fn, float(sticking_forces(w, th, math.sqrt(u))[1]) if w.kappa > 0 else 0.0)
        else:
            th, u, xd, reason = _slip_phase(w, th, u, xd, 1.0 if mode == "slip+" else -1.0, b, max_step)
        if reason in ("slip+", "slip-"):
            mode = reason
        elif reason == "stop":
            xd = 0.0
            mode = _stick_decision(w, th, u)
        elif reason != "impact":
            return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, reason, th)
        else:
            break
    pre = (math.sqrt(u), xd)
    kind, imp = impact_closed_form(w, *pre)
    if not imp.admissible:
        return _record(theta_dot0, x_dot0, b, kind, pre, nan2, imp.impulse_t / imp.impulse_n, "impact", th)
    return _record(theta_dot0, x_dot0, b, kind, pre, (imp.theta_dot, imp.x_dot), imp.impulse_t / imp.impulse_n,
                   None, th)


def _step_generic(w: FrictionWheel, theta_dot0: float, x_dot0: float, max_step: float, max_phases: int,
                  rtol: float) -> StepRecord:
    model = contact_model(w)
    p = w.phi
    b = _Builder()
    nan2 = (math.nan, math.nan)
    q0 = np.array([0.0, 0.0, -p])
    qd0 = np.array([0.0 if abs(x_dot0) <= X_TOL else x_dot0, 0.0, theta_dot0])
    res = ss.integrate_stance(model, q0, qd0, w.mu, rtol=rtol, atol=rtol * ATOL / RTOL, slip_max_step=max_step,
                              max_phases=max_phases, v_tol=X_TOL)
    for ph in res.phases:
        b.phases.append(ph.mode)
        b.angles.append(float(ph.q_start[2]))
    b.min_fn = res.min_normal_force / w.gravity
    b.duration = res.t_end
    if "midstance" in res.sections:
        _, _, qd_mid = res.sections["midstance"]
        b.mid = (float(qd_mid[2]), float(qd_mid[0]))
    if res.failure is not None:
        return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, res.failure, float(res.q_end[2]))
    pre = (float(res.qd_end[2]), float(res.qd_end[0]))
    out = ss.impact(model, res.q_end, res.qd_end, w.mu)
    post = (float(out.qd_plus[2]), float(out.swing_velocity[0]))
    ratio = float(out.impulse[0] / out.impulse[1])
    ok = out.consistent and post[0] > 0
    return _record(theta_dot0, x_dot0, b, out.kind, pre, post if ok else nan2, ratio, None if ok else "impact",
                   float(res.q_end[2]))


def step(
    w: FrictionWheel,
    state: Sequence[float],
    *,
    method: str = "fast",
    max_step: float | None = None,
    max_phases: int = 40,
    rtol: float = RTOL,
) -> StepRecord:
    """One step of the hybrid stick-slip dynamics (002 Sec. 3.3, Appendix A) from the post-impact state
    ``state`` = (theta_dot, x_dot) at theta = -phi: stance phases with the mode logic of 002 eq 35, then the
    frictional impact at theta = phi (eqs 43-45 corrected) and the relabelling to the next spoke.

    ``method``: "fast" (theta-domain, closed-form sticking phases) or "generic"
    (:func:`mjpoincare.analysis.theory.stick_slip.integrate_stance` on the matrix model of :func:`contact_model`).
    ``max_step``: largest step while slipping (theta in rad for "fast", default 0.05; time for "generic",
    default 1e-2). ``rtol``: the generic method's relative tolerance (absolute: rtol x ATOL/RTOL); the fast method
    runs at RTOL. No validation of ``w`` here (see :func:`validate`).
    """
    theta_dot0, x_dot0 = float(state[0]), float(state[1])
    if method == "fast":
        return _step_fast(w, theta_dot0, x_dot0, SLIP_MAX_STEP if max_step is None else max_step, max_phases)
    if method == "generic":
        return _step_generic(w, theta_dot0, x_dot0, ss.SLIP_MAX_STEP if max_step is None else max_step, max_phases,
                             rtol)
    raise ValueError(f"method must be 'fast' or 'generic' (got {method!r})")


# --- classification, settling, gaits --------------------------------------------------------------------------


def classify_record(record: StepRecord) -> str | None:
    """Gait type of one step (002 Sec. 3.3): "A" sticking impact and stick throughout; "B" sticking impact and some
    slip; "C" slipping impact with a stick phase; "D+"/"D-" slipping impact and slip throughout, split by the sign of
    Delta x_dot; None on failure."""
    if record.failure is not None or record.impact is None:
        return None
    if record.impact == "sticking":
        return "A" if all(m == "stick" for m in record.phases) else "B"
    if "stick" in record.phases:
        return "C"
    return "D+" if record.dx > 0 else "D-"


def classify(records: Sequence[StepRecord]) -> str | None:
    """Gait type (see :func:`classify_record`) of a converged sequence of steps: the type of its last step, or the
    last step's failure reason ("backward", "detached", ...)."""
    if not records:
        return None
    last = records[-1]
    return last.failure if last.failure is not None else classify_record(last)


@dataclass(frozen=True)
class Settled:
    """Outcome of :func:`settle`: ``outcome`` a gait type ("A", "B", "C", "D+"), a failure reason, or "unsettled";
    ``steps`` the number of steps taken; ``records`` all of them."""

    outcome: str
    steps: int
    records: tuple[StepRecord, ...]


def settle(
    w: FrictionWheel, state: Sequence[float], max_steps: int = 300, tol: float = 1e-9, method: str = "fast"
) -> Settled:
    """Iterate the post-impact map from ``state`` = (theta_dot, x_dot) until a step changes the state by less than
    ``tol`` (theta_dot and x_dot for A/B/C; theta_dot only for D+, where x_dot grows without bound), a step fails,
    or ``max_steps``. D- never settles: x_dot falls to 0 in finitely many steps (002 Sec. 3.3, Fig. 3.6)."""
    validate(w)
    records: list[StepRecord] = []
    z = (float(state[0]), float(state[1]))
    for k in range(1, max_steps + 1):
        rec = step(w, z, method=method)
        records.append(rec)
        if rec.failure is not None:
            return Settled(rec.failure, k, tuple(records))
        label = classify_record(rec)
        d_th, d_x = abs(rec.theta_dot - z[0]), abs(rec.x_dot - z[1])
        if (label in ("A", "B", "C") and max(d_th, d_x) < tol) or (label == "D+" and d_th < tol):
            return Settled(str(label), k, tuple(records))
        z = rec.post
    return Settled("unsettled", max_steps, tuple(records))


@dataclass(frozen=True)
class Gait:
    """A period-1 gait (002 Sec. 3.3): ``kind`` "A", "B", "C", "D+" or "D-"; ``fixed_point`` (theta_dot*,) or, for
    C, (theta_dot*, x_dot*) at the post-impact section; ``eigenvalues`` of the return map's Jacobian (1-D for A, B,
    D; 2-D for C); ``phases`` and ``phase_angles`` of the step; ``impact``; ``dx_per_step`` Delta x_dot per step (D;
    0 otherwise); ``pre_impact`` (theta_dot^-, x_dot^-) (for D, x_dot^- - x_dot^+ ); ``period`` the step time
    (units 1/omega_c); ``midstance_rate`` theta_dot at theta = 0 and ``midstance_x_dot`` x_dot there (for D the
    increment over the post-impact x_dot); ``impulse_ratio`` F~_t/F~_n; ``min_fn`` min f_n/(mg)."""

    kind: str
    fixed_point: NDArray[np.float64]
    eigenvalues: NDArray[np.complex128]
    phases: tuple[str, ...]
    phase_angles: tuple[float, ...]
    impact: str
    dx_per_step: float
    pre_impact: tuple[float, float]
    period: float
    midstance_rate: float
    midstance_x_dot: float
    impulse_ratio: float
    min_fn: float


def _affine_fixed_point(fun: Callable[[float], float], s0: float, tol: float = 1e-13) -> float | None:
    """Secant iteration on G(s) = P(sqrt s)^2 - s (s = theta_dot^2), nearly affine for these maps
    (exactly affine for A, eq 15, and for D, :func:`slip_affine_coefficients`); None if G is undefined there."""
    g0 = fun(s0)
    if not math.isfinite(g0):
        return None
    for s1 in (s0 * (1 - 1e-5), s0 * (1 + 1e-5)):
        g1 = fun(s1)
        if math.isfinite(g1):
            break
    else:
        return None
    for _ in range(40):
        if g1 == g0:
            return s1 if g1 == 0.0 else None
        s2 = s1 - g1 * (s1 - s0) / (g1 - g0)
        if not s2 > 0.0:
            return None
        s0, g0, s1 = s1, g1, s2
        g1 = fun(s1)
        if not math.isfinite(g1):
            return None
        if abs(s1 - s0) <= tol * s1:
            return s1
    return None


def _derivative(fun: Callable[[float], float], x: float, h: float) -> float:
    """Central difference, or a one-sided one where the map is undefined on one side (at a branch edge)."""
    up, down, mid = fun(x + h), fun(x - h), fun(x)
    if math.isfinite(up) and math.isfinite(down):
        return (up - down) / (2 * h)
    if math.isfinite(up):
        return (up - mid) / h
    return (mid - down) / h


def _gait_from(w: FrictionWheel, z: NDArray[np.float64], x_dot: float, kind: str, eig: NDArray[np.complex128]) -> Gait:
    rec = step(w, (float(z[0]), x_dot))
    label = classify_record(rec)
    dx = rec.dx if kind == "D" else 0.0
    mid_x = rec.midstance[1] - x_dot if kind == "D" else rec.midstance[1]
    pre_x = rec.x_dot_pre - x_dot if kind == "D" else rec.x_dot_pre
    return Gait(str(label), z, eig, rec.phases, rec.phase_angles, str(rec.impact), dx, (rec.theta_dot_pre, pre_x),
                rec.duration, rec.midstance[0], mid_x, rec.impulse_ratio, rec.min_fn)


def find_gait(w: FrictionWheel, kind: str, guess: Sequence[float] | None = None) -> Gait | None:
    """Period-1 gait of type ``kind`` ("A", "B", "C" or "D", 002 Sec. 3.3) by Newton shooting on the simulator, or
    None if no such gait exists at this mu.

    A, B: 1-D map theta_dot -> theta_dot^+ with x_dot = 0 (a sticking impact leaves x_dot^+ = 0); secant on
    theta_dot^2 from eq 16. C: 2-D map in (theta_dot, x_dot) (Newton from ``guess`` or from a forward iteration
    started at (eq 16, 0)). D: 1-D map in theta_dot at x_dot = X_NEUTRAL (the slip dynamics eq 42 and the slipping
    impact's theta row do not depend on x_dot > 0); ``dx_per_step`` gives Delta x_dot and the kind "D+"/"D-" its sign.
    The converged step must be of the requested type, without failure; eigenvalues by central differences.
    """
    validate(w)
    if kind not in _GAIT_KINDS:
        raise ValueError(f"kind must be one of {_GAIT_KINDS} (got {kind!r})")
    if kind == "C":
        return _find_c(w, guess)
    x_dot = X_NEUTRAL if kind == "D" else 0.0
    start = float(guess[0]) if guess is not None else sticking_fixed_point(w)
    if kind == "D" and guess is None:
        start = type_d_linear(w)[0]
        if not math.isfinite(start):
            return None

    def post(th: float) -> float:
        rec = step(w, (th, x_dot))
        ok = rec.failure is None and (rec.impact == "sticking") == (kind in "AB")
        return rec.theta_dot if ok else math.nan

    s_star = _affine_fixed_point(lambda s: post(math.sqrt(s)) ** 2 - s, start**2)
    if s_star is None:
        return None
    th_star = math.sqrt(s_star)
    rec = step(w, (th_star, x_dot))
    label = classify_record(rec)
    if label is None or label[0] != kind:
        return None
    lam = _derivative(post, th_star, 1e-5 * th_star)
    if not math.isfinite(lam):
        return None
    return _gait_from(w, np.array([th_star]), x_dot, kind, np.array([lam], dtype=complex))


def _c_post(w: FrictionWheel, z: NDArray[np.float64]) -> NDArray[np.float64]:
    """The 2-D post-impact map of a C-like step (slipping impact, x_dot^+ > 0), NaN otherwise."""
    rec = step(w, (float(z[0]), float(z[1])))
    if rec.failure is not None or rec.impact != "slipping" or not rec.x_dot > 0:
        return np.array([math.nan, math.nan])
    return np.array([rec.theta_dot, rec.x_dot])


def _c_fixed_point(w: FrictionWheel, z0: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Type C fixed point by chord-Newton from z0, None unless it converges to a Type C step."""
    z_star = chord_newton(lambda v: _c_post(w, v) - v, z0, tol=1e-14, step_tol=1e-12, max_iter=40,
                          relative_step=True, halvings=0)
    if z_star is None or not z_star[1] > 0 or classify_record(step(w, tuple(z_star))) != "C":
        return None
    return z_star


def _find_c(w: FrictionWheel, guess: Sequence[float] | None) -> Gait | None:
    def post(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return _c_post(w, z)

    if guess is None:
        z = np.array([sticking_fixed_point(w), 0.0])
        for _ in range(40):
            rec = step(w, tuple(z))
            if rec.failure is not None:
                return None
            z = np.array(rec.post)
            if classify_record(rec) == "C" and z[1] > 0:
                break
        else:
            return None
    else:
        z = np.asarray(guess, dtype=float)
    z_star = _c_fixed_point(w, z)
    if z_star is None:
        return None
    eig = sort_eigenvalues(np.linalg.eigvals(central_jacobian(post, z_star, 1e-6, relative=True)).astype(complex))
    return _gait_from(w, z_star, float(z_star[1]), "C", eig)


def midstance_rate(gait: Gait) -> float:
    """theta_dot at theta = 0 (mid-stance) on the gait: the section the MuJoCo side samples, away from the smeared
    soft impact (derivation page docs/theory/stick-slip.md, Secs. 5-6)."""
    return gait.midstance_rate


def midstance_x_dot(gait: Gait) -> float:
    """x_dot at theta = 0 on the gait (for D: the increment over the post-impact x_dot, which is neutral)."""
    return gait.midstance_x_dot


# --- regions of attraction (002 Sec. 3.4, Fig. 3.8) -------------------------------------------------------------


def _bisect(pred: Callable[[float], bool], lo: float, hi: float, tol: float) -> float:
    """Boundary between pred(lo) = False and pred(hi) = True by bisection."""
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if pred(mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def attraction_window(w: FrictionWheel, tol: float = 1e-8) -> tuple[float, float]:
    """(theta_dot_min(mu), theta_dot_max(mu)) with x_dot0 = 0 (002 Sec. 3.4, Fig. 3.8a), by bisection (to ``tol``)
    on the first step from (theta_dot0, 0): the lower edge is where it stops rolling back ("backward"), the upper where
    it starts to fail otherwise (f_n -> 0, "detached"; for mu >~ 1e4 the Painleve case, see
    :func:`attraction_upper_limit`). For mu = inf this reproduces :func:`attraction_window_rigid` (eq 26). Later
    steps are not checked: past the first step the post-impact speeds move towards the gait."""
    validate(w)
    ref = sticking_fixed_point(w)

    def backward(th: float) -> bool:
        return step(w, (th, 0.0)).failure == "backward"

    def detached(th: float) -> bool:
        return step(w, (th, 0.0)).failure not in (None, "backward")

    tiny = 1e-9
    lower = _bisect(lambda th: not backward(th), tiny, ref, tol) if backward(tiny) else 0.0
    hi = 2.0 * ref
    while not detached(hi):
        hi *= 1.5
        if hi > 100.0:
            return lower, math.inf
    return lower, _bisect(detached, ref, hi, tol)


@lru_cache(maxsize=64)
def attractors(w: FrictionWheel) -> tuple[Gait, ...]:
    """The stable gaits of types A, B, C and D+ that exist at this mu (cached)."""
    out = []
    for kind in _GAIT_KINDS:
        gait = find_gait(w, kind)
        if gait is not None and gait.kind != "D-" and np.max(np.abs(gait.eigenvalues)) < 1.0:
            out.append(gait)
    return tuple(out)


def longest_period(w: FrictionWheel, mus: Sequence[float]) -> float:
    """The longest period (nondimensional) of the stable gaits of ``w`` at each friction of ``mus`` (0 where there is
    none), and at least the no-slip wheel's sticking gait's (1 if it has none): the time a run of one step needs."""
    periods = [max([g.period for g in attractors(replace(w, mu=float(mu)))], default=0.0) for mu in mus]
    rigid = find_gait(replace(w, mu=math.inf), "A")
    periods.append(rigid.period if rigid is not None else 1.0)
    return max(periods)


def no_gait_reason(w: FrictionWheel) -> str:
    """Why ``w`` has no stable gait of types A-D+ (002 Sec. 3.3): mu below the D branch (the wheel rolls back), or
    none found."""
    edges = gait_boundaries(w.kappa, w.spokes, w.slope)
    if math.isfinite(edges.d_lower) and w.mu < edges.d_lower:
        return (f"mu must be >= {edges.d_lower:.4f} for spokes={w.spokes}, kappa={w.kappa:g}, slope={w.slope:g} (got "
                f"{w.mu:g}): below the Type D branch no stable gait exists and the wheel rolls back (002 Sec. 3.3)")
    return (f"mu={w.mu:g} has no stable gait of types A-D+ for spokes={w.spokes}, kappa={w.kappa:g}, "
            f"slope={w.slope:g} (the reference finds none; 002 Sec. 3.3): choose another mu or kappa")


def _distance(gait: Gait, z: tuple[float, float]) -> float:
    if gait.kind == "C":
        return max(abs(z[0] - gait.fixed_point[0]), abs(z[1] - gait.fixed_point[1]))
    if gait.kind in ("A", "B"):
        return max(abs(z[0] - gait.fixed_point[0]), abs(z[1]))
    return abs(z[0] - gait.fixed_point[0]) if z[1] > 0 else math.inf


def basin_outcome(
    w: FrictionWheel, theta_dot0: ArrayLike, x_dot0: ArrayLike, max_steps: int = 300, tol: float = 1e-4
) -> tuple[NDArray[np.str_], NDArray[np.int64]]:
    """Outcome of the post-impact state(s) (theta_dot0, x_dot0) (broadcast arrays): the label of the stable gait
    reached ("A", "B", "C", "D+", see :func:`attractors`), a failure ("backward", "detached", "painleve", "impact",
    "chatter") or "unsettled", and the number of steps until the state is within ``tol`` of that gait's fixed point
    (theta_dot and x_dot; theta_dot only for D+) after a step of that type (-1 if none). 002 Sec. 3.4: slip enlarges
    the region of attraction but slows the convergence; both are measured here."""
    th, xd = np.broadcast_arrays(np.asarray(theta_dot0, dtype=float), np.asarray(x_dot0, dtype=float))
    labels = np.empty(th.shape, dtype=object)
    steps = np.full(th.shape, -1, dtype=np.int64)
    gaits = attractors(w)
    for idx in np.ndindex(th.shape):
        z = (float(th[idx]), float(xd[idx]))
        label = "unsettled"
        for k in range(1, max_steps + 1):
            rec = step(w, z)
            if rec.failure is not None:
                label = rec.failure
                break
            z = rec.post
            kind = classify_record(rec)
            hit = [g for g in gaits if g.kind == kind and _distance(g, z) < tol]
            if hit:
                label, steps[idx] = hit[0].kind, k
                break
        labels[idx] = label
    return labels.astype(str), steps


# --- gait-type boundaries in mu (002 Sec. 3.3, Fig. 3.5) --------------------------------------------------------


@dataclass(frozen=True)
class GaitBoundaries:
    """Boundaries in mu for one (kappa, n, alpha) (002 Sec. 3.3; docs/theory/stick-slip.md Secs. 2, 5 for the paper
    set):
    ``ab`` A/B (= max(mu_c, |sigma~|): stick throughout needs both), ``bc`` B/C (the B gait's impact starts to
    slip), ``c_lower`` the lower end of the C branch (continued from B/C; it tends to tan(alpha), where C grazes into
    the D orbit with Delta x_dot = 0, and Newton stops a few 1e-6 above), ``d_sign`` D+/D- (Delta x_dot = 0;
    equals tan(alpha), :func:`d_sign_boundary`), ``d_upper``/``d_lower`` the edges of the D branch (detachment
    above, backward roll below), ``start_slip`` the mu below which the slowest admissible start slips at once
    (:func:`start_slip_threshold`). NaN where a branch is not found."""

    ab: float
    bc: float
    c_lower: float
    d_sign: float
    d_upper: float
    d_lower: float
    start_slip: float


def _d_record(w: FrictionWheel) -> StepRecord | None:
    """The step of the Type D gait at its formal fixed point (:func:`type_d_linear`, exact while the step is a D
    step because the D map is affine in theta_dot^2), or None if that step is not a D step returning to itself."""
    th, _ = type_d_linear(w)
    if not math.isfinite(th):
        return None
    rec = step(w, (th, X_NEUTRAL))
    label = classify_record(rec)
    if label is None or label[0] != "D" or abs(rec.theta_dot - th) > 1e-7 * th:
        return None
    return rec


@lru_cache(maxsize=16)
def gait_boundaries(kappa: float, spokes: int, slope: float, tol: float = 1e-6) -> GaitBoundaries:
    """Locate the gait-type boundaries of :class:`GaitBoundaries` by bisection in mu on the simulator (to ``tol``):
    A/B on whether the eq-16 orbit stays a Type A step; B/C on :func:`find_gait` "B"; C's lower end on
    :func:`find_gait` "C" continued downwards from B/C; the D edges on whether the D fixed point's step is a D step
    (:func:`_d_record`); D+/D- by brentq on its Delta x_dot."""

    def wheel(mu: float) -> FrictionWheel:
        return FrictionWheel(spokes, kappa, slope, mu)

    base = wheel(math.inf)
    validate(base)
    nan = math.nan
    th_a = sticking_fixed_point(base)

    def a_holds(mu: float) -> bool:
        rec = step(wheel(mu), (th_a, 0.0))
        return rec.failure is None and classify_record(rec) == "A"

    sig = abs(impulse_ratio(spokes, kappa))
    ab = _bisect(a_holds, 0.0, 1.5 * max(critical_friction(base)[0], sig) + 1e-3, tol)
    bc = _bisect(lambda mu: find_gait(wheel(mu), "B") is not None, 0.5 * sig, ab * (1 - 1e-4), tol)

    c_lower = nan
    first = find_gait(wheel(bc - 1e-3), "C")
    if first is not None:
        last = [first.fixed_point]

        def c_exists(mu: float) -> bool:
            z_star = _c_fixed_point(wheel(mu), last[0])
            if z_star is not None:
                last[0] = z_star
            return z_star is not None

        hi_c = bc - 1e-3
        while c_exists(hi_c - 0.005) and hi_c > 0.01:
            hi_c -= 0.005
        c_lower = float(_bisect(c_exists, hi_c - 0.005, hi_c, tol))

    def d_exists(mu: float) -> bool:
        return _d_record(wheel(mu)) is not None

    grid = np.linspace(0.01, min(1.4, 1.2 * ab), 30)
    have = [float(mu) for mu in grid if d_exists(mu)]
    if not have:
        return GaitBoundaries(ab, bc, c_lower, nan, nan, nan, start_slip_threshold(base))
    lo_in, hi_in = have[0], have[-1]
    step_mu = float(grid[1] - grid[0])
    d_lower = float(_bisect(d_exists, max(lo_in - step_mu, 1e-6), lo_in, tol)) if lo_in > grid[0] else nan
    d_upper = float(_bisect(lambda mu: not d_exists(mu), hi_in, hi_in + step_mu, tol))

    def dx(mu: float) -> float:
        rec = _d_record(wheel(mu))
        return rec.dx if rec is not None else nan

    d_sign = float(brentq(dx, lo_in, hi_in, xtol=tol)) if dx(lo_in) * dx(hi_in) < 0 else nan
    return GaitBoundaries(ab, bc, c_lower, d_sign, d_upper, d_lower, start_slip_threshold(base))
