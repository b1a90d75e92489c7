"""Parameters of the planar rimless wheel on a slope, their admissible ranges and the regions they fall in.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3; 002 = Gamus & Or (2015),
"Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst., Sec. 3.1. The wheel of 003 Sec. 3.1
(eq 3.1 admissible set) with the hub inertia of 002 Sec. 3.1 (kappa <= 1), the stance rate of 003 eq 3.2 / 002 eq 12,
the impact coefficient of 002 eq 14 (003 eq 3.11) and the step's energy gain K of 003 eq 3.5 / 002 eq 13; conventions
in :mod:`mjpoincare.analysis.theory.rimless_wheel`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Tolerance of the equalities gamma == alpha (region Ω2) and (3.16) with equality (region Ω4).
REGION_TOL = 1e-12


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
