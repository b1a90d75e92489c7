"""The compass-gait biped's period-1 gait by Newton shooting, its multipliers and the first period doubling.

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4, eq 4.18 and Fig. 18: the
fixed point of the post-impact map by Newton shooting (not the thesis' grid search of Sec. 4.4.2), continued in the
slope from the Fig. 18 gait and in the constant torques; its Floquet multipliers (given by Goswami et al. 1996/98, not
by 003) and the slope of the first flip bifurcation of Goswami et al. 1998.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory.compass_biped.one_step import _section_state, return_map
from mjpoincare.analysis.theory.compass_biped.params import CompassBiped, validate
from mjpoincare.analysis.theory.shooting import central_jacobian
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, fsolve

#: Slope of the built-in fixed point, from which :func:`fixed_point` continues in the slope (003 Fig. 18).
_REF_SLOPE = 0.04
#: Post-impact section state (theta_st+, dtheta_st+ sqrt(l/g), dtheta_sw+ sqrt(l/g)) of the Kisa gait at 0.04.
_REF_Z = (-0.2073985186, 1.0406442919 / math.sqrt(9.81), 0.4810330477 / math.sqrt(9.81))
#: Largest slope increment of one continuation stage in :func:`fixed_point`.
_CONT_STEP = 0.005
_TORQUE_STEP = 0.05  # N m per continuation stage in the constant torques


def _solve_fixed(bp: CompassBiped, guess: NDArray[np.float64]) -> NDArray[np.float64]:
    """Newton-type shooting (MINPACK hybrd) on P(z) - z = 0; ValueError if it does not converge."""

    def gap(z: NDArray[np.float64]) -> NDArray[np.float64]:
        try:
            return return_map(bp, z) - z
        except RuntimeError:
            return np.full(3, 1e3)

    z, _, _, msg = fsolve(gap, guess, full_output=True, xtol=1e-13)
    # judged by the residual: from a guess already at the root (continuation) hybrd stalls at the integration noise
    # floor (~1e-12) and reports "not making good progress" although the gait is found
    if np.max(np.abs(gap(z))) > 1e-9:
        raise ValueError(f"fixed-point shooting failed at slope {bp.slope!r}: {msg}")
    return z


def _continue(bp: CompassBiped, z0: NDArray[np.float64], slope0: float) -> NDArray[np.float64]:
    """Natural-parameter continuation in the slope from a fixed point z0 at slope0 to bp.slope, stages of at most
    ``_CONT_STEP`` rad, each Newton guess linearly extrapolated from the previous two fixed points."""
    stages = max(1, math.ceil(abs(bp.slope - slope0) / _CONT_STEP))
    zs = [np.asarray(z0, dtype=float)]
    for slope in np.linspace(slope0, bp.slope, stages + 1)[1:]:
        guess = zs[-1] if len(zs) == 1 else 2.0 * zs[-1] - zs[-2]
        zs.append(_solve_fixed(replace(bp, slope=float(slope)), guess))
    return zs[-1]


def _continue_torques(bp: CompassBiped, z0: NDArray[np.float64]) -> NDArray[np.float64]:
    """Continuation from the passive fixed point z0 of bp's geometry to bp's constant torques, stages of at most
    ``_TORQUE_STEP`` N m, guesses extrapolated as in :func:`_continue`."""
    stages = math.ceil(max(abs(bp.tau_ankle), abs(bp.tau_hip)) / _TORQUE_STEP)
    zs = [np.asarray(z0, dtype=float)]
    for frac in np.linspace(0.0, 1.0, stages + 1)[1:]:
        guess = zs[-1] if len(zs) == 1 else 2.0 * zs[-1] - zs[-2]
        zs.append(_solve_fixed(replace(bp, tau_ankle=frac * bp.tau_ankle, tau_hip=frac * bp.tau_hip), guess))
    return zs[-1]


@lru_cache(maxsize=256)
def _fixed_point_cached(bp: CompassBiped, guess: tuple[float, float, float] | None) -> tuple[float, ...]:
    if guess is not None:
        return tuple(_solve_fixed(bp, np.array(guess)))
    rate = math.sqrt(bp.gravity / bp.l)
    ref_guess = np.array([_REF_Z[0], _REF_Z[1] * rate, _REF_Z[2] * rate])
    passive = replace(bp, tau_ankle=0.0, tau_hip=0.0)
    ref = _solve_fixed(replace(passive, slope=_REF_SLOPE), ref_guess)
    return tuple(_continue_torques(bp, _continue(passive, ref, _REF_SLOPE)))


def fixed_point(bp: CompassBiped, guess: ArrayLike | None = None) -> NDArray[np.float64]:
    """Period-1 gait x* = (theta_st+, theta_sw+, dtheta_st+, dtheta_sw+) just after the impact: a fixed point
    of the Poincaré map 003 eq 4.18 (passive, 003 eq 4.19, unless bp has constant torques), found by Newton
    shooting on the 3-D post-impact section (:func:`return_map`), not by 003's grid search (Sec. 4.4.2).

    ``guess``: a 3-vector z on the section or a 4-vector x. Default: the 003 Fig. 18 gait (slope 0.04, rates scaled
    by sqrt(g/l)), solved for bp's masses and lengths, continued in the slope to bp.slope, then in the torques from 0
    to bp's (:func:`_continue_torques`); this reaches the
    stable (long-step) gait for m_h/m_l = 2, a = b (003 and Goswami et al. 1996/98) over slopes 0.005..0.0766.
    ValueError if the shooting does not converge.
    """
    validate(bp)
    if guess is not None:
        g = np.asarray(guess, dtype=float)
        g = g[[0, 2, 3]] if g.size == 4 else g
        z = _fixed_point_cached(bp, (float(g[0]), float(g[1]), float(g[2])))
    else:
        z = _fixed_point_cached(bp, None)
    return _section_state(bp, z)


def _jacobian(bp: CompassBiped, z: NDArray[np.float64], eps: float) -> NDArray[np.float64]:
    """dP/dz of :func:`return_map` by central differences with step eps."""
    return central_jacobian(lambda zz: return_map(bp, zz), z, eps)


@lru_cache(maxsize=256)
def _eigenvalues_cached(bp: CompassBiped, z: tuple[float, float, float], eps: float) -> tuple[complex, ...]:
    return tuple(sort_eigenvalues(np.linalg.eigvals(_jacobian(bp, np.array(z), eps)).astype(complex)))


def eigenvalues(bp: CompassBiped, x_star: ArrayLike | None = None, eps: float = 1e-6) -> NDArray[np.complex128]:
    """The 3 eigenvalues (Floquet multipliers) of the post-impact section map at the gait x* (default
    :func:`fixed_point`), by central finite differences with step eps; sorted by modulus, descending (conjugate
    pairs: positive imaginary part first). Stability of the gait of 003 eq 4.18 (003 gives no multipliers;
    Goswami et al. 1996/98 do). Computed once per (model, state, step) and process: a new array each call."""
    x = fixed_point(bp) if x_star is None else np.asarray(x_star, dtype=float)
    z = x[[0, 2, 3]]
    return np.array(_eigenvalues_cached(bp, (float(z[0]), float(z[1]), float(z[2])), float(eps)), dtype=complex)


def period_doubling_slope(m_h: float, m_l: float, a: float, b: float, lo: float, hi: float) -> float:
    """Slope (rad) in (lo, hi) at which a multiplier of the passive gait crosses -1 (first period doubling of the
    Goswami et al. 1998 bifurcation cascade; g = 9.81).

    The gait is continued in the slope (see :func:`fixed_point`) and the root of det(J + I) = prod(lambda_i + 1)
    (J = the post-impact section Jacobian; a complex pair contributes |lambda + 1|^2 > 0) is bracketed on a grid
    of spacing <= 0.005 rad and refined by Brent's method. ValueError if det(J + I) keeps its sign on [lo, hi].
    """
    base = CompassBiped(m_h, m_l, a, b, lo)
    validate(base)
    known: dict[float, NDArray[np.float64]] = {}

    def flip(slope: float) -> float:
        bp = replace(base, slope=slope)
        nearest = min(known, key=lambda s: abs(s - slope)) if known else None
        z = np.asarray(_fixed_point_cached(bp, None)) if nearest is None else _continue(bp, known[nearest], nearest)
        known[slope] = z
        return float(np.linalg.det(_jacobian(bp, z, 1e-6) + np.eye(3)))

    grid = np.linspace(lo, hi, max(2, math.ceil((hi - lo) / _CONT_STEP) + 1))
    values = [flip(float(s)) for s in grid]
    for k in range(len(grid) - 1):
        if values[k] * values[k + 1] < 0.0:
            return float(brentq(flip, grid[k], grid[k + 1], xtol=1e-9))
    raise ValueError(f"no multiplier crosses -1 for slopes in [{lo!r}, {hi!r}]")
