"""Parameters of the passive (or constant-torque) compass-gait biped, their ranges and the benchmark sets.

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4, Sec. 4.1 and Fig. 15 (point
masses m_l on the legs at a from the foot, m_h at the hip; the slope range of eq 4.2; defaults = Fig. 18), and the
benchmark of Goswami, Thuilot & Espiau (1996/1998); conventions and the torques' senses in
:mod:`mjpoincare.analysis.theory.compass_biped`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class CompassBiped:
    """Compass-gait biped parameters (003 Sec. 4.1, Fig. 15; defaults = 003 Fig. 18).

    ``m_h`` hip mass > 0 (kg), ``m_l`` leg point mass > 0 (kg), ``a`` foot-to-leg-mass and ``b`` leg-mass-to-hip
    distances > 0 (m), ``slope`` gamma in (0, pi/2) rad, ``gravity`` g > 0 (m/s^2), constant ``tau_ankle`` and
    ``tau_hip`` (N m; their senses in :mod:`~mjpoincare.analysis.theory.compass_biped`).
    """

    m_h: float = 10.0
    m_l: float = 5.0
    a: float = 0.5
    b: float = 0.5
    slope: float = 0.04
    gravity: float = 9.81
    tau_ankle: float = 0.0
    tau_hip: float = 0.0

    @property
    def l(self) -> float:  # noqa: E743 (the papers' leg length)
        """Leg length l = a + b (003 Sec. 4.1)."""
        return self.a + self.b

    @property
    def total_mass(self) -> float:
        """m_h + 2 m_l (kg)."""
        return self.m_h + 2.0 * self.m_l


def validate(bp: CompassBiped) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range (003 Sec. 4.1; slope range of 003 eq 4.2,
    endpoint 0 excluded because no passive gait exists there)."""
    for name, unit in (("m_h", "kg"), ("m_l", "kg"), ("a", "m"), ("b", "m")):
        value = getattr(bp, name)
        if not value > 0.0:
            raise ValueError(f"{name} must be > 0 {unit} (got {value!r})")
    if not 0.0 < bp.slope < math.pi / 2:
        raise ValueError(f"slope must be in (0, pi/2) rad (got {bp.slope!r})")
    if not bp.gravity > 0.0:
        raise ValueError(f"gravity must be > 0 m/s^2 (got {bp.gravity!r})")


def goswami(slope: float = 0.0523599, g: float = 9.81) -> CompassBiped:
    """Goswami, Thuilot & Espiau (1996/98) benchmark: m_h/m_l = 2, b/a = 1, l = 1, slope 3 deg by default
    (m_l = 5, m_h = 10; the gait and its multipliers do not depend on the mass scale)."""
    return CompassBiped(m_h=10.0, m_l=5.0, a=0.5, b=0.5, slope=slope, gravity=g)


def kisa() -> CompassBiped:
    """The 003 Fig. 18 parameters: m_h = 10, m_l = 5, a = b = 0.5, g = 9.81, gamma = 0.04."""
    return CompassBiped()
