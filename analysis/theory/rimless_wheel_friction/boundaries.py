"""Boundaries in mu between the gait types A-D of the rimless wheel with Coulomb friction (002 Sec. 3.3, Fig. 3.5).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3.3 and Fig. 3.5: the A/B, B/C and D+/D- boundaries, the lower end of the C branch and the edges of the D branch,
located by bisection in mu on the simulator; derivation page docs/theory/stick-slip.md, Secs. 2 and 5.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_friction.gaits import _c_fixed_point, classify_record, find_gait
from mjpoincare.analysis.theory.rimless_wheel_friction.one_step import StepRecord, step
from mjpoincare.analysis.theory.rimless_wheel_friction.params import X_NEUTRAL, FrictionWheel, validate
from mjpoincare.analysis.theory.rimless_wheel_friction.slip import type_d_linear
from mjpoincare.analysis.theory.rimless_wheel_friction.sticking import (
    critical_friction,
    impulse_ratio,
    start_slip_threshold,
    sticking_fixed_point,
)
from scipy.optimize import brentq


def _bisect(pred: Callable[[float], bool], lo: float, hi: float, tol: float) -> float:
    """Boundary between pred(lo) = False and pred(hi) = True by bisection."""
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if pred(mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@dataclass(frozen=True)
class GaitBoundaries:
    """Boundaries in mu for one (kappa, n, alpha) (002 Sec. 3.3; docs/theory/stick-slip.md Secs. 2, 5 for the paper
    set):
    ``ab`` A/B (= max(mu_c, |sigma~|): stick throughout needs both), ``bc`` B/C (the B gait's impact starts to
    slip), ``c_lower`` the lower end of the C branch (continued from B/C; it tends to tan(alpha), where C grazes into
    the D orbit with Delta x_dot = 0, and Newton stops a few 1e-6 above), ``d_sign`` D+/D- (Delta x_dot = 0;
    equals tan(alpha), :func:`d_sign_boundary`), ``d_upper``/``d_lower`` the edges of the D branch (detachment
    above, backward roll below), ``start_slip`` the mu below which the slowest admissible start slips at once
    (:func:`start_slip_threshold`). NaN where a branch is not found."""

    ab: float
    bc: float
    c_lower: float
    d_sign: float
    d_upper: float
    d_lower: float
    start_slip: float


def _d_record(w: FrictionWheel) -> StepRecord | None:
    """The step of the Type D gait at its formal fixed point (:func:`type_d_linear`, exact while the step is a D
    step because the D map is affine in theta_dot^2), or None if that step is not a D step returning to itself."""
    th, _ = type_d_linear(w)
    if not math.isfinite(th):
        return None
    rec = step(w, (th, X_NEUTRAL))
    label = classify_record(rec)
    if label is None or label[0] != "D" or abs(rec.theta_dot - th) > 1e-7 * th:
        return None
    return rec


@lru_cache(maxsize=16)
def gait_boundaries(kappa: float, spokes: int, slope: float, tol: float = 1e-6) -> GaitBoundaries:
    """Locate the gait-type boundaries of :class:`GaitBoundaries` by bisection in mu on the simulator (to ``tol``):
    A/B on whether the eq-16 orbit stays a Type A step; B/C on :func:`find_gait` "B"; C's lower end on
    :func:`find_gait` "C" continued downwards from B/C; the D edges on whether the D fixed point's step is a D step
    (:func:`_d_record`); D+/D- by brentq on its Delta x_dot."""

    def wheel(mu: float) -> FrictionWheel:
        return FrictionWheel(spokes, kappa, slope, mu)

    base = wheel(math.inf)
    validate(base)
    nan = math.nan
    th_a = sticking_fixed_point(base)

    def a_holds(mu: float) -> bool:
        rec = step(wheel(mu), (th_a, 0.0))
        return rec.failure is None and classify_record(rec) == "A"

    sig = abs(impulse_ratio(spokes, kappa))
    ab = _bisect(a_holds, 0.0, 1.5 * max(critical_friction(base)[0], sig) + 1e-3, tol)
    bc = _bisect(lambda mu: find_gait(wheel(mu), "B") is not None, 0.5 * sig, ab * (1 - 1e-4), tol)

    c_lower = nan
    first = find_gait(wheel(bc - 1e-3), "C")
    if first is not None:
        last = [first.fixed_point]

        def c_exists(mu: float) -> bool:
            z_star = _c_fixed_point(wheel(mu), last[0])
            if z_star is not None:
                last[0] = z_star
            return z_star is not None

        hi_c = bc - 1e-3
        while c_exists(hi_c - 0.005) and hi_c > 0.01:
            hi_c -= 0.005
        c_lower = float(_bisect(c_exists, hi_c - 0.005, hi_c, tol))

    def d_exists(mu: float) -> bool:
        return _d_record(wheel(mu)) is not None

    grid = np.linspace(0.01, min(1.4, 1.2 * ab), 30)
    have = [float(mu) for mu in grid if d_exists(mu)]
    if not have:
        return GaitBoundaries(ab, bc, c_lower, nan, nan, nan, start_slip_threshold(base))
    lo_in, hi_in = have[0], have[-1]
    step_mu = float(grid[1] - grid[0])
    d_lower = float(_bisect(d_exists, max(lo_in - step_mu, 1e-6), lo_in, tol)) if lo_in > grid[0] else nan
    d_upper = float(_bisect(lambda mu: not d_exists(mu), hi_in, hi_in + step_mu, tol))

    def dx(mu: float) -> float:
        rec = _d_record(wheel(mu))
        return rec.dx if rec is not None else nan

    d_sign = float(brentq(dx, lo_in, hi_in, xtol=tol)) if dx(lo_in) * dx(hi_in) < 0 else nan
    return GaitBoundaries(ab, bc, c_lower, d_sign, d_upper, d_lower, start_slip_threshold(base))
