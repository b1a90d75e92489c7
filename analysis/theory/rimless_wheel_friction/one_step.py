"""One step of the rimless wheel with Coulomb friction, by two independent methods.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3.3 and Appendix A: the stance phases with the mode logic of eq 35, then the frictional impact at theta = phi
(eqs 43-45, corrected) and the relabelling. ``method="fast"`` runs the theta-domain phases of
:mod:`mjpoincare.analysis.theory.rimless_wheel_friction.phases`; ``method="generic"`` runs
:mod:`mjpoincare.analysis.theory.stick_slip` on the matrix model of eq 11 (:func:`contact_model`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.rimless_wheel_friction.params import ATOL, RTOL, SLIP_MAX_STEP, X_TOL, FrictionWheel
from mjpoincare.analysis.theory.rimless_wheel_friction.phases import _Builder, _slip_phase, _stick_phase
from mjpoincare.analysis.theory.rimless_wheel_friction.slip import impact_closed_form
from mjpoincare.analysis.theory.rimless_wheel_friction.sticking import sticking_forces
from numpy.typing import NDArray


def contact_model(w: FrictionWheel) -> ss.ContactModel:
    """The wheel as a :class:`mjpoincare.analysis.theory.stick_slip.ContactModel` on q = (x, y, theta) (002 eq 11,
    nondimensional): M = [[1, 0, cos], [0, 1, -sin], [cos, -sin, 1+kappa]], h = B + G with
    B = (-theta_dot^2 sin, -theta_dot^2 cos, 0), G = g(-sin(alpha), cos(alpha), -sin(alpha+theta)),
    W = [[1, 0, 0], [0, 1, 0]], W~ = d(tip of the spoke ahead)/dq (= eq 11's W~_c at theta = phi), guard: height of
    the spoke ahead y + cos(theta) - cos(theta - 2phi). Failure event "backward" (theta_dot -> 0), section
    "midstance" (theta = 0 upward). Needs kappa > 0 (M is singular at kappa = 0)."""
    if not w.kappa > 0.0:
        raise ValueError(f"kappa must be > 0 for the generic model (M is singular at kappa = 0; got {w.kappa!r})")
    k, g, a, p = w.kappa, w.gravity, w.slope, w.phi
    jac = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])

    def mass(q: NDArray[np.float64]) -> NDArray[np.float64]:
        s, c = math.sin(q[2]), math.cos(q[2])
        return np.array([[1.0, 0.0, c], [0.0, 1.0, -s], [c, -s, 1.0 + k]])

    def bias(q: NDArray[np.float64], qd: NDArray[np.float64]) -> NDArray[np.float64]:
        s, c, om2 = math.sin(q[2]), math.cos(q[2]), qd[2] ** 2
        return np.array([-om2 * s - g * math.sin(a), -om2 * c + g * math.cos(a), -g * math.sin(a + q[2])])

    def swing(q: NDArray[np.float64]) -> NDArray[np.float64]:
        th = q[2]
        return np.array(
            [[1.0, 0.0, math.cos(th) - math.cos(th - 2 * p)], [0.0, 1.0, -math.sin(th) + math.sin(th - 2 * p)]]
        )

    return ss.ContactModel(
        mass_matrix=mass,
        bias=bias,
        contact_jacobian=lambda _q: jac,
        contact_jacobian_rate=lambda _q, _qd: np.zeros(2),
        swing_jacobian=swing,
        impact_guard=lambda q, _qd: q[1] + math.cos(q[2]) - math.cos(q[2] - 2 * p),
        guard_direction=-1.0,
        failure_events=(("backward", lambda _q, qd: qd[2], -1.0),),
        sections=(("midstance", lambda q, _qd: q[2], 1.0),),
    )


@dataclass(frozen=True)
class StepRecord:
    """One step from a post-impact state (theta_dot0, x_dot0) at theta = -phi (see :func:`step`).

    ``phases`` ("stick", "slip+", "slip-") in order with ``phase_angles`` theta at their starts; ``impact``
    "sticking"/"slipping" (None on failure); ``theta_dot_pre``/``x_dot_pre`` just before the impact; ``theta_dot``/
    ``x_dot`` the next post-impact state (NaN on failure); ``impulse_ratio`` F~_t/F~_n applied; ``min_fn`` min f_n/(mg)
    over the stance (sampled); ``failure`` None, "backward" (theta_dot -> 0: rolls back), "detached" (f_n -> 0;
    also any slip at kappa = 0, where eq 42 gives f_n = 0), "painleve" (D of eq 42 <= 0), "impact" (the impact law
    is inconsistent: F~_n <= 0, slip reversal within the impact or theta_dot^+ <= 0) or "chatter";
    ``failure_angle`` theta where it happened; ``duration`` the stance time; ``midstance`` (theta_dot, x_dot) at
    theta = 0 (NaN if not reached).
    """

    theta_dot0: float
    x_dot0: float
    phases: tuple[str, ...]
    phase_angles: tuple[float, ...]
    impact: str | None
    theta_dot_pre: float
    x_dot_pre: float
    theta_dot: float
    x_dot: float
    impulse_ratio: float
    min_fn: float
    failure: str | None
    failure_angle: float
    duration: float
    midstance: tuple[float, float]

    @property
    def dx(self) -> float:
        """x_dot - x_dot0: the change of slip speed over the step (Delta x_dot of 002 Sec. 3.3)."""
        return self.x_dot - self.x_dot0

    @property
    def post(self) -> tuple[float, float]:
        """Next post-impact state (theta_dot, x_dot)."""
        return self.theta_dot, self.x_dot


def _stick_decision(w: FrictionWheel, th: float, u: float) -> str:
    """Mode at x_dot = 0 (002 eq 35): stick if the sticking force (eq 19) is in the cone, else slip against f_t."""
    f_t, f_n = sticking_forces(w, th, math.sqrt(max(u, 0.0)))
    return ss.mode_from_stick_force((float(f_t), float(f_n)), w.mu)


def _record(
    theta_dot0: float, x_dot0: float, b: _Builder, impact: str | None, pre: tuple[float, float],
    post: tuple[float, float], ratio: float, failure: str | None, angle: float,
) -> StepRecord:
    return StepRecord(
        theta_dot0, x_dot0, tuple(b.phases), tuple(b.angles), impact, pre[0], pre[1], post[0], post[1], ratio,
        b.min_fn, failure, angle, b.duration, b.mid,
    )


def _step_fast(w: FrictionWheel, theta_dot0: float, x_dot0: float, max_step: float, max_phases: int) -> StepRecord:
    b = _Builder()
    nan2 = (math.nan, math.nan)
    th, u, xd = -w.phi, theta_dot0**2, x_dot0
    if not theta_dot0 > 0.0:
        return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, "backward", th)
    if abs(xd) <= X_TOL:
        xd = 0.0
        mode = _stick_decision(w, th, u)
    else:
        mode = "slip+" if xd > 0 else "slip-"
    while True:
        if len(b.phases) >= max_phases:
            return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, "chatter", th)
        b.phases.append(mode)
        b.angles.append(th)
        if mode == "stick":
            th, u, reason = _stick_phase(w, th, u, b)
            xd = 0.0
        elif w.kappa == 0.0 or math.isinf(w.mu):
            reason = "detached"  # kappa = 0: eq 42 gives f_n = 0 while slipping; mu = inf: f_n < 0 under sticking
            b.min_fn = min(b.min_fn, float(sticking_forces(w, th, math.sqrt(u))[1]) if w.kappa > 0 else 0.0)
        else:
            th, u, xd, reason = _slip_phase(w, th, u, xd, 1.0 if mode == "slip+" else -1.0, b, max_step)
        if reason in ("slip+", "slip-"):
            mode = reason
        elif reason == "stop":
            xd = 0.0
            mode = _stick_decision(w, th, u)
        elif reason != "impact":
            return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, reason, th)
        else:
            break
    pre = (math.sqrt(u), xd)
    kind, imp = impact_closed_form(w, *pre)
    if not imp.admissible:
        return _record(theta_dot0, x_dot0, b, kind, pre, nan2, imp.impulse_t / imp.impulse_n, "impact", th)
    return _record(theta_dot0, x_dot0, b, kind, pre, (imp.theta_dot, imp.x_dot), imp.impulse_t / imp.impulse_n,
                   None, th)


def _step_generic(w: FrictionWheel, theta_dot0: float, x_dot0: float, max_step: float, max_phases: int,
                  rtol: float) -> StepRecord:
    model = contact_model(w)
    p = w.phi
    b = _Builder()
    nan2 = (math.nan, math.nan)
    q0 = np.array([0.0, 0.0, -p])
    qd0 = np.array([0.0 if abs(x_dot0) <= X_TOL else x_dot0, 0.0, theta_dot0])
    res = ss.integrate_stance(model, q0, qd0, w.mu, rtol=rtol, atol=rtol * ATOL / RTOL, slip_max_step=max_step,
                              max_phases=max_phases, v_tol=X_TOL)
    for ph in res.phases:
        b.phases.append(ph.mode)
        b.angles.append(float(ph.q_start[2]))
    b.min_fn = res.min_normal_force / w.gravity
    b.duration = res.t_end
    if "midstance" in res.sections:
        _, _, qd_mid = res.sections["midstance"]
        b.mid = (float(qd_mid[2]), float(qd_mid[0]))
    if res.failure is not None:
        return _record(theta_dot0, x_dot0, b, None, nan2, nan2, math.nan, res.failure, float(res.q_end[2]))
    pre = (float(res.qd_end[2]), float(res.qd_end[0]))
    out = ss.impact(model, res.q_end, res.qd_end, w.mu)
    post = (float(out.qd_plus[2]), float(out.swing_velocity[0]))
    ratio = float(out.impulse[0] / out.impulse[1])
    ok = out.consistent and post[0] > 0
    return _record(theta_dot0, x_dot0, b, out.kind, pre, post if ok else nan2, ratio, None if ok else "impact",
                   float(res.q_end[2]))


def step(
    w: FrictionWheel,
    state: Sequence[float],
    *,
    method: str = "fast",
    max_step: float | None = None,
    max_phases: int = 40,
    rtol: float = RTOL,
) -> StepRecord:
    """One step of the hybrid stick-slip dynamics (002 Sec. 3.3, Appendix A) from the post-impact state
    ``state`` = (theta_dot, x_dot) at theta = -phi: stance phases with the mode logic of 002 eq 35, then the
    frictional impact at theta = phi (eqs 43-45 corrected) and the relabelling to the next spoke.

    ``method``: "fast" (theta-domain, closed-form sticking phases) or "generic"
    (:func:`mjpoincare.analysis.theory.stick_slip.integrate_stance` on the matrix model of :func:`contact_model`).
    ``max_step``: largest step while slipping (theta in rad for "fast", default 0.05; time for "generic",
    default 1e-2). ``rtol``: the generic method's relative tolerance (absolute: rtol x ATOL/RTOL); the fast method
    runs at RTOL. No validation of ``w`` here (see :func:`validate`).
    """
    theta_dot0, x_dot0 = float(state[0]), float(state[1])
    if method == "fast":
        return _step_fast(w, theta_dot0, x_dot0, SLIP_MAX_STEP if max_step is None else max_step, max_phases)
    if method == "generic":
        return _step_generic(w, theta_dot0, x_dot0, ss.SLIP_MAX_STEP if max_step is None else max_step, max_phases,
                             rtol)
    raise ValueError(f"method must be 'fast' or 'generic' (got {method!r})")
