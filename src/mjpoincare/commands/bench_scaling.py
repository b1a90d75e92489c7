"""``mjpoincare bench SCENARIO --scaling``: the 1 -> N core speedup of a sweep, beside what the machine allows.

Two measurements, each the best of ``repeats`` runs (wall clocks on shared machines jitter by 10-30 %):

* the machine's ceiling: the scenario's own MuJoCo work (the rollout batches of one validation, one thread, no
  Python in between) run once alone, then N copies at once in N processes. With perfect scaling the N copies
  take as long as one; ``ceiling = N * alone / together`` is the throughput gain the cores can give to
  independent MuJoCo work (shared caches, memory bandwidth and, on virtual machines, shared physical cores
  lower it);
* the sweep: the same points validated with 1 worker and with N (:func:`mjpoincare.commands.sweep.sweep_point`
  through :func:`mjpoincare.core.parallel.run_jobs`, one rollout thread per point), ``speedup`` = their wall ratio,
  and ``efficiency`` = speedup / ceiling: how much of what the machine offers the suite gets.
"""

from __future__ import annotations

import os
import time
from collections.abc import Mapping
from typing import Any

import mujoco
from mujoco import rollout as mj_rollout

from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.sweep import sweep_point
from mjpoincare.commands.validation import resolve_inputs, run_steps
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.parallel import run_jobs
from mjpoincare.core.params import ParameterError, parse_values
from mjpoincare.core.result import write_json


def rollout_work(name: str, assignments: Mapping[str, str]) -> float:
    """Wall seconds of one validation's rollout batches in ``mujoco.rollout`` alone, on one thread."""
    scenario, _, params, settings = resolve_inputs(name, {**assignments, "threads": "1"}, None)
    model, batches = scenario.validation_batches(params, settings)
    data = mujoco.MjData(model)
    start = time.perf_counter()
    for state0, nstep in batches:
        mj_rollout.rollout(model, data, state0, nstep=nstep)
    return time.perf_counter() - start


def _concurrent_wall(fn: Any, jobs: list[tuple[Any, ...]], workers: int) -> float:
    start = time.perf_counter()
    for _ in run_jobs(fn, jobs, workers=workers):
        pass
    return time.perf_counter() - start


def measure_scaling(name: str, param: str, values: list[str], assignments: Mapping[str, str], *,
                    workers: int = 2, repeats: int = 3) -> dict[str, Any]:
    """Ceiling and sweep speedup from 1 to ``workers`` processes (best of ``repeats`` each)."""
    if workers < 2 or repeats < 1:
        raise ParameterError(f"--workers must be >= 2 and --repeats >= 1 for --scaling (got {workers}, {repeats})")
    point = {**assignments, "threads": "1"}
    for value in values:
        resolve_inputs(name, {**point, param: value}, None)
    sweep_steps = sum(run_steps(name, {**point, param: value}, None) for value in values)
    refuse_long(2 * repeats * sweep_steps, f"bench --scaling {name} ({len(values)} values x {2 * repeats} sweeps)",
                allow=False, remedy="raise timestep, or give fewer --values or --repeats")
    alone = min(_concurrent_wall(rollout_work, [(name, point)], 1) for _ in range(repeats))
    together = min(_concurrent_wall(rollout_work, [(name, point)] * workers, workers) for _ in range(repeats))
    jobs = [(name, param, value, point, None) for value in values]
    serial = min(_concurrent_wall(sweep_point, jobs, 1) for _ in range(repeats))
    parallel = min(_concurrent_wall(sweep_point, jobs, workers) for _ in range(repeats))
    ceiling = workers * alone / together
    speedup = serial / parallel
    return {"scenario": name, "param": param, "values": values, "workers": workers, "repeats": repeats,
            "cpu_count": os.cpu_count(), "mujoco_version": mujoco.__version__,
            "rollout_alone_s": alone, "rollout_together_s": together, "ceiling": ceiling,
            "sweep_serial_s": serial, "sweep_parallel_s": parallel, "speedup": speedup,
            "efficiency": speedup / ceiling}


def run_scaling(name: str, param: str, values_text: str, assignments: Mapping[str, str], json_path: str | None,
                *, workers: int = 2, repeats: int = 3) -> int:
    """Print the scaling table (and write its JSON); exit 0."""
    r = measure_scaling(name, param, parse_values(values_text), assignments, workers=workers, repeats=repeats)
    n = r["workers"]
    print("\n".join([
        f"{name}: 1 -> {n} cores (best of {r['repeats']}; {len(r['values'])} sweep points over {param}, "
        f"{r['cpu_count']} cores seen)",
        markdown_table(("measurement", "1 process, s", f"{n} processes, s", "gain"), [
            (f"machine ceiling: one validation's rollouts, x{n} copies at once", f"{r['rollout_alone_s']:.2f}",
             f"{r['rollout_together_s']:.2f} (x{n} work)", f"x{r['ceiling']:.2f}"),
            (f"sweep ({len(r['values'])} validations)", f"{r['sweep_serial_s']:.2f}", f"{r['sweep_parallel_s']:.2f}",
             f"x{r['speedup']:.2f}")]),
        f"\nthe sweep gets {100 * r['efficiency']:.0f} % of the gain the machine gives independent MuJoCo work"]))
    if json_path:
        write_json(jsonable(r), json_path.format(scenario=name))
    return 0
