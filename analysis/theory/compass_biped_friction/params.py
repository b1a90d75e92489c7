"""Parameters of the compass biped with Coulomb friction and their admissible ranges (002 Sec. 4.1, eq 27).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 4.1 (the paper's values are the defaults) and eq 27 (the mass moments K, b, M_tot); the model and its conventions
are described in :mod:`mjpoincare.analysis.theory.compass_biped_friction`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]


#: Number of physical coordinates (theta1, theta2, x, y); the model carries 2 more (clock, work accumulator).
NQ = 4


@dataclass(frozen=True)
class FrictionBiped:
    """Compass biped of 002 Sec. 4.1 (paper values as defaults): leg length ``l`` (m), leg point mass ``m`` (kg)
    at ``d`` (m) from the foot, hip mass ``m_h`` (kg), gravity ``g`` (m/s^2), slope alpha (rad; 0 = level ground of
    002 Sec. 5), Coulomb coefficient ``mu`` (``math.inf`` = no slip)."""

    l: float = 1.6
    d: float = 0.8
    m: float = 4.0
    m_h: float = 2.0
    g: float = 9.8
    slope: float = math.radians(1.0)
    mu: float = math.inf

    @property
    def k(self) -> float:
        """K = d m + l (m + m_h), the stance-leg mass moment of 002 eq 27 (kg m)."""
        return self.d * self.m + self.l * (self.m + self.m_h)

    @property
    def b(self) -> float:
        """Hip-to-swing-mass distance l - d (m)."""
        return self.l - self.d

    @property
    def total_mass(self) -> float:
        """M_tot = 2 m + m_h (kg)."""
        return 2.0 * self.m + self.m_h


def validate(bp: FrictionBiped) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range (002 Sec. 4.1: l > 0, 0 < d < l,
    m, m_h > 0; g > 0; |alpha| < pi/2; mu >= 0, inf allowed)."""
    if not bp.l > 0.0:
        raise ValueError(f"l must be > 0 m (got {bp.l!r})")
    if not 0.0 < bp.d < bp.l:
        raise ValueError(f"d must be in (0, l) = (0, {bp.l!r}) m (got {bp.d!r})")
    for name in ("m", "m_h"):
        if not getattr(bp, name) > 0.0:
            raise ValueError(f"{name} must be > 0 kg (got {getattr(bp, name)!r})")
    if not bp.g > 0.0:
        raise ValueError(f"g must be > 0 m/s^2 (got {bp.g!r})")
    if not abs(bp.slope) < math.pi / 2:
        raise ValueError(f"slope must be in (-pi/2, pi/2) rad (got {bp.slope!r})")
    if not bp.mu >= 0.0:
        raise ValueError(f"mu must be >= 0 (got {bp.mu!r})")
