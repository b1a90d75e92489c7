"""Stability of the slotted skate's straight motions and the limit of a short slot (000 eqs 3.9-3.12, 4.1).

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*, eq (3.10) (the eigenvalue sigma4), (3.9) (the entry d theta+/d H), the criteria (3.11)-(3.12) read
as |sigma4| < 1, the per-impact energy coefficient of (B.3), and the smooth-sleigh limit: the exponent of (2.1) and
the series (4.1) with its corrected Delta^2 term (derivation page docs/theory/slotted-skate.md, Secs. 2 and 5).
"""

from __future__ import annotations

import math

from mjpoincare.analysis.theory.slotted_skate.map import impact_coefficients
from mjpoincare.analysis.theory.slotted_skate.params import SlottedSkate, validate


def sigma4(sk: SlottedSkate, forward: bool) -> float:
    """Stability eigenvalue (3.10): [1 + L0 (L0 + Delta)]/[1 + (L0 + Delta)^2] for V* > 0 and
    [1 + L0 (L0 + Delta)]/(1 + L0^2) for V* < 0 (= C2 of the non-reversing impact)."""
    validate(sk)
    l_old = sk.L_rear if forward else sk.L_front
    return sk.c / (1.0 + l_old * l_old)


def C1(sk: SlottedSkate, forward: bool) -> float:
    """Per-impact energy coefficient of the non-reversing stance, E_{k+1} - E_k = C1 H_k^2 (B.3):
    -Delta^2/[2 (1 + (L0+Delta)^2)^2 (1 + L0^2)] for V > 0, ends swapped for V < 0."""
    validate(sk)
    ends = (sk.L_rear, sk.L_front) if forward else (sk.L_front, sk.L_rear)
    return impact_coefficients(sk, *ends)[0]


def dtheta_dH(sk: SlottedSkate, V_star: float) -> float:
    """Jacobian entry d theta+/d H at the straight-motion fixed point (3.9), which the paper leaves implicit:
    [arctan(L0 + Delta) - arctan(L0)]/|V*| (derivation page Sec. 2, derived from B.3 at H = 0), same for both
    directions."""
    validate(sk)
    return (math.atan(sk.L_rear) - math.atan(sk.L_front)) / abs(V_star)


def _criterion(sk: SlottedSkate, forward: bool) -> tuple[bool, bool]:
    """(3.11)/(3.12) with x = L0/Delta, kappa = 1/Delta^2, read as the exact |sigma4| < 1 (derivation page Sec. 5,
    item 7):
    V > 0: sigma4 < 1 iff x > -1, sigma4 > -1 iff 2 kappa + (1 + 2x)(1 + x) > 0;
    V < 0: sigma4 < 1 iff x < 0, sigma4 > -1 iff 2 kappa + x (1 + 2x) > 0."""
    x, kappa = sk.L0 / sk.Delta, 1.0 / sk.Delta**2
    if forward:
        return x > -1.0, 2.0 * kappa + (1.0 + 2.0 * x) * (1.0 + x) > 0.0
    return x < 0.0, 2.0 * kappa + x * (1.0 + 2.0 * x) > 0.0


def stability(sk: SlottedSkate) -> dict[str, object]:
    """Stability of the straight motions (3.11)-(3.12), with sigma4 of (3.10).

    Keys: ``forward``/``backward`` in {"stable", "unstable", "neutral"} from the criteria (neutral: |sigma4| = 1,
    i.e. L0 = -Delta forward, L0 = 0 backward, or the boundary of the second condition); ``sigma4_forward``,
    ``sigma4_backward``; ``wobble_forward``/``wobble_backward`` (sigma4 < 0, iff 1 + L0 (L0 + Delta) < 0: H alternates
    in sign); ``coexistence`` (both stable, Fig. 7).
    """
    validate(sk)
    out: dict[str, object] = {}
    for key, fwd in (("forward", True), ("backward", False)):
        below_one, above_minus_one = _criterion(sk, fwd)
        s4 = sigma4(sk, fwd)
        if below_one and above_minus_one:
            out[key] = "stable"
        elif abs(s4) == 1.0:
            out[key] = "neutral"
        else:
            out[key] = "unstable"
        out[f"sigma4_{key}"] = s4
        out[f"wobble_{key}"] = s4 < 0.0
    out["coexistence"] = out["forward"] == "stable" and out["backward"] == "stable"
    return out


def sleigh_rate(L: float, V_star: float = 1.0) -> float:
    """Stability exponent of the smooth Chaplygin sleigh (2.1): xi4 = -L V*/(1 + L^2) (000 Sec. 2.1)."""
    return -L * V_star / (1.0 + L * L)


def smooth_limit_rate(sk: SlottedSkate, V_star: float = 1.0) -> float:
    """Per-unit-time rate of the discrete skate, xi4 = (V*/Delta) ln sigma4 (4.1), sigma4 of the direction of V*;
    tends to :func:`sleigh_rate` (L0) as Delta -> 0. Raises ``ValueError`` for sigma4 <= 0 (wobble, no log)."""
    s4 = sigma4(sk, V_star > 0.0)
    if not s4 > 0.0:
        raise ValueError(f"sigma4 must be > 0 for a real rate (got {s4!r})")
    return abs(V_star) / sk.Delta * math.log(s4)


def smooth_limit_series(sk: SlottedSkate, V_star: float = 1.0, order: int = 3) -> float:
    """Series (4.1) of :func:`smooth_limit_rate` for V* > 0 up to Delta^(order-1), with the corrected Delta^2 term:
    xi4/V* = -L0/B + (L0^2 - 2) Delta/(2 B^2) - L0 (L0^2 - 6) Delta^2/(3 B^3) + (L0^4 - 12 L0^2 + 2) Delta^3/(4 B^4),
    B = 1 + L0^2 (the paper prints L0^2 - 2 in the Delta^2 term)."""
    validate(sk)
    l0, dl, b = sk.L0, sk.Delta, 1.0 + sk.L0**2
    terms = (
        -l0 / b,
        0.5 * (l0 * l0 - 2.0) / b**2 * dl,
        -l0 * (l0 * l0 - 6.0) / (3.0 * b**3) * dl**2,
        (l0**4 - 12.0 * l0**2 + 2.0) / (4.0 * b**4) * dl**3,
    )
    return V_star * sum(terms[: max(1, min(order, 4))])
