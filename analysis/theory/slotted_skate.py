"""Discrete Chaplygin sleigh ("slotted skate"): stance closed forms, plastic peg impact, exact return map.

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the
discrete Chaplygin sleigh*, eqs (2.1), (3.1)-(3.15), (4.1), (B.1)-(B.13);
re-derived on the derivation page docs/theory/slotted-skate.md.

Conventions (the paper's nondimensional units; m = rho = v0 = 1 makes SI numbers equal paper numbers): lengths
are divided by the radius of gyration rho = sqrt(I/m), speeds by v0, time tau = t v0 / rho, energy E = T/(m v0^2),
angular momentum H = h/(m rho v0). ``L0`` is the signed distance from the slot FRONT end back to the mass centre G
(> 0: G ahead of the slot), ``Delta`` > 0 the slot length. G lies on the slot axis. D in [0, Delta] is the peg's
distance from the slot front and L = L0 + D the distance from the peg forward to G. V is the slot speed
(e_lambda . v_G), Omega = dtheta/dtau, v_G = V e_lambda + L Omega e_n.

Stance (3.1): D' = V, V' = L Omega^2, theta' = Omega, Omega' = -2 L V Omega/(1 + L^2), with the invariants
E = [V^2 + (1 + L^2) Omega^2]/2 (3.3) and H = (1 + L^2) Omega about the peg (3.4).

Peg protocol: the peg enters at one slot end and leaves at the other (or, if V reverses in the stance, at the end
where it entered); a new peg is then inserted at the slot end opposite to the one just left. With L_old the end
left and L_new the other end, L_old L_new = L0 (L0 + Delta) always, and the plastic impact gives
H+ = C2 H-, E+ = E- + C1 H-^2 with C2 = (1 + L_old L_new)/(1 + L_old^2), C1 = -Delta^2/[2 (1+L_old^2)^2 (1+L_new^2)]
(3.6)/(3.7) in the derivation page's unified form.

Post-impact section Sigma: q = (D, E, theta, H) with D = 0 (V > 0) or D = Delta (V < 0), H about the current peg.

Corrections to the paper as printed used here (derivation page Sec. 5, each re-checked in
tests/test_theory_slotted_skate.py):
(3.7) the last bracket is [1 + (L0 + (Delta - D-))^2]; (B.3)/(B.4) theta: the integrand keeps the sign of H and
runs over (0, Delta) whatever the direction, reversal stances give 2 H |int_{D+}^{Dc}|; (B.8) reads max, not min;
(4.1) the Delta^2 coefficient is -L0 (L0^2 - 6)/[3 (1 + L0^2)^3], not -L0 (L0^2 - 2)/[3 (1 + L0^2)^3].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad, solve_ivp

RTOL = 1e-12
ATOL = 1e-12
#: Relative tolerance of the stance quadratures (B.3)/(B.4).
QUAD_EPSREL = 1e-13
#: Longest stance integrated by :func:`simulate_exact` before the motion is declared a spin (3.8), in tau.
MAX_STANCE = 1e6
#: |H| below which :func:`final_state` considers the rotation decayed (relative to sqrt(2 E)).
FINAL_H_TOL = 1e-15


@dataclass(frozen=True)
class SlottedSkate:
    """Slotted-skate parameters (000 Sec. 3, Fig. 1b), nondimensional by rho.

    ``L0`` signed distance from the slot front end back to G (any finite value; > 0: G ahead of the slot,
    -Delta < L0 < 0: G inside it, L0 < -Delta: G behind it); ``Delta`` slot length > 0.
    """

    L0: float
    Delta: float

    @property
    def c(self) -> float:
        """c = 1 + L0 (L0 + Delta) = 1 + L_old L_new, the numerator of (3.6)/(3.10)."""
        return 1.0 + self.L0 * (self.L0 + self.Delta)

    @property
    def L_front(self) -> float:
        """L at the slot front end, L0."""
        return self.L0

    @property
    def L_rear(self) -> float:
        """L at the slot rear end, L0 + Delta."""
        return self.L0 + self.Delta


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


@dataclass(frozen=True)
class MapStep:
    """A state on the post-impact section Sigma (3.5): (D+, E+, theta+, H+) with H+ about the new peg.

    ``reversed`` and ``duration`` describe the stance that ended in this impact (False and 0 for an initial state).
    """

    D_plus: float
    E_plus: float
    theta_plus: float
    H_plus: float
    reversed: bool
    duration: float

    def velocities(self, sk: SlottedSkate) -> tuple[float, float]:
        """Post-impact (V+, Omega+) from (3.3)/(3.4): Omega+ = H+/(1 + L^2), V+ = +-sqrt(2E+ - H+ Omega+),
        + iff D+ = 0."""
        L = sk.L0 + self.D_plus
        om = self.H_plus / (1.0 + L * L)
        v = math.sqrt(max(2.0 * self.E_plus - self.H_plus * om, 0.0))
        return (v if _is_front(sk, self.D_plus) else -v), om


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


def validate(sk: SlottedSkate) -> None:
    """Raise ``ValueError`` naming the parameter and its allowed range (000 Sec. 3: delta > 0; l0 signed)."""
    if not math.isfinite(sk.L0):
        raise ValueError(f"L0 must be finite (got {sk.L0!r})")
    if not (math.isfinite(sk.Delta) and sk.Delta > 0.0):
        raise ValueError(f"Delta must be > 0 (got {sk.Delta!r})")


def _is_front(sk: SlottedSkate, D: float) -> bool:
    """True for D = 0, False for D = Delta; anything else is not on the section Sigma."""
    if D == 0.0:
        return True
    if abs(D - sk.Delta) <= 1e-12 * max(1.0, sk.Delta):
        return False
    raise ValueError(f"D must be 0 or Delta = {sk.Delta!r} on the post-impact section (got {D!r})")


def _check_direction(sk: SlottedSkate, D: float, direction: int | None) -> bool:
    front = _is_front(sk, D)
    if direction is not None and direction != (1 if front else -1):
        raise ValueError(f"direction must be +1 for D = 0 and -1 for D = Delta (got D={D!r}, direction={direction!r})")
    return front


def stance_invariants(sk: SlottedSkate, D: float, V: float, Omega: float) -> tuple[float, float]:
    """(E, H) of a stance state: E = [V^2 + (1 + L^2) Omega^2]/2 (3.3), H = (1 + L^2) Omega (3.4), L = L0 + D."""
    k = 1.0 + (sk.L0 + D) ** 2
    return 0.5 * (V * V + k * Omega * Omega), k * Omega


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


# ------------------------------------------------------------------------------------------------------------------
# Independent reference: planar rigid body, stance ODE + Cartesian impulse at the new peg.
# ------------------------------------------------------------------------------------------------------------------


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _cartesian(sk: SlottedSkate, peg: np.ndarray, D: float, V: float, th: float, om: float):  # type: ignore[no-untyped-def]
    """(r_G, v_G, e_lambda, e_n) of the body engaged at ``peg`` (m = rho = 1)."""
    el = np.array([math.cos(th), math.sin(th)])
    en = np.array([-math.sin(th), math.cos(th)])
    L = sk.L0 + D
    return peg + L * el, V * el + L * om * en, el, en


def _energy_momentum(r_g: np.ndarray, v_g: np.ndarray, om: float, point: np.ndarray) -> tuple[float, float]:
    """E = |v_G|^2/2 + omega^2/2 and h about ``point`` = omega + (r_G - point) x v_G (m = I = 1)."""
    return 0.5 * float(v_g @ v_g) + 0.5 * om * om, om + _cross(r_g - point, v_g)


def simulate_exact(
    sk: SlottedSkate, V0: float, Omega0: float, theta0: float, n_impacts: int, rtol: float = RTOL
) -> list[MapStep]:
    """Independent reference for :func:`iterate`: integrate the stance ODE (3.1) with ``solve_ivp`` (DOP853) and
    terminal events at the slot ends (front crossed with V < 0, rear with V > 0), then insert the new peg at the
    opposite slot end at its plane position P' = r_G - L_new e_lambda and apply the impulse Pi e_n at P' that
    makes the normal velocity of the body point over P' vanish, solved from linear and angular momentum balance
    of the rigid body in Cartesian form (no use of (3.6)/(3.7)). E and H about the peg are evaluated from r_G, v_G
    and omega. Reversals follow from which end the event fires at. Returns the section states after each impact.
    """
    validate(sk)
    q0 = initial_state(sk, V0, Omega0, theta0)
    D, V, th, om = q0.D_plus, V0, theta0, Omega0
    peg = np.zeros(2)
    l0 = sk.L0

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        L = l0 + y[0]
        return [y[1], L * y[3] ** 2, y[3], -2.0 * L * y[1] * y[3] / (1.0 + L * L)]

    def front(_t: float, y: np.ndarray) -> float:
        return float(y[0])

    def rear(_t: float, y: np.ndarray) -> float:
        return float(y[0] - sk.Delta)

    front.terminal, front.direction = True, -1  # type: ignore[attr-defined]
    rear.terminal, rear.direction = True, 1  # type: ignore[attr-defined]
    out: list[MapStep] = []
    for _ in range(n_impacts):
        start_front = D == 0.0
        sol = solve_ivp(
            rhs, (0.0, MAX_STANCE), [D, V, th, om], method="DOP853", rtol=rtol, atol=ATOL * 1e-2,
            events=(front, rear), dense_output=False,
        )  # fmt: skip
        hit_front = sol.t_events[0].size > 0
        if not (hit_front or sol.t_events[1].size > 0):
            raise RuntimeError("no slot end reached (spinning equilibrium?)")
        y = sol.y_events[0][0] if hit_front else sol.y_events[1][0]
        t_end = float(sol.t_events[0][0] if hit_front else sol.t_events[1][0])
        d_end = 0.0 if hit_front else sk.Delta  # snap the event state onto the slot end
        reversed_ = hit_front == start_front
        r_g, v_g, el, en = _cartesian(sk, peg, d_end, float(y[1]), float(y[2]), float(y[3]))
        w = float(y[3])
        d_new = sk.Delta if hit_front else 0.0
        new_peg = r_g - (l0 + d_new) * el
        # Impulse Pi e_n at new_peg: v_G+ = v_G + Pi e_n, w+ = w + (new_peg - r_G) x (Pi e_n); require the normal
        # velocity of the material point at new_peg, e_n . (v_G+ + w+ z x (new_peg - r_G)), to vanish.
        arm = new_peg - r_g
        zx_arm = np.array([-arm[1], arm[0]])
        vn = float(en @ (v_g + w * zx_arm))
        dw_per_pi = _cross(arm, en)
        dvn_per_pi = 1.0 + dw_per_pi * float(en @ zx_arm)
        pi = -vn / dvn_per_pi
        v_g = v_g + pi * en
        w = w + dw_per_pi * pi
        e_plus, h_plus = _energy_momentum(r_g, v_g, w, new_peg)
        out.append(
            MapStep(
                D_plus=d_new, E_plus=e_plus, theta_plus=float(y[2]), H_plus=h_plus, reversed=reversed_,
                duration=t_end,
            )
        )  # fmt: skip
        peg, D, V, th, om = new_peg, d_new, float(v_g @ el), float(y[2]), w
    return out
