"""The scenario registry: every entry point (CLI, tests, bench, render) lists scenarios from here.

The registry discovers scenarios: it lists the entry points of the group ``mjpoincare.scenarios`` of every installed
distribution (this one's are in its ``pyproject.toml``; another distribution adds a system by declaring its own,
docs/adding-a-scenario.md), by name. A scenario's module is imported when the scenario is first looked up, so a
command that runs one scenario loads only that one (its theory, its model and their libraries).

The folder holds the registry (this module, a layer of its own above the systems), the records a system declares
(``base``: the Scenario and its parts; ``gate_cases``: its gate runs) and one subpackage per system, whose
``__init__`` is the system's Scenario and whose modules are its runs, checks and gate declarations. A system's
modules may import the records, the simulation (never an engine's module: the seam is ``simulate``),
:mod:`mjpoincare.core` and :mod:`mjpoincare.analysis`; never another layer above them, and a command reaches a system
only through this registry.
"""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping
from importlib.metadata import EntryPoint, entry_points

from mjpoincare.core.params import ParameterError, did_you_mean
from mjpoincare.scenarios.base import DeclarationError, Evaluation, Scenario, Tolerances, at_preset
from mjpoincare.scenarios.declaration import check_declaration, check_evaluation, load_error
from mjpoincare.scenarios.gate_cases import GateCase

#: The entry-point group a distribution declares its scenarios in: ``name = "module:attribute"`` of a Scenario.
GROUP = "mjpoincare.scenarios"


class Registry(MutableMapping[str, Scenario]):
    """Scenarios by name, discovered from the entry points of :data:`GROUP` when first listed, each imported on
    first access. Setting a listed name replaces its scenario in this process (a test's variant of a scenario);
    deleting it goes back to the entry point's."""

    def __init__(self, group: str) -> None:
        self._group = group
        self._entries: dict[str, EntryPoint] | None = None
        self._loaded: dict[str, Scenario] = {}
        #: name -> the one-line error of a scenario whose module or declaration failed (it stays out of every run)
        self.broken: dict[str, str] = {}

    @property
    def entries(self) -> dict[str, EntryPoint]:
        """Name -> entry point, sorted by name (a name two distributions declare is an error, not a shadow)."""
        if self._entries is None:
            found: dict[str, EntryPoint] = {}
            for entry in entry_points(group=self._group):
                if entry.name in found and found[entry.name].value != entry.value:
                    raise RuntimeError(f"scenario {entry.name!r} is declared twice: {found[entry.name].value} and "
                                       f"{entry.value}")
                found[entry.name] = entry
            self._entries = dict(sorted(found.items()))
        return self._entries

    def distribution(self, name: str) -> str | None:
        """The name of the distribution that declares scenario ``name`` (``mjpoincare`` for the built-in ones)."""
        dist = self.entries[name].dist
        return None if dist is None else dist.name

    def __getitem__(self, name: str) -> Scenario:
        """The scenario, loaded and its declaration checked on first access; a plugin that fails either raises
        :class:`DeclarationError` in one line naming the distribution, its entry point, the field and the fix (the
        same line every later access: other scenarios are unaffected)."""
        if name in self.broken:
            raise DeclarationError(self.broken[name])
        if name not in self._loaded:
            entry = self.entries[name]
            where = f"plugin {self.distribution(name) or '?'} ({entry.value})"
            try:
                scenario = entry.load()
                if not isinstance(scenario, Scenario):
                    raise DeclarationError(f"the entry point loads a {type(scenario).__name__}, not a Scenario")
                check_declaration(scenario, name)
            except Exception as err:  # an author's mistake at import or declaration: one line, never a traceback
                self.broken[name] = f"{where}: {load_error(err)}"
                raise DeclarationError(self.broken[name]) from None
            self._loaded[name] = scenario
        return self._loaded[name]

    def __setitem__(self, name: str, scenario: Scenario) -> None:
        if name not in self.entries:
            raise KeyError(f"{name!r} is not a registered scenario (declare an entry point in {self._group!r})")
        self._loaded[name] = scenario

    def __delitem__(self, name: str) -> None:
        self._loaded.pop(name, None)

    def __iter__(self) -> Iterator[str]:
        return iter(self.entries)

    def __len__(self) -> int:
        return len(self.entries)


REGISTRY = Registry(GROUP)


def loadable() -> list[str]:
    """Every registered scenario whose module and declaration load (a broken plugin's error is in
    ``REGISTRY.broken``), in the registry's order."""
    names = []
    for name in REGISTRY:
        try:
            REGISTRY[name]
        except DeclarationError:
            continue
        names.append(name)
    return names


def default_scenarios() -> tuple[str, ...]:
    """What ``mjpoincare validate`` runs when no scenario is named (the main job): every registered scenario whose
    :attr:`Scenario.default` is set, a plugin's included, in the registry's order (by name); a broken plugin is left
    out (its error in ``REGISTRY.broken``)."""
    return tuple(name for name in loadable() if REGISTRY[name].default)


def get(name: str) -> Scenario:
    """The scenario called ``name``; unknown names raise :class:`ParameterError` listing the known ones."""
    if name not in REGISTRY:
        known = list(REGISTRY)
        if "=" in name:
            raise ParameterError(f"unknown scenario {name!r}: to set a parameter or setting, give --set {name}")
        hint = did_you_mean(name.replace("_", "-").lower(), known)
        raise ParameterError(f"unknown scenario {name!r}{hint} (known: {', '.join(known)})")
    return REGISTRY[name]


__all__ = ["GROUP", "REGISTRY", "DeclarationError", "Evaluation", "GateCase", "Scenario", "Tolerances", "at_preset",
           "check_evaluation", "default_scenarios", "get", "loadable"]
