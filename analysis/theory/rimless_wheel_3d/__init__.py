"""Closed-form theory of the 3D rimless spoked wheel rolling down a slope (plastic impacts, pivoting stance foot).

Source: 001 = Coleman, Chatterjee & Ruina (1997), "Motions of a rimless spoked wheel: a simple 3D system with
impacts", Dyn. Stab. Sys. 12(3) (several printed equations are illegible; every formula here was re-derived, see the
derivation page ``docs/theory/rimless-wheel-3d.md``). Equation numbers are the paper's.

Units and conventions: m = l = g = 1, so rates are in sqrt(g/l) and times in sqrt(l/g). The wheel is one rigid
planar body (hub + n massless spokes of length 1, point feet); ``J`` = D/(m l^2) is the polar (axle) moment, the
in-plane (diametral) central moments are J/2 (perpendicular-axis theorem, eq 1 read as D/2). Slope frame: x down
the fall line, y across the slope, z normal; gravity (sin alpha, 0, -cos alpha). Orientation by 3-1-2 Euler
angles R = Rz(psi) Rx(phi) Ry(theta): psi heading, phi bank (about the rolling direction x' = (cos psi, sin psi,
0)), theta pitch (about the axle y'' = (-sin psi cos phi, cos psi cos phi, sin phi)). The hub is at P + R e3
(P the stance foot); rolling forward is theta_dot > 0. A stance runs theta: -beta -> +beta, beta = pi/n, and
the next foot touches exactly at theta = +beta whatever psi and phi are (every foot height is cos(phi) times its
in-plane height), after which theta resets to -beta (eqs 4-5, 44). Rates are ordered (psi_dot, phi_dot,
theta_dot), the paper's state is q = (psi, phi, theta, psi_dot, phi_dot, theta_dot) (eq 2).

Derivations (re-done here, all checked against the independent hybrid integrator
:mod:`mjpoincare.analysis.theory.rimless_wheel_3d.hybrid`):

* Planar cycle at heading psi (eqs 12-13): the axle y'' is horizontal iff g . y'' = 0, i.e.
  tan phi = -sin psi tan alpha. Then gravity lies in the wheel plane and its component along the ground line x'
  is sin alpha cos psi = sin gamma (effective slope). The hub height along the in-plane "up" is cos(theta + gamma),
  so the stance has the energy integral (1/2)(1+J) theta_dot^2 + cos(theta + gamma) = const.
* Impact (eq 6): angular momentum about the new foot is conserved. Resolved along the axle a, the new spoke u and
  w = a x u: omega_a+ = mu omega_a-, omega_u+ = omega_u- (needs J > 0), omega_w+ = ((J/2 + cos 2beta) omega_w-
  - sin 2beta omega_u-)/(J/2 + 1). Converted to Euler rates at theta = beta this is T(phi) of
  :func:`impact_matrix`.
* Planar return map (eq 11): omega_{k+1}^2 = mu^2 (omega_k^2 + 4 sin beta sin gamma/(1+J)), affine in the
  squared rate, multiplier mu^2 (= lambda2 of the 3D map).

Corrections (where this module disagrees with the paper as printed; the derivation page carries them too):

* Eq 1: the in-plane central moment is D/2 (printed "6/4 D"); the example needs J = 1/2.
* Eq 6: the rate order is (psi_dot, phi_dot, theta_dot), and in the R = Rz Rx Ry convention the (2,1) entry is
  -2 sin(2pi/n) cos(phi)/(2+J) and the (3,1) entry +2 J sin^2(pi/n) sin(phi)/((1+J)(2+J)). The paper's printed
  entries use the diametral moment K = J/2: 1 + (2/(1+K))(cos^2(pi/n) - 1) = 1 - 4 sin^2(pi/n)/(2+J) and
  mu = 1 + (2/(1+2K))(cos^2(pi/n) - 1). This agrees with the derivation page (derived by hand and checked to 1e-12
  against the vector law in the tests).
* Eq 10: the last term has a minus sign: 1 - cos(beta) cos(gamma_c) - ((1+mu^2)/(1-mu^2)) sin(beta) sin(gamma_c)
  = 0 (it is "post-impact energy just clears the top" with the fixed point of eq 11 substituted).
* Eq 12: tan phi* = sin psi tan alpha in magnitude; the sign in this convention is negative
  (phi* = -atan(sin psi tan alpha)). Eq 13: sin gamma = sin alpha cos psi (the printed sinh does not hold).
* Eq 32: lambda2 ~ 1 - 4 pi^2 eps^2/(1+J) (printed "1 - (4 eps^2 + 2 eps^4)"); the pair is
  1 + f1 eps^2/2 +- eps sqrt(f0) with the f0, f1, f2 of :func:`asymptotic_coefficients`. Only f0 is derived
  here analytically (rolling-disk wobble, see its docstring); f1 and f2 are the derivation page's forms, identified from
  integrations. This module does not derive them in closed form but re-identifies all three independently: a
  Richardson extrapolation of the hybrid integrator's eigenvalues at n = 32, 64, 128 reproduces f0, f1, f2 to
  < 1e-4 relative at (J, g1) = (1/2, 1.902) and (1, 3) (1.5e-3 near the pole at (1/4, 1.5)); the error of eq 32
  falls like n^-3 and Table 2's asymptotic row is reproduced.
* Derivation page, Sec. 1 and the Pt/Pn column of its Sec. 4 table: |P_t|/P_n = sin(beta) cos(beta)/(J + cos^2 beta)
  is the impulse ratio in the wheel plane (along the ground line / along the in-plane normal n'). On a banked cycle
  (psi != 0) n' is tilted by phi* from the slope normal, so the friction the slope must supply at the impact is
  sqrt(rho^2 + sin^2 phi*)/cos phi* (:func:`impact_friction_ratio`): 0.1366, not 0.1309, for the Table-2 case
  (0.1357, 0.0683, 0.1355, 0.2056 for the other banked rows; the page states both). The rows with psi = 0 agree.
  Everything else on the page that this module checks agrees; in addition validity needs mu > 0 (spokes = 3 with
  J <= 1/2 sends the wheel backwards at every impact).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import quad
from scipy.optimize import brentq


@dataclass(frozen=True)
class RimlessWheel3D:
    """3D rimless wheel (001 Sec. 2-3), nondimensional m = l = g = 1.

    ``spokes`` n >= 3, ``slope`` alpha in (0, pi/2) rad, ``J`` = D/(m l^2) > 0 the polar moment of inertia about
    the axle (the paper's example: J = 1/2, a uniform disk of radius l), ``heading`` psi in (-pi/2, pi/2) rad
    (0 = straight down the fall line).
    """

    spokes: int
    slope: float
    J: float = 0.5
    heading: float = 0.0

    @property
    def beta(self) -> float:
        """Half the angle between neighbouring spokes, beta = pi/n (001 Sec. 2)."""
        return math.pi / self.spokes

    @property
    def mu(self) -> float:
        """Collision coefficient mu = (J + cos 2beta)/(1 + J) (001 eqs 6, 11, 14)."""
        return collision_coefficient(self.spokes, self.J)

    @property
    def gamma(self) -> float:
        """Effective slope in the wheel plane, asin(sin alpha cos psi) (001 eq 13)."""
        return effective_slope(self.slope, self.heading)

    @property
    def bank(self) -> float:
        """Bank of the planar cycle at this heading, -atan(sin psi tan alpha) (001 eq 12)."""
        return planar_bank(self.slope, self.heading)


class StabilityThresholds(NamedTuple):
    """Large-n stability thresholds of the planar cycle (001 eqs 33-36, re-derived).

    ``disk`` and ``lambda5`` bound alpha1 cos psi = n alpha cos psi (eqs 33, 34); ``rate2_disk`` and
    ``rate2_lambda5`` are the same bounds on theta_dot*^2 (eqs 35, 36). Stable 3D rolling needs both, and for
    J > 0 the ``lambda5`` one is the stricter.
    """

    disk: float
    lambda5: float
    rate2_disk: float
    rate2_lambda5: float


def _as_out(out: NDArray[np.float64]) -> NDArray[np.float64] | float:
    return float(out) if np.ndim(out) == 0 else out


def collision_coefficient(spokes: int, J: float) -> float:
    """mu = (J + cos(2 pi/n))/(1 + J) = 1 + (2/(1+J))(cos^2(pi/n) - 1), the (3,3) entry of T (001 eqs 6, 11, 14).

    Angular momentum about the new foot, axle component: (1+J) theta_dot+ = (J + cos 2beta) theta_dot-
    (the hub's velocity turns by 2 beta). Planar results are valid for J >= 0.
    """
    if spokes < 3 or J < 0.0:
        raise ValueError(f"collision_coefficient needs spokes >= 3 and J >= 0 (got spokes={spokes}, J={J})")
    return (J + math.cos(2.0 * math.pi / spokes)) / (1.0 + J)


def effective_slope(slope: float, heading: float) -> float:
    """gamma = asin(sin alpha cos psi), the slope seen in the wheel plane at heading psi (001 eq 13, corrected)."""
    return math.asin(math.sin(slope) * math.cos(heading))


def planar_bank(slope: float, heading: float) -> float:
    """Bank phi* that makes the wheel plane contain gravity: phi* = -atan(sin psi tan alpha) (001 eq 12).

    The axle y'' = (-sin psi cos phi, cos psi cos phi, sin phi) is horizontal iff
    sin alpha (-sin psi cos phi) - cos alpha sin phi = 0. The paper prints the magnitude (its phi has the
    opposite sign to R = Rz(psi) Rx(phi) Ry(theta)).
    """
    return -math.atan(math.sin(heading) * math.tan(slope))


def _gain(w: RimlessWheel3D) -> float:
    """Squared-rate gain of one stance, 4 sin beta sin gamma/(1+J) (energy integral between theta = -+beta)."""
    return 4.0 * math.sin(w.beta) * math.sin(w.gamma) / (1.0 + w.J)


def _formal_rate2(w: RimlessWheel3D) -> float:
    """theta_dot*^2 = mu^2 gain/(1 - mu^2), the fixed point of the affine map of eq 11 (may not be reachable)."""
    mu2 = w.mu**2
    return mu2 * _gain(w) / (1.0 - mu2)


def _top_margin(w: RimlessWheel3D, rate2: float) -> float:
    """(1/2)(1+J) rate2 + cos(gamma - beta) - 1: > 0 iff a stance started at theta = -beta with theta_dot^2 = rate2
    passes the top theta = -gamma (always true for gamma >= beta)."""
    if w.gamma >= w.beta:
        return math.inf
    return 0.5 * (1.0 + w.J) * rate2 + math.cos(w.gamma - w.beta) - 1.0


def planar_cycle_exists(w: RimlessWheel3D) -> bool:
    """Whether the planar rolling cycle exists: mu > 0 and the fixed point of eq 11 clears the top of the stance
    (equivalent to gamma > gamma_c of eq 10, corrected; 001 Sec. 5)."""
    return w.mu > 0.0 and _top_margin(w, _formal_rate2(w)) > 0.0


def planar_pitch_rate(w: RimlessWheel3D) -> float:
    """theta_dot* just after impact on the planar cycle (001 eq 14, re-derived):

    theta_dot*^2 = 4 mu^2 sin(beta) sin(gamma)/((1+J)(1-mu^2)) = mu^2 (1+J) sin(gamma)/(sin(beta)(J + cos^2 beta)).

    NaN if the cycle does not exist (:func:`planar_cycle_exists`). Valid for J >= 0 (planar).
    """
    if not planar_cycle_exists(w):
        return math.nan
    return math.sqrt(_formal_rate2(w))


def pre_impact_pitch_rate(w: RimlessWheel3D) -> float:
    """theta_dot just before impact on the planar cycle, theta_dot*/mu (001 eqs 6, 14)."""
    return planar_pitch_rate(w) / w.mu


def pitch_rate_at(w: RimlessWheel3D, theta: ArrayLike) -> NDArray[np.float64] | float:
    """theta_dot(theta) on the planar cycle, from the energy integral (001 Sec. 5, eq 14):

    theta_dot^2 = theta_dot*^2 + 2 (cos(gamma - beta) - cos(theta + gamma))/(1+J), theta in [-beta, beta].
    """
    th = np.asarray(theta, dtype=float)
    sq = planar_pitch_rate(w) ** 2 + 2.0 * (math.cos(w.gamma - w.beta) - np.cos(th + w.gamma)) / (1.0 + w.J)
    with np.errstate(invalid="ignore"):
        return _as_out(np.sqrt(sq))


def midstance_pitch_rate(w: RimlessWheel3D) -> float:
    """theta_dot at mid-stance theta = 0 on the planar cycle (energy integral, 001 Sec. 5)."""
    return float(pitch_rate_at(w, 0.0))


def step_period(w: RimlessWheel3D) -> float:
    """Step time of the planar cycle, T = int_{-beta}^{beta} dtheta/theta_dot(theta) (001 eq 15, no closed form).

    NaN if the cycle does not exist.
    """
    if not planar_cycle_exists(w):
        return math.nan

    def inv_rate(th: float) -> float:
        return 1.0 / float(pitch_rate_at(w, th))

    points = [-w.gamma] if w.gamma < w.beta else None
    value, _ = quad(inv_rate, -w.beta, w.beta, points=points, epsabs=1e-14, epsrel=1e-12, limit=200)
    return float(value)


def existence_threshold(spokes: int, J: float) -> float:
    """gamma_c, the least effective slope with a planar rolling cycle: root in (0, beta) of (001 eq 10, corrected)

    1 - cos(beta) cos(gamma_c) - ((1 + mu^2)/(1 - mu^2)) sin(beta) sin(gamma_c) = 0.

    It is "the cycle's post-impact energy (1/2)(1+J) theta_dot*^2 just lifts the hub over the top" with
    theta_dot*^2 of eq 14. NaN if mu <= 0 (no forward cycle at any slope). Large n: gamma_c ~ (pi/n)^3/(1+J).
    """
    mu = collision_coefficient(spokes, J)
    if mu <= 0.0:
        return math.nan
    beta = math.pi / spokes
    c = (1.0 + mu * mu) / (1.0 - mu * mu)

    def lhs(gamma: float) -> float:
        return 1.0 - math.cos(beta) * math.cos(gamma) - c * math.sin(beta) * math.sin(gamma)

    return float(brentq(lhs, 0.0, beta, xtol=1e-16, rtol=1e-15))


def validate(w: RimlessWheel3D) -> None:
    """Raise ``ValueError`` naming the parameter and the bound (001 Sec. 2-5).

    spokes >= 3 (integer), 0 < slope < pi/2, J > 0 (J = 0 makes I_C singular about the spoke axis and the 3D
    impact ill-posed), |heading| < pi/2, mu > 0 (else every impact reverses the rolling) and effective slope
    gamma > gamma_c (eq 10 corrected; below it the wheel rocks to a stop).
    """
    if isinstance(w.spokes, bool) or not isinstance(w.spokes, (int, np.integer)) or w.spokes < 3:
        raise ValueError(f"spokes: must be an integer >= 3 (got {w.spokes!r})")
    if not 0.0 < w.slope < math.pi / 2:
        raise ValueError(f"slope: must be in (0, pi/2) rad (got {w.slope!r})")
    if not w.J > 0.0:
        raise ValueError(f"J: must be > 0 (got {w.J!r}; J = 0 makes the 3D impact ill-posed)")
    if not abs(w.heading) < math.pi / 2:
        raise ValueError(f"heading: must be in (-pi/2, pi/2) rad (got {w.heading!r})")
    if not w.mu > 0.0:
        bound = -math.cos(2.0 * w.beta)
        raise ValueError(f"J: collision coefficient mu = {w.mu:.4g} <= 0 for spokes={w.spokes} (needs J > {bound:.4g})")
    gamma_c = existence_threshold(w.spokes, w.J)
    if not w.gamma > gamma_c:
        raise ValueError(
            f"slope: effective slope {w.gamma:.4g} below the existence threshold {gamma_c:.4g} "
            f"for spokes={w.spokes}, J={w.J:g}, heading={w.heading:g}"
        )


def impact_matrix(spokes: int, J: float, bank: float) -> NDArray[np.float64]:
    """T(phi) of 001 eq 6 (reconstructed): Euler rates (psi_dot, phi_dot, theta_dot)+ = T (...)- at theta = pi/n.

    With s = sin(pi/n)::

        T = [[1 - 4 s^2/(2+J),                      0, 0 ],
             [-2 sin(2 pi/n) cos(phi)/(2+J),         1, 0 ],
             [2 J s^2 sin(phi)/((1+J)(2+J)),         0, mu]]

    Derived from the body-frame law (module docstring): omega . n' (n' the in-plane normal to the ground line) is
    scaled by (J + 2 cos 2beta)/(J + 2) = 1 - 4 s^2/(2+J), omega . x' loses 2 sin 2beta/(2+J) times omega . n', the
    axle rate is scaled by mu; then psi_dot = omega.n'/cos(phi), phi_dot = omega.x',
    theta_dot = omega.y'' - psi_dot sin(phi). Independent of psi.
    """
    if J <= 0.0:
        raise ValueError(f"J: must be > 0 for the 3D impact (got {J!r})")
    beta = math.pi / spokes
    s2 = math.sin(beta) ** 2
    mu = collision_coefficient(spokes, J)
    return np.array(
        [
            [1.0 - 4.0 * s2 / (2.0 + J), 0.0, 0.0],
            [-2.0 * math.sin(2.0 * beta) * math.cos(bank) / (2.0 + J), 1.0, 0.0],
            [2.0 * J * s2 * math.sin(bank) / ((1.0 + J) * (2.0 + J)), 0.0, mu],
        ]
    )


def impact_friction_ratio(w: RimlessWheel3D) -> float:
    """|P_t|/P_n at the impact of the planar cycle, in the SLOPE frame (001 Sec. 3.2.2 plastic impact; the paper
    assumes enough friction and prints no number).

    In the wheel plane the hub velocity turns from theta_dot- (cos b, -sin b) to mu theta_dot- (cos b, sin b)
    (components along the ground line x' and the in-plane normal n'), so the in-plane ratio is
    rho = cos(b)(1 - mu)/(sin(b)(1 + mu)) = sin(b) cos(b)/(J + cos^2 b). The wheel plane is banked by phi*
    (eq 12) and n' = (sin psi sin phi, -cos psi sin phi, cos phi), so on the slope
    |P_t|/P_n = sqrt(rho^2 + sin^2 phi*)/cos phi*. Independent of the speed.
    """
    b = w.beta
    rho = math.sin(b) * math.cos(b) / (w.J + math.cos(b) ** 2)
    phi = w.bank
    return math.hypot(rho, math.sin(phi)) / math.cos(phi)


def planar_return_map(w: RimlessWheel3D, rate2: ArrayLike) -> NDArray[np.float64] | float:
    """Exact planar return map on squared post-impact rates (001 eq 11, re-derived):

    theta_dot_{k+1}^2 = mu^2 (theta_dot_k^2 + 4 sin(beta) sin(gamma)/(1+J)).

    Energy integral over theta: -beta -> beta, then the impact theta_dot+ = mu theta_dot-. NaN where the stance
    does not pass the top (the wheel rocks back) or rate2 < 0.
    """
    r2 = np.asarray(rate2, dtype=float)
    ok = r2 >= 0.0
    if w.gamma < w.beta:
        ok &= 0.5 * (1.0 + w.J) * r2 + math.cos(w.gamma - w.beta) - 1.0 > 0.0
    return _as_out(np.where(ok, w.mu**2 * (r2 + _gain(w)), np.nan))


def midstance_return_map(w: RimlessWheel3D, rate: ArrayLike) -> NDArray[np.float64] | float:
    """The planar map (001 eq 11) on mid-stance pitch rates theta_dot(0): the energy integral over theta: -beta -> 0
    adds lift = theta_dot(0)^2 - theta_dot+^2 = 2 (cos(gamma - beta) - cos gamma)/(1 + J) to a squared post-impact
    rate, so theta_dot(0)_k+1 = sqrt(planar_return_map(theta_dot(0)_k^2 - lift) + lift)."""
    lift = 2.0 * (math.cos(w.gamma - w.beta) - math.cos(w.gamma)) / (1.0 + w.J)
    return _as_out(np.sqrt(planar_return_map(w, np.asarray(rate, dtype=float) ** 2 - lift) + lift))


def _g1(w: RimlessWheel3D) -> float:
    """alpha1 cos psi with alpha1 = n alpha (001 eq 17 scaling, eps = 1/n)."""
    return w.spokes * w.slope * math.cos(w.heading)


def asymptotic_coefficients(w: RimlessWheel3D) -> tuple[float, float, float]:
    """(f0, f1, f2) of 001 eq 32 with g1 = alpha1 cos psi = n alpha cos psi (docs/theory/rimless-wheel-3d.md, Sec. 3):

    f0 = 8 pi^2 (pi - 2(1+J) g1)/((2+J) g1),
    f1 = -(4 pi^2/(2+J)) (J g1^2 + 2 X^2)/(g1 X),  X = 2(1+J) g1 - pi,
    f2 = (4 pi^2/(2+J)) ((2+J) g1 - pi)/X.

    f0 is the rolling-disk wobble: the lean of a disk rolling at Omega0^2 = g1/pi obeys
    (1 + J/2) phi'' + (2(1+J) Omega0^2 - 1) phi = 0, and -f0 eps^2 is (wobble frequency x step time
    2 pi eps/Omega0)^2. f1, f2 are the derivation page's forms identified from integrations extrapolated to n -> inf
    (re-checked by Richardson extrapolation in the tests). NaN at the pole X = 0.
    """
    g1 = _g1(w)
    J = w.J
    x = 2.0 * (1.0 + J) * g1 - math.pi
    c = 4.0 * math.pi**2 / (2.0 + J)
    f0 = 8.0 * math.pi**2 * (math.pi - 2.0 * (1.0 + J) * g1) / ((2.0 + J) * g1)
    if x == 0.0:
        return f0, math.nan, math.nan
    f1 = -c * (J * g1**2 + 2.0 * x**2) / (g1 * x)
    f2 = c * ((2.0 + J) * g1 - math.pi) / x
    return f0, f1, f2


def asymptotic_eigenvalues(w: RimlessWheel3D) -> NDArray[np.complex128]:
    """Eigenvalues lambda0..lambda5 of the 6x6 post-impact Jacobian for many spokes, 001 eq 32 (eps = 1/n):

    [lambda0, lambda1, lambda2, lambda3, lambda4, lambda5] =
    [0, 1, 1 - 4 pi^2 eps^2/(1+J), 1 + f1 eps^2/2 + eps sqrt(f0), 1 + f1 eps^2/2 - eps sqrt(f0), 1 - f2 eps^2].

    lambda0 = 0 (the 6-D section), lambda1 = 1 (heading family), lambda2 the planar mu^2 to O(eps^2),
    lambda3,4 the wobble pair: for f0 < 0 lambda3 has Im > 0 and lambda4 = conj(lambda3); for f0 > 0 both are real
    and lambda3 > lambda4. Errors are O(eps^3).
    """
    validate(w)
    f0, f1, f2 = asymptotic_coefficients(w)
    eps = 1.0 / w.spokes
    root = eps * np.sqrt(complex(f0))
    centre = 1.0 + 0.5 * f1 * eps**2
    lam2 = 1.0 - 4.0 * math.pi**2 * eps**2 / (1.0 + w.J)
    return np.array([0.0, 1.0, lam2, centre + root, centre - root, 1.0 - f2 * eps**2], dtype=complex)


def stability_thresholds(J: float) -> StabilityThresholds:
    """Large-n stability thresholds (001 eqs 33-36, re-derived from eq 32):

    (33) f0 < 0 <=> alpha1 cos psi > pi/(2(1+J)) <=> (35) theta_dot*^2 > 1/(2(1+J)) (rolling-disk criterion);
    (34) f2 > 0 <=> alpha1 cos psi > pi/(2+J)     <=> (36) theta_dot*^2 > 1/(2+J).

    Given (33), |lambda3,4| < 1 follows: f1 + |f0| = -4 pi^2 J g1/((2+J)(2(1+J) g1 - pi)) < 0.
    """
    if not J > 0.0:
        raise ValueError(f"J: must be > 0 (got {J!r})")
    return StabilityThresholds(
        disk=math.pi / (2.0 * (1.0 + J)),
        lambda5=math.pi / (2.0 + J),
        rate2_disk=1.0 / (2.0 * (1.0 + J)),
        rate2_lambda5=1.0 / (2.0 + J),
    )


def minimum_stable_slope_asymptotic(spokes: int, J: float, heading: float = 0.0) -> float:
    """alpha_min ~ pi/((2+J) n cos psi): least slope for stable 3D rolling at large n (001 eqs 34/36).

    Asymptotic only: the exact thresholds are higher at finite n (derivation page Sec. 3: n alpha_crit = 1.48537,
    1.30927, 1.26938, 1.25920 for n = 8, 16, 32, 64 at psi = 0, J = 1/2, against pi/2.5 = 1.25664).
    """
    if spokes < 3 or not abs(heading) < math.pi / 2:
        raise ValueError(f"need spokes >= 3 and |heading| < pi/2 (got spokes={spokes}, heading={heading})")
    return stability_thresholds(J).lambda5 / (spokes * math.cos(heading))
