"""The theory's answer to a planted physics change (:mod:`mjpoincare.gate.power`): for each check of a gate case, the
error a simulator reproducing the planted physics exactly would show against the theory at the unplanted parameters,
in the check's own measure (relative, absolute, max-abs over matched multipliers, the fraction of a category that
differs), computed from the theory alone, as a :class:`~mjpoincare.scenarios.base.Rival`'s distance is.

A *theory plant* moves one parameter of a scenario's theory to ``p (1 + size)``: its effect on a check above the
check's tolerance is a failure the tolerance must show. A *control* is a change the theory and the model both cannot
see (:data:`CONTROLS`, each with the reason): its effect on every check is exactly 0, and it must be caught by
nothing. Every other plant (the time step, the contact's time constant and damping ratio, impratio, the cone, the
integrator, a dropped contact pair) is a change of the simulator the rigid-impact theories do not have: its effect
on every check is 0 by the theory, and only the baseline can see it.

Sources (docs/references.md): 001 = Coleman, Chatterjee & Ruina (1997), the 3D wheel; 002 = Gamus & Or (2015), the
friction wheel and the friction biped; 003 = Kiša (2020), the planar wheel and the compass biped; 000 = Coleman &
Holmes (1999), the slotted skate.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np

from mjpoincare.analysis.eigenvalues import eigenvalue_error
from mjpoincare.analysis.theory import compass_biped as biped_theory
from mjpoincare.analysis.theory import compass_biped_friction as friction_biped_theory
from mjpoincare.analysis.theory import rimless_wheel as wheel_theory
from mjpoincare.analysis.theory import rimless_wheel_3d as wheel3d_theory
from mjpoincare.analysis.theory import rimless_wheel_friction as friction_wheel_theory
from mjpoincare.analysis.theory import slotted_skate as skate_theory
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid
from mjpoincare.core.params import Values
from mjpoincare.scenarios.compass_biped import biped
from mjpoincare.scenarios.compass_biped_friction.gait_choice import friction, gait_name, solved_gait
from mjpoincare.scenarios.rimless_wheel.basin_judging import basin_flips
from mjpoincare.scenarios.rimless_wheel.runs import wheel
from mjpoincare.scenarios.rimless_wheel_3d import runs as wheel3d_runs
from mjpoincare.scenarios.rimless_wheel_friction.rollout import friction_wheel, rate_unit
from mjpoincare.scenarios.slotted_skate.design import skate

#: check -> the error an exact simulator of the planted physics shows (None: the theory's effect on this check is not
#: computed here).
Effects = dict[str, float | None]
#: ``(params, factor) -> effects``: the theory at the parameter x ``factor`` against the theory at ``params``.
Effect = Callable[[Values, float], Effects]

#: The integrator switch where the preset's implicitfast has nothing to treat implicitly.
_SAME_STEP = ("no force the integrator treats implicitly (no joint damping, no actuator with a velocity gain; contact "
              "damping is the constraint solver's): implicitfast and Euler take the same semi-implicit Euler step "
              "(MuJoCo's Computation chapter, Integrators), equal to rounding")

#: scenario -> change -> why neither the theory nor the model can see it: its effect on every check is exactly 0.
CONTROLS: Mapping[str, Mapping[str, str]] = {
    "rimless-wheel": {
        "mass_inertia": "one rigid body: its motion does not depend on its mass scale (003 eqs 3.3-3.11 have "
                        "no m), and MuJoCo's constraint impedance is mass-normalised",
        "friction": "the foot sticks (mu >= the friction the gait needs, 002 eqs 22-25) and the theory has no mu",
        "integrator": _SAME_STEP},
    "rimless-wheel-3d": {
        "mass_inertia": "one rigid body: its motion does not depend on its mass scale (001 is nondimensional in m)",
        "friction": "the foot sticks (mu >= the impact's |Pt|/Pn, 001 Sec. 3) and the theory has no mu"},
    "rimless-wheel-friction": {
        "mass_inertia": "one rigid body: its motion does not depend on its mass scale (002 eq 11 has no m)",
        "integrator": _SAME_STEP},
    "compass-biped": {
        "friction": "the feet stick (mu = 1 above the gait's demand) and the theory has no mu (003 Ch. 4)",
        "integrator": _SAME_STEP},
    # Not friction, though Gait A sticks throughout (mu = 1 above its mu_c = 0.175, 002 Sec. 4.1): its fast preset's
    # pyramidal cone builds each contact's rows from the normal and mu times the tangent (MuJoCo's Computation chapter,
    # friction cones), so mu moves a sticking contact's response. Measured: mu x 1.01 moves the fitted fixed point
    # by 1.1e-6 under the pyramidal cone and by 2e-14 (roundoff) under the elliptic one.
    "compass-biped-friction": {
        "integrator": _SAME_STEP},
    "slotted-skate": {
        "gravity": "the skate moves in the horizontal plane, its pegs joint equalities: gravity does no work (000 has "
                   "no g)",
        "mass_inertia": "one rigid body: its motion does not depend on its mass scale (000 is nondimensional in m)",
        "friction": "the model has no contact (its pegs are joint equalities)",
        "impratio": "the model has no contact (its pegs are joint equalities)",
        "cone": "the model has no contact (its pegs are joint equalities)",
        "contact_pair": "the model has no contact (its pegs are joint equalities)"},
}


def _relative(wrong: float, right: float) -> float:
    return abs(wrong - right) / abs(right)


def _matched(wrong: np.ndarray, right: np.ndarray) -> float:
    """max |lambda_wrong - lambda| over the multipliers matched to the theory's."""
    return eigenvalue_error(right, wrong)


def _differs(wrong: object, right: object) -> float:
    """A category check's error: 1 where the category differs (every judged sample with it), else 0."""
    return float(wrong != right)


def _scaled(params: Values, name: str, factor: float) -> dict[str, object]:
    return {**params, name: float(params[name]) * factor}


# -- rimless-wheel (003 Sec. 3; 002 Sec. 3.1 for the hub inertia) -----------------------------------------------------

def _planar_wheel(field: str, power: float = 1.0) -> Effect:
    """The planar wheel with ``field`` x factor^power: the fitted map (003 eqs 3.11-3.14; 002 eqs 14, 16, 17), the
    step period (003 eq 3.5) and the basins."""

    def effect(params: Values, factor: float) -> Effects:
        right = wheel(params)
        wrong = replace(right, **{field: getattr(right, field) * factor**power})
        star, star_wrong = wheel_theory.rolling_fixed_point(right), wheel_theory.rolling_fixed_point(wrong)
        return {"omega_post_impact": _relative(star_wrong, star),
                "eigenvalue": abs(wheel_theory.rolling_multiplier(wrong) - wheel_theory.rolling_multiplier(right)),
                "impact_coefficient": _relative(wrong.beta, right.beta),
                "step_period": _relative(wheel_theory.step_period(wrong, star_wrong),
                                         wheel_theory.step_period(right, star)),
                "basins": basin_flips(right, wrong)}

    return effect


# -- rimless-wheel-3d (001; nondimensional, rates in sqrt(g/l)) --------------------------------------------------------

def _wheel3d(name: str, power: float = 1.0) -> Effect:
    """The 3D wheel with parameter ``name`` x factor^power: the planar cycle (001 eqs 12-14), the exact mid-stance
    multipliers (Table 2) and the neutral heading (Table 1: lambda1 = 1 on both sides, so no heading check moves)."""

    def effect(params: Values, factor: float) -> Effects:
        changed = _scaled(params, name, factor**power)
        unit = wheel3d_runs.rate_unit(changed) / wheel3d_runs.rate_unit(params)  # the checks read rad/s

        def rate(p: Values, heading: float | None = None) -> float:
            return wheel3d_theory.midstance_pitch_rate(wheel3d_runs.wheel(p, heading))

        right, wrong = wheel3d_runs.wheel(params), wheel3d_runs.wheel(changed)
        eig, eig_wrong = hybrid.midstance_eigenvalues(right).named(), hybrid.midstance_eigenvalues(wrong).named()
        headings = wheel3d_runs.planar_headings(params)
        return {"pitch_rate": _relative(rate(changed) * unit, rate(params)),
                "bank": abs(wrong.bank - right.bank),
                "heading_eigenvalue": 0.0, "heading_drift": 0.0,
                **{k: abs(eig_wrong[k] - eig[k]) for k in ("wobble_modulus", "wobble_angle", "lambda5", "lambda2")},
                "planar_pitch_rate": max(_relative(rate(changed, h) * unit, rate(params, h)) for h in headings),
                "planar_bank": max(abs(wheel3d_runs.wheel(changed, h).bank - wheel3d_runs.wheel(params, h).bank)
                                   for h in headings)}

    return effect


# -- rimless-wheel-friction (002 Sec. 3, App. A; nondimensional, rates in omega_c) -------------------------------------

def _settled(w: friction_wheel_theory.FrictionWheel) -> friction_wheel_theory.Gait | None:
    """The stable gait the wheel settles on (the scenario's reference gait), None if it has none."""
    gaits = friction_wheel_theory.attractors(w)
    return gaits[0] if gaits else None


def _largest(gait: friction_wheel_theory.Gait) -> complex:
    return complex(gait.eigenvalues[np.argmax(np.abs(gait.eigenvalues))])


def _friction_wheel(name: str, power: float = 1.0) -> Effect:
    """The friction wheel with parameter ``name`` x factor^power: the gait it settles on (002 eqs 15-17, 35, 42-45),
    its mid-stance rate (read in the unplanted omega_c), multiplier, impact, phases, slip onset and mu_c (eq 23)."""

    def effect(params: Values, factor: float) -> Effects:
        changed = _scaled(params, name, factor**power)
        w, w_wrong = friction_wheel(params), friction_wheel(changed)
        right, wrong = _settled(w), _settled(w_wrong)
        unit = rate_unit(changed) / rate_unit(params)
        if right is None or wrong is None:
            return {}
        both = right.kind == wrong.kind
        mu_c = friction_wheel_theory.critical_friction(replace(w, mu=math.inf))[0]
        mu_c_wrong = friction_wheel_theory.critical_friction(replace(w_wrong, mu=math.inf))[0]
        return {"gait_type": _differs(wrong.kind, right.kind),
                "midstance_rate": _relative(wrong.midstance_rate * unit, right.midstance_rate),
                "eigenvalue": abs(_largest(wrong) - _largest(right)),
                "impact_kind": _differs(wrong.impact, right.impact),
                "phase_sequence": _differs(wrong.phases, right.phases),
                "sliding_contact_law": 0.0,  # MuJoCo's contact law against itself: no parameter of 002 enters
                "slip_onset": abs(wrong.phase_angles[-1] - right.phase_angles[-1]) if both and right.kind == "B"
                else None,
                "dx_per_step": _relative(wrong.dx_per_step * unit, right.dx_per_step)
                if both and right.kind.startswith("D") else None,
                "critical_friction": _relative(mu_c_wrong, mu_c)}

    return effect


# -- compass-biped (003 Ch. 4) -----------------------------------------------------------------------------------------

def _compass_biped(name: str) -> Effect:
    """The compass biped with parameter ``name`` x factor: its period-1 gait (003 eq 4.18), multipliers, step period
    and length; the trailing foot lifts off on both sides (003 eqs 4.15-4.17), so its release check does not move."""

    def effect(params: Values, factor: float) -> Effects:
        right, wrong = biped(params), biped(_scaled(params, name, factor))
        x, x_wrong = biped_theory.fixed_point(right), biped_theory.fixed_point(wrong)
        return {"fixed_point": float(np.max(np.abs(x_wrong - x))),
                "eigenvalues": _matched(biped_theory.eigenvalues(wrong, x_wrong), biped_theory.eigenvalues(right, x)),
                "step_period": _relative(biped_theory.step_period(wrong, x_wrong), biped_theory.step_period(right, x)),
                "step_length": _relative(biped_theory.step_length(wrong, x_wrong), biped_theory.step_length(right, x)),
                "trailing_foot_release": 0.0}

    return effect


# -- compass-biped-friction (002 Sec. 4) -------------------------------------------------------------------------------

def _friction_biped(field: str) -> Effect:
    """The friction biped's gait with its biped's ``field`` x factor, found by the theory's own Newton shooting from
    the gait's state (002 eqs 31-35): its legs-parallel state, 3 largest multipliers, step, speed and mu_c; the
    checks of the stance's force ratio and phases are not computed here."""

    def effect(params: Values, factor: float) -> Effects:
        right = solved_gait(gait_name(params), friction(params), float(params["kp"]), float(params["kd"]))
        bp = replace(right.biped, **{field: getattr(right.biped, field) * factor})
        wrong = (friction_biped_theory.find_gait(bp, right.z[:3], right.actuation) if right.kind == "A" else
                 friction_biped_theory.find_gait(bp, right.z[: right.jacobian.shape[0]], right.actuation,
                                                 right.jacobian))
        lam = right.eigenvalues[:3]

        def demand(g: friction_biped_theory.Gait) -> float:
            return friction_biped_theory.critical_friction(g.biped, g.z, g.actuation).stance

        return {"fixed_point": float(np.max(np.abs(friction_biped_theory.legs_parallel(wrong)[0]
                                                    - friction_biped_theory.legs_parallel(right)[0]))),
                "eigenvalues": _matched(wrong.eigenvalues[:3], lam),
                "gait_stability": _differs(wrong.spectral_radius < 1.0, right.spectral_radius < 1.0),
                "step_period": _relative(wrong.record.period, right.record.period),
                "step_length": _relative(wrong.record.step_length, right.record.step_length),
                "speed": _relative(friction_biped_theory.average_speed(wrong.record),
                                   friction_biped_theory.average_speed(right.record)),
                "critical_friction": _relative(demand(wrong), demand(right)),
                "friction_ratio_window": None, "phase_sequence": None, "phase_times": None, "impact_kind": None,
                "impact_slip": None}

    return effect


# -- slotted-skate (000) -----------------------------------------------------------------------------------------------

def _skate_gyration(params: Values, factor: float) -> Effects:
    """The skate with its radius of gyration rho x factor: sigma4 (000 eq 3.10) in both directions and its
    stability verdicts (3.11-3.12); the batch's heading, energy and reversal checks are not computed here."""
    right, wrong = skate(params), skate(_scaled(params, "rho", factor))
    out: Effects = {}
    for direction, forward in (("forward", True), ("backward", False)):
        s4, s4_wrong = skate_theory.sigma4(right, forward), skate_theory.sigma4(wrong, forward)
        out[f"sigma4_{direction}"] = out[f"sigma4_fit_{direction}"] = abs(s4_wrong - s4)
        out[f"stability_{direction}"] = _differs(abs(s4_wrong) < 1.0, abs(s4) < 1.0)
    return out | dict.fromkeys(("energy_loss", "heading", "reversals", "collisions_before_reversal", "final_speed",
                                "final_reversals"))


#: scenario -> change -> the theory's effect of the change (a theory plant). ``gyration`` scales the tracked body's
#: rotational inertia by (1 + size)^2 (its radius of gyration by 1 + size, the mass unchanged), ``slope`` rotates
#: gravity in the plane of motion (every sloped model realizes its slope as gravity's direction), ``gravity`` and
#: ``hip_mass`` scale g and the hip's mass, ``friction`` the Coulomb coefficient.
THEORY: Mapping[str, Mapping[str, Effect]] = {
    "rimless-wheel": {"slope": _planar_wheel("slope"), "gyration": _planar_wheel("gyration"),
                      "gravity": _planar_wheel("gravity")},
    "rimless-wheel-3d": {"slope": _wheel3d("slope"), "gyration": _wheel3d("J", 2.0), "gravity": _wheel3d("gravity")},
    "rimless-wheel-friction": {"slope": _friction_wheel("slope"), "gyration": _friction_wheel("kappa", 2.0),
                               "gravity": _friction_wheel("gravity"), "friction": _friction_wheel("mu")},
    "compass-biped": {"slope": _compass_biped("slope"), "gravity": _compass_biped("gravity"),
                      "hip_mass": _compass_biped("m_h")},
    "compass-biped-friction": {"slope": _friction_biped("slope"), "gravity": _friction_biped("g")},
    "slotted-skate": {"gyration": _skate_gyration},
}


def kind(scenario: str, change: str) -> str:
    """What a change is to a scenario: ``theory`` (a parameter of its theory), ``control`` (invisible to the theory
    and the model, :data:`CONTROLS`) or ``simulator`` (a change the theory does not have)."""
    if change in CONTROLS.get(scenario, {}):
        return "control"
    return "theory" if change in THEORY.get(scenario, {}) else "simulator"


def effects(scenario: str, change: str, params: Values, size: float | None) -> Effects:
    """Every check's error an exact simulator of the change shows against the theory at ``params``: the theory
    plant's :data:`THEORY` effect at factor 1 + size; 0 for a control or a change of the simulator (empty: the
    caller fills in the case's checks)."""
    if kind(scenario, change) != "theory" or size is None:
        return {}
    return THEORY[scenario][change](params, 1.0 + size)
