"""The rimless wheel's rollouts and what they record: starts on the post-impact section (003 Sec. 3.2), the chunked
rollout of a batch of them, and per trajectory its mid-stance crossings, impacts, flight clearance and final window,
with the outcome of that window (rolling, standing, flight; 003 Sec. 3.3).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.analysis.adaptive_stopping import FitSettling
from mjpoincare.analysis.outcomes import classify_outcomes
from mjpoincare.analysis.sections import Crossings, level_crossings, wrap_events, wrap_phase
from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.core.params import Values
from mjpoincare.core.seam import Chunk, RolloutReport
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import Foot, JointIndex
from mjpoincare.simulation.simulate import initial_states, rollout_batch

#: Floor on the hub's radius of gyration / leg_length (kappa >= 1e-4; why: docs/scenarios/rimless-wheel.md).
MIN_GYRATION = 1e-2


def wheel(params: Values) -> theory.RimlessWheel:
    """The analytic model of the simulated wheel: the scenario parameters, with the hub's radius of gyration
    raised to at least MIN_GYRATION x leg_length (the model and the theory use the same value)."""
    length = float(params["leg_length"])
    return theory.RimlessWheel(spokes=int(params["spokes"]), slope=float(params["slope"]), leg_length=length,
                               gyration=max(float(params["gyration"]), MIN_GYRATION * length),
                               gravity=float(params["gravity"]), mass=float(params["mass"]))


#: Forward impacts with no backward motion between or after them that make rolling a settled outcome: the first
#: of them was followed by a whole step, so its post-impact speed exceeded omega_f, and the return map (increasing,
#: with omega* its only fixed point) keeps every later one above it (003 Sec. 3.3, Def. 3.20).
#: ``foot_radius`` in the wheels' models (planar, 3-D, with friction).
WHEEL_FOOT = Foot(meaning="spheres at the spoke tips, standing for the papers' point feet (lowest point at "
                          "leg_length): a rounded foot rolls, which biases the impact factor by about +0.7 r/l")
ROLLING_IMPACTS = 2
FIT_STEPS = 6  # impacts per fitting trajectory, at most: beta^12 of the initial offset remains (0.016 for n = 8)
TAIL_SECONDS = 1.0  # final window classified by the basin check
TAIL_CHUNKS = 4  # rollout chunks per tail window: the basin grid's outcome is looked at every quarter window
#: All feet this far (x leg_length) above the ground = flight (a centimetre, above MuJoCo's ~1 mm impact hop).
FLIGHT_CLEARANCE = 1e-2


def post_impact_states(model: mujoco.MjModel, w: theory.RimlessWheel, omega0: np.ndarray,
                       foot_radius: float, slip: np.ndarray | float = 0.0) -> np.ndarray:
    """Initial states just after an impact (two feet on the ground) with post-impact speeds ``omega0``.

    As in the map's section (003 Sec. 3.2): omega0 > 0 pivots on the downhill foot (hinge angle
    -alpha), omega0 < 0 on the uphill foot (+alpha); the hub moves as rotation about the pivot.
    ``slip`` (m/s, default 0: sticking) is the pivot's velocity along the slope, added to the hub's
    (Gamus & Or's x_dot of the stance tip, for the stick-slip scenario).
    """
    a, l = w.alpha, w.leg_length
    psi = np.where(omega0 >= 0, -a, a)
    qpos = np.stack([np.zeros_like(omega0), np.full_like(omega0, (l - foot_radius) * math.cos(a) + foot_radius),
                     psi], axis=1)
    qvel = np.stack([l * omega0 * np.cos(psi) + slip, -l * omega0 * np.sin(psi), omega0], axis=1)
    return initial_states(model, qpos, qvel)


class Recorder:
    """Consumes rollout chunks: mid-stance samples, impacts, flight flags and the final window."""

    def __init__(self, model: mujoco.MjModel, w: theory.RimlessWheel, batch: int, foot_radius: float) -> None:
        self.w, self.radius = w, foot_radius
        self.x, self.z, self.pitch = (JointIndex.of(model, name) for name in ("x", "z", "pitch"))
        self.mid = Crossings.empty(3)
        self.impacts = Crossings.empty(1)
        self.max_clearance = np.zeros(batch)
        self.window: list[Chunk] = []  # the last TAIL_CHUNKS chunks
        self.last_backward = np.full(batch, -np.inf)  # time of each trajectory's last sample with omega <= 0
        #: Each trajectory's outcome from the tail window in which it settled (:meth:`settle`), "" before.
        self.settled = np.full(batch, "", dtype=object)

    def __call__(self, chunk: Chunk) -> None:
        w = self.w
        psi = wrap_phase(chunk.qpos[:, :, self.pitch.qpos], w.alpha)
        values = np.stack([chunk.qvel[:, :, self.pitch.dof], chunk.qpos[:, :, self.x.qpos],
                           chunk.qpos[:, :, self.z.qpos]], axis=2)
        self.mid = self.mid.concat(level_crossings(chunk.time, psi, values, max_jump=w.alpha))
        self.impacts = self.impacts.concat(wrap_events(chunk.time, psi, w.alpha))
        clearance = chunk.qpos[:, :, self.z.qpos] - (w.leg_length - self.radius) * np.cos(psi) - self.radius
        self.max_clearance = np.fmax(self.max_clearance, np.fmax.reduce(clearance, axis=1))
        self.window = [*self.window, chunk][-TAIL_CHUNKS:]
        backward = chunk.qvel[:, :, self.pitch.dof] <= 0.0
        last = backward.shape[1] - 1 - np.argmax(backward[:, ::-1], axis=1)
        rows = np.arange(len(last))
        self.last_backward = np.where(backward.any(axis=1), chunk.time[rows, last], self.last_backward)

    def settle(self) -> np.ndarray:
        """Per trajectory: whether its outcome has settled, i.e. can no longer change. It settles over a tail window
        in which it stands (the rocking only decays, 003 Sec. 3.3), or rolls after ROLLING_IMPACTS forward impacts
        with no backward motion; that window's outcome is kept (:attr:`settled`) and the trajectory needs no more
        steps."""
        open_ = self.settled == ""
        if len(self.window) < TAIL_CHUNKS or not open_.any():
            return ~open_
        rows = np.flatnonzero(open_)
        outcome = tail_outcomes(self.w, self, rows)  # builds the tail window once per look
        forward = np.bincount(self.impacts.trajectory[self.impacts.time > self.last_backward[self.impacts.trajectory]],
                              minlength=len(self.last_backward))[rows]
        now = (outcome == "standing") | ((outcome == "rolling") & (forward >= ROLLING_IMPACTS))
        self.settled[rows[now]] = outcome[now]
        return self.settled != ""

    @property
    def tail(self) -> Chunk | None:
        """The last tail window (TAIL_CHUNKS chunks, each chunk's repeated row 0 dropped), or None before it."""
        if len(self.window) < TAIL_CHUNKS:
            return None
        parts = [self.window[0]] + [Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]) for c in self.window[1:]]
        return Chunk(*(np.concatenate([getattr(c, f) for c in parts], axis=1) for f in ("time", "qpos", "qvel")))


def chunk_steps(model: mujoco.MjModel) -> int:
    """Steps per native rollout chunk: a TAIL_CHUNKS-th of a tail window."""
    return max(1, round(TAIL_SECONDS / TAIL_CHUNKS / model.opt.timestep))


def whole_chunks(model: mujoco.MjModel, seconds: float) -> int:
    """Steps covering ``seconds`` (at least one tail window) in whole chunks."""
    return chunk_steps(model) * max(TAIL_CHUNKS, math.ceil(seconds / (chunk_steps(model) * model.opt.timestep)))


def fit_seconds(w: theory.RimlessWheel) -> float:
    """Duration of the fitting runs: FIT_STEPS steps at the fixed point's period, plus half a second."""
    return FIT_STEPS * theory.step_period(w, theory.rolling_fixed_point(w)) + 0.5


def simulate(model: mujoco.MjModel, w: theory.RimlessWheel, omega0: np.ndarray, seconds: float,
              settings: Values, *, until_decided: bool = False, settling: FitSettling | None = None
              ) -> tuple[Recorder, RolloutReport]:
    """Roll the starts ``omega0`` for ``seconds``; with ``until_decided``, step each start until its outcome settles
    (:meth:`Recorder.settle`) and end when every one has; with ``settling``, once it says the post-impact samples so
    far are enough."""
    radius = float(settings["foot_radius"])
    recorder = Recorder(model, w, len(omega0), radius)
    stop = None
    if settling is not None:
        def stop() -> bool:
            return settling([post[:, None] for post in post_impact_samples(w, recorder, len(omega0))])
    report = rollout_batch(model, post_impact_states(model, w, omega0, radius), whole_chunks(model, seconds),
                           recorder, **rollout_options(settings), chunk_steps=chunk_steps(model), stop=stop,
                           finished=recorder.settle if until_decided else None)
    return recorder, report


def post_impact_samples(w: theory.RimlessWheel, rec: Recorder, batch: int) -> list[np.ndarray]:
    """Each trajectory's post-impact speeds, pulled back from its mid-stance crossings along the sticking stance
    flow (003 eq 3.5, 002 eq 13)."""
    return [np.asarray(theory.post_impact_speed(w, w.slope, seq[:, 0]), float) for seq in rec.mid.sequences(batch)]


def tail_outcomes(w: theory.RimlessWheel, rec: Recorder, rows: np.ndarray | None = None) -> np.ndarray:
    """Each start's outcome over the last recorded window (:func:`classify_outcomes`), or that of starts ``rows``."""
    tail = rec.tail
    assert tail is not None
    pick = slice(None) if rows is None else rows
    runaway = 1.5 * math.sqrt(w.gravity / w.leg_length)
    psi = wrap_phase(tail.qpos[pick, :, rec.pitch.qpos], w.alpha)
    clearance = tail.qpos[pick, :, rec.z.qpos] - (w.leg_length - rec.radius) * np.cos(psi) - rec.radius
    return classify_outcomes(tail.qvel[pick, :, rec.pitch.dof], clearance,
                             rest_speed=0.05 * theory.rolling_fixed_point(w), runaway_speed=runaway,
                             flight_clearance=FLIGHT_CLEARANCE * w.leg_length)


def final_outcomes(w: theory.RimlessWheel, rec: Recorder) -> np.ndarray:
    """Each start's outcome: the one it settled on (:meth:`Recorder.settle`), else that of the last recorded window
    (a start still unsettled when the run ended)."""
    out = rec.settled.copy()
    open_ = np.flatnonzero(out == "")
    if open_.size:
        out[open_] = tail_outcomes(w, rec, open_)
    return out.astype(str)
