"""The scenario registry: every entry point (CLI, tests, bench, render) lists scenarios from here."""

from __future__ import annotations

from mjpoincare.params import ParameterError
from mjpoincare.scenarios.base import Evaluation, Scenario
from mjpoincare.scenarios.compass_biped import COMPASS_BIPED
from mjpoincare.scenarios.compass_biped_friction import COMPASS_BIPED_FRICTION
from mjpoincare.scenarios.rimless_wheel import RIMLESS_WHEEL
from mjpoincare.scenarios.rimless_wheel_3d import RIMLESS_WHEEL_3D
from mjpoincare.scenarios.rimless_wheel_friction import RIMLESS_WHEEL_FRICTION
from mjpoincare.scenarios.slotted_skate import SLOTTED_SKATE

REGISTRY: dict[str, Scenario] = {s.name: s for s in (RIMLESS_WHEEL, COMPASS_BIPED, SLOTTED_SKATE, RIMLESS_WHEEL_3D,
                                                    RIMLESS_WHEEL_FRICTION, COMPASS_BIPED_FRICTION)}
DEFAULT_SCENARIOS: tuple[str, ...] = ("rimless-wheel", "compass-biped", "slotted-skate", "rimless-wheel-3d",
                                     "rimless-wheel-friction")


def get(name: str) -> Scenario:
    """The scenario called ``name``; unknown names raise :class:`ParameterError` listing the known ones."""
    try:
        return REGISTRY[name]
    except KeyError:
        raise ParameterError(f"unknown scenario {name!r}; known: {', '.join(REGISTRY)}") from None


__all__ = ["DEFAULT_SCENARIOS", "REGISTRY", "Evaluation", "Scenario", "get"]
