"""Generic stick-slip machinery of a planar N-DOF robot with one point stance foot (002 Appendix A).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn.
Syst., Sec. 2 eqs (1)-(8) and Appendix A eqs (31)-(40); re-derivation on the derivation page
docs/theory/stick-slip.md, Sec. 4.

Notation (002 eq 2, with the sign of (34) fixed): M(q) qdd = -h(q, qd) + W(q)^T f, where h = B + G - E u is
supplied by the model, W = dr/dq = [w_t^T; w_n^T] is the (2, N) Jacobian of the stance foot r (rows: tangential,
normal), f = (f_t, f_n) is the contact force on the robot and W~(q) = dr~/dq is the swing-foot Jacobian.
Contact modes (002 eq 35): ``"stick"`` (v_t = v_n = 0), ``"slip+"`` (v_t = w_t^T qd > 0, f_t = -mu f_n) and
``"slip-"`` (v_t < 0, f_t = +mu f_n). Flight is not modelled: f_n reaching 0 ends the stance as ``"detached"``
(as in 002, which treats it as a failure).

The module knows nothing about a particular robot: a :class:`ContactModel` bundles the callables, the impact
guard (swing-foot height) and optional named failure events (e.g. a rimless wheel rolling back) and sections
(e.g. mid-stance) to record. It never imports mujoco.

Corrections to 002 Appendix A (re-derived; also listed on the derivation page, Sec. 7):

* (34) prints qdd = M^-1 (B + G - E u + W^T f); with (2) it must be M^-1 (-B - G + E u + W^T f). (31) and (33)
  are correct as printed.
* The sticking constraint is W(q) qd = 0 (printed "W(q) = 0"), and its derivative is solved for qdd (printed qd).
* (39): the slipping impulse direction is Gamma~ = (s mu, 1)^T (tangential first, like f = (f_t, f_n)); the printed
  (1, s mu)^T swaps the components. The sign s is taken from the plastic (sticking) impulse,
  s = sgn(F~_t,stick): the impulse is projected onto the cone edge it left (Chatterjee-Ruina with e = e_t = 0).
  002's s = -sgn(v~_t^-) agrees whenever v~_t^- != 0 and the slip does not reverse; it is undefined for
  v~_t^- = 0. This impact law cannot represent slip reversal within the impact; :func:`impact` flags it.
* The slip normal force (33) is only meaningful for a positive "normal effective inverse mass"
  w_n^T M^-1 W^T Gamma; a non-positive value is the Painleve case (inconsistent or indeterminate), which 002
  excludes (its ref. [54]); it ends the stance as ``"painleve"``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]

MODES = ("stick", "slip+", "slip-")
RTOL = 1e-11
ATOL = 1e-12
#: Default largest time step while slipping (grazing trap: a slip that starts on the cone boundary can end again
#: within one long solver step; derivation page docs/theory/stick-slip.md, Sec. 4).
SLIP_MAX_STEP = 1e-2
#: |v_t| below which a state counts as not slipping when the mode is chosen.
V_TOL = 1e-10
#: Samples per phase of the dense solution on which f_n is checked for a dip below 0 between solver steps.
FN_SAMPLES = 33


@dataclass(frozen=True)
class ContactModel:
    """A planar robot with one point stance foot (002 Sec. 2), as callables of (q, qd) (arrays of shape (N,)).

    ``mass_matrix`` M(q) (N, N), symmetric positive definite; ``bias`` h(q, qd) = B + G - E u (N,) (002 eq 2);
    ``contact_jacobian`` W(q) (2, N), rows w_t, w_n of the stance foot (002 eq 1); ``contact_jacobian_rate``
    Wdot(q, qd) qd (2,); ``swing_jacobian`` W~(q) (2, N) of the swing foot (002 eq 36); ``impact_guard`` g(q, qd),
    the swing foot's height, whose crossing of 0 in ``guard_direction`` ends the stance with an impact (002 eq 7).
    ``failure_events``: (name, g(q, qd), direction) that end the stance with outcome ``name``.
    ``sections``: (name, g(q, qd), direction) whose first crossing is recorded (non-terminal).
    """

    mass_matrix: Callable[[Vector], Matrix]
    bias: Callable[[Vector, Vector], Vector]
    contact_jacobian: Callable[[Vector], Matrix]
    contact_jacobian_rate: Callable[[Vector, Vector], Vector]
    swing_jacobian: Callable[[Vector], Matrix]
    impact_guard: Callable[[Vector, Vector], float]
    guard_direction: float = -1.0
    failure_events: tuple[tuple[str, Callable[[Vector, Vector], float], float], ...] = ()
    sections: tuple[tuple[str, Callable[[Vector, Vector], float], float], ...] = ()


class Phase(NamedTuple):
    """One continuous phase of a stance: contact mode, start time, configuration and velocities at its start."""

    mode: str
    t_start: float
    q_start: Vector
    qd_start: Vector


class ContactState(NamedTuple):
    """Contact force f = (f_t, f_n) on the robot, accelerations qdd, and for slip modes the denominator
    w_n^T M^-1 W^T Gamma of (33) (NaN for stick)."""

    force: Vector
    qdd: Vector
    denominator: float


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


class ImpactResult(NamedTuple):
    """Result of :func:`impact`: ``kind`` "sticking" or "slipping", post-impact velocities, the impulse
    F~ = (F~_t, F~_n) at the swing foot, the sign s of the slipping impulse (0 for sticking), the swing foot's
    post-impact velocity v~+ = W~ qd+, the old stance foot's post-impact normal velocity (> 0: it lifts off) and
    ``consistent`` (F~_n > 0, positive slip denominator, v~_t+ opposite to s, old foot not pushed into the ground).
    """

    kind: str
    qd_plus: Vector
    impulse: Vector
    sign: float
    swing_velocity: Vector
    liftoff_velocity: float
    consistent: bool


def _slip_sign(mode: str) -> float:
    return {"slip+": 1.0, "slip-": -1.0}[mode]


def stick_force(mass: Matrix, bias: Vector, jac: Matrix, jac_rate_qd: Vector) -> Vector:
    """Sticking contact force f = (W M^-1 W^T)^-1 (W M^-1 h - Wdot qd) (002 eq 31)."""
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    return np.linalg.solve(jac @ minv[:, 1:], jac @ minv[:, 0] - jac_rate_qd)


def slip_normal_force(
    mass: Matrix, bias: Vector, jac: Matrix, jac_rate_qd: Vector, mu: float, direction: float
) -> tuple[float, float]:
    """Slipping normal force (002 eq 33) for slip direction sgn(v_t) = ``direction``, Gamma = (-direction mu, 1)
    (002 eq 32): f_n = (w_n^T M^-1 h - wdot_n^T qd) / (w_n^T M^-1 W^T Gamma).

    Returns (f_n, denominator); a denominator <= 0 is the Painleve case (002 Appendix A, ref. [54]).
    """
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    gamma = np.array([-direction * mu, 1.0])
    denominator = float(jac[1] @ minv[:, 1:] @ gamma)
    return float(jac[1] @ minv[:, 0] - jac_rate_qd[1]) / denominator, denominator


def contact_state(model: ContactModel, q: Vector, qd: Vector, mode: str, mu: float) -> ContactState:
    """Contact force and accelerations in a given mode: f from (31) (stick) or (32)-(33) (slip), then
    qdd = M^-1 (-h + W^T f) (002 eq 34 with its sign corrected)."""
    mass = model.mass_matrix(q)
    bias = model.bias(q, qd)
    jac = model.contact_jacobian(q)
    rate = model.contact_jacobian_rate(q, qd)
    minv = np.linalg.solve(mass, np.column_stack([bias, jac.T]))
    minv_h, minv_wt = minv[:, 0], minv[:, 1:]
    if mode == "stick":
        force = np.linalg.solve(jac @ minv_wt, jac @ minv_h - rate)
        denominator = math.nan
    else:
        gamma = np.array([-_slip_sign(mode) * mu, 1.0])
        denominator = float(jac[1] @ minv_wt @ gamma)
        force = gamma * (float(jac[1] @ minv_h - rate[1]) / denominator)
    return ContactState(force, -minv_h + minv_wt @ force, denominator)


def cone_margin(force: ArrayLike, mu: float) -> float:
    """mu f_n - |f_t| (>= 0 inside the Coulomb cone, 002 eq 3); f_n for mu = inf."""
    f_t, f_n = np.asarray(force, dtype=float)
    return float(f_n) if math.isinf(mu) else float(mu * f_n - abs(f_t))


def mode_from_stick_force(force: ArrayLike, mu: float) -> str:
    """Mode logic (002 eq 35) at v_t = 0: "stick" if the sticking force (31) lies in the cone, else slip with
    sgn(v_t) = -sgn(f_t,stick) (the slip that friction at the cone edge opposes)."""
    if cone_margin(force, mu) >= 0.0:
        return "stick"
    return "slip+" if float(np.asarray(force)[0]) < 0.0 else "slip-"


def initial_mode(model: ContactModel, q: ArrayLike, qd: ArrayLike, mu: float, v_tol: float = V_TOL) -> str:
    """Contact mode of a state (002 eq 35): slip in the direction of v_t if |v_t| > v_tol, else the mode of
    :func:`mode_from_stick_force`."""
    q = np.asarray(q, dtype=float)
    qd = np.asarray(qd, dtype=float)
    v_t = float(model.contact_jacobian(q)[0] @ qd)
    if v_t > v_tol:
        return "slip+"
    if v_t < -v_tol:
        return "slip-"
    return mode_from_stick_force(contact_state(model, q, qd, "stick", mu).force, mu)


def _project(model: ContactModel, q: Vector, qd: Vector, mode: str) -> Vector:
    """Remove constraint drift: the M-orthogonal projection of qd onto W qd = 0 (stick) or w_n^T qd = 0 (slip),
    i.e. the plastic impact law (38) applied at the stance foot."""
    jac = model.contact_jacobian(q)
    if mode != "stick":
        jac = jac[1:]
    minv_wt = np.linalg.solve(model.mass_matrix(q), jac.T)
    return qd - minv_wt @ np.linalg.solve(jac @ minv_wt, jac @ qd)


def sticking_impact(mass: Matrix, swing_jac: Matrix, qd_minus: Vector) -> tuple[Vector, Vector]:
    """Perfectly plastic sticking impact at the swing foot (002 eqs 37-38):
    F~ = -(W~ M^-1 W~^T)^-1 W~ qd-, qd+ = qd- + M^-1 W~^T F~. Returns (qd+, F~)."""
    minv_wt = np.linalg.solve(mass, swing_jac.T)
    impulse = -np.linalg.solve(swing_jac @ minv_wt, swing_jac @ qd_minus)
    return qd_minus + minv_wt @ impulse, impulse


def slipping_impact(
    mass: Matrix, swing_jac: Matrix, qd_minus: Vector, mu: float, sign: float
) -> tuple[Vector, Vector, float]:
    """Slipping impact (002 eqs 39-40, corrected Gamma~ = (s mu, 1)^T): no rebound w~_n^T qd+ = 0 with
    F~ = Gamma~ F~_n, F~_n = -w~_n^T qd- / (w~_n^T M^-1 W~^T Gamma~). Returns (qd+, F~, denominator)."""
    gamma = np.array([sign * mu, 1.0])
    minv_wt = np.linalg.solve(mass, swing_jac.T)
    denominator = float(swing_jac[1] @ minv_wt @ gamma)
    impulse = gamma * (-float(swing_jac[1] @ qd_minus) / denominator)
    return qd_minus + minv_wt @ impulse, impulse, denominator


def impact(model: ContactModel, q: ArrayLike, qd_minus: ArrayLike, mu: float, tol: float = 1e-12) -> ImpactResult:
    """Frictional plastic impact (002 Sec. 2.2 and Appendix A.2): the sticking impact (37-38) if its impulse lies
    in the cone (002 eq 5), else the slipping impact (39-40, corrected) with s = sgn(F~_t,stick).

    No impulse acts at the old stance foot (002's assumption); ``liftoff_velocity`` = w_n^T qd+ of the old foot
    tells whether it actually separates. Relabelling (002 eq 6) is the model's business.
    """
    q = np.asarray(q, dtype=float)
    qd_minus = np.asarray(qd_minus, dtype=float)
    mass = model.mass_matrix(q)
    swing = model.swing_jacobian(q)
    qd_plus, impulse = sticking_impact(mass, swing, qd_minus)
    kind, sign, denominator = "sticking", 0.0, 1.0
    if not (impulse[1] > 0.0 and cone_margin(impulse, mu) >= -tol * abs(impulse[1])):
        sign = 1.0 if impulse[0] > 0.0 else -1.0
        qd_plus, impulse, denominator = slipping_impact(mass, swing, qd_minus, mu, sign)
        kind = "slipping"
    swing_velocity = swing @ qd_plus
    liftoff = float(model.contact_jacobian(q)[1] @ qd_plus)
    scale = tol * max(1.0, float(np.max(np.abs(qd_minus))))
    consistent = bool(impulse[1] > 0.0 and denominator > 0.0 and liftoff >= -scale)
    if kind == "slipping":
        consistent = consistent and sign * float(swing_velocity[0]) <= scale
    return ImpactResult(kind, qd_plus, impulse, sign, swing_velocity, liftoff, consistent)


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
