"""Poincaré samples detected, vectorised, on recorded trajectories (numpy only).

A section is a level set ``phase = level`` crossed in a given direction. For an impacting
system the natural phase is the stance angle wrapped to one step, ``psi in [-alpha, alpha)``:
its wrap-around marks an impact (support transfer) and its zero crossing is mid-stance, far
from any impact transient. :func:`level_crossings` finds the crossings of all trajectories of a
batch at once and linearly interpolates time and any carried values there (error O(dt^2)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Crossings:
    """Section samples of a batch: trajectory index, time and interpolated values, in time order."""

    trajectory: np.ndarray  # (N,) int
    time: np.ndarray  # (N,)
    values: np.ndarray  # (N, m)

    @staticmethod
    def empty(width: int) -> Crossings:
        """No samples, with ``width`` value columns."""
        return Crossings(np.zeros(0, int), np.zeros(0), np.zeros((0, width)))

    def concat(self, other: Crossings) -> Crossings:
        """These samples followed by ``other``'s (e.g. the next chunk of the same batch)."""
        return Crossings(
            np.concatenate([self.trajectory, other.trajectory]),
            np.concatenate([self.time, other.time]),
            np.concatenate([self.values, other.values]),
        )

    def sequences(self, batch: int) -> list[np.ndarray]:
        """Per-trajectory sample sequences (n_i, m), in time order, for ``batch`` trajectories."""
        order = np.lexsort((self.time, self.trajectory))
        traj, values = self.trajectory[order], self.values[order]
        return [values[traj == i] for i in range(batch)]

    def times(self, batch: int) -> list[np.ndarray]:
        """Per-trajectory crossing times, in order."""
        order = np.lexsort((self.time, self.trajectory))
        traj, times = self.trajectory[order], self.time[order]
        return [times[traj == i] for i in range(batch)]


def wrap_phase(angle: np.ndarray, half_period: float) -> np.ndarray:
    """Wrap ``angle`` to ``[-half_period, half_period)``: the stance spoke's angle for a rimless wheel."""
    return angle - 2.0 * half_period * np.floor((angle + half_period) / (2.0 * half_period))


def level_crossings(
    time: np.ndarray,
    phase: np.ndarray,
    values: np.ndarray,
    *,
    level: float = 0.0,
    direction: int = +1,
    max_jump: float = np.inf,
) -> Crossings:
    """Crossings of ``phase == level`` in ``direction`` (+1 upward, -1 downward) on a batch.

    ``time`` and ``phase`` are (B, T); ``values`` (B, T, m) are linearly interpolated at each
    crossing. Steps where ``|phase|`` jumps by more than ``max_jump`` (a wrap-around at an
    impact) are not crossings; NaN rows (diverged trajectories) never produce a sample.
    """
    a, b = phase[:, :-1] - level, phase[:, 1:] - level
    hit = ((a < 0) & (b >= 0)) if direction > 0 else ((a > 0) & (b <= 0))
    hit &= np.abs(b - a) <= max_jump
    traj, k = np.nonzero(hit)
    frac = (a[traj, k] / (a[traj, k] - b[traj, k]))[:, None]
    t = time[traj, k] + frac[:, 0] * (time[traj, k + 1] - time[traj, k])
    v = values[traj, k] + frac * (values[traj, k + 1] - values[traj, k])
    return Crossings(traj, t, v)


def wrap_events(time: np.ndarray, phase: np.ndarray, half_period: float) -> Crossings:
    """Support transfers: steps where the wrapped phase jumps by more than ``half_period``.

    The sign of the jump is the direction of the step (+1: forward, the phase fell from
    ``+half_period`` to ``-half_period``; -1: backward). Values hold that sign; the time is the
    step's midpoint (resolution one timestep).
    """
    jump = phase[:, 1:] - phase[:, :-1]
    traj, k = np.nonzero(np.abs(jump) > half_period)
    sign = -np.sign(jump[traj, k])
    return Crossings(traj, 0.5 * (time[traj, k] + time[traj, k + 1]), sign[:, None])
