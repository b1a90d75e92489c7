"""The nearest wrong physics each check of ``rimless-wheel`` must reject, and the error it would show.

Sources: 003 = Kiša (2020), Sec. 3 (return map eqs 3.11-3.14, basins eqs 3.17-3.18, Table 1); 002 = Gamus & Or (2015),
Sec. 3.1 (hub inertia: stance rate eq 12, impact coefficient eq 14, fixed point eq 16, multiplier eq 17).

* The fitted map (``omega_post_impact``, ``eigenvalue``, ``impact_coefficient``, ``step_period``): a hub inertia the
  model would wrongly have, the one MuJoCo infers from the hub's drawn cylinder (radius 0.05 m, the model's
  ``inertiafromgeom``): kappa = (0.05 m)^2 / (2 l^2) = 1.25e-3 at l = 1 m instead of the model's floor 1e-4. It moves
  beta (002 eq 14), the stance rate (002 eq 12) and with them omega* (002 eq 16), beta^2 (eq 17) and the period.
* ``basins``: the same wheel with its mass spread evenly along the spokes (kappa = 1/3, 002's paper wheel) instead of
  at the hub; the band edges of 003 eqs 3.17-3.18 are set by beta^-2m, so only a change of beta this large moves an
  edge past a grid speed (each grid speed is a band's midpoint).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import lru_cache

from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.scenarios.base import Rival, Values
from mjpoincare.scenarios.rimless_wheel.basin_judging import basin_flips
from mjpoincare.scenarios.rimless_wheel.runs import wheel

#: Radius of the hub's drawn cylinder (models/rimless_wheel_2d.xml), m: its solid-cylinder inertia is m R^2 / 2.
HUB_CYLINDER_RADIUS = 0.05
#: kappa of a wheel whose mass is spread evenly along its spokes (each a uniform rod about the hub: l^2 / 3).
SPOKE_MASS_KAPPA = 1.0 / 3.0


def _model(params: Values) -> theory.RimlessWheel:
    """The scenario's analytic wheel (gyration floor applied)."""
    return wheel(params)


def _cylinder_hub(w: theory.RimlessWheel) -> theory.RimlessWheel:
    """The wheel with the drawn hub cylinder's radius of gyration R / sqrt(2)."""
    return replace(w, gyration=HUB_CYLINDER_RADIUS / math.sqrt(2.0))


def _map_values(w: theory.RimlessWheel) -> tuple[float, float, float, float]:
    """(omega*, beta^2, beta, T(omega*)) of the rolling gait (002 eqs 14, 16, 17; 003 eq 3.5)."""
    star = theory.rolling_fixed_point(w)
    return star, theory.rolling_multiplier(w), w.beta, theory.step_period(w, star)


def _map_distance(index: int, relative: bool) -> Callable[[Values], float]:
    """The check's error (relative or absolute) on value ``index`` of :func:`_map_values` under the cylinder hub."""

    def distance(params: Values) -> float:
        w = _model(params)
        right, wrong = _map_values(w)[index], _map_values(_cylinder_hub(w))[index]
        return abs(wrong - right) / abs(right) if relative else abs(wrong - right)

    return distance


@lru_cache(maxsize=32)
def _basin_flips(spokes: int, slope: float, leg_length: float, gyration: float, gravity: float) -> float:
    """Share of the judged grid speeds whose end state differs on the wheel with its mass along the spokes."""
    w = theory.RimlessWheel(spokes, slope, leg_length, gyration, gravity)
    return basin_flips(w, replace(w, gyration=math.sqrt(SPOKE_MASS_KAPPA) * leg_length))


def _basins(params: Values) -> float:
    w = _model(params)
    return _basin_flips(w.spokes, w.slope, w.leg_length, w.gyration, w.gravity)


_CYLINDER = ("hub inertia of the drawn hub cylinder (MuJoCo's inertia from the hub geom, kappa = 1.25e-3 at l = 1 m) "
             "instead of the gyration floor: beta, rate2 of 002 eqs 12, 14")
_CYLINDER_WEAK = ("a hub of kappa 1.25e-3 moves beta (002 eq 12) by O(kappa), the size of the soft impact's own "
                  "error at the accurate preset; the step period tells it")

RIVALS: dict[str, Rival] = {
    "omega_post_impact": Rival(physics=_CYLINDER + ", omega* of eq 16", distance=_map_distance(0, True),
                               weak=_CYLINDER_WEAK),
    "eigenvalue": Rival(physics=_CYLINDER + ", multiplier beta^2 of eq 17", distance=_map_distance(1, False),
                        weak=_CYLINDER_WEAK),
    "impact_coefficient": Rival(physics=_CYLINDER + ", impact coefficient beta", distance=_map_distance(2, True),
                                weak=_CYLINDER_WEAK),
    "step_period": Rival(physics=_CYLINDER + ", step period at omega* (003 eq 3.5)", distance=_map_distance(3, True)),
    "basins": Rival(physics="mass spread evenly along the spokes (kappa = 1/3, 002's paper wheel) instead of at the "
                            "hub: the basin bands of 003 eqs 3.17-3.18", distance=_basins),
}
