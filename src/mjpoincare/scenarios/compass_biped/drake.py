"""The compass biped's outside peer: Drake's hybrid ``CompassGait`` (:mod:`mjpoincare.engines.peers.drake`), the biped
of 003 Ch. 4 and Goswami et al. (1998) without an ankle torque: its values are set beside the suite's theory for the
same biped (003 eq 4.18)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from mjpoincare.analysis.eigenvalues import match_eigenvalues
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.core.params import ParameterError, Values
from mjpoincare.engines.peers import Peer, PeerValues, drake

#: Drake's accuracy settings of the bench rows (runge_kutta5).
BENCH_ACCURACIES = (1e-4, 1e-6, 1e-8)
#: The parameter sets of the agreement table (and of tests/test_peer_drake.py).
AGREEMENT_CASES: tuple[dict[str, str], ...] = (
    {}, {"slope": "0.0523599"}, {"a": "0.6", "b": "0.4", "slope": "0.05"}, {"m_h": "15"}, {"tau_hip": "0.1"},
)


def check_params(params: Values) -> None:
    """Refuse a missing pydrake or an ankle torque (Drake's CompassGait has none)."""
    drake.require()
    if float(params["tau_ankle"]) != 0.0:
        raise ParameterError(f"tau_ankle must be 0 with --peer drake: Drake's CompassGait has no ankle torque "
                             f"(got {params['tau_ankle']})")


def drake_peer(biped: Callable[[Values], theory.CompassBiped]) -> Peer:
    """Drake's compass gait as the scenario's peer; ``biped`` maps the scenario's parameters onto the biped."""

    def values(params: Values, accuracy: float) -> PeerValues:
        bp = biped(params)
        cycle = drake.compass_gait(bp, accuracy=accuracy)
        x_star = theory.fixed_point(bp)
        lam = theory.eigenvalues(bp, x_star)
        return {"fixed_point": (np.array(cycle.fixed_point), x_star),
                "eigenvalues": (match_eigenvalues(lam, np.array(cycle.eigenvalues)), lam),
                "step_period": (cycle.step_period, theory.step_period(bp, x_star)),
                "step_length": (cycle.step_length, theory.step_length(bp, x_star))}, cycle

    return drake.peer(check_params=check_params, values=values,
                      model_note=lambda p: "Drake's CompassGait is the checks' model (003 Ch. 4)",
                      bench_accuracies=BENCH_ACCURACIES,
                      bench_metrics={"fixed_point_error": "fixed_point", "eigenvalues_error": "eigenvalues"},
                      bench_model="the scenario's biped", agreement_cases=AGREEMENT_CASES)
