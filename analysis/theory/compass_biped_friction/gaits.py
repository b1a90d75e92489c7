"""The named gaits of the compass biped with Coulomb friction: passive Gaits A-C and actuated Gaits I-III.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Sec. 4 (passive Gaits A, B, C on the 1 deg slope, Figs 4.1-4.2) and Sec. 5 (Gaits I, II with the constant torques of
eq 28, Gait III with the PD tracking of eq 30 on level ground, Figs 5.1-5.2): their setups, the seeds computed here
and the continuation in mu from the nearest seed; derivation page docs/theory/stick-slip.md, Secs. 3 and 7.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.actuation import (
    PASSIVE,
    Actuation,
    ConstantTorque,
    PDTracking,
    ReferenceTrajectory,
)
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped
from mjpoincare.analysis.theory.compass_biped_friction.shooting import Gait, continuation, find_gait
from mjpoincare.analysis.theory.compass_biped_friction.trajectories import reference_trajectory

_AB_SEEDS = (
    (0.2, (0.1478369, 0.7327968, -0.5006679)),
    (0.14, (0.1408071, 0.7102088, -0.5168477)),
    (0.11, (0.1227550, 0.6475338, -0.5131655)),
)
#: (mu, section state z*) pairs of each named gait of 002 from which :func:`paper_gait` continues (computed here;
#: see :mod:`~mjpoincare.analysis.theory.compass_biped_friction`). "A" and "B" are one branch (sticking impact): Gait A
#: for mu >= mu_c = 0.1749, Gait B below. Gait C's post-impact theta1_dot+ is small at low mu (0.044 rad/s at 0.14), so
#: it has seeds at both ends.
GAIT_SEEDS: dict[str, tuple[tuple[float, tuple[float, ...]], ...]] = {
    "A": _AB_SEEDS,
    "B": _AB_SEEDS,
    "C": ((0.14, (0.0790379, 0.0437766, -0.4317612, 0.6341740)), (0.2, (0.1137971, 0.2499297, -0.5764132, 0.5770183))),
    "I": ((0.2, (0.1480151, 0.7340354, -0.5026890)), (0.11, (0.1259916, 0.6483977, -0.6059526))),
    "II": ((0.2, (0.0871665, 0.4447162, -0.4921641, 0.0839298)),),
    "III": (
        (0.2, (0.0744951, 0.2627163, -0.4256346, 0.2531528)),
        (0.09, (0.0720499, 0.2311505, -0.3868293, 0.2788256)),
    ),
}
#: Gait I and II torques (tau1, tau2) of 002 Sec. 5 (effective convention, see
#: :mod:`~mjpoincare.analysis.theory.compass_biped_friction`).
GAIT_I_TORQUES = (-2.73, 0.54)
GAIT_II_TORQUES = (-0.69, 0.12)
#: mu of the passive Gait C whose joint trajectory Gait III tracks (002 Sec. 5: "Gait C ... in Figure 4.2(a)",
#: which is drawn for mu = 0.14).
GAIT_III_REFERENCE_MU = 0.14


@lru_cache(maxsize=4)
def gait_c_reference(mu: float = GAIT_III_REFERENCE_MU, samples: int = 401) -> ReferenceTrajectory:
    """Joint trajectory of the passive Gait C (slope 1 deg) at ``mu``: Gait III's reference (002 eq 30)."""
    gait = paper_gait("C", mu)
    return reference_trajectory(gait.biped, gait.z, samples=samples)


def paper_setup(name: str, mu: float) -> tuple[FrictionBiped, Actuation]:
    """Biped and actuation of a named gait of 002: "A"/"B"/"C" passive on the 1 deg slope (Sec. 4), "I"/"II"
    constant torques (E_eff) and "III" PD (kp = kd = 15, direct, tracking :func:`gait_c_reference`) on level
    ground (Sec. 5)."""
    if name in ("A", "B", "C"):
        return FrictionBiped(mu=mu), PASSIVE
    level = FrictionBiped(slope=0.0, mu=mu)
    if name == "I":
        return level, ConstantTorque(*GAIT_I_TORQUES)
    if name == "II":
        return level, ConstantTorque(*GAIT_II_TORQUES)
    if name == "III":
        return level, PDTracking(gait_c_reference())
    raise ValueError(f"unknown gait {name!r}; one of A, B, C, I, II, III")


@lru_cache(maxsize=64)
def paper_gait(name: str, mu: float, max_step: float = 0.01) -> Gait:
    """The named gait of 002 ("A" and "B" are one branch, see :data:`GAIT_SEEDS`) at friction ``mu``, continued
    from the seed nearest in mu in steps of at most ``max_step`` (for mu = inf: Newton from the largest-mu seed).
    ValueError if the branch does not reach mu."""
    if name not in GAIT_SEEDS:
        raise ValueError(f"unknown gait {name!r}; one of {', '.join(GAIT_SEEDS)}")
    bp, act = paper_setup(name, mu)
    seeds = GAIT_SEEDS[name]
    seed_mu, seed_z = max(seeds) if math.isinf(mu) else min(seeds, key=lambda s: abs(s[0] - mu))
    if math.isinf(mu) or mu == seed_mu:
        return find_gait(bp, seed_z, act)
    n = math.ceil(abs(mu - seed_mu) / max_step - 1e-9)
    mus = [float(m) for m in np.linspace(seed_mu, mu, n + 1)[1:]]
    gaits = continuation(bp, mus, seed_z, act, mu_start=seed_mu)
    if len(gaits) < len(mus):
        raise ValueError(f"gait {name} could not be continued from mu = {seed_mu} to {mu}")
    return gaits[-1]
