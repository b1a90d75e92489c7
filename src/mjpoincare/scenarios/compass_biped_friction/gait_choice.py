"""The analytic gait a parameter set of ``compass-biped-friction`` names: the gait, its friction (002 Sec. 4: passive
Gaits A, B, C; Sec. 5: actuated Gaits I, II, III) and the theory's solution for it, re-derived in
:mod:`mjpoincare.analysis.theory.compass_biped_friction`."""

from __future__ import annotations

import math
from functools import lru_cache

from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.core.params import Values

#: 002's friction per gait when ``mu`` = 0: A above mu_c (any mu >= 0.175 is the same gait), B 0.14 (Fig. 4.2a),
#: C 0.2 (Fig. 4.2b, the less unstable end of its branch: |lambda|max 1.53 vs 1.82 at 0.14), I 0.2 (Fig. 5.1),
#: II 0.2 (Sec. 5), III 0.2 (Fig. 5.2).
PAPER_MU = {"a": 1.0, "b": 0.14, "c": 0.2, "i": 0.2, "ii": 0.2, "iii": 0.2}
def gait_name(params: Values) -> str:
    """The theory's gait name (A, B, I, III)."""
    return str(params["gait"]).upper()


def friction(params: Values) -> float:
    """mu, with 0 meaning the gait's paper value."""
    mu = float(params["mu"])
    return PAPER_MU[str(params["gait"])] if mu == 0.0 else mu


@lru_cache(maxsize=16)
def solved_gait(name: str, mu: float, kp: float, kd: float) -> theory.Gait:
    if name == "A":
        # sticking throughout: the gait does not depend on mu >= its demand; Newton from the seed (002 Sec. 4.1)
        gait = theory.paper_gait("A", math.inf)
        demand = theory.critical_friction(gait.biped, gait.z)
        if mu < max(demand.stance, demand.impulse):
            raise ValueError(f"mu must be >= {demand.stance:.5f} (mu_c of Gait A, 002 Sec. 4.1; below it is Gait B)"
                             f" (got {mu})")
        bp = theory.FrictionBiped(mu=mu)
        return theory.find_gait(bp, gait.z[:3], theory.PASSIVE)
    if name == "III" and (kp, kd) != (15.0, 15.0):
        bp = theory.FrictionBiped(slope=0.0, mu=mu)
        base = theory.paper_gait("III", mu)
        return theory.find_gait(bp, base.z, theory.PDTracking(theory.gait_c_reference(), kp, kd))
    return theory.paper_gait(name, mu)


def gait(params: Values) -> theory.Gait:
    """The analytic gait (002 Secs. 4-5) for the scenario parameters."""
    return solved_gait(gait_name(params), friction(params), float(params["kp"]), float(params["kd"]))
