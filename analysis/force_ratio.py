"""The stance's contact force ratio f_t/f_n against the stance angle, and its maximum, the critical friction
(002 = Gamus & Or 2015, eq 19-23), measured on recorded rows (numpy only)."""

from __future__ import annotations

import math

import numpy as np


def ratio_profile(theta: np.ndarray, force_t: np.ndarray, force_n: np.ndarray, select: np.ndarray, phi: float,
                  width: float = 2e-3) -> tuple[np.ndarray, np.ndarray]:
    """The force ratio f_t/f_n against theta in [-phi, phi], pooled over the rows ``select`` of ``theta``,
    ``force_t`` and ``force_n`` (all (B, T), the forces per row): impulse sums per bin of ``width`` rad, which average
    a soft contact's chatter. Returns (bin centres, ratios), each (K,), NaN where a bin has fewer than 3 rows or
    almost no normal force (the pulses of a chattering contact fell into its neighbours: less than 5 % of the typical
    normal force)."""
    edges = np.arange(-phi, phi + 0.5 * width, width)
    idx = np.clip(np.digitize(theta[select], edges) - 1, 0, edges.size - 2)
    ft = np.bincount(idx, force_t[select], minlength=edges.size - 1)
    fn = np.bincount(idx, force_n[select], minlength=edges.size - 1)
    count = np.bincount(idx, minlength=edges.size - 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean_n = np.where(count >= 3, fn / count, np.nan)
        held = np.nan_to_num(mean_n) > 0.05 * (np.nanmedian(mean_n) if np.isfinite(mean_n).any() else np.inf)
        ratio = np.where(held, ft / fn, np.nan)
    return 0.5 * (edges[1:] + edges[:-1]), ratio


def critical_ratio(centres: np.ndarray, ratio: np.ndarray, phi: float, span: float = 0.02) -> float:
    """max |f_t/f_n| along the stance from a :func:`ratio_profile` (``centres``, ``ratio``: (K,)); 002 eq 23 takes it
    over [-phi, phi] (for the paper's set it sits at +phi): the measured bins, and each end extrapolated to -+phi by a
    quadratic through the last ``span`` rad of bins where the end is within a quarter span of a bin (never across an
    impact window). NaN with fewer than 6 finite bins."""
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
