"""Consecutive section samples: the pairs ``(x_k, x_{k+1})`` a return map is fitted to, and a fit-free multiplier.

A batch of simulated trajectories gives, on a Poincaré section, sequences of consecutive crossings; this module forms
the pairs (never across a gap or two sequences) and, for a 1-D map, the median contraction ratio about a known fixed
point. Only numpy is used.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


def sample_pairs(sequences: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Build the pairs ``(x_k, x_{k+1})`` from sequences of consecutive section samples.

    Args:
        sequences: one array per trajectory, of shape ``(n_i, d)`` or ``(n_i,)`` (then ``d = 1``),
            holding consecutive section crossings.  A row containing NaN marks a missing crossing:
            no pair is formed with it, so pairs never span a gap.  Pairs never span two sequences.

    Returns:
        ``(x, x_next)``, each of shape ``(N, d)``.

    Raises:
        ValueError: if no sequence is given, a sequence has more than two dimensions, or the
            sequences disagree on ``d``.
    """
    if len(sequences) == 0:
        raise ValueError("sample_pairs needs at least one sequence")
    dim: int | None = None
    firsts: list[np.ndarray] = []
    seconds: list[np.ndarray] = []
    for index, sequence in enumerate(sequences):
        samples = np.asarray(sequence, dtype=float)
        if samples.ndim == 1:
            samples = samples[:, None]
        if samples.ndim != 2:
            raise ValueError(f"sequence {index} must have shape (n,) or (n, d), got {samples.shape}")
        if dim is None:
            dim = samples.shape[1]
        elif samples.shape[1] != dim:
            raise ValueError(f"sequence {index} has dimension {samples.shape[1]}, expected {dim}")
        present = ~np.isnan(samples).any(axis=1)
        keep = present[:-1] & present[1:]
        firsts.append(samples[:-1][keep])
        seconds.append(samples[1:][keep])
    return np.concatenate(firsts, axis=0), np.concatenate(seconds, axis=0)


def convergence_ratio(sequence: np.ndarray, fixed_point: float, noise_floor: float = 0.0) -> float:
    """Fit-free multiplier estimate of a 1-D map: median of ``|x_{k+1} - x*| / |x_k - x*|``.

    Valid for a positive real multiplier (for a negative one it returns its modulus).  Steps
    where ``|x_k - x*| <= noise_floor`` (the ratio would be dominated by noise) or where either
    sample is NaN are ignored.

    Args:
        sequence: ``(n,)`` (or ``(n, 1)``) consecutive section samples of one trajectory.
        fixed_point: the fixed point ``x*``.
        noise_floor: distance from ``x*`` below which a step is ignored (>= 0).

    Returns:
        The median ratio.

    Raises:
        ValueError: on a non-1-D sequence, a negative noise floor, or no usable step.
    """
    samples = np.asarray(sequence, dtype=float)
    if samples.ndim == 2 and samples.shape[1] == 1:
        samples = samples[:, 0]
    if samples.ndim != 1:
        raise ValueError(f"convergence_ratio needs a 1-D sequence, got shape {np.shape(sequence)}")
    if noise_floor < 0:
        raise ValueError(f"noise_floor must be >= 0, got {noise_floor}")
    distance = np.abs(samples - float(fixed_point))
    before, after = distance[:-1], distance[1:]
    usable = np.isfinite(before) & np.isfinite(after) & (before > noise_floor)
    if not np.any(usable):
        raise ValueError("no step of the sequence is farther than noise_floor from the fixed point")
    return float(np.median(after[usable] / before[usable]))
