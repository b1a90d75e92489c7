"""The post-impact return map of the planar rimless wheel, its fixed points, multipliers and parameter regions.

Sources: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Sec. 3; 002 = Gamus & Or (2015),
"Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst., Sec. 3.1. The forward/backward
thresholds (003 eqs 3.4, 3.7; 3.14 corrected), the return map of 003 eqs 3.13/3.14 (with c -> beta of 002 eq 14 and
g/l -> rate2 of 002 eq 12), the rolling and standing fixed points with their multipliers (003 Sec. 3.3.2, Thms
3.10/3.13; 002 eqs 16-17), the regions Ω1-Ω5 of 003 Sec. 3.3.5 / Table 1 and the existence bound of 003 eq 3.16 (002
eq 18).
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel.params import (
    REGION_TOL,
    RimlessWheel,
    _beta_positive,
    _level,
    _steep,
    validate,
)
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq


def forward_threshold(w: RimlessWheel) -> float:
    """omega_f = sqrt(2 rate2 (1 - cos(gamma - alpha))),
    the least post-impact speed completing a forward step.

    003 eq 3.4 (g/l -> rate2); 002 eq 26 (theta_dot_min).
    For gamma >= alpha the hub starts on or past the vertical, no threshold is needed and 0.0 is returned.
    """
    if w.slope >= w.alpha - REGION_TOL:
        return 0.0
    return math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope - w.alpha)))


def backward_threshold(w: RimlessWheel) -> float:
    """Largest (negative) post-impact speed that completes a backward (uphill) step.

    003 eq 3.7 for gamma <= alpha: omega_b = -sqrt(2 rate2 (1 - cos(gamma + alpha)))
    (the step must pass the vertical). Corrected for gamma > alpha (003 eq 3.14 is wrong there): the step stays
    on theta > 0 and only has to reach gamma - alpha, where omega^2 = omega0^2 - K, so the threshold is
    -sqrt(K). Both agree at gamma = alpha.
    """
    if w.slope >= w.alpha:
        return -math.sqrt(w.K)
    return -math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope + w.alpha)))


def _branches(w: RimlessWheel, omega: NDArray[np.float64]) -> tuple[NDArray[np.bool_], ...]:
    """Masks (forward, rocking, backward) of the return map 003 eqs 3.13/3.14 (corrected);
    thresholds excluded."""
    hi = forward_threshold(w)
    lo = backward_threshold(w)
    if _steep(w):
        return omega >= hi, (omega > lo) & (omega < hi), omega <= lo
    return omega > hi, (omega > lo) & (omega < hi), omega < lo


def return_map(w: RimlessWheel, omega: ArrayLike) -> NDArray[np.float64] | float:
    """Post-impact speed -> next post-impact speed,
    003 eqs 3.13 (gamma <= alpha) and 3.14 (gamma > alpha, corrected).

    Forward step beta sqrt(omega^2 + K) (003 3.5 + 3.11), rocking -beta omega (3.10 + 3.11),
    backward step -beta sqrt(omega^2 - K) (3.8 + 3.11), with cos 2alpha -> beta (002 eq 14) and
    g/l -> rate2 (002 eq 12). For gamma > alpha the backward threshold is -sqrt(K)
    (see :func:`backward_threshold`). NaN on the heteroclinic thresholds (gamma <= alpha).
    """
    om = np.asarray(omega, dtype=float)
    fwd, rock, back = _branches(w, om)
    with np.errstate(invalid="ignore"):
        out = np.select(
            [fwd, rock, back],
            [w.beta * np.sqrt(om**2 + w.K), -w.beta * om, -w.beta * np.sqrt(np.maximum(om**2 - w.K, 0.0))],
            default=np.nan,
        )
    return float(out) if out.ndim == 0 else out


def return_map_derivative(w: RimlessWheel, omega: ArrayLike) -> NDArray[np.float64] | float:
    """dP/domega of :func:`return_map` (derivative of 003 eqs 3.13/3.14 corrected, c -> beta of 002 eq 14).

    Forward beta omega/sqrt(omega^2 + K), rocking -beta, backward -beta omega/sqrt(omega^2 - K)
    (infinite at omega = -sqrt(K) for gamma > alpha). NaN on the heteroclinic thresholds.
    """
    om = np.asarray(omega, dtype=float)
    fwd, rock, back = _branches(w, om)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.select(
            [fwd, rock, back],
            [
                w.beta * om / np.sqrt(om**2 + w.K),
                np.full_like(om, -w.beta),
                -w.beta * om / np.sqrt(np.maximum(om**2 - w.K, 0.0)),
            ],
            default=np.nan,
        )
    return float(out) if out.ndim == 0 else out


def _rolling_formula(w: RimlessWheel) -> float:
    """beta sqrt(K/(1 - beta^2)), the root of P(omega) = omega on the forward branch
    (003 Sec. 3.3.2, 002 eq 16)."""
    return w.beta * math.sqrt(w.K / (1.0 - w.beta**2))


def rolling_exists(w: RimlessWheel) -> bool:
    """Whether the rolling fixed point exists: 0 < beta and (gamma >= alpha or (3.16) holds strictly).

    003 eq 3.16 generalised: beta sqrt(K/(1 - beta^2)) > omega_f; equivalently 002 eq 18.
    With beta <= 0 (n = 3, or n = 4 and kappa = 0) a forward step never returns to the forward branch.
    """
    if not _beta_positive(w):
        return False
    if w.slope >= w.alpha - REGION_TOL:
        return True
    return _rolling_formula(w) > forward_threshold(w)


def rolling_fixed_point(w: RimlessWheel) -> float:
    """omega*_roll = beta sqrt(K/(1 - beta^2))
    (003 Sec. 3.3.2: 2 cot 2alpha sqrt((g/l) sin gamma sin alpha) for kappa = 0; 002 eq 16 in SI units).
    NaN when it does not exist (see :func:`rolling_exists`)."""
    return _rolling_formula(w) if rolling_exists(w) else math.nan


def rolling_multiplier(w: RimlessWheel) -> float:
    """P'(omega*_roll) = beta^2 (002 eq 17; for 003 Thm 3.13 it is cos^2 2alpha, re-derived):
    with P = beta sqrt(omega^2 + K), P' = beta omega*/sqrt(omega*^2 + K) = beta omega*/(omega*/beta).
    NaN if no rolling gait."""
    return w.beta**2 if rolling_exists(w) else math.nan


def standing_exists(w: RimlessWheel) -> bool:
    """Whether omega*_stop = 0 exists: gamma <= alpha (003 Sec. 3.3.2, Table 1; unstable at gamma = alpha)."""
    return w.slope <= w.alpha + REGION_TOL


def standing_multiplier(w: RimlessWheel) -> float:
    """P'(0) = -beta on the rocking branch (003 eq 3.13 with 3.10-3.11, Thm 3.10; c -> beta of 002 eq 14).

    NaN where the standing point does not exist or is not on the rocking branch (gamma >= alpha).
    """
    return -w.beta if w.slope < w.alpha - REGION_TOL else math.nan


def region(w: RimlessWheel) -> int:
    """Parameter region 1..5 of 003 Sec. 3.3.5 / Table 1 / Fig. 14.

    Ω1 gamma > alpha; Ω2 gamma == alpha (tolerance 1e-12); for gamma < alpha the generalised (3.16),
    beta^2 K/(1 - beta^2) vs omega_f^2 (compared in units of rate2, tolerance 1e-12): Ω3 "<", Ω4 "=", Ω5 ">".
    """
    if _steep(w):
        return 1
    if _level(w):
        return 2
    lhs = w.beta * abs(w.beta) * w.K / (1.0 - w.beta**2) / w.rate2
    rhs = forward_threshold(w) ** 2 / w.rate2
    if abs(lhs - rhs) <= REGION_TOL:
        return 4
    return 5 if lhs > rhs else 3


def existence_bound(
    spokes: int, gyration: float = 0.0, leg_length: float = 1.0, gravity: float = 9.81
) -> float:
    """gamma*(alpha): slope where the generalised 003 eq 3.16 (002 eq 18) holds with equality,
    omega*_roll = omega_f.

    A rolling gait exists for slope > gamma* (003 Fig. 14; alpha_min of 002).
    Independent of g and l at fixed kappa. NaN when beta <= 0 (no rolling gait at any slope).
    """

    def gap(slope: float) -> float:
        w = RimlessWheel(spokes, slope, leg_length, gyration, gravity)
        return (_rolling_formula(w) ** 2 - forward_threshold(w) ** 2) / w.rate2

    w0 = RimlessWheel(spokes, math.pi / (2 * spokes), leg_length, gyration, gravity)
    validate(w0)
    if not _beta_positive(w0):
        return math.nan
    return float(brentq(gap, 1e-14, w0.alpha * (1.0 - 1e-12), xtol=1e-15, rtol=1e-15))
