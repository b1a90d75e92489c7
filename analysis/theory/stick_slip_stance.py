"""Event-driven integration of one stance of a planar robot through its stick and slip phases (002 eqs 2, 31-35).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Appendix A: each phase integrated with DOP853 in its contact mode until the impact guard, a mode switch of eq 35
(stick -> slip at the cone edge, slip -> stick or reversal at v_t = 0), detachment (f_n = 0), the Painleve case of eq
33 or a model failure event, with constraint-drift removal at each phase start and the grazing trap of the derivation
page docs/theory/stick-slip.md, Sec. 4.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from mjpoincare.analysis.theory.stick_slip_contact import (
    V_TOL,
    ContactModel,
    ContactState,
    Vector,
    _slip_sign,
    contact_state,
    initial_mode,
    mode_from_stick_force,
)
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

RTOL = 1e-11
ATOL = 1e-12
#: Default largest time step while slipping (grazing trap: a slip that starts on the cone boundary can end again
#: within one long solver step; derivation page docs/theory/stick-slip.md, Sec. 4).
SLIP_MAX_STEP = 1e-2
#: Samples per phase of the dense solution on which f_n is checked for a dip below 0 between solver steps.
FN_SAMPLES = 33


class Phase(NamedTuple):
    """One continuous phase of a stance: contact mode, start time, configuration and velocities at its start."""

    mode: str
    t_start: float
    q_start: Vector
    qd_start: Vector


@dataclass(frozen=True)
class StanceResult:
    """Result of :func:`integrate_stance`.

    ``phases`` in order; ``outcome`` is ``"impact"`` (guard reached: ``q_end``, ``qd_end`` is the pre-impact
    state), ``"detached"`` (f_n reached 0), ``"painleve"`` (slip denominator of (33) reached 0), a model failure
    event's name, ``"stalled"`` (t_max reached), ``"chatter"`` (more than max_phases phases) or ``"solver"``.
    ``min_normal_force`` is min f_n over the stance (checked on the dense solution), ``sections`` maps a section
    name to (t, q, qd) at its first crossing.
    """

    phases: tuple[Phase, ...]
    outcome: str
    t_end: float
    q_end: Vector
    qd_end: Vector
    min_normal_force: float
    sections: dict[str, tuple[float, Vector, Vector]] = field(default_factory=dict)

    @property
    def impacted(self) -> bool:
        """The stance ended at the impact guard."""
        return self.outcome == "impact"

    @property
    def detached(self) -> bool:
        """The stance ended with f_n = 0 (002 Sec. 3.4: contact detachment)."""
        return self.outcome == "detached"

    @property
    def failure(self) -> str | None:
        """None on an impact, else the outcome."""
        return None if self.impacted else self.outcome


def _project(model: ContactModel, q: Vector, qd: Vector, mode: str) -> Vector:
    """Remove constraint drift: the M-orthogonal projection of qd onto W qd = 0 (stick) or w_n^T qd = 0 (slip),
    i.e. the plastic impact law (38) applied at the stance foot."""
    jac = model.contact_jacobian(q)
    if mode != "stick":
        jac = jac[1:]
    minv_wt = np.linalg.solve(model.mass_matrix(q), jac.T)
    return qd - minv_wt @ np.linalg.solve(jac @ minv_wt, jac @ qd)


class _Cache:
    """Memo of the last contact_state evaluation (events and right-hand side share states)."""

    def __init__(self, model: ContactModel, mode: str, mu: float, n: int) -> None:
        self.model, self.mode, self.mu, self.n = model, mode, mu, n
        self.key: bytes | None = None
        self.value: ContactState | None = None

    def __call__(self, y: Vector) -> ContactState:
        key = y.tobytes()
        if key != self.key or self.value is None:
            self.value = contact_state(self.model, y[: self.n], y[self.n :], self.mode, self.mu)
            self.key = key
        return self.value


def _stop_event(
    model: ContactModel, cache: _Cache, sgn: float, start: tuple[float, Vector], n: int
) -> Callable[[float, Vector], float]:
    """Slip -> stick/reversal event sgn v_t. A slip that starts from v_t = 0 has v_t ~ a0 (t - t0) with a0 >= 0,
    possibly tiny (the start lies just outside the cone), and may stop again before the first solver step ends;
    sgn v_t alone would then put the root at t0 (the grazing trap of docs/theory/stick-slip.md, Sec. 4). For such a
    start the event is sgn v_t/(t - t0), which starts at a0 = sgn dv_t/dt and has only the true root."""
    t0, y0 = start

    def v_t(y: Vector) -> float:
        return float(model.contact_jacobian(y[:n])[0] @ y[n:])

    if abs(v_t(y0)) > V_TOL:
        return lambda _t, y: sgn * v_t(y)
    q0, qd0 = y0[:n], y0[n:]
    a0 = sgn * float(model.contact_jacobian(q0)[0] @ cache(y0).qdd + model.contact_jacobian_rate(q0, qd0)[0])
    return lambda t, y: sgn * v_t(y) / (t - t0) if t > t0 else a0


def _phase_events(
    model: ContactModel, cache: _Cache, mode: str, mu: float, n: int, start: tuple[float, Vector]
) -> tuple[list[Callable[[float, Vector], float]], list[str]]:
    """Terminal and section event functions of one phase, with their meaning ("->mode", outcome or "section:")."""
    events: list[Callable[[float, Vector], float]] = []
    names: list[str] = []

    def add(fun: Callable[[float, Vector], float], direction: float, name: str, terminal: bool = True) -> None:
        fun.terminal = terminal  # type: ignore[attr-defined]
        fun.direction = direction  # type: ignore[attr-defined]
        events.append(fun)
        names.append(name)

    add(lambda _t, y: float(model.impact_guard(y[:n], y[n:])), model.guard_direction, "impact")
    add(lambda _t, y: float(cache(y).force[1]), -1.0, "detached")
    if mode == "stick":
        if not math.isinf(mu):
            add(lambda _t, y: float(cache(y).force[0] + mu * cache(y).force[1]), -1.0, "->slip+")
            add(lambda _t, y: float(mu * cache(y).force[1] - cache(y).force[0]), -1.0, "->slip-")
    else:
        sgn = _slip_sign(mode)
        add(_stop_event(model, cache, sgn, start, n), -1.0, "stop")
        add(lambda _t, y: cache(y).denominator, -1.0, "painleve")
    for name, fun, direction in model.failure_events:
        add(lambda _t, y, fun=fun: float(fun(y[:n], y[n:])), direction, name)
    for name, fun, direction in model.sections:
        add(lambda _t, y, fun=fun: float(fun(y[:n], y[n:])), direction, "section:" + name, terminal=False)
    return events, names


def _first_dip(values: Callable[[float], float], t0: float, t1: float, samples: int) -> tuple[float, float]:
    """(min of ``values`` over [t0, t1], first time where it is <= 0, or inf): dense samples, a bounded refinement
    around the smallest sample (a tangential dip between samples), brentq for the crossing."""
    ts = np.linspace(t0, t1, samples)
    vs = np.array([values(t) for t in ts])
    i = int(np.argmin(vs))
    vmin, tmin = float(vs[i]), float(ts[i])
    if 0 < i < samples - 1:
        res = minimize_scalar(values, bounds=(ts[i - 1], ts[i + 1]), method="bounded", options={"xatol": 1e-12})
        if res.fun < vmin:
            vmin, tmin = float(res.fun), float(res.x)
    if vmin > 0.0:
        return vmin, math.inf
    if vs[0] <= 0.0:
        return vmin, t0
    neg = np.nonzero(vs <= 0.0)[0]
    hi = float(ts[neg[0]]) if neg.size else tmin
    lo = float(ts[np.searchsorted(ts, hi) - 1])
    return vmin, float(brentq(values, lo, hi, xtol=1e-14, rtol=1e-14))


def integrate_stance(
    model: ContactModel,
    q0: ArrayLike,
    qd0: ArrayLike,
    mu: float,
    *,
    t0: float = 0.0,
    t_max: float = 50.0,
    mode: str | None = None,
    rtol: float = RTOL,
    atol: float = ATOL,
    slip_max_step: float = SLIP_MAX_STEP,
    max_phases: int = 50,
    v_tol: float = V_TOL,
) -> StanceResult:
    """Event-driven integration of one stance (002 eqs 2, 31-35) from (q0, qd0) until the impact guard or a failure.

    Each phase is integrated with DOP853 (``solve_ivp``) in its mode until a terminal event: the guard
    (outcome "impact"), f_n = 0 ("detached"), stick -> slip when f_t reaches -+mu f_n (new slip direction
    -sgn(f_t)), slip -> stick or slip reversal when v_t reaches 0 (mode of :func:`mode_from_stick_force`), the
    Painleve denominator of (33) reaching 0 ("painleve"), or a model failure event. The step is limited to
    ``slip_max_step`` while slipping (grazing trap, docs/theory/stick-slip.md, Sec. 4). At each phase start the
    velocities are projected onto the active constraints (drift removal). f_n is also checked on the dense solution,
    so a tangential dip below 0 between solver steps still counts as a detachment.
    """
    q = np.asarray(q0, dtype=float).copy()
    qd = np.asarray(qd0, dtype=float).copy()
    n = q.size
    mode = mode or initial_mode(model, q, qd, mu, v_tol)
    phases: list[Phase] = []
    sections: dict[str, tuple[float, Vector, Vector]] = {}
    t = float(t0)
    min_fn = math.inf
    outcome = "stalled"
    while True:
        if len(phases) >= max_phases:
            outcome = "chatter"
            break
        qd = _project(model, q, qd, mode)
        phases.append(Phase(mode, t, q.copy(), qd.copy()))
        if mode != "stick":
            start = contact_state(model, q, qd, mode, mu) if not math.isinf(mu) else None
            if start is None or start.denominator <= 0.0 or start.force[1] < 0.0:
                # mu = inf: slip only when f_n,stick < 0; denominator <= 0: Painleve; f_n < 0: no contact force
                outcome = "painleve" if start is not None and start.denominator <= 0.0 else "detached"
                fn_now = contact_state(model, q, qd, "stick", mu).force[1] if start is None else start.force[1]
                min_fn = min(min_fn, float(fn_now))
                break
        cache = _Cache(model, mode, mu, n)
        events, names = _phase_events(model, cache, mode, mu, n, (t, np.concatenate([q, qd])))

        def rhs(_t: float, y: Vector, cache: _Cache = cache) -> Vector:
            return np.concatenate([y[n:], cache(y).qdd])

        slipping = mode != "stick"
        sol = solve_ivp(
            rhs,
            (t, t_max),
            np.concatenate([q, qd]),
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=events,
            dense_output=True,
            max_step=slip_max_step if slipping else np.inf,
            first_step=min(1e-4, slip_max_step) if slipping else None,
        )
        hits = [
            (float(te[0]), k) for k, te in enumerate(sol.t_events) if te.size and not names[k].startswith("section:")
        ]
        t_end = float(sol.t[-1])
        y_end = sol.y[:, -1]
        name = "stalled" if sol.status == 0 else "solver"
        if sol.status == 1 and hits:
            t_hit, k = min(hits)
            name, t_end, y_end = names[k], t_hit, sol.y_events[k][0]

        def normal(s: float, sol=sol, cache=cache) -> float:  # type: ignore[no-untyped-def]
            return float(cache(sol.sol(s)).force[1])

        if t_end > t:
            fn_min, t_dip = _first_dip(normal, t, t_end, FN_SAMPLES)
            if t_dip < t_end and name != "detached":
                name, t_end, y_end = "detached", t_dip, sol.sol(t_dip)
                fn_min = 0.0
            min_fn = min(min_fn, fn_min)
        for k, label in enumerate(names):
            if label.startswith("section:") and sol.t_events[k].size:
                key = label[len("section:") :]
                ts = float(sol.t_events[k][0])
                if key not in sections and ts <= t_end:
                    ye = sol.y_events[k][0]
                    sections[key] = (ts, ye[:n].copy(), ye[n:].copy())
        q, qd, t = y_end[:n].copy(), y_end[n:].copy(), t_end
        min_fn = min(min_fn, float(contact_state(model, q, qd, mode, mu).force[1]))
        if name == "->slip+" or name == "->slip-":
            mode = name[2:]
        elif name == "stop":
            qd = _project(model, q, qd, "stick")
            mode = mode_from_stick_force(contact_state(model, q, qd, "stick", mu).force, mu)
        else:
            outcome = name
            break
    return StanceResult(tuple(phases), outcome, t, q, qd, min_fn, sections)
