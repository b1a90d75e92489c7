"""Stance measurements of ``compass-biped-friction`` from MuJoCo's recorded rows, and the checks built on them: the
stance foot's motion and the contact force ratio per step, the stance phases (stick / slip+ / slip-), the impact
kind and the slide just after the impact, each read the same way from the exact step of Gamus & Or (2015, seed
002, Secs. 4-5, eq 27) through :func:`mjpoincare.analysis.theory.compass_biped_friction.stance_foot_motion`.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.theory import compass_biped_friction as theory

IMPACT_TIMECONSTS = 3.0  # contact time constants after a heel strike at which x_dot+ is read
RELEASE_SKIP = 5e-3  # s after heel strike excluded from force ratios and phase labels: the soft impact's transient
V_SLIP = 5e-3  # m/s: stance foot tangential speed above which a row slips (rimless-wheel-friction's fast value)
MERGE_PHASE_S = 2e-3  # phases shorter than this are merged into the previous one (stick-slip flicker at onsets)


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
    """Stance phases (stick / slip+ / slip-) and start times from the stance foot's tangential velocity (rows
    within RELEASE_SKIP of either heel strike dropped), flicker shorter than MERGE_PHASE_S merged."""
    t, v = stance["t"], stance["v_t"]
    keep = (t > RELEASE_SKIP) & (t < t[-1] - RELEASE_SKIP)
    t, v = t[keep], v[keep]
    labels = np.where(v > V_SLIP, "slip+", np.where(v < -V_SLIP, "slip-", "stick"))
    runs: list[list] = []
    for i, lab in enumerate(labels):
        if runs and runs[-1][0] == lab:
            runs[-1][2] = i
        else:
            runs.append([lab, i, i])
    merged: list[list] = []
    for lab, i0, i1 in runs:
        if merged and ((i1 - i0 + 1) * dt < MERGE_PHASE_S or merged[-1][0] == lab):
            merged[-1][2] = i1
        else:
            merged.append([lab, i0, i1])
    return [(str(lab), float(t[i0])) for lab, i0, _ in merged]


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




def stance_checks(g: theory.Gait, name: str, stances: list[dict[str, np.ndarray]], dt: float, timeconst: float,
                  tol: dict[str, float], extras: dict[str, object]) -> list[checks.Check]:
    """Checks on the settled stances of trajectory 0 (``stances`` from :func:`stance_rows`): Gait A's friction
    ratio and mu_c (002 Sec. 4.1); every gait's phase sequence and switch times against the exact step classified
    the same way, its impact kind (002 Sec. 4.2) and the foot's slide in the window the phase labels skip; measured
    values go into ``extras``."""
    rec = g.record
    out: list[checks.Check] = []
    if name == "A":
        demand = theory.critical_friction(g.biped, g.z)
        # 002's mu_c is reached at t = 0+ (just after the impact); MuJoCo's soft impact hides the first ms, so both
        # ratios are compared on the same window [RELEASE_SKIP, T - RELEASE_SKIP] and the measured one extrapolated
        # to 0+ by a quadratic fit over its first 50 ms
        measured, early = [], []
        for st in stances:
            sel = (st["t"] > RELEASE_SKIP) & (st["t"] < st["t"][-1] - RELEASE_SKIP)
            measured.append(float(np.max(np.abs(st["ratio"][sel]))))
            first = sel & (st["t"] < RELEASE_SKIP + 0.05)
            early.append(float(abs(np.polyval(np.polyfit(st["t"][first], st["ratio"][first], 2), 0.0))))
        t_grid = np.linspace(RELEASE_SKIP, rec.period - RELEASE_SKIP, 2000)
        window_th = float(np.max(np.abs(analytic_ratio(g, t_grid))))
        out.append(checks.relative("friction_ratio_window", window_th, float(np.mean(measured)),
                                   tol["friction_ratio"], "", "max |f_t/f_n| over the stance minus 5 ms at each end, "
                                   "MuJoCo momentum rate vs the analytic stick-phase forces"))
        out.append(checks.relative("critical_friction", demand.stance, float(np.mean(early)), tol["friction_ratio"],
                                   "", "mu_c = max |f_t/f_n| (002 Sec. 4.1, at t = 0+): the measured ratio's "
                                   "quadratic fit over 5-55 ms extrapolated to t = 0"))
        extras["critical_friction"] = {"analytic": demand._asdict(), "measured_window": measured,
                                       "measured_extrapolated": early}
    if stances:
        patterns = [phases(st, dt) for st in stances]
        slip = [float(st["x"][-1] - st["x"][0]) for st in stances]
        lift = [float(np.max(st["height"][(st["t"] > RELEASE_SKIP) & (st["t"] < st["t"][-1] - RELEASE_SKIP)]))
                for st in stances]
        exact = classified_pattern(g, dt)
        expected = [lab for lab, _ in exact]
        seq_ok = [[lab for lab, _ in pat] == expected for pat in patterns]
        out.append(checks.Check(name="phase_sequence", analytic=0.0, simulated=float(len(seq_ok) - sum(seq_ok)),
                                error=float(len(seq_ok) - sum(seq_ok)), tolerance=0.0, kind="count", unit="",
                                why=f"settled steps whose stance phases differ from the exact step's "
                                f"{' -> '.join(expected)} (002: {' -> '.join(rec.phases)}; both labelled by the stance "
                                f"foot speed > {V_SLIP} m/s from {RELEASE_SKIP * 1e3:g} ms after a strike to "
                                f"{RELEASE_SKIP * 1e3:g} ms before the next: a slip that ends sooner after the impact "
                                "is impact_slip's)"))
        if len(expected) > 1 and all(seq_ok):
            times_sim = np.mean([[t0 for _, t0 in pat] for pat in patterns], axis=0)[1:]
            times_th = np.array([t0 for _, t0 in exact[1:]])
            extras["phase_times"] = {"analytic_002": list(rec.phase_times[1:]), "analytic_classified": times_th,
                                     "measured": times_sim}
            out.append(checks.Check(name="phase_times", analytic=times_th, simulated=times_sim,
                                    error=float(np.max(np.abs(times_sim - times_th))), tolerance=tol["phase_time"],
                                    kind="max-abs", unit="s", why="stance phase switch times after the impact, "
                                    f"both classified by the stance-foot speed threshold {V_SLIP} m/s (the exact "
                                    "foot's speed on the same time grid): a stick -> slip switch shows only once the "
                                    "slip speed has grown to the threshold, 10 ms after 002's switch for Gait B"))
        v_impact = [impact_velocity(st, timeconst) for st in stances]
        kinds = ["slipping" if abs(v) > V_SLIP else "sticking" for v in v_impact]
        wrong = float(sum(k != rec.impact for k in kinds))
        out.append(checks.Check(name="impact_kind", analytic=0.0, simulated=wrong, error=wrong, tolerance=0.0,
                                kind="count", unit="",
                                why=f"settled heel strikes whose kind differs from 002's {rec.impact} impact "
                                f"(slipping: the new stance foot's speed {IMPACT_TIMECONSTS:g} contact time constants "
                                f"after the strike above {V_SLIP} m/s)"))
        slips = [impact_slip(st) for st in stances]
        slip_th = float(theory.stance_foot_motion(g.biped, g.z, [RELEASE_SKIP], g.actuation)[0][0])
        v_pre = float((theory.swing_jacobian(g.biped, rec.q_pre) @ np.asarray(rec.qd_pre)[: theory.NQ])[0])
        jump = abs(v_pre - float(g.z[3]))
        out.append(checks.absolute(
            "impact_slip", slip_th, float(np.mean(slips)), jump * timeconst / 2, "m",
            f"the new stance foot's slide over its first {RELEASE_SKIP * 1e3:g} ms on the slope (the window the phase "
            f"labels skip), MuJoCo's from its touchdown vs the exact foot's from the impact (002 eq 27; {rec.impact} "
            f"impact, x_dot+ = {g.z[3]:.3g} m/s): the exact impulse is instantaneous, MuJoCo's soft contact relaxes "
            "the contact velocity at the rate 2/timeconst, so the foot keeps the speed the exact impact takes off, "
            f"|v_t- - x_dot+| = {jump:.3g} m/s (v_t- the exact foot's before it), for about timeconst/2 longer"))
        extras["impact"] = {"analytic": rec.impact, "x_dot_plus_analytic": float(g.z[3]), "measured": kinds,
                            "x_dot_plus_measured": v_impact, "slip_analytic": slip_th, "slip_measured": slips}
        extras["phases"] = {"analytic": list(zip(rec.phases, rec.phase_times, strict=True)),
                            "measured": patterns, "slip_distance_analytic": rec.slip_distance,
                            "slip_distance_measured": slip, "max_stance_foot_height": lift}
    return out
