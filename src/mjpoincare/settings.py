"""Simulator settings (timestep, integrator, contact softness, ...) and how they reach an MjSpec.

Settings are declared as :class:`~mjpoincare.params.Param` records so that ``--set timestep=1e-4``
is checked exactly like a physical parameter. Each scenario names its presets (``fast``,
``accurate``) as partial overrides of :data:`DEFAULTS`; the preset's tolerances live with the
scenario, because the error a setting produces depends on the system.
"""

from __future__ import annotations

from collections.abc import Mapping

import mujoco

from mjpoincare.params import Param, Value

INTEGRATORS = {
    "euler": mujoco.mjtIntegrator.mjINT_EULER,
    "implicit": mujoco.mjtIntegrator.mjINT_IMPLICIT,
    "implicitfast": mujoco.mjtIntegrator.mjINT_IMPLICITFAST,
    "rk4": mujoco.mjtIntegrator.mjINT_RK4,
}
CONES = {"pyramidal": mujoco.mjtCone.mjCONE_PYRAMIDAL, "elliptic": mujoco.mjtCone.mjCONE_ELLIPTIC}

SETTINGS: tuple[Param, ...] = (
    Param("timestep", 1e-4, "integration step, s", float, 0.0, 0.05, low_open=True),
    Param("integrator", "implicitfast", "MuJoCo integrator", str, choices=tuple(INTEGRATORS)),
    Param("cone", "elliptic", "friction cone", str, choices=tuple(CONES)),
    Param("impratio", 10.0, "friction-to-normal impedance ratio (elliptic cone)", float, 0.0, None, True),
    Param("solref_timeconst", 1e-3, "contact time constant, s (MuJoCo clamps it to >= 2 timesteps)",
          float, 0.0, 1.0, low_open=True),
    Param("solref_dampratio", 1.0, "contact damping ratio (>= 1: no rebound)", float, 0.0, 100.0, True),
    Param("solimp_dmin", 0.99, "solimp d0: impedance at zero penetration", float, 0.0, 1.0, True, True),
    Param("solimp_dmax", 0.999, "solimp d_width: impedance at full width", float, 0.0, 1.0, True, True),
    Param("solimp_width", 1e-4, "solimp width, m", float, 0.0, 1.0, low_open=True),
    Param("foot_radius", 5e-4, "radius of the point-foot spheres, m (bias ~ +0.7 r/l)", float, 0.0, 0.05,
          low_open=True),
    Param("iterations", 100, "constraint solver iterations (20 at tolerance 1e-8 gave wrong impacts)", int, 1, 10000),
    Param("tolerance", 1e-10, "constraint solver tolerance", float, 0.0, 1.0),
    Param("noslip_iterations", 0, "noslip post-processing iterations", int, 0, 1000),
    Param("threads", 2, "rollout threads", int, 1, 256),
)
DEFAULTS: dict[str, Value] = {p.name: p.default for p in SETTINGS}


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


def as_json(settings: Mapping[str, Value]) -> dict[str, object]:
    """Settings for a result file: the flat values plus MuJoCo's own ``solref``/``solimp`` vectors."""
    return {**settings, "solref": solref(settings), "solimp": solimp(settings)}
