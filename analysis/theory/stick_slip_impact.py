"""The frictional plastic impact at the swing foot of a planar robot (002 Sec. 2.2, eqs 5, 37-40).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 2.2 and Appendix A.2: the perfectly plastic sticking impact (37)-(38) if its impulse lies in the cone (eq 5),
else the slipping impact (39)-(40) with the corrected direction Gamma~ = (s mu, 1)^T and s taken from the sticking
impulse; derivation page docs/theory/stick-slip.md, Secs. 4 and 7.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from mjpoincare.analysis.theory.stick_slip_contact import ContactModel, Matrix, Vector, cone_margin
from numpy.typing import ArrayLike


class ImpactResult(NamedTuple):
    """Result of :func:`impact`: ``kind`` "sticking" or "slipping", post-impact velocities, the impulse
    F~ = (F~_t, F~_n) at the swing foot, the sign s of the slipping impulse (0 for sticking), the swing foot's
    post-impact velocity v~+ = W~ qd+, the old stance foot's post-impact normal velocity (> 0: it lifts off) and
    ``consistent`` (F~_n > 0, positive slip denominator, v~_t+ opposite to s, old foot not pushed into the ground).
    """

    kind: str
    qd_plus: Vector
    impulse: Vector
    sign: float
    swing_velocity: Vector
    liftoff_velocity: float
    consistent: bool


def sticking_impact(mass: Matrix, swing_jac: Matrix, qd_minus: Vector) -> tuple[Vector, Vector]:
    """Perfectly plastic sticking impact at the swing foot (002 eqs 37-38):
    F~ = -(W~ M^-1 W~^T)^-1 W~ qd-, qd+ = qd- + M^-1 W~^T F~. Returns (qd+, F~)."""
    minv_wt = np.linalg.solve(mass, swing_jac.T)
    impulse = -np.linalg.solve(swing_jac @ minv_wt, swing_jac @ qd_minus)
    return qd_minus + minv_wt @ impulse, impulse


def slipping_impact(
    mass: Matrix, swing_jac: Matrix, qd_minus: Vector, mu: float, sign: float
) -> tuple[Vector, Vector, float]:
    """Slipping impact (002 eqs 39-40, corrected Gamma~ = (s mu, 1)^T): no rebound w~_n^T qd+ = 0 with
    F~ = Gamma~ F~_n, F~_n = -w~_n^T qd- / (w~_n^T M^-1 W~^T Gamma~). Returns (qd+, F~, denominator)."""
    gamma = np.array([sign * mu, 1.0])
    minv_wt = np.linalg.solve(mass, swing_jac.T)
    denominator = float(swing_jac[1] @ minv_wt @ gamma)
    impulse = gamma * (-float(swing_jac[1] @ qd_minus) / denominator)
    return qd_minus + minv_wt @ impulse, impulse, denominator


def impact(model: ContactModel, q: ArrayLike, qd_minus: ArrayLike, mu: float, tol: float = 1e-12) -> ImpactResult:
    """Frictional plastic impact (002 Sec. 2.2 and Appendix A.2): the sticking impact (37-38) if its impulse lies
    in the cone (002 eq 5), else the slipping impact (39-40, corrected) with s = sgn(F~_t,stick).

    No impulse acts at the old stance foot (002's assumption); ``liftoff_velocity`` = w_n^T qd+ of the old foot
    tells whether it actually separates. Relabelling (002 eq 6) is the model's business.
    """
    q = np.asarray(q, dtype=float)
    qd_minus = np.asarray(qd_minus, dtype=float)
    mass = model.mass_matrix(q)
    swing = model.swing_jacobian(q)
    qd_plus, impulse = sticking_impact(mass, swing, qd_minus)
    kind, sign, denominator = "sticking", 0.0, 1.0
    if not (impulse[1] > 0.0 and cone_margin(impulse, mu) >= -tol * abs(impulse[1])):
        sign = 1.0 if impulse[0] > 0.0 else -1.0
        qd_plus, impulse, denominator = slipping_impact(mass, swing, qd_minus, mu, sign)
        kind = "slipping"
    swing_velocity = swing @ qd_plus
    liftoff = float(model.contact_jacobian(q)[1] @ qd_plus)
    scale = tol * max(1.0, float(np.max(np.abs(qd_minus))))
    consistent = bool(impulse[1] > 0.0 and denominator > 0.0 and liftoff >= -scale)
    if kind == "slipping":
        consistent = consistent and sign * float(swing_velocity[0]) <= scale
    return ImpactResult(kind, qd_plus, impulse, sign, swing_velocity, liftoff, consistent)
