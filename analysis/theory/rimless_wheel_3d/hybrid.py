"""Exact event-driven reference of the 3D rimless wheel, independent of the closed forms of
:mod:`mjpoincare.analysis.theory.rimless_wheel_3d`.

Model (the physics of 001 = Coleman, Chatterjee & Ruina 1997, Sec. 3, solved generically; m = l = g = 1):

* Stance (001 eq 3, replaced by Newton-Euler): the stance foot P is a frictional ball joint (no slip, no torsional
  friction). The state is the rotation matrix R (body -> slope frame, 9 entries) and the body angular velocity
  Omega; R' = R [Omega]x and, about P in body axes, I_P Omega' + Omega x I_P Omega = e3 x (R^T g) with
  I_P = diag(J/2 + 1, J + 1, J/2), g = (sin alpha, 0, -cos alpha), hub = P + R e3, body e2 = axle.
* Impact (001 eqs 4-6, NOT via the Euler-rate matrix T): the event is the height of the next foot,
  hub_z + (R d)_z with d = (sin 2beta, 0, -cos 2beta) the next spoke in body axes, crossing zero downwards (that
  it happens at pitch +pi/n is a result, not an input). The rates jump by conservation of angular momentum about
  the new foot P': (I_C + |r'|^2 1 - r' r'^T) omega+ = I_C omega- + r' x (omega- x r), r = G - P, r' = G - P'
  (world frame, I_C = R diag(J/2, J, J/2) R^T); then R -> R Ry(-2 beta) (the new stance spoke becomes body -e3).
  The impulse at the new foot is v_G+ - v_G-; the trailing foot gets none.
* Integration: ``solve_ivp(method="DOP853", rtol=1e-12, atol=1e-12)`` with terminal events (impact; the trailing
  foot touching again = rolled back; hub height below 0.05 = fallen). Unilateral contact and friction are not
  enforced; :class:`StepRecord` reports the minimum normal force and the friction the stance needs.

Euler angles are only used at the section: R = Rz(psi) Rx(phi) Ry(theta) (phi = asin R[2,1],
theta = atan2(-R[2,0], R[2,2]), psi = atan2(-R[0,1], R[1,1])) and omega = psi_dot e_z + phi_dot x' + theta_dot y''.
The post-impact section state is x = (psi, phi, psi_dot, phi_dot, theta_dot) at theta = -pi/n (5-D; 001 uses the
6-D q with one extra eigenvalue 0). The mid-stance section is the upward crossing theta = 0, the section a soft-
contact simulator should use; its map is conjugate to the post-impact map (same eigenvalues).

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler`: the 3-1-2 Euler angles, rates and state in scalar
  form (001 Sec. 2, eq 2)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_dynamics`: the stance ODE, its events and the angular-
  momentum impact (001 Sec. 3)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_maps`: the post-impact and mid-stance maps, fixed points and
  Jacobians (001 Sec. 4)
* :mod:`~mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_eigen`: the named eigenvalues (001 Sec. 8.1, Table 2) and
  the analytic summary
"""

from __future__ import annotations

from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_dynamics import ATOL, FALLEN_HEIGHT, MAX_STANCE_TIME, RTOL
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_eigen import (
    Eigen3D,
    analytic_summary,
    eigenvalues_3d,
    family_tangent,
    identify_eigenvalues,
    midstance_eigenvalues,
    minimum_stable_slope,
    transverse_modulus,
)
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_euler import (
    angular_velocity,
    euler_angles,
    euler_rates,
    euler_state,
    pose,
)
from mjpoincare.analysis.theory.rimless_wheel_3d.hybrid_maps import (
    StepRecord,
    impact_rates,
    jacobian,
    midstance_fixed_point,
    midstance_jacobian,
    midstance_map,
    midstance_state,
    planar_fixed_point,
    simulate,
    step,
    step_record,
)

__all__ = ["ATOL", "FALLEN_HEIGHT", "MAX_STANCE_TIME", "RTOL", "Eigen3D", "StepRecord", "analytic_summary",
           "angular_velocity", "eigenvalues_3d", "euler_angles", "euler_rates", "euler_state", "family_tangent",
           "identify_eigenvalues", "impact_rates", "jacobian", "midstance_eigenvalues", "midstance_fixed_point",
           "midstance_jacobian", "midstance_map", "midstance_state", "minimum_stable_slope", "planar_fixed_point",
           "pose", "simulate", "step", "step_record", "transverse_modulus"]
