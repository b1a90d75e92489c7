"""Parameters of the rimless wheel with Coulomb friction, its nondimensional units and admissible slopes.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3 eq 11 (n spokes, kappa = I_c/(m l^2), slope alpha, mu), eq 14 (beta), eqs 18/21 (the slope window of a
contact-preserving sticking gait, computed by :mod:`mjpoincare.analysis.theory.rimless_wheel`) and the rate omega_c
below eq 12 (002's "tau_c"); conventions in :mod:`mjpoincare.analysis.theory.rimless_wheel_friction`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory import rimless_wheel as rw

RTOL = 1e-11
ATOL = 1e-12
#: Largest theta step (rad) of a slipping phase in the fast method (grazing trap, docs/theory/stick-slip.md Sec. 4).
SLIP_MAX_STEP = 0.05
#: Post-impact slip speed used to shoot Type D gaits: x_dot is neutral while it stays > 0 (002 Sec. 3.3).
X_NEUTRAL = 10.0
#: |x_dot| below which a post-impact state counts as not slipping.
X_TOL = 1e-12


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
