"""Compass biped with Coulomb friction: stick-slip stance, frictional heel strike, passive and actuated gaits.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 4 (passive CB on a slope, eq 27, Figs 4.1-4.2), Sec. 5 (actuated CB on level ground, eqs 28-30,
Figs 5.1-5.2) and Appendix A (eqs 31-40); re-derivation with numbers on the derivation page
docs/theory/stick-slip.md, Secs. 3, 4 and 7. The
stance and impact machinery is the model-agnostic :mod:`mjpoincare.analysis.theory.stick_slip`; the modules of this
system (listed at the end) only supply the matrices of eq 27, the actuation, the heel-strike guard, the relabelling
and the shooting, and this module re-exports their public API. None of them imports mujoco.

Model (002 eq 27, SI units): legs of length ``l`` with a point mass ``m`` at distance ``d`` from the foot, hip
mass ``m_h``, slope ``slope`` = alpha, friction ``mu`` (static = kinetic). q = (theta1, theta2, x, y): (x, y) is the
stance foot in the slope frame (x downhill = walking direction, y along the slope normal); theta1 is the stance
leg's foot->hip direction (sin theta1, cos theta1) and theta2 the swing leg's hip->foot direction
(sin theta2, -cos theta2), both from the slope normal. Swing foot r~ = (x + l(S1 + S2), y + l(C1 - C2)).
With K = d m + l (m + m_h), b = l - d, M_tot = 2m + m_h:
M = [[d^2 m + l^2 (m + m_h), l m b C12, K C1, -K S1], [., m b^2, m b C2, m b S2], [., ., M_tot, 0], [., ., 0, M_tot]],
B = (-l m b S12 th2d^2, -l m b S12 th1d^2, -m b S2 th2d^2 - K S1 th1d^2, -K C1 th1d^2 + m b C2 th2d^2),
G = g (-K sin(theta1 + alpha), -m b sin(alpha - theta2), -M_tot sin(alpha), M_tot cos(alpha)),
W = [[0, 0, 1, 0], [0, 0, 0, 1]], W~ = [[l C1, l C2, 1, 0], [-l S1, l S2, 0, 1]] (002 eq 27 as printed; the tests
re-derive M, B, G from the point-mass Lagrangian by finite differences). Equations of motion 002 eq 2 in the sign
of :mod:`mjpoincare.analysis.theory.stick_slip`: M qdd = -(B + G - Q) + W^T f, Q the actuation's generalised force.

Step: from the post-impact state theta1 = theta2 = -theta*, (theta1_dot, theta2_dot, x_dot) and y_dot = 0, the
stance is integrated (stick / slip+ / slip-, 002 eq 35) until heel strike theta1 = theta2 > 0 (swing foot ahead and
descending); the scuffing of the swing foot near mid-stance is ignored, as in 002 Sec. 4.1. Then the frictional
plastic impact of 002 eqs 37-40 (sticking if its impulse is in the cone, else slipping) and the relabelling of 002
Sec. 4 (theta1 <-> -theta2, theta1_dot <-> -theta2_dot; the new stance foot is the old swing foot, its post-impact
velocity (x_dot+, 0) the new (x_dot, y_dot)). Poincaré section: post-impact, z = (theta*, theta1_dot+, theta2_dot+)
plus x_dot+ when the impact slips (002 Sec. 4.2; 3-D for Gaits A, B, 4-D for Gait C).

Actuation (002 Sec. 5), stated as the generalised force Q on (theta1, theta2):

* :class:`ConstantTorque` (eq 28, Gaits I/II): 002 prints E = [[1, 0, 0, 0], [1, 1, 0, 0]]^T, i.e.
  Q = (tau1 + tau2, tau2); this is the Jacobian of a physical ankle torque on theta1 and a hip torque on the
  inter-leg angle theta1 + theta2. With the reported Gait I torques tau1 = -2.73, tau2 = 0.54 it gives
  Q1 = -2.19 N m, and the biped falls backwards on its first step (tests; derivation page Sec. 3.3). The torques
  fit the "gravity replacement" Q1 = g K (sin(theta1 + alpha) - sin(theta1)) ~ +2.19 cos(theta1),
  Q2 = g m b (sin(alpha - theta2) + sin(theta2)) ~ +0.547 cos(theta2) of alpha = 1 deg only with the effective
  E_eff = [[-1, 0, 0, 0], [-1, 1, 0, 0]]^T: Q = (-tau1 - tau2, tau2) (default ``convention="effective"``). The same
  Q comes from physical (printed-E) ankle and hip torques (tau_a, tau_h) = (-tau1 - 2 tau2, tau2), e.g. (1.65, 0.54)
  N m for Gait I: a simulator must reproduce Q, not the printed tau.
* :class:`PDTracking` (eq 30, Gait III): tau_i = -kp (theta_i - theta_i^r(phi)) - kd (theta_i_dot -
  theta_i_dot^r(phi)) with phi the time since the last impact (phase reset), applied as Q = (tau1, tau2), the
  generalised force on each angle (``convention="direct"``; with E_eff the stance-leg feedback would have the
  destabilising sign). The reference is a stored gait trajectory (:class:`ReferenceTrajectory`, sampled with
  :func:`reference_trajectory`); 002's is the passive Gait C of its Fig. 4.2a, mu = 0.14 (:func:`gait_c_reference`).

Time dependence: :class:`.stick_slip.ContactModel` has time-free callables, so :func:`contact_model`
appends two decoupled unit-mass coordinates: index 4 is the phase clock phi (phi_dot = 1, phi_ddot = 0) and index 5
an actuator-work accumulator whose velocity is W_act(t) = int Q . qd dt (its acceleration is Q . qd). Neither enters
W, W~ or the coupling of M, so the stick-slip machinery is used unchanged (stick_slip.py is not modified).

Gaits (002 Secs. 4-5; :func:`paper_gait`, seeds in :data:`GAIT_SEEDS`, values in the tests):

* A (sticking throughout) and B (sticking impact, slip+ -> stick -> slip-): the values of the derivation page,
  Sec. 3.2; B loses stability at mu = 0.11035 (linear interpolation of the page's table: 0.1104; 002 "~0.11").
  Gait A equals the passive biped of
  :mod:`~mjpoincare.analysis.theory.compass_biped` (003 Ch. 4) in that module's angles.
* C (slipping impact with forward slip, slip+ -> stick, stuck before the heel strike) is found here by
  :func:`search_gaits` (grid on the pre-impact section, then Newton): unstable
  (|lambda|max 1.82 at mu = 0.14, 1.53 at 0.2), impact angle 4.53 deg at mu = 0.14 (002: "4 deg" in Fig. 4.2a)
  and 6.52 deg at 0.2, coexisting with B and with A above mu_c, as 002 says. The 4-D map has one multiplier ~0
  (the slip -> stick transition collapses x_dot, like the rimless wheel's Type C). Continued upwards, the branch
  ends at mu = 0.3044, where its post-impact slip vanishes and it joins a second, unstable sticking-impact passive
  gait (theta* = 0.14282, multipliers 2.342, 0.625, 0.273, |sigma~| = 0.3044). Why it is easy to miss: in Gait C
  the legs pass parallel only after the stance leg has passed the normal (theta1 ~ 0.014 rad), so the swing foot
  dips < 0.3 mm below the ground ahead of the stance foot until it emerges at theta1 = theta2 ~ 0.026 rad; a
  heel-strike guard that stops at the legs-parallel crossing rejects the orbit (:func:`heel_strike_guard`,
  :func:`heel_strike_after_scuff`, ``StepRecord.late_swing``). And theta1_dot+ is tiny (0.044 rad/s at mu = 0.14),
  so perturbed orbits roll back.
* I (E_eff, -2.73/0.54): the derivation page's Sec. 3.3 table; stability is lost at mu = 0.10350 (002 "stable
  for mu > 0.11").
* II (-0.69/0.12, E_eff, slipping impact): unstable on [0.09, 0.2], c_mt = 0.0044 as in 002; W = 0.120 J (002
  0.1), S = 0.279 m (002 0.23). The energy split is not 002's: friction work -0.005 J and impact loss 0.116 J at
  mu = 0.2 (002: 0.078 J and 0.022 J). 002 says these torques are the mean inverse-dynamics torques of Gait C on
  level ground, but rows theta1, theta2 of eq 2 carry no contact force (W has zero columns there), so for any
  passive slope trajectory the level-ground inverse dynamics give exactly Q = G(alpha = 0) - G(alpha) on the angles,
  ~ (2.19, 0.55) N m, i.e. Gait I's torques, not (-0.69, 0.12).
* III (PD tracking Gait C of mu = 0.14, direct convention): stable on [0.09, 0.2] with slipping impact and forward
  post-impact slip, also above mu_c; S = 0.24-0.25 m (002 ~0.23); |lambda|max 0.57 (mu = 0.2) to 0.86 (0.09), not
  002's "< 0.5 for all mu". Pure PD tracking of Gait A on level ground (no feedforward) found no gait: the biped
  rolls back after a few steps.

Corrections to 002 found here (also on the derivation page, Sec. 7 items 3-5, 12-14):

* (34) sign, (39) Gamma~ = (s mu, 1)^T, W q_dot = 0 (not W = 0): see :mod:`mjpoincare.analysis.theory.stick_slip`.
* Sec. 5 / (28): E and the reported torques are sign-inconsistent (above).
* Sec. 4.1 says the scuffing collision is "where theta1 = theta2", while the legs pass parallel at
  theta2 = -theta1. The swing foot crosses the ground line twice before the heel strike and is below it in between
  (:func:`scuffing_crossings`): along Gait A first at theta1 = theta2 < 0 (foot behind the stance foot), then at
  theta2 = -theta1 (legs parallel); along Gait C first at theta2 = -theta1 (theta1 > 0), then at
  theta1 = theta2 > 0 (foot ahead, emerging). Both statements name one end of that interval; the heel strike is the
  later, downward crossing theta1 = theta2 > 0.
* Sec. 5 (29): c_mt = W/(M_tot g S) with the total weight M_tot g, W in J (printed "W = 0.1").

Independent confirmation: :mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping` computes the same
gaits by complementarity time-stepping in floating-base coordinates, sharing no equation, mode logic or impact law with
these modules; its Richardson-extrapolated strides reproduce the fixed points of Gaits B, C, I, II, III to 4e-6, the
step quantities to 6e-6 and the multipliers to 6e-3 (tests/test_theory_compass_biped_time_stepping.py). Where 002
disagrees (III |lambda|max < 0.5; II S = 0.23 m, W = 0.1 J), the evidence supports this model's values for the model as
printed (eq 27, the torques and gains of Sec. 5 in the convention that reproduces Gait I); what 002 computed differently
is not recoverable from the paper.

Modules (each imports only those above it; the stick-slip machinery is re-exported as ``ss``):

* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.params`: the parameters and their admissible ranges (002 Sec.
  4.1)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.actuation`: constant torques and PD tracking (002 eqs 28, 30)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.dynamics`: the matrices of 002 eq 27, the heel-strike guards,
  the contact model
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.one_step`: one step, the post-impact map and the gait types
  (002 Secs. 4-5)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.shooting`: fixed points, multipliers, continuation in mu (002
  Sec. 4.2)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.search`: the pre-impact section and the search that finds
  Gait C
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.demand`: friction demand, cost of transport and speed (002
  Secs. 4.1, 5)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.trajectories`: the PD reference, stance-foot motion and
  scuffing along a step
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.gaits`: the paper's Gaits A-C and I-III (002 Secs. 4-5)
"""

from __future__ import annotations

from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.actuation import (
    E_EFFECTIVE,
    E_PRINTED,
    PASSIVE,
    Actuation,
    ConstantTorque,
    PDTracking,
    ReferenceTrajectory,
)
from mjpoincare.analysis.theory.compass_biped_friction.demand import (
    FrictionDemand,
    average_speed,
    cost_of_transport,
    critical_friction,
)
from mjpoincare.analysis.theory.compass_biped_friction.dynamics import (
    FALL_ANGLE,
    contact_model,
    coriolis_vector,
    energy,
    gravity_vector,
    heel_strike_after_scuff,
    heel_strike_guard,
    kinetic_energy,
    mass_matrix,
    point_masses,
    potential_energy,
    section_state,
    swing_foot,
    swing_jacobian,
)
from mjpoincare.analysis.theory.compass_biped_friction.gaits import (
    GAIT_I_TORQUES,
    GAIT_II_TORQUES,
    GAIT_III_REFERENCE_MU,
    GAIT_SEEDS,
    gait_c_reference,
    paper_gait,
    paper_setup,
)
from mjpoincare.analysis.theory.compass_biped_friction.one_step import (
    T_MAX,
    StepRecord,
    _phase_solutions,
    classify,
    describe,
    return_map,
    step,
)
from mjpoincare.analysis.theory.compass_biped_friction.params import NQ, FrictionBiped, validate
from mjpoincare.analysis.theory.compass_biped_friction.search import impact_from_pre, pre_impact_map, search_gaits
from mjpoincare.analysis.theory.compass_biped_friction.shooting import (
    FD_STEP,
    NEWTON_TOL,
    Gait,
    continuation,
    eigenvalues,
    find_gait,
    fixed_point,
    map_jacobian,
    spectral_radius,
    stability_loss_mu,
)
from mjpoincare.analysis.theory.compass_biped_friction.trajectories import (
    legs_parallel,
    reference_trajectory,
    scuffing_crossings,
    stance_foot_motion,
)

__all__ = ["E_EFFECTIVE", "E_PRINTED", "FALL_ANGLE", "FD_STEP", "GAIT_III_REFERENCE_MU", "GAIT_II_TORQUES",
           "GAIT_I_TORQUES", "GAIT_SEEDS", "NEWTON_TOL", "NQ", "PASSIVE", "T_MAX", "Actuation", "ConstantTorque",
           "FrictionBiped", "FrictionDemand", "Gait", "PDTracking", "ReferenceTrajectory", "StepRecord",
           "_phase_solutions", "average_speed", "classify", "contact_model", "continuation", "coriolis_vector",
           "cost_of_transport", "critical_friction", "describe", "eigenvalues", "energy", "find_gait", "fixed_point",
           "gait_c_reference", "gravity_vector", "heel_strike_after_scuff", "heel_strike_guard", "impact_from_pre",
           "kinetic_energy", "legs_parallel", "map_jacobian", "mass_matrix", "paper_gait", "paper_setup",
           "point_masses", "potential_energy", "pre_impact_map", "reference_trajectory", "return_map",
           "scuffing_crossings", "search_gaits", "section_state", "spectral_radius", "ss", "stability_loss_mu",
           "stance_foot_motion", "step", "swing_foot", "swing_jacobian", "validate"]
