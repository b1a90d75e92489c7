"""Rimless wheel with hub inertia and Coulomb friction: stick-slip gaits A-D, their maps and basins.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 3 eqs (11)-(26), Figs 3.3-3.8, Appendix A eqs (41)-(45); re-derivation with oracles on the derivation
page docs/theory/stick-slip.md, Secs. 1, 2, 4, 5, 7. The rigid (sticking) closed forms are reused from
:mod:`mjpoincare.analysis.theory.rimless_wheel` (003/002 eqs 12-17, 22-25) through :func:`rigid_wheel`.

Conventions (002's, nondimensional): m = l = 1 and g = 1 + kappa, so the stance rate omega_c =
sqrt(g/(l (1+kappa))) = 1 (002's "tau_c" is this rate; :func:`omega_c` converts: theta_dot_SI = theta_dot omega_c,
x_dot_SI = x_dot l omega_c, t_SI = t/omega_c). q = (x, y, theta): (x, y) is the stance-spoke tip in the slope
frame (x downhill, y normal), theta the stance spoke's angle from the slope normal (> 0: hub downhill of the tip).
A step runs theta: -phi -> +phi with phi = pi/n; the next spoke lands at theta = +phi. The slope is alpha
(``slope``). A post-impact state is (theta_dot, x_dot) at theta = -phi, y = y_dot = 0; x_dot is the slip speed of
the new stance tip, unchanged across the relabelling (both tips lie on the ground line). Forces are reported as
f/(m g), impulses in units of m l omega_c. Contact modes: "stick", "slip+" (x_dot > 0, forward/downhill slip),
"slip-".

Two independent implementations of a step: ``method="fast"`` integrates in theta, with the sticking phases in
closed form (energy integral 002 eq 13, forces eq 19) and the slipping phases from eq 42 (u = theta_dot^2 obeys
a linear ODE in theta); ``method="generic"`` runs the Appendix-A matrix machinery of
:mod:`mjpoincare.analysis.theory.stick_slip` in time on q = (x, y, theta) with M, B, G, W, W~ of eq 11.

Corrections to 002 (re-derived; also on the derivation page, Sec. 7 items 1-8):

* tau_c of 002 is the rate omega_c = sqrt(g/(l(1+kappa))), not a time; every "rad/tau_c" is theta_dot/omega_c.
* (41): the kinetic-energy cross term is -2 y_dot theta_dot l sin(theta) (M_23 = -m l sin theta of eq 11).
* (25) prints |sigma~|; the sticking-impulse ratio is -sin(2phi)/(2(kappa + cos^2 phi)) (the ground pushes uphill).
* (39): Gamma~ = (s mu, 1)^T; (44) needs the factor 2 in 2(kappa + cos^2 phi) l theta_dot^- of the denominator
  (else it contradicts (25) at x_dot^- = 0).
* (45): written with s_F = sgn(F~_t) (-1 for forward slip), theta_dot^+ = (2kappa - 1 + cos2phi - s_F mu sin2phi)
  / D_s theta_dot^- and x_dot^+ = x_dot^- + 2 l sin(phi) (2 s_F mu (kappa + cos^2 phi) + sin 2phi)/D_s theta_dot^-,
  D_s = 2kappa + 1 - cos2phi + s_F mu sin2phi. The printed theta row uses s = -s_F (against the paper's own
  s = -sgn(v~_t^-)), and the printed x row's kappa term 2 s mu kappa sin(phi) should be 4 s mu kappa l sin(phi).
  Only the corrected row reproduces 002's Delta x_dot = -0.0517 (Fig. 3.6).
* (34) has a sign error (see :mod:`mjpoincare.analysis.theory.stick_slip`).

Results of these modules that the derivation page docs/theory/stick-slip.md takes from them (the rest of its Secs.
1, 2, 4, 5 reproduces here):

* Sec. 2, slipping-impact gain at mu = 0.2: eq 45 (corrected) gives 0.80158, which is also the ratio
  0.775514/0.967486 of the page's Type D table; 0.9570 at mu = 0.3.
* Sec. 2, upper edge of the attraction window, 1.12050 at mu = 1e6: above mu ~ 1e3 the first step fails by the
  Painleve case (forward slip starting at theta < 0 with D = kappa + sin^2 + mu sin cos < 0), not by f_n -> 0;
  detachment is the failure up to mu ~ 1e3. The edge tends to sqrt((3+kappa) cos(alpha) - 2cos(alpha-phi))
  = 1.120496 as mu -> inf (the sticking f_n reaching 0 exactly at theta = 0).
* Secs. 2 and 5, lower end of the C branch: it ends at mu = tan(alpha) = 0.230868, the D+/D- boundary, in a grazing
  bifurcation: the stick phase shrinks like sqrt(mu - tan(alpha)) and the orbit becomes the D orbit with
  Delta x_dot = 0 (found here down to tan(alpha) + 5e-6).

Additional exact results derived here (not in 002; used as oracles): over a Type D step u = theta_dot^2 is affine,
u(phi) = Phi u(-phi) + Psi (:func:`slip_affine_coefficients`), so theta_dot*^2 = gamma^2 Psi/(1 - gamma^2 Phi) and
lambda_D = gamma^2 Phi with gamma the slipping-impact gain (:func:`type_d_linear`); and momentum balance over a step
gives Delta x_dot = g T (sin(alpha) - mu cos(alpha)) for a D gait of period T, so the D+/D- boundary is
mu = tan(alpha) exactly (:func:`d_sign_boundary`).

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.params`: the wheel, its units and its admissible slopes (002
  eqs 11, 14, 18/21)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.sticking`: the sticking gait in closed form (002 eqs 15-26)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.slip`: slipping stance and frictional impact in closed form
  (002 eqs 42-45)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.phases`: the fast method's stick and slip phases, integrated
  in theta
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.one_step`: one step by the fast or the generic method (002
  Sec. 3.3, Appendix A)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.gaits`: gait types A-D, settling, period-1 gaits (002 Sec.
  3.3)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.boundaries`: the gait-type boundaries in mu (002 Fig. 3.5)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_friction.basins`: attraction window, stable gaits and basins (002 Sec.
  3.4, Fig. 3.8)
"""

from __future__ import annotations

from mjpoincare.analysis.theory.rimless_wheel_friction.basins import (
    attraction_window,
    attractors,
    basin_outcome,
    longest_period,
    no_gait_reason,
)
from mjpoincare.analysis.theory.rimless_wheel_friction.boundaries import GaitBoundaries, gait_boundaries
from mjpoincare.analysis.theory.rimless_wheel_friction.gaits import (
    Gait,
    Settled,
    classify,
    classify_record,
    find_gait,
    midstance_rate,
    midstance_x_dot,
    settle,
)
from mjpoincare.analysis.theory.rimless_wheel_friction.one_step import StepRecord, contact_model, step
from mjpoincare.analysis.theory.rimless_wheel_friction.params import (
    ATOL,
    RTOL,
    SLIP_MAX_STEP,
    X_NEUTRAL,
    X_TOL,
    FrictionWheel,
    beta,
    omega_c,
    rigid_wheel,
    slope_bounds,
    validate,
)
from mjpoincare.analysis.theory.rimless_wheel_friction.slip import (
    ImpactValues,
    impact_closed_form,
    slip_affine_coefficients,
    slip_dynamics,
    slipping_impact,
    sticking_impact,
    type_d_linear,
)
from mjpoincare.analysis.theory.rimless_wheel_friction.sticking import (
    attraction_upper_limit,
    attraction_window_rigid,
    critical_friction,
    d_sign_boundary,
    force_ratio,
    impulse_ratio,
    start_slip_threshold,
    sticking_eigenvalue,
    sticking_fixed_point,
    sticking_forces,
    sticking_map,
)

__all__ = ["ATOL", "RTOL", "SLIP_MAX_STEP", "X_NEUTRAL", "X_TOL", "FrictionWheel", "Gait", "GaitBoundaries",
           "ImpactValues", "Settled", "StepRecord", "attraction_upper_limit", "attraction_window",
           "attraction_window_rigid", "attractors", "basin_outcome", "beta", "classify", "classify_record",
           "contact_model", "critical_friction", "d_sign_boundary", "find_gait", "force_ratio", "gait_boundaries",
           "impact_closed_form", "impulse_ratio", "longest_period", "midstance_rate", "midstance_x_dot",
           "no_gait_reason", "omega_c", "rigid_wheel", "settle", "slip_affine_coefficients", "slip_dynamics",
           "slipping_impact", "slope_bounds", "start_slip_threshold", "step", "sticking_eigenvalue",
           "sticking_fixed_point", "sticking_forces", "sticking_impact", "sticking_map", "type_d_linear", "validate"]
