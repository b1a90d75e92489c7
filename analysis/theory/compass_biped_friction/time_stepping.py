"""Compass biped with Coulomb friction by complementarity time-stepping: a second, independent computation of the
stick-slip gaits of 002 (Gamus & Or) Secs. 4-5.

:mod:`~mjpoincare.analysis.theory.compass_biped_friction` is event-driven: eq 27's matrices in the stance-foot
coordinates (theta1, theta2, x, y), a stick / slip+ / slip- mode per phase with its own force law (002 eqs 31-35), event
functions for every mode switch, and the impact law split into its sticking and slipping cases (eqs 37-40). Nothing of
that is used here.

* **Coordinates and equations.** Floating base q = (x_h, y_h, phi1, phi2): the hip in the slope frame (x downhill,
  y along the slope normal) and the absolute angle of each leg, hip -> foot direction (sin phi, -cos phi) from the
  slope normal. The Lagrangian of the three point masses (hip ``m_h``; leg masses ``m`` at ``b = l - d`` from the
  hip), L = 1/2 sum m |p_dot|^2 - sum m g (p_y cos alpha - p_x sin alpha), gives
  M = [[M_tot, 0, m b cos phi1, m b cos phi2], [0, M_tot, m b sin phi1, m b sin phi2],
       [., ., m b^2, 0], [., ., 0, m b^2]],
  M q_ddot = F(q, q_dot) + J^T lambda with F = (M_tot g sin alpha + m b (sin phi1 phi1_dot^2 + sin phi2 phi2_dot^2),
  -M_tot g cos alpha - m b (cos phi1 phi1_dot^2 + cos phi2 phi2_dot^2), -m g b sin(phi1 - alpha),
  -m g b sin(phi2 - alpha)) plus the actuation, and each foot r_i = (x_h + l sin phi_i, y_h - l cos phi_i) with
  the Jacobian rows (t, n) = ([1, 0, l cos phi_i], [0, 1, l sin phi_i]) in its columns (x_h, y_h, phi_i).
* **Actuation** as physical couples (002 Sec. 5): an ankle torque ``ankle`` on the stance leg, reacted by the
  ground, and a hip torque ``hip`` on the inter-leg angle phi2 - phi1, reacted by the stance leg; their generalised
  forces follow from virtual work: Q_phi1 = -ankle - hip, Q_phi2 = hip (the stance leg is leg 1; its 002 angle is
  theta1 = -phi1, the swing leg's theta2 = phi2).
* **Contact** by the Stewart-Trinkle / Anitescu-Potra time-stepping scheme (see docs/references.md): per step h,
  M (v+ - v) = h F(q, v, t) + J^T P, q+ = q + h v+, with the stance foot's impulse P = (P_t, P_n) solving the
  Signorini-Coulomb complementarity problem 0 <= P_n _|_ g/h + v_n+ >= 0, |P_t| <= mu P_n, P_t = -mu P_n sgn(v_t+)
  while sliding (maximal dissipation), enumerated over its four cases (free, stick, slide+, slide-). The stick/slip
  phases are whatever case each step's problem takes; no mode logic and no force law per mode. A step in which the
  case changes is shortened to end where the case it leaves stops being valid (its complementarity margin crosses
  0, :func:`case_margin`), so that the switch does not leave an O(h) error that depends on where it falls in the
  step grid (which would make the map's central differences noisy).
* **Heel strike.** The swing foot's contact is armed once the foot is ahead of the stance foot and above the slope
  (002 Sec. 4.1 ignores the scuffing before that); the step in which the armed foot would pass the slope is
  shortened so that it lands exactly (secant on the step fraction), and the plastic frictional impact is the same
  complementarity problem with h = 0 for both feet at once (inelastic: v_n+ >= 0 _|_ P_n >= 0 at each foot, Coulomb
  cone), 16 cases enumerated. Before it, the stance foot's velocity is made consistent at the landing configuration
  (:func:`_consistent`), for the same reason. Whether the impact sticks or slips, and whether the old stance foot
  lifts off, are outputs of that problem, not assumptions.

The scheme is first order in h (:func:`stride` at several h; :func:`richardson`), so these modules check the
event-driven gaits' fixed points, multipliers, step lengths, work and phase times to the accuracy its step allows.
They import no MuJoCo and nothing of :mod:`~mjpoincare.analysis.theory.compass_biped_friction` but the parameter record
and, for Gait III, the reference trajectory that defines the controller.

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping_model`: the floating-base equations and the
  actuation as couples (002 Sec. 5)
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping_contacts`: the Signorini-Coulomb
  complementarity problem, enumerated
* :mod:`~mjpoincare.analysis.theory.compass_biped_friction.time_stepping_stride`: one stride, its return map, Jacobian
  and Richardson extrapolation
"""

from __future__ import annotations

from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_contacts import (
    CASES,
    LCP_TOL,
    case_margin,
    coulomb_contacts,
)
from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_model import (
    Controller,
    constant_torques,
    energy,
    foot,
    foot_jacobian,
    free_force,
    mass_matrix,
    pd_tracking,
)
from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_stride import (
    FALL_ANGLE,
    LANDING_TOL,
    ROOT_ITERATIONS,
    SWITCH_TOL,
    T_MAX,
    Stride,
    from_section,
    map_jacobian,
    return_map,
    richardson,
    stride,
)

__all__ = ["CASES", "FALL_ANGLE", "LANDING_TOL", "LCP_TOL", "ROOT_ITERATIONS", "SWITCH_TOL", "T_MAX", "Controller",
           "Stride", "case_margin", "constant_torques", "coulomb_contacts", "energy", "foot", "foot_jacobian",
           "free_force", "from_section", "map_jacobian", "mass_matrix", "pd_tracking", "return_map", "richardson",
           "stride"]
