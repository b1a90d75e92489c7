"""``mjpoincare bench``: run time against error over timestep, integrator and contact settings.

Every configuration is a full validation run (the same pipeline users run) with one set of
simulator settings; the table gives wall time, steps/s and the errors of the scenario's accuracy
checks, marks the Pareto front (no other configuration is both faster and more accurate), and
sets two reference figures beside it:

* MuJoCo alone: ``mujoco.rollout`` on the same model and initial states with nothing else to do
  (one call, no chunking, no sampling), to show what the pipeline costs on top;
* the exact event-driven ``solve_ivp`` reference at several tolerances, with its own error, to
  compare its cost at equal accuracy.
* for the rimless wheel and the compass gait, Drake's hybrid simulation (:mod:`mjpoincare.engines.peers`, the extra
  ``peers``) at three accuracies: the row a user wanting the exact cycle would pick instead.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
from mujoco import rollout as mj_rollout

from mjpoincare import scenarios
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_inputs, run_steps, run_validation
from mjpoincare.core import progress
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.params import Value
from mjpoincare.core.result import write_json
from mjpoincare.engines.peers.compare import bench_block
from mjpoincare.scenarios.base import Foot

#: (label, setting overrides): timestep refinement per integrator with the contact time constant kept at
#: 10 steps, then contact variants at 0.1 ms steps.
SWEEP: tuple[tuple[str, dict[str, Value]], ...] = tuple(
    [(f"{integ} dt={dt:g}", {"integrator": integ, "timestep": dt, "solref_timeconst": 10 * dt})
     for integ, steps in (("implicitfast", (8e-4, 4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5)), ("euler", (4e-4, 1e-4)),
                          ("rk4", (4e-4, 1e-4)))
     for dt in steps]
    + [(f"implicitfast dt=1e-4 {name}", {"integrator": "implicitfast", "timestep": 1e-4, **extra})
       for name, extra in (("tc=2dt", {"solref_timeconst": 2e-4}), ("tc=40dt", {"solref_timeconst": 4e-3}),
                           ("dampratio=3", {"solref_timeconst": 1e-3, "solref_dampratio": 3.0}),
                           ("pyramidal", {"solref_timeconst": 1e-3, "cone": "pyramidal"}),
                           ("foot r=2mm", {"solref_timeconst": 1e-3, "foot_radius": 2e-3}))]
)
QUICK: tuple[str, ...] = ("implicitfast dt=0.0008", "implicitfast dt=0.0004")
#: What each scene skips, as (name, what is skipped, settings with the skip, settings without it). Each pair is
#: validated (best wall time of two runs) to show the speed the skip buys and that the error did not move.
SKIPS: tuple[tuple[str, str, dict[str, str], dict[str, str]], ...] = (
    ("diagnostics off", "no sensors, no energy computation (nothing reads them)", {}, {"diagnostics": "1"}),
    ("collision filtering", "contacts only between the feet and the ground", {}, {"unskip": "collisions"}),
    ("contact disabled", "no contact detection where only equality constraints act", {}, {"unskip": "contact"}),
    ("dense Jacobian", "dense constraint Jacobian for a few-dof model (vs sparse)", {"jacobian": "dense"},
     {"jacobian": "sparse"}),
    ("solver budget", "the preset's solver budget (vs 20 iterations at tolerance 1e-8)", {},
     {"iterations": "20", "tolerance": "1e-8"}),
    ("2 rollout threads", "mujoco.rollout threads across initial states (vs 1)", {"threads": "2"}, {"threads": "1"}),
)
REFERENCE_RTOLS = (1e-3, 1e-5, 1e-7, 1e-9)


def raw_rollout_rate(name: str, assignments: Mapping[str, str]) -> dict[str, float]:
    """``mujoco.rollout`` alone (one call per batch, nothing else) on the work one validation does.

    Returns its steps/s and, for comparison, the whole validation's (simulation + sampling + fit +
    checks) steps/s measured right after it in the same process: ``pipeline_fraction`` is their ratio.
    """
    scenario, _, params, settings = resolve_inputs(name, assignments, None)
    model, batches = scenario.validation_batches(params, settings)
    threads = int(settings["threads"])
    datas = [mujoco.MjData(model) for _ in range(threads)]
    steps, wall = 0, 0.0
    with mj_rollout.Rollout(nthread=threads) as pool:
        for state0, nstep in batches:
            start = time.perf_counter()
            pool.rollout(model, datas, state0, nstep=nstep)
            wall += time.perf_counter() - start
            steps += state0.shape[0] * nstep
    pipeline = run_validation(name, assignments, None).timing
    return {"steps": float(steps), "wall_s": wall, "steps_per_s": steps / wall,
            "pipeline_steps_per_s": pipeline["steps_per_s"],
            "pipeline_fraction": pipeline["steps_per_s"] / (steps / wall)}


def pareto_front(walls: list[float], errors: list[float]) -> list[bool]:
    """True for configurations that no other one beats on both wall time and error."""
    flags = []
    for i, (w, e) in enumerate(zip(walls, errors, strict=True)):
        dominated = any(
            (w2 <= w and e2 <= e) and (w2 < w or e2 < e)
            for j, (w2, e2) in enumerate(zip(walls, errors, strict=True)) if j != i and math.isfinite(e2)
        )
        flags.append(math.isfinite(e) and not dominated)
    return flags


def foot_row(config: tuple[str, dict[str, Value]], foot: Foot | None) -> tuple[str, dict[str, Value]] | None:
    """A sweep row as the scenario runs it: the large-foot row at its foot's largest searched radius, or dropped
    when the model has no feet; every other row as it is."""
    label, overrides = config
    if "foot_radius" not in overrides:
        return config
    if foot is None:
        return None
    return label.replace(f"r={float(overrides['foot_radius']) * 1e3:g}mm", f"r={foot.high * 1e3:g}mm"), {
        **overrides, "foot_radius": foot.high}


def run_bench(name: str, assignments: Mapping[str, str], output: str, json_path: str | None,
              quick: bool = False) -> int:
    """Run the sweep, print the table, write the PNG (and JSON); exit 0, or 2 on bad input."""
    scenario = scenarios.get(name)
    resolve_inputs(name, assignments, None)  # bad input fails before any run
    configs = [foot_row(c, scenario.foot) for c in SWEEP if not quick or c[0] in QUICK]
    configs = [c for c in configs if c is not None]
    steps = sum(run_steps(name, {**{k: str(v) for k, v in o.items()}, **assignments}, None) for _, o in configs)
    refuse_long(steps, f"bench {name} ({len(configs)} runs)", allow=False, remedy="raise timestep")
    rows: list[dict[str, Any]] = []
    accuracy = scenario.bench_checks
    with progress.bar(len(configs), f"bench {name}", unit="config") as bar:
        for label, overrides in configs:
            merged = {**{k: str(v) for k, v in overrides.items()}, **assignments}
            result = run_validation(name, merged, None)
            by_name = {c.name: c for c in result.checks}
            rows.append({"config": label, "settings": overrides, "wall_s": result.timing["wall_s"],
                         "steps_per_s": result.timing["steps_per_s"], "stable": by_name["stable"].passed,
                         **{f"{c}_error": by_name[c].error for c in accuracy},
                         **{f"{c}_error_kind": by_name[c].kind for c in accuracy}})
            bar.set_postfix_str(f"{label}: {rows[-1]['wall_s']:.2f} s")
            bar.update(1)
    key = f"{accuracy[0]}_error"
    front = pareto_front([r["wall_s"] for r in rows], [r[key] for r in rows])
    for row, flag in zip(rows, front, strict=True):
        row["pareto"] = flag
    raw = raw_rollout_rate(name, assignments)
    _, _, params, _ = resolve_inputs(name, assignments, None)
    reference = [scenario.exact_model_bench(params, rtol) for rtol in ([1e-3, 1e-7] if quick else REFERENCE_RTOLS)]
    peer_text, peer = bench_block(scenario.peers, params)
    print(format_table(rows, accuracy, raw, reference) + peer_text)
    _plot(rows, reference, key, output.format(scenario=name), name, peer)
    if json_path:
        json_path = json_path.format(scenario=name)
        write_json(jsonable({"scenario": name, "mujoco_version": mujoco.__version__, "rows": rows,
                             "raw_rollout": raw, "reference": reference, "peer": peer}), json_path)
    return 0


def _timed(name: str, assignments: Mapping[str, str], accuracy: tuple[str, ...]) -> dict[str, Any]:
    runs = [run_validation(name, assignments, None) for _ in range(2)]
    best = min(runs, key=lambda r: r.timing["wall_s"])
    by_name = {c.name: c for c in best.checks}
    return {"wall_s": best.timing["wall_s"], "steps_per_s": best.timing["steps_per_s"], "passed": best.passed,
            "error": by_name[accuracy[0]].error}


def run_skips(name: str, assignments: Mapping[str, str], json_path: str | None) -> int:
    """Each skip of :data:`SKIPS` measured on scenario ``name``: speed and error with and without it."""
    scenario = scenarios.get(name)
    _, _, params, settings = resolve_inputs(name, assignments, None)
    contact_off = bool(scenario.build(params, settings).opt.disableflags & int(mujoco.mjtDisableBit.mjDSBL_CONTACT))
    rows = []
    skips = [(label, what, on, off) for label, what, on, off in SKIPS
             # only the scenes that skip contact detection entirely can undo it; the others filter pairs
             if (label == "contact disabled") == contact_off or "unskip" not in off]
    with progress.bar(len(skips), f"skips {name}", unit="skip") as bar:
        for label, what, on, off in skips:
            with_skip = _timed(name, {**on, **assignments}, scenario.bench_checks)
            without = _timed(name, {**off, **assignments}, scenario.bench_checks)
            rows.append({"skip": label, "what": what, "with": with_skip, "without": without,
                         "speedup": without["wall_s"] / with_skip["wall_s"]})
            bar.set_postfix_str(f"{label}: x{rows[-1]['speedup']:.2f}")
            bar.update(1)
    key = scenario.bench_checks[0]
    print(f"{name}: what each skip buys (default preset, best of 2 validations; error = {key})")
    print(markdown_table(("skip", "what", "wall with / without (s)", "speedup", "error with", "error without"), [
        (r["skip"], r["what"], f"{r['with']['wall_s']:.2f} / {r['without']['wall_s']:.2f}", f"x{r['speedup']:.2f}",
         f"{r['with']['error']:.3e}", f"{r['without']['error']:.3e}") for r in rows]))
    if json_path:
        write_json(jsonable({"scenario": name, "mujoco_version": mujoco.__version__, "skips": rows}),
                   json_path.format(scenario=name))
    return 0


def format_table(rows: list[dict[str, Any]], accuracy: tuple[str, ...], raw: dict[str, float],
                 reference: list[dict[str, float]]) -> str:
    """Markdown table (the README's time-against-error table is pasted from it)."""
    lines = [markdown_table(
        ("settings", "wall s", "steps/s", *(f"{c} error" for c in accuracy), "Pareto"),
        [(f"{r['config']}{'' if r['stable'] else ' (UNSTABLE)'}", f"{r['wall_s']:.2f}", f"{r['steps_per_s']:.3g}",
          *(f"{r[f'{c}_error']:.2e}" for c in accuracy), "*" if r["pareto"] else "") for r in rows])]
    lines.append(f"\nmujoco.rollout alone on the same batches (default preset): {raw['steps_per_s']:.3g} steps/s "
                 f"({raw['steps']:.3g} steps in {raw['wall_s']:.2f} s); the whole validation right after: "
                 f"{raw['pipeline_steps_per_s']:.3g} steps/s = {100 * raw['pipeline_fraction']:.0f} % of it")
    metrics = [k for k in reference[0] if k not in ("rtol", "wall_s")]
    lines.append("\n" + markdown_table(
        ("solve_ivp reference (the scenario's own method and events), same fit", "wall s", *metrics),
        [(f"rtol={ref['rtol']:g}", f"{ref['wall_s']:.2f}", *(f"{ref[k]:.2e}" for k in metrics)) for ref in reference]))
    return "\n".join(lines)


def _plot(rows: list[dict[str, Any]], reference: list[dict[str, float]], key: str, path: str, name: str,
          peer: dict[str, Any] | None) -> None:
    from matplotlib.figure import Figure
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    fig = Figure(figsize=(7.6, 4.8))
    ax = fig.subplots()
    walls = np.array([r["wall_s"] for r in rows])
    errors = np.array([r[key] for r in rows])
    front = np.array([r["pareto"] for r in rows])
    ax.scatter(walls, errors, c=["tab:red" if f else "tab:blue" for f in front], zorder=3)
    for r in rows:
        ax.annotate(r["config"], (r["wall_s"], r[key]), fontsize=6, xytext=(3, 3), textcoords="offset points")
    order = np.argsort(walls[front])
    ax.plot(walls[front][order], errors[front][order], "r--", lw=1, label="MuJoCo Pareto front")
    ref_key = key if key in reference[0] else next(k for k in reference[0] if k.endswith("_error"))
    ax.plot([r["wall_s"] for r in reference], [r[ref_key] for r in reference], "ks-", label="solve_ivp reference")
    for ref in reference:
        ax.annotate(f"rtol {ref['rtol']:g}", (ref["wall_s"], ref[ref_key]), fontsize=6, xytext=(3, -9),
                    textcoords="offset points")
    if peer:
        ax.plot([r["wall_s"] for r in peer["rows"]], [r[ref_key] for r in peer["rows"]], "g^-",
                label=f"Drake {peer['version']} ({peer['scheme']})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.margins(x=0.12)  # room for the rightmost point's label
    ax.set_xlabel("wall time of one validation, s (2 threads)")
    kinds = {r.get(f"{key}_kind") for r in rows} - {None}
    ax.set_ylabel(key.replace("_", " ") + (f" ({kinds.pop()})" if len(kinds) == 1 else ""))
    ax.set_title(f"{name}: run time against error (MuJoCo {mujoco.__version__})")
    ax.legend(fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
