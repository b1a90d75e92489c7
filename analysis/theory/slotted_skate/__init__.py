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

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.slotted_skate.params`: the skate, its validation and the section state (000 Sec. 3,
  eqs 3.3-3.5)
* :mod:`~mjpoincare.analysis.theory.slotted_skate.map`: stance closed forms, peg impact and the exact return map (000
  eqs 3.5-3.8, B.1-B.5)
* :mod:`~mjpoincare.analysis.theory.slotted_skate.straight_stability`: sigma4, the stability criteria and the smooth-
  sleigh limit (000 eqs 3.9-3.12, 4.1)
* :mod:`~mjpoincare.analysis.theory.slotted_skate.final`: reversals and final states (000 eqs B.6-B.12)
* :mod:`~mjpoincare.analysis.theory.slotted_skate.exact`: the independent rigid-body reference
"""

from __future__ import annotations

from mjpoincare.analysis.theory.slotted_skate.exact import ATOL, MAX_STANCE, RTOL, simulate_exact
from mjpoincare.analysis.theory.slotted_skate.final import (
    FINAL_H_TOL,
    FinalState,
    collisions_before_reversal,
    final_energy,
    final_speed_b12,
    final_state,
)
from mjpoincare.analysis.theory.slotted_skate.map import (
    QUAD_EPSREL,
    StanceResult,
    energy_loss,
    impact_coefficients,
    impact_ratio,
    initial_state,
    iterate,
    return_map,
    stance,
    turning_points,
)
from mjpoincare.analysis.theory.slotted_skate.params import MapStep, SlottedSkate, stance_invariants, validate
from mjpoincare.analysis.theory.slotted_skate.straight_stability import (
    C1,
    dtheta_dH,
    sigma4,
    sleigh_rate,
    smooth_limit_rate,
    smooth_limit_series,
    stability,
)

__all__ = ["ATOL", "C1", "FINAL_H_TOL", "MAX_STANCE", "QUAD_EPSREL", "RTOL", "FinalState", "MapStep", "SlottedSkate",
           "StanceResult", "collisions_before_reversal", "dtheta_dH", "energy_loss", "final_energy", "final_speed_b12",
           "final_state", "impact_coefficients", "impact_ratio", "initial_state", "iterate", "return_map", "sigma4",
           "simulate_exact", "sleigh_rate", "smooth_limit_rate", "smooth_limit_series", "stability", "stance",
           "stance_invariants", "turning_points", "validate"]
