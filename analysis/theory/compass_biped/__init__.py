"""Passive compass-gait biped on a slope: swing dynamics, heel-strike impact and the period-1 gait.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4,
eqs (4.2)-(4.20) and Fig. 18; the same model as Goswami, Thuilot & Espiau (1996/1998), "A study of the
passive gait of a compass-like biped robot" (benchmark parameters m_h/m = 2, a = b, l = 1, slope 3 deg).

Conventions (SI units, 003's): q = (theta_st, theta_sw), each the foot->hip direction of a leg measured from the
TRUE vertical, clockwise positive; +x is downhill and the slope falls from left to right. Point masses m_l on each
leg at distance a from the foot (b from the hip), m_h at the hip, l = a + b. Positions with the origin at the
stance foot and u(theta) = (sin theta, cos theta): stance-leg mass a u(theta_st), hip l u(theta_st), swing-leg
mass l u(theta_st) - b u(theta_sw), swing foot l u(theta_st) - l u(theta_sw). The hip torque tau is positive
counter-clockwise on the swing leg with work tau (theta_sw - theta_st), so B = (-1, 1). A state is
x = (theta_st, theta_sw, dtheta_st, dtheta_sw).

Actuation (for the actuated biped; 0 = the passive walker of 003): constant torques, ``tau_hip`` between the legs
as in 003 eq 4.5 (generalised forces (-tau_hip, +tau_hip)) and ``tau_ankle``, the ground's torque on the stance leg,
clockwise positive (generalised force (+tau_ankle, 0): it pushes the hip downhill). Both act in the EoM only; the
impact law is unchanged (finite torques give no impulse).

Heel strike (003 eq 4.6): theta_st + theta_sw = 2 gamma with theta_st > theta_sw (swing foot in front); the
mid-stance crossing theta_st = theta_sw, where the swing foot scuffs, is ignored (003 Sec. 4.1: the swing leg
"retracts" without moving its mass). At impact the legs are relabelled (003 eq 4.7) and
Q+ qd+ = Q- qd- (003 eqs 4.15-4.17) with alpha = (theta_st- - theta_sw-)/2, the half inter-leg angle.

Re-derived here: the EoM (4.5) from the Lagrangian, and Q+/Q- (4.15)/(4.16) from the two conserved angular
momenta (whole biped about the new contact point, trailing leg about the hip); both agree with the thesis.
The thesis finds its gait by grid search plus forward simulation (Sec. 4.4.2) with first-order event location,
so its Fig. 18 state is ~3e-4 off the true fixed point; here the fixed point is found by Newton shooting.

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.compass_biped.params`: the biped, its admissible parameters and the benchmark sets
  (003 Sec. 4.1, Goswami)
* :mod:`~mjpoincare.analysis.theory.compass_biped.dynamics`: the swing EoM and the heel-strike impact law (003 eqs 4.5,
  4.15-4.18)
* :mod:`~mjpoincare.analysis.theory.compass_biped.one_step`: one step, the post-impact map, period and length (003 eqs
  4.6, 4.18-4.19)
* :mod:`~mjpoincare.analysis.theory.compass_biped.shooting`: the period-1 gait, its multipliers and the first period
  doubling
* :mod:`~mjpoincare.analysis.theory.compass_biped.midswing`: the legs-parallel section and the lowest swing-foot height
  (003 eq 4.20)
"""

from __future__ import annotations

from mjpoincare.analysis.theory.compass_biped.dynamics import (
    coriolis,
    energy,
    gravity_vector,
    impact_map,
    impact_matrices,
    mass_matrix,
    swing_dynamics,
    swing_foot_height,
)
from mjpoincare.analysis.theory.compass_biped.midswing import (
    legs_parallel_state,
    lowest_swing_height,
    parallel_return_map,
    post_impact_from_parallel,
)
from mjpoincare.analysis.theory.compass_biped.one_step import (
    ATOL,
    MAX_SWING,
    RTOL,
    StepResult,
    return_map,
    step,
    step_length,
    step_period,
)
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped, goswami, kisa, validate
from mjpoincare.analysis.theory.compass_biped.shooting import eigenvalues, fixed_point, period_doubling_slope

__all__ = ["ATOL", "MAX_SWING", "RTOL", "CompassBiped", "StepResult", "coriolis", "eigenvalues", "energy",
           "fixed_point", "goswami", "gravity_vector", "impact_map", "impact_matrices", "kisa", "legs_parallel_state",
           "lowest_swing_height", "mass_matrix", "parallel_return_map", "period_doubling_slope",
           "post_impact_from_parallel", "return_map", "step", "step_length", "step_period", "swing_dynamics",
           "swing_foot_height", "validate"]
