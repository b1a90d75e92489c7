"""Basins of attraction of the planar rimless wheel's rolling and standing motions, and starts that probe them.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3; 002 = Gamus & Or (2015),
"Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst., Sec. 3.1. The basin bands of 003
Def. 3.20 (eqs 3.17-3.18, c -> beta of 002 eq 14, g/l -> rate2), the long-term outcome of a start by 003 Table 1 and
Thms 3.14-3.21, whether iterating the map keeps contact (002 eq 19), and initial speeds around the rolling fixed point
and in every basin.
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel.map import forward_threshold, region, return_map, rolling_fixed_point
from mjpoincare.analysis.theory.rimless_wheel.params import RimlessWheel, _beta_positive
from mjpoincare.analysis.theory.rimless_wheel.stance import step_stays_in_contact
from numpy.typing import NDArray

#: Distance (rad/s) from a basin edge within which :func:`predicted_outcome` answers "boundary".
BOUNDARY_TOL = 1e-9


def _require_basin_parameters(w: RimlessWheel) -> None:
    if not _beta_positive(w):
        raise ValueError(
            f"basins need 0 < beta < 1 (got beta = {w.beta!r}; spokes must be >= 4, kappa > 0 for n=4)"
        )


def basin_band_edges(w: RimlessWheel, m_max: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Edges of the Ω5 basin bands, 003 Def. 3.20 (c -> beta, g/l -> rate2).

    Returns (omega1, omega2) with omega1[m] = omega_1^m for m = 0..m_max and
    omega2[m] = omega_2^m for m = 0..m_max+1, where
    omega_1^m = -sqrt(2 rate2 [beta^-2m (1 - cos(gamma+alpha))
      + 2 sin gamma sin alpha (1 - beta^-2m)/(1 - beta^-2)])
    and omega_2^m is the same with beta^-2(m+1) (1 - cos(gamma - alpha)).
    Then I^m_roll = (omega1[m], omega2[m]) and I^m_stop = (omega2[m+1], omega1[m]) (003 eqs 3.17-3.18).
    """
    _require_basin_parameters(w)
    s = math.sin(w.slope) * math.sin(w.alpha)
    b2 = w.beta**-2

    def geometric(m: NDArray[np.float64]) -> NDArray[np.float64]:
        return (1.0 - b2**m) / (1.0 - b2)

    m1 = np.arange(m_max + 1, dtype=float)
    m2 = np.arange(m_max + 2, dtype=float)
    omega1 = -np.sqrt(
        2.0 * w.rate2 * (b2**m1 * (1.0 - math.cos(w.slope + w.alpha)) + 2.0 * s * geometric(m1))
    )
    omega2 = -np.sqrt(
        2.0 * w.rate2 * (b2 ** (m2 + 1) * (1.0 - math.cos(w.slope - w.alpha)) + 2.0 * s * geometric(m2))
    )
    return omega1, omega2


def _forward_preimages(w: RimlessWheel, target: float, upto: float) -> list[float]:
    """Forward-branch preimages target_{-m} <= upto:
    omega^2 = beta^-2m target^2 - K (1 - beta^-2m)/(1 - beta^-2) (inverse of 003 Lemma 3.1 with c -> beta);
    only grows when target > omega*_roll (region Ω3)."""
    out = [target]
    while out[-1] <= upto and len(out) < 10_000:
        nxt = math.sqrt((out[-1] / w.beta) ** 2 - w.K)
        if nxt <= out[-1]:
            break
        out.append(nxt)
    return out


def _bands_below(w: RimlessWheel, omega0: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Band edges of :func:`basin_band_edges` with enough bands that omega_1^m_max < omega0 - 1."""
    m_max = 4
    while True:
        omega1, omega2 = basin_band_edges(w, m_max)
        if omega1[-1] < omega0 - 1.0:
            return omega1, omega2
        m_max *= 2


def predicted_outcome(w: RimlessWheel, omega0: float) -> str:
    """Long-term outcome from post-impact speed omega0 by the basin formulas, not by iterating the map.

    003 Table 1 and Thms 3.14-3.21 (Ω5: eqs 3.17-3.18 with the bands of :func:`basin_band_edges`).
    Returns "rolling", "standing" or "boundary" (within 1e-9 rad/s of a basin edge, i.e. of the set H of speeds
    that reach omega_f or omega_b). Ω1: always rolling; Ω2: rolling except omega0 = 0 and H;
    Ω3: standing except H; Ω4: rolling above omega_f (the semistable ghost), standing below;
    Ω5: the band table. Requires 0 < beta < 1.
    """
    _require_basin_parameters(w)
    reg = region(w)
    if reg == 1:
        return "rolling"
    omega_f = forward_threshold(w)
    omega1, omega2 = _bands_below(w, min(omega0, 0.0))
    edges = [omega_f, *omega1]
    if reg == 5:
        edges.extend(omega2)
    if reg == 3:
        edges.extend(_forward_preimages(w, omega_f, omega0 + 1.0))
    if min(abs(omega0 - e) for e in edges) <= BOUNDARY_TOL:
        return "boundary"
    if reg == 2 or (reg in (4, 5) and omega0 > omega_f):
        return "rolling"
    if reg in (3, 4) or omega0 > omega2[0]:
        return "standing"
    m = int(np.argmax(omega1 < omega0))  # first band index with omega_1^m < omega0
    return "rolling" if omega0 < omega2[m] else "standing"


def flight_free(w: RimlessWheel, omega0: float, steps: int) -> bool:
    """Whether iterating the return map (003 eqs 3.13/3.14 corrected) from omega0 for ``steps`` impacts keeps
    f_n >= 0 (002 eq 19) during every stance: forward steps, rocking excursions and backward steps are all
    checked (see :func:`excursion_min_normal_force`). Iteration stops early on a heteroclinic threshold (NaN).
    """
    omega = float(omega0)
    for _ in range(steps):
        if not math.isfinite(omega):
            break
        if not step_stays_in_contact(w, omega):
            return False
        omega = float(return_map(w, omega))
    return True


def fit_initial_speeds(w: RimlessWheel, count: int) -> NDArray[np.float64]:
    """``count`` post-impact speeds around the rolling fixed point (003 eq 3.13), inside its basin (above
    omega_f) and flight-free on the first step (:func:`step_stays_in_contact`): from
    max(0.85 omega*, omega_f + 0.3 (omega* - omega_f)) to at most 1.15 omega*."""
    star = rolling_fixed_point(w)
    low = max(0.85 * star, forward_threshold(w) + 0.3 * (star - forward_threshold(w)))
    high = 1.15 * star
    while not step_stays_in_contact(w, high) and high > 1.01 * star:
        high = star + 0.5 * (high - star)
    return np.linspace(low, high, count)


def basin_initial_speeds(w: RimlessWheel, bands: int = 3) -> NDArray[np.float64]:
    """Post-impact speeds probing every basin of 003 Table 1 / Def. 3.20 (region Ω5), sorted.

    The midpoint of each rolling band I^m_roll and standing band I^m_stop for m < ``bands``, two
    speeds in (omega_2^0, 0) and in (0, omega_f) (standing), two above omega_f (rolling).
    """
    omega1, omega2 = basin_band_edges(w, bands)
    roll = 0.5 * (omega1[:bands] + omega2[:bands])
    stop = 0.5 * (omega2[1 : bands + 1] + omega1[:bands])
    omega_f, star = forward_threshold(w), rolling_fixed_point(w)
    near_zero = [omega2[0] * 2 / 3, omega2[0] / 3, omega_f / 3, omega_f * 2 / 3]
    forward = [omega_f + 0.5 * (star - omega_f), 1.2 * star]
    return np.sort(np.concatenate([roll, stop, near_zero, forward]))


def basin_edges(w: RimlessWheel, bands: int = 8) -> NDArray[np.float64]:
    """Every basin edge down to band ``bands`` (003 Def. 3.20): omega_f, 0 and the band edges omega_1^m, omega_2^m."""
    omega1, omega2 = basin_band_edges(w, bands)
    return np.concatenate([[forward_threshold(w), 0.0], omega1, omega2])


def basin_bands(w: RimlessWheel, bands: int = 3) -> list[list[float | str]]:
    """[low, high, outcome] of the bands I^m_roll and I^m_stop for m < ``bands`` (003 eqs 3.17-3.18), then the
    standing band (omega_2^0, omega_f) and the rolling band (omega_f, 1.3 omega*)."""
    omega1, omega2 = basin_band_edges(w, bands)
    out: list[list[float | str]] = [[float(omega1[m]), float(omega2[m]), "rolling"] for m in range(bands)]
    out += [[float(omega2[m + 1]), float(omega1[m]), "standing"] for m in range(bands)]
    out += [[float(omega2[0]), float(forward_threshold(w)), "standing"],
            [float(forward_threshold(w)), float(1.3 * rolling_fixed_point(w)), "rolling"]]
    return out
