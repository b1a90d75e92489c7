"""The pre-impact section of the compass biped with Coulomb friction and the grid search that finds Gait C.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Secs. 4.2 and 5: the heel strike (eqs 37-40) and relabelling from a pre-impact state, the Poincaré map on the
pre-impact section (conjugate to the post-impact map) and a grid-plus-Newton search for period-1 gaits with a slipping
impact (002's Gait C, II); derivation page docs/theory/stick-slip.md, Sec. 3.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.actuation import PASSIVE, Actuation
from mjpoincare.analysis.theory.compass_biped_friction.dynamics import _model
from mjpoincare.analysis.theory.compass_biped_friction.one_step import StepRecord, step
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped, Vector
from mjpoincare.analysis.theory.compass_biped_friction.shooting import NEWTON_TOL
from mjpoincare.analysis.theory.shooting import chord_newton
from numpy.typing import ArrayLike


def impact_from_pre(bp: FrictionBiped, p: ArrayLike, actuation: Actuation | None = None
                    ) -> tuple[Vector | None, ss.ImpactResult]:
    """Heel strike (002 eqs 37-40) and relabelling from a pre-impact state p = (theta, theta1_dot-, theta2_dot-[,
    x_dot-]) at theta1 = theta2 = theta: (post-impact section state z, impact result); z is None when the impact
    law is inconsistent."""
    pp = np.asarray(p, dtype=float)
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    th = float(pp[0])
    q = np.array([th, th, 0.0, 0.0, 0.0, 0.0])
    qd = np.array([pp[1], pp[2], pp[3] if pp.size > 3 else 0.0, 0.0, 1.0, 0.0])
    imp = ss.impact(model, q, qd, bp.mu)
    if not imp.consistent:
        return None, imp
    return np.array([th, -imp.qd_plus[1], -imp.qd_plus[0], imp.swing_velocity[0]]), imp


def pre_impact_map(bp: FrictionBiped, p: ArrayLike, actuation: Actuation | None = None
                   ) -> tuple[Vector, StepRecord | None, ss.ImpactResult]:
    """Poincaré map on the pre-impact section p = (theta, theta1_dot-, theta2_dot-, x_dot-) (conjugate to the
    post-impact map of 002 Sec. 4.2): impact, relabelling, stance. Returns (next p or NaN, record, impact). When the
    stance ends sticking, x_dot- = 0 whatever the start, so on such steps the map is effectively 3-D (the slip ->
    stick transition of Gait C collapses x_dot; one post-impact multiplier is 0, as for the rimless wheel's Type C)."""
    z, imp = impact_from_pre(bp, p, actuation)
    if z is None:
        return np.full(4, math.nan), None, imp
    rec = step(bp, z, actuation)
    if rec.failure is not None:
        return np.full(4, math.nan), rec, imp
    return np.concatenate([rec.q_pre[:1], rec.qd_pre[:3]]), rec, imp


def search_gaits(bp: FrictionBiped, thetas: Sequence[float], rates1: Sequence[float], rates2: Sequence[float],
                 actuation: Actuation | None = None, impact: str = "slipping", candidates: int = 8) -> list[Vector]:
    """Search for period-1 gaits with the given impact kind (default slipping: 002's Gait C, II) on a grid of
    pre-impact states (theta, theta1_dot-, theta2_dot-) with x_dot- = 0 (stuck before the impact): the
    ``candidates`` grid points with the smallest scaled one-step residual max |(p' - p)/(0.05, 0.5, 0.5)| seed a
    Newton shooting on the 3-D pre-impact map (:func:`pre_impact_map`); each converged orbit is returned as its
    post-impact section state z* (4 components), duplicates removed. Cost: one step per grid point."""
    scale = np.array([0.05, 0.5, 0.5])
    scored: list[tuple[float, Vector]] = []
    for th in thetas:
        for w1 in rates1:
            for w2 in rates2:
                p = np.array([th, w1, w2])
                nxt, rec, imp = pre_impact_map(bp, np.append(p, 0.0), actuation)
                if rec is None or imp.kind != impact or not np.all(np.isfinite(nxt)):
                    continue
                scored.append((float(np.max(np.abs((nxt[:3] - p) / scale))), p))
    scored.sort(key=lambda item: item[0])

    def gap(p: Vector) -> Vector:
        nxt, rec, imp = pre_impact_map(bp, np.append(p, 0.0), actuation)
        if rec is None or imp.kind != impact or abs(nxt[3]) > 1e-9:
            return np.full(3, math.nan)
        return nxt[:3] - p

    found: list[Vector] = []
    for _, p in scored[:candidates]:
        p_star = chord_newton(gap, p, tol=NEWTON_TOL)
        if p_star is None:
            continue
        z, _ = impact_from_pre(bp, np.append(p_star, 0.0), actuation)
        if z is not None and not any(np.allclose(z, f, atol=1e-6) for f in found):
            found.append(z)
    return found
