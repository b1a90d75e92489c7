"""Parameters of the discrete Chaplygin sleigh ("slotted skate") and its states on the post-impact section.

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*, Sec. 3 and Fig. 1b (the slot's offset L0 and length Delta, nondimensional by the radius of
gyration), the invariants E (3.3) and H (3.4) of a stance and the post-impact section Sigma of (3.5); conventions in
:mod:`mjpoincare.analysis.theory.slotted_skate` and on the derivation page docs/theory/slotted-skate.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


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
