"""One step of the compass biped with Coulomb friction: stick-slip stance, frictional heel strike, relabelling.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Secs. 4-5 and Appendix A: the stance by :func:`mjpoincare.analysis.theory.stick_slip.integrate_stance` (eqs 2, 31-35)
until the heel strike theta1 = theta2 > 0 (the scuffing of Sec. 4.1 ignored), the frictional plastic impact (eqs
37-40, corrected), the relabelling of Sec. 4, the post-impact Poincaré map of Sec. 4.2 and the gait types A-D;
derivation page docs/theory/stick-slip.md, Secs. 3-4.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any

import numpy as np
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.actuation import PASSIVE, Actuation
from mjpoincare.analysis.theory.compass_biped_friction.dynamics import (
    _model,
    energy,
    heel_strike_after_scuff,
    kinetic_energy,
    section_state,
    swing_foot,
)
from mjpoincare.analysis.theory.compass_biped_friction.params import NQ, FrictionBiped, Vector
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

#: Longest stance integrated (s) before a step counts as "stalled" (002's period is ~0.75 s).
T_MAX = 5.0


@dataclass(frozen=True)
class StepRecord:
    """One step from a post-impact section state (see :func:`step`).

    ``z0`` the start (theta*, theta1_dot+, theta2_dot+, x_dot+); ``z`` the next post-impact section state (NaN on
    failure); ``failure`` None or the stance outcome ("detached", "painleve", "fell", "backward", "stalled",
    "chatter", "solver"), "scuff" (the stance ended at theta1 = theta2 <= 0, no heel strike ahead) or "impact" (the
    impact law is inconsistent: F~_n <= 0, slip reversal, or the old stance foot pushed into the ground); ``impact``
    "sticking"/"slipping"; ``phases`` the stance modes in order ("stick", "slip+" = forward slip, "slip-", 002
    eq 35) with their start times ``phase_times``; ``period`` T (s); ``step_length`` S = displacement of the stance
    foot over the stance plus the foot separation 2 l sin(theta-) at heel strike (m; the distance the biped advances
    per step); ``slip_distance`` the stance foot's displacement; ``q_pre``, ``qd_pre`` physical state before the
    impact; ``actuator_work`` W_act = int Q . qd dt (J, 002 eq 29); ``friction_work`` int f_t v_t dt (J, <= 0; from
    the energy balance, the normal force does no work); ``impact_loss`` kinetic energy lost at the heel strike (J),
    of which ``impact_loss_tangential`` = -F~_t (v~_t- + v~_t+)/2 by the tangential impulse (the rest,
    -F~_n v~_n-/2, by the normal one); ``impulse`` (F~_t, F~_n) (N s); ``liftoff_velocity`` slope-normal velocity of
    the trailing foot after the impact (m/s); ``min_fn`` min f_n (N); ``late_swing``: the legs passed parallel only
    after the stance leg had passed the normal (theta1 > 0), so the swing foot travelled below the ground ahead of
    the stance foot before emerging (ignored, as the scuffing of 002 Sec. 4.1).

    Only with ``forces=True`` (else NaN): ``max_ratio`` max |f_t/f_n| over the stance (= mu while slipping) at
    ``max_ratio_time`` with the signed value ``max_ratio_sigma``; ``min_swing_height`` the lowest swing-foot height
    inside the stance (m; < 0: the ignored scuffing dip) at ``min_swing_height_time``.
    """

    z0: Vector
    z: Vector
    failure: str | None
    impact: str | None
    phases: tuple[str, ...]
    phase_times: tuple[float, ...]
    period: float
    step_length: float
    slip_distance: float
    q_pre: Vector
    qd_pre: Vector
    actuator_work: float
    friction_work: float
    impact_loss: float
    impact_loss_tangential: float
    impulse: Vector
    liftoff_velocity: float
    min_fn: float
    late_swing: bool
    max_ratio: float = math.nan
    max_ratio_time: float = math.nan
    max_ratio_sigma: float = math.nan
    min_swing_height: float = math.nan
    min_swing_height_time: float = math.nan

    @property
    def impulse_ratio(self) -> float:
        """sigma~ = F~_t/F~_n of the heel-strike impulse (002 Sec. 4.1, Fig. 4.1c 'x')."""
        return float(self.impulse[0] / self.impulse[1])

    @property
    def theta_star(self) -> float:
        """Impact angle theta1 = theta2 at the heel strike (rad)."""
        return float(self.q_pre[0])


def _nan_record(z0: Vector, failure: str, phases: tuple[str, ...], times: tuple[float, ...], t: float,
                q: Vector, qd: Vector, min_fn: float, late: bool) -> StepRecord:
    nan = math.nan
    return StepRecord(z0, np.full(4, nan), failure, None, phases, times, t, nan, nan, q[:NQ].copy(), qd[:NQ].copy(),
                      nan, nan, nan, nan, np.full(2, nan), nan, min_fn, late)


@lru_cache(maxsize=64)
def _late_model(bp: FrictionBiped, actuation: Actuation) -> ss.ContactModel:
    return replace(_model(bp, actuation), impact_guard=lambda q, _qd: heel_strike_after_scuff(q))


def _stance(bp: FrictionBiped, act: Actuation, q0: Vector, qd0: Vector, t_max: float, rtol: float = ss.RTOL
            ) -> tuple[ss.StanceResult, bool]:
    """integrate_stance (002 eqs 2, 31-35) to the heel strike theta1 = theta2 > 0, continued once through a late
    legs-parallel crossing (:func:`heel_strike_after_scuff`), at relative tolerance ``rtol`` (absolute rtol x
    ATOL/RTOL). Returns (stance, continued); a continued stance has the phases of both parts (a phase split at the
    crossing appears twice)."""
    tol = {"rtol": rtol, "atol": rtol * ss.ATOL / ss.RTOL}
    first = ss.integrate_stance(_model(bp, act), q0, qd0, bp.mu, t_max=t_max, **tol)
    q = first.q_end
    if not (first.impacted and q[1] - q[0] < -1e-8 and q[0] > 0.0):
        return first, False
    rest = ss.integrate_stance(_late_model(bp, act), q, first.qd_end, bp.mu, t0=first.t_end, t_max=t_max,
                               mode=first.phases[-1].mode, **tol)
    merged = ss.StanceResult(first.phases + rest.phases, rest.outcome, rest.t_end, rest.q_end, rest.qd_end,
                             min(first.min_normal_force, rest.min_normal_force), {**rest.sections, **first.sections})
    return merged, True


def _collapse(phases: Sequence[ss.Phase]) -> tuple[tuple[str, ...], tuple[float, ...]]:
    """Modes and start times with consecutive repeats merged."""
    modes: list[str] = []
    times: list[float] = []
    for p in phases:
        if not modes or modes[-1] != p.mode:
            modes.append(p.mode)
            times.append(p.t_start)
    return tuple(modes), tuple(times)


def _phase_solutions(model: ss.ContactModel, stance: ss.StanceResult, mu: float) -> list[tuple[str, float, float, Any]]:
    """Re-integrate each phase of a stance from its recorded start (same mode, same tolerances) with a dense
    output: (mode, t0, t1, OdeSolution or None for a zero-length phase)."""
    out: list[tuple[str, float, float, Any]] = []
    ends = [p.t_start for p in stance.phases[1:]] + [stance.t_end]
    n = NQ + 2
    for phase, t1 in zip(stance.phases, ends, strict=True):
        if not t1 > phase.t_start:
            out.append((phase.mode, phase.t_start, t1, None))
            continue

        def rhs(_t: float, y: Vector, mode: str = phase.mode) -> Vector:
            return np.concatenate([y[n:], ss.contact_state(model, y[:n], y[n:], mode, mu).qdd])

        sol = solve_ivp(rhs, (phase.t_start, t1), np.concatenate([phase.q_start, phase.qd_start]), method="DOP853",
                        rtol=ss.RTOL, atol=ss.ATOL, dense_output=True,
                        max_step=ss.SLIP_MAX_STEP if phase.mode != "stick" else np.inf)
        out.append((phase.mode, phase.t_start, t1, sol.sol))
    return out


def _refined_max(fun: Callable[[float], float], t0: float, t1: float, samples: int) -> tuple[float, float]:
    """(max of fun on [t0, t1], where): dense samples and a bounded refinement around the best one."""
    ts = np.linspace(t0, t1, samples)
    vals = np.array([fun(t) for t in ts])
    i = int(np.argmax(vals))
    t_best, v_best = float(ts[i]), float(vals[i])
    if 0 < i < samples - 1:
        res = minimize_scalar(lambda t: -fun(t), bounds=(ts[i - 1], ts[i + 1]), method="bounded",
                              options={"xatol": 1e-12})
        if -res.fun > v_best:
            t_best, v_best = float(res.x), float(-res.fun)
    return v_best, t_best


def _diagnostics(bp: FrictionBiped, model: ss.ContactModel, stance: ss.StanceResult) -> tuple[float, ...]:
    """(max |f_t/f_n|, its time, signed f_t/f_n there, min swing-foot height, its time) over the stance, on the
    re-integrated phases (129 samples each plus a bounded refinement); a slip phase contributes |f_t/f_n| = mu."""
    mu, n = bp.mu, NQ + 2
    ratio = (-math.inf, math.nan, math.nan)
    low = (math.inf, math.nan)
    for mode, t0, t1, sol in _phase_solutions(model, stance, mu):
        if sol is None:
            continue

        def height(t: float, sol: Any = sol) -> float:
            y = sol(t)
            return float(bp.l * (math.cos(y[0]) - math.cos(y[1])))

        # the swing foot starts and ends on the ground: only the interior counts
        lo, hi = (t0, t1)
        if t0 == 0.0:
            lo = t0 + 1e-6 * (t1 - t0)
        if t1 == stance.t_end:
            hi = t1 - 1e-6 * (t1 - t0)
        neg_h, t_h = _refined_max(lambda t: -height(t), lo, hi, 129)
        if -neg_h < low[0]:
            low = (-neg_h, t_h)
        if mode != "stick":
            if ratio[0] < mu:
                ratio = (mu, t0, (-1.0 if mode == "slip+" else 1.0) * mu)
            continue

        def sigma(t: float, sol: Any = sol) -> float:
            y = sol(t)
            f = ss.contact_state(model, y[:n], y[n:], "stick", mu).force
            return float(f[0] / f[1])

        v, t = _refined_max(lambda t: abs(sigma(t)), t0, t1, 129)
        if v > ratio[0]:
            ratio = (v, t, sigma(t))
    return (*ratio, *low)


def step(bp: FrictionBiped, z: ArrayLike, actuation: Actuation | None = None, *, forces: bool = False,
         t_max: float = T_MAX, rtol: float = ss.RTOL) -> StepRecord:
    """One step of the (actuated) biped from the post-impact section state z = (theta*, theta1_dot+, theta2_dot+)
    or (..., x_dot+) (002 Secs. 4-5): the stance by :func:`~mjpoincare.analysis.theory.stick_slip.integrate_stance` (002
    eqs 2, 31-35) until the heel strike theta1 = theta2 > 0 (the swing foot's passages below the ground line are
    ignored, 002 Sec. 4.1), the frictional impact :func:`~mjpoincare.analysis.theory.stick_slip.impact` (002 eqs 37-40,
    corrected) and the relabelling theta1 <-> -theta2, theta1_dot <-> -theta2_dot (002 Sec. 4).
    ``forces``: also compute max |f_t/f_n| and the lowest swing-foot height (re-integrates the phases; slower).
    ``rtol``: the stance integration's relative tolerance (:func:`_stance`).
    """
    act = PASSIVE if actuation is None else actuation
    model = _model(bp, act)
    z0 = np.zeros(4)
    zz = np.asarray(z, dtype=float)
    z0[: zz.size] = zz
    q0, qd0 = section_state(z0)
    mu = bp.mu
    stance, late = _stance(bp, act, q0, qd0, t_max, rtol)
    phases, times = _collapse(stance.phases)
    q, qd = stance.q_end, stance.qd_end
    if not stance.impacted:
        return _nan_record(z0, stance.outcome, phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    if abs(q[1] - q[0]) > 1e-8 or not q[0] > 0.0:
        return _nan_record(z0, "scuff", phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    imp = ss.impact(model, q, qd, mu)
    if not imp.consistent:
        return _nan_record(z0, "impact", phases, times, stance.t_end, q, qd, stance.min_normal_force, late)
    qd_plus = imp.qd_plus
    e_start = energy(bp, q0, qd0)
    e_pre = energy(bp, q, qd)
    w_act = float(qd[5])
    v_minus = model.swing_jacobian(q) @ qd
    extra = _diagnostics(bp, model, stance) if forces else (math.nan,) * 5
    return StepRecord(
        z0=z0,
        z=np.array([0.5 * (q[0] + q[1]), -qd_plus[1], -qd_plus[0], imp.swing_velocity[0]]),
        failure=None,
        impact=imp.kind,
        phases=phases,
        phase_times=times,
        period=stance.t_end,
        step_length=float(swing_foot(bp, q)[0]),
        slip_distance=float(q[2]),
        q_pre=q[:NQ].copy(),
        qd_pre=qd[:NQ].copy(),
        actuator_work=w_act,
        friction_work=e_pre - e_start - w_act,
        impact_loss=kinetic_energy(bp, q, qd) - kinetic_energy(bp, q, qd_plus),
        impact_loss_tangential=float(-imp.impulse[0] * (v_minus[0] + imp.swing_velocity[0]) / 2.0),
        impulse=imp.impulse.copy(),
        liftoff_velocity=imp.liftoff_velocity,
        min_fn=stance.min_normal_force,
        late_swing=late,
        max_ratio=extra[0],
        max_ratio_time=extra[1],
        max_ratio_sigma=extra[2],
        min_swing_height=extra[3],
        min_swing_height_time=extra[4],
    )


def return_map(bp: FrictionBiped, z: ArrayLike, actuation: Actuation | None = None, rtol: float = ss.RTOL
               ) -> Vector:
    """Poincaré map on the post-impact section (002 Sec. 4.2): z -> z' with z = (theta*, theta1_dot+,
    theta2_dot+) (3-D, x_dot+ = 0: Gaits A, B) or (..., x_dot+) (4-D: Gait C); the output has the input's length.
    NaN on a failed step. ``rtol``: as :func:`step`'s."""
    zz = np.asarray(z, dtype=float)
    return step(bp, zz, actuation, rtol=rtol).z[: zz.size]


def classify(record: StepRecord) -> str:
    """Gait type of a step (002 Sec. 4.2): ``"A"`` sticking impact, stick throughout; ``"B"`` sticking impact with
    slip during the stance; ``"C"`` slipping impact with a stick phase during the stance; ``"D"`` slipping impact,
    slip throughout (the Type-D-like gait 002 did not find for the CB). A failed step gives "failed: <reason>"."""
    if record.failure is not None:
        return f"failed: {record.failure}"
    slips = any(p != "stick" for p in record.phases)
    if record.impact == "sticking":
        return "B" if slips else "A"
    return "C" if "stick" in record.phases else "D"


def describe(record: StepRecord) -> str:
    """Human-readable step pattern, e.g. "sticking impact; slip+ -> stick -> slip-" (slip+ = forward slip)."""
    if record.failure is not None:
        return f"failed: {record.failure} after {' -> '.join(record.phases)}"
    return f"{record.impact} impact; {' -> '.join(record.phases)}"
