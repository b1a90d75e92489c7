"""Slipping stance and frictional impact of the rimless wheel in closed form (002 Appendix A.3).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Appendix A.3: the slipping stance of eq 42, the sticking impact with pre-impact slip (eq 43, admissibility eq 44 with
the factor 2 restored) and the slipping impact (eq 45, corrected); and, derived here, the affine map of u =
theta_dot^2 over a slip in one direction and the Type D gait it gives (derivation page docs/theory/stick-slip.md,
Secs. 2, 4 and 7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_friction.params import X_NEUTRAL, FrictionWheel, beta
from numpy.typing import NDArray
from scipy.integrate import solve_ivp


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
    """Slipping impact (002 eq 45, corrected; see :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction`), F_t = sign
    mu F_n with sign = s_F = sgn(F_t of the sticking candidate) (-1 for forward slip): with D_s = 2kappa + 1 - cos2phi +
    s_F mu sin2phi, theta_dot^+ = (2kappa - 1 + cos2phi - s_F mu sin2phi)/D_s theta_dot^-,
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
