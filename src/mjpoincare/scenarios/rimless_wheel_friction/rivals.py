"""The nearest wrong physics each check of ``rimless-wheel-friction`` must reject, and the error it would show.

Source: 002 = Gamus & Or (2015), Sec. 3 (sticking map eqs 15-17, forces eq 19, friction ratio eqs 22-23, sticking
impulse eq 25) and Appendix A (slipping stance eq 42, impacts eqs 43-45 corrected).

* The gait (``gait_type``, ``midstance_rate``, ``eigenvalue``, ``phase_sequence``): the other side of the stick/slip
  divide. Where the gait slips (B, C, D) the rival sticks throughout (mu = inf: Type A, eqs 15-17, beta^2 = 0.734
  against the Type B multiplier 0.762 at the defaults); where it sticks (A) the rival's friction lies just below the
  A/B boundary max(mu_c, |sigma~|) (eqs 23, 25), where a short slip precedes each impact (Type B).
* ``impact_kind``: where the impact sticks, friction just below the sticking impulse ratio |sigma~| (eq 25), so the
  impact slips (eq 45); where it slips, the sticking impact of eq 43 (mu = inf).
* ``slip_onset``: the onset read off the sticking orbit (eq 22 on the eq 16 orbit reaching -mu), as 002 Sec. 3.2 reads
  it, instead of the Type B gait's own stance.
* ``critical_friction``, ``dx_per_step``: the slope made by adding the downhill component g sin(alpha) to an untilted
  gravity instead of rotating it: slope atan(sin alpha) under gravity g sqrt(1 + sin^2 alpha).
* ``sliding_contact_law``: MuJoCo's contact law without its regulariser (a hard cone, jar_n = mu |jar_t|).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from mjpoincare.analysis.theory import rimless_wheel_friction as theory
from mjpoincare.scenarios.base import Rival, Values
from mjpoincare.scenarios.rimless_wheel_friction.rollout import friction_wheel

#: Relative step of the rival's friction across a boundary.
ACROSS = 1e-3
_GRID = 2001


@lru_cache(maxsize=64)
def _gait(w: theory.FrictionWheel) -> theory.Gait | None:
    """The stable gait ``w`` settles on (the scenario's reference gait), None if it has none."""
    gaits = theory.attractors(w)
    return gaits[0] if gaits else None


def _other_side(w: theory.FrictionWheel) -> theory.FrictionWheel:
    """The wheel across the stick/slip divide: no slip (mu = inf) where the gait slips, else mu just below the A/B
    boundary max(mu_c, |sigma~|) (002 eqs 23, 25)."""
    gait = _gait(w)
    if gait is not None and gait.kind != "A":
        return replace(w, mu=math.inf)
    edge = max(theory.critical_friction(replace(w, mu=math.inf))[0], abs(theory.impulse_ratio(w.spokes, w.kappa)))
    return replace(w, mu=edge * (1.0 - ACROSS))


def _impact_flipped(w: theory.FrictionWheel) -> theory.FrictionWheel:
    """Friction just below |sigma~| (002 eq 25) where the gait's impact sticks, no slip (eq 43) where it slips."""
    gait = _gait(w)
    if gait is not None and gait.impact == "slipping":
        return replace(w, mu=math.inf)
    return replace(w, mu=abs(theory.impulse_ratio(w.spokes, w.kappa)) * (1.0 - ACROSS))


def _tilt_lost(w: theory.FrictionWheel) -> tuple[theory.FrictionWheel, float]:
    """The wheel on slope atan(sin alpha), and sqrt(g'/g) = (1 + sin^2 alpha)^(1/4) for its gravity
    g' = g sqrt(1 + sin^2 alpha): its speeds in the true wheel's units of 002 are its nondimensional ones times that."""
    return replace(w, slope=math.atan(math.sin(w.slope))), (1.0 + math.sin(w.slope) ** 2) ** 0.25


def _differs(value: Callable[[theory.Gait], object], rival: Callable[[theory.FrictionWheel], theory.FrictionWheel]
             ) -> Callable[[Values], float]:
    """A category check's distance: 1.0 where the rival's gait has another ``value`` (or no gait), else 0.0."""

    def distance(params: Values) -> float:
        w = friction_wheel(params)
        right, wrong = _gait(w), _gait(rival(w))
        if right is None:
            return math.nan
        return 1.0 if wrong is None or value(wrong) != value(right) else 0.0

    return distance


def _largest_multiplier(gait: theory.Gait) -> complex:
    return complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])


def _midstance_rate(params: Values) -> float:
    w = friction_wheel(params)
    right, wrong = _gait(w), _gait(_other_side(w))
    if right is None or wrong is None:
        return math.nan
    return abs(wrong.midstance_rate - right.midstance_rate) / abs(right.midstance_rate)


def _eigenvalue(params: Values) -> float:
    w = friction_wheel(params)
    right, wrong = _gait(w), _gait(_other_side(w))
    if right is None or wrong is None:
        return math.nan
    return abs(_largest_multiplier(wrong) - _largest_multiplier(right))


def _sticking_onset(w: theory.FrictionWheel) -> float:
    """theta where the friction ratio of the sticking orbit (002 eq 22 on the eq 16 orbit) first reaches -mu (forward
    slip, f_t = -mu f_n); NaN if it never does."""
    grid = np.linspace(-w.phi, w.phi, _GRID)
    excess = -np.asarray(theory.force_ratio(w, grid)) - w.mu
    above = np.nonzero(excess >= 0.0)[0]
    if not above.size:
        return math.nan
    i = int(above[0])
    if i == 0:
        return float(grid[0])
    return float(brentq(lambda th: -float(theory.force_ratio(w, th)) - w.mu, grid[i - 1], grid[i], xtol=1e-14))


def _slip_onset(params: Values) -> float:
    w = friction_wheel(params)
    gait = _gait(w)
    if gait is None or gait.kind != "B":
        return math.nan
    return abs(_sticking_onset(w) - gait.phase_angles[-1])


def _critical_friction(params: Values) -> float:
    w = replace(friction_wheel(params), mu=math.inf)
    right = theory.critical_friction(w)[0]
    return abs(theory.critical_friction(_tilt_lost(w)[0])[0] - right) / right


def _dx_per_step(params: Values) -> float:
    w = friction_wheel(params)
    right = _gait(w)
    rival, scale = _tilt_lost(w)
    wrong = _gait(rival)
    if right is None or wrong is None or not right.kind.startswith("D") or not wrong.kind.startswith("D"):
        return math.nan
    return abs(scale * wrong.dx_per_step - right.dx_per_step) / abs(right.dx_per_step)


_STICK_SLIP = ("the other side of the stick/slip divide: no slip (mu = inf, Type A, 002 eqs 15-17) where the gait "
               "slips; mu just below the A/B boundary max(mu_c, |sigma~|) (eqs 23, 25, Type B) where it sticks")
_TILT = "slope by adding g sin(alpha) to an untilted gravity: slope atan(sin alpha), gravity g sqrt(1 + sin^2 alpha)"

RIVALS: dict[str, Rival] = {
    "gait_type": Rival(physics=_STICK_SLIP + ": the settled type", distance=_differs(lambda g: g.kind, _other_side)),
    "midstance_rate": Rival(physics=_STICK_SLIP + ": the mid-stance rate", distance=_midstance_rate),
    "eigenvalue": Rival(physics=_STICK_SLIP + ": the largest multiplier", distance=_eigenvalue),
    "impact_kind": Rival(
        physics="friction just below the sticking impulse ratio |sigma~| (002 eq 25) where the impact sticks, so it "
                "slips (eq 45); the sticking impact (eq 43, mu = inf) where it slips",
        distance=_differs(lambda g: g.impact, _impact_flipped)),
    "phase_sequence": Rival(physics=_STICK_SLIP + ": the stick/slip phases of a step (eq 35)",
                            distance=_differs(lambda g: g.phases, _other_side)),
    "sliding_contact_law": Rival(
        physics="MuJoCo's contact law without its regulariser (hard cone, jar_n = mu |jar_t|, analysis/soft_contact "
                "eq 1 with R_n = 0): on a sliding row at rest normally jar_n = -R_n f_n < 0, so its residual is 1",
        distance=lambda _params: 1.0),
    "slip_onset": Rival(physics="slip onset read off the sticking orbit (002 eq 22 on the eq 16 orbit reaching -mu) "
                                "instead of the Type B gait's own stance", distance=_slip_onset,
                       weak="the sticking orbit's onset lies inside the onset's tolerance of the slipping gait's; "
                            "the mid-stance rate, the eigenvalue and the gait type tell sticking from slipping"),
    "dx_per_step": Rival(physics=_TILT + ": Delta x_dot of the D gait (002 Fig. 3.6)", distance=_dx_per_step),
    "critical_friction": Rival(physics=_TILT + ": mu_c of 002 eq 23", distance=_critical_friction),
}
