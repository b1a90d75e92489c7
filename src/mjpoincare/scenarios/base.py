"""What a scenario is: one model + its parameters + its analytic reference + its tolerances.

A :class:`Scenario` is declared once (in its own module) and used by the CLI, the tests, the
benchmark and the renderer alike; :mod:`mjpoincare.scenarios` keeps the registry.

Tolerances and their reasons. A scenario's ``tolerances`` field maps a preset to its :class:`Tolerances` (the bound
of each check by name, and why; rimless-wheel-3d: one such table per impact mode); :func:`at_preset` reads it, and a
preset without tolerances is an error, never a fallback.
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

import mujoco
import numpy as np

from mjpoincare.analysis.checks import Check
from mjpoincare.core.outputs import (
    AnalyticValues,
    BasinMap,
    FitSummary,
    Reported,
    ReturnMapPlot,
    SectionConvergence,
)
from mjpoincare.core.params import Param, ParameterError, PluginDeprecationWarning, Values, did_you_mean
from mjpoincare.core.seam import RolloutReport
from mjpoincare.core.settings import SEARCH_SPACE, Dimension
from mjpoincare.engines.peers import Peer
from mjpoincare.scenarios.gate_cases import GateCase
from mjpoincare.scenarios.paper_results import PaperResult

T = TypeVar("T")


class MissingTolerances(LookupError):
    """A scenario offers a preset for which it declares no tolerances (a bug in the scenario, not in its input)."""


class DeclarationError(ParameterError, TypeError):
    """A mistake in a scenario's declaration or in what its ``evaluate`` returns (the system author's, not the user's
    input): one line naming the field and the fix; the commands exit 2 with it, as for a refused input."""


def at_preset(table: Mapping[str, T], scenario: str, preset: str) -> T:
    """``table[preset]``: a scenario's tolerances (or the reasons for them) at ``preset``.

    A preset the table does not name raises :class:`MissingTolerances` naming the scenario and the preset: a run is
    never judged against another preset's tolerances.
    """
    try:
        return table[preset]
    except KeyError:
        raise MissingTolerances(f"scenario {scenario!r} declares no tolerances for preset {preset!r} "
                                f"(declared: {', '.join(table)})") from None


@dataclass(frozen=True)
class Tolerances:
    """A preset's tolerances: the bound of each check, and why each bound is what it is.

    Attributes:
        bounds: check name -> bound (absolute or relative, as the check's ``kind`` says).
        why: what sets the error at this preset and what was measured (the sentence the checks' texts end with).
        reasons: check name -> the reason for that check's bound, where it has its own.
    """

    bounds: Mapping[str, float]
    why: str = ""
    reasons: Mapping[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        """Refuse a bound that is not a finite positive number (0 would fail every run, NaN pass none, in a way that
        reads as physics)."""
        for check, bound in self.bounds.items():
            if isinstance(bound, bool) or not isinstance(bound, (int, float)) or not math.isfinite(bound) \
                    or bound <= 0:
                raise DeclarationError(f"Tolerances: the bound of {check!r} must be a finite number > 0 (got "
                                       f"{bound!r})")

    def __getitem__(self, check: str) -> float:
        """The bound of ``check``; one that the table does not bound raises :class:`DeclarationError` naming the
        bounds it has."""
        try:
            return self.bounds[check]
        except KeyError:
            raise DeclarationError(f"Tolerances: no bound for {check!r}{did_you_mean(check, self.bounds)} (bounds: "
                                   f"{', '.join(self.bounds)})") from None


#: A scenario's tolerances by preset.
ToleranceTable = Mapping[str, Tolerances]


@dataclass(frozen=True)
class JointIndex:
    """Where a joint's coordinates start in ``qpos`` and its velocities in ``qvel``/``qacc`` (``jnt_qposadr``,
    ``jnt_dofadr``): measurement code resolves each joint by name once per model and reads the state through it.

    Attributes:
        qpos: the joint's first coordinate in ``qpos``.
        dof: the joint's first degree of freedom in ``qvel`` and ``qacc``.
    """

    qpos: int
    dof: int

    @classmethod
    def of(cls, model: mujoco.MjModel, name: str) -> JointIndex:
        """The indices of joint ``name`` in ``model`` (raises KeyError for a joint the model does not have)."""
        joint = model.joint(name)
        return cls(qpos=int(joint.qposadr[0]), dof=int(joint.dofadr[0]))


@dataclass
class Evaluation:
    """A scenario's run: its checks, what the rollouts did, the typed outputs the commands read, and free-form extras.

    Attributes:
        checks: the checks, in the order the table shows them.
        rollout: what the rollouts did (steps, wall time, divergence, MuJoCo's warnings).
        extras: anything else worth keeping (JSON-ready values), written under the result's ``extras`` key: no
            command reads it, and no key of it can overwrite a field of the result.
        analytic: the theory's eigenvalues and values at these parameters (``sweep``'s analytic column).
        fit: the fitted return map (``sweep``'s fitted column, the report's eigenvalue plot).
        return_map: the report's return-map figure.
        section_convergence: the report's panel for a map with no 1-D analytic form.
        basins: the report's basin figure.
        reported: figures the table shows under the checks without judging them, by name.
    """

    checks: list[Check]
    rollout: RolloutReport
    extras: dict[str, Any] = field(default_factory=dict)
    analytic: AnalyticValues | None = None
    fit: FitSummary | None = None
    return_map: ReturnMapPlot | None = None
    section_convergence: SectionConvergence | None = None
    basins: BasinMap | None = None
    reported: dict[str, Reported] = field(default_factory=dict)

    def __post_init__(self) -> None:
        """Refuse, in one line naming the field and its record, an extra under a name that is now a typed field
        (a plugin written when ``extras["fit"]`` and the like were how the commands found these values)."""
        for key in sorted(self.extras.keys() & TYPED_EXTRAS.keys()):
            name, record = TYPED_EXTRAS[key]
            raise DeclarationError(f"Evaluation: extras[{key!r}] is now the field {name}= (a "
                                   f"mjpoincare.plugin.{record}), not an extra")
        if not isinstance(self.rollout, RolloutReport):
            raise DeclarationError(f"Evaluation: rollout= must be the RolloutReport of the scenario's rollouts (what "
                                   f"rollout_batch or event_rollout returns; got {type(self.rollout).__name__})")
        if not isinstance(self.checks, (list, tuple)) or not all(isinstance(c, Check) for c in self.checks):
            raise DeclarationError("Evaluation: checks= must be a list of Check (made by relative, absolute, "
                                   "fraction or categorical)")


#: Former extras that are now fields of :class:`Evaluation`: key -> (field, record).
TYPED_EXTRAS = {"analytic": ("analytic", "AnalyticValues"), "fit": ("fit", "FitSummary"),
                "return_map": ("return_map", "ReturnMapPlot"),
                "section_convergence": ("section_convergence", "SectionConvergence"),
                "basins": ("basins", "BasinMap"), "basin_bands": ("basins", "BasinMap"),
                "reported": ("reported", "Reported")}


@dataclass(frozen=True)
class StressCase:
    """One edge case of ``mjpoincare stress``: ``--set``-style ``assignments`` on top of the fast preset.

    ``expect``: ``"run"`` (must run without crash or unreported NaN) or ``"refused"`` (outside the theory's
    assumptions: the input check must refuse it with exit 2).
    """

    name: str
    assignments: Mapping[str, str]
    why: str
    expect: str = "run"


@dataclass(frozen=True)
class Soak:
    """A long run from the fixed point: one section coordinate per impact, and its analytic fixed-point value."""

    samples: np.ndarray
    analytic: float
    label: str
    rollout: RolloutReport


@dataclass(frozen=True)
class Rival:
    """The nearest plausible wrong physics a simulator or a model could have for one check, and how far from the
    theory it puts the check: the check tells the right physics from this one only where the distance exceeds the
    tolerance plus the measured error and its spread (``docs/results/discrimination.md``).

    Attributes:
        physics: what is wrong, in the papers' terms (one line: the asymptotic row of a table, a sticking impact law
            where the paper slips, a hub inertia the wheel does not have, ...).
        distance: ``(params) -> error``: the check's error, in the check's own measure (its ``kind``: relative,
            absolute, max-abs over matched eigenvalues, ...; a category check: 1.0 where the rival's category
            differs, 0.0 where it is the same), that a simulator reproducing the rival physics exactly would show at
            the scenario's parameters ``params``, computed from the theory under both physics. None: no check can
            tell them apart (``indistinct`` says why).
        indistinct: one line: why no check at any parameter the scenario offers can tell the rival from the theory.
        weak: one line: why none of the scenario's gate cases tells the rival apart with this check although the
            theory puts it at a distance (the distance against what the tolerance and the measured error let
            through, and which check does tell it); only where no gate case's ratio exceeds 1.
    """

    physics: str
    distance: Callable[[Values], float] | None = None
    indistinct: str = ""
    weak: str = ""

    def __post_init__(self) -> None:
        if (self.distance is None) == (not self.indistinct):
            raise ValueError(f"rival {self.physics!r}: give its distance, or why no check can tell it apart")


@dataclass(frozen=True)
class CoveragePoint:
    """A parameter point the preset search (``mjpoincare tune``) judges every trial at: a preset holds only where it
    holds at all of a scenario's coverage points.

    Attributes:
        name: short label (tables, the study's JSON).
        assignments: ``--set``-style parameter values on top of the scenario's defaults.
        why: what makes the point hard (a bound it sits near, a gait, a mode).
        miss_at: the target presets at which the point is a declared miss (no setting is known to pass it): a trial
            still runs it, after the judged points, and the study reports its best trial there, but it counts in
            neither objective.
    """

    name: str
    assignments: Mapping[str, str]
    why: str
    miss_at: tuple[str, ...] = ()


class RegionMapCompute(Protocol):
    """A region map's computation (:attr:`RegionMap.compute`) on resolved inputs."""

    def __call__(self, params: Values, settings: Values, preset: str, x: np.ndarray, y: np.ndarray, *,
                 workers: int) -> dict[str, Any]:
        """The map over the grid ``x`` x ``y``.

        Args:
            p: the scenario's checked parameters.
            s: the checked simulator settings.
            preset: the preset's name.
            x: the values of the map's first axis, shape (nx,).
            y: the values of its second axis, shape (ny,).
            workers: processes the map may use for independent work (a map may need more, or run in one).

        Returns:
            The map's data (numbers, arrays, texts; JSON once :func:`~mjpoincare.analysis.checks.jsonable` has
            converted it), which :attr:`RegionMap.summary`, :attr:`RegionMap.plot` and :attr:`RegionMap.passed` read.
        """
        ...


@dataclass(frozen=True)
class RegionMap:
    """The ``mjpoincare sweep SCENARIO --grid`` facet: a map over a grid of two axes, simulated against the reference.

    It computes on resolved inputs and returns data; the command parses the grid, resolves the inputs (both before any
    simulation), prints :attr:`summary`, writes the PNG and the JSON (``scenario`` and the data) and returns the exit
    code from :attr:`passed`.

    Attributes:
        axes: the grid's two axes (their names, what they are and their bounds), in the order :attr:`compute` takes
            them; ``--grid`` is :func:`~mjpoincare.core.params.parse_grid` over them.
        output: the PNG path when ``-o`` is not given (``{scenario}`` is filled in).
        compute: the map (:class:`RegionMapCompute`).
        summary: ``(data) -> text``: what the command prints.
        plot: ``(data, path)``: writes the PNG at ``path``.
        passed: ``(data) -> bool``: the map agrees with the reference (exit 0; else 1).
    """

    axes: tuple[Param, Param]
    output: str
    compute: RegionMapCompute
    summary: Callable[[dict[str, Any]], str]
    plot: Callable[[dict[str, Any], str], None]
    passed: Callable[[dict[str, Any]], bool]


class SweepPlan(Protocol):
    """A scenario's sweep's work ahead of its simulation (:attr:`ParamSweep.plan`)."""

    def __call__(self, params: Values, settings: Values, values: Sequence[float], *, workers: int) -> list[tuple[Any,
                                                                                                                 ...]]:
        """The reference at each value, grouped into the jobs of :attr:`ParamSweep.compute`.

        Args:
            p: the scenario's checked parameters (the swept one at its declared value).
            s: the checked simulator settings.
            values: the values to run, increasing.
            workers: processes the references may use (a sweep may need more).

        Returns:
            Each job's arguments after ``(p, s, preset)``.
        """
        ...


@dataclass(frozen=True)
class ParamSweep:
    """A scenario's own sweep of one of its parameters (``mjpoincare sweep SCENARIO --param NAME``), in place of the
    generic one validation per value: the values simulated together and judged as a whole.

    It computes on resolved inputs and returns data; the command resolves the other inputs and checks the values
    against the parameter's declared range (before any simulation), keeps the rows in the resumable results file
    (:class:`~mjpoincare.core.parallel.ResumableRows`, one row per value, ``row[NAME]`` the value), prints :attr:`table`
    and the timing, and returns the exit code from :attr:`passed`.

    Attributes:
        plan: the references and the jobs (:class:`SweepPlan`).
        compute: ``(p, s, preset, *job) -> rows``: one job's rows, one per value (JSON once ``jsonable`` has converted
            them; a NaN is written as null and read back as NaN on resume).
        summarize: ``(p, rows) -> summary``: the sweep's summary over all rows (the JSON's ``summary``).
        table: ``(rows, summary) -> text``: what the command prints.
        passed: ``(summary) -> bool``: the sweep agrees with the reference (exit 0; else 1).
    """

    plan: SweepPlan
    compute: Callable[..., list[dict[str, Any]]]
    summarize: Callable[[Values, list[dict[str, Any]]], dict[str, Any]]
    table: Callable[[list[dict[str, Any]], dict[str, Any]], str]
    passed: Callable[[dict[str, Any]], bool]


@dataclass(frozen=True)
class Foot:
    """What the ``foot_radius`` setting is in a scenario's model.

    Attributes:
        meaning: the spheres of that radius and what they stand for (``mjpoincare list`` shows it), e.g. the point
            feet of the paper's model made contact spheres, and the bias they add.
        low: the smallest radius the preset search tries, m.
        high: the largest, m; also ``bench``'s "large foot" row.
    """

    meaning: str
    low: float = 1e-4
    high: float = 2e-3


#: Fields of :class:`Scenario` renamed, old name -> new name: a declaration (``Scenario(probe=...)``) or a read
#: (``scenario.probe``) by the old name still works until the next release, with a :class:`PluginDeprecationWarning`.
RENAMED_FIELDS: dict[str, str] = {
    "probe": "validation_batches",
    "clip": "video_states",
    "reference_bench": "exact_model_bench",
    "mechanisms": "seam_mechanisms",
    "mechanisms_at": "seam_mechanisms_at",
    "check_inputs": "check_params_with_settings",
    "accuracy_checks": "bench_checks",
}
#: :data:`RENAMED_FIELDS` and the renamed methods: what a read by the old name reaches.
RENAMED_ATTRIBUTES: dict[str, str] = {**RENAMED_FIELDS, "mechanisms_for": "seam_mechanisms_for"}


def _renamed_fields(kwargs: dict[str, Any]) -> dict[str, Any]:
    """``kwargs`` of a :class:`Scenario` with each old field name replaced by its new one, one
    :class:`PluginDeprecationWarning` for each (attributed to the declaration); both names given is a
    :class:`DeclarationError`."""
    out = dict(kwargs)
    for old, new in RENAMED_FIELDS.items():
        if old in out:
            if new in out:
                raise DeclarationError(f"Scenario: {old}= is the old name of {new}=: give {new}= only")
            warnings.warn(f"Scenario: {old}= is renamed {new}= (the old name works until the next release)",
                          PluginDeprecationWarning, stacklevel=3)
            out[new] = out.pop(old)
    return out


def _accept_renamed(cls: type[T]) -> type[T]:
    """``cls`` (a dataclass) whose ``__init__`` takes the old names of :data:`RENAMED_FIELDS` as well."""
    init = cls.__init__

    @functools.wraps(init)
    def __init__(self: T, *args: Any, **kwargs: Any) -> None:
        init(self, *args, **_renamed_fields(kwargs))

    cls.__init__ = __init__  # type: ignore[misc]
    return cls


@_accept_renamed
@dataclass(frozen=True)
class Scenario:
    """A validation scenario.

    Attributes:
        name: CLI name, e.g. ``rimless-wheel``.
        summary: one line for ``mjpoincare list``.
        source: the paper and equations the analytic reference comes from.
        params: the physical parameters with defaults and bounds.
        presets: simulator-setting overrides per preset name (``fast``, ``accurate``).
        check_params: cross-parameter validation (raises :class:`ParameterError`).
        check_params_with_settings: ``(params, settings) -> None``: the parameters and the simulator settings checked
            together (raises :class:`ParameterError`, one line naming both), before any simulation; None: nothing
            couples them.
        default: part of the default validation (``mjpoincare validate`` with no scenario named, the main job).
        foot: what the ``foot_radius`` setting is in this scenario's model and the preset search's range for it
            (:class:`Foot`); None: the model has no foot spheres, and ``converge``'s foot axis, ``bench``'s foot row
            and the search leave ``foot_radius`` out.
        build: ``(params, settings) -> MjModel``.
        evaluate: ``(params, settings, preset, seed) -> Evaluation``; ``preset`` picks the tolerances.
        bench_checks: the checks whose errors ``bench`` sets against wall time (the first: the Pareto axis), and
            whose simulated values ``stress`` watches for a run that left its cycle.
        validation_batches: ``(params, settings) -> (model, [(initial states, nstep), ...])``: the rollout batches
            ``evaluate`` runs, built and not stepped: a run's steps are counted from them before it starts (the cost
            check), and ``mujoco.rollout`` is timed alone on the same work.
        exact_model_bench: ``(params, rtol) -> dict`` time and error of the exact-model (solve_ivp) reference run at
            tolerance ``rtol`` through the same fit (keys ``rtol``, ``wall_s``, ``<check>_error``), for ``bench``.
        video_states: ``(params, settings, model, nstep) -> states (nstep, nstate)``: one trajectory's full-physics
            states to render (simulated with whatever controller the scenario needs), or ``(states, mocap_pos)``
            with the mocap positions (nstep, nmocap, 3) of each row.
        track_body: body the render camera follows.
        frame_tilt: parameter whose value (rad) rotates rendered frames (a slope made by tilted gravity).
        camera_distance: render camera distance, m.
        camera_elevation: render camera elevation, degrees (0: side view of a sagittal-plane model; -89: from
            above, for a system moving in the ground plane).
        default_preset: preset used when none is named.
        stress_cases: the scenario's own edge cases for ``mjpoincare stress`` (extreme parameters); the
            simulator-setting edges (timestep ladder, integrators, solvers, cones, contact softness) are generic.
        soak: ``(params, settings, impacts) -> Soak``: ``impacts`` impacts from the fixed point (None: the scenario
            has no limit cycle to soak on).
        region_map: the optional ``sweep --grid`` facet (:class:`RegionMap`; None: the scenario has no region map,
            and ``--grid`` is refused).
        param_sweeps: the scenario's own sweeps by parameter name (:class:`ParamSweep`), run by ``sweep --param NAME``
            in place of the generic sweep; every other parameter or setting gets the generic sweep.
        seam_mechanisms: the seam mechanisms its event controllers and checks use (keys of
            :data:`mjpoincare.simulation.seam_check.MECHANISMS`), each self-tested on the loaded MuJoCo before the
            scenario runs.
        coverage: the parameter points that span the scenario's range (:class:`CoveragePoint`; the defaults first):
            the preset search judges each trial at all of them.
        search_space: the settings the preset search varies (:class:`~mjpoincare.core.settings.Dimension`); the preset's
            other settings are the scene's own and stay as declared.
        peers: outside simulators' models of the system (:class:`~mjpoincare.engines.peers.Peer`), for ``validate
        --peer``
            and the bench's peer rows.
        tolerances: preset -> :class:`Tolerances` (or mode -> such a table): what ``evaluate`` judges each check
            against, and why.
        seam_mechanisms_at: ``(params) -> mechanisms`` when a run uses fewer than all of ``seam_mechanisms`` (a mode
            of the scenario that needs one the others do not): a backend that lacks it refuses only those runs.
        gate_cases: the runs the regression gate asserts (:class:`~mjpoincare.scenarios.gate_cases.GateCase`; the
            defaults at every preset at least), each check in its form: gated, watched or a declared miss.
        checks: every check ``evaluate`` reports at some inputs, by name and in its order (not ``stable``, which the
            validation appends to every run). A run reports :meth:`checks_for` of them, and
            :func:`mjpoincare.commands.validation.run_validation` appends a failing check of kind ``missing`` for each
            of those it does not report: a check that disappears fails. A check measured only where the samples allow (a
            fit that needs 3 sample pairs) is declared all the same, so that a run whose samples do not allow it fails.
            Empty: the scenario declares nothing, and nothing is appended.
        checks_at: ``(params, settings) -> checks``, in ``checks``' order, where a run reports fewer than all of
            ``checks``: the paper has the quantity at some parameters only (a gait, a friction regime), or the
            settings decide it (an exact step's phases as classified on the timestep's grid); None: all of ``checks``.
        rivals: check name -> its :class:`Rival`: every check of ``checks`` has one (the contract test holds the
            scenarios to it).
        paper_results: the papers' results the scenario covers
            (:class:`~mjpoincare.scenarios.paper_results.PaperResult`), each with how MuJoCo is run for it
            (``mjpoincare reproduce``, ``docs/results/papers/``).
    """

    name: str
    summary: str
    source: str
    params: tuple[Param, ...]
    presets: Mapping[str, Values]
    check_params: Callable[[Values], None]
    build: Callable[[Values, Values], mujoco.MjModel]
    evaluate: Callable[[Values, Values, str, int], Evaluation]
    bench_checks: tuple[str, ...]
    validation_batches: Callable[[Values, Values], tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]]
    exact_model_bench: Callable[[Values, float], dict[str, float]]
    video_states: Callable[[Values, Values, mujoco.MjModel, int], np.ndarray | tuple[np.ndarray, np.ndarray]]
    track_body: str
    frame_tilt: str | None = None
    camera_distance: float = 3.0
    camera_elevation: float = 0.0
    default_preset: str = "fast"
    stress_cases: tuple[StressCase, ...] = ()
    soak: Callable[[Values, Values, int], Soak] | None = None
    region_map: RegionMap | None = None
    param_sweeps: Mapping[str, ParamSweep] = field(default_factory=dict)
    seam_mechanisms: tuple[str, ...] = ()
    coverage: tuple[CoveragePoint, ...] = (CoveragePoint("defaults", {}, "the scenario's default parameters"),)
    search_space: tuple[Dimension, ...] = SEARCH_SPACE
    peers: tuple[Peer, ...] = ()
    tolerances: ToleranceTable | Mapping[str, ToleranceTable] = field(default_factory=dict)
    gate_cases: tuple[GateCase, ...] = ()
    seam_mechanisms_at: Callable[[Values], tuple[str, ...]] | None = None
    checks: tuple[str, ...] = ()
    checks_at: Callable[[Values, Values], tuple[str, ...]] | None = None
    rivals: Mapping[str, Rival] = field(default_factory=dict)
    check_params_with_settings: Callable[[Values, Values], None] | None = None
    default: bool = False
    foot: Foot | None = None
    paper_results: tuple[PaperResult, ...] = ()

    def seam_mechanisms_for(self, params: Values) -> tuple[str, ...]:
        """The seam mechanisms a run at ``params`` uses: ``seam_mechanisms_at(params)``, or all of
        ``seam_mechanisms``."""
        return self.seam_mechanisms if self.seam_mechanisms_at is None else self.seam_mechanisms_at(params)

    def checks_for(self, params: Values, settings: Values) -> tuple[str, ...]:
        """The checks a run at ``params`` and ``settings`` reports (checked inputs): ``checks_at(params,
        settings)``, or ``checks``."""
        return self.checks if self.checks_at is None else self.checks_at(params, settings)

    @property
    def search_dimensions(self) -> tuple[Dimension, ...]:
        """:attr:`search_space` with ``foot_radius`` over the scenario's own range (:attr:`foot`), or without it
        when the model has no feet."""
        out = []
        for dim in self.search_space:
            if dim.name == "foot_radius":
                if self.foot is None:
                    continue
                dim = replace(dim, low=self.foot.low, high=self.foot.high)
            out.append(dim)
        return tuple(out)

    @property
    def tolerance_modes(self) -> dict[str, ToleranceTable]:
        """The scenario's preset -> :class:`Tolerances` tables by mode (rimless-wheel-3d: one per impact mode); a
        scenario without modes has its one table under ``""``."""
        table: Mapping[str, Any] = self.tolerances
        return {"": table} if set(table) & set(self.presets) else dict(table)

    @property
    def tolerance_tables(self) -> list[ToleranceTable]:
        """The scenario's preset -> :class:`Tolerances` tables: its one, or one per mode (rimless-wheel-3d)."""
        return list(self.tolerance_modes.values())

    if not TYPE_CHECKING:  # a type checker sees the new names only
        def __getattr__(self, name: str) -> Any:
            """A renamed field or method read by its old name (:data:`RENAMED_ATTRIBUTES`), with a
            :class:`PluginDeprecationWarning`."""
            new = RENAMED_ATTRIBUTES.get(name)
            if new is None:
                raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
            warnings.warn(f"Scenario.{name} is renamed Scenario.{new} (the old name works until the next release)",
                          PluginDeprecationWarning, stacklevel=2)
            return getattr(self, new)

    def preset(self, name: str | None) -> tuple[str, Values]:
        """The preset's name and setting overrides (the default preset when ``name`` is None)."""
        name = name or self.default_preset
        if name not in self.presets:
            raise ParameterError(f"preset must be one of {', '.join(self.presets)} (got {name!r})")
        return name, self.presets[name]
