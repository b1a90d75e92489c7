"""The scenario registry: every entry point (CLI, tests, bench, render) lists scenarios from here.

A scenario's module is imported when the scenario is first looked up, so a command that runs one scenario loads
only that one (its theory, its model and their libraries).
"""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping
from importlib import import_module

from mjpoincare.params import ParameterError
from mjpoincare.scenarios.base import Evaluation, Scenario

#: Scenario name -> ``module:attribute`` of its :class:`Scenario`, in listing order.
ENTRIES: dict[str, str] = {
    "rimless-wheel": "mjpoincare.scenarios.rimless_wheel:RIMLESS_WHEEL",
    "compass-biped": "mjpoincare.scenarios.compass_biped:COMPASS_BIPED",
    "slotted-skate": "mjpoincare.scenarios.slotted_skate:SLOTTED_SKATE",
    "rimless-wheel-3d": "mjpoincare.scenarios.rimless_wheel_3d:RIMLESS_WHEEL_3D",
    "rimless-wheel-friction": "mjpoincare.scenarios.rimless_wheel_friction:RIMLESS_WHEEL_FRICTION",
    "compass-biped-friction": "mjpoincare.scenarios.compass_biped_friction:COMPASS_BIPED_FRICTION",
}
DEFAULT_SCENARIOS: tuple[str, ...] = ("rimless-wheel", "compass-biped", "slotted-skate", "rimless-wheel-3d",
                                     "rimless-wheel-friction")


class Registry(MutableMapping[str, Scenario]):
    """Scenarios by name, each imported from its ``module:attribute`` entry on first access."""

    def __init__(self, entries: dict[str, str]) -> None:
        self._entries = dict(entries)
        self._loaded: dict[str, Scenario] = {}

    def __getitem__(self, name: str) -> Scenario:
        if name not in self._loaded:
            module, attribute = self._entries[name].split(":")
            scenario = getattr(import_module(module), attribute)
            if scenario.name != name:
                raise RuntimeError(f"registry entry {name!r} loads scenario {scenario.name!r}")
            self._loaded[name] = scenario
        return self._loaded[name]

    def __setitem__(self, name: str, scenario: Scenario) -> None:
        self._entries.setdefault(name, "")
        self._loaded[name] = scenario

    def __delitem__(self, name: str) -> None:
        del self._entries[name]
        self._loaded.pop(name, None)

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)


REGISTRY = Registry(ENTRIES)


def get(name: str) -> Scenario:
    """The scenario called ``name``; unknown names raise :class:`ParameterError` listing the known ones."""
    if name not in REGISTRY:
        raise ParameterError(f"unknown scenario {name!r}; known: {', '.join(REGISTRY)}")
    return REGISTRY[name]


__all__ = ["DEFAULT_SCENARIOS", "ENTRIES", "REGISTRY", "Evaluation", "Scenario", "get"]
