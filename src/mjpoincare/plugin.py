"""The extension point for system authors: everything a scenario plugin imports, from one module.

A plugin is a distribution that declares a :class:`Scenario` under the entry point group ``mjpoincare.scenarios``
(docs/adding-a-scenario.md walks through one). It imports from here only; these names are the stable API, and the
modules they live in are not (a plugin that imports them there keeps working while they stay, but no promise is
made). What each group is for:

- **the scenario and its records**: :class:`Scenario` (one model, its parameters, presets, analytic reference and
  tolerances, declared once), :class:`Param` and :data:`Values` (a scenario's parameters and their checked values),
  :class:`Tolerances` and :func:`at_preset`, :class:`Rival` (a check's nearest wrong physics and its distance),
  :class:`Evaluation` (what ``evaluate`` returns), :class:`StressCase`,
  :class:`CoveragePoint`, :class:`Foot` (what the ``foot_radius`` setting is in the model), :class:`Soak`,
  :class:`ParamSweep` with its :class:`SweepPlan`, :class:`RegionMap` with its :class:`RegionMapCompute`, the outside
  peers' :class:`Peer` and :class:`PeerRun`, a rollout's :class:`RolloutReport`, and the gate's :class:`GateCase`,
  :class:`Watch` and :class:`Miss`: every type a field of :class:`Scenario` names;
- **the papers' results a scenario covers** (``mjpoincare reproduce``): :class:`PaperResult` with its MuJoCo run, one
  of :class:`AtValidation` (read off the validation by :func:`check_reader`, :func:`largest_multiplier_reader` or the
  plugin's own reader of a validation's :class:`Result`), :class:`Experiment`, :class:`Curve` (a figure),
  :class:`Bracket` (a bound located by bisection) and :class:`Refusal`; a run returns a :class:`Reading` and reaches
  the validation, the scenario's inputs, model and tolerances through the :class:`Runner` the command passes in;
- **what a run reports beside its checks** (fields of :class:`Evaluation`, read by the commands):
  :class:`AnalyticValues` (the theory's eigenvalues: ``sweep``'s analytic column), :class:`FitSummary` (the fitted
  map: ``sweep``'s fitted column, the report's eigenvalue plot), :class:`ReturnMapPlot`,
  :class:`SectionConvergence` and :class:`BasinMap` (the report's figures), :class:`Reported` (a figure shown under
  the table, not judged); anything else goes into ``Evaluation.extras``, nested under ``extras`` in the JSON;
- **checks**: :class:`Check` and its constructors :func:`relative`, :func:`absolute`, :func:`fraction` and
  :func:`categorical`;
- **the return map**: :func:`sample_pairs` (section samples to (x_k, x_k+1) pairs) and :func:`fit_return_map`
  (polynomial fit, fixed point, multipliers and their bootstrap spread, as :class:`ReturnMapFit`);
- **sections**: :func:`level_crossings` (a signal's crossings of a level, interpolated within a step, as
  :class:`Crossings`);
- **rollouts**: :func:`initial_states` (full-physics states from qpos and qvel, ``(B, nstate)``),
  :func:`rollout_batch` (a batch through ``mujoco.rollout`` in chunks, each handed to a consumer as a
  :class:`Chunk` of ``(B, steps + 1, ...)`` arrays), :func:`event_rollout` (the same with a controller that
  switches contacts and actuators between chunks), :func:`plain_clip` (one trajectory's states for a video);
- **the model**: :func:`load_spec` (a plugin's own MJCF file, by its path, with the shared looks its
  ``<include file="common/looks.xml"/>`` asks for) and :func:`compile_spec` (the spec compiled with the run's
  ``unskip`` setting, a compile error as one line; the gate's planted changes reach models compiled here);
- **simulator settings**: :func:`apply_options`, :func:`apply_unskip`, :func:`solref`, :func:`solimp` (a model
  built from a spec with the run's settings), :func:`rollout_options` (the keyword arguments a rollout takes from
  them), :func:`search_space` and :class:`Dimension` (what ``mjpoincare tune`` searches);
- **errors**: :class:`ParameterError`, raised by ``check_params`` for a refused input (exit 2, one line).
"""

from __future__ import annotations

from mjpoincare.analysis.checks import Check, absolute, categorical, fraction, relative
from mjpoincare.analysis.returnmap import ReturnMapFit, fit_return_map, sample_pairs
from mjpoincare.analysis.sections import Crossings, level_crossings
from mjpoincare.core.mjcf_loader import compile_spec, load_spec
from mjpoincare.core.outputs import (
    AnalyticValues,
    BasinMap,
    FitSummary,
    Reported,
    ReturnMapPlot,
    SectionConvergence,
)
from mjpoincare.core.params import Param, ParameterError, Values
from mjpoincare.core.result import Result
from mjpoincare.core.seam import Chunk, RolloutReport
from mjpoincare.core.settings import (
    Dimension,
    apply_options,
    apply_unskip,
    rollout_options,
    search_space,
    solimp,
    solref,
)
from mjpoincare.engines.peers import Peer, PeerRun
from mjpoincare.scenarios.base import (
    CoveragePoint,
    Evaluation,
    Foot,
    ParamSweep,
    RegionMap,
    RegionMapCompute,
    Rival,
    Scenario,
    Soak,
    StressCase,
    SweepPlan,
    Tolerances,
    at_preset,
)
from mjpoincare.scenarios.gate_cases import GateCase, Miss, Watch
from mjpoincare.scenarios.paper_results import (
    AtValidation,
    Bracket,
    Curve,
    Experiment,
    PaperResult,
    Reading,
    Refusal,
    Runner,
    check_reader,
    largest_multiplier_reader,
)
from mjpoincare.simulation.simulate import event_rollout, initial_states, plain_clip, rollout_batch

__all__ = [
    "AnalyticValues",
    "AtValidation",
    "BasinMap",
    "Bracket",
    "Check",
    "Chunk",
    "CoveragePoint",
    "Crossings",
    "Curve",
    "Dimension",
    "Evaluation",
    "Experiment",
    "FitSummary",
    "Foot",
    "GateCase",
    "Miss",
    "PaperResult",
    "Param",
    "ParamSweep",
    "ParameterError",
    "Peer",
    "PeerRun",
    "Reading",
    "Refusal",
    "RegionMap",
    "RegionMapCompute",
    "Reported",
    "Result",
    "ReturnMapFit",
    "ReturnMapPlot",
    "Rival",
    "RolloutReport",
    "Runner",
    "Scenario",
    "SectionConvergence",
    "Soak",
    "StressCase",
    "SweepPlan",
    "Tolerances",
    "Values",
    "Watch",
    "absolute",
    "apply_options",
    "apply_unskip",
    "at_preset",
    "categorical",
    "check_reader",
    "compile_spec",
    "event_rollout",
    "fit_return_map",
    "fraction",
    "initial_states",
    "largest_multiplier_reader",
    "level_crossings",
    "load_spec",
    "plain_clip",
    "relative",
    "rollout_batch",
    "rollout_options",
    "sample_pairs",
    "search_space",
    "solimp",
    "solref",
]
