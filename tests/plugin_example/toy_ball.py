"""Scenario ``bouncing-ball``: a ball dropped on a plane, MuJoCo's soft contact against its closed form.

A toy plugin written only against the extension point (docs/adding-a-scenario.md): the registry finds it through the
entry point in toy_ball-0.1.dist-info/entry_points.txt once this folder is on the path.

Analytic reference. MuJoCo's contact is a soft constraint (MuJoCo docs, Computation, "Soft contact model"; Modeling,
"Solver parameters"): while active, a1 = (1 - d) a0 + d aref with aref = -b r' - k r, r the signed distance,
b = 2 / (dmax tau), k = d / (dmax^2 tau^2 zeta^2) for solref = (tau, zeta), d the impedance (solimp). At d = dmax the
penetration is a spring-damper of damping ratio zeta, r'' + 2 zeta w r' + w^2 r = 0, w = 1 / (tau zeta): from r = 0,
r' = -v, r = -(v / w_d) exp(-zeta w t) sin(w_d t), w_d = w sqrt(1 - zeta^2). The contact never pulls: its force
d m (g - b r' - k r) vanishes, and the ball leaves, where 2 zeta w r' + w^2 r = 0 (up to g, below), at w_d t = theta,
cos theta = 2 zeta^2 - 1, with r' = e v:  e = exp(-zeta theta / sqrt(1 - zeta^2)), after a contact of tau ln(1/e).
Released at r = 0 (bilateral), e would be exp(-pi zeta / sqrt(1 - zeta^2)): 2 % lower at zeta = 0.1, 45 % at 0.5, 0 at
1, where MuJoCo still rebounds (e -> exp(-2)); MuJoCo follows e (zeta = 0.1-1, timestep 2e-6, up to the offset below).
A rebound at e v flies 2 e v / g; the apexes obey h_k+1 = e^2 h_k: a linear map, fixed point 0, eigenvalue e^2.

MuJoCo adds (measured on the exact soft-constraint ODE, solve_ivp) a release-depth offset, -2 g zeta^2 tau / (e v): the
ball climbs the depth 2 zeta^2 tau e v where the force vanishes against gravity (-0.06 % to -0.37 % at 4.4 to 0.7 m/s,
fast preset), and solimp's impedance (0.99 at contact, 0.999 from 0.1 mm on) +0.002 % to +0.04 %. Each impact meets the
step grid at its own phase: single impacts scatter (±1.9 % at 30 steps a contact, ±1 % at 59), and so, through the
next flight, does the next phase (a 1e-12 change of the starts reshuffles the later impacts).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import mujoco
import numpy as np
from scipy.integrate import solve_ivp

from mjpoincare.plugin import (
    AnalyticValues,
    Chunk,
    CoveragePoint,
    Crossings,
    Dimension,
    Evaluation,
    FitSummary,
    GateCase,
    Param,
    ParameterError,
    Scenario,
    Tolerances,
    Values,
    absolute,
    apply_options,
    at_preset,
    compile_spec,
    fit_return_map,
    initial_states,
    level_crossings,
    load_spec,
    plain_clip,
    relative,
    rollout_batch,
    rollout_options,
    sample_pairs,
    search_space,
    solimp,
    solref,
)

#: The model: a file beside this module, which includes the shared looks (sky, floor material, headlight).
MJCF = Path(__file__).with_name("toy_ball.xml")
PARAMS = (Param("drop_height", 1.0, "the highest start's drop, m (the others down to half)", float, 0.0, 100.0, True),
          Param("radius", 0.05, "ball radius, m (the reference does not depend on it)", float, 0.0, 1.0, True),
          Param("gravity", 9.81, "gravity, m/s^2", float, 0.0, 1e3, True))
#: zeta = 0.1 is the system (e = 0.744); the presets differ in the step and the time constant (30, 59 steps a contact)
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 1e-4, "solref_timeconst": 0.01, "solref_dampratio": 0.1},
    "accurate": {"timestep": 2.5e-5, "solref_timeconst": 0.005, "solref_dampratio": 0.1}}
STARTS = np.linspace(1.0, 0.5, 8)  # drop heights, x drop_height
IMPACTS = 5  # judged per start: the last at e^4 = 0.31 of the first's speed
_WHY = "{} times the largest |error| measured at drop heights 0.25-4 m and reshuffled starts (mechanisms: docstring)"
_FLIGHT = "each semi-implicit Euler flight lands a step early, -dt/T: measured {} (defaults) to {} (low drop)"
TOLERANCES = {
    "fast": Tolerances({"restitution": 0.015, "eigenvalue": 0.015, "flight_period": 1.5e-3}, _WHY.format("2.7-3.3"), {
        "restitution": "median of 40 impacts: |error| <= 5.3e-3 (drop heights), 3.5e-3 (24 reshuffled starts)",
        "eigenvalue": "affine fit of 32 apex pairs: |error| <= 4.7e-3 (drop heights), 5.6e-3 (reshuffled)",
        "flight_period": _FLIGHT.format("-2.3e-4", "-4.6e-4")}),
    "accurate": Tolerances({"restitution": 5e-3, "eigenvalue": 5e-3, "flight_period": 4e-4}, _WHY.format("2-3.6"), {
        "restitution": "median of 40 impacts: |error| <= 2.2e-3 (drop heights), 2.5e-3 (24 reshuffled starts)",
        "eigenvalue": "affine fit of 32 apex pairs: |error| <= 1.9e-3 (drop heights), 1.9e-3 (reshuffled)",
        "flight_period": _FLIGHT.format("-5.7e-5", "-1.1e-4")})}


def restitution(zeta: float) -> float:
    """MuJoCo's restitution at solref damping ratio ``zeta``: the unilateral spring-damper's (module docstring), for
    zeta >= 1 continued (theta / sqrt(1 - zeta^2) -> 2 at 1, arccosh(2 zeta^2 - 1) / sqrt(zeta^2 - 1) above)."""
    c, q = 2.0 * zeta**2 - 1.0, abs(1.0 - zeta**2)
    phase = 2.0 if q == 0.0 else (math.acos(c) if zeta < 1.0 else math.acosh(c)) / math.sqrt(q)
    return math.exp(-zeta * phase)


def check_params_with_settings(p: Values, s: Values) -> None:
    """The closed forms take the contact as a spring-damper in the penetration of a sphere: the deepest penetration,
    about v / omega (the fastest impact v = sqrt(2 g drop_height), MuJoCo's contact frequency omega = 1 / (timeconst
    dampratio)), must stay under half the radius; a parameter (the radius, the drop) against a setting (the contact's
    softness), refused before any simulation."""
    depth = math.sqrt(2.0 * float(p["gravity"]) * float(p["drop_height"])) * float(s["solref_timeconst"]) * float(
        s["solref_dampratio"])
    if depth > 0.5 * float(p["radius"]):
        raise ParameterError(f"radius={p['radius']:g} m must be at least twice the ball's deepest penetration, "
                             f"{depth:.3g} m at solref_timeconst={s['solref_timeconst']:g} s and drop_height="
                             f"{p['drop_height']:g} m")


def build(p: Values, s: Values) -> mujoco.MjModel:
    """The ball with ``p``'s radius and gravity; the settings' options and contact softness (on both geoms: MuJoCo
    mixes the two geoms' solref and solimp)."""
    spec = load_spec(MJCF)
    apply_options(spec, s)
    spec.option.gravity = [0.0, 0.0, -float(p["gravity"])]
    spec.geom("ball").size = [float(p["radius"]), 0.0, 0.0]
    for geom in spec.geoms:
        geom.solref, geom.solimp = solref(s), solimp(s)
    return compile_spec(spec, s)


def batch(model: mujoco.MjModel, p: Values, s: Values) -> tuple[np.ndarray, int]:
    """The starts, each halfway down its drop (h / 2 above the plane, falling at sqrt(g h): a drop from h, with a
    velocity for ``mjpoincare margins``' start perturbation to scale), and the steps to the highest one's IMPACTS-th
    apex, + 5 %."""
    g, e, tau = float(p["gravity"]), restitution(float(s["solref_dampratio"])), float(s["solref_timeconst"])
    h, v = STARTS * float(p["drop_height"]), math.sqrt(2.0 * g * float(p["drop_height"]))
    flights = (1 - math.sqrt(0.5) + 2 * sum(e**k for k in range(1, IMPACTS)) + e**IMPACTS) * v / g
    return (initial_states(model, (float(p["radius"]) + h / 2)[:, None], -np.sqrt(g * h)[:, None]),
            math.ceil(1.05 * (flights + IMPACTS * tau * math.log(1 / e)) / model.opt.timestep))


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
    report = rollout_batch(model, *batch(model, p, s), rec, **rollout_options(s))
    ratio, speed, flight = [], [], []
    for down, up, t_down, t_up in zip(rec.down.sequences(n), rec.up.sequences(n), rec.down.times(n),
                                      rec.up.times(n), strict=True):
        m = min(len(down), len(up), IMPACTS)
        ratio += list(-up[:m, 0] / down[:m, 0])
        speed += list(up[: m - 1, 0])
        flight += list(t_down[1:m] - t_up[: m - 1])
    v, t = np.array(speed), np.array(flight)
    analytic = AnalyticValues(eigenvalues=[e**2], values={  # the apex map's multiplier: sweep's analytic column
        "restitution": e, "contact_s": -float(s["solref_timeconst"]) * math.log(e),
        "bilateral": math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2)) if zeta < 1 else 0.0})
    extras: dict[str, object] = {}
    summary = None
    try:
        fit = fit_return_map(*sample_pairs([a[:IMPACTS] for a in rec.apex.sequences(n)]), degree=1, seed=seed)
        eigenvalue, summary = float(fit.eigenvalues[0].real), FitSummary.of(fit)
    except ValueError as err:  # too few apexes: a diverged run
        eigenvalue, extras["fit_error"] = math.nan, str(err)
    why = {name: f"{text}; {tol.reasons[name]}; {tol.why}" for name, text in (
        ("restitution", "rebound / impact speed where the lowest point crosses the plane (unilateral spring-damper)"),
        ("eigenvalue", "slope of the apex return map h_k -> h_k+1, e^2"),
        ("flight_period", "flight time per unit rebound speed, 2/g (least squares through 0 over every flight)"))}
    out = [relative("restitution", e, float(np.median(ratio)) if ratio else math.nan, tol["restitution"], "",
                           why["restitution"]),
           absolute("eigenvalue", e**2, eigenvalue, tol["eigenvalue"], "", why["eigenvalue"]),
           relative("flight_period", 2.0 / g, float(t @ v / (v @ v)) if len(v) else math.nan,
                           tol["flight_period"], "s/(m/s)", why["flight_period"])]
    return Evaluation(out, report, extras, analytic=analytic, fit=summary)


def validation_batches(p: Values, s: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The model and the one batch :func:`evaluate` runs."""
    model = build(p, s)
    return model, [batch(model, p, s)]


def exact_model_bench(p: Values, rtol: float) -> dict[str, float]:
    """The closed form against the exact event-driven contact (solve_ivp at ``rtol``, released where the force
    vanishes) at each start's impact speed, at the fast preset's zeta and tau: time and errors."""
    zeta, tau = float(PRESETS["fast"]["solref_dampratio"]), float(PRESETS["fast"]["solref_timeconst"])
    w, e, start = 1.0 / (tau * zeta), restitution(zeta), time.perf_counter()

    def push(t: float, y: np.ndarray) -> float:  # the spring-damper's force per unit mass, >= 0 in contact
        return -(2 * zeta * w * y[1] + w * w * y[0])

    push.terminal, push.direction = True, -1  # type: ignore[attr-defined]
    rebound = float(np.median([solve_ivp(lambda t, y: [y[1], push(t, y)], (0, 10 * tau), [0, -v], events=push,
                                         rtol=rtol, atol=rtol * v * tau).y_events[0][0, 1] / v
                               for v in np.sqrt(2 * float(p["gravity"]) * float(p["drop_height"]) * STARTS)]))
    return {"rtol": rtol, "wall_s": time.perf_counter() - start, "restitution_error": abs(rebound / e - 1),
            "eigenvalue_error": abs(rebound**2 - e * e), "flight_period_error": 0.0}


def video_states(p: Values, s: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """The highest start's drop."""
    return plain_clip(model, batch(model, p, s)[0][:1], nstep)


_ALL = ("restitution", "eigenvalue", "flight_period", "stable")
BOUNCING_BALL = Scenario(
    name="bouncing-ball", summary="toy plugin: a ball bouncing on a plane: MuJoCo's restitution, apex map, flights",
    source="MuJoCo docs, Computation 'Soft contact model' and Modeling 'Solver parameters' (solref, solimp)",
    params=PARAMS, presets=PRESETS, check_params=lambda p: None, check_params_with_settings=check_params_with_settings,
    build=build, evaluate=evaluate, bench_checks=("restitution", "eigenvalue", "flight_period"),
    validation_batches=validation_batches, exact_model_bench=exact_model_bench, video_states=video_states,
    track_body="ball", camera_distance=2.0, seam_mechanisms=("rollout",), tolerances=TOLERANCES,
    gate_cases=(GateCase.of("bouncing-ball", "fast", _ALL), GateCase.of("bouncing-ball", "accurate", _ALL)),
    coverage=(CoveragePoint("defaults", {}, "drop 1 m: impacts at 4.4 m/s down to 1.4 m/s"),
              CoveragePoint("low drop", {"drop_height": "0.25"}, "down to 0.7 m/s: the largest release-depth offset"),
              CoveragePoint("high drop", {"drop_height": "2"}, "up to 6.3 m/s: the deepest penetration")),
    search_space=search_space("timestep", "integrator", extra=(  # a contact lasts 0.3 tau: 3-120 steps
        Dimension("solref_timeconst", 10.0, 400.0, log=True, per_timestep=True),)))
