"""Exact event-driven reference simulator of the planar rimless wheel (independent of the closed forms).

Model (the physics of 003 Sec. 3.1-3.2 = Kiša 2020 and of 002 Sec. 3.1 eqs 11-14 = Gamus & Or 2015,
but solved generically, without using any of the closed forms of :mod:`mjpoincare.analysis.theory.rimless_wheel`):

* A planar rigid body with generalized coordinates q = (x, z, psi) in the SLOPE frame: x downhill along the
  slope, z normal to it, psi the stance spoke's angle from the slope normal, clockwise positive
  (003's theta = psi + gamma). Mass m, inertia I = m gyration^2 about the hub,
  gravity g (sin gamma, -cos gamma).
* Spoke j's foot sits at hub + l (-sin psi_j, -cos psi_j) with psi_j = psi + 2 alpha (j - k) for stance
  spoke k; the spoke ahead (downhill) is j = k - 1, the one behind is j = k + 1. The state stores psi as
  psi_start + delta with the offset delta integrated from 0, so that small rocking excursions keep full
  relative precision (Zeno sequences).
* Stance: the stance foot is pinned (two holonomic constraints, Jacobian J). The saddle-point system
  [[M, -J^T], [J, 0]] [qdd; lambda] = [f; -Jdot qd] gives the accelerations and the contact force
  lambda = (f_t, f_n) on the wheel (f_t positive downhill, f_n positive pushing away from the slope).
  This form also works for a point mass (I = 0, M singular) because M is positive definite on the null
  space of J.
* Impact: when another foot reaches the slope, i.e. its height above the stance foot,
  2 l sin(alpha) sin(alpha -/+ psi), falls to 0, a plastic impulse is applied at the NEW foot and the old foot
  is released: [[M, -J^T], [J, 0]] [qd+; Lambda] = [M qd-; 0], which equals
  qd+ = [1 - M^-1 J^T (J M^-1 J^T)^-1 J] qd- when M is invertible. Lambda = (tangential, normal) impulse.
  After the impact the configuration is snapped onto the exact two-feet-on-ground pose
  (new stance angle -/+ alpha, new foot at z = 0), removing constraint drift.
* Events via ``solve_ivp(method="DOP853", rtol=1e-11, atol=1e-12)`` with terminal events. Unilateral contact
  is NOT enforced during integration (as in the analytic map): f_n < 0 is only flagged, and with
  ``stop_on_flight`` the run stops after that stance with outcome "flight". Whether the released foot
  separates after an impact is not checked.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel import RimlessWheel, validate
from numpy.typing import NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar, root_scalar

RTOL = 1e-11
ATOL = 1e-12
#: |omega| below which the wheel is declared standing (Zeno rocking accumulated).
STANDING_TOL = 1e-7
_SAMPLES = 257


@dataclass(frozen=True)
class HybridResult:
    """Result of :func:`simulate_hybrid`.

    ``t_impacts``, ``omega_post`` (post-impact d(psi)/dt = 003's theta_dot, sign = direction),
    ``impulse_ratio`` (tangential/normal impulse at the new foot) and
    ``kinds`` ("forward", "backward" or "rock": how the stance ended) have one entry per impact.
    ``min_normal_force`` (min f_n/(m g)) and ``max_friction_ratio`` (max |f_t/f_n|) have one entry per
    integrated stance phase (one more than impacts when the run ended inside a stance).
    ``outcome``: "rolling" (all impacts done, last one a forward step), "standing" (|omega| < 1e-7),
    "flight" (``stop_on_flight`` and f_n < 0), "stalled" (a stance exceeded ``max_stance_time``,
    e.g. a heteroclinic speed) or "moving" (all impacts done otherwise).
    ``flight`` is True if f_n < 0 occurred in any stance.
    """

    t_impacts: NDArray[np.float64]
    omega_post: NDArray[np.float64]
    impulse_ratio: NDArray[np.float64]
    kinds: tuple[str, ...]
    min_normal_force: NDArray[np.float64]
    max_friction_ratio: NDArray[np.float64]
    outcome: str
    flight: bool = field(default=False)


def _mass_matrix(w: RimlessWheel) -> NDArray[np.float64]:
    inertia = w.mass * w.gyration**2
    return np.diag([w.mass, w.mass, inertia])


def _jacobian(w: RimlessWheel, psi: NDArray[np.float64]) -> NDArray[np.float64]:
    """d(foot)/dq for foot = (x - l sin psi, z - l cos psi); batched over psi (shape (..., 2, 3))."""
    psi = np.asarray(psi, dtype=float)
    jac = np.zeros((*psi.shape, 2, 3))
    jac[..., 0, 0] = 1.0
    jac[..., 1, 1] = 1.0
    jac[..., 0, 2] = -w.leg_length * np.cos(psi)
    jac[..., 1, 2] = w.leg_length * np.sin(psi)
    return jac


def _kkt(w: RimlessWheel, jac: NDArray[np.float64]) -> NDArray[np.float64]:
    """Saddle-point matrices [[M, -J^T], [J, 0]], batched over the leading axes of jac."""
    kkt = np.zeros((*jac.shape[:-2], 5, 5))
    kkt[..., :3, :3] = _mass_matrix(w)
    kkt[..., :3, 3:] = -np.swapaxes(jac, -1, -2)
    kkt[..., 3:, :3] = jac
    return kkt


def stance_dynamics(
    w: RimlessWheel, psi: NDArray[np.float64] | float, qd: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pinned-foot dynamics M qdd = f + J^T lambda, J qdd = -Jdot qd
    (003 eq 3.2, 002 eqs 11-12, solved generically).

    ``psi``: stance spoke angle(s) from the slope normal (shape (...));
    ``qd``: (..., 3) velocities (xdot, zdot, psidot).
    Returns qdd (..., 3) and the contact force on the wheel lambda = (f_t, f_n) (..., 2) in newtons.
    """
    psi = np.asarray(psi, dtype=float)
    qd = np.asarray(qd, dtype=float)
    jac = _jacobian(w, psi)
    om2 = qd[..., 2] ** 2
    rhs = np.zeros((*psi.shape, 5))
    rhs[..., 0] = w.mass * w.gravity * math.sin(w.slope)
    rhs[..., 1] = -w.mass * w.gravity * math.cos(w.slope)
    rhs[..., 3] = -w.leg_length * np.sin(psi) * om2
    rhs[..., 4] = -w.leg_length * np.cos(psi) * om2
    sol = np.linalg.solve(_kkt(w, jac), rhs[..., None])[..., 0]
    return sol[..., :3], sol[..., 3:]


def plastic_impact(
    w: RimlessWheel, psi_new: float, qd_minus: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Plastic impulse projection onto the new foot's constraint (003 eq 3.11 / 002 eq 14, solved generically):
    [[M, -J^T], [J, 0]] [qd+; Lambda] = [M qd-; 0].
    Returns qd+ and the impulse Lambda = (tangential, normal)."""
    rhs = np.concatenate([_mass_matrix(w) @ qd_minus, np.zeros(2)])
    sol = np.linalg.solve(_kkt(w, _jacobian(w, np.asarray(psi_new))), rhs)
    return sol[:3], sol[3:]


def _pose(w: RimlessWheel, foot_x: float, psi: float, omega: float) -> tuple[NDArray[np.float64], ...]:
    """Hub position and velocity pivoting on a foot at (foot_x, 0) with stance angle psi and rate omega."""
    l = w.leg_length
    q = np.array([foot_x + l * math.sin(psi), l * math.cos(psi)])
    qd = np.array([l * omega * math.cos(psi), -l * omega * math.sin(psi), omega])
    return q, qd


def _stance_forces(
    w: RimlessWheel, sol: Callable, psi0: float, t: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Contact force ratios lambda/(m g) along a dense stance solution at times t (shape (len(t), 2))."""
    y = np.atleast_2d(sol(t).T)
    _, lam = stance_dynamics(w, psi0 + y[:, 2], y[:, 3:])
    return lam / (w.mass * w.gravity)


def _extreme(fun: Callable[[NDArray[np.float64]], NDArray[np.float64]], t0: float, t1: float) -> float:
    """min of fun over [t0, t1]: dense sampling, then bounded refinement around the best sample."""
    t = np.linspace(t0, t1, _SAMPLES)
    v = fun(t)
    i = int(np.argmin(v))
    if 0 < i < _SAMPLES - 1 and np.isfinite(v[i]):
        res = minimize_scalar(
            lambda s: float(fun(np.array([s]))[0]), bounds=(t[i - 1], t[i + 1]), method="bounded"
        )
        return float(min(res.fun, v[i]))
    return float(v[i])


def _stance_extremes(
    w: RimlessWheel, sol: Callable, psi0: float, t0: float, t1: float
) -> tuple[float, float]:
    """(min f_n/(m g), max |f_t/f_n|) over a stance solution on [t0, t1]."""
    if t1 <= t0:
        lam = _stance_forces(w, sol, psi0, np.array([t0]))[0]
        return float(lam[1]), float(abs(lam[0] / lam[1]))

    def fn(t: NDArray[np.float64]) -> NDArray[np.float64]:
        return _stance_forces(w, sol, psi0, t)[:, 1]

    def neg_ratio(t: NDArray[np.float64]) -> NDArray[np.float64]:
        lam = _stance_forces(w, sol, psi0, t)
        return -np.abs(lam[:, 0] / lam[:, 1])

    return _extreme(fn, t0, t1), -_extreme(neg_ratio, t0, t1)


def simulate_hybrid(
    w: RimlessWheel,
    omega0: float,
    n_impacts: int,
    *,
    stop_on_flight: bool = False,
    max_stance_time: float = 30.0,
    rtol: float = RTOL,
    atol: float = ATOL,
) -> HybridResult:
    """Simulate the rimless wheel from a post-impact pose (two feet on the slope) with rate omega0.

    The pivot is the downhill foot (stance angle psi = -alpha) if omega0 >= 0, the uphill foot (psi = +alpha)
    otherwise; this is the post-impact section of 003 eqs 3.13/3.14 and 002 eq 15.
    Runs until ``n_impacts`` impacts, standing, flight (if ``stop_on_flight``) or a stalled stance.
    See :class:`HybridResult`. ``rtol``/``atol`` are solve_ivp's tolerances
    (defaults: the exact reference; looser ones are timed by the benchmark).
    """
    validate(w)
    l, a = w.leg_length, w.alpha
    foot_x, t_now, omega = 0.0, 0.0, float(omega0)
    psi0 = -a if omega >= 0.0 else a
    times: list[float] = []
    speeds: list[float] = []
    impulses: list[float] = []
    kinds: list[str] = []
    min_fn: list[float] = []
    max_ratio: list[float] = []
    flight = False
    outcome = "moving"

    def rhs(_t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        qdd, _ = stance_dynamics(w, psi0 + y[2], y[3:])
        return np.concatenate([y[3:], qdd])

    def ahead_lands(_t: float, y: NDArray[np.float64]) -> float:
        return 2.0 * l * math.sin(a) * math.sin(a - psi0 - y[2])

    def behind_lands(_t: float, y: NDArray[np.float64]) -> float:
        return 2.0 * l * math.sin(a) * math.sin(a + psi0 + y[2])

    for event in (ahead_lands, behind_lands):
        event.terminal = True  # type: ignore[attr-defined]
        event.direction = -1.0  # type: ignore[attr-defined]

    while len(times) < n_impacts:
        q, qd = _pose(w, foot_x, psi0, omega)
        y0 = np.array([q[0], q[1], 0.0, *qd])
        scale = max(abs(omega), STANDING_TOL) / w.rate2
        sol = solve_ivp(
            rhs,
            (t_now, t_now + max_stance_time),
            y0,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=(ahead_lands, behind_lands),
            dense_output=True,
            first_step=min(1e-3, 1e-3 * scale),
        )
        t_end = float(sol.t[-1])

        fn_min, ratio_max = _stance_extremes(w, sol.sol, psi0, t_now, t_end)
        min_fn.append(fn_min)
        max_ratio.append(ratio_max)
        flight = flight or min_fn[-1] < 0.0
        if sol.status != 1:
            outcome = "stalled"
            break
        landed_ahead = sol.t_events[0].size > 0
        y = sol.y_events[0][0] if landed_ahead else sol.y_events[1][0]
        psi_new = -a if landed_ahead else a
        foot_x = y[0] - l * math.sin(psi_new)
        qd_plus, impulse = plastic_impact(w, psi_new, y[3:])
        kinds.append(
            ("forward" if omega >= 0.0 else "rock") if landed_ahead else ("backward" if omega < 0 else "rock")
        )
        omega, psi0, t_now = float(qd_plus[2]), psi_new, t_end
        times.append(t_now)
        speeds.append(omega)
        impulses.append(float(impulse[0] / impulse[1]))
        if abs(omega) < STANDING_TOL:
            outcome = "standing"
            break
        if stop_on_flight and flight:
            outcome = "flight"
            break
    else:
        outcome = "rolling" if kinds and kinds[-1] == "forward" else "moving"
    return HybridResult(
        t_impacts=np.array(times),
        omega_post=np.array(speeds),
        impulse_ratio=np.array(impulses),
        kinds=tuple(kinds),
        min_normal_force=np.array(min_fn),
        max_friction_ratio=np.array(max_ratio),
        outcome=outcome,
        flight=flight,
    )


def hybrid_return_map(w: RimlessWheel, omega0: float) -> float:
    """One step of the post-impact return map by simulation (reference for 003 eqs 3.13/3.14, 002 eq 15);
    NaN if the stance stalls (heteroclinic speed)."""
    res = simulate_hybrid(w, omega0, 1)
    return float(res.omega_post[0]) if res.omega_post.size else math.nan


def hybrid_fixed_point(w: RimlessWheel) -> float:
    """Rolling fixed point by secant shooting on s = omega^2, G(s) = P(sqrt s)^2 - s, started from a fast
    forward step (reference for 003 Sec. 3.3.2 / 002 eq 16;
    energy bookkeeping makes G nearly affine on the forward branch).
    NaN if shooting does not end on a forward-step fixed point."""
    start = (3.0 * math.sqrt(w.gravity / w.leg_length)) ** 2

    def gap(s: float) -> float:
        return hybrid_return_map(w, math.sqrt(max(s, 0.0))) ** 2 - s

    res = root_scalar(
        gap, x0=start, x1=start + gap(start), method="secant", xtol=1e-14, rtol=1e-14, maxiter=40
    )
    if not res.converged or not math.isfinite(res.root) or res.root <= 0.0:
        return math.nan
    omega_star = math.sqrt(res.root)
    check = simulate_hybrid(w, omega_star, 1)
    if check.kinds != ("forward",) or abs(check.omega_post[0] - omega_star) > 1e-9 * omega_star:
        return math.nan
    return omega_star


def hybrid_multiplier(w: RimlessWheel, step: float = 1e-4) -> float:
    """dP/domega at the rolling fixed point by central finite differences of :func:`hybrid_return_map`
    (reference for 002 eq 17; relative step ``step``)."""
    omega_star = hybrid_fixed_point(w)
    h = step * omega_star
    return (hybrid_return_map(w, omega_star + h) - hybrid_return_map(w, omega_star - h)) / (2.0 * h)
