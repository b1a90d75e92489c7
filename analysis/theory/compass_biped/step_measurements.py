"""Per-step measurements of the compass biped's gait from a simulator's event records (numpy only): the step table at
the legs-parallel section and the switched-off swing foot's depth below the slope.

The records are per trajectory, as a gait controller keeps them: legs-parallel section samples y_k and their
times, heel strikes (time, x of the new stance foot; the first stance foot is at x = 0) and, per swing while the
swing foot's contact is off, (lowest swing-foot height, stance-foot height at that row), m along the slope normal
(< 0: below the slope). The exact model's swing foot passes through the slope mid-swing as well (Kiša 2020 Sec.
4.1; Gamus & Or 2015 Sec. 4.1 ignore this scuffing too).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from mjpoincare.analysis.theory import compass_biped as theory

Swings = Sequence[Sequence[tuple[float, float]]]


def crossing_steps(samples: Sequence[Sequence[np.ndarray]], sample_times: Sequence[Sequence[float]],
                   strikes: Sequence[Sequence[tuple[float, float]]], *, first: int = 0,
                   step_work: Sequence[Sequence[float]] | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per section sample k of a trajectory that a heel strike j >= ``first`` follows: y_k, the time to sample
    k + 1, the length of the step that swing ends (stance foot j + 1 minus stance foot j, the first at x = 0) and,
    with ``step_work`` (per trajectory, the work of each step, heel strike to heel strike), the work of step j; a
    sample whose step has no recorded work is left out. Without ``step_work`` the works are empty."""
    ys, dts, lengths, works = [], [], [], []
    for b, (ys_b, times, hits) in enumerate(zip(samples, sample_times, strikes, strict=True)):
        strike_t = np.array([t for t, _ in hits])
        feet = np.array([0.0, *(x for _, x in hits)])
        for k in range(len(ys_b) - 1):
            j = int(np.searchsorted(strike_t, times[k]))  # first heel strike after crossing k
            if not first <= j < len(strike_t) or (step_work is not None and j >= len(step_work[b])):
                continue
            ys.append(ys_b[k])
            dts.append(times[k + 1] - times[k])
            lengths.append(feet[j + 1] - feet[j])
            if step_work is not None:
                works.append(step_work[b][j])
    return np.array(ys), np.array(dts), np.array(lengths), np.array(works)


def swing_foot_report(swing_low: Swings, exact_depth: float) -> dict[str, object]:
    """The reported swing-foot depth (no verdict: the exact model lets the foot pass through the slope, 003 Sec.
    4.1): the deepest the switched-off swing foot went below the slope over the run (``swing_low`` per trajectory,
    trajectory 0 from the fixed point), beside ``exact_depth`` (the exact gait's own dip) and the stance foot's depth
    in the slope at the same rows."""
    lows = [low for swings in swing_low for low in swings]
    value = -min((h for h, _ in lows), default=math.nan)
    gait = -min((h for h, _ in swing_low[0]), default=math.nan)
    sink = -min((h for _, h in lows), default=math.nan)
    return {"value": value, "unit": "m", "note": (
        f"deepest the switched-off swing foot went below the slope over the run's {len(lows)} swings (perturbed "
        f"starts included; from the fixed point {gait:.4g} m); the exact gait's swing dips {exact_depth:.4g} m; "
        f"MuJoCo's stance foot was up to {sink:.3g} m deep in the slope then (the soft contact's penetration under "
        "the load and left over from the impact)")}


def swing_foot_detail(bp: theory.CompassBiped, lows: Sequence[tuple[float, float]], samples: Sequence[np.ndarray],
                      foot_radius: float, exact_depth: float) -> dict[str, object]:
    """Trajectory 0's swings (it starts on the exact fixed point; ``lows`` and ``samples`` are its records): the
    switched-off swing foot's depth below the slope and below the stance foot, and the exact depth of the same
    swing, from the post-impact state its legs-parallel sample pulls back to (003 eq 4.19), scaled by (l - r)/l
    (MuJoCo's legs reach the slope at l - r from the foot sphere's centre); nan for a sample from which the exact
    biped falls (a simulated gait far from the exact one)."""
    scale = (bp.l - foot_radius) / bp.l

    def exact_depth_from(y: np.ndarray) -> float:
        try:
            return -scale * theory.lowest_swing_height(bp, theory.post_impact_from_parallel(bp, y))
        except RuntimeError:
            return math.nan

    same = [exact_depth_from(y) for y in samples[: len(lows)]]
    return {"exact_depth": exact_depth, "depth": [-h for h, _ in lows],
            "depth_below_stance_foot": [h_st - h for h, h_st in lows], "exact_depth_same_swing": same,
            "note": "trajectory 0 (from the exact fixed point), per swing, m; below the slope = below the stance foot "
                    "+ the stance foot's depth in the slope"}
