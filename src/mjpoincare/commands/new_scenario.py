"""``mjpoincare new-scenario NAME``: a minimal working scenario plugin to start from (docs/adding-a-scenario.md).

It writes a distribution folder: ``pyproject.toml`` (the entry point in the group ``mjpoincare.scenarios``), the
package (the scenario: a ball dropped from rest, its fall time against the closed form sqrt(2 h / g), with only the
required fields of :class:`~mjpoincare.plugin.Scenario` and its tolerances and gate cases), its MJCF model and a
README of what to replace. ``pip install -e FOLDER`` then ``mjpoincare check-plugin NAME`` pass as written; the
physics is the author's to replace.
"""

from __future__ import annotations

import re
from pathlib import Path

from mjpoincare.core.params import ParameterError

#: A scenario name: lower-case words joined by hyphens (a CLI name, and a Python package once hyphens are underscores).
NAME = re.compile(r"[a-z][a-z0-9]*(-[a-z0-9]+)*")

PYPROJECT = '''[build-system]
requires = ["setuptools>=68"]
build-backend = "setuptools.build_meta"

[project]
name = "{name}"
version = "0.1.0"
description = "{name}: a mjpoincare scenario plugin"
requires-python = ">=3.10"
dependencies = ["mjpoincare"]

[project.entry-points."mjpoincare.scenarios"]
{name} = "{package}:SCENARIO"

[tool.setuptools]
packages = ["{package}"]

[tool.setuptools.package-data]
{package} = ["model.xml"]
'''

MODEL = '''<mujoco model="{name}">
  <include file="common/looks.xml"/>
  <worldbody>
    <light pos="0 -1 3" dir="0 0.3 -1"/>
    <geom name="floor" type="plane" size="0 0 0.1" material="grid" contype="0" conaffinity="0"/>
    <body name="ball">
      <joint name="z" type="slide" axis="0 0 1"/>
      <geom name="ball" type="sphere" size="0.05" mass="1" rgba="0.9 0.3 0.2 1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
'''

MODULE = '''"""Scenario ``{name}``: a ball dropped from rest, MuJoCo's fall time against the closed form (written by
``mjpoincare new-scenario``: replace the physics, keep the shape).

Analytic reference: a drop from height h under gravity g lasts T = sqrt(2 h / g). MuJoCo's semi-implicit Euler
step lands about half a step early, -dt / (2 T) relative: the tolerances are several times that at each preset.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import mujoco
import numpy as np
from scipy.integrate import solve_ivp

from mjpoincare.plugin import (
    Crossings,
    Evaluation,
    GateCase,
    Param,
    Scenario,
    Tolerances,
    Values,
    apply_options,
    at_preset,
    compile_spec,
    initial_states,
    level_crossings,
    load_spec,
    plain_clip,
    relative,
    rollout_batch,
    rollout_options,
)

MJCF = Path(__file__).with_name("model.xml")
PARAMS = (Param("drop_height", 1.0, "the drop, m", float, 0.01, 100.0),
          Param("gravity", 9.81, "gravity, m/s^2", float, 0.1, 100.0))
PRESETS: dict[str, dict[str, float | int | str]] = {{"fast": {{"timestep": 1e-3}}, "accurate": {{"timestep": 1e-4}}}}
TOLERANCES = {{
    "fast": Tolerances({{"fall_time": 5e-3}}, "about 4 times the semi-implicit Euler step's -dt/(2T) at h = 1 m"),
    "accurate": Tolerances({{"fall_time": 5e-4}}, "about 4 times the semi-implicit Euler step's -dt/(2T) at h = 1 m"),
}}
RADIUS = 0.05  # m, the ball's radius in model.xml: its centre falls h from h + RADIUS


def fall_time(p: Values) -> float:
    """The closed form: sqrt(2 h / g)."""
    return math.sqrt(2.0 * float(p["drop_height"]) / float(p["gravity"]))


def build(p: Values, s: Values) -> mujoco.MjModel:
    """The model with ``p``'s gravity and the run's simulator settings."""
    spec = load_spec(MJCF)
    apply_options(spec, s)
    spec.option.gravity = [0.0, 0.0, -float(p["gravity"])]
    return compile_spec(spec, s)


def _batch(model: mujoco.MjModel, p: Values) -> tuple[np.ndarray, int]:
    """The start (the ball at rest, h above its landing height) and the steps to 1.2 fall times."""
    start = initial_states(model, np.array([[RADIUS + float(p["drop_height"])]]), np.zeros((1, 1)))
    return start, math.ceil(1.2 * fall_time(p) / model.opt.timestep)


def evaluate(p: Values, s: Values, preset: str, seed: int) -> Evaluation:
    """Drop the ball; the fall time is where its centre crosses RADIUS on the way down."""
    del seed  # nothing random here
    tol = at_preset(TOLERANCES, "{name}", preset)
    model = build(p, s)
    found = [Crossings.empty(1)]

    def consume(chunk) -> None:  # noqa: ANN001
        found[0] = found[0].concat(level_crossings(chunk.time, chunk.qpos[:, :, 0] - RADIUS, chunk.qvel[:, :, :1],
                                                   direction=-1))

    report = rollout_batch(model, *_batch(model, p), consume, **rollout_options(s))
    times = found[0].times(1)[0]
    simulated = float(times[0]) if len(times) else math.nan
    return Evaluation([relative("fall_time", fall_time(p), simulated, tol["fall_time"], "s",
                                "time to fall drop_height from rest against sqrt(2 h / g); " + tol.why)], report)


def validation_batches(p: Values, s: Values) -> tuple[mujoco.MjModel, list[tuple[np.ndarray, int]]]:
    """The batch ``evaluate`` runs, for timing ``mujoco.rollout`` alone on it."""
    model = build(p, s)
    return model, [_batch(model, p)]


def exact_model_bench(p: Values, rtol: float) -> dict[str, float]:
    """The exact fall (solve_ivp at ``rtol``, a terminal event at the landing) against the closed form."""
    g, h = float(p["gravity"]), float(p["drop_height"])
    landed = lambda t, y: y[0]  # noqa: E731
    landed.terminal, landed.direction = True, -1
    start = time.perf_counter()
    sol = solve_ivp(lambda t, y: [y[1], -g], (0.0, 10.0 * fall_time(p)), [h, 0.0], rtol=rtol, atol=rtol * 1e-3,
                    events=landed)
    wall = time.perf_counter() - start
    return {{"rtol": rtol, "wall_s": wall,
            "fall_time_error": abs(float(sol.t_events[0][0]) - fall_time(p)) / fall_time(p)}}


def video_states(p: Values, s: Values, model: mujoco.MjModel, nstep: int) -> np.ndarray:
    """The drop, for a video."""
    return plain_clip(model, _batch(model, p)[0], nstep)


SCENARIO = Scenario(
    name="{name}", summary="{name}: a ball dropped from rest (replace with your system)",
    source="free fall, T = sqrt(2 h / g) (replace with your paper and equation)",
    params=PARAMS, presets=PRESETS, check_params=lambda p: None, build=build, evaluate=evaluate,
    bench_checks=("fall_time",), validation_batches=validation_batches, exact_model_bench=exact_model_bench,
    video_states=video_states, track_body="ball",
    tolerances=TOLERANCES, checks=("fall_time",),
    gate_cases=(GateCase.of("{name}", "fast", ("fall_time", "stable")),
                GateCase.of("{name}", "accurate", ("fall_time", "stable"))))
'''

README = '''# {name}

A mjpoincare scenario plugin, written by `mjpoincare new-scenario {name}`: a ball dropped from rest, its fall time
against sqrt(2 h / g). It runs as written:

    pip install -e .
    mjpoincare check-plugin {name}
    mjpoincare validate {name}

What to replace (docs/adding-a-scenario.md in mjpoincare walks through each):

- `{package}/model.xml`: your system's MJCF model;
- `PARAMS`: its physical parameters, each with bounds the theory holds for;
- `fall_time`, `evaluate`: your analytic reference (the paper's equation, in the docstring) and the experiment
  that measures it in MuJoCo, returning an `Evaluation` of the checks `checks=` declares;
- `TOLERANCES`: each check's bound per preset and why it is what it is (measured, with margin);
- `exact_model_bench`: the exact model through the same measurement (for `mjpoincare bench`);
- `gate_cases`: the runs the regression gate asserts (`mjpoincare margins` measures them).
'''


def write_scenario(name: str, folder: str | None) -> Path:
    """The plugin's files in ``folder`` (default: ./NAME); refused, before anything is written, for a name that is
    not a scenario name or a folder that exists."""
    if not NAME.fullmatch(name):
        raise ParameterError(f"scenario name must be lower-case words joined by hyphens, e.g. my-walker (got {name!r})")
    root = Path(folder) if folder else Path(name)
    if root.exists():
        raise ParameterError(f"{root} exists: new-scenario writes a new folder (give another --dir)")
    package = name.replace("-", "_")
    files = {root / "pyproject.toml": PYPROJECT, root / package / "__init__.py": MODULE,
             root / package / "model.xml": MODEL, root / "README.md": README}
    for path, text in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text.format(name=name, package=package))
    return root
