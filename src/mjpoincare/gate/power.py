"""The gate's power: physics changes of known size planted through the model or the settings, each run through the
gate's cases, and which checks catch it by their tolerance and which by the baseline (:mod:`mjpoincare.gate.baseline`).

A gate that never fails may be watching a stable simulator or be blind; only a planted change of known size tells
which. Each :class:`Plant` changes one thing:

- through the settings: the timestep, solref's time constant and impratio, each scaled by ``1 + size``; the friction
  cone and the integrator, each switched to another choice;
- through the compiled model (:func:`mjpoincare.core.mjcf_loader.planted`, every model the run compiles): gravity, one
  body's mass and rotational inertia together (the body the renders follow: the wheel's hub, the biped's hip, the
  skate), and every geom's sliding friction, each scaled by ``1 + size`` (and a Coulomb coefficient ``mu`` the
  scenario sets per trajectory at run time, which overrides the model's, scaled through its parameter); and one
  contact pair dropped (the first colliding geom of a moving body made to collide with nothing).

A planted run is judged as the gate judges its case: **caught by the tolerance** when a gated or watched check fails
or a declared miss leaves its band (or the run raises: a crash is loud); **caught by the baseline** when a check
moves beyond its allowance (:func:`mjpoincare.core.allowance.allowance`: 3 resolutions, never below a millionth of its
tolerance) from the committed baseline. An unplanted control run of every case must be caught by neither, or nothing
else in the table means anything.
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
from mjpoincare.gate import baseline, records
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios.gate_cases import GateCase

#: The relative sizes of the scaled changes.
SIZES = (1e-4, 1e-3, 1e-2)
#: The other choice a switched setting takes (from the preset's).
SWITCHES = {"cone": {"elliptic": "pyramidal", "pyramidal": "elliptic"},
            "integrator": {"implicitfast": "euler", "euler": "implicitfast", "implicit": "implicitfast",
                           "rk4": "implicitfast"}}


@dataclass(frozen=True)
class Plant:
    """One planted change.

    Attributes:
        change: what is changed (``gravity``, ``timestep``, ``mass_inertia``, ``friction``, ``solref_timeconst``,
            ``impratio``, ``cone``, ``integrator``, ``contact_pair``; ``none``: the control run).
        size: the relative size of a scaled change (``None``: a switch, a drop or the control).
    """

    change: str
    size: float | None = None

    @property
    def label(self) -> str:
        """``change`` with its size, e.g. ``gravity x(1+1e-3)``."""
        return self.change if self.size is None else f"{self.change} x(1+{self.size:g})"


def plants() -> tuple[Plant, ...]:
    """The control, every scaled change at every size of :data:`SIZES`, and the switches and the drop."""
    scaled = ("gravity", "timestep", "mass_inertia", "friction", "solref_timeconst", "impratio")
    return (Plant("none"), *(Plant(c, s) for c in scaled for s in SIZES), Plant("cone"), Plant("integrator"),
            Plant("contact_pair"))


def default_cases() -> tuple[GateCase, ...]:
    """Every scenario's gate case on its defaults at its default preset."""
    out = []
    for name, scenario in scenarios.REGISTRY.items():
        out += [c for c in gate.cases() if c.scenario == name and c.preset == scenario.default_preset and not c.values]
    return tuple(out)


def setting_assignments(plant: Plant, case: GateCase) -> dict[str, Value]:
    """The ``--set`` values of a plant made through the settings, or through a friction parameter the scenario
    applies per trajectory (empty for one made through the model alone)."""
    if plant.change == "friction":
        from mjpoincare.commands.validation import resolve_values

        _, _, params, _ = resolve_values(case.scenario, dict(case.values), case.preset)
        mu = params.get("mu")
        return {"mu": float(mu) * (1.0 + float(plant.size or 0.0))} if isinstance(mu, float) and mu > 0 else {}
    if plant.change in ("timestep", "solref_timeconst", "impratio"):
        from mjpoincare.commands.validation import resolve_inputs

        _, _, _, settings = resolve_inputs(case.scenario, dict(case.values), case.preset)
        return {plant.change: float(settings[plant.change]) * (1.0 + float(plant.size or 0.0))}
    if plant.change in SWITCHES:
        from mjpoincare.commands.validation import resolve_inputs

        _, _, _, settings = resolve_inputs(case.scenario, dict(case.values), case.preset)
        return {plant.change: SWITCHES[plant.change][str(settings[plant.change])]}
    return {}


def model_edit(plant: Plant, body: str) -> Callable[[mujoco.MjModel], str] | None:
    """The edit of a compiled model a plant made through the model makes (None for one made through the settings);
    the edit returns what it changed, in words."""
    scale = 1.0 + float(plant.size or 0.0)
    if plant.change == "gravity":
        def edit(model: mujoco.MjModel) -> str:
            model.opt.gravity[:] *= scale
            return "gravity"
    elif plant.change == "mass_inertia":
        def edit(model: mujoco.MjModel) -> str:
            index = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body)
            if index < 0:
                return f"nothing (no body {body})"
            model.body_mass[index] *= scale
            model.body_inertia[index] *= scale
            mujoco.mj_setConst(model, mujoco.MjData(model))
            return f"body {body}"
    elif plant.change == "friction":
        def edit(model: mujoco.MjModel) -> str:
            model.geom_friction[:, 0] *= scale
            model.pair_friction[:, :2] *= scale
            return "every geom's sliding friction"
    elif plant.change == "contact_pair":
        def edit(model: mujoco.MjModel) -> str:
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
    else:
        return None
    return edit


def run_plant(label: str, plant: Plant) -> dict[str, Any]:
    """The gate case ``label`` run with ``plant``: which checks its tolerance verdicts and the committed baseline
    catch (a module-level function: run in worker processes)."""
    case = gate.case(label)
    edit = model_edit(plant, scenarios.get(case.scenario).track_body)
    assignments = {**dict(case.values), **setting_assignments(plant, case)}
    edited: list[str] = []
    start = time.perf_counter()
    from mjpoincare.commands.validation import run_validation

    try:
        with planted(None if edit is None else lambda m: edited.append(edit(m))):
            result = run_validation(case.scenario, assignments, case.preset, 0)
    except Exception as err:  # a planted change that crashes the run is caught loudly
        return {"case": label, "change": plant.change, "size": plant.size, "raised": f"{type(err).__name__}: {err}",
                "tolerance": [], "baseline": [], "edited": sorted(set(edited)),
                "wall_s": time.perf_counter() - start}
    misses = {m.check: m for m in case.misses}
    by_tolerance = [c.name for c in result.checks
                    if (not misses[c.name].matches(c.error) if c.name in misses else not c.passed)]
    committed = committed_baseline()
    key = baseline.key_of(case.scenario, case.preset, dict(case.values))
    by_baseline = sorted({d.check for d in baseline.deviations(result, committed, key)})
    recorded = committed["runs"][key]["checks"]
    moves = [(abs(c.error - recorded[c.name]["error"])
              / allowance(recorded[c.name]["resolution"], recorded[c.name]["tolerance"], recorded[c.name]["error"]),
              c.name)
             for c in result.checks if c.name in recorded and recorded[c.name]["error"] is not None
             and recorded[c.name]["resolution"] is not None and math.isfinite(c.error)]
    return {"case": label, "change": plant.change, "size": plant.size, "raised": None,
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


def power_rows(cases: Sequence[GateCase], chosen: Sequence[Plant], workers: int) -> list[dict[str, Any]]:
    """Every case under every plant, ``workers`` processes at a time, in (plant, case) order."""
    from mjpoincare.core.parallel import run_jobs

    jobs = [(c.label, p) for p in chosen for c in cases]
    rows = list(run_jobs(run_plant, jobs, workers=workers))
    order = {(label, p.change, p.size): i for i, (label, p) in enumerate(jobs)}
    return sorted(rows, key=lambda r: order[(r["case"], r["change"], r["size"])])


def blind(rows: Sequence[Mapping[str, Any]]) -> list[Mapping[str, Any]]:
    """The planted runs caught by neither the tolerance nor the baseline."""
    return [r for r in rows if r["change"] != "none" and verdict(r) == "-"]


def holds(rows: Sequence[Mapping[str, Any]]) -> bool:
    """Whether every control run is caught by nothing (the table means something only then)."""
    return all(verdict(r) == "-" for r in rows if r["change"] == "none")
