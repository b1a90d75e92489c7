"""The harness's self-tests: every seam mechanism works on the loaded MuJoCo (and on MJX and MuJoCo Warp where they
are installed), a planted broken mechanism refuses the run with exit 2 and one line naming it, and every scenario
declares each mechanism its controllers call. Marked ``mujoco``: the MuJoCo upgrade gate (``make gate``) runs them."""

from __future__ import annotations

import ast
import importlib
import inspect
from collections.abc import Callable, Iterator
from types import ModuleType

import mujoco
import numpy as np
import pytest
from conftest import BACKEND_DISTRIBUTIONS, required_in_ci

from mjpoincare import cli
from mjpoincare.core.mjcompat import efc_diag_inverse_inertia
from mjpoincare.engines.backends import LACKS, REQUIRES, _importable
from mjpoincare.engines.backends.mujoco_c import MujocoBatch, switch_contact_filter
from mjpoincare.scenarios import REGISTRY
from mjpoincare.simulation import seam_check

pytestmark = pytest.mark.mujoco

#: The seam method (or MuJoCo C field reader, or ``control=``: native control handed to a rollout) each mechanism
#: stands behind.
CALLS = {"set_contact": "contact", "set_eq_active": "equality", "set_friction": "friction",
         "advance": "fractional_step", "set_actuator": "actuator", "control=": "control",
         "efc_diag_inverse_inertia": "contact_fields"}


@pytest.fixture(autouse=True)
def _fresh_self_tests() -> Iterator[None]:
    """Each test sees the self-tests run anew (they are cached per process), and leaves no planted result behind."""
    seam_check.failure.cache_clear()
    yield
    seam_check.failure.cache_clear()


@pytest.mark.parametrize("key", list(seam_check.MECHANISMS))
def test_every_mechanism_works_on_the_loaded_mujoco(key: str) -> None:
    assert seam_check.failure(key) is None


def _backends() -> list[str]:
    """The optional backends installed here, and those CI must have (their tests then fail if missing)."""
    return [b for b, (modules, _) in REQUIRES.items()
            if all(_importable(m) for m in modules) or required_in_ci(BACKEND_DISTRIBUTIONS[b])]


@pytest.mark.parametrize("backend", _backends())
def test_every_mechanism_works_on_the_other_backends(backend: str) -> None:
    modules, extra = REQUIRES[backend]
    if not all(_importable(m) for m in modules):
        pytest.fail(f"CI installs {extra}, but {modules} do not import")
    precision = "float32" if backend == "warp" else "float64"
    failures = {key: seam_check.failure(key, backend, precision) for key in seam_check.MECHANISMS}
    lacked = set(LACKS.get(backend, ())) - {k for k, m in seam_check.MECHANISMS.items() if m.c_only}
    assert {k for k, f in failures.items() if f is not None} == lacked, failures


def test_a_contact_release_that_does_nothing_refuses_the_run(monkeypatch: pytest.MonkeyPatch,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(MujocoBatch, "set_contact", lambda self, index, geom, on: None)
    assert cli.main(["validate", "compass-biped"]) == cli.EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    assert out == ""  # nothing simulated, nothing reported
    lines = err.strip().splitlines()
    assert len(lines) == 1, lines
    assert "contact release and restore does not work" in lines[0] and f"MuJoCo {mujoco.__version__}" in lines[0]


def test_a_mechanism_that_raises_is_a_refusal_not_a_traceback(monkeypatch: pytest.MonkeyPatch,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    def missing(self: MujocoBatch, index: int, mu: float) -> None:
        raise AttributeError("'MjModel' object has no attribute 'geom_friction'")

    monkeypatch.setattr(MujocoBatch, "set_friction", missing)
    assert cli.main(["validate", "rimless-wheel-friction"]) == cli.EXIT_BAD_INPUT
    assert "per-trajectory friction does not work" in capsys.readouterr().err


_SET_CONTACT, _ADVANCE, _SET_ACTUATOR, _RUN_CHUNK = (MujocoBatch.set_contact, MujocoBatch.advance,
                                                    MujocoBatch.set_actuator, MujocoBatch.run_chunk)


def _contact_of_every_geom(self: MujocoBatch, index: int, geom: int, on: bool) -> None:
    """Switches every geom of trajectory ``index``, not only ``geom``."""
    for each in range(self.models[index].ngeom):
        _SET_CONTACT(self, index, each, on)


def _advance_of_trajectory_0(self: MujocoBatch, index: int, state: np.ndarray, seconds: float) -> np.ndarray:
    """Steps with trajectory 0's model whatever ``index``."""
    return _ADVANCE(self, 0, state, seconds)


def _contact_keyed_by_geom(self: MujocoBatch, index: int, geom: int, on: bool) -> None:
    """Keeps a released contact by geom only: a second trajectory's release of the same geom finds it released."""
    switch_contact_filter(self._released, self._model(index), 0, geom, on)


def _advance_from_current_state(self: MujocoBatch, index: int, state: np.ndarray, seconds: float) -> np.ndarray:
    """Steps from the batch's current state of trajectory ``index``, not from ``state``."""
    return _ADVANCE(self, index, self.states()[index], seconds)


def _actuator_without_gear(self: MujocoBatch, index: int, actuator: int, *, bias: float | None = None,
                           gear: float | None = None) -> None:
    """Sets the bias force and leaves the gear as it was."""
    _SET_ACTUATOR(self, index, actuator, bias=bias)


def _chunk_without_control(self: MujocoBatch, nstep: int, control: np.ndarray | None = None,
                           rows: np.ndarray | None = None) -> np.ndarray:
    """Steps with no ctrl whatever ``control``."""
    return _RUN_CHUNK(self, nstep, rows=rows)


def _chunk_with_trajectory_0s_control(self: MujocoBatch, nstep: int, control: np.ndarray | None = None,
                                      rows: np.ndarray | None = None) -> np.ndarray:
    """Steps every trajectory with trajectory 0's ctrl."""
    return _RUN_CHUNK(self, nstep, None if control is None else np.repeat(control[:1], len(control), axis=0), rows)


def _chunk_with_first_step_control(self: MujocoBatch, nstep: int, control: np.ndarray | None = None,
                                   rows: np.ndarray | None = None) -> np.ndarray:
    """Holds each trajectory's first ctrl over the whole chunk."""
    return _RUN_CHUNK(self, nstep, None if control is None else np.repeat(control[:, :1], nstep, axis=1), rows)


def _chunk_of_every_row(self: MujocoBatch, nstep: int, control: np.ndarray | None = None,
                        rows: np.ndarray | None = None) -> np.ndarray:
    """Steps every trajectory whatever ``rows``."""
    return _RUN_CHUNK(self, nstep, control)


#: Broken seam methods planted into MuJoCo C's batch, each with the mechanism whose self-test must refuse it and a
#: scenario run that uses that mechanism (compass-biped-friction's Gait III: its PD reference is native control).
PLANTED: dict[str, tuple[str, Callable[..., object], str, list[str]]] = {
    "contact switched on every geom": ("set_contact", _contact_of_every_geom, "contact", ["compass-biped"]),
    "fractional step ignoring the trajectory": ("advance", _advance_of_trajectory_0, "fractional_step",
                                                ["slotted-skate"]),
    "contact release kept by geom only": ("set_contact", _contact_keyed_by_geom, "contact", ["compass-biped"]),
    "fractional step from the current state": ("advance", _advance_from_current_state, "fractional_step",
                                               ["slotted-skate"]),
    "actuator ignoring the gear": ("set_actuator", _actuator_without_gear, "actuator", ["compass-biped"]),
    "control ignored": ("run_chunk", _chunk_without_control, "control",
                        ["compass-biped-friction", "--set", "gait=iii"]),
    "trajectory 0's control for all": ("run_chunk", _chunk_with_trajectory_0s_control, "control",
                                       ["compass-biped-friction", "--set", "gait=iii"]),
    "first step's control held": ("run_chunk", _chunk_with_first_step_control, "control",
                                  ["compass-biped-friction", "--set", "gait=iii"]),
    "chosen rows ignored": ("run_chunk", _chunk_of_every_row, "rollout", ["rimless-wheel"]),
}


@pytest.mark.parametrize("planted", list(PLANTED))
def test_a_planted_break_refuses_the_scenario_that_uses_it(planted: str, monkeypatch: pytest.MonkeyPatch,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    """Each break is seen by its mechanism's self-test (which the unbroken seam passes), and the validation of a
    scenario that declares the mechanism is refused with exit 2 and one line, nothing simulated."""
    method, broken, key, run = PLANTED[planted]
    monkeypatch.setattr(MujocoBatch, method, broken)
    assert seam_check.failure(key) is not None  # seen before a validation that would simulate with it
    assert key in REGISTRY[run[0]].seam_mechanisms
    seam_check.failure.cache_clear()
    assert cli.main(["validate", *run]) == cli.EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    assert out == ""  # nothing simulated, nothing reported
    lines = err.strip().splitlines()
    assert len(lines) == 1, lines
    assert f"{seam_check.MECHANISMS[key].name} does not work on MuJoCo {mujoco.__version__}" in lines[0], lines[0]


def test_a_contact_field_read_at_another_row_refuses_the_run(monkeypatch: pytest.MonkeyPatch,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    """A diagonal inverse inertia read one constraint row off (the bob's equality's for the ball, the ball's friction
    row for the pebble) does not turn a resting ball's contact force into the acceleration g."""
    monkeypatch.setattr(seam_check, "efc_diag_inverse_inertia",
                        lambda data: np.roll(efc_diag_inverse_inertia(data), 1))
    assert cli.main(["validate", "rimless-wheel-friction"]) == cli.EXIT_BAD_INPUT
    assert "contact fields (normal force, diagonal inverse inertia) does not work" in capsys.readouterr().err


def test_scenarios_without_the_broken_mechanism_still_run_its_self_test_only_when_declared(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(MujocoBatch, "set_contact", lambda self, index, geom, on: None)
    seam_check.require(REGISTRY["rimless-wheel"].seam_mechanisms)  # the planar wheel releases no contact
    with pytest.raises(seam_check.MechanismFailed, match="contact release"):
        seam_check.require(REGISTRY["compass-biped"].seam_mechanisms)


def _scenario_modules(module: ModuleType) -> list[ModuleType]:
    """``module`` and every ``mjpoincare.scenarios`` module it imports, transitively."""
    seen: dict[str, ModuleType] = {}
    todo = [module]
    while todo:
        current = todo.pop()
        if current.__name__ in seen:
            continue
        seen[current.__name__] = current
        for value in vars(current).values():
            owner = value if inspect.ismodule(value) else inspect.getmodule(value)
            if owner is not None and owner.__name__.startswith("mjpoincare.scenarios.") and owner.__name__ not in seen:
                todo.append(owner)
    return list(seen.values())


def _calls(module: ModuleType) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(ast.parse(inspect.getsource(module))):
        if isinstance(node, ast.Call):
            func = node.func
            names.add(func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", ""))
            names.update(f"{keyword.arg}=" for keyword in node.keywords if keyword.arg)
    return names


@pytest.mark.parametrize("name", list(REGISTRY))
def test_every_scenario_declares_the_mechanisms_it_calls(name: str) -> None:
    scenario = REGISTRY[name]
    assert set(scenario.seam_mechanisms) <= set(seam_check.MECHANISMS), scenario.seam_mechanisms
    assert "rollout" in scenario.seam_mechanisms
    module = importlib.import_module(scenario.evaluate.__module__)
    used = {CALLS[call] for m in _scenario_modules(module) for call in _calls(m) if call in CALLS}
    assert used <= set(scenario.seam_mechanisms), f"{name} calls {sorted(used)}, declares {scenario.seam_mechanisms}"
