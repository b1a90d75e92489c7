"""Simulator settings (timestep, integrator, contact softness, ...) and how they reach an MjSpec.

Settings are declared as :class:`~mjpoincare.core.params.Param` records so that ``--set timestep=1e-4``
is checked exactly like a physical parameter. Each scenario names its presets (``fast``,
``accurate``) as partial overrides of :data:`DEFAULTS`; the preset's tolerances live with the
scenario, because the error a setting produces depends on the system.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import mujoco

from mjpoincare.core.parallel import machine_cores
from mjpoincare.core.params import Param, Value

INTEGRATORS = {
    "euler": mujoco.mjtIntegrator.mjINT_EULER,
    "implicit": mujoco.mjtIntegrator.mjINT_IMPLICIT,
    "implicitfast": mujoco.mjtIntegrator.mjINT_IMPLICITFAST,
    "rk4": mujoco.mjtIntegrator.mjINT_RK4,
    **({"discrete": mujoco.mjtIntegrator.mjINT_DISCRETE} if hasattr(mujoco.mjtIntegrator, "mjINT_DISCRETE") else {}),
}
CONES = {"pyramidal": mujoco.mjtCone.mjCONE_PYRAMIDAL, "elliptic": mujoco.mjtCone.mjCONE_ELLIPTIC}
SOLVERS = {"newton": mujoco.mjtSolver.mjSOL_NEWTON, "cg": mujoco.mjtSolver.mjSOL_CG, "pgs": mujoco.mjtSolver.mjSOL_PGS}
JACOBIANS = {"auto": mujoco.mjtJacobian.mjJAC_AUTO, "dense": mujoco.mjtJacobian.mjJAC_DENSE,
             "sparse": mujoco.mjtJacobian.mjJAC_SPARSE}
#: Sensors the ``diagnostics`` setting adds (rollouts record their min and max): the smallest contact distance
#: (negative = penetration) over all contacts, and the kinetic energy.
DIAGNOSTIC_SENSORS = ("min_contact_distance", "kinetic_energy")
BACKENDS = ("mujoco", "mjx", "warp", "drake")
#: The precisions each backend runs in (MuJoCo C: double only; MuJoCo Warp: single only).
BACKEND_PRECISIONS = {"mujoco": ("float64",), "mjx": ("float64", "float32"), "warp": ("float32",),
                      "drake": ("float64",)}
_CONTACT_DIST, _REDUCE_MINDIST = 8, 1  # MuJoCo contact-sensor data bit "dist" and reduce mode "mindist"


SETTINGS: tuple[Param, ...] = (
    Param("timestep", 1e-4, "integration step, s", float, 0.0, 0.05, low_open=True),
    Param("integrator", "implicitfast", "MuJoCo integrator", str, choices=tuple(INTEGRATORS)),
    Param("cone", "elliptic", "friction cone", str, choices=tuple(CONES)),
    Param("impratio", 10.0, "friction-to-normal impedance ratio (elliptic cone)", float, 0.0, None, True),
    Param("solref_timeconst", 1e-3, "contact time constant, s (MuJoCo clamps it to >= 2 timesteps)",
          float, 0.0, 1.0, low_open=True),
    Param("solref_dampratio", 1.0, "contact damping ratio of the penetration (the unilateral contact still rebounds a "
          "little at 1: docs/adding-a-scenario.md)", float, 0.0, 100.0, True),
    Param("solimp_dmin", 0.99, "solimp d0: impedance at zero penetration", float, 0.0, 1.0, True, True),
    Param("solimp_dmax", 0.999, "solimp d_width: impedance at full width", float, 0.0, 1.0, True, True),
    Param("solimp_width", 1e-4, "solimp width, m", float, 0.0, 1.0, low_open=True),
    Param("foot_radius", 5e-4, "radius of the spheres that stand for a model's point feet, m (what they are in each "
          "scenario, and whether it has any: mjpoincare list)", float, 0.0, 0.05, low_open=True),
    Param("iterations", 100, "constraint solver iterations (20 at tolerance 1e-8 gave wrong impacts)", int, 1, 10000),
    Param("tolerance", 1e-10, "constraint solver tolerance", float, 0.0, 1.0),
    Param("noslip_iterations", 0, "noslip post-processing iterations", int, 0, 1000),
    Param("solver", "newton", "constraint solver", str, choices=tuple(SOLVERS)),
    Param("jacobian", "auto", "constraint Jacobian storage", str, choices=tuple(JACOBIANS)),
    Param("threads", machine_cores(), "rollout threads (default: this machine's cores; results are bit-identical "
          "across thread counts; pin with --set threads=N)", int, 1, 256),
    Param("start_perturbation", 0.0, "relative change of every start state's velocities (a rounding-sized change, "
          "e.g. 1e-12, that must not change a verdict: mjpoincare margins)", float, 0.0, 1e-6),
    Param("unskip", "none", "undo one of the scene's skips, to measure it (bench --skips): collisions = every geom "
          "collides with every other (no filtering to the feet and the ground), contact = contact detection on where "
          "only equality constraints act", str, choices=("none", "collisions", "contact")),
    Param("backend", "mujoco", "simulator the rollouts run on: MuJoCo C, MJX (JAX; extra mjpoincare[mjx]), MuJoCo "
          "Warp (extra mjpoincare[warp]) or Drake's MultibodyPlant (extra mjpoincare[peers]: the scenario's model "
          "translated, docs/engines.md); same models, experiment designs, checks and tolerances", str,
          choices=BACKENDS),
    Param("drake_approximation", "sap", "backend=drake: the discrete contact approximation (Drake's SAP, TAMSI, "
          "Lagged or Similar)", str, choices=("sap", "tamsi", "lagged", "similar")),
    Param("drake_contact", "point", "backend=drake: compliant point contact, or hydroelastic contact where the "
          "geometry allows it (spheres on a half space)", str, choices=("point", "hydroelastic")),
    Param("precision", "auto", "floating point of the rollouts: auto (the backend's first: float64 for MuJoCo C and "
          "MJX, float32 for MuJoCo Warp), float64, or float32 (MJX as RL setups run it; MuJoCo Warp's only one)", str,
          choices=("auto", "float64", "float32")),
    Param("batch", 0, "trajectories per rollout: region maps (sweep --grid) and mu sweeps are split into rollouts of "
          "this many starts, and MJX and Warp pad every smaller rollout to it (padding never seen), so that a run "
          "compiles once; thousands on a GPU. 0: the scenarios' own split and no padding", int, 0, 1_000_000),
    Param("adaptive_stopping", 1, "1: a fitting batch stops once more steps no longer sharpen its fit "
          "(docs/presets.md); 0: the full design, the same at every setting (converge uses it)", int, 0, 1),
    Param("diagnostics", 0, "1: record the deepest penetration and the largest kinetic energy (adds 2 sensors "
          "and the energy computation; off unless asked, as nothing else reads them)", int, 0, 1),
)
DEFAULTS: dict[str, Value] = {p.name: p.default for p in SETTINGS}


@dataclass(frozen=True)
class Dimension:
    """One setting the preset search (``mjpoincare tune``) varies, and its range.

    Attributes:
        name: the setting (a name in :data:`SETTINGS`).
        low, high: the numeric range (ignored with ``choices``).
        log: sample the range on a log scale.
        choices: the values of a categorical setting (or a few values of a numeric one).
        per_timestep: the sampled number is in timesteps; the setting is that number times the trial's timestep
            (the contact time constant: MuJoCo clamps it to >= 2 timesteps, so it is searched from there).
    """

    name: str
    low: float = 0.0
    high: float = 0.0
    log: bool = False
    choices: tuple[Value, ...] = ()
    per_timestep: bool = False


#: The settings a contact scene can be searched over: the step, the contact's time constant (in steps) and damping,
#: the integrator, the friction cone and its impedance ratio, noslip, the foot spheres' radius, and the constraint
#: solver's iterations and tolerance. A scenario searches the subset its physics depends on (a few trials go further
#: in fewer dimensions).
SEARCH_SPACE: tuple[Dimension, ...] = (
    Dimension("timestep", 1e-5, 1e-3, log=True),
    Dimension("solref_timeconst", 2.0, 40.0, log=True, per_timestep=True),
    Dimension("solref_dampratio", 0.5, 10.0, log=True),
    Dimension("integrator", choices=("implicitfast", "euler", "rk4")),
    Dimension("cone", choices=("elliptic", "pyramidal")),
    Dimension("impratio", 1.0, 100.0, log=True),
    Dimension("noslip_iterations", choices=(0, 2, 10)),
    Dimension("foot_radius", 1e-4, 2e-3, log=True),
    Dimension("iterations", choices=(20, 50, 100, 200)),
    Dimension("tolerance", 1e-14, 1e-6, log=True),
)


def search_space(*names: str, extra: tuple[Dimension, ...] = ()) -> tuple[Dimension, ...]:
    """The dimensions of :data:`SEARCH_SPACE` called ``names`` (all of them when none is named), then ``extra``."""
    chosen = [d for d in SEARCH_SPACE if not names or d.name in names]
    missing = set(names) - {d.name for d in chosen}
    if missing:
        raise KeyError(f"not in SEARCH_SPACE: {', '.join(sorted(missing))}")
    return (*chosen, *extra)


def solref(settings: Mapping[str, Value]) -> list[float]:
    """MuJoCo ``solref`` (time constant, damping ratio) from the settings."""
    return [float(settings["solref_timeconst"]), float(settings["solref_dampratio"])]


def solimp(settings: Mapping[str, Value]) -> list[float]:
    """MuJoCo ``solimp`` (d0, d_width, width, midpoint 0.5, power 2) from the settings."""
    return [float(settings["solimp_dmin"]), float(settings["solimp_dmax"]), float(settings["solimp_width"]),
            0.5, 2.0]


def apply_options(spec: mujoco.MjSpec, settings: Mapping[str, Value]) -> None:
    """Set the global simulator options of ``spec`` (timestep, integrator, cone, solver)."""
    spec.option.timestep = float(settings["timestep"])
    spec.option.integrator = INTEGRATORS[str(settings["integrator"])]
    spec.option.cone = CONES[str(settings["cone"])]
    spec.option.impratio = float(settings["impratio"])
    spec.option.iterations = int(settings["iterations"])
    spec.option.tolerance = float(settings["tolerance"])
    spec.option.noslip_iterations = int(settings["noslip_iterations"])
    spec.option.solver = SOLVERS[str(settings["solver"])]
    spec.option.jacobian = JACOBIANS[str(settings["jacobian"])]
    if int(settings["diagnostics"]):
        spec.option.enableflags |= int(mujoco.mjtEnableBit.mjENBL_ENERGY)
        contact = spec.add_sensor(name=DIAGNOSTIC_SENSORS[0], type=mujoco.mjtSensor.mjSENS_CONTACT)
        contact.intprm[:3] = [_CONTACT_DIST, _REDUCE_MINDIST, 1]
        spec.add_sensor(name=DIAGNOSTIC_SENSORS[1], type=mujoco.mjtSensor.mjSENS_E_KINETIC)


def apply_unskip(spec: mujoco.MjSpec, settings: Mapping[str, Value]) -> None:
    """Undo the skip named by the ``unskip`` setting on a fully built ``spec`` (for measuring what it saves)."""
    which = str(settings.get("unskip", "none"))
    if which == "collisions":
        for geom in spec.geoms:
            geom.contype, geom.conaffinity = 1, 1
    elif which == "contact":
        spec.option.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_CONTACT)


def rollout_options(settings: Mapping[str, Value]) -> dict[str, Any]:
    """The keyword arguments every batched rollout takes from the settings (threads, start perturbation, backend,
    precision, batch, and the engine's own options: Drake's contact approximation and contact model)."""
    engine = ({"approximation": str(settings["drake_approximation"]),
               "hydroelastic": settings["drake_contact"] == "hydroelastic"} if settings["backend"] == "drake" else {})
    return {"threads": int(settings["threads"]), "start_perturbation": float(settings["start_perturbation"]),
            "backend": str(settings["backend"]), "precision": str(settings["precision"]),
            "batch": int(settings["batch"]), "engine_options": engine}


def as_json(settings: Mapping[str, Value]) -> dict[str, object]:
    """Settings for a result file: the flat values plus MuJoCo's own ``solref``/``solimp`` vectors."""
    return {**settings, "solref": solref(settings), "solimp": solimp(settings)}
