"""The stance phases of the rimless wheel's fast step method, integrated in the spoke angle theta.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3 and Appendix A.3: a sticking phase in closed form (energy integral eq 13, forces eq 19) and a slipping phase
from eq 42 (u = theta_dot^2 as a function of theta), each ending at the impact angle, a mode switch of eq 35 or a
failure (detachment, Painleve, rolling back); derivation page docs/theory/stick-slip.md, Sec. 4.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel_friction.params import ATOL, RTOL, FrictionWheel
from numpy.typing import NDArray
from scipy.integrate import IntegrationWarning, quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar

_GRID = 65


@dataclass
class _Builder:
    phases: list[str] = field(default_factory=list)
    angles: list[float] = field(default_factory=list)
    min_fn: float = math.inf
    duration: float = 0.0
    mid: tuple[float, float] = (math.nan, math.nan)


def _first_root(fun: Callable[[float], float], grid: NDArray[np.float64], vals: NDArray[np.float64]) -> float:
    """First point of grid[0] < theta <= grid[-1] where fun <= 0 (inf if none): the first non-positive sample,
    or a dip between samples detected from the parabola through three samples and refined by minimize_scalar."""
    if vals[0] < 0.0:
        return float(grid[0])
    neg = np.nonzero(vals[1:] <= 0.0)[0]
    j = int(neg[0]) + 1 if neg.size else len(grid)
    m = max(j - 2, 0)
    v0, v1, v2 = vals[:m], vals[1 : m + 1], vals[2 : m + 2]
    curv = v0 - 2 * v1 + v2
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = np.where((v1 <= v0) & (v1 <= v2) & (curv > 0), v1 - (v2 - v0) ** 2 / (8 * curv), np.inf)
    for i in np.nonzero(vertex <= 0.05 * (np.abs(v2 - v0) + curv))[0]:
        lo, hi = float(grid[i]), float(grid[i + 2])
        res = minimize_scalar(fun, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        if res.fun <= 0.0:
            return float(brentq(fun, lo, float(res.x), xtol=1e-15, rtol=1e-15))
    if j < len(grid):
        return float(brentq(fun, float(grid[j - 1]), float(grid[j]), xtol=1e-15, rtol=1e-15))
    return math.inf


def _sampled_min(vals: NDArray[np.float64]) -> float:
    """Minimum of equally spaced samples, refined by the parabola through the smallest sample and its neighbours."""
    if vals.size == 0:
        return math.inf
    i = int(np.argmin(vals))
    if 0 < i < vals.size - 1:
        v0, v1, v2 = vals[i - 1], vals[i], vals[i + 1]
        curv = v0 - 2 * v1 + v2
        if curv > 0:
            return float(v1 - (v2 - v0) ** 2 / (8 * curv))
    return float(vals[i])


def _stick_phase(w: FrictionWheel, th0: float, u0: float, b: _Builder) -> tuple[float, float, str]:
    """Sticking phase from (th0, u0 = theta_dot^2) in closed form (002 eqs 12-13, 19): returns (theta_end, u_end,
    reason), reason "impact" (theta = phi), "slip+"/"slip-" (cone edge reached: f_t = -+mu f_n), "detached"
    (f_n = 0) or "backward" (theta_dot = 0)."""
    a, k, p = w.slope, w.kappa, w.phi
    e0 = u0 + 2.0 * math.cos(a + th0)
    cos_a, sin_a = math.cos(a), math.sin(a)

    def u_of(th: float) -> float:
        return e0 - 2.0 * math.cos(a + th)

    def forces(th: float) -> tuple[float, float]:
        core = math.cos(a + th) - u_of(th)
        return (core * math.sin(th) - k * sin_a) / (1 + k), (core * math.cos(th) + k * cos_a) / (1 + k)

    extra = [x for x in (-a, 0.0) if th0 < x < p]
    grid = np.unique(np.concatenate([np.linspace(th0, p, _GRID), extra]))
    u = e0 - 2.0 * np.cos(a + grid)
    core = np.cos(a + grid) - u
    f_n = (core * np.cos(grid) + k * cos_a) / (1 + k)
    f_t = (core * np.sin(grid) - k * sin_a) / (1 + k)
    ends: list[tuple[float, str]] = [
        (_first_root(u_of, grid, u), "backward"),
        (_first_root(lambda th: forces(th)[1], grid, f_n), "detached"),
    ]
    if not math.isinf(w.mu):
        mu = w.mu
        ends.append((_first_root(lambda th: forces(th)[0] + mu * forces(th)[1], grid, f_t + mu * f_n), "slip+"))
        ends.append((_first_root(lambda th: mu * forces(th)[1] - forces(th)[0], grid, mu * f_n - f_t), "slip-"))
    th_end, reason = min(ends)
    if math.isinf(th_end):
        th_end, reason = p, "impact"
    b.min_fn = min(b.min_fn, _sampled_min(f_n[grid <= th_end]), forces(th_end)[1])
    if th0 <= 0.0 <= th_end:
        b.mid = (math.sqrt(max(u_of(0.0), 0.0)), 0.0)
    if th_end > th0:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", IntegrationWarning)
            b.duration += quad(lambda th: 1.0 / math.sqrt(max(u_of(th), 1e-300)), th0, th_end, limit=200)[0]
    return th_end, max(u_of(th_end), 0.0), reason


def _slip_phase(
    w: FrictionWheel, th0: float, u0: float, xd0: float, sign: float, b: _Builder, max_step: float
) -> tuple[float, float, float, str]:
    """Slipping phase from (th0, u0, xd0) integrated in theta (002 eq 42 with u = theta_dot^2:
    du/dtheta = 2 theta_ddot, dx_dot/dtheta = x_ddot/theta_dot, dt/dtheta = 1/theta_dot), DOP853 with events:
    x_dot = 0 ("stop"), D = 0 ("painleve"), f_n = 0 ("detached"), u = 0 ("backward"). f_n and u are also checked
    for dips between steps on the dense solution. Returns (theta_end, u_end, x_dot_end, reason)."""
    a, k, g, p = w.slope, w.kappa, w.gravity, w.phi
    smu = sign * w.mu
    gcos, ksin = g * math.cos(a), k * math.sin(a)

    def rhs(th: float, y: NDArray[np.float64]) -> list[float]:
        u = y[0]
        s, c = math.sin(th), math.cos(th)
        den = k + s * s + smu * s * c
        core = gcos - u * c
        f_n = k * core / den
        xdd = ((1 + k) * (u * s - smu * f_n) + g * (ksin - math.cos(a + th) * s)) / (k + s * s)
        r = 1.0 / math.sqrt(abs(u)) if u != 0.0 else 1e150
        return [2.0 * core * (s + smu * c) / den, xdd * r, r]

    # A slip that starts from x_dot = 0 has x_dot ~ a0 (theta - th0) with a0 >= 0, possibly tiny (the start lies just
    # outside the cone): its stop may come before the first solver step ends, and sign*x_dot alone would put the
    # root at th0 (the grazing trap). sign*x_dot/(theta - th0), which starts at a0, has only the true root.
    a0 = sign * rhs(th0, np.array([u0, xd0, 0.0]))[1] if xd0 == 0.0 else math.nan

    def stop(th: float, y: NDArray[np.float64]) -> float:
        if xd0 != 0.0:
            return sign * y[1]
        return sign * y[1] / (th - th0) if th > th0 else a0

    def painleve(th: float, _y: NDArray[np.float64]) -> float:
        s = math.sin(th)
        return k + s * s + smu * s * math.cos(th)

    def detach(th: float, y: NDArray[np.float64]) -> float:
        return gcos - y[0] * math.cos(th)

    def backward(_th: float, y: NDArray[np.float64]) -> float:
        return y[0]

    if painleve(th0, None) <= 0.0:  # type: ignore[arg-type]
        return th0, u0, xd0, "painleve"
    if detach(th0, np.array([u0])) <= 0.0:
        b.min_fn = min(b.min_fn, float(k * detach(th0, np.array([u0])) / painleve(th0, None) / g))  # type: ignore
        return th0, u0, xd0, "detached"
    events = (stop, painleve, detach, backward)
    names = ("stop", "painleve", "detached", "backward")
    for ev in events:
        ev.terminal = True  # type: ignore[attr-defined]
        ev.direction = -1.0  # type: ignore[attr-defined]
    sol = solve_ivp(
        rhs, (th0, p), [u0, xd0, 0.0], method="DOP853", rtol=RTOL, atol=ATOL, events=events, dense_output=True,
        max_step=max_step, first_step=min(1e-3, max(p - th0, 1e-12)),
    )
    th_end, y_end, reason = float(sol.t[-1]), sol.y[:, -1], "impact"
    hits = [(float(te[0]), i) for i, te in enumerate(sol.t_events) if te.size]
    if sol.status == 1 and hits:
        th_hit, i = min(hits)
        th_end, y_end, reason = th_hit, sol.y_events[i][0], names[i]
    elif sol.status != 0:
        reason = "backward" if sol.y[0, -1] < 1e-6 else "chatter"
    if th_end > th0:
        grid = np.linspace(th0, th_end, _GRID)
        ys = sol.sol(grid)
        for fun_vals, fun, label in (
            (ys[0], lambda t: float(sol.sol(t)[0]), "backward"),
            (gcos - ys[0] * np.cos(grid), lambda t: gcos - float(sol.sol(t)[0]) * math.cos(t), "detached"),
        ):
            th_dip = _first_root(fun, grid, fun_vals)
            if th_dip < th_end and reason != label:
                th_end, y_end, reason = th_dip, sol.sol(th_dip), label
        fn = k * (gcos - ys[0] * np.cos(grid)) / (k + np.sin(grid) ** 2 + smu * np.sin(grid) * np.cos(grid)) / g
        b.min_fn = min(b.min_fn, _sampled_min(fn[grid <= th_end]))
        if th0 <= 0.0 <= th_end:
            ym = sol.sol(0.0)
            b.mid = (math.sqrt(max(ym[0], 0.0)), float(ym[1]))
    s_end = math.sin(th_end)
    den_end = k + s_end**2 + smu * s_end * math.cos(th_end)
    fn_end = float(k * (gcos - y_end[0] * math.cos(th_end)) / den_end / g) if den_end > 0 else -math.inf
    b.min_fn = min(b.min_fn, fn_end)
    b.duration += float(y_end[2])
    return th_end, float(y_end[0]), float(y_end[1]), reason
