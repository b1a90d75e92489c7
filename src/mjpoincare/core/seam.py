"""The rollout seam's protocol: what every engine implements and every scenario's event controller uses.

A batch of B trajectories (:class:`Batch`) is stepped in native chunks; each chunk's recorded states (time, qpos,
qvel; :class:`Chunk`) go to a consumer, and between chunks an event controller may rewrite chosen trajectories'
states, switch a trajectory's contacts, equality constraints or actuators, change its friction, and land a state on
a guard with a fractional step. What the batch did (steps, time, divergence, warnings, sensor extremes) is its
:class:`RolloutReport`. States are MuJoCo's full-physics vectors (MuJoCo docs, "State": ``mjSTATE_FULLPHYSICS``).

The engines (:mod:`mjpoincare.engines.backends`: MuJoCo C, MJX, MuJoCo Warp) implement :class:`Batch`; the chunked event
loop (:mod:`mjpoincare.simulation.simulate`) drives any of them. This module knows no engine.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import TracebackType
from typing import Protocol

import mujoco
import numpy as np

STATE_SPEC = mujoco.mjtState.mjSTATE_FULLPHYSICS


@dataclass(frozen=True)
class Chunk:
    """States recorded over one chunk: ``time`` (B, T), ``qpos`` (B, T, nq), ``qvel`` (B, T, nv).

    Row 0 repeats the last row of the previous chunk (or is the initial state).
    """

    time: np.ndarray
    qpos: np.ndarray
    qvel: np.ndarray


@dataclass
class RolloutReport:
    """What a batch rollout did: ``steps`` simulated (trajectory-steps), ``batch_steps`` (each chunk's steps once:
    the steps a GPU takes one after the other, whatever the batch size), ``wall_s`` spent stepping, ``compile_s``
    spent compiling (MJX and Warp; 0 on MuJoCo C), divergence, warnings."""

    steps: int = 0
    wall_s: float = 0.0
    diverged: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    warnings: list[str] = field(default_factory=list)
    final_state: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    #: Smallest and largest value of each sensor over all recorded steps (empty when the model has none).
    sensor_min: np.ndarray = field(default_factory=lambda: np.zeros(0))
    sensor_max: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: Each sensor's largest value over the batch in the first two recorded steps (the scale of the initial states;
    #: two because MuJoCo's energy sensors lag the state by one step).
    sensor_first: np.ndarray = field(default_factory=lambda: np.zeros(0))
    compile_s: float = 0.0
    batch_steps: int = 0

    def merge(self, other: RolloutReport) -> RolloutReport:
        """One report for two batches run one after the other."""
        low, high = _sensor_extremes(self, other.sensor_min, other.sensor_max)
        first = (np.fmax(self.sensor_first, other.sensor_first) if self.sensor_first.size and other.sensor_first.size
                 else (self.sensor_first if self.sensor_first.size else other.sensor_first))
        return RolloutReport(steps=self.steps + other.steps, wall_s=self.wall_s + other.wall_s,
                             diverged=np.concatenate([self.diverged, other.diverged]),
                             warnings=self.warnings + other.warnings, final_state=self.final_state,
                             sensor_min=low, sensor_max=high, sensor_first=first,
                             compile_s=self.compile_s + other.compile_s,
                             batch_steps=self.batch_steps + other.batch_steps)

    def record_sensors(self, sensordata: np.ndarray) -> None:
        """Fold a chunk's sensor readings (..., nsensordata) into the extremes (NaN rows ignored)."""
        if sensordata.shape[-1] == 0 or not np.isfinite(sensordata).any():
            return
        if self.sensor_first.size == 0:
            first = sensordata.reshape(-1, *sensordata.shape[-2:])[:, :2].reshape(-1, sensordata.shape[-1])
            self.sensor_first = np.where(np.isnan(first), -np.inf, first).max(axis=0)
        flat = sensordata.reshape(-1, sensordata.shape[-1])
        nan = np.isnan(flat)
        self.sensor_min, self.sensor_max = _sensor_extremes(self, np.where(nan, np.inf, flat).min(axis=0),
                                                            np.where(nan, -np.inf, flat).max(axis=0))

    @property
    def steps_per_s(self) -> float:
        """Raw simulation rate over all trajectories."""
        return self.steps / self.wall_s if self.wall_s > 0 else float("nan")


def _sensor_extremes(report: RolloutReport, low: np.ndarray, high: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    if report.sensor_min.size == 0:
        return low, high
    if low.size == 0:
        return report.sensor_min, report.sensor_max
    return np.fmin(report.sensor_min, low), np.fmax(report.sensor_max, high)


#: ``geom_margin`` of a geom whose contacts are switched off on MJX and MuJoCo Warp: a contact would need a
#: penetration deeper than 1000 km. Those backends can change ``geom_margin`` per trajectory at runtime but not
#: ``geom_contype`` (MuJoCo docs, "Collision detection": a contact is generated when the distance is below the
#: margin). MuJoCo C before 3.5 still generates the contact of a geom resting on a plane with this margin, so
#: :class:`MujocoBatch` switches contacts with the collision filter instead (:func:`switch_contact_filter`).
RELEASED_MARGIN = -1e6


def switch_contact(released: dict[tuple[int, int], float], margins: np.ndarray, index: int, geom: int, on: bool
                   ) -> None:
    """:meth:`Batch.set_contact` through the margin (MJX, MuJoCo Warp): trajectory ``index``'s geom margins
    ``margins`` (a writable view of its own, (ngeom,)) get :data:`RELEASED_MARGIN` at ``geom`` when its contact is
    switched off, and the margin kept in ``released`` back when it is switched on again (switching twice either way
    changes nothing)."""
    if on:
        if (index, geom) in released:
            margins[geom] = released.pop((index, geom))
    elif (index, geom) not in released:
        released[index, geom] = float(margins[geom])
        margins[geom] = RELEASED_MARGIN


class Batch(Protocol):
    """B trajectories stepped in native chunks, with per-trajectory events between chunks: the seam a backend
    implements. States are full-physics vectors (nstate,) (MuJoCo docs, "State": ``mjSTATE_FULLPHYSICS``)."""

    report: RolloutReport
    #: The timestep of every trajectory, s.
    timestep: float

    def __enter__(self) -> Batch:
        """The batch, ready to run (a backend may compile here)."""
        ...

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        """Release the batch; ``report`` then holds the final states and the backend's warnings."""
        ...

    def run_chunk(self, nstep: int, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> np.ndarray:
        """Step every trajectory ``nstep`` steps from its current state (``control`` (B, nstep, nu): the ctrl of each
        step); the recorded states (B, nstep + 1, nstate), row 0 the start, NaN from a divergence on (flagged in
        ``report``). Each trajectory's current state becomes its last step. ``rows`` (k,): step these trajectories
        only; every other one keeps its state and its rows of the chunk are NaN, never flagged (MuJoCo C and Drake
        step and count only ``rows``; MJX and Warp step their compiled batch whole and count it whole)."""
        ...

    def states(self) -> np.ndarray:
        """The current states (B, nstate), a copy."""
        ...

    def set_states(self, indices: np.ndarray, states: np.ndarray) -> None:
        """Continue trajectories ``indices`` (k,) from ``states`` (k, nstate); the others are untouched."""
        ...

    def set_contact(self, index: int, geom: int, on: bool) -> None:
        """Switch geom ``geom``'s contacts off (none is generated) or back on, in trajectory ``index`` only."""
        ...

    def set_eq_active(self, index: int, eq: int, on: bool) -> None:
        """Switch equality constraint ``eq`` off or on, in trajectory ``index`` only."""
        ...

    def set_actuator(self, index: int, actuator: int, *, bias: float | None = None, gear: float | None = None
                     ) -> None:
        """Trajectory ``index``'s actuator ``actuator``: its constant bias force (``biasprm[0]``) and/or its ``gear[0]``
        (MuJoCo docs, "Actuation model")."""
        ...

    def set_friction(self, index: int, mu: float) -> None:
        """Trajectory ``index``'s sliding friction coefficient: every geom's ``friction[0]`` (MuJoCo mixes a contact's
        friction as the larger of its two geoms', so every contact of the trajectory then has ``mu``)."""
        ...

    def advance(self, index: int, state: np.ndarray, seconds: float, ctrl: np.ndarray | None = None) -> np.ndarray:
        """``state`` (nstate,) after one step of ``seconds`` (a fraction of the timestep) of trajectory ``index``'s
        model and integrator, under ``ctrl`` (nu,) (zero when None): how an event controller lands a state on its
        guard."""
        ...
