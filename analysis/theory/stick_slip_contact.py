"""Contact forces and mode logic of a planar robot with one point stance foot (002 eqs 2, 31-35).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 2 eqs (1)-(3) and Appendix A eqs (31)-(35): the robot as a :class:`ContactModel` of callables, the sticking force
(31), the slipping normal force (32)-(33), the accelerations (34, sign corrected) and the mode logic (35); derivation
page docs/theory/stick-slip.md, Secs. 4 and 7. Corrections to 002 in :mod:`mjpoincare.analysis.theory.stick_slip`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]

MODES = ("stick", "slip+", "slip-")
#: |v_t| below which a state counts as not slipping when the mode is chosen.
V_TOL = 1e-10


@dataclass(frozen=True)
class ContactModel:
    """A planar robot with one point stance foot (002 Sec. 2), as callables of (q, qd) (arrays of shape (N,)).

    ``mass_matrix`` M(q) (N, N), symmetric positive definite; ``bias`` h(q, qd) = B + G - E u (N,) (002 eq 2);
    ``contact_jacobian`` W(q) (2, N), rows w_t, w_n of the stance foot (002 eq 1); ``contact_jacobian_rate``
    Wdot(q, qd) qd (2,); ``swing_jacobian`` W~(q) (2, N) of the swing foot (002 eq 36); ``impact_guard`` g(q, qd),
    the swing foot's height, whose crossing of 0 in ``guard_direction`` ends the stance with an impact (002 eq 7).
    ``failure_events``: (name, g(q, qd), direction) that end the stance with outcome ``name``.
    ``sections``: (name, g(q, qd), direction) whose first crossing is recorded (non-terminal).
    """

    mass_matrix: Callable[[Vector], Matrix]
    bias: Callable[[Vector, Vector], Vector]
    contact_jacobian: Callable[[Vector], Matrix]
    contact_jacobian_rate: Callable[[Vector, Vector], Vector]
    swing_jacobian: Callable[[Vector], Matrix]
    impact_guard: Callable[[Vector, Vector], float]
    guard_direction: float = -1.0
    failure_events: tuple[tuple[str, Callable[[Vector, Vector], float], float], ...] = ()
    sections: tuple[tuple[str, Callable[[Vector, Vector], float], float], ...] = ()


class ContactState(NamedTuple):
    """Contact force f = (f_t, f_n) on the robot, accelerations qdd, and for slip modes the denominator
    w_n^T M^-1 W^T Gamma of (33) (NaN for stick)."""

    force: Vector
    qdd: Vector
    denominator: float


def _slip_sign(mode: str) -> float:
    return {"slip+": 1.0, "slip-": -1.0}[mode]


def stick_force(mass: Matrix, bias: Vector, jac: Matrix, jac_rate_qd: Vector) -> Vector:
    """Sticking contact force f = (W M^-1 W^T)^-1 (W M^-1 h - Wdot qd) (002 eq 31)."""
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    return np.linalg.solve(jac @ minv[:, 1:], jac @ minv[:, 0] - jac_rate_qd)


def slip_normal_force(
    mass: Matrix, bias: Vector, jac: Matrix, jac_rate_qd: Vector, mu: float, direction: float
) -> tuple[float, float]:
    """Slipping normal force (002 eq 33) for slip direction sgn(v_t) = ``direction``, Gamma = (-direction mu, 1)
    (002 eq 32): f_n = (w_n^T M^-1 h - wdot_n^T qd) / (w_n^T M^-1 W^T Gamma).

    Returns (f_n, denominator); a denominator <= 0 is the Painleve case (002 Appendix A, ref. [54]).
    """
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    gamma = np.array([-direction * mu, 1.0])
    denominator = float(jac[1] @ minv[:, 1:] @ gamma)
    return float(jac[1] @ minv[:, 0] - jac_rate_qd[1]) / denominator, denominator


def contact_state(model: ContactModel, q: Vector, qd: Vector, mode: str, mu: float) -> ContactState:
    """Contact force and accelerations in a given mode: f from (31) (stick) or (32)-(33) (slip), then
    qdd = M^-1 (-h + W^T f) (002 eq 34 with its sign corrected)."""
    mass = model.mass_matrix(q)
    bias = model.bias(q, qd)
    jac = model.contact_jacobian(q)
    rate = model.contact_jacobian_rate(q, qd)
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    minv_h, minv_wt = minv[:, 0], minv[:, 1:]
    if mode == "stick":
        force = np.linalg.solve(jac @ minv_wt, jac @ minv_h - rate)
        denominator = math.nan
    else:
        gamma = np.array([-_slip_sign(mode) * mu, 1.0])
        denominator = float(jac[1] @ minv_wt @ gamma)
        force = gamma * (float(jac[1] @ minv_h - rate[1]) / denominator)
    return ContactState(force, -minv_h + minv_wt @ force, denominator)


def cone_margin(force: ArrayLike, mu: float) -> float:
    """mu f_n - |f_t| (>= 0 inside the Coulomb cone, 002 eq 3); f_n for mu = inf."""
    f_t, f_n = np.asarray(force, dtype=float)
    return float(f_n) if math.isinf(mu) else float(mu * f_n - abs(f_t))


def mode_from_stick_force(force: ArrayLike, mu: float) -> str:
    """Mode logic (002 eq 35) at v_t = 0: "stick" if the sticking force (31) lies in the cone, else slip with
    sgn(v_t) = -sgn(f_t,stick) (the slip that friction at the cone edge opposes)."""
    if cone_margin(force, mu) >= 0.0:
        return "stick"
    return "slip+" if float(np.asarray(force)[0]) < 0.0 else "slip-"


def initial_mode(model: ContactModel, q: ArrayLike, qd: ArrayLike, mu: float, v_tol: float = V_TOL) -> str:
    """Contact mode of a state (002 eq 35): slip in the direction of v_t if |v_t| > v_tol, else the mode of
    :func:`mode_from_stick_force`."""
    q = np.asarray(q, dtype=float)
    qd = np.asarray(qd, dtype=float)
    v_t = float(model.contact_jacobian(q)[0] @ qd)
    if v_t > v_tol:
        return "slip+"
    if v_t < -v_tol:
        return "slip-"
    return mode_from_stick_force(contact_state(model, q, qd, "stick", mu).force, mu)
