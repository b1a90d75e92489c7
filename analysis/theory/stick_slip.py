"""Generic stick-slip machinery of a planar N-DOF robot with one point stance foot (002 Appendix A).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 2 eqs (1)-(8) and Appendix A eqs (31)-(40); re-derivation on the derivation page
docs/theory/stick-slip.md, Sec. 4.

Notation (002 eq 2, with the sign of (34) fixed): M(q) qdd = -h(q, qd) + W(q)^T f, where h = B + G - E u is
supplied by the model, W = dr/dq = [w_t^T; w_n^T] is the (2, N) Jacobian of the stance foot r (rows: tangential,
normal), f = (f_t, f_n) is the contact force on the robot and W~(q) = dr~/dq is the swing-foot Jacobian.
Contact modes (002 eq 35): ``"stick"`` (v_t = v_n = 0), ``"slip+"`` (v_t = w_t^T qd > 0, f_t = -mu f_n) and
``"slip-"`` (v_t < 0, f_t = +mu f_n). Flight is not modelled: f_n reaching 0 ends the stance as ``"detached"``
(as in 002, which treats it as a failure).

The modules know nothing about a particular robot: a :class:`ContactModel` bundles the callables, the impact
guard (swing-foot height) and optional named failure events (e.g. a rimless wheel rolling back) and sections
(e.g. mid-stance) to record. They never import mujoco.

Corrections to 002 Appendix A (re-derived; also listed on the derivation page, Sec. 7):

* (34) prints qdd = M^-1 (B + G - E u + W^T f); with (2) it must be M^-1 (-B - G + E u + W^T f). (31) and (33)
  are correct as printed.
* The sticking constraint is W(q) qd = 0 (printed "W(q) = 0"), and its derivative is solved for qdd (printed qd).
* (39): the slipping impulse direction is Gamma~ = (s mu, 1)^T (tangential first, like f = (f_t, f_n)); the printed
  (1, s mu)^T swaps the components. The sign s is taken from the plastic (sticking) impulse,
  s = sgn(F~_t,stick): the impulse is projected onto the cone edge it left (Chatterjee-Ruina with e = e_t = 0).
  002's s = -sgn(v~_t^-) agrees whenever v~_t^- != 0 and the slip does not reverse; it is undefined for
  v~_t^- = 0. This impact law cannot represent slip reversal within the impact; :func:`impact` flags it.
* The slip normal force (33) is only meaningful for a positive "normal effective inverse mass"
  w_n^T M^-1 W^T Gamma; a non-positive value is the Painleve case (inconsistent or indeterminate), which 002
  excludes (its ref. [54]); it ends the stance as ``"painleve"``.

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`.stick_slip_contact`: the contact model, forces, accelerations and mode logic (002 eqs 2, 31-35)
* :mod:`.stick_slip_impact`: the frictional plastic impact (002 eqs 5, 37-40)
* :mod:`.stick_slip_stance`: the event-driven integration of one stance (002 Appendix A)
"""

from __future__ import annotations

from mjpoincare.analysis.theory.stick_slip_contact import (
    MODES,
    V_TOL,
    ContactModel,
    ContactState,
    cone_margin,
    contact_state,
    initial_mode,
    mode_from_stick_force,
    slip_normal_force,
    stick_force,
)
from mjpoincare.analysis.theory.stick_slip_impact import ImpactResult, impact, slipping_impact, sticking_impact
from mjpoincare.analysis.theory.stick_slip_stance import (
    ATOL,
    FN_SAMPLES,
    RTOL,
    SLIP_MAX_STEP,
    Phase,
    StanceResult,
    integrate_stance,
)

__all__ = ["ATOL", "FN_SAMPLES", "MODES", "RTOL", "SLIP_MAX_STEP", "V_TOL", "ContactModel", "ContactState",
           "ImpactResult", "Phase", "StanceResult", "cone_margin", "contact_state", "impact", "initial_mode",
           "integrate_stance", "mode_from_stick_force", "slip_normal_force", "slipping_impact", "stick_force",
           "sticking_impact"]
