"""Rivals of ``compass-biped``'s checks: the nearest wrong physics for each, and the error it would show.

Source: 003 = Kiša (2020), *Mathematical modelling of walking robots*, MSc thesis, Ch. 4: the swing EoM (eq 4.5), the
heel-strike impact (eqs 4.15-4.17) and the gait of eq 4.18 / Fig. 18 (Goswami et al. 1996/98 model). Each rival's
gait is found with the theory's own Newton shooting (:mod:`mjpoincare.analysis.theory.compass_biped`) at the changed
parameters; the trailing foot's rival falls with the free biped's acceleration at release (the same acceleration the
check's tolerance uses).
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np

from mjpoincare.analysis.eigenvalues import eigenvalue_error
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.analysis.theory.compass_biped import flight
from mjpoincare.scenarios.base import Rival, Values
from mjpoincare.scenarios.compass_biped.controller import RELEASE_WINDOW
from mjpoincare.scenarios.compass_biped.runs import biped

#: Relative slope error of the slope rival (a gravity vector tilted 1% too far: 0.023 deg at 0.04 rad).
SLOPE_ERROR = 0.01
#: g of the gravity rival: 9.80 instead of 9.81 m/s^2 (002's value, which the friction biped's build passes).
RIVAL_GRAVITY = 9.80

@lru_cache(maxsize=32)
def _gait(bp: theory.CompassBiped) -> tuple[np.ndarray, np.ndarray, float, float]:
    """(x*, multipliers, step period, step length) of the period-1 gait (003 eq 4.18)."""
    x = theory.fixed_point(bp)
    return x, theory.eigenvalues(bp, x), theory.step_period(bp, x), theory.step_length(bp, x)


def _steeper(bp: theory.CompassBiped) -> theory.CompassBiped:
    return replace(bp, slope=bp.slope * (1.0 + SLOPE_ERROR))


def _fixed_point(params: Values) -> float:
    """max |x*_rival - x*| on the post-impact state (003 eq 4.18), slope 1% steeper."""
    bp = biped(params)
    return float(np.max(np.abs(_gait(_steeper(bp))[0] - _gait(bp)[0])))


def _eigenvalues(params: Values) -> float:
    """max |lambda_rival - lambda| over the matched multipliers, slope 1% steeper."""
    bp = biped(params)
    lam = _gait(bp)[1]
    return eigenvalue_error(lam, _gait(_steeper(bp))[1])


def _step_period(params: Values) -> float:
    """|T_rival/T - 1| with g = 9.80 (the swing time scales with sqrt(l/g))."""
    bp = biped(params)
    return abs(_gait(replace(bp, gravity=RIVAL_GRAVITY))[2] / _gait(bp)[2] - 1.0)


def _step_length(params: Values) -> float:
    """|S_rival/S - 1| (S = 2 l sin alpha*, 003 eqs 4.15-4.17), slope 1% steeper."""
    bp = biped(params)
    return abs(_gait(_steeper(bp))[3] / _gait(bp)[3] - 1.0)


def _trailing_foot_release(params: Values) -> float:
    """Depth the released trailing foot falls from rest over the check's window, |a| W^2/2, a = its slope-normal
    acceleration at the exact pre-impact state (point foot, r = 0)."""
    bp = biped(params)
    x_minus = theory.step(bp, _gait(bp)[0]).x_minus
    return max(0.0, -flight.release_acceleration(bp, x_minus, 0.0)) * RELEASE_WINDOW**2 / 2.0


_SLOPE = "a slope 1% steeper than the model's (gravity tilted by 1.01 gamma; 003 eq 4.5's G and the guard eq 4.6)"

RIVALS: dict[str, Rival] = {
    "fixed_point": Rival(physics=_SLOPE, distance=_fixed_point),
    "eigenvalues": Rival(physics=_SLOPE, distance=_eigenvalues,
                         weak="a 1 % steeper slope moves the multipliers by less than the eigenvalue tolerance the "
                              "fit through the soft impact needs at either preset; the fixed point tells the steeper "
                              "slope"),
    "step_period": Rival(physics="g = 9.80 instead of 9.81 m/s^2 (002's value; the swing of 003 eq 4.5 runs "
                         "sqrt(9.81/9.80) slower)", distance=_step_period,
                         weak="g 0.1 % low stretches the gait's time by 0.05 % and leaves its angles and multipliers "
                              "as they are (003 eq 4.5 in units of sqrt(l/g)): only the period sees it, and by half "
                              "the accurate preset's tolerance, the accuracy its preset search holds"),
    "step_length": Rival(physics=_SLOPE, distance=_step_length),
    "trailing_foot_release": Rival(
        physics="an impact law that leaves the trailing foot at rest instead of lifting it off (003 eqs 4.15-4.17 give "
                "it an upward speed), so the released foot falls through the slope from rest",
        distance=_trailing_foot_release),
}
