"""Independent reference for the slotted skate: the planar rigid body integrated, with a Cartesian peg impulse.

Source: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*: the stance ODE (3.1) integrated with ``solve_ivp`` to the slot ends, then the impulse at the new
peg from linear and angular momentum balance of the rigid body in Cartesian form, without (3.6)/(3.7); it checks the
exact map of :mod:`mjpoincare.analysis.theory.slotted_skate.map`.
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.slotted_skate.map import initial_state
from mjpoincare.analysis.theory.slotted_skate.params import MapStep, SlottedSkate, validate
from scipy.integrate import solve_ivp

RTOL = 1e-12
ATOL = 1e-12
#: Longest stance integrated by :func:`simulate_exact` before the motion is declared a spin (3.8), in tau.
MAX_STANCE = 1e6


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _cartesian(sk: SlottedSkate, peg: np.ndarray, D: float, V: float, th: float, om: float):  # type: ignore[no-untyped-def]
    """(r_G, v_G, e_lambda, e_n) of the body engaged at ``peg`` (m = rho = 1)."""
    el = np.array([math.cos(th), math.sin(th)])
    en = np.array([-math.sin(th), math.cos(th)])
    L = sk.L0 + D
    return peg + L * el, V * el + L * om * en, el, en


def _energy_momentum(r_g: np.ndarray, v_g: np.ndarray, om: float, point: np.ndarray) -> tuple[float, float]:
    """E = |v_G|^2/2 + omega^2/2 and h about ``point`` = omega + (r_G - point) x v_G (m = I = 1)."""
    return 0.5 * float(v_g @ v_g) + 0.5 * om * om, om + _cross(r_g - point, v_g)


def simulate_exact(
    sk: SlottedSkate, V0: float, Omega0: float, theta0: float, n_impacts: int, rtol: float = RTOL
) -> list[MapStep]:
    """Independent reference for :func:`iterate`: integrate the stance ODE (3.1) with ``solve_ivp`` (DOP853) and
    terminal events at the slot ends (front crossed with V < 0, rear with V > 0), then insert the new peg at the
    opposite slot end at its plane position P' = r_G - L_new e_lambda and apply the impulse Pi e_n at P' that
    makes the normal velocity of the body point over P' vanish, solved from linear and angular momentum balance
    of the rigid body in Cartesian form (no use of (3.6)/(3.7)). E and H about the peg are evaluated from r_G, v_G
    and omega. Reversals follow from which end the event fires at. Returns the section states after each impact.
    """
    validate(sk)
    q0 = initial_state(sk, V0, Omega0, theta0)
    D, V, th, om = q0.D_plus, V0, theta0, Omega0
    peg = np.zeros(2)
    l0 = sk.L0

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        L = l0 + y[0]
        return [y[1], L * y[3] ** 2, y[3], -2.0 * L * y[1] * y[3] / (1.0 + L * L)]

    def front(_t: float, y: np.ndarray) -> float:
        return float(y[0])

    def rear(_t: float, y: np.ndarray) -> float:
        return float(y[0] - sk.Delta)

    front.terminal, front.direction = True, -1  # type: ignore[attr-defined]
    rear.terminal, rear.direction = True, 1  # type: ignore[attr-defined]
    out: list[MapStep] = []
    for _ in range(n_impacts):
        start_front = D == 0.0
        sol = solve_ivp(
            rhs, (0.0, MAX_STANCE), [D, V, th, om], method="DOP853", rtol=rtol, atol=ATOL * 1e-2,
            events=(front, rear), dense_output=False,
        )  # fmt: skip
        hit_front = sol.t_events[0].size > 0
        if not (hit_front or sol.t_events[1].size > 0):
            raise RuntimeError("no slot end reached (spinning equilibrium?)")
        y = sol.y_events[0][0] if hit_front else sol.y_events[1][0]
        t_end = float(sol.t_events[0][0] if hit_front else sol.t_events[1][0])
        d_end = 0.0 if hit_front else sk.Delta  # snap the event state onto the slot end
        reversed_ = hit_front == start_front
        r_g, v_g, el, en = _cartesian(sk, peg, d_end, float(y[1]), float(y[2]), float(y[3]))
        w = float(y[3])
        d_new = sk.Delta if hit_front else 0.0
        new_peg = r_g - (l0 + d_new) * el
        # Impulse Pi e_n at new_peg: v_G+ = v_G + Pi e_n, w+ = w + (new_peg - r_G) x (Pi e_n); require the normal
        # velocity of the material point at new_peg, e_n . (v_G+ + w+ z x (new_peg - r_G)), to vanish.
        arm = new_peg - r_g
        zx_arm = np.array([-arm[1], arm[0]])
        vn = float(en @ (v_g + w * zx_arm))
        dw_per_pi = _cross(arm, en)
        dvn_per_pi = 1.0 + dw_per_pi * float(en @ zx_arm)
        pi = -vn / dvn_per_pi
        v_g = v_g + pi * en
        w = w + dw_per_pi * pi
        e_plus, h_plus = _energy_momentum(r_g, v_g, w, new_peg)
        out.append(
            MapStep(
                D_plus=d_new, E_plus=e_plus, theta_plus=float(y[2]), H_plus=h_plus, reversed=reversed_,
                duration=t_end,
            )
        )  # fmt: skip
        peg, D, V, th, om = new_peg, d_new, float(v_g @ el), float(y[2]), w
    return out
