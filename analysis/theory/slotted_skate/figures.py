"""The slotted skate's results that the return map's checks do not state directly (000 Fig. 2(b), Fig. 3, Fig. 10,
eqs 3.8, B.8, B.13, B.16): the unstable bands of a long slot, the symmetric skate's basins, the spinning saddle, the
two turning points and the period-2 limit of a vanishing radius of gyration.

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*; derivation page docs/theory/slotted-skate.md (Secs. 2 and 5: B.8 reads max, not min).
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.slotted_skate.params import SlottedSkate, validate
from mjpoincare.analysis.theory.slotted_skate.straight_stability import C1, sigma4


def _band_product(x: float, forward: bool) -> float:
    """The product whose negative half is twice the band's kappa: (1 + 2x)(1 + x) (V > 0, 3.11) or x (1 + 2x)
    (V < 0, 3.12), x = L0/Delta."""
    return (1.0 + 2.0 * x) * (1.0 + x) if forward else x * (1.0 + 2.0 * x)


def band_edge_delta(x: float, forward: bool) -> float:
    """The slot length Delta at which the straight motion at x = L0/Delta turns unstable, sigma4 = -1 (the edge of the
    unstable band of 000 Fig. 2(b)): 2 kappa + (1 + 2x)(1 + x) = 0 for V* > 0 (3.11), 2 kappa + x (1 + 2x) = 0 for
    V* < 0 (3.12), kappa = 1/Delta^2; longer slots are unstable. Raises ValueError where x has no band (the product
    is >= 0: -1/2 <= x or x <= -1 forward, -1/2 <= x <= 0 fails backward)."""
    product = _band_product(x, forward)
    if not product < 0.0:
        raise ValueError(f"x = {x!r} has no unstable band for V* {'> 0' if forward else '< 0'} (3.11)-(3.12)")
    return 1.0 / math.sqrt(-0.5 * product)


def unstable_band(Delta: float, forward: bool) -> tuple[float, float] | None:
    """The band of x = L0/Delta where sigma4 < -1 at slot length Delta (000 Fig. 2(b)): ((-3 - s)/4, (-3 + s)/4) for
    V* > 0 and ((-1 - s)/4, (-1 + s)/4) for V* < 0, s = sqrt(1 - 16/Delta^2); None for Delta <= 4 (no band)."""
    if not Delta > 4.0:
        return None
    s = math.sqrt(1.0 - 16.0 / Delta**2)
    centre = -0.75 if forward else -0.25
    return centre - s / 4.0, centre + s / 4.0


def _symmetric(sk: SlottedSkate) -> None:
    validate(sk)
    if abs(sk.L0 + 0.5 * sk.Delta) > 1e-12 * max(1.0, sk.Delta):
        raise ValueError(f"the symmetric case needs L0 = -Delta/2 (got L0={sk.L0!r}, Delta={sk.Delta!r})")


def spin_boundary_speeds(sk: SlottedSkate, Omega0: float, count: int) -> list[float]:
    """The initial slot speeds V_n > 0, n = 0 .. count - 1, of the symmetric skate (L0 = -Delta/2) that reach the
    spinning equilibrium after n collisions at initial rate Omega0 (B.13):
    (V_n/Omega0)^2 = c'^2 [C2^(2n) - 2 C1 (1 - C2^(2n))/(1 - C2^2)] - c', c' = 1 + L0^2 (decreasing in n)."""
    _symmetric(sk)
    cp, c1, c2 = 1.0 + sk.L0**2, C1(sk, True), sigma4(sk, True)
    out = []
    for n in range(count):
        g = c2 ** (2 * n)
        out.append(abs(Omega0) * math.sqrt(cp * cp * (g - 2.0 * c1 * (1.0 - g) / (1.0 - c2 * c2)) - cp))
    return out


def symmetric_final_speed(sk: SlottedSkate, V0: float, Omega0: float) -> float:
    """Final slot speed of the symmetric skate from (V0, Omega0) (000 Fig. 3, B.12-B.13): |V_f| = |V0|, in V0's
    direction above V_0 and, for |V0| in (V_(k+1), V_k), after k + 1 reversals, (-1)^(k+1) times it. NaN on a
    boundary (the spinning equilibrium). Raises ValueError for V0 = 0 (no slot motion: below every boundary)."""
    if not (V0 != 0.0 and math.isfinite(V0)):
        raise ValueError(f"V0 must be finite and != 0 (got {V0!r})")
    speeds, n = [], 1
    while not speeds or speeds[-1] >= abs(V0):
        speeds = spin_boundary_speeds(sk, Omega0, n)
        n *= 2
    if abs(V0) in speeds:
        return math.nan
    reversals = sum(int(v > abs(V0)) for v in speeds)
    return V0 * (-1.0) ** reversals


def two_turning_point_range(sk: SlottedSkate) -> tuple[float, float]:
    """The range of r = 2E/H^2 in which both roots of (B.5) lie in the slot, one met by each direction of travel: (B.8)
    read with max, max{1/(1 + L0^2), 1/(1 + (L0 + Delta)^2)} < r < 1 (the paper prints min); only -Delta < L0 < 0 has
    one (else the range is empty: low >= 1)."""
    validate(sk)
    if not -sk.Delta < sk.L0 < 0.0:
        return 1.0, 1.0
    return max(1.0 / (1.0 + sk.L_front**2), 1.0 / (1.0 + sk.L_rear**2)), 1.0


def spin_saddle_eigenvalues(Omega_eq: float) -> np.ndarray:
    """Eigenvalues of (3.1) linearised at the spinning equilibrium q_eq = (-L0, 0, theta0 + Omega_eq tau, Omega_eq)
    (000 Sec. 3.1.2, 3.8), sorted: the Jacobian in (D, V, theta, Omega) has rows (0, 1, 0, 0), (Omega_eq^2, 0, 0, 0),
    (0, 0, 0, 1), (0, 0, 0, 0) (L = 0, V = 0), so 0, 0 and -+Omega_eq: a saddle."""
    jac = np.array([[0.0, 1.0, 0.0, 0.0], [Omega_eq**2, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0]])
    return np.sort(np.linalg.eigvals(jac).real)


def period2_multiplier(sk: SlottedSkate) -> float:
    """H after two reversing stances over H before, the flip-flop of 000 Fig. 10: the product of the two reversal
    impacts' C2 (B.4), c^2/[(1 + L0^2)(1 + (L0 + Delta)^2)], c = 1 + L0 (L0 + Delta). It tends to 1 as rho -> 0 at
    fixed l0/delta (lengths / rho grow), the neutral period-2 orbit of B.16 (:func:`period2_rho0_ratios`)."""
    validate(sk)
    return sk.c**2 / ((1.0 + sk.L_front**2) * (1.0 + sk.L_rear**2))


def period2_rho0_ratios(x: float) -> tuple[float, float]:
    """The two impacts' C2 of the flip-flop at rho = 0 (B.16, lengths / delta, x = l0/delta): L0/(L0 + 1) and its
    inverse, product 1 (neutral, 000 Fig. 10)."""
    ratio = x / (x + 1.0)
    return ratio, 1.0 / ratio
