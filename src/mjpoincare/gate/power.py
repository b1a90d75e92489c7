"""The gate's power: physics changes of known size planted through the model or the settings, each run through the
gate's cases; which checks catch it by their tolerance and which by the baseline (:mod:`mjpoincare.gate.baseline`),
next to what the theory says the change does to each check (:mod:`mjpoincare.gate.effects`).

A gate that never fails may be watching a stable simulator or be blind; only a planted change of known size tells
which. Each :class:`Plant` changes one thing, of one of three kinds per scenario (:func:`mjpoincare.gate.effects.kind`):

- a **theory** parameter, moved to ``p (1 + size)`` in the simulated model while every check stays judged against
  the theory at ``p``, through every model the run compiles (:func:`mjpoincare.core.mjcf_loader.planted`): the
  slope (gravity rotated in the plane of motion by ``slope x size``: every sloped model realizes its slope as
  gravity's direction), the radius of gyration (the tracked body's rotational inertia alone x ``(1 + size)^2``),
  gravity's magnitude, the compass biped's hip mass, and the friction wheel's Coulomb coefficient (every geom's and
  the ``mu`` it sets per trajectory);
- a change of the **simulator** the rigid-impact theories do not have: the timestep, solref's time constant and
  damping ratio and impratio scaled through the settings, the cone and the integrator switched, one contact pair
  dropped (the first colliding geom of a moving body made to collide with nothing);
- a **control**, which neither the theory nor the model can see (one body's mass and inertia scaled together,
  gravity on the horizontal skate, friction on a sticking foot, contact settings on a model without contact): run
  at one size, it must be caught by nothing, as must the unplanted run of every case.

A planted run is judged as the gate judges its case: **caught by the tolerance** when a gated or watched check fails
or a declared miss leaves its band (or the run raises: a crash is loud); **caught by the baseline** when a check
moves beyond its allowance (:func:`mjpoincare.core.allowance.allowance`: 3 resolutions, never below a millionth of its
tolerance) from the committed baseline.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import mujoco

from mjpoincare import scenarios
from mjpoincare.core.allowance import allowance
from mjpoincare.core.mjcf_loader import planted
from mjpoincare.core.params import Value
from mjpoincare.gate import baseline, effects, records
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios.gate_cases import GateCase

#: The relative sizes of the scaled changes.
SIZES = (1e-4, 1e-3, 1e-2)
#: The one size a control is run at (the largest: a control that reads "-" there reads "-" below it).
CONTROL_SIZE = SIZES[-1]
#: The changes scaled by ``1 + size``: the theory's parameters, then the simulator's settings, then the controls'.
SCALED = ("slope", "gyration", "gravity", "hip_mass", "friction", "timestep", "solref_timeconst", "solref_dampratio",
          "impratio", "mass_inertia")
#: The changes switched to another choice or dropped (no size).
SWITCHED = ("cone", "integrator", "contact_pair")
#: The settings a change of the simulator scales.
SCALED_SETTINGS = ("timestep", "solref_timeconst", "solref_dampratio", "impratio")
#: The other choice a switched setting takes (from the preset's).
SWITCHES = {"cone": {"elliptic": "pyramidal", "pyramidal": "elliptic"},
            "integrator": {"implicitfast": "euler", "euler": "implicitfast", "implicit": "implicitfast",
                           "rk4": "implicitfast"}}


@dataclass(frozen=True)
class Plant:
    """One planted change.

    Attributes:
        change: what is changed (one of :data:`SCALED` or :data:`SWITCHED`; ``none``: the unplanted control run).
        size: the relative size of a scaled change (``None``: a switch, a drop or the unplanted control).
    """

    change: str
    size: float | None = None

    @property
    def label(self) -> str:
        """``change`` with its size, e.g. ``slope x(1+1e-3)``."""
        return self.change if self.size is None else f"{self.change} x(1+{self.size:g})"


def applies(scenario: str, change: str) -> bool:
    """Whether ``change`` is planted in ``scenario``: a theory parameter only where its theory has it (and the
    model realizes it), a control only where it is declared one, every change of the simulator everywhere."""
    if change in ("slope", "gyration", "hip_mass"):
        return effects.kind(scenario, change) == "theory"
    if change == "mass_inertia":
        return effects.kind(scenario, change) == "control"
    return True


def plants(scenario: str | None = None) -> tuple[Plant, ...]:
    """The unplanted control, then every change planted in ``scenario`` (every scenario's when None): a scaled one at
    every size of :data:`SIZES` (a control at :data:`CONTROL_SIZE` only), a switch or the drop once."""
    names = scenarios.loadable() if scenario is None else [scenario]
    out: dict[Plant, None] = {Plant("none"): None}
    for change in (*SCALED, *SWITCHED):
        for name in names:
            if not applies(name, change):
                continue
            if change in SWITCHED:
                out[Plant(change)] = None
            elif effects.kind(name, change) == "control":
                out[Plant(change, CONTROL_SIZE)] = None
            else:
                out.update(dict.fromkeys(Plant(change, size) for size in SIZES))
    return tuple(out)


def default_cases() -> tuple[GateCase, ...]:
    """Every scenario's gate case on its defaults at its default preset."""
    out = []
    for name in scenarios.loadable():
        preset = scenarios.REGISTRY[name].default_preset
        out += [c for c in gate.cases() if c.scenario == name and c.preset == preset and not c.values]
    return tuple(out)


def setting_assignments(plant: Plant, case: GateCase) -> dict[str, Value]:
    """The ``--set`` values of a plant made through the settings, or through a friction parameter the scenario
    applies per trajectory (empty for one made through the model alone)."""
    from mjpoincare.commands.validation import resolve_inputs

    _, _, params, settings = resolve_inputs(case.scenario, dict(case.values), case.preset)
    scale = 1.0 + float(plant.size or 0.0)
    if plant.change == "friction":
        mu = params.get("mu")
        return {"mu": float(mu) * scale} if isinstance(mu, float) and mu > 0 else {}
    if plant.change in SCALED_SETTINGS:
        return {plant.change: float(settings[plant.change]) * scale}
    if plant.change in SWITCHES:
        return {plant.change: SWITCHES[plant.change][str(settings[plant.change])]}
    return {}


def _tilt(model: mujoco.MjModel, scale: float) -> str:
    """Gravity rotated in the x-z plane (the plane of motion) from slope s = atan2(g_x, -g_z) to s x ``scale``."""
    g = model.opt.gravity
    magnitude, slope = math.hypot(g[0], g[2]), math.atan2(g[0], -g[2])
    g[0], g[2] = magnitude * math.sin(slope * scale), -magnitude * math.cos(slope * scale)
    return f"gravity's direction (slope {slope:.6g} rad)"


def _body(model: mujoco.MjModel, body: str) -> int:
    index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body)
    if index < 0:
        raise KeyError(f"no body {body}")
    return index


def _scale_body(model: mujoco.MjModel, body: str, mass: float, inertia: float) -> str:
    """The body's mass x ``mass`` and its rotational inertia x ``inertia`` (the model's constants recomputed)."""
    index = _body(model, body)
    model.body_mass[index] *= mass
    model.body_inertia[index] *= inertia
    mujoco.mj_setConst(model, mujoco.MjData(model))
    return f"body {body}"


def _drop_contact(model: mujoco.MjModel) -> str:
    """The first colliding geom of a moving body made to collide with nothing."""
    if model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT:
        return "nothing (the model disables contact)"
    colliding = [g for g in range(model.ngeom) if model.geom_bodyid[g] > 0
                 and (model.geom_contype[g] or model.geom_conaffinity[g])]
    if not colliding:
        return "nothing (no colliding geom on a moving body)"
    g = colliding[0]
    model.geom_contype[g] = model.geom_conaffinity[g] = 0
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom {g}"
    return f"{name} of body {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, model.geom_bodyid[g])}"


def _scale_friction(model: mujoco.MjModel, scale: float) -> str:
    model.geom_friction[:, 0] *= scale
    model.pair_friction[:, :2] *= scale
    return "every geom's sliding friction"


def _scale_gravity(model: mujoco.MjModel, scale: float) -> str:
    model.opt.gravity[:] *= scale
    return "gravity"


def model_edit(plant: Plant, body: str) -> Callable[[mujoco.MjModel], str] | None:
    """The edit of a compiled model a plant made through the model makes (None for one made through the settings);
    the edit returns what it changed, in words. ``body``: the scenario's tracked body (the wheel's hub, the biped's
    hip, the skate)."""
    scale = 1.0 + float(plant.size or 0.0)
    edits: dict[str, Callable[[mujoco.MjModel], str]] = {
        "slope": lambda m: _tilt(m, scale),
        "gyration": lambda m: _scale_body(m, body, 1.0, scale**2),
        "gravity": lambda m: _scale_gravity(m, scale),
        "hip_mass": lambda m: _scale_body(m, body, scale, 1.0),
        "mass_inertia": lambda m: _scale_body(m, body, scale, scale),
        "friction": lambda m: _scale_friction(m, scale),
        "contact_pair": _drop_contact,
    }
    return edits.get(plant.change)


def _expected(case: GateCase, plant: Plant, recorded: Mapping[str, Mapping[str, Any]]) -> dict[str, Any]:
    """The plant's kind to the case's scenario, its effect on each recorded check (None: not computed) and the checks
    whose effect exceeds their tolerance: those a simulator reproducing the planted physics exactly would fail."""
    from mjpoincare.commands.validation import resolve_values

    kind = "control" if plant.change == "none" else effects.kind(case.scenario, plant.change)
    computed: effects.Effects = {}
    if kind == "theory":
        _, _, params, _ = resolve_values(case.scenario, dict(case.values), case.preset)
        computed = effects.effects(case.scenario, plant.change, params, plant.size)
    missed = {m.check for m in case.misses}
    effect = {name: (computed.get(name) if kind == "theory" else 0.0) for name in recorded if name != "stable"}
    must_fail = [name for name, e in effect.items() if e is not None and name not in missed
                 and (math.isnan(e) or e > float(recorded[name]["tolerance"]))]
    return {"kind": kind, "effects": effect, "must_fail": must_fail}


def run_plant(label: str, plant: Plant) -> dict[str, Any]:
    """The gate case ``label`` run with ``plant``: which checks its tolerance verdicts and the committed baseline
    catch, and what the theory says the plant does to each (a module-level function: run in worker processes)."""
    case = gate.case(label)
    edit = model_edit(plant, scenarios.get(case.scenario).track_body)
    assignments = {**dict(case.values), **setting_assignments(plant, case)}
    committed = committed_baseline()
    key = baseline.key_of(case.scenario, case.preset, dict(case.values))
    recorded = committed["runs"][key]["checks"]
    expected = _expected(case, plant, recorded)
    edited: list[str] = []
    start = time.perf_counter()
    from mjpoincare.commands.validation import run_validation

    try:
        with planted(None if edit is None else lambda m: edited.append(edit(m))):
            result = run_validation(case.scenario, assignments, case.preset, 0)
    except Exception as err:  # a planted change that crashes the run is caught loudly
        return {"case": label, "change": plant.change, "size": plant.size, **expected,
                "raised": f"{type(err).__name__}: {err}", "tolerance": [], "baseline": [],
                "edited": sorted(set(edited)), "largest_move": [0.0, ""], "wall_s": time.perf_counter() - start}
    misses = {m.check: m for m in case.misses}
    by_tolerance = [c.name for c in result.checks
                    if (not misses[c.name].matches(c.error) if c.name in misses else not c.passed)]
    by_baseline = sorted({d.check for d in baseline.deviations(result, committed, key)})
    moves = [(abs(c.error - recorded[c.name]["error"])
              / allowance(recorded[c.name]["resolution"], recorded[c.name]["tolerance"], recorded[c.name]["error"]),
              c.name)
             for c in result.checks if c.name in recorded and recorded[c.name]["error"] is not None
             and recorded[c.name]["resolution"] is not None and math.isfinite(c.error)]
    return {"case": label, "change": plant.change, "size": plant.size, **expected, "raised": None,
            "settings": {k: v for k, v in assignments.items() if k not in dict(case.values)},
            "edited": sorted(set(edited)), "tolerance": by_tolerance, "baseline": by_baseline,
            "largest_move": list(max(moves, default=(0.0, ""))), "wall_s": time.perf_counter() - start}


def committed_baseline() -> dict[str, Any]:
    """The gate's committed baseline (:func:`mjpoincare.gate.records.committed`: found through the package, from an
    installed wheel as from a checkout)."""
    return baseline.load(str(records.committed(records.BASELINE)))


def verdict(row: Mapping[str, Any]) -> str:
    """A row's cell: ``T`` caught by the tolerance, ``B`` by the baseline, ``-`` by neither (with the counts)."""
    if row["raised"]:
        return "raised"
    parts = [f"T{len(row['tolerance'])}" if row["tolerance"] else "", f"B{len(row['baseline'])}"
             if row["baseline"] else ""]
    return " ".join(p for p in parts if p) or "-"


def jobs(cases: Sequence[GateCase], chosen: Sequence[Plant]) -> list[tuple[str, Plant]]:
    """(case, plant) for every chosen plant planted in each case's scenario, in (plant, case) order."""
    return [(c.label, p) for p in chosen for c in cases if p in plants(c.scenario)]


def power_rows(cases: Sequence[GateCase], chosen: Sequence[Plant], workers: int) -> list[dict[str, Any]]:
    """Every case under every plant planted in its scenario, ``workers`` processes at a time, in (plant, case)
    order."""
    from mjpoincare.core.parallel import run_jobs

    todo = jobs(cases, chosen)
    rows = list(run_jobs(run_plant, todo, workers=workers))
    order = {(label, p.change, p.size): i for i, (label, p) in enumerate(todo)}
    return sorted(rows, key=lambda r: order[(r["case"], r["change"], r["size"])])


def is_control(row: Mapping[str, Any]) -> bool:
    """Whether a row is a control run: unplanted, or a change the case's scenario cannot see."""
    return row["change"] == "none" or row.get("kind") == "control"


def blind(rows: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    """The planted runs that are no control and were caught by neither the tolerance nor the baseline."""
    return [r for r in rows if not is_control(r) and verdict(r) == "-"]


def holds(rows: Sequence[Mapping[str, Any]]) -> bool:
    """Whether every control run is caught by nothing (the table means something only then)."""
    return all(verdict(r) == "-" for r in rows if is_control(r))


@dataclass(frozen=True)
class Smallest:
    """The smallest size of one scaled change in one case that each judge detects (None: none up to the largest).

    Attributes:
        case: the gate case's label.
        change: the planted change.
        kind: ``theory`` or ``simulator`` (:func:`mjpoincare.gate.effects.kind`).
        theory: the smallest size at which the theory says a check must fail its tolerance.
        tolerance: the smallest size the tolerance caught (a run that raised counts).
        baseline: the smallest size the baseline caught.
    """

    case: str
    change: str
    kind: str
    theory: float | None
    tolerance: float | None
    baseline: float | None


def smallest(rows: Sequence[Mapping[str, Any]]) -> list[Smallest]:
    """Per case and scaled change that is no control, the smallest size each judge detects, in the rows' order."""
    groups: dict[tuple[str, str], list[Mapping[str, Any]]] = {}
    for r in rows:
        if r["size"] is not None and not is_control(r):
            groups.setdefault((r["case"], r["change"]), []).append(r)

    def first(group: list[Mapping[str, Any]], caught: Callable[[Mapping[str, Any]], bool]) -> float | None:
        return min((float(r["size"]) for r in group if caught(r)), default=None)

    return [Smallest(case=case, change=change, kind=str(group[0].get("kind", "simulator")),
                     theory=first(group, lambda r: bool(r.get("must_fail"))),
                     tolerance=first(group, lambda r: bool(r["raised"] or r["tolerance"])),
                     baseline=first(group, lambda r: bool(r["baseline"])))
            for (case, change), group in groups.items()]
