"""Scenario ``rimless-wheel-friction``: the planar rimless wheel with Coulomb friction, stick-slip gaits A-D.

Analytic reference: Gamus & Or (2015), Sec. 3 and Appendix A, through the exact event-driven hybrid simulator of
:mod:`mjpoincare.analysis.theory.rimless_wheel_friction` (sticking map eq 12-17, force ratio and mu_c eq 19-23, sticking
impulse ratio eq 25, slip dynamics eq 42, frictional impacts eq 43-45 as corrected there, regions of attraction
eq 26 / Fig. 3.8). Gait types (002 Sec. 3.3): A sticking impact and stick throughout; B sticking impact, stick ->
slip; C slipping impact, slip -> stick -> slip; D slipping impact and forward slip throughout (D+ / D-: the slip
speed grows / shrinks each step; D- is a transient).

Model: the planar wheel of :mod:`mjpoincare.scenarios.rimless_wheel` (``models/rimless_wheel_2d.xml``, slope by
tilted gravity), rebuilt by its ``build`` with the hub's radius of gyration sqrt(kappa) l and friction ``mu`` on
both the feet and the floor (MuJoCo combines friction by the element-wise max: the floor's default would cap mu).

Measurement, all vectorised on the recorded states (no Python between MuJoCo steps):

* **Mid-stance section** theta = 0 (wrapped hinge angle crossing 0 upward): theta_dot and the stance foot's slip
  speed x_dot, far from the soft impact.
* **Contact force ratio** f_t/f_n of the stance foot from the hub's recorded acceleration (the spokes are massless,
  so m (a_hub - g) is the total contact force; a window of a few steps averages it).
* **Phases**: a stance row slips (slip+ / slip-) when its friction force is on the cone's edge,
  |f_t| >= (1 - eps) mu f_n over a 1 ms window (Coulomb: a sliding contact has saturated friction), in the
  direction the friction opposes; otherwise it sticks. The foot's speed against ``v_thr`` (well above MuJoCo's
  creep while stuck, measured per preset, see ``WHY``) gives the velocity-only classification that the results
  report beside it: it cannot see the slips near the A/B edge, whose speed stays below the creep.
* **Impacts**: the support transfer (wrap of the hinge angle) and an impact window of four of the contact's slow
  time constants after it; the impact is *slipping* when the new foot's speed just after the window exceeds
  ``v_thr`` or the impulse ratio over the window is on the cone's edge.

All rates are reported nondimensionally (002's units, m = l = 1, omega_c = sqrt(g/(l(1+kappa))) = 1).
The friction sweep and the regions of attraction are in :mod:`mjpoincare.scenarios.rimless_wheel_friction_sweep`
and :mod:`mjpoincare.scenarios.rimless_wheel_friction_basins`; they reuse this module's measurement.
"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import mujoco
import numpy as np

from mjpoincare.analysis import checks
from mjpoincare.analysis.returnmap import fit_return_map, sample_pairs
from mjpoincare.analysis.sections import level_crossings, wrap_phase
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.mjlog import captured_mujoco_log
from mjpoincare.params import Param, ParameterError
from mjpoincare.scenarios import rimless_wheel as rw
from mjpoincare.scenarios.base import Evaluation, Scenario, Soak, StressCase, Values
from mjpoincare.settings import rollout_options
from mjpoincare.simulate import Chunk, RolloutReport, event_rollout

PAPER_SLOPE = math.radians(13.0)

PARAMS: tuple[Param, ...] = (
    Param("spokes", 10, "number of spokes n (phi = pi/n)", int, 3, 64),
    Param("kappa", 1.0 / 3.0, "hub inertia kappa = I_c/(m l^2) (002 eq 11; slip needs kappa > 0)", float, 0.0, 1.0),
    Param("slope", PAPER_SLOPE, "slope alpha, rad (paper: 13 deg)", float, 0.0, math.pi / 2, True, True),
    Param("mu", 0.3, "Coulomb friction coefficient, static = kinetic (paper's stick-slip case 0.3: Type B)", float,
          0.0, 1e3),
    Param("leg_length", 1.0, "spoke length l, m", float, 0.0, 100.0, low_open=True),
    Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, low_open=True),
)

#: Contact: the stiffest time constant MuJoCo allows (2 steps) and damping ratio 3. Measured (paper set, A gait at
#: mu = 2, mid-stance theta_dot): damping ratio 1 makes the wheel hop after every impact (6 mm high, 35-55 % of the
#: time in flight) and biases the rate by -1.3 % to -3.4 % (tc = 2 dt) or +0.5 % (tc = 10 dt); ratio 3 removes the
#: flight and leaves +0.06 % to +0.1 % (the 0.5 mm foot's rolling predicts +0.06 %). A longer time constant both
#: raises the creep while stuck (proportional to it) and delays the normal force (slow pole 2 tc dampratio^2).
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 2e-4, "solref_timeconst": 4e-4, "solref_dampratio": 3.0, "integrator": "implicitfast",
             "cone": "elliptic"},
    "accurate": {"timestep": 5e-5, "solref_timeconst": 1e-4, "solref_dampratio": 3.0, "integrator": "implicitfast",
                 "cone": "elliptic"},
    "coarse": {"timestep": 4e-4, "solref_timeconst": 8e-4, "solref_dampratio": 3.0, "integrator": "implicitfast",
               "cone": "elliptic"},
}

#: Speed (nondimensional, units l omega_c) above which the stance foot moves: impacts and the velocity-only
#: classification. Measured creep of stuck feet (|x_dot| over the stick rows, paper set): fast median 1e-4, 99th
#: percentile 1.1e-3; accurate 2.5e-5 / 2.9e-4; coarse 1.9e-4 / 2.3e-3.
V_THRESHOLD: dict[str, float] = {"fast": 5e-3, "accurate": 2e-3, "coarse": 1e-2}
SATURATION_EPS = 5e-3  # friction on the cone: |f_t/f_n| >= (1 - eps) mu (a slipping row reads mu to 4 digits)
TOLERANCES: dict[str, dict[str, float]] = {
    "fast": {"midstance_rate": 5e-3, "eigenvalue": 0.02, "dx_per_step": 0.1, "slip_onset": 0.02,
             "critical_friction": 0.02},
    "accurate": {"midstance_rate": 2e-3, "eigenvalue": 0.02, "dx_per_step": 0.1, "slip_onset": 0.02,
                 "critical_friction": 0.02},
}
WHY: dict[str, str] = {
    "midstance_rate": "theta_dot at mid-stance (002 Sec. 3.3); measured 0.8-1.5e-3 (fast) and 0.2-1.3e-3 (accurate) "
                      "for A, B, C: the 0.5 mm foot's rolling alone gives +6e-4, the rest grows with the contact time "
                      "constant",
    "eigenvalue": "multiplier of a quadratic fit of the mid-stance map theta_dot_k -> theta_dot_k+1 (a conjugate "
                  "of the post-impact map, 002 eq 17 / Sec. 3.3; C: lambda_max, its other multiplier is 0); issue "
                  "target 0.02",
    "dx_per_step": "change of the slip speed per step of a D gait (002 Sec. 3.3, Fig. 3.6), from mid-stance x_dot; "
                   "relative, 10 % as reference card 002 Sec. 5 suggests for small slip speeds",
    "slip_onset": "theta where the last slip phase of a B step starts (friction reaches the cone, 002 eq 22), "
                  "0.02 rad as the reference card suggests",
    "critical_friction": "max |f_t/f_n| along the settled A stances of the fitting starts (impulses binned by 2 mrad "
                         "of theta, the ends extrapolated to -+phi) against mu_c (002 eq 23); the issue's 2 %",
    "v_thr": "foot speed above which it moves: 20-75x the median creep of a stuck foot, 2-7x its 99th percentile "
             "(MuJoCo's regularised friction; the creep is independent of impratio 1-1000, noslip 0-3 and the cone, "
             "and grows with the contact time constant)",
}

FIT_OFFSETS = (-0.12, -0.06, 0.0, 0.06, 0.12)  # relative offsets of theta_dot0 around the gait's post-impact state
FIT_PAIRS = 12  # mid-stance pairs per fitting trajectory (beta^24 of the offset remains: near the fixed point)
SIM_STEPS = 30  # steps simulated per trajectory (the slowest reference transient settles to 1e-3 within ~25)
#: x_dot0 of the slipping start checked for its settled type (a D- transient at mu = 0.3). A sliding foot lifts off at
#: normal speed mu x_dot in MuJoCo (measured): 0.05 keeps that lift at 0.2 mm; 0.3 flies 6 mm (see the README).
SLIP_START = 0.05
#: x_dot0 of starts on a Type D gait (its theta_dot map does not depend on x_dot > 0). Small, because the slip speed
#: of D+ grows every step and MuJoCo's sliding foot lifts off at mu x_dot (measured): 0.1 flies after 1-6 steps.
D_START_SLIP = 0.02
D_SIM_STEPS = 12  # D gaits: theta_dot converges within ~5 steps (lambda ~ 0.34) and the slip speed keeps growing
SETTLED_STEPS = 5  # the last steps of a run compared with the reference gait
IMPACT_WINDOW_TC = 5.0  # the impact window is at least this many contact time constants
RATIO_WINDOW_S = 1e-3  # force ratio: impulses over a centred window of this length (s), averaging chatter
MIN_PHASE_STEPS = 2  # a step has a stick (slip) phase when at least this many rows stick (slip)
MERGE_PHASE_S = 1e-3  # phases shorter than this (s) are merged into the one before: stick-slip flicker at an onset
BACKWARD_RATE = -0.01  # nondimensional theta_dot below which the wheel rolls back
#: Lowest foot this high (x leg_length) = flight ("detached"). MuJoCo's convex contact lifts a slipping foot by up to
#: 0.6 mm below the reference's detachment edge (measured, mu = 0.3); above the edge the flight exceeds 3 mm within
#: 0.02 of theta_dot0.
FLIGHT_CLEARANCE = 1e-3
MU_NO_SLIP = 10.0  # "unbounded" friction in simulation: far above mu_c; the reference uses the same finite mu


# --- model and units ----------------------------------------------------------------------------------------------


def friction_wheel(p: Values) -> theory.FrictionWheel:
    """The nondimensional reference wheel (002 eq 11)."""
    return theory.FrictionWheel(int(p["spokes"]), float(p["kappa"]), float(p["slope"]), float(p["mu"]))


def rate_unit(p: Values) -> float:
    """omega_c = sqrt(g/(l(1+kappa))), 1/s: theta_dot_SI = theta_dot omega_c, x_dot_SI = x_dot l omega_c."""
    return theory.omega_c(float(p["leg_length"]), float(p["gravity"]), float(p["kappa"]))


def rigid_params(p: Values) -> dict[str, float | int]:
    """Parameters of :mod:`mjpoincare.scenarios.rimless_wheel` for the same wheel (hub mass 1 kg, gyration
    sqrt(kappa) l, the same mu on feet and floor)."""
    l = float(p["leg_length"])
    return {"spokes": int(p["spokes"]), "slope": float(p["slope"]), "leg_length": l, "mass": 1.0,
            "gyration": math.sqrt(float(p["kappa"])) * l, "mu": float(p["mu"]), "gravity": float(p["gravity"])}


@lru_cache(maxsize=64)
def attractors(w: theory.FrictionWheel) -> tuple[theory.Gait, ...]:
    return theory.attractors(w)


@lru_cache(maxsize=16)
def cached_boundaries(kappa: float, spokes: int, slope: float) -> theory.GaitBoundaries:
    return theory.gait_boundaries(kappa, spokes, slope)


def check_params(p: Values) -> None:
    """Refuse what the theory excludes (002 Sec. 3, eqs 18/21; Appendix A): the theory's own validation, kappa > 0
    (slip needs hub inertia: eq 42 gives f_n = 0 at kappa = 0; MuJoCo's pitch needs inertia too) and a mu with a
    stable gait (below the D branch the wheel rolls back)."""
    w = friction_wheel(p)
    try:
        theory.validate(w)
    except ValueError as err:
        raise ParameterError(str(err)) from None
    low = rw.MIN_GYRATION**2
    if w.kappa < low:
        raise ParameterError(
            f"kappa must be in [{low:g}, 1] (got {w.kappa:g}): slipping needs hub inertia (002 eq 42: f_n = "
            f"kappa (...)/D vanishes at kappa = 0) and MuJoCo's pitch joint needs it (see rimless-wheel)")
    if not attractors(w):
        edges = cached_boundaries(w.kappa, w.spokes, w.slope)
        if math.isfinite(edges.d_lower) and w.mu < edges.d_lower:
            raise ParameterError(
                f"mu must be >= {edges.d_lower:.4f} for spokes={w.spokes}, kappa={w.kappa:g}, slope={w.slope:g} (got "
                f"{w.mu:g}): below the Type D branch no stable gait exists and the wheel rolls back (002 Sec. 3.3)")
        raise ParameterError(
            f"mu={w.mu:g} has no stable gait of types A-D+ for spokes={w.spokes}, kappa={w.kappa:g}, "
            f"slope={w.slope:g} (the reference finds none; 002 Sec. 3.3): choose another mu or kappa")


def build(p: Values, s: Values) -> mujoco.MjModel:
    """The rimless wheel of ``rimless-wheel`` (same MJCF and MjSpec rebuild) with gyration sqrt(kappa) l and mu."""
    return rw.build(rigid_params(p), s)


def start_states(model: mujoco.MjModel, p: Values, s: Values, starts: np.ndarray) -> np.ndarray:
    """Full-physics states just after an impact for nondimensional post-impact states ``starts`` (B, 2) =
    (theta_dot0, x_dot0) of 002 (x_dot0: slip speed of the new stance tip)."""
    unit, l = rate_unit(p), float(p["leg_length"])
    w = rw.wheel(rigid_params(p))
    return rw.post_impact_states(model, w, starts[:, 0] * unit, float(s["foot_radius"]), starts[:, 1] * l * unit)


def with_friction(model: mujoco.MjModel, mu: float) -> mujoco.MjModel:
    """A copy of ``model`` whose feet and floor have friction ``mu`` (one model per trajectory in a batch)."""
    out = copy.copy(model)
    out.geom_friction[:, 0] = mu
    return out


# --- simulation -------------------------------------------------------------------------------------------------


@dataclass
class Recorded:
    """Recorded states of a batch: ``time`` (B, T), ``qpos`` and ``qvel`` (B, T, 3)."""

    time: np.ndarray
    qpos: np.ndarray
    qvel: np.ndarray
    report: RolloutReport


def simulate(models: Sequence[mujoco.MjModel], state0: np.ndarray, seconds: float, s: Values) -> Recorded:
    """Roll every initial state out for ``seconds`` (one :func:`mujoco.rollout` batch, a model per trajectory, native
    chunks of 0.5 s) and keep every recorded row."""
    dt = models[0].opt.timestep
    nstep = max(1, math.ceil(seconds / dt))
    chunk = math.ceil(nstep / math.ceil(nstep / max(1, round(0.5 / dt))))  # equal chunks of <= 0.5 s: no overshoot
    parts: list[Chunk] = []

    def keep(c: Chunk, _models: list[mujoco.MjModel]) -> np.ndarray:
        parts.append(c if not parts else Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]))
        return np.full(c.time.shape[0], chunk)

    report = event_rollout(list(models), state0, nstep, keep, chunk_steps=chunk, **rollout_options(s))
    time_ = np.concatenate([c.time for c in parts], axis=1)[:, : nstep + 1]
    qpos = np.concatenate([c.qpos for c in parts], axis=1)[:, : nstep + 1]
    qvel = np.concatenate([c.qvel for c in parts], axis=1)[:, : nstep + 1]
    return Recorded(time_, qpos, qvel, report)


# --- measurement on the recorded rows ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Classifier:
    """Thresholds of the stick/slip classification (nondimensional speeds, times in s)."""

    mu: np.ndarray  # (B,) friction of each trajectory
    v_thr: float
    eps: float
    impact_window: float


def classifier(mu: np.ndarray | float, s: Values, preset: str, batch: int) -> Classifier:
    """Thresholds for ``preset``: ``V_THRESHOLD``; the impact window, four of the contact's slow time constants
    2 tc dampratio^2. The soft impact leaves the new foot 0.2-0.3 mm deep (fast preset); that penetration relaxes at
    the slow rate and meanwhile the normal force lags the rigid one (zero for 1-6 ms, then ramping up): measured at
    mu = 0.3 (where the theory holds the post-impact force 15 % inside the cone), the friction stays on the cone, at
    creep speed, for up to 17 ms (2.3 slow time constants) after 12-25 % of the sticking impacts. At least
    IMPACT_WINDOW_TC time constants."""
    dt = float(s["timestep"])
    tc = max(float(s["solref_timeconst"]), 2 * dt)
    window = max(IMPACT_WINDOW_TC * tc, 8 * tc * float(s["solref_dampratio"]) ** 2, 3 * dt)
    return Classifier(np.broadcast_to(np.asarray(mu, float), (batch,)).copy(),
                      V_THRESHOLD.get(preset, V_THRESHOLD["fast"]), SATURATION_EPS, window)


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
    force_t: np.ndarray  # contact force per unit mass along the slope (raw, per step)
    force_n: np.ndarray  # and normal to it
    stance: np.ndarray
    since: np.ndarray
    wrap: np.ndarray  # (B, T) True at the last row before a forward support transfer
    mode: np.ndarray
    vmode: np.ndarray  # the same from the foot's speed alone (|x_dot| > v_thr), for comparison


STICK, SLIP_POS, SLIP_NEG, EXCLUDED = 0, 1, 2, 3
MODE_NAMES = ("stick", "slip+", "slip-")


def _window_sum(x: np.ndarray, width: int) -> np.ndarray:
    """Centred moving sum over ``width`` rows along axis 1 (edges use what exists)."""
    if width <= 1:
        return x.copy()
    c = np.concatenate([np.zeros((x.shape[0], 1)), np.cumsum(x, axis=1)], axis=1)
    n = x.shape[1]
    lo = np.clip(np.arange(n) - width // 2, 0, n)
    hi = np.clip(lo + width, 0, n)
    return c[:, hi] - c[:, lo]


def row_signals(rec: Recorded, p: Values, s: Values, cls: Classifier, gravity: np.ndarray) -> Rows:
    """The per-row signals of :class:`Rows`, vectorised over the batch. ``gravity`` is the model's (slope-frame)
    gravity vector; the contact force per unit mass is a_hub - g from the recorded velocities (exact for
    Euler/implicitfast: v_k+1 = v_k + dt a_k)."""
    phi = math.pi / int(p["spokes"])
    l, unit = float(p["leg_length"]), rate_unit(p)
    r = float(s["foot_radius"])
    dt = float(s["timestep"])
    theta = wrap_phase(rec.qpos[:, :, 2], phi)
    omega = rec.qvel[:, :, 2]
    slip = (rec.qvel[:, :, 0] - omega * ((l - r) * np.cos(theta) + r)) / (l * unit)
    clearance = (rec.qpos[:, :, 1] - (l - r) * np.cos(theta) - r) / l
    acc = np.diff(rec.qvel, axis=1) / dt
    f_t = np.concatenate([acc[:, :, 0] - gravity[0], np.zeros((acc.shape[0], 1))], axis=1)
    f_n = np.concatenate([acc[:, :, 1] - gravity[2], np.zeros((acc.shape[0], 1))], axis=1)
    jump = theta[:, 1:] - theta[:, :-1]
    forward = np.concatenate([jump < -phi, np.zeros((theta.shape[0], 1), bool)], axis=1)
    stance = np.concatenate([np.zeros((theta.shape[0], 1), int), np.cumsum(forward[:, :-1], axis=1)], axis=1)
    cols = np.arange(theta.shape[1])[None, :]
    last = np.maximum.accumulate(np.where(np.roll(forward, 1, axis=1) & (cols > 0), cols, 0), axis=1)
    since = rec.time - np.take_along_axis(rec.time, last, axis=1)
    # window sums of the stance force: the impact-window rows are left out, so a window that reaches across a
    # support transfer holds only the stance foot's force (the impulse at the transfer is the next row's)
    # the row before a transfer is part of the impact too: the new foot can touch a fraction of a step before the
    # geometric transfer (the old foot sits in its own penetration), and that row's force is then the impulse
    impact = (since < cls.impact_window) | forward
    width = max(1, round(RATIO_WINDOW_S / dt))
    st = _window_sum(np.where(impact, 0.0, np.nan_to_num(f_t)), width)
    sn = _window_sum(np.where(impact, 0.0, np.nan_to_num(f_n)), width)
    contact = sn > 1e-3 * abs(float(gravity[2])) * width
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(contact, st / sn, np.nan)
    mu = cls.mu[:, None]
    sat_pos = ratio <= -(1 - cls.eps) * mu
    sat_neg = ratio >= (1 - cls.eps) * mu
    # Coulomb: a contact slips when its friction is on the cone (the direction is the one friction opposes)
    mode = np.full(theta.shape, STICK, np.int8)
    mode[sat_pos] = SLIP_POS
    mode[sat_neg] = SLIP_NEG
    # off contact (the foot in the air: a hop, or MuJoCo's lift of a sliding foot) a row is neither stick nor slip
    off = impact | ~contact | ~np.isfinite(theta)
    mode[off] = EXCLUDED
    # the velocity-only classification, for comparison: the foot's speed against v_thr
    vmode = np.full(theta.shape, STICK, np.int8)
    vmode[slip > cls.v_thr] = SLIP_POS
    vmode[slip < -cls.v_thr] = SLIP_NEG
    vmode[off] = EXCLUDED
    return Rows(rec.time, theta, omega / unit, slip, clearance, ratio, f_t, f_n, stance, since, forward, mode,
                vmode)


@dataclass
class Steps:
    """Per-step observations of a batch, arrays (B, S) over step index j (stance j and the impact ending it);
    NaN / -1 / False where a trajectory has no such complete step.

    ``mid_rate``/``mid_slip`` theta_dot and x_dot at mid-stance; ``post_slip`` x_dot just after the impact that
    starts stance j (j = 0: after the first impact window of the initial state); ``impact_slipping`` whether the
    impact ending step j slips; ``impulse_ratio`` F~_t/F~_n of that impact; ``slip_rows``/``stick_rows`` steps in
    each mode; ``onset`` theta at the start of the last slip phase; ``kind`` gait type of the step ("A", "B", "C",
    "D+", "D-", "" unknown); ``complete`` the step's impact and the next post-impact speed were recorded;
    ``failure`` per trajectory: "", "backward" or "detached", with ``failure_step``."""

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
    """Scatter ``values`` at (traj, stance) into a (B, S) array: the first value, their sum or max."""
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


def step_table(rows: Rows, cls: Classifier, max_steps: int) -> Steps:
    """Aggregate the rows into per-step observations (vectorised scatter over (trajectory, stance))."""
    B, T = rows.theta.shape
    S = max_steps
    shape = (B, S)
    dt = float(np.nanmedian(np.diff(rows.time[0]))) if T > 1 else 1.0
    # failures: rolling back (theta_dot < 0) or flight (the lowest foot clear of the ground)
    back = rows.rate < BACKWARD_RATE
    flew = rows.clearance > FLIGHT_CLEARANCE
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
    runs = phase_runs(rows, valid, dt)
    onset = _onsets(runs, shape)
    # step j is complete when stance j + 1 has its post-impact sample
    post_next = np.concatenate([post_slip[:, 1:], np.full((B, 1), np.nan)], axis=1)
    complete = np.isfinite(post_next) & np.isfinite(post_slip)
    with np.errstate(invalid="ignore"):
        imp_slip = (np.abs(post_next) > cls.v_thr) | (np.abs(impulse_ratio) >= (1 - cls.eps) * cls.mu[:, None])
        vimp_slip = np.abs(post_next) > cls.v_thr
    least = max(1, MIN_PHASE_STEPS)
    dx = post_next - post_slip
    kind = _kinds(complete, imp_slip, slip_rows >= least, stick_rows >= least, dx)
    vkind = _kinds(complete, vimp_slip, vslip_rows >= least, vstick_rows >= least, dx)
    return Steps(mid_rate, mid_slip, post_slip, imp_slip & complete, impulse_ratio, slip_rows, stick_rows, onset,
                 kind, complete, failure, failure_step, vkind, runs)


def _mode_counts(mode: np.ndarray, stance: np.ndarray, valid: np.ndarray, shape: tuple[int, int]
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Rows of each stance that slip and that stick (impact-window and air rows not counted)."""
    tr, kr = np.nonzero(valid & (mode != EXCLUDED))
    m, st = mode[tr, kr], stance[tr, kr]
    return (_per_stance((m != STICK).astype(float), tr, st, shape, "sum"),
            _per_stance((m == STICK).astype(float), tr, st, shape, "sum"))


def _kinds(complete: np.ndarray, impact_slips: np.ndarray, has_slip: np.ndarray, has_stick: np.ndarray,
           dx: np.ndarray) -> np.ndarray:
    """Gait type of each step (002 Sec. 3.3): A / B sticking impact without / with slip; C / D slipping impact with /
    without a stick phase, D+ / D- by the sign of the change of the post-impact slip speed."""
    kind = np.full(complete.shape, "", dtype=object)
    kind[complete & ~impact_slips & ~has_slip] = "A"
    kind[complete & ~impact_slips & has_slip] = "B"
    kind[complete & impact_slips & has_stick] = "C"
    kind[complete & impact_slips & ~has_stick & (dx > 0)] = "D+"
    kind[complete & impact_slips & ~has_stick & ~(dx > 0)] = "D-"
    return kind.astype(str)


def ratio_profile(rows: Rows, select: np.ndarray, phi: float, width: float = 2e-3) -> tuple[np.ndarray, np.ndarray]:
    """The stance force ratio f_t/f_n against theta, pooled over the rows ``select`` (B, T) (impact windows left
    out): impulse sums per bin of ``width`` rad, which average MuJoCo's contact chatter. Returns (bin centres,
    ratios), NaN where a bin has fewer than 3 rows or almost no normal force (the pulses of a chattering contact fell
    into its neighbours: less than 5 % of the typical normal force)."""
    sel = select & (rows.mode != EXCLUDED)
    edges = np.arange(-phi, phi + 0.5 * width, width)
    idx = np.clip(np.digitize(rows.theta[sel], edges) - 1, 0, edges.size - 2)
    ft = np.bincount(idx, rows.force_t[sel], minlength=edges.size - 1)
    fn = np.bincount(idx, rows.force_n[sel], minlength=edges.size - 1)
    count = np.bincount(idx, minlength=edges.size - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean_n = np.where(count >= 3, fn / count, np.nan)
        held = np.nan_to_num(mean_n) > 0.05 * (np.nanmedian(mean_n) if np.isfinite(mean_n).any() else np.inf)
        ratio = np.where(held, ft / fn, np.nan)
    return 0.5 * (edges[1:] + edges[:-1]), ratio


def critical_ratio(centres: np.ndarray, ratio: np.ndarray, phi: float, span: float = 0.02) -> float:
    """max |f_t/f_n| along the stance (002 eq 23 takes it over [-phi, phi]; for the paper set it sits at +phi): the
    measured bins, and each end extrapolated to -+phi by a quadratic through the last ``span`` rad of bins where the
    end is within a quarter span of a bin (never across an impact window)."""
    ok = np.isfinite(ratio)
    if ok.sum() < 6:
        return math.nan
    c, r = centres[ok], ratio[ok]
    best = float(np.max(np.abs(r)))
    for end, near in ((phi, c >= c.max() - span), (-phi, c <= c.min() + span)):
        gap = abs(end - c[near][np.argmin(np.abs(c[near] - end))]) if near.any() else math.inf
        if near.sum() >= 4 and gap <= 0.25 * span:
            best = max(best, abs(float(np.polyval(np.polyfit(c[near], r[near], 2), end))))
    return best


def settled_rows(rows: Rows, steps: Steps, trajectories: Sequence[int], kind: str) -> np.ndarray:
    """(B, T) mask of the rows of the settled steps (:func:`_settled`) of ``trajectories`` that are of type ``kind``."""
    mask = np.zeros(rows.mode.shape, bool)
    for b in trajectories:
        js = [int(j) for j in _settled(steps, int(b)) if steps.kind[b, j] == kind]
        mask[b] = np.isin(rows.stance[b], js)
    return mask


@dataclass(frozen=True)
class Runs:
    """Stick/slip phases as runs of rows (impact-window and air rows left out), runs shorter than ``MERGE_PHASE_S``
    absorbed into the phase before them (into the next one at the start of a stance): ``traj``, ``stance``,
    ``mode``, ``first`` row index and ``theta`` at the run's start, in time order."""

    traj: np.ndarray
    stance: np.ndarray
    mode: np.ndarray
    first: np.ndarray
    theta: np.ndarray


def _run_starts(traj: np.ndarray, stance: np.ndarray, mode: np.ndarray) -> np.ndarray:
    new = np.ones(traj.size, bool)
    new[1:] = (traj[1:] != traj[:-1]) | (stance[1:] != stance[:-1]) | (mode[1:] != mode[:-1])
    return np.nonzero(new)[0]


def phase_runs(rows: Rows, valid: np.ndarray, dt: float) -> Runs:
    """The merged phase runs of every stance (vectorised; two merging passes)."""
    tr, kr = np.nonzero(valid & (rows.mode != EXCLUDED))
    stance, mode = rows.stance[tr, kr], rows.mode[tr, kr].astype(int)
    shortest = max(1, round(MERGE_PHASE_S / dt))
    for _ in range(2):
        if tr.size == 0:
            break
        starts = _run_starts(tr, stance, mode)
        lengths = np.diff(np.append(starts, tr.size))
        run_mode = mode[starts]
        same_prev = np.zeros(starts.size, bool)
        same_prev[1:] = (tr[starts[1:]] == tr[starts[:-1]]) & (stance[starts[1:]] == stance[starts[:-1]])
        same_next = np.append(same_prev[1:], False)
        short = lengths < shortest
        new_mode = run_mode.copy()
        prev_mode = np.roll(run_mode, 1)
        next_mode = np.roll(run_mode, -1)
        new_mode[short & same_prev] = prev_mode[short & same_prev]
        first_short = short & ~same_prev & same_next
        new_mode[first_short] = next_mode[first_short]
        mode = np.repeat(new_mode, lengths)
    starts = _run_starts(tr, stance, mode) if tr.size else np.zeros(0, int)
    return Runs(tr[starts], stance[starts], mode[starts], kr[starts], rows.theta[tr[starts], kr[starts]])


def _onsets(runs: Runs, shape: tuple[int, int]) -> np.ndarray:
    """theta at the start of the last slip phase of each stance (NaN if none)."""
    out = np.full(shape, np.nan)
    slip = (runs.mode != STICK) & (runs.stance < shape[1])
    out[runs.traj[slip], runs.stance[slip]] = runs.theta[slip]  # later runs overwrite earlier ones
    return out


def phase_sequence(runs: Runs, b: int, j: int) -> tuple[tuple[str, ...], tuple[float, ...]]:
    """The stick/slip phases of stance ``j`` of trajectory ``b`` and the theta at their starts."""
    sel = (runs.traj == b) & (runs.stance == j)
    return (tuple(MODE_NAMES[int(m)] for m in runs.mode[sel]), tuple(float(x) for x in runs.theta[sel]))


def outcome(steps: Steps, b: int, velocity_only: bool = False) -> str:
    """Settled outcome of trajectory ``b``: its failure, else the type of its last complete step ("" if none);
    ``velocity_only``: the type from the foot's speed alone."""
    if steps.failure[b]:
        return str(steps.failure[b])
    done = np.nonzero(steps.complete[b])[0]
    kinds = steps.vkind if velocity_only else steps.kind
    return str(kinds[b, done[-1]]) if done.size else ""


def steps_to_converge(mid_rate: np.ndarray, kinds: np.ndarray, final_kind: str, tol: float) -> int:
    """First step after which every mid-stance rate is within ``tol`` (relative) of the last one and every step has
    the final type (-1 if never). The same rule is applied to the reference's steps, so the counts compare."""
    finite = np.nonzero(np.isfinite(mid_rate))[0]
    if finite.size < 2 or not final_kind:
        return -1
    last = mid_rate[finite[-1]]
    ok = (np.abs(mid_rate - last) <= tol * abs(last)) & (kinds == final_kind)
    ok = ok[: finite[-1] + 1]
    bad = np.nonzero(~ok)[0]
    return int(bad[-1] + 1) if bad.size else 0


# --- the reference ------------------------------------------------------------------------------------------------


def reference_gait(w: theory.FrictionWheel) -> theory.Gait:
    """The stable gait this mu settles on (002 Sec. 3.3; at most one of A, B, C, D+ per mu for the paper set)."""
    gaits = attractors(w)
    if not gaits:
        raise ParameterError(f"mu={w.mu:g} has no stable gait of types A-D+")
    return gaits[0]


def gait_start(gait: theory.Gait) -> tuple[float, float]:
    """Post-impact (theta_dot, x_dot) on ``gait``; a D gait starts at x_dot = D_START_SLIP (its map is neutral in
    x_dot > 0)."""
    if gait.kind.startswith("D"):
        return float(gait.fixed_point[0]), D_START_SLIP
    if gait.kind == "C":
        return float(gait.fixed_point[0]), float(gait.fixed_point[1])
    return float(gait.fixed_point[0]), 0.0


@dataclass(frozen=True)
class Reference:
    """The reference run from one start: settled outcome (:func:`theory.settle`) and per-step mid-stance rates and
    types over the first ``steps`` steps (for the convergence count)."""

    outcome: str
    settle_steps: int
    mid_rate: np.ndarray
    kinds: np.ndarray


def reference_run(w: theory.FrictionWheel, start: Sequence[float], steps: int) -> Reference:
    """:func:`theory.settle` from ``start`` (002 Sec. 3.3); its first ``steps`` records give mid-stance rates."""
    settled = theory.settle(w, start)
    recs = list(settled.records)
    z = recs[-1].post if recs and recs[-1].failure is None else None
    while len(recs) < steps and z is not None:
        rec = theory.step(w, z)
        recs.append(rec)
        z = rec.post if rec.failure is None else None
    recs = recs[:steps]
    mid = np.array([r.midstance[0] for r in recs])
    kinds = np.array([theory.classify_record(r) or "" for r in recs])
    return Reference(settled.outcome, settled.steps, mid, kinds)


# --- the validation -----------------------------------------------------------------------------------------------


@dataclass
class Run:
    """A validation batch: starts, recorded rows, their steps and the reference gait."""

    starts: np.ndarray
    fit_mask: np.ndarray
    rows: Rows
    steps: Steps
    cls: Classifier
    report: RolloutReport
    gait: theory.Gait


def fit_starts(gait: theory.Gait, w: theory.FrictionWheel) -> tuple[np.ndarray, np.ndarray]:
    """Starts (B, 2): the gait's post-impact state with theta_dot0 offsets FIT_OFFSETS (the fit), and one slipping
    start (theta_dot*, SLIP_START) when the reference settles from it on a gait (not for D, nor where a slipping
    start is a Painleve case); returns (starts, fit mask)."""
    th, xd = gait_start(gait)
    fit = [(th * (1 + d), xd) for d in FIT_OFFSETS]
    extra = []
    if not gait.kind.startswith("D"):
        settled = theory.settle(w, (th, SLIP_START), max_steps=80, tol=1e-6)
        if settled.outcome in ("A", "B", "C", "D+", "unsettled"):
            extra.append((th, SLIP_START))
    starts = np.array(fit + extra, float)
    return starts, np.arange(len(starts)) < len(fit)


def run_batch(p: Values, s: Values, preset: str, starts: np.ndarray, steps: int,
              mus: np.ndarray | None = None, extra: float = 0.0) -> tuple[Rows, Steps, Classifier, RolloutReport]:
    """Simulate ``starts`` for ``steps`` gait periods plus ``extra`` seconds (one rollout; ``mus`` gives each
    trajectory its own friction) and measure them."""
    model = build(p, s)
    mu_all = np.full(len(starts), float(p["mu"])) if mus is None else np.asarray(mus, float)
    models = [model] * len(starts) if mus is None else [with_friction(model, float(m)) for m in mu_all]
    period = period_seconds(p, mu_all)
    rec = simulate(models, start_states(model, p, s, starts), steps * period + extra, s)
    cls = classifier(mu_all, s, preset, len(starts))
    rows = row_signals(rec, p, s, cls, np.asarray(model.opt.gravity))
    return rows, step_table(rows, cls, steps + 2), cls, rec.report


def period_seconds(p: Values, mus: np.ndarray) -> float:
    """Longest gait period over the friction values (s), at least the sticking gait's, for sizing the runs."""
    base = dict(p)
    periods = []
    for mu in np.unique(mus):
        w = friction_wheel({**base, "mu": float(mu)})
        gaits = attractors(w)
        periods.append(max([g.period for g in gaits], default=0.0))
    rigid = theory.find_gait(friction_wheel({**base, "mu": math.inf}), "A")
    periods.append(rigid.period if rigid is not None else 1.0)
    return max(periods) / rate_unit(p)


def fit_steps(steps: Steps, mask: np.ndarray, kind: str, seed: int) -> tuple[Any, np.ndarray, np.ndarray]:
    """Quadratic fit of the mid-stance map from consecutive samples of the fitting trajectories, using only pairs
    whose two steps are of the gait's type (a perturbed start may pass through another type first, e.g. D- on the
    way to C, where the mid-stance map is not a function of theta_dot alone) and that precede any failure."""
    xs, ys = [], []
    for b in np.nonzero(mask)[0]:
        last = steps.failure_step[b] if steps.failure[b] else steps.kind.shape[1]
        rate, kinds = steps.mid_rate[b, :last], steps.kind[b, :last]
        ok = (kinds[:-1] == kind) & (kinds[1:] == kind) & np.isfinite(rate[:-1]) & np.isfinite(rate[1:])
        idx = np.nonzero(ok)[0][:FIT_PAIRS]
        xs.append(rate[idx])
        ys.append(rate[idx + 1])
    x, y = np.concatenate(xs)[:, None], np.concatenate(ys)[:, None]
    return fit_return_map(x, y, degree=2, seed=seed), x[:, 0], y[:, 0]


def _settled(steps: Steps, b: int) -> np.ndarray:
    """Indices of the last SETTLED_STEPS complete steps of trajectory ``b`` before its failure, if any (at most the
    second half of the steps it completed: a run cut short by a flight has few settled steps)."""
    done = np.nonzero(steps.complete[b])[0]
    if steps.failure[b]:
        done = done[done < steps.failure_step[b]]
    return done[-min(SETTLED_STEPS, (done.size + 1) // 2):] if done.size else done


def evaluate(p: Values, s: Values, preset: str, seed: int) -> Evaluation:
    """Simulate the reference gait's post-impact state, its perturbations and a slipping start in one batch;
    compare settled type, mid-stance rate, multiplier, slip onset, impact kind and (D) slip growth per step."""
    w = friction_wheel(p)
    gait = reference_gait(w)
    tol = TOLERANCES.get(preset, TOLERANCES["fast"])
    starts, fit_mask = fit_starts(gait, w)
    nsteps = D_SIM_STEPS if gait.kind.startswith("D") else SIM_STEPS
    rows, steps, cls, report = run_batch(p, s, preset, starts, nsteps)
    refs = [reference_run(w, tuple(z), nsteps) for z in starts]
    out: list[checks.Check] = []
    sim_types = [outcome(steps, b) for b in range(len(starts))]
    agree = sum(r.outcome == t for r, t in zip(refs, sim_types, strict=True))
    main = int(np.nonzero(fit_mask)[0][len(FIT_OFFSETS) // 2])
    out.append(_match("gait_type", refs[main].outcome, sim_types[main], len(starts) - agree, len(starts),
                      "settled type (failure, else the type of the last step) of each start (the gait's post-impact "
                      "state, theta_dot0 offsets, a slipping start) vs the reference's theory.settle from the same "
                      f"start (002 Sec. 3.3); error = fraction that differ: simulated {sim_types}, reference "
                      f"{[r.outcome for r in refs]}"))
    extras: dict[str, Any] = {}
    try:
        fit, x, x_next = fit_steps(steps, fit_mask, gait.kind, seed)
        mid_sim, lam_sim = float(fit.fixed_point[0]), float(np.real(fit.eigenvalues[0]))  # 1-D map: real
        extras["fit"] = fit.to_dict()
        grid = np.linspace(float(x.min()), float(x.max()), 40)
        extras["return_map"] = {"label": "mid-stance theta_dot (nondimensional)", "x": x, "x_next": x_next,
                                "analytic_x": grid, "analytic_y": gait.midstance_rate
                                + abs(gait.eigenvalues[0]) * (grid - gait.midstance_rate),
                                "analytic_eigenvalues": [complex(e) for e in gait.eigenvalues]}
    except ValueError as err:  # too few samples: every start failed or left the gait
        mid_sim = lam_sim = math.nan
        extras["fit_error"] = str(err)
    out.append(checks.relative("midstance_rate", gait.midstance_rate, mid_sim, tol["midstance_rate"], "",
                               f"fixed point of the mid-stance map vs the reference gait {gait.kind} "
                               f"({WHY['midstance_rate']})"))
    lam_ref = complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])
    out.append(checks.absolute("eigenvalue", lam_ref.real if lam_ref.imag == 0 else lam_ref, lam_sim,
                               tol["eigenvalue"], "", WHY["eigenvalue"]))
    settled = _settled(steps, main)
    impact_sim = ["slipping" if steps.impact_slipping[main, j] else "sticking" for j in settled]
    out.append(_match("impact_kind", gait.impact, _most_common(impact_sim),
                      sum(k != gait.impact for k in impact_sim), len(settled),
                      f"kind of the settled steps' impacts ({impact_sim}) vs the gait's (002 eq 44): slipping when "
                      "the new foot's speed after the impact window exceeds v_thr or the impulse ratio is on the cone; "
                      f"v_thr = {cls.v_thr:g} ({WHY['v_thr']}); error = fraction that differ"))
    phases = [phase_sequence(steps.runs, main, int(j)) for j in settled]
    names = [" > ".join(ph[0]) for ph in phases]
    out.append(_match("phase_sequence", " > ".join(gait.phases), _most_common(names),
                      sum(ph[0] != gait.phases for ph in phases), len(settled),
                      f"stick/slip phases of the settled steps ({names}) vs the gait's (002 eq 35): a row slips when "
                      "its friction is on the cone (force ratio of the hub's recorded acceleration over 1 ms); error "
                      "= fraction that differ"))
    if gait.kind == "B":
        onset_sim = float(np.nanmedian(steps.onset[main, settled])) if settled.size else math.nan
        out.append(checks.absolute("slip_onset", gait.phase_angles[-1], onset_sim, tol["slip_onset"], "rad",
                                   WHY["slip_onset"]))
    if gait.kind.startswith("D"):
        dx = np.diff(steps.mid_slip[main, settled]) if settled.size > 1 else np.zeros(0)
        dx = dx[np.isfinite(dx)]
        dx_sim = float(np.mean(dx)) if dx.size else math.nan
        out.append(checks.relative("dx_per_step", gait.dx_per_step, dx_sim, tol["dx_per_step"], "",
                                   WHY["dx_per_step"]))
    if gait.kind == "A":
        phi = math.pi / w.spokes
        centres, ratio = ratio_profile(rows, settled_rows(rows, steps, np.nonzero(fit_mask)[0], "A"), phi)
        rigid = theory.FrictionWheel(w.spokes, w.kappa, w.slope, math.inf)
        mu_c = theory.critical_friction(rigid)[0]
        out.append(checks.relative("critical_friction", mu_c, critical_ratio(centres, ratio, phi),
                                   tol["critical_friction"], "", WHY["critical_friction"]))
        analytic_ratio = np.asarray(theory.force_ratio(rigid, centres), float)
        extras["force_ratio_profile"] = {"theta": centres, "simulated": ratio, "analytic": analytic_ratio,
                                         "max_abs_error": float(np.nanmax(np.abs(ratio - analytic_ratio)))}
    extras["analytic"] = _analytic(w, gait)
    extras["steps"] = _step_report(rows, steps, cls, main, refs[main])
    extras["thresholds"] = {"v_thr": cls.v_thr, "saturation_eps": cls.eps, "impact_window_s": cls.impact_window,
                            "creep": creep(rows, steps)}
    extras["starts"] = [{"theta_dot0": float(z[0]), "x_dot0": float(z[1]), "simulated": t,
                         "simulated_velocity_only": outcome(steps, b, velocity_only=True), "reference": r.outcome,
                         "reference_steps": r.settle_steps}
                        for b, (z, t, r) in enumerate(zip(starts, sim_types, refs, strict=True))]
    return Evaluation(out, report, extras)


def _match(name: str, analytic: str, simulated: str, wrong: int, total: int, why: str) -> checks.Check:
    """A categorical check: the reference's and the (main) simulated category, error = fraction that differ."""
    error = wrong / total if total else math.nan
    return checks.Check(name, analytic, simulated or "none", error, 0.0, "fraction", "", why)


def _most_common(items: Sequence[str]) -> str:
    return max(set(items), key=list(items).count) if items else ""


def creep(rows: Rows, steps: Steps) -> dict[str, float]:
    """|x_dot| (nondimensional) of the stance foot over the stick rows of trajectories that did not fail."""
    ok = (steps.failure == "")[:, None] & (rows.mode == STICK)
    v = np.abs(rows.slip[ok])
    if v.size == 0:
        return {"median": math.nan, "p99": math.nan, "max": math.nan}
    return {"median": float(np.median(v)), "p99": float(np.percentile(v, 99)), "max": float(v.max())}


def _analytic(w: theory.FrictionWheel, gait: theory.Gait) -> dict[str, Any]:
    rigid = theory.FrictionWheel(w.spokes, w.kappa, w.slope, math.inf)
    return {"gait": gait.kind, "fixed_point": gait.fixed_point, "eigenvalues": [complex(e) for e in gait.eigenvalues],
            "phases": list(gait.phases), "phase_angles": list(gait.phase_angles), "impact": gait.impact,
            "dx_per_step": gait.dx_per_step, "midstance_rate": gait.midstance_rate,
            "midstance_x_dot": gait.midstance_x_dot, "period": gait.period, "impulse_ratio": gait.impulse_ratio,
            "mu_c": theory.critical_friction(rigid)[0],
            "sticking_impulse_ratio": theory.impulse_ratio(w.spokes, w.kappa),
            "slope_bounds": theory.slope_bounds(w.spokes, w.kappa)}


def _step_report(rows: Rows, steps: Steps, cls: Classifier, b: int, ref: Reference) -> list[dict[str, Any]]:
    table = []
    for j in np.nonzero(steps.complete[b])[0]:
        ph, ang = phase_sequence(steps.runs, b, int(j))
        table.append({"step": int(j) + 1, "kind": str(steps.kind[b, j]),
                      "reference_kind": str(ref.kinds[j]) if j < ref.kinds.size else "",
                      "mid_rate": steps.mid_rate[b, j],
                      "reference_mid_rate": float(ref.mid_rate[j]) if j < ref.mid_rate.size else math.nan,
                      "mid_slip": steps.mid_slip[b, j], "phases": list(ph), "phase_angles": list(ang),
                      "impact": "slipping" if steps.impact_slipping[b, j] else "sticking",
                      "impulse_ratio": steps.impulse_ratio[b, j], "slip_onset": steps.onset[b, j]})
    return table


# --- probe, reference bench, render clip, soak ----------------------------------------------------------------------


def probe(p: Values, s: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The model and the (initial states, steps) of the batch :func:`evaluate` runs."""
    w = friction_wheel(p)
    gait = reference_gait(w)
    starts, _ = fit_starts(gait, w)
    model = build(p, s)
    nstep = math.ceil(SIM_STEPS * period_seconds(p, np.array([w.mu])) / model.opt.timestep)
    return model, [(start_states(model, p, s, starts), nstep)]


def reference_bench(p: Values, rtol: float) -> dict[str, float]:
    """The exact reference (theory.step, the generic Appendix-A integrator at tolerance ``rtol``) through the same
    mid-stance fit: wall time and the eigenvalue / mid-stance errors against the fast-method gait."""
    w = friction_wheel(p)
    gait = reference_gait(w)
    starts, mask = fit_starts(gait, w)
    start = time.perf_counter()
    sequences = []
    for z in starts[mask]:
        state, seq = (float(z[0]), float(z[1])), []
        for _ in range(FIT_PAIRS + 1):
            rec = theory.step(w, state, method="generic", max_step=None)
            if rec.failure is not None:
                break
            seq.append(rec.midstance[0])
            state = rec.post
        sequences.append(np.array(seq)[:, None])
    del rtol  # the generic integrator runs at the theory module's own tolerance (RTOL 1e-11)
    fit = fit_return_map(*sample_pairs(sequences), degree=2)
    wall = time.perf_counter() - start
    lam = complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])
    return {"rtol": theory.RTOL, "wall_s": wall,
            "midstance_rate_error": abs(float(fit.fixed_point[0]) - gait.midstance_rate) / gait.midstance_rate,
            "eigenvalue_error": abs(complex(fit.eigenvalues[0]) - lam)}


def clip(p: Values, s: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """States of a clip from the reference gait's post-impact state perturbed by +10 % in theta_dot."""
    from mujoco import rollout as mj_rollout

    gait = reference_gait(friction_wheel(p))
    th, xd = gait_start(gait)
    state0 = start_states(model, p, s, np.array([[1.1 * th, xd]]))
    with captured_mujoco_log():
        states, _ = mj_rollout.rollout(model, mujoco.MjData(model), state0, nstep=nstep)
    return states[0]


def soak(p: Values, s: Values, impacts: int) -> Soak:
    """``impacts`` steps on the reference gait in one trajectory: the mid-stance theta_dot of each step."""
    w = friction_wheel(p)
    gait = reference_gait(w)
    model = build(p, s)
    seconds = impacts * period_seconds(p, np.array([w.mu])) + 0.5
    rec = simulate([model], start_states(model, p, s, np.array([gait_start(gait)])), seconds, s)
    cls = classifier(w.mu, s, "fast", 1)
    rows = row_signals(rec, p, s, cls, np.asarray(model.opt.gravity))
    phi = math.pi / w.spokes
    mid = level_crossings(rec.time, rows.theta, rows.rate[:, :, None], max_jump=phi)
    return Soak(mid.values[:, 0], gait.midstance_rate, "mid-stance theta_dot (nondimensional)", rec.report)


STRESS_CASES = (
    StressCase("type A", {"mu": "2"}, "no slip (mu > mu_c = 0.914)"),
    StressCase("type B near the A/B edge", {"mu": "0.85"}, "a short slip phase before each impact"),
    StressCase("type C", {"mu": "0.24"}, "slipping impact, slip -> stick -> slip"),
    StressCase("type D+", {"mu": "0.2"}, "forward slip throughout, the slip speed grows each step"),
    StressCase("low friction D+", {"mu": "0.1"}, "near the D branch's lower end (0.080)"),
    StressCase("huge friction", {"mu": "1000"}, "friction far above mu_c"),
    StressCase("light hub", {"kappa": "0.05"}, "kappa = 0.05: the slip normal force ~ kappa (002 eq 42); Type C"),
    StressCase("light hub, no gait", {"kappa": "0.01"}, "kappa = 0.01, mu = 0.3: no stable gait of types A-D+",
               expect="refused"),
    StressCase("below the D branch", {"mu": "0.05"}, "no stable gait: the wheel rolls back", expect="refused"),
    StressCase("point-mass hub", {"kappa": "0"}, "slip needs kappa > 0 (002 eq 42)", expect="refused"),
    StressCase("slope above alpha_max", {"slope": "0.3"}, "f_n < 0 on the sticking gait (002 eq 21)",
               expect="refused"),
)


RIMLESS_WHEEL_FRICTION = Scenario(
    name="rimless-wheel-friction",
    summary="rimless wheel with Coulomb friction: stick-slip gait types A-D, multipliers, slip onset, impacts",
    source="Gamus & Or 2015 Sec. 3 (eq 11-26, Figs 3.3-3.8) and Appendix A (eq 31-45, corrected)",
    params=PARAMS,
    presets=PRESETS,
    check_params=check_params,
    build=build,
    evaluate=evaluate,
    accuracy_checks=("midstance_rate", "eigenvalue"),
    probe=probe,
    reference_bench=reference_bench,
    clip=clip,
    track_body="hub",
    frame_tilt="slope",
    camera_distance=4.0,
    stress_cases=STRESS_CASES,
    soak=soak,
)
