"""Rivals of ``compass-biped-friction``'s checks: the nearest wrong friction physics for each, and its error.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Secs. 4-5: the stick-slip stance (eqs 2, 31-35), the frictional heel strike (sticking eqs 37-38, slipping eqs 39-40),
mu_c of Sec. 4.1, the stability of Sec. 4.2 and the cost of transport of eq 29. Every rival gait is found with the
theory's own solvers (:func:`~mjpoincare.analysis.theory.compass_biped_friction.paper_gait`,
:func:`~mjpoincare.analysis.theory.compass_biped_friction.find_gait`) at a changed friction or actuation; the impact-law
rivals apply the other impact law of 002 to the gait's own pre-impact state. The phase checks classify the rival's
stance on the fast preset's time grid, as the scenario's ``checks_at`` does.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np

from mjpoincare.analysis.eigenvalues import eigenvalue_error
from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.compass_biped_friction.dynamics import _model
from mjpoincare.analysis.theory.compass_biped_friction.stance_measurements import (
    RELEASE_SKIP,
    analytic_ratio,
    classified_pattern,
)
from mjpoincare.scenarios.base import Rival, Values
from mjpoincare.scenarios.compass_biped_friction.gait_choice import friction, gait_name, solved_gait
from mjpoincare.scenarios.compass_biped_friction.presets import PRESETS

#: Relative friction error of the friction rival: a Coulomb coefficient 5% low (for a gait sticking throughout, whose
#: gait does not depend on mu above its mu_c: 5% below its mu_c, where its stance first slips).
FRICTION_ERROR = 0.05
#: Gait I's friction rival for the phase checks: 0.12, where its stance slips as visibly as Gait B's (002 Fig. 5.1).
GAIT_I_SLIPPING_MU = 0.12
#: Just below the frictions at which Gaits B and I lose stability (0.1104, 0.1035; 002 Secs. 4.2, 5).
UNSTABLE_MU = {"A": 0.105, "B": 0.105, "I": 0.10}

_Key = tuple[str, float, float, float]


def _key(params: Values) -> _Key:
    return gait_name(params), friction(params), float(params["kp"]), float(params["kd"])


def _own(key: _Key) -> theory.Gait:
    return solved_gait(*key)


@lru_cache(maxsize=16)
def _friction_rival(key: _Key) -> theory.Gait:
    """The gait with the Coulomb coefficient 5% low (a gait sticking throughout: 5% below its mu_c)."""
    g = _own(key)
    if g.kind == "A":
        mu_c = theory.critical_friction(g.biped, g.z, g.actuation).stance
        return theory.find_gait(replace(g.biped, mu=(1.0 - FRICTION_ERROR) * mu_c), g.z[:3], g.actuation)
    return theory.find_gait(replace(g.biped, mu=(1.0 - FRICTION_ERROR) * g.biped.mu), g.z[: g.jacobian.shape[0]],
                            g.actuation, g.jacobian)


@lru_cache(maxsize=16)
def _phase_rival(key: _Key) -> theory.Gait:
    """A gait just across a friction bound of 002, where the stance phases change: A below its mu_c (friction rival),
    B above it (Gait A), C with the sticking impact of the A/B branch at its mu, I at 0.12, II 5% low."""
    name, mu = key[0], key[1]
    if name in ("A", "II"):
        return _friction_rival(key)
    if name == "B":
        return theory.paper_gait("A", math.inf)
    if name == "C":
        return theory.paper_gait("B", mu)
    if name == "I":
        return theory.paper_gait("I", GAIT_I_SLIPPING_MU)
    raise ValueError(f"no phase rival for gait {name}")


@lru_cache(maxsize=16)
def _stability_rival(key: _Key) -> theory.Gait:
    """A gait on the other side of |lambda|max = 1 (002 Sec. 4.2): A, B, I just below their stability loss; C the
    sticking-impact A/B branch at its mu (stable); II with Gait I's torques (stable); III without its PD tracking,
    i.e. the passive Gait C it tracks (unstable)."""
    name, mu = key[0], key[1]
    if name in UNSTABLE_MU:
        return theory.paper_gait("B" if name == "A" else name, UNSTABLE_MU[name])
    if name == "C":
        return theory.paper_gait("B", mu)
    if name == "II":
        return theory.paper_gait("I", mu)
    return theory.paper_gait("C", theory.GAIT_III_REFERENCE_MU)


def _fast_dt() -> float:
    return float(PRESETS["fast"]["timestep"])


def _relative(rival: float, value: float) -> float:
    return abs(rival - value) / abs(value)


def _fixed_point(params: Values) -> float:
    """max |y*_rival - y*| on the legs-parallel state (theta1, theta1_dot, -theta2_dot), friction 5% low."""
    key = _key(params)
    return float(np.max(np.abs(theory.legs_parallel(_friction_rival(key))[0] - theory.legs_parallel(_own(key))[0])))


def _eigenvalues(params: Values) -> float:
    """max |lambda_rival - lambda| over the 3 largest multipliers, matched; friction 5% low."""
    key = _key(params)
    lam = _own(key).eigenvalues[:3]
    return eigenvalue_error(lam, _friction_rival(key).eigenvalues[:3])


def _category(changed: bool) -> float:
    return 1.0 if changed else 0.0


def _gait_stability(params: Values) -> float:
    """1 where the rival's stability class (|lambda|max < 1) differs from the gait's."""
    key = _key(params)
    return _category((_own(key).spectral_radius < 1.0) != (_stability_rival(key).spectral_radius < 1.0))


def _step_period(params: Values) -> float:
    key = _key(params)
    return _relative(_friction_rival(key).record.period, _own(key).record.period)


def _step_length(params: Values) -> float:
    key = _key(params)
    return _relative(_friction_rival(key).record.step_length, _own(key).record.step_length)


def _speed(params: Values) -> float:
    key = _key(params)
    return _relative(theory.average_speed(_friction_rival(key).record), theory.average_speed(_own(key).record))


def _cost_of_transport(params: Values) -> float:
    key = _key(params)
    rival, own = _friction_rival(key), _own(key)
    return _relative(theory.cost_of_transport(rival.biped, rival.record),
                     theory.cost_of_transport(own.biped, own.record))


def _friction_ratio_window(params: Values) -> float:
    """Gait A: the window's max |f_t/f_n| (stance minus 5 ms at each end) against the rival's, whose slip phases hold
    the ratio at mu (002 eq 35): its stance-wide max (the ratio peaks inside the window)."""
    key = _key(params)
    own = _own(key)
    window = float(np.max(np.abs(analytic_ratio(own, np.linspace(RELEASE_SKIP, own.record.period - RELEASE_SKIP,
                                                                    2000)))))
    return _relative(_friction_rival(key).record.max_ratio, window)


def _critical_friction(params: Values) -> float:
    """Gait A: mu_c (002 Sec. 4.1) against the rival's max |f_t/f_n| (its slip saturates at mu = 0.95 mu_c)."""
    key = _key(params)
    own = _own(key)
    mu_c = theory.critical_friction(own.biped, own.z, own.actuation).stance
    return _relative(_friction_rival(key).record.max_ratio, mu_c)


def _labels(g: theory.Gait) -> list[str]:
    return [label for label, _ in classified_pattern(g, _fast_dt())]


def _rival_impact(g: theory.Gait) -> tuple[theory.FrictionBiped, ss.ImpactResult]:
    """The gait's pre-impact state through the other impact law of 002: a sticking heel strike (eqs 37-38) where the
    gait's slips; where it sticks, a friction 5% below the impulse ratio |sigma~| (002 Sec. 4.1) for the heel strike
    and the stance after it, so that it slips (eqs 39-40; the gait's own mu may admit no slipping stance: Gait A's
    at mu = 1 is a Painleve case). Returns the rival's biped and impact."""
    rec = g.record
    sticking = rec.impact == "slipping"
    bp = g.biped if sticking else replace(g.biped, mu=(1.0 - FRICTION_ERROR) * abs(rec.impulse_ratio))
    q = np.concatenate([rec.q_pre, [rec.period, rec.actuator_work]])
    qd = np.concatenate([rec.qd_pre, [1.0, 0.0]])
    return bp, ss.impact(_model(bp, g.actuation), q, qd, math.inf if sticking else bp.mu)


def _with_impact(g: theory.Gait) -> theory.Gait:
    """The step from the rival impact's post-impact state (:func:`_rival_impact`), relabelled (002 Sec. 4)."""
    bp, imp = _rival_impact(g)
    z = np.array([g.record.theta_star, -imp.qd_plus[1], -imp.qd_plus[0], imp.swing_velocity[0]])
    return replace(g, biped=bp, z=z, record=theory.step(bp, z, g.actuation))


def _phase_sequence(params: Values) -> float:
    """1 where the rival's stance phases, classified as the check classifies them, differ from the gait's; Gait III:
    the step after a sticking heel strike (002 eqs 37-38) at its pre-impact state."""
    key = _key(params)
    own = _own(key)
    rival = _with_impact(own) if key[0] == "III" else _phase_rival(key)
    return _category(_labels(rival) != _labels(own))


def _phase_times(params: Values) -> float:
    """max |t_rival - t| over the classified phase switch times, friction 5% low (same phases)."""
    key = _key(params)
    own, rival = classified_pattern(_own(key), _fast_dt()), classified_pattern(_friction_rival(key), _fast_dt())
    if [lab for lab, _ in own] != [lab for lab, _ in rival]:
        raise ValueError(f"the friction rival of gait {key[0]} changes its phases")
    return float(max(abs(a - b) for (_, a), (_, b) in zip(own[1:], rival[1:], strict=True)))


def _impact_kind(params: Values) -> float:
    """1 where the other impact law of 002 at the gait's pre-impact state gives the other impact kind."""
    own = _own(_key(params))
    return _category(_rival_impact(own)[1].kind != own.record.impact)


def _impact_slip(params: Values) -> float:
    """|slide_rival - slide| of the new stance foot over the first RELEASE_SKIP after the heel strike (002 eq 27),
    the rival's from the other impact law's post-impact state."""
    own = _own(_key(params))
    rival = _with_impact(own)
    slide = float(theory.stance_foot_motion(own.biped, own.z, [RELEASE_SKIP], own.actuation)[0][0])
    slide_rival = float(theory.stance_foot_motion(rival.biped, rival.z, [RELEASE_SKIP], own.actuation)[0][0])
    return abs(slide_rival - slide)


_FRICTION = ("a Coulomb coefficient 5% low (002 eqs 31-35, 37-40; for a gait sticking throughout, 5% below its mu_c "
             "of 002 Sec. 4.1, where its stance first slips)")
_IMPACT = ("the other impact law of 002 at the gait's pre-impact state: a slipping heel strike (eqs 39-40, friction 5% "
           "below the impulse ratio |sigma~|) where the gait's sticks, a sticking one (eqs 37-38) where it slips")

RIVALS: dict[str, Rival] = {
    "fixed_point": Rival(physics=_FRICTION, distance=_fixed_point),
    "eigenvalues": Rival(physics=_FRICTION, distance=_eigenvalues),
    "gait_stability": Rival(
        physics="a gait across |lambda|max = 1 (002 Sec. 4.2): A, B, I just below their stability-loss friction; C "
                "the coexisting sticking-impact gait; II with Gait I's torques; III without its PD tracking",
        distance=_gait_stability),
    "step_period": Rival(physics=_FRICTION, distance=_step_period),
    "step_length": Rival(physics=_FRICTION, distance=_step_length),
    "speed": Rival(physics=_FRICTION, distance=_speed),
    "cost_of_transport": Rival(physics=_FRICTION, distance=_cost_of_transport),
    "friction_ratio_window": Rival(physics=_FRICTION, distance=_friction_ratio_window),
    "critical_friction": Rival(physics=_FRICTION, distance=_critical_friction),
    "phase_sequence": Rival(
        physics="a friction across a bound of 002 where the stance phases change (A below mu_c, B above it, C's "
                "sticking-impact gait, I at 0.12, II 5% low; III: a sticking heel strike, eqs 37-38)",
        distance=_phase_sequence),
    "phase_times": Rival(physics=_FRICTION, distance=_phase_times),
    "impact_kind": Rival(physics=_IMPACT, distance=_impact_kind),
    "impact_slip": Rival(physics=_IMPACT, distance=_impact_slip),
}
