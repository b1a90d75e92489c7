"""Which end state the basin check predicts for a start and which starts it judges (003 Sec. 3.3, Table 1, eqs
3.17-3.18): one rule for the check, its rival and the gate's power."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from mjpoincare.analysis.theory import rimless_wheel as theory

#: A start within this fraction of its speed (at least 0.1 rad/s) of a basin edge is reported, not judged.
EDGE_MARGIN = 0.02


def predicted_outcome(w: theory.RimlessWheel, omega0: float) -> str:
    """The end state the theory gives a start (003 Table 1; a run that would lift off within 6 steps: "flight")."""
    outcome = theory.predicted_outcome(w, omega0)
    if outcome != "boundary" and not theory.flight_free(w, omega0, 6):
        return "flight"
    return outcome


def judged(w: theory.RimlessWheel, omega0: Sequence[float], predicted: Sequence[str]) -> np.ndarray:
    """Which starts the check judges: those predicted rolling or standing and not within :data:`EDGE_MARGIN` of a
    basin edge (eqs 3.17-3.18)."""
    edges = theory.basin_edges(w)
    near = np.array([np.min(np.abs(om - edges)) < EDGE_MARGIN * max(abs(om), 0.1) for om in omega0], dtype=bool)
    return np.array([p in ("rolling", "standing") for p in predicted], dtype=bool) & ~near


def basin_flips(right: theory.RimlessWheel, wrong: theory.RimlessWheel) -> float:
    """Share of the basin grid's judged starts (the grid and the judging of the theory at ``right``) whose predicted
    end state differs on ``wrong``: the basin check's error under ``wrong`` (NaN where none is judged)."""
    omega0 = [float(v) for v in theory.basin_initial_speeds(right)]
    predicted = [predicted_outcome(right, om) for om in omega0]
    mask = judged(right, omega0, predicted)
    if not mask.any():
        return math.nan
    differ = sum(predicted_outcome(wrong, om) != p for om, p, j in zip(omega0, predicted, mask, strict=True) if j)
    return differ / int(mask.sum())
