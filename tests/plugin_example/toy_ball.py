"""Scenario ``bouncing-ball``: a ball dropped on a plane, MuJoCo's soft contact against its closed form.

A toy written only against mjpoincare's extension point (docs/adding-a-scenario.md): it lives in tests/plugin_example/,
outside the package, and the registry finds it through the entry point ``bouncing-ball = toy_ball:BOUNCING_BALL``
(toy_ball-0.1.dist-info/entry_points.txt) once this folder is on the path.

Analytic reference. MuJoCo's contact is a soft constraint (MuJoCo docs, Computation, "Soft constraints"; Modeling,
"Solver parameters"): while active it sets the acceleration to a1 = (1 - d) a0 + d aref, aref = -b r' - k r, with r
the signed distance, solref = (tau, zeta), b = 2 / (dmax tau), k = d / (dmax^2 tau^2 zeta^2) and the impedance d
(solimp). At d = dmax the penetration is a spring-damper of damping ratio zeta: r'' + 2 zeta w r' + w^2 r = 0,
w = 1 / (tau zeta), so from r = 0, r' = -v, r = -(v / w_d) exp(-zeta w t) sin(w_d t), w_d = w sqrt(1 - zeta^2). The
contact pushes and never pulls: its force d m (g - b r' - k r) vanishes, and the ball leaves, where
2 zeta w r' + w^2 r = 0 (up to g, below): at w_d t = theta, cos theta = 2 zeta^2 - 1, where r' = e v with

    e = exp(-zeta theta / sqrt(1 - zeta^2)),  theta = arccos(2 zeta^2 - 1);  the contact lasts tau ln(1/e).

A spring released at r = 0 (bilateral) would give exp(-pi zeta / sqrt(1 - zeta^2)): 2 % lower at zeta = 0.1, 45 % at
0.5, 0 at 1, where MuJoCo still rebounds (e -> exp(-2)); MuJoCo follows e above (checked at zeta = 0.1-1, timestep
2e-6). A rebound at e v flies 2 e v / g and the apexes obey h_k+1 = e^2 h_k: a linear return map, fixed point 0,
eigenvalue e^2.

What MuJoCo adds (measured on the exact soft-constraint ODE, solve_ivp): the force vanishes 2 zeta^2 tau e v below the
plane and the ball climbs that depth against gravity, slower by 2 g zeta^2 tau / (e v) (the release-depth offset: at
the fast preset -0.06 % at 4.4 m/s, -0.19 % at 1.4 m/s, -0.37 % at 0.7 m/s; half at the accurate one); solimp's
impedance, 0.99 at contact rising to 0.999 within 0.1 mm, adds +0.002 % to +0.04 %. Each impact starts at its own
phase of the step grid, which scatters single impacts' restitution (±1.9 % at 30 steps per contact, ±1 % at 59) and,
through the next flight, the next impact's phase: a 1e-12 change of the starts reshuffles the later impacts.
"""

from __future__ import annotations

import math
import time

import mujoco
import numpy as np
from mjpoincare.analysis import checks
from mjpoincare.analysis.returnmap import fit_return_map, sample_pairs
from mjpoincare.analysis.sections import Crossings, level_crossings
from scipy.integrate import solve_ivp

from mjpoincare import settings as sim_settings
from mjpoincare.params import Param, ParameterError, Values
from mjpoincare.scenarios.base import CoveragePoint, Evaluation, Scenario, Tolerances, at_preset
from mjpoincare.scenarios.gate_cases import GateCase
from mjpoincare.seam import Chunk
from mjpoincare.simulate import initial_states, plain_clip, rollout_batch

MJCF = """<mujoco model="toy_ball"><worldbody>
  <light pos="0 -1 3" dir="0 0.3 -1"/><geom name="floor" type="plane" size="0 0 0.1" rgba="0.3 0.5 0.7 1"/>
  <body name="ball"><joint name="z" type="slide" axis="0 0 1"/>
    <geom name="ball" type="sphere" size="0.05" mass="1" condim="1" rgba="0.9 0.3 0.2 1"/></body>
</worldbody></mujoco>"""
PARAMS = (Param("drop_height", 1.0, "highest start's drop height, m (the others down to half)", float, 0.0, 100.0, True),
          Param("radius", 0.05, "ball radius, m (the reference does not depend on it)", float, 0.0, 1.0, True),
          Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, True))
#: zeta = 0.1 is the system (e = 0.744); the presets differ in the step and the time constant (30, 59 steps a contact)
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 1e-4, "solref_timeconst": 0.01, "solref_dampratio": 0.1},
    "accurate": {"timestep": 2.5e-5, "solref_timeconst": 0.005, "solref_dampratio": 0.1}}
STARTS = np.linspace(1.0, 0.5, 8)  # drop heights, x drop_height
IMPACTS = 5  # judged per start: the last at e^4 = 0.31 of the first's speed
_WHY = ("about {} times the largest error measured at drop heights 0.25, 0.5, 1, 2 and 4 m (module docstring: the "
        "step grid's scatter, the release-depth offset and solimp)")
_FLIGHT = "the semi-implicit Euler flight lands a step early: -dt/T, measured {} (defaults) to {} (low drop)"
TOLERANCES = {
    "fast": Tolerances({"restitution": 0.015, "eigenvalue": 0.015, "flight_period": 1.5e-3}, _WHY.format(3), {
        "restitution": "median of 40 impacts, measured |error| <= 5.3e-3 (gate spread 7e-4)",
        "eigenvalue": "affine fit of 32 apex pairs, measured |error| <= 4.7e-3 (gate spread 2.2e-4)",
        "flight_period": _FLIGHT.format("-2.3e-4", "-4.6e-4")}),
    "accurate": Tolerances({"restitution": 5e-3, "eigenvalue": 5e-3, "flight_period": 4e-4}, _WHY.format(2.5), {
        "restitution": "median of 40 impacts, measured |error| <= 2.2e-3 (gate spread 9.7e-4)",
        "eigenvalue": "affine fit of 32 apex pairs, measured |error| <= 1.9e-3 (gate spread 9.2e-5)",
        "flight_period": _FLIGHT.format("-5.7e-5", "-1.1e-4")})}


def restitution(zeta: float) -> float:
    """MuJoCo's restitution at solref damping ratio ``zeta``: the unilateral spring-damper's (module docstring)."""
    if not 0.0 < zeta < 1.0:
        raise ParameterError(f"solref_dampratio must be in (0, 1) for bouncing-ball's closed form (got {zeta:g})")
    return math.exp(-zeta * math.acos(2.0 * zeta**2 - 1.0) / math.sqrt(1.0 - zeta**2))


def check_params(p: Values) -> None:
    """Nothing couples the parameters (each Param bounds its own range)."""


def build(p: Values, s: Values) -> mujoco.MjModel:
    """The ball with ``p``'s radius and gravity; the settings' options and contact softness (on both geoms: MuJoCo
    mixes the two geoms' solref and solimp)."""
    spec = mujoco.MjSpec.from_string(MJCF)
    sim_settings.apply_options(spec, s)
    spec.option.gravity = [0.0, 0.0, -float(p["gravity"])]
    spec.geom("ball").size = [float(p["radius"]), 0.0, 0.0]
    for geom in spec.geoms:
        geom.solref, geom.solimp = sim_settings.solref(s), sim_settings.solimp(s)
    sim_settings.apply_unskip(spec, s)
    return spec.compile()


def starts(model: mujoco.MjModel, p: Values) -> np.ndarray:
    """Each start halfway down its drop (h / 2 above the plane, falling at sqrt(g h)): a drop from h, with a velocity
    for ``mjpoincare margins``' start perturbation to scale."""
    h = STARTS * float(p["drop_height"])
    return initial_states(model, (float(p["radius"]) + h / 2)[:, None], -np.sqrt(float(p["gravity"]) * h)[:, None])


def nsteps(model: mujoco.MjModel, p: Values, s: Values) -> int:
    """Steps to the highest start's IMPACTS-th apex, + 5 %."""
    g, e, tau = float(p["gravity"]), restitution(float(s["solref_dampratio"])), float(s["solref_timeconst"])
    v = math.sqrt(2.0 * g * float(p["drop_height"]))
    flights = (1 - math.sqrt(0.5) + 2 * sum(e**k for k in range(1, IMPACTS)) + e**IMPACTS) * v / g
    return math.ceil(1.05 * (flights + IMPACTS * tau * math.log(1 / e)) / model.opt.timestep)


class _Recorder:
    """The plane's crossings by the ball's lowest point (down, up: the speed there) and the apexes (the height)."""

    def __init__(self, radius: float) -> None:
        self.radius = radius
        self.down, self.up, self.apex = Crossings.empty(1), Crossings.empty(1), Crossings.empty(1)

    def __call__(self, chunk: Chunk) -> None:
        height, speed = chunk.qpos[:, :, :1] - self.radius, chunk.qvel[:, :, :1]  # qpos = qvel = (z,)
        self.down = self.down.concat(level_crossings(chunk.time, height[..., 0], speed, direction=-1))
        self.up = self.up.concat(level_crossings(chunk.time, height[..., 0], speed, direction=+1))
        self.apex = self.apex.concat(level_crossings(chunk.time, speed[..., 0], height, direction=-1))


def evaluate(p: Values, s: Values, preset: str, seed: int) -> Evaluation:
    """One batch of drops, IMPACTS impacts each: restitution, the apex map's eigenvalue, the flight time."""
    zeta, g = float(s["solref_dampratio"]), float(p["gravity"])
    e, tol = restitution(zeta), at_preset(TOLERANCES, BOUNCING_BALL.name, preset)
    model, rec, n = build(p, s), _Recorder(float(p["radius"])), len(STARTS)
    report = rollout_batch(model, starts(model, p), nsteps(model, p, s), rec, **sim_settings.rollout_options(s))
    ratio, speed, flight = [], [], []
    for down, up, t_down, t_up in zip(rec.down.sequences(n), rec.up.sequences(n), rec.down.times(n),
                                      rec.up.times(n), strict=True):
        m = min(len(down), len(up), IMPACTS)
        ratio += list(-up[:m, 0] / down[:m, 0])
        speed += list(up[: m - 1, 0])
        flight += list(t_down[1:m] - t_up[: m - 1])
    v, t = np.array(speed), np.array(flight)
    extras: dict[str, object] = {"analytic": {"restitution": e, "contact_s": float(s["solref_timeconst"]) * -math.log(e),
                                              "bilateral": math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))}}
    try:
        fit = fit_return_map(*sample_pairs([a[:IMPACTS] for a in rec.apex.sequences(n)]), degree=1, seed=seed)
        eigenvalue, extras["fit"] = float(fit.eigenvalues[0].real), fit.to_dict()
    except ValueError as err:  # too few apexes: a diverged run
        eigenvalue, extras["fit_error"] = math.nan, str(err)
    why = {name: f"{text}; {tol.reasons[name]}; {tol.why}" for name, text in (
        ("restitution", "rebound / impact speed where the lowest point crosses the plane (unilateral spring-damper)"),
        ("eigenvalue", "slope of the apex return map h_k -> h_k+1, e^2"),
        ("flight_period", "flight time per unit rebound speed, 2/g (least squares through 0 over every flight)"))}
    out = [checks.relative("restitution", e, float(np.median(ratio)) if ratio else math.nan, tol["restitution"], "",
                           why["restitution"]),
           checks.absolute("eigenvalue", e**2, eigenvalue, tol["eigenvalue"], "", why["eigenvalue"]),
           checks.relative("flight_period", 2.0 / g, float(t @ v / (v @ v)) if len(v) else math.nan,
                           tol["flight_period"], "s/(m/s)", why["flight_period"])]
    return Evaluation(out, report, extras)


def probe(p: Values, s: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The model and the one batch :func:`evaluate` runs."""
    model = build(p, s)
    return model, [(starts(model, p), nsteps(model, p, s))]


def reference_bench(p: Values, rtol: float) -> dict[str, float]:
    """The closed form against the exact event-driven contact (solve_ivp at ``rtol``, released where the force
    vanishes) at each start's impact speed, at the fast preset's zeta and tau: time and errors."""
    zeta, tau = float(PRESETS["fast"]["solref_dampratio"]), float(PRESETS["fast"]["solref_timeconst"])
    w, e = 1.0 / (tau * zeta), restitution(zeta)

    def push(t: float, y: np.ndarray) -> float:  # the spring-damper's force per unit mass, >= 0 in contact
        return -(2 * zeta * w * y[1] + w * w * y[0])

    push.terminal, push.direction = True, -1  # type: ignore[attr-defined]
    start = time.perf_counter()
    rebound = np.median([solve_ivp(lambda t, y: [y[1], push(t, y)], (0, 10 * tau), [0, -v], events=push, rtol=rtol,
                                   atol=rtol * v * tau).y_events[0][0, 1] / v
                         for v in np.sqrt(2 * float(p["gravity"]) * float(p["drop_height"]) * STARTS)])
    return {"rtol": rtol, "wall_s": time.perf_counter() - start, "restitution_error": abs(rebound / e - 1),
            "eigenvalue_error": abs(rebound**2 - e * e), "flight_period_error": 0.0}


def clip(p: Values, s: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """The highest start's drop."""
    return plain_clip(model, starts(model, p)[:1], nstep)


_ALL = "restitution eigenvalue flight_period stable"
BOUNCING_BALL = Scenario(
    name="bouncing-ball", summary="toy plugin: a ball bouncing on a plane: MuJoCo's restitution, apex map, flights",
    source="MuJoCo docs, Computation 'Soft constraints' and Modeling 'Solver parameters' (solref, solimp)",
    params=PARAMS, presets=PRESETS, check_params=check_params, build=build, evaluate=evaluate,
    accuracy_checks=("restitution", "eigenvalue", "flight_period"), probe=probe, reference_bench=reference_bench,
    clip=clip, track_body="ball", camera_distance=2.0, mechanisms=("rollout",), tolerances=TOLERANCES,
    gate_cases=(GateCase.of("bouncing-ball", "fast", _ALL), GateCase.of("bouncing-ball", "accurate", _ALL)),
    coverage=(CoveragePoint("defaults", {}, "drop 1 m: impacts at 4.4 m/s down to 1.4 m/s"),
              CoveragePoint("low drop", {"drop_height": "0.25"}, "down to 0.7 m/s: the largest release-depth offset"),
              CoveragePoint("high drop", {"drop_height": "2"}, "up to 6.3 m/s: the deepest penetration")),
    search_space=sim_settings.search_space("timestep", "solref_timeconst", "integrator"))
