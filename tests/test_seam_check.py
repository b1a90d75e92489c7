"""The harness's self-tests: every seam mechanism works on the loaded MuJoCo (and on MJX and MuJoCo Warp where they
are installed), a planted broken mechanism refuses the run with exit 2 and one line naming it, and every scenario
declares each mechanism its controllers call."""

from __future__ import annotations

import ast
import importlib
import inspect
from collections.abc import Iterator
from types import ModuleType

import mujoco
import pytest
from conftest import BACKEND_DISTRIBUTIONS, required_in_ci

from mjpoincare import cli, seam_check
from mjpoincare.backends import LACKS, REQUIRES, _importable
from mjpoincare.backends.mujoco_c import MujocoBatch
from mjpoincare.scenarios import REGISTRY

#: The seam method (or MuJoCo C field reader) each mechanism stands behind.
CALLS = {"set_contact": "contact", "set_eq_active": "equality", "set_friction": "friction",
         "advance": "fractional_step", "set_actuator": "actuator", "efc_diag_inverse_inertia": "contact_fields"}


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


def test_scenarios_without_the_broken_mechanism_still_run_its_self_test_only_when_declared(
        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(MujocoBatch, "set_contact", lambda self, index, geom, on: None)
    seam_check.require(REGISTRY["rimless-wheel"].mechanisms)  # the planar wheel releases no contact
    with pytest.raises(seam_check.MechanismFailed, match="contact release"):
        seam_check.require(REGISTRY["compass-biped"].mechanisms)


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
    return names


@pytest.mark.parametrize("name", list(REGISTRY))
def test_every_scenario_declares_the_mechanisms_it_calls(name: str) -> None:
    scenario = REGISTRY[name]
    assert set(scenario.mechanisms) <= set(seam_check.MECHANISMS), scenario.mechanisms
    assert "rollout" in scenario.mechanisms
    module = importlib.import_module(scenario.evaluate.__module__)
    used = {CALLS[call] for m in _scenario_modules(module) for call in _calls(m) if call in CALLS}
    assert used <= set(scenario.mechanisms), f"{name} calls {sorted(used)}, declares {scenario.mechanisms}"
