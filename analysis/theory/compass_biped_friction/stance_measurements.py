"""Stance measurements of the compass biped with Coulomb friction, on rows recorded from a simulator (numpy only):
the stance foot's motion and the contact force ratio per step, the stance phases (stick / slip+ / slip-), the
impact kind and the slide just after the impact, and the same read from the exact step of Gamus & Or (2015, Secs.
4-5, eq 27) through :func:`mjpoincare.analysis.theory.compass_biped_friction.stance_foot_motion`.

A row is (time, stance leg, qpos (x, z, hinge 0, hinge 1), qvel): the ``compass-biped`` model's hip slides and
absolute leg hinges, the stance hinge being 002's theta1 and the swing hinge -theta2.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from mjpoincare.analysis.contact_modes import MERGE_PHASE, MODE_NAMES, merge_short_runs, run_starts, speed_modes
from mjpoincare.analysis.theory import compass_biped_friction as theory

IMPACT_TIMECONSTS = 3.0  # contact time constants after a heel strike at which x_dot+ is read
RELEASE_SKIP = 5e-3  # s after heel strike excluded from force ratios and phase labels: the soft impact's transient
V_SLIP = 5e-3  # m/s: stance foot tangential speed above which a row slips (rimless-wheel-friction's fast value)


def reference_at(ref: theory.ReferenceTrajectory, phase: np.ndarray) -> tuple[np.ndarray, ...]:
    """Vectorised :meth:`ReferenceTrajectory.evaluate` (cubic Hermite, linear continuation past the end)."""
    t = ref.times
    ph = np.clip(phase, t[0], None)
    i = np.clip(np.searchsorted(t, ph, side="right") - 1, 0, len(t) - 2)
    h = t[i + 1] - t[i]
    s = np.clip((ph - t[i]) / h, 0.0, 1.0)
    s2, s3 = s * s, s * s * s
    h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, (s3 - 2 * s2 + s) * h, -2 * s3 + 3 * s2, (s3 - s2) * h
    out = []
    for j in (0, 1):
        out.append(h00 * ref.theta[i, j] + h10 * ref.theta_dot[i, j] + h01 * ref.theta[i + 1, j]
                   + h11 * ref.theta_dot[i + 1, j])
    for j in (0, 1):
        w = (h00 * ref.theta_dot[i, j] + h10 * ref.theta_ddot[i, j] + h01 * ref.theta_dot[i + 1, j]
             + h11 * ref.theta_ddot[i + 1, j])
        out.append(w)
    past = np.maximum(phase - t[-1], 0.0)
    out[0] = np.where(past > 0, ref.theta[-1, 0] + ref.theta_dot[-1, 0] * past, out[0])
    out[1] = np.where(past > 0, ref.theta[-1, 1] + ref.theta_dot[-1, 1] * past, out[1])
    out[2] = np.where(past > 0, ref.theta_dot[-1, 0], out[2])
    out[3] = np.where(past > 0, ref.theta_dot[-1, 1], out[3])
    return tuple(out)


def stance_rows(rows: np.ndarray, strike_times: list[float], bp: theory.FrictionBiped, radius: float
                ) -> list[dict[str, np.ndarray]]:
    """Trajectory 0 split into stances (heel strike to heel strike): phase t, stance-foot tangential velocity and
    height, and |f_t/f_n| from the momentum rate (f = dP/dt - M g, the stance foot the only contact)."""
    t, st = rows[:, 0], rows[:, 1].astype(int)
    qpos, qvel = rows[:, 2:6], rows[:, 6:10]
    idx = np.arange(len(t))
    q_st, qd_st = qpos[idx, 2 + st], qvel[idx, 2 + st]
    lever = bp.l - radius
    v_t = qvel[:, 0] - bp.l * qd_st * np.cos(q_st)  # rolling contact point of the stance foot sphere
    height = qpos[:, 1] - lever * np.cos(q_st) - radius
    m, mh, b = bp.m, bp.m_h, bp.b
    total = 2 * m + mh
    px = total * qvel[:, 0] - m * b * (qvel[:, 2] * np.cos(qpos[:, 2]) + qvel[:, 3] * np.cos(qpos[:, 3]))
    pz = total * qvel[:, 1] + m * b * (qvel[:, 2] * np.sin(qpos[:, 2]) + qvel[:, 3] * np.sin(qpos[:, 3]))
    fx = np.gradient(px, t) - total * bp.g * math.sin(bp.slope)
    fz = np.gradient(pz, t) + total * bp.g * math.cos(bp.slope)
    strikes = [0.0, *strike_times]
    out = []
    for t0, t1 in itertools.pairwise(strikes):
        sel = (t > t0) & (t < t1)
        out.append({"t": t[sel] - t0, "v_t": v_t[sel], "height": height[sel], "ratio": fx[sel] / fz[sel],
                    "f_n": fz[sel], "x": qpos[sel, 0] - lever * np.sin(q_st[sel])})
    return out


def impact_velocity(stance: dict[str, np.ndarray], timeconst: float) -> float:
    """The stance foot's tangential velocity just after the heel strike (002's x_dot+, Sec. 4.2: 0 for a sticking
    impact): its value IMPACT_TIMECONSTS contact time constants after the strike, when MuJoCo's soft impact is over
    (it relaxes the contact velocity at the rate 2/timeconst: e^-6 of the pre-impact velocity is left). Measured:
    Gait B's foot then moves at 1.7e-3 m/s (fast) while it starts its slip+, Gait II's at 0.026-0.057 m/s during
    its 5 ms slip (002 0.084 at 0+); a line through [5, 10] ms extrapolated to 0 misread both."""
    t, v = stance["t"], stance["v_t"]
    return float(v[min(int(np.searchsorted(t, IMPACT_TIMECONSTS * timeconst)), len(t) - 1)])


def impact_slip(stance: dict[str, np.ndarray]) -> float:
    """How far the new stance foot slides along the slope in the first RELEASE_SKIP after it meets the slope (the
    window :func:`phases` skips): from the touchdown, where its height crosses 0 (interpolated between rows), to
    RELEASE_SKIP later (m, > 0 forward)."""
    t, h, x = stance["t"], stance["height"], stance["x"]
    i = int(np.argmax(h <= 0.0))
    frac = h[i - 1] / (h[i - 1] - h[i]) if i > 0 else 0.0
    t_on = t[i - 1] + frac * (t[i] - t[i - 1]) if i > 0 else t[0]
    x_on = x[i - 1] + frac * (x[i] - x[i - 1]) if i > 0 else x[0]
    return float(np.interp(t_on + RELEASE_SKIP, t, x) - x_on)


def phases(stance: dict[str, np.ndarray], dt: float) -> list[tuple[str, float]]:
    """Stance phases (stick / slip+ / slip-) and start times from the stance foot's tangential speed against V_SLIP
    (rows within RELEASE_SKIP of either heel strike dropped), by the shared classifier
    (:func:`mjpoincare.analysis.contact_modes.speed_modes`, runs shorter than
    :data:`~mjpoincare.analysis.contact_modes.MERGE_PHASE` merged)."""
    t, v = stance["t"], stance["v_t"]
    keep = (t > RELEASE_SKIP) & (t < t[-1] - RELEASE_SKIP)
    t, v = t[keep], v[keep]
    group = np.zeros(t.size, int)
    mode = merge_short_runs(group, speed_modes(v, V_SLIP).astype(int), max(1, round(MERGE_PHASE / dt)))
    return [(MODE_NAMES[int(mode[i])], float(t[i])) for i in run_starts(group, mode)]


def classified_pattern(g: theory.Gait, dt: float) -> list[tuple[str, float]]:
    """The exact step's stance phases as :func:`phases` sees them: its stance-foot speed (002 eq 27,
    :func:`mjpoincare.analysis.theory.compass_biped_friction.stance_foot_motion`) sampled every ``dt`` and classified
    by the same threshold, windows and merging as the simulated rows (Gait II's 5.2 ms slip+ ends inside the first
    RELEASE_SKIP: seen as "stick" on both sides; that slip is the impact_slip check's)."""
    t = dt * np.arange(1, math.floor(g.record.period / dt) + 1)
    _, v = theory.stance_foot_motion(g.biped, g.z, t, g.actuation)
    return phases({"t": t, "v_t": v}, dt)


def analytic_ratio(g: theory.Gait, t: np.ndarray) -> np.ndarray:
    """f_t/f_n of the analytic step at phases ``t`` (stick phases: foot fixed; from the point masses' accelerations
    of the reference trajectory, 002 eq 27)."""
    bp = g.biped
    ref = theory.reference_trajectory(bp, g.z, g.actuation, samples=2001)
    r1, r2, w1, w2 = reference_at(ref, t)
    a1 = np.interp(t, ref.times, ref.theta_ddot[:, 0])
    a2 = np.interp(t, ref.times, ref.theta_ddot[:, 1])
    s1, c1, s2, c2 = np.sin(r1), np.cos(r1), np.sin(r2), np.cos(r2)
    hip = np.stack([bp.l * (c1 * a1 - s1 * w1**2), bp.l * (-s1 * a1 - c1 * w1**2)])
    swing = hip + bp.b * np.stack([c2 * a2 - s2 * w2**2, s2 * a2 + c2 * w2**2])
    acc = bp.m_h * hip + bp.m * (bp.d / bp.l) * hip + bp.m * swing
    total = bp.total_mass
    fx = acc[0] - total * bp.g * math.sin(bp.slope)
    fz = acc[1] + total * bp.g * math.cos(bp.slope)
    return fx / fz
