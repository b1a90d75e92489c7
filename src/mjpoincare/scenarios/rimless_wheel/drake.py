"""The rimless wheel's outside peer: Drake's hybrid ``RimlessWheel`` (:mod:`mjpoincare.engines.peers.drake`).

Drake's wheel is the point-mass wheel of 003 Sec. 3 (kappa = 0 in 002's terms, 002 eqs 12, 14). Its values are set
beside the suite's theory for that model (003 eqs 3.11-3.13) and beside the checks' own analytic values, whose hub
inertia is floored (:data:`mjpoincare.scenarios.rimless_wheel.runs.MIN_GYRATION`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.core.params import ParameterError, Values
from mjpoincare.engines.peers import Peer, PeerValues, drake

#: Drake's accuracy settings of the bench rows (runge_kutta5).
BENCH_ACCURACIES = (1e-4, 1e-6, 1e-8)
#: The parameter sets of the agreement table (and of tests/test_peer_drake.py).
AGREEMENT_CASES: tuple[dict[str, str], ...] = (
    {}, {"spokes": "6", "slope": "0.2"}, {"spokes": "12", "slope": "0.1", "leg_length": "2", "mass": "3"},
    {"spokes": "32", "slope": "0.05", "gravity": "3.7"},
)


def point_mass_wheel(params: Values) -> theory.RimlessWheel:
    """The suite's analytic wheel of Drake's model: the scenario's parameters with kappa = 0 (no gyration floor)."""
    return theory.RimlessWheel(spokes=int(params["spokes"]), slope=float(params["slope"]),
                               leg_length=float(params["leg_length"]),
                               gyration=0.0, gravity=float(params["gravity"]), mass=float(params["mass"]))


def check_params(params: Values) -> None:
    """Refuse a missing pydrake or a hub with inertia (Drake's RimlessWheel has a point-mass hub)."""
    drake.require()
    if float(params["gyration"]) != 0.0:
        raise ParameterError(f"gyration must be 0 with --peer drake: Drake's RimlessWheel has a point-mass hub "
                             f"(got {params['gyration']})")


def values(params: Values, accuracy: float) -> PeerValues:
    """Drake's omega+, multiplier, impact coefficient and step period, each beside the theory at kappa = 0."""
    w = point_mass_wheel(params)
    gait = drake.rimless_wheel(w, accuracy=accuracy)
    star = theory.rolling_fixed_point(w)
    return {"omega_post_impact": (gait.omega_post_impact, star),
            "eigenvalue": (gait.multiplier, theory.rolling_multiplier(w)),
            "impact_coefficient": (gait.impact_coefficient, w.beta),
            "step_period": (gait.step_period, theory.step_period(w, star))}, gait


def drake_peer(wheel: Callable[[Values], theory.RimlessWheel]) -> Peer:
    """Drake's rimless wheel as the scenario's peer; ``wheel`` maps the scenario's parameters onto the checks' own
    analytic wheel (the model note names its floored kappa)."""

    def model_note(params: Values) -> str:
        return (f"Drake's RimlessWheel has a point-mass hub (kappa = 0); the checks' analytic values use the "
                f"scenario's floor kappa = {wheel(params).kappa:.3g}")

    def model_shift(params: Values, peer_values: dict[str, tuple[Any, Any]]) -> str:
        floored = theory.rolling_fixed_point(wheel(params))
        shift = theory.rolling_fixed_point(point_mass_wheel(params)) - floored
        drake_omega = peer_values["omega_post_impact"][0]
        return (f"Drake's omega+ minus the scenario's analytic omega+ (kappa = {wheel(params).kappa:g}) = "
                f"{drake_omega - floored:.3e} rad/s; the theory's own shift from kappa = {wheel(params).kappa:g} to "
                f"kappa = 0 (002 eqs 12, 14) = {shift:.3e} rad/s")

    return drake.peer(check_params=check_params, values=values, model_note=model_note, model_shift=model_shift,
                      bench_accuracies=BENCH_ACCURACIES,
                      bench_metrics={"omega_post_impact_error": "omega_post_impact", "eigenvalue_error": "eigenvalue"},
                      bench_model="point-mass hub, kappa = 0", agreement_cases=AGREEMENT_CASES)
