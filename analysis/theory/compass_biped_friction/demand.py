"""Friction demand, cost of transport and speed of a compass-biped gait (002 Secs. 4.1, 5, eq 29).

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 4.1 (mu_c and the impulse ratio |sigma~| of a sticking gait, Fig. 4.1c) and Sec. 5 (the specific cost c_mt of eq
29 with the total weight, and the average speed); derivation page docs/theory/stick-slip.md, Sec. 7 item 14.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import NamedTuple

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.actuation import Actuation
from mjpoincare.analysis.theory.compass_biped_friction.one_step import StepRecord, step
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped
from numpy.typing import ArrayLike


class FrictionDemand(NamedTuple):
    """Friction needed by a sticking gait (002 Sec. 4.1, Fig. 4.1c): ``stance`` mu_c = max |f_t/f_n| over the
    stance, reached at ``time`` (s after the impact) with signed ratio ``sigma``; ``impulse`` |sigma~| =
    |F~_t/F~_n| of the heel strike. Stick throughout needs mu >= max(stance, impulse)."""

    stance: float
    time: float
    sigma: float
    impulse: float


def critical_friction(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None) -> FrictionDemand:
    """mu_c and |sigma~| of the gait z* computed with mu = inf (002 Sec. 4.1: mu_c = 0.175, |sigma~| = 0.145 for
    Gait A)."""
    rec = step(replace(bp, mu=math.inf), z_star, actuation, forces=True)
    if rec.failure is not None:
        raise ValueError(f"the step from {np.asarray(z_star)!r} fails ({rec.failure})")
    return FrictionDemand(rec.max_ratio, rec.max_ratio_time, rec.max_ratio_sigma, abs(rec.impulse_ratio))


def cost_of_transport(bp: FrictionBiped, record: StepRecord) -> float:
    """Specific cost c_mt = W_act/(M_tot g S) (002 eq 29 with the total weight; docs/theory/stick-slip.md, Sec. 7
    item 14)."""
    return record.actuator_work / (bp.total_mass * bp.g * record.step_length)


def average_speed(record: StepRecord) -> float:
    """v = S/T (m/s) (002 Sec. 5, below eq 29)."""
    return record.step_length / record.period
