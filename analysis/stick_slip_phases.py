"""Stick/slip phases and gait types of a rimless wheel's steps, measured on recorded rows (numpy only).

The contact modes are 002's (Gamus & Or 2015, eq 35): ``stick``, ``slip+`` (the foot slides forward, friction
f_t = -mu f_n) and ``slip-``; the gait types are those of 002 Sec. 3.3: A sticking impact and stick throughout,
B sticking impact and stick -> slip, C slipping impact and slip -> stick -> slip, D slipping impact and slip
throughout (D+ / D-: the slip speed grows / shrinks each step).

* **Rows** (:func:`stance_rows`): a stance row slips when its friction force is on the cone's edge,
  |f_t| >= (1 - eps) mu f_n over a short window (Coulomb: a sliding contact has saturated friction), in the
  direction the friction opposes; otherwise it sticks. Rows in the impact window after a support transfer, or off
  contact, are neither. The foot's speed against ``v_thr`` gives the velocity-only classification beside it: it
  cannot see the slips whose speed stays below the creep of a soft contact.
* **Phases** (:func:`phase_runs`): runs of one mode, flicker shorter than ``merge_phase`` merged away.
* **Steps** (:func:`step_table`): per stance j, the mid-stance section theta = 0, the impact that ends it (slipping
  when the new foot's speed after the impact window exceeds ``v_thr`` or the impulse ratio over the window is on
  the cone's edge), the phases and the gait type; per trajectory the failure (rolling back, or flight).

Every array is (B, T) over trajectories and recorded rows, or (B, S) over trajectories and steps.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from mjpoincare.analysis.contact_modes import (
    CONE_EPS,
    EXCLUDED,
    MERGE_PHASE,
    MODE_NAMES,
    STICK,
    cone_modes,
    merge_short_runs,
    run_starts,
    speed_modes,
)
from mjpoincare.analysis.returnmap import ReturnMapFit, fit_return_map, sample_pairs
from mjpoincare.analysis.sections import level_crossings


@dataclass(frozen=True)
class Classifier:
    """Thresholds of the stick/slip classification (speeds nondimensional, times in s).

    ``mu`` (B,) friction of each trajectory; ``v_thr`` foot speed above which it moves; ``impact_window`` time after
    a support transfer that belongs to the impact; ``eps`` friction on the cone when |f_t/f_n| >= (1 - eps) mu;
    ``ratio_window`` force ratio from impulses over a centred window of this length (averages contact chatter);
    ``merge_phase`` phases shorter than this are merged into the one before (stick-slip flicker at an onset);
    ``min_phase_rows`` a step has a stick (slip) phase when at least this many rows stick (slip)."""

    mu: np.ndarray
    v_thr: float
    impact_window: float
    eps: float = CONE_EPS
    ratio_window: float = 1e-3
    merge_phase: float = MERGE_PHASE
    min_phase_rows: int = 2


@dataclass
class Rows:
    """Per-row signals of a batch (B, T): stance angle ``theta`` (wrapped), ``rate`` theta_dot and ``slip`` speed of
    the stance foot's contact point (nondimensional), ``clearance`` of the lowest foot (x l), the windowed contact
    force ratio ``ratio`` f_t/f_n (NaN off contact), ``stance`` index (forward support transfers so far),
    ``since`` time since the last transfer (s), ``mode`` 0 stick, 1 slip+, 2 slip-, 3 impact window / air."""

    time: np.ndarray
    theta: np.ndarray
    rate: np.ndarray
    slip: np.ndarray
    clearance: np.ndarray
    ratio: np.ndarray
    force_t: np.ndarray  # contact force per unit mass along the slope (raw, per row)
    force_n: np.ndarray  # and normal to it
    stance: np.ndarray
    since: np.ndarray
    wrap: np.ndarray  # True at the last row before a forward support transfer
    mode: np.ndarray
    vmode: np.ndarray  # the same from the foot's speed alone (|x_dot| > v_thr), for comparison


def window_sum(x: np.ndarray, width: int) -> np.ndarray:
    """Moving sum of ``x`` (B, T) over ``width`` rows along axis 1, centred on each row; (B, T). Near the first row
    the window is shifted to start there, near the last it is cut short."""
    if width <= 1:
        return x.copy()
    c = np.concatenate([np.zeros((x.shape[0], 1)), np.cumsum(x, axis=1)], axis=1)
    n = x.shape[1]
    lo = np.clip(np.arange(n) - width // 2, 0, n)
    hi = np.clip(lo + width, 0, n)
    return c[:, hi] - c[:, lo]


def stance_rows(*, time: np.ndarray, theta: np.ndarray, rate: np.ndarray, slip: np.ndarray, clearance: np.ndarray,
                force_t: np.ndarray, force_n: np.ndarray, half_step: float, timestep: float, weight: float,
                cls: Classifier) -> Rows:
    """Support transfers, contact force ratio and contact mode of every row, vectorised over the batch.

    All arrays (B, T): ``theta`` the stance angle wrapped to [-half_step, half_step) (half_step = phi = pi/n), ``rate``
    and ``slip`` theta_dot and the stance foot's speed, ``clearance`` of the lowest foot, ``force_t``/``force_n``
    the contact force per unit mass along and normal to the slope; ``weight`` |g_n|, the normal force per unit mass
    of a wheel at rest (a window holds contact when its normal impulse exceeds 1e-3 of the weight's)."""
    phi, dt = half_step, timestep
    jump = theta[:, 1:] - theta[:, :-1]
    forward = np.concatenate([jump < -phi, np.zeros((theta.shape[0], 1), bool)], axis=1)
    stance = np.concatenate([np.zeros((theta.shape[0], 1), int), np.cumsum(forward[:, :-1], axis=1)], axis=1)
    cols = np.arange(theta.shape[1])[None, :]
    last = np.maximum.accumulate(np.where(np.roll(forward, 1, axis=1) & (cols > 0), cols, 0), axis=1)
    since = time - np.take_along_axis(time, last, axis=1)
    # window sums of the stance force: the impact-window rows are left out, so a window that reaches across a
    # support transfer holds only the stance foot's force (the impulse at the transfer is the next row's)
    # the row before a transfer is part of the impact too: the new foot can touch a fraction of a step before the
    # geometric transfer (the old foot sits in its own penetration), and that row's force is then the impulse
    impact = (since < cls.impact_window) | forward
    width = max(1, round(cls.ratio_window / dt))
    st = window_sum(np.where(impact, 0.0, np.nan_to_num(force_t)), width)
    sn = window_sum(np.where(impact, 0.0, np.nan_to_num(force_n)), width)
    contact = sn > 1e-3 * weight * width
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(contact, st / sn, np.nan)
    # Coulomb: a contact slips when its friction is on the cone (the direction is the one friction opposes)
    mode = cone_modes(ratio, cls.mu[:, None], cls.eps)
    # off contact (the foot in the air: a hop, or a sliding foot lifted by a soft contact) a row is neither
    off = impact | ~contact | ~np.isfinite(theta)
    mode[off] = EXCLUDED
    # the velocity-only classification, for comparison: the foot's speed against v_thr
    vmode = speed_modes(slip, cls.v_thr)
    vmode[off] = EXCLUDED
    return Rows(time=time, theta=theta, rate=rate, slip=slip, clearance=clearance, ratio=ratio, force_t=force_t,
                force_n=force_n, stance=stance, since=since, wrap=forward, mode=mode, vmode=vmode)


@dataclass(frozen=True)
class Runs:
    """Stick/slip phases as runs of rows (impact-window and air rows left out), in time order, each (R,):
    ``traj``, ``stance``, ``mode``, ``first`` row index and ``theta`` at the run's start."""

    traj: np.ndarray
    stance: np.ndarray
    mode: np.ndarray
    first: np.ndarray
    theta: np.ndarray


def phase_runs(rows: Rows, valid: np.ndarray, dt: float, merge_phase: float) -> Runs:
    """The phases of every stance over the ``valid`` (B, T) rows: runs shorter than ``merge_phase`` (s) absorbed
    into the phase before them (into the next one at the start of a stance), :func:`merge_short_runs`."""
    tr, kr = np.nonzero(valid & (rows.mode != EXCLUDED))
    stance, mode = rows.stance[tr, kr], rows.mode[tr, kr].astype(int)
    group = tr.astype(np.int64) * (int(stance.max(initial=0)) + 1) + stance  # one group per trajectory and stance
    mode = merge_short_runs(group, mode, max(1, round(merge_phase / dt)))
    starts = run_starts(group, mode) if tr.size else np.zeros(0, int)
    return Runs(traj=tr[starts], stance=stance[starts], mode=mode[starts], first=kr[starts],
                theta=rows.theta[tr[starts], kr[starts]])


def phase_sequence(runs: Runs, b: int, j: int) -> tuple[tuple[str, ...], tuple[float, ...]]:
    """The stick/slip phases of stance ``j`` of trajectory ``b`` and the theta at their starts."""
    sel = (runs.traj == b) & (runs.stance == j)
    return (tuple(MODE_NAMES[int(m)] for m in runs.mode[sel]), tuple(float(x) for x in runs.theta[sel]))


@dataclass
class Steps:
    """Per-step observations of a batch, arrays (B, S) over step index j (stance j and the impact ending it);
    NaN / -1 / False where a trajectory has no such complete step.

    ``mid_rate``/``mid_slip`` theta_dot and x_dot at mid-stance; ``post_slip`` x_dot just after the impact that
    starts stance j (j = 0: after the first impact window of the initial state); ``impact_slipping`` whether the
    impact ending step j slips; ``impulse_ratio`` F~_t/F~_n of that impact; ``slip_rows``/``stick_rows`` rows in
    each mode; ``onset`` theta at the start of the last slip phase; ``kind`` gait type of the step ("A", "B", "C",
    "D+", "D-", "" unknown); ``complete`` the step's impact and the next post-impact speed were recorded;
    ``failure`` (B,): "", "backward" or "detached", with ``failure_step`` (B,)."""

    mid_rate: np.ndarray
    mid_slip: np.ndarray
    post_slip: np.ndarray
    impact_slipping: np.ndarray
    impulse_ratio: np.ndarray
    slip_rows: np.ndarray
    stick_rows: np.ndarray
    onset: np.ndarray
    kind: np.ndarray
    complete: np.ndarray
    failure: np.ndarray
    failure_step: np.ndarray
    vkind: np.ndarray  # the type from the foot's speed alone (|x_dot| > v_thr), for comparison
    runs: Runs


def _per_stance(values: np.ndarray, traj: np.ndarray, stance: np.ndarray, shape: tuple[int, int],
                reduce: str = "first") -> np.ndarray:
    """Scatter ``values`` (N,) at (``traj``, ``stance``) (N,) into a ``shape`` (B, S) array: the first value, their
    sum or max (NaN, or 0 for the sum, where none)."""
    out = np.full(shape, np.nan) if reduce != "sum" else np.zeros(shape)
    ok = (stance >= 0) & (stance < shape[1])
    traj, stance, values = traj[ok], stance[ok], values[ok]
    if reduce == "first":
        order = np.lexsort((np.arange(traj.size), stance, traj))
        t, st, v = traj[order], stance[order], values[order]
        first = np.ones(t.size, bool)
        first[1:] = (t[1:] != t[:-1]) | (st[1:] != st[:-1])
        out[t[first], st[first]] = v[first]
    elif reduce == "sum":
        np.add.at(out, (traj, stance), values)
    else:
        fill = np.full(shape, -np.inf)
        np.maximum.at(fill, (traj, stance), values)
        out = np.where(np.isfinite(fill), fill, np.nan)
    return out


def step_table(rows: Rows, cls: Classifier, max_steps: int, *, backward_rate: float,
               flight_clearance: float) -> Steps:
    """Aggregate the rows into per-step observations of ``max_steps`` steps (vectorised scatter over (trajectory,
    stance)). A trajectory fails at its first row with theta_dot < ``backward_rate`` ("backward") or the lowest
    foot higher than ``flight_clearance`` ("detached"); nothing after that row counts."""
    B, T = rows.theta.shape
    S = max_steps
    shape = (B, S)
    dt = float(np.nanmedian(np.diff(rows.time[0]))) if T > 1 else 1.0
    back = rows.rate < backward_rate
    flew = rows.clearance > flight_clearance
    fail_row = np.where((back | flew).any(axis=1), np.argmax(back | flew, axis=1), T)
    failure = np.where(fail_row < T, np.where(np.take_along_axis(flew, np.minimum(fail_row, T - 1)[:, None],
                                                                 axis=1)[:, 0], "detached", "backward"), "")
    failure_step = np.where(fail_row < T, np.take_along_axis(rows.stance, np.minimum(fail_row, T - 1)[:, None],
                                                             axis=1)[:, 0], -1)
    valid = np.arange(T)[None, :] < fail_row[:, None]
    # mid-stance samples
    values = np.stack([rows.rate, rows.slip, rows.stance.astype(float)], axis=2)
    values = np.where(valid[:, :, None], values, np.nan)
    phi = float(np.nanmax(np.abs(rows.theta))) if np.isfinite(rows.theta).any() else math.pi
    mid = level_crossings(rows.time, np.where(valid, rows.theta, np.nan), values, max_jump=phi)
    st_mid = np.round(mid.values[:, 2]).astype(int) if mid.trajectory.size else np.zeros(0, int)
    mid_rate = _per_stance(mid.values[:, 0], mid.trajectory, st_mid, shape)
    mid_slip = _per_stance(mid.values[:, 1], mid.trajectory, st_mid, shape)
    # post-impact slip: first row at or after the impact window of each stance
    prev_since = np.concatenate([np.full((B, 1), -np.inf), rows.since[:, :-1]], axis=1)
    same = np.concatenate([np.zeros((B, 1), bool), rows.stance[:, 1:] == rows.stance[:, :-1]], axis=1)
    first_after = (rows.since >= cls.impact_window) & (~same | (prev_since < cls.impact_window)) & valid
    tb, kb = np.nonzero(first_after)
    post_slip = _per_stance(rows.slip[tb, kb], tb, rows.stance[tb, kb], shape)
    # impact impulse ratio: force sums over the impact window that starts each stance j >= 1 (ends step j - 1)
    win = (rows.since < cls.impact_window) & (rows.stance > 0) & valid
    tw, kw = np.nonzero(win)
    imp_t = _per_stance(rows.force_t[tw, kw], tw, rows.stance[tw, kw] - 1, shape, "sum")
    imp_n = _per_stance(rows.force_n[tw, kw], tw, rows.stance[tw, kw] - 1, shape, "sum")
    with np.errstate(divide="ignore", invalid="ignore"):
        impulse_ratio = np.where(imp_n > 0, imp_t / imp_n, np.nan)
    # phases: rows per mode (Coulomb classification, and the velocity-only one for comparison)
    slip_rows, stick_rows = _mode_counts(rows.mode, rows.stance, valid, shape)
    vslip_rows, vstick_rows = _mode_counts(rows.vmode, rows.stance, valid, shape)
    runs = phase_runs(rows, valid, dt, cls.merge_phase)
    onset = _onsets(runs, shape)
    # step j is complete when stance j + 1 has its post-impact sample
    post_next = np.concatenate([post_slip[:, 1:], np.full((B, 1), np.nan)], axis=1)
    complete = np.isfinite(post_next) & np.isfinite(post_slip)
    with np.errstate(invalid="ignore"):
        imp_slip = (np.abs(post_next) > cls.v_thr) | (np.abs(impulse_ratio) >= (1 - cls.eps) * cls.mu[:, None])
        vimp_slip = np.abs(post_next) > cls.v_thr
    least = max(1, cls.min_phase_rows)
    dx = post_next - post_slip
    kind = gait_types(complete, imp_slip, slip_rows >= least, stick_rows >= least, dx)
    vkind = gait_types(complete, vimp_slip, vslip_rows >= least, vstick_rows >= least, dx)
    return Steps(mid_rate=mid_rate, mid_slip=mid_slip, post_slip=post_slip, impact_slipping=imp_slip & complete,
                 impulse_ratio=impulse_ratio, slip_rows=slip_rows, stick_rows=stick_rows, onset=onset, kind=kind,
                 complete=complete, failure=failure, failure_step=failure_step, vkind=vkind, runs=runs)


def _mode_counts(mode: np.ndarray, stance: np.ndarray, valid: np.ndarray, shape: tuple[int, int]
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Rows of each stance that slip and that stick (impact-window and air rows not counted)."""
    tr, kr = np.nonzero(valid & (mode != EXCLUDED))
    m, st = mode[tr, kr], stance[tr, kr]
    return (_per_stance((m != STICK).astype(float), tr, st, shape, "sum"),
            _per_stance((m == STICK).astype(float), tr, st, shape, "sum"))


def _onsets(runs: Runs, shape: tuple[int, int]) -> np.ndarray:
    """theta at the start of the last slip phase of each stance, ``shape`` (B, S) (NaN if none)."""
    out = np.full(shape, np.nan)
    slip = (runs.mode != STICK) & (runs.stance < shape[1])
    out[runs.traj[slip], runs.stance[slip]] = runs.theta[slip]  # later runs overwrite earlier ones
    return out


def gait_types(complete: np.ndarray, impact_slips: np.ndarray, has_slip: np.ndarray, has_stick: np.ndarray,
               dx: np.ndarray) -> np.ndarray:
    """Gait type of each step, all (B, S) (002 Sec. 3.3): A / B sticking impact without / with slip; C / D slipping
    impact with / without a stick phase, D+ / D- by the sign of the change ``dx`` of the post-impact slip speed;
    "" where the step is not complete."""
    kind = np.full(complete.shape, "", dtype=object)
    kind[complete & ~impact_slips & ~has_slip] = "A"
    kind[complete & ~impact_slips & has_slip] = "B"
    kind[complete & impact_slips & has_stick] = "C"
    kind[complete & impact_slips & ~has_stick & (dx > 0)] = "D+"
    kind[complete & impact_slips & ~has_stick & ~(dx > 0)] = "D-"
    return kind.astype(str)


def outcome(steps: Steps, b: int, velocity_only: bool = False) -> str:
    """Settled outcome of trajectory ``b``: its failure, else the type of its last complete step ("" if none);
    ``velocity_only``: the type from the foot's speed alone."""
    if steps.failure[b]:
        return str(steps.failure[b])
    done = np.nonzero(steps.complete[b])[0]
    kinds = steps.vkind if velocity_only else steps.kind
    return str(kinds[b, done[-1]]) if done.size else ""


def settled_steps(steps: Steps, b: int, count: int) -> np.ndarray:
    """Indices of the last ``count`` complete steps of trajectory ``b`` before its failure, if any (at most the
    second half of the steps it completed: a run cut short by a flight has few settled steps)."""
    done = np.nonzero(steps.complete[b])[0]
    if steps.failure[b]:
        done = done[done < steps.failure_step[b]]
    return done[-min(count, (done.size + 1) // 2):] if done.size else done


def settled_rows(rows: Rows, steps: Steps, trajectories: Sequence[int], kind: str, count: int) -> np.ndarray:
    """(B, T) mask of the contact rows (impact windows and air left out) of the settled steps (:func:`settled_steps`
    with ``count``) of ``trajectories`` that are of type ``kind``."""
    mask = np.zeros(rows.mode.shape, bool)
    for b in trajectories:
        js = [int(j) for j in settled_steps(steps, int(b), count) if steps.kind[b, j] == kind]
        mask[b] = np.isin(rows.stance[b], js)
    return mask & (rows.mode != EXCLUDED)


def midstance_pairs(steps: Steps, trajectories: Sequence[int], kind: str, max_pairs: int
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Consecutive mid-stance rates (theta_dot_k, theta_dot_k+1), each (N, 1), of ``trajectories``: at most the
    first ``max_pairs`` per trajectory whose two steps are of type ``kind`` and precede any failure (a perturbed
    start may pass through another type first, e.g. D- on the way to C, where the mid-stance map is not a function
    of theta_dot alone)."""
    xs, ys = [], []
    for b in trajectories:
        last = steps.failure_step[b] if steps.failure[b] else steps.kind.shape[1]
        rate, kinds = steps.mid_rate[b, :last], steps.kind[b, :last]
        x, y = sample_pairs([np.where((kinds == kind) & np.isfinite(rate), rate, np.nan)])
        xs.append(x[:max_pairs])
        ys.append(y[:max_pairs])
    return np.concatenate(xs), np.concatenate(ys)


def fit_midstance_map(steps: Steps, trajectories: Sequence[int], kind: str, max_pairs: int, seed: int
                      ) -> tuple[ReturnMapFit, np.ndarray, np.ndarray]:
    """Quadratic fit of the mid-stance map theta_dot_k -> theta_dot_k+1 (002 Sec. 3.3) from the pairs of
    :func:`midstance_pairs`; returns the fit and the pairs (N,), (N,)."""
    x, y = midstance_pairs(steps, trajectories, kind, max_pairs)
    return fit_return_map(x, y, degree=2, seed=seed), x[:, 0], y[:, 0]


def steps_to_converge(mid_rate: np.ndarray, kinds: np.ndarray, final_kind: str, tol: float) -> int:
    """First step after which every mid-stance rate of ``mid_rate`` (S,) is within ``tol`` (relative) of the last one
    and every step of ``kinds`` (S,) has the final type (-1 if never). The same rule applies to the reference's
    steps, so the counts compare."""
    finite = np.nonzero(np.isfinite(mid_rate))[0]
    if finite.size < 2 or not final_kind:
        return -1
    last = mid_rate[finite[-1]]
    ok = (np.abs(mid_rate - last) <= tol * abs(last)) & (kinds == final_kind)
    ok = ok[: finite[-1] + 1]
    bad = np.nonzero(~ok)[0]
    return int(bad[-1] + 1) if bad.size else 0


def creep(rows: Rows, steps: Steps) -> dict[str, float]:
    """|x_dot| (nondimensional) of the stance foot over the stick rows of trajectories that did not fail: median,
    99th percentile and maximum (NaN if there are none)."""
    ok = (steps.failure == "")[:, None] & (rows.mode == STICK)
    v = np.abs(rows.slip[ok])
    if v.size == 0:
        return {"median": math.nan, "p99": math.nan, "max": math.nan}
    return {"median": float(np.median(v)), "p99": float(np.percentile(v, 99)), "max": float(v.max())}


def step_report(steps: Steps, b: int, reference_kinds: np.ndarray, reference_mid_rate: np.ndarray
                ) -> list[dict[str, Any]]:
    """The complete steps of trajectory ``b`` as records: the measured type, mid-stance values, phases, impact and
    slip onset beside the reference's type and mid-stance rate of the same step (``reference_kinds``,
    ``reference_mid_rate``: (S,) from the same start; "" / NaN past their end)."""
    table = []
    for j in np.nonzero(steps.complete[b])[0]:
        ph, ang = phase_sequence(steps.runs, b, int(j))
        table.append({"step": int(j) + 1, "kind": str(steps.kind[b, j]),
                      "reference_kind": str(reference_kinds[j]) if j < reference_kinds.size else "",
                      "mid_rate": steps.mid_rate[b, j],
                      "reference_mid_rate": float(reference_mid_rate[j]) if j < reference_mid_rate.size else math.nan,
                      "mid_slip": steps.mid_slip[b, j], "phases": list(ph), "phase_angles": list(ang),
                      "impact": "slipping" if steps.impact_slipping[b, j] else "sticking",
                      "impulse_ratio": steps.impulse_ratio[b, j], "slip_onset": steps.onset[b, j]})
    return table
