"""Closed forms of the rimless wheel's sticking gait with Coulomb friction (002 Secs. 3.1-3.2, 3.4).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3.1-3.2 eqs 15-17 (the sticking map, its fixed point and eigenvalue), eq 19 (the contact forces), eqs 22-23 (the
friction ratio along the orbit and mu_c), eq 25 (the sticking-impulse ratio, sign restored) and Sec. 3.4 eq 26 (the
attraction window for mu = inf); plus the limits derived here (derivation page docs/theory/stick-slip.md, Sec. 2).
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory import rimless_wheel as rw
from mjpoincare.analysis.theory.rimless_wheel_friction.params import FrictionWheel, beta, rigid_wheel
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar


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
