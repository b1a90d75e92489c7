"""The experiment design of ``slotted-skate`` on the theory's side (Coleman & Holmes 1999): the nondimensional skate
of the parameters, the batch of starts, the run's duration by the analytic map (3.1-3.12) and the impacts to the final
state (B.10/B.12)."""

from __future__ import annotations

import math

import numpy as np

from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.core.params import Values
from mjpoincare.scenarios.slotted_skate.tolerances import TOLERANCES

IMPACTS = 14  # enough for P1's backward starts to reach their reversal (B.6: 11 impacts at Omega0 = 0.1)
SCALES = (0.5, 1.0, 1.5)  # the batch: Omega0 x these, in the given direction and mirrored

def skate(params: Values) -> theory.SlottedSkate:
    """The nondimensional analytic model (lengths / rho)."""
    return theory.SlottedSkate(L0=float(params["l0"]) / float(params["rho"]),
                               Delta=float(params["delta"]) / float(params["rho"]))

def initial_conditions(params: Values) -> tuple[np.ndarray, np.ndarray]:
    """The batch: Omega0 scaled by SCALES, in the given direction and mirrored (V0 -> -V0)."""
    v0, om0 = float(params["V0"]), float(params["Omega0"])
    V = np.array([v0] * len(SCALES) + [-v0] * len(SCALES))
    Om = np.array([om0 * k for k in SCALES] * 2)
    return V, Om

def run_duration(params: Values, V: np.ndarray, Om: np.ndarray) -> float:
    """Time (s) of IMPACTS + 1 stances of the slowest trajectory, by the analytic map, plus 10 %."""
    sk = skate(params)
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    worst = 0.0
    for v, om in zip(V, Om, strict=True):
        steps = theory.iterate(sk, v / v0, om * rho / v0, 0.0, IMPACTS + 1)
        worst = max(worst, sum(st.duration for st in steps))
    return 1.1 * worst * rho / v0

FINAL_DECAY = 1e-6  # a final state exists where |H| decays to this fraction of its initial value (B.10/B.12)
FINAL_IMPACTS_MAX = 400
#: The final-state run ends at the first impact where the map's own slot speed is within this of its limit V_f, in
#: units of v0: a thousandth of the tightest final_speed tolerance, so that stopping there moves the check's error by
#: at most 0.1 % of any preset's tolerance.
FINAL_SPEED_RESOLUTION = 1e-3 * min(t.bounds["final_speed"] for t in TOLERANCES.values())


def has_final_state(params: Values, sk: theory.SlottedSkate) -> bool:
    """Whether the user's start has a final state: its rotation decays by FINAL_DECAY within FINAL_IMPACTS_MAX
    impacts of the map (not an unstable, spinning motion)."""
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    q = theory.initial_state(sk, float(params["V0"]) / v0, float(params["Omega0"]) * rho / v0, 0.0)
    h0, n = abs(q.H_plus), 0
    while abs(q.H_plus) > FINAL_DECAY * h0 and n < FINAL_IMPACTS_MAX:
        q = theory.return_map(sk, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
        n += 1
    return h0 != 0.0 and abs(q.H_plus) <= FINAL_DECAY * h0


def slot_speed(q: theory.MapStep) -> float:
    """The map state's slot speed (paper units), signed by the end its peg went in (front: forward)."""
    return math.copysign(math.sqrt(2.0 * q.E_plus), 1.0 if q.D_plus == 0.0 else -1.0)


def final_impacts(params: Values, sk: theory.SlottedSkate
                   ) -> tuple[theory.MapStep, int, float, int, float] | None:
    """The map from the user's start to the first impact whose slot speed is within FINAL_SPEED_RESOLUTION of the
    final speed (B.10/B.12): the state there, the impacts, the time (paper units) and the reversals on the way, and
    the final speed V_f; None where there is no final state (:func:`has_final_state`)."""
    if not has_final_state(params, sk):
        return None
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    V, Om = float(params["V0"]) / v0, float(params["Omega0"]) * rho / v0
    v_final = theory.final_state(sk, V, Om).V_f
    q = theory.initial_state(sk, V, Om, 0.0)
    n, duration, reversals = 0, 0.0, 0
    while abs(slot_speed(q) - v_final) > FINAL_SPEED_RESOLUTION and n < FINAL_IMPACTS_MAX:
        q = theory.return_map(sk, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
        n, duration, reversals = n + 1, duration + q.duration, reversals + int(q.reversed)
    return q, n, duration, reversals, v_final
