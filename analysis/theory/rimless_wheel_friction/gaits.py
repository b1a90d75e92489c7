"""Gait types A-D of the rimless wheel with Coulomb friction: classification, settling and period-1 gaits.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 3.3 (Figs 3.3-3.7): the type of a step (A, B, C, D+/D-), iteration of the post-impact map until it settles, and
the period-1 gait of each type by Newton shooting on the simulator with its eigenvalues; derivation page
docs/theory/stick-slip.md, Secs. 2 and 5.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory.rimless_wheel_friction.one_step import StepRecord, step
from mjpoincare.analysis.theory.rimless_wheel_friction.params import X_NEUTRAL, FrictionWheel, validate
from mjpoincare.analysis.theory.rimless_wheel_friction.slip import type_d_linear
from mjpoincare.analysis.theory.rimless_wheel_friction.sticking import sticking_fixed_point
from mjpoincare.analysis.theory.shooting import central_jacobian, chord_newton
from numpy.typing import NDArray

_GAIT_KINDS = ("A", "B", "C", "D")


def classify_record(record: StepRecord) -> str | None:
    """Gait type of one step (002 Sec. 3.3): "A" sticking impact and stick throughout; "B" sticking impact and some
    slip; "C" slipping impact with a stick phase; "D+"/"D-" slipping impact and slip throughout, split by the sign of
    Delta x_dot; None on failure."""
    if record.failure is not None or record.impact is None:
        return None
    if record.impact == "sticking":
        return "A" if all(m == "stick" for m in record.phases) else "B"
    if "stick" in record.phases:
        return "C"
    return "D+" if record.dx > 0 else "D-"


def classify(records: Sequence[StepRecord]) -> str | None:
    """Gait type (see :func:`classify_record`) of a converged sequence of steps: the type of its last step, or the
    last step's failure reason ("backward", "detached", ...)."""
    if not records:
        return None
    last = records[-1]
    return last.failure if last.failure is not None else classify_record(last)


@dataclass(frozen=True)
class Settled:
    """Outcome of :func:`settle`: ``outcome`` a gait type ("A", "B", "C", "D+"), a failure reason, or "unsettled";
    ``steps`` the number of steps taken; ``records`` all of them."""

    outcome: str
    steps: int
    records: tuple[StepRecord, ...]


def settle(
    w: FrictionWheel, state: Sequence[float], max_steps: int = 300, tol: float = 1e-9, method: str = "fast"
) -> Settled:
    """Iterate the post-impact map from ``state`` = (theta_dot, x_dot) until a step changes the state by less than
    ``tol`` (theta_dot and x_dot for A/B/C; theta_dot only for D+, where x_dot grows without bound), a step fails,
    or ``max_steps``. D- never settles: x_dot falls to 0 in finitely many steps (002 Sec. 3.3, Fig. 3.6)."""
    validate(w)
    records: list[StepRecord] = []
    z = (float(state[0]), float(state[1]))
    for k in range(1, max_steps + 1):
        rec = step(w, z, method=method)
        records.append(rec)
        if rec.failure is not None:
            return Settled(rec.failure, k, tuple(records))
        label = classify_record(rec)
        d_th, d_x = abs(rec.theta_dot - z[0]), abs(rec.x_dot - z[1])
        if (label in ("A", "B", "C") and max(d_th, d_x) < tol) or (label == "D+" and d_th < tol):
            return Settled(str(label), k, tuple(records))
        z = rec.post
    return Settled("unsettled", max_steps, tuple(records))


@dataclass(frozen=True)
class Gait:
    """A period-1 gait (002 Sec. 3.3): ``kind`` "A", "B", "C", "D+" or "D-"; ``fixed_point`` (theta_dot*,) or, for
    C, (theta_dot*, x_dot*) at the post-impact section; ``eigenvalues`` of the return map's Jacobian (1-D for A, B,
    D; 2-D for C); ``phases`` and ``phase_angles`` of the step; ``impact``; ``dx_per_step`` Delta x_dot per step (D;
    0 otherwise); ``pre_impact`` (theta_dot^-, x_dot^-) (for D, x_dot^- - x_dot^+ ); ``period`` the step time
    (units 1/omega_c); ``midstance_rate`` theta_dot at theta = 0 and ``midstance_x_dot`` x_dot there (for D the
    increment over the post-impact x_dot); ``impulse_ratio`` F~_t/F~_n; ``min_fn`` min f_n/(mg)."""

    kind: str
    fixed_point: NDArray[np.float64]
    eigenvalues: NDArray[np.complex128]
    phases: tuple[str, ...]
    phase_angles: tuple[float, ...]
    impact: str
    dx_per_step: float
    pre_impact: tuple[float, float]
    period: float
    midstance_rate: float
    midstance_x_dot: float
    impulse_ratio: float
    min_fn: float


def _affine_fixed_point(fun: Callable[[float], float], s0: float, tol: float = 1e-13) -> float | None:
    """Secant iteration on G(s) = P(sqrt s)^2 - s (s = theta_dot^2), nearly affine for these maps
    (exactly affine for A, eq 15, and for D, :func:`slip_affine_coefficients`); None if G is undefined there."""
    g0 = fun(s0)
    if not math.isfinite(g0):
        return None
    for s1 in (s0 * (1 - 1e-5), s0 * (1 + 1e-5)):
        g1 = fun(s1)
        if math.isfinite(g1):
            break
    else:
        return None
    for _ in range(40):
        if g1 == g0:
            return s1 if g1 == 0.0 else None
        s2 = s1 - g1 * (s1 - s0) / (g1 - g0)
        if not s2 > 0.0:
            return None
        s0, g0, s1 = s1, g1, s2
        g1 = fun(s1)
        if not math.isfinite(g1):
            return None
        if abs(s1 - s0) <= tol * s1:
            return s1
    return None


def _derivative(fun: Callable[[float], float], x: float, h: float) -> float:
    """Central difference, or a one-sided one where the map is undefined on one side (at a branch edge)."""
    up, down, mid = fun(x + h), fun(x - h), fun(x)
    if math.isfinite(up) and math.isfinite(down):
        return (up - down) / (2 * h)
    if math.isfinite(up):
        return (up - mid) / h
    return (mid - down) / h


def _gait_from(w: FrictionWheel, z: NDArray[np.float64], x_dot: float, kind: str, eig: NDArray[np.complex128]) -> Gait:
    rec = step(w, (float(z[0]), x_dot))
    label = classify_record(rec)
    dx = rec.dx if kind == "D" else 0.0
    mid_x = rec.midstance[1] - x_dot if kind == "D" else rec.midstance[1]
    pre_x = rec.x_dot_pre - x_dot if kind == "D" else rec.x_dot_pre
    return Gait(str(label), z, eig, rec.phases, rec.phase_angles, str(rec.impact), dx, (rec.theta_dot_pre, pre_x),
                rec.duration, rec.midstance[0], mid_x, rec.impulse_ratio, rec.min_fn)


def find_gait(w: FrictionWheel, kind: str, guess: Sequence[float] | None = None) -> Gait | None:
    """Period-1 gait of type ``kind`` ("A", "B", "C" or "D", 002 Sec. 3.3) by Newton shooting on the simulator, or
    None if no such gait exists at this mu.

    A, B: 1-D map theta_dot -> theta_dot^+ with x_dot = 0 (a sticking impact leaves x_dot^+ = 0); secant on
    theta_dot^2 from eq 16. C: 2-D map in (theta_dot, x_dot) (Newton from ``guess`` or from a forward iteration
    started at (eq 16, 0)). D: 1-D map in theta_dot at x_dot = X_NEUTRAL (the slip dynamics eq 42 and the slipping
    impact's theta row do not depend on x_dot > 0); ``dx_per_step`` gives Delta x_dot and the kind "D+"/"D-" its sign.
    The converged step must be of the requested type, without failure; eigenvalues by central differences.
    """
    validate(w)
    if kind not in _GAIT_KINDS:
        raise ValueError(f"kind must be one of {_GAIT_KINDS} (got {kind!r})")
    if kind == "C":
        return _find_c(w, guess)
    x_dot = X_NEUTRAL if kind == "D" else 0.0
    start = float(guess[0]) if guess is not None else sticking_fixed_point(w)
    if kind == "D" and guess is None:
        start = type_d_linear(w)[0]
        if not math.isfinite(start):
            return None

    def post(th: float) -> float:
        rec = step(w, (th, x_dot))
        ok = rec.failure is None and (rec.impact == "sticking") == (kind in "AB")
        return rec.theta_dot if ok else math.nan

    s_star = _affine_fixed_point(lambda s: post(math.sqrt(s)) ** 2 - s, start**2)
    if s_star is None:
        return None
    th_star = math.sqrt(s_star)
    rec = step(w, (th_star, x_dot))
    label = classify_record(rec)
    if label is None or label[0] != kind:
        return None
    lam = _derivative(post, th_star, 1e-5 * th_star)
    if not math.isfinite(lam):
        return None
    return _gait_from(w, np.array([th_star]), x_dot, kind, np.array([lam], dtype=complex))


def _c_post(w: FrictionWheel, z: NDArray[np.float64]) -> NDArray[np.float64]:
    """The 2-D post-impact map of a C-like step (slipping impact, x_dot^+ > 0), NaN otherwise."""
    rec = step(w, (float(z[0]), float(z[1])))
    if rec.failure is not None or rec.impact != "slipping" or not rec.x_dot > 0:
        return np.array([math.nan, math.nan])
    return np.array([rec.theta_dot, rec.x_dot])


def _c_fixed_point(w: FrictionWheel, z0: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """Type C fixed point by chord-Newton from z0, None unless it converges to a Type C step."""
    z_star = chord_newton(lambda v: _c_post(w, v) - v, z0, tol=1e-14, step_tol=1e-12, max_iter=40,
                          relative_step=True, halvings=0)
    if z_star is None or not z_star[1] > 0 or classify_record(step(w, tuple(z_star))) != "C":
        return None
    return z_star


def _find_c(w: FrictionWheel, guess: Sequence[float] | None) -> Gait | None:
    def post(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return _c_post(w, z)

    if guess is None:
        z = np.array([sticking_fixed_point(w), 0.0])
        for _ in range(40):
            rec = step(w, tuple(z))
            if rec.failure is not None:
                return None
            z = np.array(rec.post)
            if classify_record(rec) == "C" and z[1] > 0:
                break
        else:
            return None
    else:
        z = np.asarray(guess, dtype=float)
    z_star = _c_fixed_point(w, z)
    if z_star is None:
        return None
    eig = sort_eigenvalues(np.linalg.eigvals(central_jacobian(post, z_star, 1e-6, relative=True)).astype(complex))
    return _gait_from(w, z_star, float(z_star[1]), "C", eig)


def midstance_rate(gait: Gait) -> float:
    """theta_dot at theta = 0 (mid-stance) on the gait: the section the MuJoCo side samples, away from the smeared
    soft impact (derivation page docs/theory/stick-slip.md, Secs. 5-6)."""
    return gait.midstance_rate


def midstance_x_dot(gait: Gait) -> float:
    """x_dot at theta = 0 on the gait (for D: the increment over the post-impact x_dot, which is neutral)."""
    return gait.midstance_x_dot
