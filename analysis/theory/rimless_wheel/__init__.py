"""Closed-form theory of the planar rimless wheel on a slope (sticking contact, plastic impacts).

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3,
eqs (3.2)-(3.18); 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions",
SIAM J. Appl. Dyn. Syst., Sec. 3.1, eqs (12)-(26).

Conventions (SI units): ``theta`` is the stance spoke's angle from the true vertical, clockwise positive, so
that a downhill lean is positive (003's convention); ``omega`` = d(theta)/dt, positive when rolling downhill.
The slope is ``gamma``; ``alpha`` = pi/n is half the inter-spoke angle. A forward step runs
theta: gamma - alpha -> gamma + alpha. The Poincaré section is "just after an impact"; the sign of omega
fixes the configuration (omega > 0: theta = gamma - alpha, pivot on the downhill foot;
omega < 0: theta = gamma + alpha, pivot on the uphill foot).

Hub inertia (002): radius of gyration ``gyration``, kappa = (gyration/l)^2. Every formula of 003 generalises
with g/l -> rate2 = g/(l(1+kappa)) (stance dynamics, 002 eq 12) and
cos 2alpha -> beta = (cos 2alpha + kappa)/(1+kappa) (impact, 002 eq 14): the stance equation keeps the form
theta'' = rate2 sin theta and the impact keeps the form omega+ = beta omega-, so the derivations of 003 carry
over symbol for symbol.

Corrections to the sources (re-derived here): for gamma > alpha the backward-step threshold of 003 (3.14)
must be -sqrt(K) instead of omega_b (3.7), because a backward step then never passes the vertical; the
rolling multiplier is beta^2 (003 gives no number).

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.rimless_wheel.params`: the wheel and its admissible parameters (003 Sec. 3.1, 002
  Sec. 3.1)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel.map`: the return map, its fixed points and the regions (003 eqs
  3.13-3.16, Table 1)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel.stance`: speeds, forces, contact validity, period and friction along a
  stance (002 eq 19)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel.basins`: basins of attraction and probing starts (003 Def. 3.20, eqs
  3.17-3.18)
"""

from __future__ import annotations

from mjpoincare.analysis.theory.rimless_wheel.basins import (
    BOUNDARY_TOL,
    basin_band_edges,
    basin_bands,
    basin_edges,
    basin_initial_speeds,
    fit_initial_speeds,
    flight_free,
    predicted_outcome,
)
from mjpoincare.analysis.theory.rimless_wheel.map import (
    backward_threshold,
    existence_bound,
    forward_threshold,
    region,
    return_map,
    return_map_derivative,
    rolling_exists,
    rolling_fixed_point,
    rolling_multiplier,
    standing_exists,
    standing_multiplier,
)
from mjpoincare.analysis.theory.rimless_wheel.params import REGION_TOL, RimlessWheel, validate
from mjpoincare.analysis.theory.rimless_wheel.stance import (
    excursion_min_normal_force,
    impact_impulse_ratio,
    no_flight_bound,
    normal_force_ratio,
    phase_speed,
    post_impact_speed,
    required_friction,
    step_period,
    step_stays_in_contact,
    tangential_force_ratio,
)

__all__ = ["BOUNDARY_TOL", "REGION_TOL", "RimlessWheel", "backward_threshold", "basin_band_edges", "basin_bands",
           "basin_edges", "basin_initial_speeds", "excursion_min_normal_force", "existence_bound", "fit_initial_speeds",
           "flight_free", "forward_threshold", "impact_impulse_ratio", "no_flight_bound", "normal_force_ratio",
           "phase_speed", "post_impact_speed", "predicted_outcome", "region", "required_friction", "return_map",
           "return_map_derivative", "rolling_exists", "rolling_fixed_point", "rolling_multiplier", "standing_exists",
           "standing_multiplier", "step_period", "step_stays_in_contact", "tangential_force_ratio", "validate"]
