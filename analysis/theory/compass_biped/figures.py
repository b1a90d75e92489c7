"""The passive gait's phase curves, as 003 (Kisa 2020) Fig. 18 plots one cycle: the stance leg's (theta_st,
dtheta_st) from the post-impact state to the next heel strike (the swing of 003 eq 4.19 to the guard of eq 4.6)."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.theory.compass_biped.one_step import ATOL, RTOL, _swing
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq


def stance_phase_curve(bp: CompassBiped, x_plus: ArrayLike, thetas: ArrayLike) -> NDArray[np.float64]:
    """dtheta_st at the stance angles ``thetas`` over the swing from the post-impact state ``x_plus`` (003 eq 4.19,
    DOP853 to the heel strike of eq 4.6, dense output; each angle located by Brent's method). The stance leg only
    rises over a passive step (dtheta_st > 0), so the curve is single valued; an angle outside the swing's range
    [theta_st+, theta_st-] raises ValueError."""
    sol = _swing(bp, x_plus, RTOL, ATOL, dense=True)
    period = float(sol.t_events[0][0])
    first, last = float(sol.sol(0.0)[0]), float(sol.sol(period)[0])
    out = []
    for theta in np.atleast_1d(np.asarray(thetas, dtype=float)):
        if not first - 1e-12 <= theta <= last + 1e-12:
            raise ValueError(f"theta_st = {theta!r} is outside the swing's range [{first:.6g}, {last:.6g}]")
        theta = min(max(theta, first), last)
        t = brentq(lambda s, th=theta: float(sol.sol(s)[0]) - th, 0.0, period, xtol=1e-14, rtol=1e-14)
        out.append(float(sol.sol(t)[2]))
    return np.asarray(out)
