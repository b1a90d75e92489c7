"""Run one scenario's validation: resolve and check the inputs, simulate, compare, time it."""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Mapping

import mujoco

from mjpoincare import scenarios
from mjpoincare.analysis.checks import Check
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.params import ParameterError, Value, resolve, unknown
from mjpoincare.core.result import Result
from mjpoincare.engines import backends
from mjpoincare.engines.peers import Peer
from mjpoincare.engines.peers.compare import compare
from mjpoincare.simulation import seam_check

#: The (scenario, parameters, settings) this process has already checked and accepted, each with its scenario (kept,
#: so that its id names it): a command checks its inputs before any simulation and the validation checks them again,
#: and a scenario's check may solve its gait (the compass biped's shooting and multipliers); a worker forked for a
#: validation inherits them.
_ACCEPTED: dict[tuple[int, str, str], scenarios.Scenario] = {}


def resolve_values(name: str, assignments: Mapping[str, Value], preset: str | None
                   ) -> tuple[scenarios.Scenario, str, dict, dict]:
    """Scenario, preset name, checked parameters and settings; bad input raises ParameterError (nothing is
    simulated). The scenario's own checks run once per process for the same values (:data:`_ACCEPTED`)."""
    scenario = scenarios.get(name)
    unknown(assignments, scenario.params, sim_settings.SETTINGS)
    preset_name, overrides = scenario.preset(preset)
    params = resolve(scenario.params, {p.name: p.default for p in scenario.params}, assignments)
    settings = resolve(sim_settings.SETTINGS, {**sim_settings.DEFAULTS, **overrides}, assignments)
    backends.check_backend(settings)
    key = (id(scenario), repr(sorted(params.items())), repr(sorted(settings.items())))
    if key not in _ACCEPTED:
        scenario.check_params(params)
        if scenario.check_params_with_settings is not None:
            scenario.check_params_with_settings(params, settings)
        _ACCEPTED[key] = scenario
    return scenario, preset_name, params, settings


def typed_values(name: str, assignments: Mapping[str, Value]) -> dict[str, Value]:
    """``--set``-style text ``assignments`` of scenario ``name`` as typed values (``{"spokes": "8"}`` ->
    ``{"spokes": 8}``), each through its :class:`~mjpoincare.core.params.Param`, for :func:`mjpoincare.validate`, which
    takes typed values only; bad text raises :class:`ParameterError`."""
    scenario = scenarios.get(name)
    unknown(assignments, scenario.params, sim_settings.SETTINGS)
    by_name = {p.name: p for p in (*scenario.params, *sim_settings.SETTINGS)}
    return {key: by_name[key].coerce(value) for key, value in assignments.items()}


def run_steps(name: str, assignments: Mapping[str, Value], preset: str | None) -> float:
    """MuJoCo steps of one validation of ``name`` (every trajectory's steps of the scenario's rollout plan,
    ``scenario.validation_batches``, which builds the model and its starts and steps nothing); bad input raises
    :class:`ParameterError`."""
    scenario, _, params, settings = resolve_values(name, assignments, preset)
    _, batches = scenario.validation_batches(params, settings)
    return float(sum(states.shape[0] * nstep for states, nstep in batches))


def resolve_inputs(name: str, assignments: Mapping[str, Value], preset: str | None
                   ) -> tuple[scenarios.Scenario, str, dict, dict]:
    """:func:`resolve_values`, then the seam self-test: a seam mechanism the scenario uses that fails its self-test on
    the loaded MuJoCo and backend raises :class:`~mjpoincare.simulation.seam_check.MechanismFailed` (both before any
    simulation of the scenario)."""
    scenario, preset_name, params, settings = resolve_values(name, assignments, preset)
    seam_check.require(scenario.seam_mechanisms_for(params), str(settings["backend"]), str(settings["precision"]))
    return scenario, preset_name, params, settings


def peer_of(scenario: scenarios.Scenario, name: str, params: Mapping[str, object]) -> Peer:
    """The scenario's peer called ``name``, its parameters checked against the peer's model; one line naming the
    scenarios that have such a peer when this one has none (before any simulation)."""
    for peer in scenario.peers:
        if peer.name == name:
            peer.check_params(params)
            return peer
    others = [s for s in scenarios.loadable() if any(peer.name == name for peer in scenarios.REGISTRY[s].peers)]
    raise ParameterError(f"--peer {name} is for {', '.join(others) or 'no scenario'} only (got {scenario.name})")


def stability_check(diverged: int, warnings: int) -> Check:
    """A run is stable when no trajectory diverged (NaN or MuJoCo reset) and MuJoCo raised no warning."""
    count = float(diverged + warnings)
    return Check(name="stable", analytic=0.0, simulated=count, error=count, tolerance=0.0, kind="count", unit="",
                 why="diverged trajectories + MuJoCo warnings: any is a failure, never silent")


def missing_checks(declared: Iterable[str], reported: Iterable[Check]) -> list[Check]:
    """A failing check (kind ``missing``, error NaN) for each of the ``declared`` checks (the scenario's
    :meth:`~mjpoincare.scenarios.base.Scenario.checks_for`) not among the ``reported`` ones, in the declared order."""
    seen = {check.name for check in reported}
    return [Check(name=name, analytic=math.nan, simulated=math.nan, error=math.nan, tolerance=0.0, kind="missing",
                  unit="", why=f"the scenario declares {name} at these parameters and the run did not report it: a "
                  "check that disappears from a run fails it")
            for name in declared if name not in seen]


def run_validation(name: str, assignments: Mapping[str, Value] | None = None, preset: str | None = None,
                   seed: int = 0, peer: str | None = None) -> Result:
    """Validate scenario ``name`` with ``--set``-style ``assignments`` under ``preset``; with ``peer``, add that
    simulator's value of each check (:func:`mjpoincare.engines.peers.compare.compare`) as the result's ``peer``.

    The result's checks: the scenario's, in the order it reports them, then a failing one for each check it declares
    at these inputs and did not report (:func:`missing_checks`), then ``stable``."""
    scenario, preset_name, params, settings = resolve_inputs(name, assignments or {}, preset)
    outside = peer_of(scenario, peer, params) if peer else None
    start = time.perf_counter()
    evaluation = scenario.evaluate(params, settings, preset_name, seed)
    wall = time.perf_counter() - start
    scenarios.check_evaluation(scenario, evaluation)
    report = evaluation.rollout
    diverged = [int(i) for i in report.diverged.nonzero()[0]]
    checks = [*evaluation.checks, *missing_checks(scenario.checks_for(params, settings), evaluation.checks),
              stability_check(len(diverged), len(report.warnings))]
    timing = {"wall_s": wall, "rollout_wall_s": report.wall_s, "steps": int(report.steps),
              "steps_per_s": report.steps / wall, "rollout_steps_per_s": report.steps_per_s,
              "compile_s": report.compile_s, "batch_steps": int(report.batch_steps)}
    diagnostics = None
    if int(settings["diagnostics"]) and report.sensor_min.size >= len(sim_settings.DIAGNOSTIC_SENSORS):
        diagnostics = {"max_penetration_m": max(0.0, -float(report.sensor_min[0])),
                       "max_kinetic_energy_J": float(report.sensor_max[1]),
                       "initial_kinetic_energy_J": float(report.sensor_first[1])}
    return Result(scenario=scenario.name, preset=preset_name, seed=seed, params=params,
                  settings=sim_settings.as_json(settings), mujoco_version=mujoco.__version__, checks=checks,
                  timing=timing, warnings=report.warnings, diverged=diverged, extras=dict(evaluation.extras),
                  analytic=evaluation.analytic, fit=evaluation.fit, return_map=evaluation.return_map,
                  section_convergence=evaluation.section_convergence, basins=evaluation.basins,
                  reported=dict(evaluation.reported), diagnostics=diagnostics,
                  peer=None if outside is None else compare(outside, params, checks))
