"""Stance checks of ``compass-biped-friction``: the friction ratio and mu_c of Gait A, and every gait's stance
phases, impact kind and slide just after the impact, measured on MuJoCo's recorded rows by
:mod:`mjpoincare.analysis.theory.compass_biped_friction.stance_measurements` and compared with the exact step of Gamus &
Or (2015, Secs. 4-5, eq 27) read the same way.
"""

from __future__ import annotations

import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.analysis.theory.compass_biped_friction.stance_measurements import (
    IMPACT_TIMECONSTS,
    RELEASE_SKIP,
    V_SLIP,
    analytic_ratio,
    classified_pattern,
    impact_slip,
    impact_velocity,
    phases,
)


def stance_checks(g: theory.Gait, name: str, stances: list[dict[str, np.ndarray]], dt: float, timeconst: float,
                  tol: dict[str, float], extras: dict[str, object]) -> list[checks.Check]:
    """Checks on the settled stances of trajectory 0 (``stances`` from
    :func:`mjpoincare.analysis.theory.compass_biped_friction.stance_measurements.stance_rows`): Gait A's friction ratio
    and mu_c (002 Sec. 4.1); every gait's phase sequence and switch times against the exact step classified the same
    way, its impact kind (002 Sec. 4.2) and the foot's slide in the window the phase labels skip; measured values go
    into ``extras``."""
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
