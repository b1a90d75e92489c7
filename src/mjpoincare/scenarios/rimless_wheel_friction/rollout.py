"""The friction wheel's model, experiment design and MuJoCo runs (Gamus & Or 2015, Sec. 3): the model and its units,
the reference gait and the starts around it, a batch rolled out with every recorded row kept and measured
(:func:`run_batch`), 002's variables of each row read from the wheel's joints
(:func:`mjpoincare.analysis.theory.rimless_wheel_friction.rows.wheel_rows`), the per-preset thresholds of the stick/slip
classification, and the stance foot's sliding rows against MuJoCo's contact law (why each number is what it is:
docs/scenarios/rimless-wheel-friction.md). Used by :mod:`mjpoincare.scenarios.rimless_wheel_friction`, its friction
sweep and its region map."""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from mjpoincare.analysis.contact_modes import EXCLUDED
from mjpoincare.analysis.soft_contact import SoftContact
from mjpoincare.analysis.stick_slip_phases import Classifier, Rows, Steps, step_table
from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.analysis.theory.rimless_wheel_friction.rows import impact_window, stance_contact, wheel_rows
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.mjcompat import efc_diag_inverse_inertia
from mjpoincare.core.params import ParameterError
from mjpoincare.core.seam import Batch, Chunk, RolloutReport
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios import rimless_wheel as rw
from mjpoincare.scenarios.base import JointIndex, Values
from mjpoincare.simulation.simulate import event_rollout

FIT_OFFSETS = (-0.12, -0.06, 0.0, 0.06, 0.12)  # relative offsets of theta_dot0 around the gait's post-impact state
FIT_PAIRS = 12  # mid-stance pairs per fitting trajectory (beta^24 of the offset remains: near the fixed point)
SIM_STEPS = 30  # steps simulated per trajectory (the slowest reference transient settles to 1e-3 within ~25)
D_SIM_STEPS = 12  # D gaits: theta_dot converges within ~5 steps (lambda ~ 0.34) and the slip speed keeps growing
SETTLED_STEPS = 5  # the last steps of a run compared with the reference gait
BACKWARD_RATE = -0.01  # nondimensional theta_dot below which the wheel rolls back
FLIGHT_CLEARANCE = 1e-3  # lowest foot this high (x leg_length) = flight ("detached")
SLIP_START = 0.05  # x_dot0 of the slipping start checked for its settled type (a D- transient at mu = 0.3)
D_START_SLIP = 0.02  # x_dot0 of starts on a Type D gait (its theta_dot map does not depend on x_dot > 0)
#: Speed (nondimensional, units l omega_c) above which the stance foot moves: impacts and the velocity-only
#: classification.
V_THRESHOLD: dict[str, float] = {"fast": 5e-3, "accurate": 2e-3, "coarse": 1e-2}
IMPACT_WINDOW_TC = 5.0  # the impact window is at least this many contact time constants


def friction_wheel(params: Values) -> theory.FrictionWheel:
    """The nondimensional reference wheel (002 eq 11)."""
    return theory.FrictionWheel(int(params["spokes"]), float(params["kappa"]), float(params["slope"]),
                                float(params["mu"]))


def rate_unit(params: Values) -> float:
    """omega_c = sqrt(g/(l(1+kappa))), 1/s: theta_dot_SI = theta_dot omega_c, x_dot_SI = x_dot l omega_c."""
    return theory.omega_c(float(params["leg_length"]), float(params["gravity"]), float(params["kappa"]))


def rigid_params(params: Values) -> dict[str, float | int]:
    """Parameters of :mod:`mjpoincare.scenarios.rimless_wheel` for the same wheel (hub mass 1 kg, gyration
    sqrt(kappa) l, the same mu on feet and floor)."""
    l = float(params["leg_length"])
    return {"spokes": int(params["spokes"]), "slope": float(params["slope"]), "leg_length": l, "mass": 1.0,
            "gyration": math.sqrt(float(params["kappa"])) * l, "mu": float(params["mu"]),
            "gravity": float(params["gravity"])}


def build(params: Values, settings: Values) -> mujoco.MjModel:
    """The rimless wheel of ``rimless-wheel`` (same MJCF and MjSpec rebuild) with gyration sqrt(kappa) l and mu."""
    return rw.build(rigid_params(params), settings)


def start_states(model: mujoco.MjModel, params: Values, settings: Values, starts: np.ndarray) -> np.ndarray:
    """Full-physics states just after an impact for nondimensional post-impact states ``starts`` (B, 2) =
    (theta_dot0, x_dot0) of 002 (x_dot0: slip speed of the new stance tip)."""
    unit, l = rate_unit(params), float(params["leg_length"])
    w = rw.wheel(rigid_params(params))
    return rw.post_impact_states(model, w, starts[:, 0] * unit, float(settings["foot_radius"]), starts[:, 1] * l * unit)


def reference_gait(w: theory.FrictionWheel) -> theory.Gait:
    """The stable gait this mu settles on (002 Sec. 3.3; at most one of A, B, C, D+ per mu for the paper set)."""
    gaits = theory.attractors(w)
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


def simulate(model: mujoco.MjModel, mu: np.ndarray, state0: np.ndarray, seconds: float, settings: Values
             ) -> tuple[Chunk, RolloutReport]:
    """Roll every initial state out for ``seconds`` (one :func:`mujoco.rollout` batch, trajectory b with friction
    ``mu[b]`` on its feet and floor, native chunks of 0.5 s) and keep every recorded row: ``time`` (B, T), ``qpos``
    and ``qvel`` (B, T, 3)."""
    dt = model.opt.timestep
    nstep = max(1, math.ceil(seconds / dt))
    chunk = math.ceil(nstep / math.ceil(nstep / max(1, round(0.5 / dt))))  # equal chunks of <= 0.5 s: no overshoot
    parts: list[Chunk] = []

    def keep(c: Chunk, _batch: Batch) -> np.ndarray:
        parts.append(c if not parts else Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]))
        return np.full(c.time.shape[0], chunk)

    def frictions(batch: Batch) -> None:
        for b, value in enumerate(mu):
            batch.set_friction(b, float(value))

    report = event_rollout(model, state0, nstep, keep, chunk_steps=chunk, setup=frictions, **rollout_options(settings))
    time_ = np.concatenate([c.time for c in parts], axis=1)[:, : nstep + 1]
    qpos = np.concatenate([c.qpos for c in parts], axis=1)[:, : nstep + 1]
    qvel = np.concatenate([c.qvel for c in parts], axis=1)[:, : nstep + 1]
    return Chunk(time_, qpos, qvel), report


def row_signals(rec: Chunk, model: mujoco.MjModel, params: Values, settings: Values, unit: float,
                cls: Classifier) -> Rows:
    """002's variables and the contact force of every recorded row of ``rec`` (joints ``x``, ``z``, ``pitch`` of
    ``model``, whose gravity is the slope frame's), nondimensional with ``unit`` = omega_c (1/s)."""
    x, z, pitch = (JointIndex.of(model, name) for name in ("x", "z", "pitch"))
    return wheel_rows(time=rec.time, pitch=rec.qpos[:, :, pitch.qpos], pitch_rate=rec.qvel[:, :, pitch.dof],
                      hub_x_dot=rec.qvel[:, :, x.dof], hub_z=rec.qpos[:, :, z.qpos],
                      hub_z_dot=rec.qvel[:, :, z.dof],
                      gravity=np.asarray(model.opt.gravity), spokes=int(params["spokes"]),
                      leg_length=float(params["leg_length"]), foot_radius=float(settings["foot_radius"]),
                      rate_unit=unit,
                      timestep=float(settings["timestep"]), cls=cls)


def classifier(mu: np.ndarray | float, settings: Values, preset: str, batch: int) -> Classifier:
    """Thresholds for ``preset``: ``V_THRESHOLD``; the impact window of the soft contact (:func:`impact_window`), at
    least IMPACT_WINDOW_TC contact time constants. The others are the classifier's."""
    window = impact_window(float(settings["timestep"]), float(settings["solref_timeconst"]),
                           float(settings["solref_dampratio"]),
                           IMPACT_WINDOW_TC)
    return Classifier(mu=np.broadcast_to(np.asarray(mu, float), (batch,)).copy(),
                      v_thr=V_THRESHOLD.get(preset, V_THRESHOLD["fast"]), impact_window=window)


@dataclass(frozen=True)
class FrictionRun:
    """One batch's recorded rows (``rec``, on ``model``), their stick/slip signals and step table, the thresholds and
    the rollout report."""

    rec: Chunk
    model: mujoco.MjModel
    rows: Rows
    steps: Steps
    cls: Classifier
    report: RolloutReport


def run_batch(params: Values, settings: Values, preset: str, starts: np.ndarray, steps: int,
              mus: np.ndarray | None = None, extra: float = 0.0, seconds: float | None = None) -> FrictionRun:
    """Simulate ``starts`` for ``steps`` gait periods plus ``extra`` seconds, or for ``seconds`` where given (a run
    where the theory has no gait to size it by), in one rollout (``mus`` gives each trajectory its own friction), and
    measure up to ``steps`` steps."""
    model = build(params, settings)
    mu_all = np.full(len(starts), float(params["mu"])) if mus is None else np.asarray(mus, float)
    duration = seconds if seconds is not None else steps * period_seconds(params, mu_all) + extra
    rec, report = simulate(model, mu_all, start_states(model, params, settings, starts), duration, settings)
    cls = classifier(mu_all, settings, preset, len(starts))
    rows = row_signals(rec, model, params, settings, rate_unit(params), cls)
    table = step_table(rows, cls, steps + 2, backward_rate=BACKWARD_RATE, flight_clearance=FLIGHT_CLEARANCE)
    return FrictionRun(rec=rec, model=model, rows=rows, steps=table, cls=cls, report=report)


def period_seconds(params: Values, mus: np.ndarray) -> float:
    """Longest gait period over the friction values (s), at least the sticking gait's, for sizing the runs."""
    return theory.longest_period(friction_wheel(params), np.unique(mus)) / rate_unit(params)


#: Sliding rows needed for the contact-law check (fewer: no sliding to check, e.g. Type A).
MIN_SLIDING_ROWS = 20


@dataclass(frozen=True)
class SlidingContact:
    """The stance foot's sliding rows (MuJoCo's cone zone, outside impact windows) against MuJoCo's contact law
    (:mod:`mjpoincare.analysis.soft_contact`, eq 2).

    Attributes:
        rows: how many sliding rows were read (touching outside impact windows, in MuJoCo's cone zone, the foot
            faster than the classifier's v_thr).
        residual: the largest relative residual of the law (eq 1, :meth:`SoftContact.sliding_law_residual`) over
            them (NaN with fewer than MIN_SLIDING_ROWS).
        lift_ratio: at each lift-off of a sliding foot (its next row off the surface), the normal velocity the step
            leaves with over mu |v_t|: (5th, 50th, 95th) percentiles (NaN without lift-offs).
        decelerating: the same percentiles of |v_t + a_t / b| / |v_t|, the part of the lift ratio eq 2 attributes to
            the foot's tangential deceleration within the contact's response time 1/b.
        lift_offs: how many lift-offs.
    """

    rows: int
    residual: float
    lift_ratio: tuple[float, float, float]
    decelerating: tuple[float, float, float]
    lift_offs: int

    def reported(self) -> dict[str, object]:
        """The lift ratio as the validation's ``reported`` entry (value, unit, note)."""
        low, mid, high = self.lift_ratio
        return {"value": mid, "unit": "", "note": (
            f"median over {self.lift_offs} lift-offs of the normal velocity a sliding step leaves with / (mu |v_t|), "
            f"5-95 % {low:.3f}-{high:.3f}; eq 2 of analysis/soft_contact: |v_t + a_t/b| / |v_t| = "
            f"{self.decelerating[1]:.3f} of it is the foot's deceleration within the contact's response time 1/b, "
            "the rest its spring")}


def _percentiles(x: np.ndarray) -> tuple[float, float, float]:
    if not x.size:
        return math.nan, math.nan, math.nan
    low, mid, high = np.percentile(x, [5, 50, 95])
    return float(low), float(mid), float(high)


def sliding_contact(rec: Chunk, model: mujoco.MjModel, params: Values, settings: Values, rows: Rows, cls: Classifier
                    ) -> SlidingContact:
    """:class:`SlidingContact` of the recorded rows ``rec`` of ``model`` (their signals ``rows``, thresholds ``cls``:
    each trajectory's friction, and the foot speed above which a lift-off counts as a slide's); MuJoCo's diagonal
    inverse inertia of a foot's normal row (``efc_diagA``) is read once from ``model`` at the first recorded state."""
    mu, cls_v_thr = cls.mu, cls.v_thr
    x, z, pitch = (JointIndex.of(model, name) for name in ("x", "z", "pitch"))
    con = stance_contact(pitch=rec.qpos[:, :, pitch.qpos], pitch_rate=rec.qvel[:, :, pitch.dof],
                         hub_x_dot=rec.qvel[:, :, x.dof], hub_z=rec.qpos[:, :, z.qpos],
                      hub_z_dot=rec.qvel[:, :, z.dof],
                         gravity=np.asarray(model.opt.gravity), spokes=int(params["spokes"]),
                         leg_length=float(params["leg_length"]), foot_radius=float(settings["foot_radius"]),
                         timestep=float(settings["timestep"]), mass=float(model.body_subtreemass[0]))
    law = SoftContact(timestep=float(settings["timestep"]), timeconst=float(settings["solref_timeconst"]),
                      dampratio=float(settings["solref_dampratio"]), solimp=sim_settings.solimp(settings),
                      impratio=float(settings["impratio"]), mu=np.asarray(mu, float)[:, None],
                      diag_inverse_inertia=_normal_diag_inverse_inertia(model, rec))
    # sliding: touching outside an impact window, in the cone's middle zone and moving faster than v_thr (at the
    # cone's apex, a_t + b v_t ~ 0, the zone a row is in cannot be told from the recorded rows)
    touching = (rows.mode != EXCLUDED) & np.isfinite(con.a_n) & (con.dist < 0) & (np.abs(rows.slip) > cls_v_thr)
    sliding = touching & law.in_cone_zone(dist=con.dist, v_n=con.v_n, v_t=con.v_t, a_n=con.a_n, a_t=con.a_t)
    residual = law.sliding_law_residual(dist=con.dist, v_n=con.v_n, v_t=con.v_t, a_n=con.a_n, a_t=con.a_t,
                                        f_n=con.f_n)[sliding]
    lifted = sliding & (np.concatenate([con.dist[:, 1:], np.full((con.dist.shape[0], 1), -1.0)], axis=1) >= 0)
    scale = law.mu * np.abs(con.v_t)
    v_after = np.concatenate([con.v_n[:, 1:], np.full((con.v_n.shape[0], 1), np.nan)], axis=1)
    decel = np.abs(con.v_t + con.a_t / law.damping) / np.abs(con.v_t)
    return SlidingContact(rows=int(sliding.sum()),
                          residual=float(residual.max()) if residual.size >= MIN_SLIDING_ROWS else math.nan,
                          lift_ratio=_percentiles((v_after / scale)[lifted]), decelerating=_percentiles(decel[lifted]),
                          lift_offs=int(lifted.sum()))


def _normal_diag_inverse_inertia(model: mujoco.MjModel, rec: Chunk) -> float:
    """MuJoCo's diagonal approximation of the inverse inertia in a foot's contact normal (``efc_diagA`` of the first
    contact's normal row; the same for every foot of the one wheel body), from one forward call at the first row."""
    data = mujoco.MjData(model)
    data.qpos[:] = rec.qpos[0, 0]
    data.qvel[:] = rec.qvel[0, 0]
    mujoco.mj_forward(model, data)
    if data.ncon == 0:
        return math.nan
    return float(efc_diag_inverse_inertia(data)[data.contact[0].efc_address])
