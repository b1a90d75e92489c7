"""The exact return map of the slotted skate: stance closed forms, plastic peg impact, iteration.

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*, eqs (3.5)-(3.8) and Appendix B: the stance from a slot end in closed form with quadratures (B.1),
its turning points (B.5), the plastic impact at the new peg (3.6)/(3.7) in the unified form of (B.3)/(B.4), and the
map f = h o p of (3.5); corrections on the derivation page docs/theory/slotted-skate.md, Sec. 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mjpoincare.analysis.theory.slotted_skate.params import (
    MapStep,
    SlottedSkate,
    _check_direction,
    stance_invariants,
    validate,
)
from scipy.integrate import quad

#: Relative tolerance of the stance quadratures (B.3)/(B.4).
QUAD_EPSREL = 1e-13


@dataclass(frozen=True)
class StanceResult:
    """One stance from a slot end (see :func:`stance`), closed forms (B.1), (B.5) and quadrature.

    ``D_end`` the slot end where the peg leaves, ``reversed`` True if V changed sign in the stance (the peg left at
    the end where it entered), ``duration`` the stance time in tau, ``dtheta`` the heading change, ``V_end`` and
    ``Omega_end`` the slot speed and angular rate just before the peg leaves.
    """

    D_end: float
    reversed: bool
    duration: float
    dtheta: float
    V_end: float
    Omega_end: float


def _check_ends(sk: SlottedSkate, L_old: float, L_new: float) -> None:
    ends = (sk.L_front, sk.L_rear)
    tol = 1e-12 * max(1.0, abs(sk.L0), sk.Delta)
    if not any(abs(L_old - a) <= tol and abs(L_new - b) <= tol for a, b in (ends, ends[::-1])):
        raise ValueError(f"L_old, L_new must be the two slot ends {ends!r} (got {L_old!r}, {L_new!r})")


def impact_ratio(sk: SlottedSkate, L_new: float) -> float:
    """Omega+/Omega- = [1 + L0 (L0 + Delta)]/(1 + L_new^2) (3.6), L_new = L of the new peg (the slot end opposite
    to the one the old peg left). From H about the new peg: H- = (1 + L_old L_new) Omega-, H+ = (1 + L_new^2) Omega+."""
    return sk.c / (1.0 + L_new * L_new)


def impact_coefficients(sk: SlottedSkate, L_old: float, L_new: float) -> tuple[float, float]:
    """(C1, C2) of the impact on the (E, H) description: E+ = E- + C1 H-^2, H+ = C2 H- with H- about the old peg
    (3.7; unified form of B.3/B.4): C1 = -Delta^2/[2 (1 + L_old^2)^2 (1 + L_new^2)],
    C2 = (1 + L_old L_new)/(1 + L_old^2)."""
    _check_ends(sk, L_old, L_new)
    ko, kn = 1.0 + L_old * L_old, 1.0 + L_new * L_new
    return -0.5 * sk.Delta**2 / (ko * ko * kn), sk.c / ko


def energy_loss(sk: SlottedSkate, H_minus: float, L_old: float, L_new: float) -> float:
    """E+ - E- = -Delta^2 H-^2 / [2 (1 + L_old^2)^2 (1 + L_new^2)] <= 0 (3.7, last bracket corrected), H- about the
    old peg; equal to -Delta^2 Omega-^2 / [2 (1 + L_new^2)], a plastic impact of normal speed Delta Omega- with
    effective mass 1/(1 + L_new^2)."""
    c1, _ = impact_coefficients(sk, L_old, L_new)
    return c1 * H_minus * H_minus


def turning_points(sk: SlottedSkate, E: float, H: float) -> tuple[float, ...]:
    """Slot positions D_c = -L0 +- sqrt(H^2/(2E) - 1) where V = 0 (B.5), restricted to the open slot (0, Delta),
    sorted. Empty if 2E/H^2 >= 1 (3.8) or no root lies inside."""
    lc2 = H * H / (2.0 * E) - 1.0
    if lc2 <= 0.0:
        return ()
    lc = math.sqrt(lc2)
    return tuple(sorted(d for d in (-sk.L0 - lc, -sk.L0 + lc) if 0.0 < d < sk.Delta))


def _quad(f, a: float, b: float) -> float:  # type: ignore[no-untyped-def]
    val, _ = quad(f, a, b, epsabs=0.0, epsrel=QUAD_EPSREL, limit=400)
    return float(val)


def stance(sk: SlottedSkate, D0: float, E: float, H: float, direction: int | None = None) -> StanceResult:
    """Stance from the slot end D0 (0: V > 0, Delta: V < 0) with invariants E, H (closed forms B.1).

    V(D)^2 = 2E - H^2/(1 + L^2) = 2E (L^2 - L_c^2)/(1 + L^2), L_c^2 = H^2/(2E) - 1. A reversal happens iff a root
    +-L_c lies strictly between the entry end and the other end (B.5); the first root met is used. Duration
    int dD/|V| and heading change H int dD/[(1 + L^2)|V|] (sign of H) by quadrature; for a reversal both are twice
    the one-way integrals, evaluated with L = L_c + (L_a - L_c) u^2 to remove the 1/sqrt singularity at L_c.
    ``direction`` (+1/-1), if given, must agree with D0. Raises ``ValueError`` if V would be imaginary at D0 (3.15)
    or the motion ends on the spinning equilibrium (L_c = 0 inside the slot, 3.8).
    """
    validate(sk)
    front = _check_direction(sk, D0, direction)
    if not (E > 0.0 and math.isfinite(E) and math.isfinite(H)):
        raise ValueError(f"E must be > 0 and H finite (got E={E!r}, H={H!r})")
    la, lb = (sk.L_front, sk.L_rear) if front else (sk.L_rear, sk.L_front)
    s = 1.0 if front else -1.0
    ka = 1.0 + la * la
    v2a = 2.0 * E - H * H / ka
    if not v2a > 0.0:
        raise ValueError(f"infeasible state: V^2 = {v2a!r} <= 0 at the entry peg (need 2E/H^2 > 1/(1+L^2), 3.15)")
    lc2 = H * H / (2.0 * E) - 1.0
    l_turn: float | None = None
    if lc2 >= 0.0:
        lc = math.sqrt(lc2)
        ahead = [r for r in (-lc, lc) if s * (r - la) > 0.0 and s * (lb - r) > 0.0]
        if ahead:
            l_turn = min(ahead, key=lambda r: s * (r - la))
            if l_turn == 0.0:
                raise ValueError("the stance ends on the spinning equilibrium (2E/H^2 = 1 with G in the slot, 3.8)")
    if l_turn is None:

        def v_of(L: float) -> float:
            k = 1.0 + L * L
            return math.sqrt((2.0 * E * k - H * H) / k)

        lo, hi = min(la, lb), max(la, lb)
        duration = _quad(lambda L: 1.0 / v_of(L), lo, hi)
        dtheta = H * _quad(lambda L: 1.0 / ((1.0 + L * L) * v_of(L)), lo, hi)
        kb = 1.0 + lb * lb
        v_end = s * math.sqrt(max(2.0 * E - H * H / kb, 0.0))
        return StanceResult(
            D_end=0.0 if not front else sk.Delta,
            reversed=False,
            duration=duration,
            dtheta=dtheta,
            V_end=v_end,
            Omega_end=H / kb,
        )
    lr = l_turn
    w = abs(la - lr)

    def common(u: float) -> tuple[float, float]:
        L = lr + (la - lr) * u * u
        return L, 2.0 * math.sqrt(w) / math.sqrt(2.0 * E * abs(L + lr))

    def t_int(u: float) -> float:
        L, g = common(u)
        return g * math.sqrt(1.0 + L * L)

    def th_int(u: float) -> float:
        L, g = common(u)
        return g / math.sqrt(1.0 + L * L)

    duration = 2.0 * _quad(t_int, 0.0, 1.0)
    dtheta = 2.0 * H * _quad(th_int, 0.0, 1.0)
    return StanceResult(
        D_end=D0 if front else sk.Delta,
        reversed=True,
        duration=duration,
        dtheta=dtheta,
        V_end=-s * math.sqrt(v2a),
        Omega_end=H / ka,
    )


def return_map(sk: SlottedSkate, D: float, E: float, theta: float, H: float, direction: int | None = None) -> MapStep:
    """One application of f = h o p (3.5): (B.3) without and (B.4) with a velocity reversal in the stance.

    No reversal: D+ = D, L_old = the other end, L_new = the current end. Reversal: D+ = Delta - D, L_old = the
    current end, L_new = the other end. Then E+ = E + C1 H^2, H+ = C2 H (:func:`impact_coefficients`), theta+ =
    theta + the stance heading change of :func:`stance`. ``direction`` is implied by D (+1 at D = 0, -1 at Delta).
    """
    front = _check_direction(sk, D, direction)
    st = stance(sk, D, E, H)
    here, other = (sk.L_front, sk.L_rear) if front else (sk.L_rear, sk.L_front)
    l_old, l_new = (here, other) if st.reversed else (other, here)
    c1, c2 = impact_coefficients(sk, l_old, l_new)
    d_plus = (sk.Delta if front else 0.0) if st.reversed else (0.0 if front else sk.Delta)
    return MapStep(
        D_plus=d_plus,
        E_plus=E + c1 * H * H,
        theta_plus=theta + st.dtheta,
        H_plus=c2 * H,
        reversed=st.reversed,
        duration=st.duration,
    )


def initial_state(sk: SlottedSkate, V0: float, Omega0: float, theta0: float = 0.0) -> MapStep:
    """Section state of a start with slot speed V0 != 0 (peg at the front if V0 > 0, at the rear if V0 < 0) and
    angular rate Omega0: (D0, E0, theta0, H0) by (3.3)/(3.4)."""
    validate(sk)
    if not (V0 != 0.0 and math.isfinite(V0) and math.isfinite(Omega0)):
        raise ValueError(f"V0 must be finite and != 0 and Omega0 finite (got V0={V0!r}, Omega0={Omega0!r})")
    d0 = 0.0 if V0 > 0.0 else sk.Delta
    e0, h0 = stance_invariants(sk, d0, V0, Omega0)
    return MapStep(D_plus=d0, E_plus=e0, theta_plus=theta0, H_plus=h0, reversed=False, duration=0.0)


def iterate(sk: SlottedSkate, V0: float, Omega0: float, theta0: float, n: int) -> list[MapStep]:
    """The n section states after impacts 1..n of :func:`return_map` from :func:`initial_state` (V0, Omega0,
    theta0); the initial state itself is not included."""
    q = initial_state(sk, V0, Omega0, theta0)
    out: list[MapStep] = []
    for _ in range(n):
        q = return_map(sk, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
        out.append(q)
    return out
