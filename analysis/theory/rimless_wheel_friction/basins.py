"""Regions of attraction of the rimless wheel with Coulomb friction: attraction window, stable gaits, basins.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3.4 and Fig. 3.8: the window of post-impact speeds whose first step succeeds, the stable gaits of types A-D+ at a
given mu, and the outcome of a start (gait reached and steps taken); derivation page docs/theory/stick-slip.md, Secs.
2, 5 and 6.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_friction.boundaries import _bisect, gait_boundaries
from mjpoincare.analysis.theory.rimless_wheel_friction.gaits import _GAIT_KINDS, Gait, classify_record, find_gait
from mjpoincare.analysis.theory.rimless_wheel_friction.one_step import step
from mjpoincare.analysis.theory.rimless_wheel_friction.params import FrictionWheel, validate
from mjpoincare.analysis.theory.rimless_wheel_friction.sticking import sticking_fixed_point
from numpy.typing import ArrayLike, NDArray


def attraction_window(w: FrictionWheel, tol: float = 1e-8) -> tuple[float, float]:
    """(theta_dot_min(mu), theta_dot_max(mu)) with x_dot0 = 0 (002 Sec. 3.4, Fig. 3.8a), by bisection (to ``tol``)
    on the first step from (theta_dot0, 0): the lower edge is where it stops rolling back ("backward"), the upper where
    it starts to fail otherwise (f_n -> 0, "detached"; for mu >~ 1e4 the Painleve case, see
    :func:`attraction_upper_limit`). For mu = inf this reproduces :func:`attraction_window_rigid` (eq 26). Later
    steps are not checked: past the first step the post-impact speeds move towards the gait."""
    validate(w)
    ref = sticking_fixed_point(w)

    def backward(th: float) -> bool:
        return step(w, (th, 0.0)).failure == "backward"

    def detached(th: float) -> bool:
        return step(w, (th, 0.0)).failure not in (None, "backward")

    tiny = 1e-9
    lower = _bisect(lambda th: not backward(th), tiny, ref, tol) if backward(tiny) else 0.0
    hi = 2.0 * ref
    while not detached(hi):
        hi *= 1.5
        if hi > 100.0:
            return lower, math.inf
    return lower, _bisect(detached, ref, hi, tol)


@lru_cache(maxsize=64)
def attractors(w: FrictionWheel) -> tuple[Gait, ...]:
    """The stable gaits of types A, B, C and D+ that exist at this mu (cached)."""
    out = []
    for kind in _GAIT_KINDS:
        gait = find_gait(w, kind)
        if gait is not None and gait.kind != "D-" and np.max(np.abs(gait.eigenvalues)) < 1.0:
            out.append(gait)
    return tuple(out)


def longest_period(w: FrictionWheel, mus: Sequence[float]) -> float:
    """The longest period (nondimensional) of the stable gaits of ``w`` at each friction of ``mus`` (0 where there is
    none), and at least the no-slip wheel's sticking gait's (1 if it has none): the time a run of one step needs."""
    periods = [max([g.period for g in attractors(replace(w, mu=float(mu)))], default=0.0) for mu in mus]
    rigid = find_gait(replace(w, mu=math.inf), "A")
    periods.append(rigid.period if rigid is not None else 1.0)
    return max(periods)


def no_gait_reason(w: FrictionWheel) -> str:
    """Why ``w`` has no stable gait of types A-D+ (002 Sec. 3.3): mu below the D branch (the wheel rolls back), or
    none found."""
    edges = gait_boundaries(w.kappa, w.spokes, w.slope)
    if math.isfinite(edges.d_lower) and w.mu < edges.d_lower:
        return (f"mu must be >= {edges.d_lower:.4f} for spokes={w.spokes}, kappa={w.kappa:g}, slope={w.slope:g} (got "
                f"{w.mu:g}): below the Type D branch no stable gait exists and the wheel rolls back (002 Sec. 3.3)")
    return (f"mu={w.mu:g} has no stable gait of types A-D+ for spokes={w.spokes}, kappa={w.kappa:g}, "
            f"slope={w.slope:g} (the reference finds none; 002 Sec. 3.3): choose another mu or kappa")


def _distance(gait: Gait, z: tuple[float, float]) -> float:
    if gait.kind == "C":
        return max(abs(z[0] - gait.fixed_point[0]), abs(z[1] - gait.fixed_point[1]))
    if gait.kind in ("A", "B"):
        return max(abs(z[0] - gait.fixed_point[0]), abs(z[1]))
    return abs(z[0] - gait.fixed_point[0]) if z[1] > 0 else math.inf


def basin_outcome(
    w: FrictionWheel, theta_dot0: ArrayLike, x_dot0: ArrayLike, max_steps: int = 300, tol: float = 1e-4
) -> tuple[NDArray[np.str_], NDArray[np.int64]]:
    """Outcome of the post-impact state(s) (theta_dot0, x_dot0) (broadcast arrays): the label of the stable gait
    reached ("A", "B", "C", "D+", see :func:`attractors`), a failure ("backward", "detached", "painleve", "impact",
    "chatter") or "unsettled", and the number of steps until the state is within ``tol`` of that gait's fixed point
    (theta_dot and x_dot; theta_dot only for D+) after a step of that type (-1 if none). 002 Sec. 3.4: slip enlarges
    the region of attraction but slows the convergence; both are measured here."""
    th, xd = np.broadcast_arrays(np.asarray(theta_dot0, dtype=float), np.asarray(x_dot0, dtype=float))
    labels = np.empty(th.shape, dtype=object)
    steps = np.full(th.shape, -1, dtype=np.int64)
    gaits = attractors(w)
    for idx in np.ndindex(th.shape):
        z = (float(th[idx]), float(xd[idx]))
        label = "unsettled"
        for k in range(1, max_steps + 1):
            rec = step(w, z)
            if rec.failure is not None:
                label = rec.failure
                break
            z = rec.post
            kind = classify_record(rec)
            hit = [g for g in gaits if g.kind == kind and _distance(g, z) < tol]
            if hit:
                label, steps[idx] = hit[0].kind, k
                break
        labels[idx] = label
    return labels.astype(str), steps
