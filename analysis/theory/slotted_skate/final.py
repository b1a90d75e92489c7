"""Reversals and final states of the slotted skate once its rotation has decayed (000 eqs B.6-B.12).

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*, Appendix B: the number of impacts before a velocity reversal (B.6)/(B.7), the final energy (B.10)
and speed (B.12) of a motion that never reverses again, and the final state by iterating the exact map (derivation
page docs/theory/slotted-skate.md, Secs. 2 and 5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mjpoincare.analysis.theory.slotted_skate.map import initial_state, return_map
from mjpoincare.analysis.theory.slotted_skate.params import SlottedSkate, _is_front, validate
from mjpoincare.analysis.theory.slotted_skate.straight_stability import C1, sigma4

#: |H| below which :func:`final_state` considers the rotation decayed (relative to sqrt(2 E)).
FINAL_H_TOL = 1e-15


@dataclass(frozen=True)
class FinalState:
    """Limit of the motion once all rotation has decayed (see :func:`final_state`).

    ``V_f`` final slot speed (sign = final direction), ``E_f`` = V_f^2/2, ``theta_f`` final heading, ``reversals``
    number of stances with a velocity reversal, ``impacts`` impacts iterated until |H| was negligible.
    """

    V_f: float
    E_f: float
    theta_f: float
    reversals: int
    impacts: int


def collisions_before_reversal(sk: SlottedSkate, D: float, E: float, H: float) -> int:
    """Number n of further non-reversing impacts before the stance that reverses (B.6)/(B.7), for L0 > 0 or
    L0 < -Delta (one turning point at most): n = floor(ln[1 + (1 - C2^2)(r (1 + L_a^2) - 1)/C3] / ln C2^2) with
    r = 2E/H^2, L_a the current peg's L, C2 the non-reversing (B.3) value and
    C3 = sgn(V) Delta (2 L0 + Delta)/(1 + L_b^2). Returns -1 if the log argument is <= 0 (no reversal ever)."""
    validate(sk)
    if -sk.Delta <= sk.L0 <= 0.0:
        raise ValueError(f"(B.6) needs L0 > 0 or L0 < -Delta (got L0={sk.L0!r}, Delta={sk.Delta!r})")
    front = _is_front(sk, D)
    la, lb = (sk.L_front, sk.L_rear) if front else (sk.L_rear, sk.L_front)
    c2 = sigma4(sk, front)
    c3 = (1.0 if front else -1.0) * sk.Delta * (2.0 * sk.L0 + sk.Delta) / (1.0 + lb * lb)
    arg = 1.0 + (1.0 - c2 * c2) * (2.0 * E / (H * H) * (1.0 + la * la) - 1.0) / c3
    if not arg > 0.0:
        return -1
    return math.floor(math.log(arg) / math.log(c2 * c2))


def final_energy(sk: SlottedSkate, E: float, H: float, forward: bool) -> float:
    """E_f = E + C1 H^2/(1 - C2^2) (B.10) for a motion that never reverses again; needs |C2| = |sigma4| < 1."""
    c2 = sigma4(sk, forward)
    if not abs(c2) < 1.0:
        raise ValueError(f"B.10 needs |sigma4| < 1 (got {c2!r})")
    return E + C1(sk, forward) * H * H / (1.0 - c2 * c2)


def final_speed_b12(sk: SlottedSkate, V: float, Omega: float) -> float:
    """Final slot speed after all rotation decays from the post-impact (V, Omega) without further reversals (B.12):
    V_f^2 = V^2 + (1 + L0^2)[1 - Delta/((L0 + Delta)(2 + (L0 + Delta)(2 L0 + Delta)))] Omega^2 for V > 0, and by the
    reflection L0 -> -(L0 + Delta), V -> -V (derivation page Sec. 2) for V < 0:
    V_f^2 = V^2 + (1 + (L0 + Delta)^2)[1 + Delta/(L0 (2 + L0 (2 L0 + Delta)))] Omega^2. Returns V_f with V's sign."""
    validate(sk)
    l0, dl = (sk.L0, sk.Delta) if V > 0.0 else (-(sk.L0 + sk.Delta), sk.Delta)
    bracket = 1.0 - dl / ((l0 + dl) * (2.0 + (l0 + dl) * (2.0 * l0 + dl)))
    vf2 = V * V + (1.0 + l0 * l0) * bracket * Omega * Omega
    return math.copysign(math.sqrt(vf2), V)


def final_state(
    sk: SlottedSkate, V0: float, Omega0: float, theta0: float = 0.0, max_impacts: int = 100000
) -> FinalState:
    """Iterate the exact map from (V0, Omega0, theta0) until |H| <= FINAL_H_TOL sqrt(2E) (then theta has converged
    and no reversal is possible), counting reversals; E_f from (B.10) at that point (equal to E to O(H^2)).
    Raises ``RuntimeError`` if |H| has not decayed after ``max_impacts`` impacts (an unstable or spinning case)."""
    q = initial_state(sk, V0, Omega0, theta0)
    reversals = 0
    for k in range(max_impacts + 1):
        if abs(q.H_plus) <= FINAL_H_TOL * math.sqrt(2.0 * q.E_plus):
            fwd = _is_front(sk, q.D_plus)
            e_f = final_energy(sk, q.E_plus, q.H_plus, fwd) if abs(sigma4(sk, fwd)) < 1.0 else q.E_plus
            v_f = math.copysign(math.sqrt(2.0 * e_f), 1.0 if fwd else -1.0)
            return FinalState(V_f=v_f, E_f=e_f, theta_f=q.theta_plus, reversals=reversals, impacts=k)
        q = return_map(sk, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
        reversals += int(q.reversed)
    raise RuntimeError(f"rotation did not decay within {max_impacts} impacts (|H| = {abs(q.H_plus)!r})")
