"""One stick/slip classifier for every system's recorded rows (numpy only): the contact modes of Gamus & Or (2015,
eq 35) -- ``stick``, ``slip+`` (the foot slides forward, friction f_t = -mu f_n) and ``slip-`` -- labelled row by
row, and the phases a stance goes through, flicker at a switch merged away with one window for all systems.

A row is labelled from one of two signals, whichever the system's measurements give cleanly:

* **cone saturation** (:func:`cone_modes`): the contact force ratio f_t/f_n on the cone's edge, |f_t| >= (1 - eps) mu
  f_n (Coulomb: a sliding contact's friction is saturated), in the direction the friction opposes. It also sees a
  slip slower than a soft contact's creep. The rimless wheel uses it (its contact force is its hub's momentum rate).
* **foot speed** (:func:`speed_modes`): the stance foot's tangential speed against a threshold above the creep of a
  stuck soft contact. The compass biped uses it: its contact force, the momentum rate of three bodies differenced
  from recorded rows, is too noisy near the cone (measured, docs/scenarios/compass-biped-friction.md).

:func:`merge_short_runs` merges runs shorter than :data:`MERGE_PHASE` into their neighbours, the same way for every
system.
"""

from __future__ import annotations

import numpy as np

STICK, SLIP_POS, SLIP_NEG, EXCLUDED = 0, 1, 2, 3
MODE_NAMES = ("stick", "slip+", "slip-")
#: s: a phase shorter than this is flicker at a switch (the soft contact crossing the cone's edge back and forth) and
#: is merged into its neighbour. Measured: the biped's Gaits B, C, II and III (fast) give the same phases at 1 and 2 ms.
MERGE_PHASE = 1e-3
#: Cone saturation: friction on the cone when |f_t/f_n| >= (1 - CONE_EPS) mu.
CONE_EPS = 5e-3


def speed_modes(speed: np.ndarray, threshold: float) -> np.ndarray:
    """Mode of each row from the foot's tangential speed (any shape): slip+ above ``threshold``, slip- below
    ``-threshold``, stick between (int8, the shape of ``speed``)."""
    mode = np.full(np.shape(speed), STICK, np.int8)
    mode[speed > threshold] = SLIP_POS
    mode[speed < -threshold] = SLIP_NEG
    return mode


def cone_modes(ratio: np.ndarray, mu: np.ndarray | float, eps: float = CONE_EPS) -> np.ndarray:
    """Mode of each row from the contact force ratio f_t/f_n (any shape; ``mu`` broadcast against it): slip+ when the
    friction is on the cone's edge pushing back (f_t <= -(1 - eps) mu f_n), slip- on the other edge, stick inside."""
    mode = np.full(np.shape(ratio), STICK, np.int8)
    with np.errstate(invalid="ignore"):
        mode[ratio <= -(1 - eps) * mu] = SLIP_POS
        mode[ratio >= (1 - eps) * mu] = SLIP_NEG
    return mode


def run_starts(group: np.ndarray, mode: np.ndarray) -> np.ndarray:
    """Indices where a run of equal ``mode`` starts within a ``group`` (both (N,), rows in time order)."""
    new = np.ones(group.size, bool)
    new[1:] = (group[1:] != group[:-1]) | (mode[1:] != mode[:-1])
    return np.nonzero(new)[0]


def merge_short_runs(group: np.ndarray, mode: np.ndarray, shortest: int, passes: int = 2) -> np.ndarray:
    """``mode`` (N,) with every run shorter than ``shortest`` rows absorbed into the run before it in its ``group``
    (N,) (e.g. one stance), or into the run after it when it opens its group; vectorised, ``passes`` passes (a merge
    can leave a shorter run next to it)."""
    mode = np.asarray(mode).copy()
    for _ in range(passes):
        if group.size == 0:
            break
        starts = run_starts(group, mode)
        lengths = np.diff(np.append(starts, group.size))
        run_mode = mode[starts]
        same_prev = np.zeros(starts.size, bool)
        same_prev[1:] = group[starts[1:]] == group[starts[:-1]]
        same_next = np.append(same_prev[1:], False)
        short = lengths < shortest
        new_mode = run_mode.copy()
        new_mode[short & same_prev] = np.roll(run_mode, 1)[short & same_prev]
        first_short = short & ~same_prev & same_next
        new_mode[first_short] = np.roll(run_mode, -1)[first_short]
        mode = np.repeat(new_mode, lengths)
    return mode
