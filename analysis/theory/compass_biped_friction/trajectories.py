"""Trajectories along one step of the compass biped with Coulomb friction: the PD reference, foot motion, scuffing.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst., eq
30 (the joint trajectory theta^r(phi) that Gait III's PD tracker follows), Secs. 4-5 (the stance foot's slip x(t) of
eq 27) and Sec. 4.1 (the swing foot's passages below the ground line, "scuffing", and the legs-parallel crossing);
derivation page docs/theory/stick-slip.md, Secs. 3 and 7.
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.actuation import PASSIVE, Actuation, ReferenceTrajectory
from mjpoincare.analysis.theory.compass_biped_friction.dynamics import _model, section_state
from mjpoincare.analysis.theory.compass_biped_friction.one_step import T_MAX, _phase_solutions, _stance
from mjpoincare.analysis.theory.compass_biped_friction.params import NQ, FrictionBiped, Vector
from mjpoincare.analysis.theory.compass_biped_friction.shooting import Gait
from numpy.typing import ArrayLike
from scipy.optimize import brentq


def reference_trajectory(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                         samples: int = 401) -> ReferenceTrajectory:
    """The joint trajectory theta^r(phi), theta_dot^r(phi) (and theta_ddot) of the step from z* (a gait of 002
    Secs. 4-5, e.g. passive Gait C), on ``samples`` equally spaced phases from 0 to the step period plus the phase
    switches (values from the re-integrated phases). This is the reference of 002 eq 30 and the control sequence a
    simulator's PD tracker needs."""
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    q0, qd0 = section_state(np.asarray(z_star, dtype=float))
    stance, _ = _stance(bp, act, q0, qd0, T_MAX)
    if not stance.impacted:
        raise ValueError(f"the step from {np.asarray(z_star)!r} fails ({stance.outcome})")
    sols = [s for s in _phase_solutions(model, stance, bp.mu) if s[3] is not None]
    grid = np.linspace(0.0, stance.t_end, samples)
    n = NQ + 2
    times: list[float] = []
    th: list[Vector] = []
    om: list[Vector] = []
    al: list[Vector] = []
    for k, (mode, t0, t1, sol) in enumerate(sols):
        inner = grid[(grid > t0) & (grid < t1)]
        ts = np.concatenate([[t0], inner, [t1]] if k == len(sols) - 1 else [[t0], inner])
        for t in ts:
            y = sol(t)
            times.append(float(t))
            th.append(y[0:2].copy())
            om.append(y[n : n + 2].copy())
            al.append(ss.contact_state(model, y[:n], y[n:], mode, bp.mu).qdd[0:2].copy())
    return ReferenceTrajectory(np.array(times), np.array(th), np.array(om), np.array(al))


def stance_foot_motion(bp: FrictionBiped, z_star: ArrayLike, times: ArrayLike, actuation: Actuation | None = None
                       ) -> tuple[Vector, Vector]:
    """(x, x_dot) of the stance foot along the slope at ``times`` after the impact of the step from z (002 Secs.
    4-5: the foot's coordinate x of eq 27, 0 at the impact; x_dot > 0 is forward slip), from the re-integrated
    phases; NaN past the heel strike. A simulator's stance-foot speed can then be classified with the same
    threshold as the exact one (a stick -> slip switch shows in the speed only once it has grown)."""
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    q0, qd0 = section_state(np.asarray(z_star, dtype=float))
    stance, _ = _stance(bp, act, q0, qd0, T_MAX)
    ts = np.asarray(times, dtype=float)
    x, v = np.full(ts.shape, np.nan), np.full(ts.shape, np.nan)
    for _mode, t0, t1, sol in _phase_solutions(model, stance, bp.mu):
        sel = (ts >= t0) & (ts <= t1)
        if sol is not None and sel.any():
            y = sol(ts[sel])
            x[sel], v[sel] = y[2], y[NQ + 2 + 2]
    return x, v


def scuffing_crossings(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                       samples: int = 2001) -> list[tuple[float, float, float]]:
    """Zero crossings of the swing-foot height l(cos theta1 - cos theta2) strictly inside the stance of the step
    from z* (002 Sec. 4.1 "scuffing"): (t, theta1, theta2) of each, from a dense sample of the stance (exact zeros
    on the sample grid, e.g. at a continued legs-parallel crossing, count as crossings)."""
    ref = reference_trajectory(bp, z_star, actuation, samples)

    def height(t: float) -> float:
        r = ref.evaluate(t)
        return math.cos(r[0]) - math.cos(r[1])

    h = np.cos(ref.theta[:, 0]) - np.cos(ref.theta[:, 1])
    out: list[tuple[float, float, float]] = []
    for i in range(1, len(h) - 1):
        t: float | None = None
        if h[i] == 0.0 and h[i - 1] * h[i + 1] < 0.0:
            t = float(ref.times[i])
        elif h[i] * h[i + 1] < 0.0 and i + 1 < len(h) - 1:
            t = float(brentq(height, ref.times[i], ref.times[i + 1], xtol=1e-13))
        if t is not None:
            r = ref.evaluate(t)
            out.append((t, r[0], r[1]))
    return out


def legs_parallel(g: Gait) -> tuple[np.ndarray, float]:
    """Analytic legs-parallel state (theta1, theta1_dot, -theta2_dot) where theta1 + theta2 = 0 rises through 0
    along the step from z* (the MuJoCo hinges are then equal), and the time of it after the impact."""
    ref = reference_trajectory(g.biped, g.z, g.actuation, samples=2001)
    gap = ref.theta[:, 0] + ref.theta[:, 1]
    i = int(np.nonzero((gap[:-1] < 0) & (gap[1:] >= 0))[0][0])
    t = float(brentq(lambda s: sum(ref.evaluate(s)[:2]), ref.times[i], ref.times[i + 1], xtol=1e-13))
    r = ref.evaluate(t)
    return np.array([r[0], r[2], -r[3]]), t
