"""The compass-gait biped at mid-swing: the legs-parallel section, its map, and the swing foot's lowest point.

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4: the legs-parallel section
theta_st = theta_sw of eq 4.20 (the thesis' own search section), its Poincaré map (conjugate to eq 4.18), the
pull-back of a mid-swing state to the post-impact section along the swing of eq 4.19, and the lowest swing-foot height
over the swing (eqs 4.1-4.3; the scuffing that Sec. 4.1 ignores).
"""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.theory.compass_biped.dynamics import impact_map, swing_dynamics, swing_foot_height
from mjpoincare.analysis.theory.compass_biped.one_step import (
    ATOL,
    RTOL,
    _heel_strike,
    _integrate_swing,
    _swing,
    step_period,
)
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar


def _legs_parallel(_t: float, y: NDArray[np.float64]) -> float:
    return y[1] - y[0]


_legs_parallel.terminal = True  # type: ignore[attr-defined]
_legs_parallel.direction = -1.0  # type: ignore[attr-defined]


def legs_parallel_state(bp: CompassBiped, x_plus: ArrayLike) -> tuple[NDArray[np.float64], float]:
    """Mid-swing section theta_st = theta_sw (003 eq 4.20, the thesis' own search section): integrate the passive
    swing (003 eq 4.19) from a post-impact state to the legs-parallel crossing. Returns
    (y, t) with y = (theta, dtheta_st, dtheta_sw) and t the time after the impact; RuntimeError if a heel strike
    or a fall comes first."""
    sol = _integrate_swing(bp, x_plus, (_legs_parallel, _heel_strike(bp)), RTOL, ATOL)
    if sol.t_events[0].size == 0:
        raise RuntimeError(f"the legs do not pass parallel from x = {np.asarray(x_plus)!r}")
    y = sol.y_events[0][0]
    return np.array([0.5 * (y[0] + y[1]), y[2], y[3]]), float(sol.t_events[0][0])


def parallel_return_map(bp: CompassBiped, y: ArrayLike) -> NDArray[np.float64]:
    """Poincaré map on the legs-parallel section y = (theta, dtheta_st, dtheta_sw), theta_st = theta_sw = theta
    (003 eq 4.20): swing to the heel strike, impact (003 eq 4.18), swing to the next legs-parallel crossing.
    Conjugate to :func:`return_map`, so it has the same multipliers. Needs theta < gamma (swing foot below the
    slope, as at the mid-stance scuffing crossing)."""
    th, om_st, om_sw = np.asarray(y, dtype=float)
    x_plus = impact_map(bp, _swing(bp, (th, th, om_st, om_sw), RTOL, ATOL).y_events[0][0])
    return legs_parallel_state(bp, x_plus)[0]


def post_impact_from_parallel(bp: CompassBiped, y: ArrayLike) -> NDArray[np.float64]:
    """Pull a legs-parallel section state y = (theta, dtheta_st, dtheta_sw) (003 eq 4.20) back along the passive
    swing (003 eq 4.19, integrated backward in time) to the post-impact section theta_st + theta_sw = 2 gamma
    (003 eq 4.6). The inverse of :func:`legs_parallel_state`: it maps a simulator's mid-swing sample to the
    post-impact state it came from, under the exact swing dynamics."""
    th, om_st, om_sw = np.asarray(y, dtype=float)

    def after_impact(_t: float, x: NDArray[np.float64]) -> float:
        return x[0] + x[1] - 2.0 * bp.slope

    after_impact.terminal = True  # type: ignore[attr-defined]
    # backward in time the sum first rises through 2 gamma where the swing foot scuffs (h = 0 mid-swing), then
    # falls to 2 gamma at the heel strike that began the swing: only the falling crossing counts
    after_impact.direction = -1.0  # type: ignore[attr-defined]
    sol = _integrate_swing(bp, [th, th, om_st, om_sw], (after_impact,), RTOL, ATOL, backward=True)
    if sol.t_events[0].size == 0:
        raise RuntimeError(f"no post-impact state before the legs-parallel state {np.asarray(y)!r}")
    return np.asarray(sol.y_events[0][0], dtype=float)


def lowest_swing_height(bp: CompassBiped, x_plus: np.ndarray) -> float:
    """The exact model's lowest swing-foot height above the slope (m, along its normal; < 0: below it, the mid-swing
    scuffing that 003 Sec. 4.1 ignores) over the passive swing (003 eq 4.19) from the post-impact state ``x_plus``
    to the heel strike: 003 eqs 4.1-4.3 on 401 samples, the lowest refined by a bounded scalar search."""
    period = step_period(bp, x_plus)
    sol = solve_ivp(lambda _t, y: [y[2], y[3], *swing_dynamics(bp, y[:2], y[2:])], (0.0, period),
                    np.asarray(x_plus, dtype=float), method="DOP853", rtol=RTOL, atol=ATOL,
                    dense_output=True)

    def height(t: float) -> float:
        return swing_foot_height(bp, sol.sol(t)[:2])

    grid = np.linspace(0.0, period, 401)
    i = int(np.argmin([height(t) for t in grid]))
    found = minimize_scalar(height, bounds=(grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]), method="bounded",
                            options={"xatol": 1e-10})
    return float(min(found.fun, height(grid[i])))
