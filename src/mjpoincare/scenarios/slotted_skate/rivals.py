"""The nearest wrong physics for each check of ``slotted-skate``, and the error each check would show under it.

Reference: 000 = M. J. Coleman & P. Holmes (1999), *Motions and stability of a piecewise holonomic system: the discrete
Chaplygin sleigh*. Every distance is computed from the theory (:mod:`mjpoincare.analysis.theory.slotted_skate`): the
rival's own map iterated over the scenario's batch (the same starts and the same run duration), each of its section
states read against the exact map (3.5, B.3/B.4) as the check reads a simulated one, in the check's own measure:

* sigma4 (3.10), its fit, the heading (B.1 quadrature) and the reversals (B.5) against a slot 1 % longer (the pegs
  at the slot ends misplaced by Delta/100);
* the stability verdicts (3.11-3.12) against the slot mounted reversed (G mirrored about the slot's middle,
  L0 -> -(L0 + Delta)): the other direction's sigma4;
* the energy per impact (3.7), the impacts before a reversal (B.6-B.7), the final speed (B.10/B.12) and the final
  reversals against a peg impact that conserves the energy (E+ = E-, H+ = C2 H- of 3.6 kept).

A peg impact with restitution is no rival: every impulse acts at the new peg, so H about it is conserved and the
bilateral peg ends with no normal velocity, the plastic state (3.6)/(3.7), whatever the restitution.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from functools import lru_cache
from typing import NamedTuple

from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.scenarios.base import Rival, Values
from mjpoincare.scenarios.slotted_skate.design import final_impacts, initial_conditions, run_duration, skate

#: Relative slot-length error of the geometric rival.
SLOT_ERROR = 0.01

#: A hashable parameter set (the lru_cache key).
_Key = tuple[tuple[str, object], ...]


class _Tally(NamedTuple):
    """What the checks of :func:`mjpoincare.scenarios.slotted_skate.evaluate` would read from the rival's batch."""

    energy: float
    heading: float
    reversal_mismatch: int
    collisions_mismatch: int


def _key(params: Values) -> _Key:
    """``params`` as a hashable, ordered key."""
    return tuple(sorted(params.items()))


def _skate(params: Values) -> theory.SlottedSkate:
    """The scenario's nondimensional skate (imported lazily: the scenario module imports this one)."""
    return skate(params)


def _longer(sk: theory.SlottedSkate) -> theory.SlottedSkate:
    """The slot SLOT_ERROR longer, its front end (and G) in place."""
    return theory.SlottedSkate(L0=sk.L0, Delta=sk.Delta * (1.0 + SLOT_ERROR))


def _mirrored(sk: theory.SlottedSkate) -> theory.SlottedSkate:
    """The slot mounted reversed: G mirrored about the slot's middle."""
    return theory.SlottedSkate(L0=-(sk.L0 + sk.Delta), Delta=sk.Delta)


def _rival_step(rival: theory.SlottedSkate, lossless: bool, q: theory.MapStep) -> theory.MapStep:
    """One impact of the rival map (3.5): ``rival``'s geometry, the energy kept where ``lossless``."""
    step = theory.return_map(rival, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
    return dataclasses.replace(step, E_plus=q.E_plus) if lossless else step


def _exact_step(sk: theory.SlottedSkate, q: theory.MapStep) -> theory.MapStep:
    """The exact map (3.5) from a rival's state, read at the same slot end (front: D = 0, rear: D = Delta)."""
    return theory.return_map(sk, 0.0 if q.D_plus == 0.0 else sk.Delta, q.E_plus, q.theta_plus, q.H_plus)


@lru_cache(maxsize=64)
def _tally(key: _Key, geometry: str, lossless: bool) -> _Tally:
    """The batch (``initial_conditions``) run under the rival for the scenario's duration, each stance ending in it
    read against the exact map: the worst energy (3.7) and heading (B.1) errors, the reversal (B.5) mismatches, and
    the starts whose first reversal differs from (B.6)'s count (where B.6 applies and the reversal is inside)."""
    params = dict(key)
    sk = _skate(params)
    rival = _longer(sk) if geometry == "longer" else sk
    V, Om = initial_conditions(params)
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    horizon = run_duration(params, V, Om) * v0 / rho
    b6 = not -sk.Delta <= sk.L0 <= 0.0
    energy = heading = 0.0
    reversal_mismatch = collisions_mismatch = 0
    for v, om in zip(V, Om, strict=True):
        q = theory.initial_state(rival, float(v) / v0, float(om) * rho / v0, 0.0)
        n = theory.collisions_before_reversal(sk, 0.0 if q.D_plus == 0.0 else sk.Delta, q.E_plus, q.H_plus) \
            if b6 and q.H_plus != 0.0 else -1
        elapsed, samples, flips = 0.0, 1, []
        while True:
            exact, step = _exact_step(sk, q), _rival_step(rival, lossless, q)
            elapsed += step.duration
            if elapsed > horizon:
                break
            energy = max(energy, abs(step.E_plus - exact.E_plus))
            heading = max(heading, abs(step.theta_plus - exact.theta_plus))
            reversal_mismatch += int(step.reversed != exact.reversed)
            if step.reversed:
                flips.append(samples - 1)
            samples, q = samples + 1, step
        if n >= 0 and n + 1 < samples:
            collisions_mismatch += int((flips[0] if flips else samples) != n)
    return _Tally(energy, heading, reversal_mismatch, collisions_mismatch)


@lru_cache(maxsize=64)
def _final(key: _Key) -> tuple[float, int] | None:
    """The user's start under the energy-conserving peg, over the impacts the final-state checks read (the map's own
    slot speed within FINAL_SPEED_RESOLUTION of V_f, B.10/B.12): its slot speed error there and its reversal-count
    error; None where the rotation does not decay (no final-state checks)."""
    params = dict(key)
    sk = _skate(params)
    decay = final_impacts(params, sk)
    if decay is None:
        return None
    _, impacts, _, reversals, v_final = decay
    rho, v0 = float(params["rho"]), abs(float(params["V0"]))
    q = theory.initial_state(sk, float(params["V0"]) / v0, float(params["Omega0"]) * rho / v0, 0.0)
    seen = 0
    for _ in range(impacts):
        q = _rival_step(sk, True, q)
        seen += int(q.reversed)
    v_last = math.copysign(math.sqrt(2.0 * q.E_plus), 1.0 if q.D_plus == 0.0 else -1.0)
    return abs(v_last - v_final), abs(seen - reversals)


def _sigma4(forward: bool) -> Callable[[Values], float]:
    """``params -> |sigma4 (3.10) of the longer slot - sigma4|``: every non-reversing H ratio of the rival is its
    sigma4, and so is its fitted slope."""

    def distance(params: Values) -> float:
        sk = _skate(params)
        return abs(theory.sigma4(_longer(sk), forward) - theory.sigma4(sk, forward))

    return distance


def _stability(forward: bool) -> Callable[[Values], float]:
    """``params -> 1.0`` where the mirrored slot's verdict |sigma4| < 1 (3.11-3.12) differs from the skate's."""

    def distance(params: Values) -> float:
        sk = _skate(params)
        return float((abs(theory.sigma4(_mirrored(sk), forward)) < 1.0) != (abs(theory.sigma4(sk, forward)) < 1.0))

    return distance


def _energy_loss(params: Values) -> float:
    """The worst |E_k+1 - E+| (m v0^2) of the batch: the loss C1 H^2 (3.7) the peg did not take."""
    return _tally(_key(params), "exact", True).energy


def _heading(params: Values) -> float:
    """The worst |theta_k+1 - theta+| (rad) of the batch on the longer slot (B.1 quadrature)."""
    return _tally(_key(params), "longer", False).heading


def _reversals(params: Values) -> float:
    """Stances of the batch on the longer slot whose reversal (B.5) differs from the exact map's."""
    return float(_tally(_key(params), "longer", False).reversal_mismatch)


def _collisions_before_reversal(params: Values) -> float:
    """Starts of the batch whose first reversal under the energy-conserving peg differs from (B.6)'s count."""
    return float(_tally(_key(params), "exact", True).collisions_mismatch)


def _final_speed(params: Values) -> float:
    """|slot speed - V_f| (v0) at the final-state impact under the energy-conserving peg (NaN: no final state)."""
    final = _final(_key(params))
    return math.nan if final is None else final[0]


def _final_reversals(params: Values) -> float:
    """|reversals - the map's| over the final-state impacts under the energy-conserving peg (NaN: no final state)."""
    final = _final(_key(params))
    return math.nan if final is None else float(final[1])


_LONGER = "slot 1 % longer (the pegs at its ends misplaced by Delta/100): C2 of (3.6) and the stance (B.1) move"
_MIRRORED = "slot mounted reversed (G mirrored about the slot's middle): the other direction's sigma4 (3.10)"
_LOSSLESS = "peg impact conserving the energy (E+ = E-, H+ by 3.6 kept) instead of the plastic loss C1 H^2 (3.7)"

RIVALS: dict[str, Rival] = {
    "sigma4_forward": Rival(physics=_LONGER, distance=_sigma4(True)),
    "sigma4_fit_forward": Rival(physics=_LONGER, distance=_sigma4(True)),
    "stability_forward": Rival(physics=_MIRRORED, distance=_stability(True)),
    "sigma4_backward": Rival(physics=_LONGER, distance=_sigma4(False)),
    "sigma4_fit_backward": Rival(physics=_LONGER, distance=_sigma4(False)),
    "stability_backward": Rival(physics=_MIRRORED, distance=_stability(False)),
    "energy_loss": Rival(physics=_LOSSLESS, distance=_energy_loss),
    "heading": Rival(physics=_LONGER, distance=_heading),
    "reversals": Rival(physics=_LONGER, distance=_reversals,
                       weak="no stance of the gate's starts reverses differently on a 1 % longer slot (a reversal, "
                            "B.5, needs H to cross 0 inside a stance, which 1 % of the peg distance does not bring "
                            "about there); sigma4 and the heading tell the longer slot"),
    "collisions_before_reversal": Rival(physics=_LOSSLESS, distance=_collisions_before_reversal),
    "final_speed": Rival(physics=_LOSSLESS, distance=_final_speed),
    "final_reversals": Rival(physics=_LOSSLESS, distance=_final_reversals,
                             weak="the energy-conserving peg reverses the skate at the same final-state impacts as "
                                  "the plastic one (the sign of H+ by 3.6 is the same under both); the energy per "
                                  "impact and the final speed tell the lossless peg"),
}
