"""``mjpoincare list | validate | bench | sweep | converge | stress | margins | power | tune | render``: the command
line."""

from __future__ import annotations

import argparse
import importlib.util
import math
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, NoReturn

from mjpoincare.core import progress
from mjpoincare.core.parallel import machine_cores
from mjpoincare.core.params import ParameterError, PluginDeprecationWarning, Value, grid_syntax, parse_assignments

if TYPE_CHECKING:
    from mjpoincare.core.result import Result

EXIT_PASS, EXIT_FAIL, EXIT_BAD_INPUT = 0, 1, 2
#: Ctrl-C: the shell's code for SIGINT (128 + 2).
EXIT_INTERRUPTED = 130


def _require_viz(what: str, *modules: str) -> None:
    """Refuse, before any simulation, a command whose output needs the optional ``viz`` extra when it is missing."""
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        raise ParameterError(f"{what} needs {', '.join(missing)}: pip install 'mjpoincare[viz]'")


def _cmd_list(args: argparse.Namespace) -> int:
    from mjpoincare import scenarios
    from mjpoincare.commands.accepted_ranges import accepted_range
    from mjpoincare.core import progress

    names = args.scenario or scenarios.loadable()
    for name in names:
        scenarios.get(name)  # an unknown name: one line, exit 2, before anything is printed
    for name in names:
        scenario = scenarios.REGISTRY[name]
        print(f"{scenario.name}: {scenario.summary}")
        print(f"  source: {scenario.source}")
        print(f"  presets: {', '.join(scenario.presets)} (default {scenario.default_preset})"
              + ("; in the default validation" if scenario.default else ""))
        print(f"  foot_radius: {scenario.foot.meaning} (searched {scenario.foot.low:g}-{scenario.foot.high:g} m)"
              if scenario.foot else "  foot_radius: not used (the model has no foot spheres)")
        with progress.bar(len(scenario.params) if args.ranges else 0, f"{name}: accepted ranges",
                          unit="parameter") as bar:
            for p in scenario.params:
                found = accepted_range(name, p) if args.ranges else None
                accepted = found.text(p) if found else ""
                bar.update(1 if args.ranges else 0)
                print(f"  {p.name} = {p.default}  ({p.doc}; {p.range_text()}"
                      + (f"; {accepted}: past it, e.g. {found.why_low or found.why_high}" if found and accepted
                         else "") + ")")
        if scenario.region_map:
            axes = scenario.region_map.axes
            print(f"  sweep --grid {grid_syntax(axes)} with " + ", ".join(f"{a.name} = {a.doc}" for a in axes))
        for param in scenario.param_sweeps:
            print(f"  sweep --param {param}: the scenario's own sweep")
        for preset, overrides in scenario.presets.items():
            print(f"  preset {preset}: " + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                                   for k, v in overrides.items()))
    if not args.ranges:
        print("(a scenario's own checks may refuse less than a parameter's declared range at other values; "
              "mjpoincare list NAME --ranges finds, for each parameter, the range they accept at the defaults)")
    from mjpoincare.core.settings import SETTINGS

    print("simulator settings (--set NAME=VALUE on top of the preset; a preset's own values are listed above):")
    for p in SETTINGS:
        print(f"  {p.name} = {p.default}  ({p.doc}; {p.range_text()})")
    for line in scenarios.REGISTRY.broken.values():  # listed last, after every scenario that loads
        print(f"mjpoincare: error: {line}", file=sys.stderr)
    return EXIT_BAD_INPUT if scenarios.REGISTRY.broken else EXIT_PASS


def _cmd_validate(args: argparse.Namespace) -> int:
    no_gl = _select_still_backend() if args.report else None  # before MuJoCo is imported
    from mjpoincare import scenarios
    from mjpoincare.api import validate
    from mjpoincare.commands.validation import peer_of, resolve_inputs, typed_values
    from mjpoincare.core.result import check_output_path, distinct_outputs, results_document, write_json

    names = args.scenario or list(scenarios.default_scenarios())
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ParameterError(f"scenario {', '.join(twice)} is named more than once")
    if args.workers is not None and args.workers < 1:
        raise ParameterError(f"--workers must be >= 1 (got {args.workers})")
    assignments = parse_assignments(args.set)
    check_output_path(args.json, "--json")  # before the inputs: resolving them self-tests the seam (a tiny rollout)
    check_output_path(args.report, "--report", directory=True)
    distinct_outputs(json=args.json, report=args.report, baseline=args.baseline if args.update_baseline else None)
    if args.update_baseline and not args.baseline:
        raise ParameterError("--update-baseline needs --baseline PATH (the file to record into)")
    if args.baseline:
        from mjpoincare.gate import baseline

        baseline.check_path(args.baseline, args.update_baseline)
    for name in names:  # refuse bad input before any simulation or file
        scenario, _, params, _ = resolve_inputs(name, assignments, args.preset)
        if args.peer:
            peer_of(scenario, args.peer, params)
        if args.extrapolate:
            from mjpoincare.commands.extrapolate import coarse_grids

            coarse_grids(name, assignments, args.preset)
    if args.report:
        _require_viz("--report", "matplotlib")
    from mjpoincare.commands.validation import run_steps
    from mjpoincare.core.cost import refuse_long

    for name in names:
        refuse_long(run_steps(name, assignments, args.preset), f"validate {name}", allow=args.allow_long)
    workers = min(len(names), args.workers or machine_cores())
    if workers > 1:
        # The scenarios side by side, one process each, and each with every core's rollout threads: their costs
        # differ tenfold, so a scenario held to its share of the cores would leave the others' cores idle once they
        # are done (the results do not depend on the threads).
        from mjpoincare.commands.validation import run_validation
        from mjpoincare.core.parallel import run_jobs

        done = run_jobs(run_validation, [(name, assignments, args.preset, args.seed, args.peer) for name in names],
                        workers=workers)
        results = []
        with progress.bar(len(names), "validate", unit="scenario") as bar:
            for result in done:
                results.append(result)
                bar.set_postfix_str(f"{result.scenario}: {'pass' if result.passed else 'FAIL'}")
                bar.update(1)
        results.sort(key=lambda r: names.index(r.scenario))
    else:
        results = []
        with progress.bar(len(names), "validate", unit="scenario") as bar:
            for name in names:
                bar.set_postfix_str(f"{name}: running")
                results.append(validate(name, args.preset, args.seed, peer=args.peer,
                                        **typed_values(name, assignments)))
                bar.update(1)
    if args.extrapolate:
        from mjpoincare.commands.extrapolate import extrapolate

        for result in results:
            result.extrapolated = extrapolate(result.scenario, assignments, args.preset, args.seed,
                                              result.checks, result.timing["wall_s"])
    if args.json != "-":
        for result in results:
            print(result.table())
            if result.peer is not None:
                from mjpoincare.engines.peers.compare import format_peer

                print(format_peer(result.peer))
            if result.extrapolated is not None:
                from mjpoincare.commands.extrapolate import table

                print(table(result.extrapolated))
            print()
    if args.json:
        write_json(results_document(results), args.json)
    changed = _compare_or_record_baseline(args, results, assignments) if args.baseline else []
    if args.report:
        from mjpoincare.commands.report import write_index, write_report

        pages = [r.to_dict() for r in results]
        paths = [write_report(page, args.report, no_gl or _report_still(page["scenario"], assignments, args.preset))
                 for page in pages]
        paths.insert(0, write_index(pages, args.report))
        if args.json != "-":
            print("\n".join(f"report: {path}" for path in paths))
    return EXIT_PASS if all(r.passed for r in results) and not changed else EXIT_FAIL


def _compare_or_record_baseline(args: argparse.Namespace, results: list[Result], assignments: dict[str, Value]
                                ) -> list[str]:
    """With ``--update-baseline``: record each result with its resolution (the gate's perturbations, re-run) into
    ``--baseline``, and return nothing; without: the lines of every check that moved beyond its allowance."""
    from mjpoincare.gate import baseline

    out = sys.stderr if args.json == "-" else sys.stdout
    if not args.update_baseline:
        recorded = baseline.load(args.baseline)
        lines = [d.message() for r in results for d in baseline.deviations(r, recorded)]
        print("\n".join([f"baseline {args.baseline}: {len(lines)} change(s) beyond the resolution", *lines])
              if lines else f"baseline {args.baseline}: no change beyond the resolution", file=out)
        return lines
    from mjpoincare.core.result import write_json
    from mjpoincare.core.stamp import environment

    previous = baseline.load(args.baseline) if Path(args.baseline).exists() else None
    records = [(baseline.run_key(r), baseline.entry(r, baseline.perturbation_spreads(r, assignments)))
               for r in results]
    write_json(baseline.updated(previous, records, environment()), args.baseline)
    print(f"baseline {args.baseline}: recorded {', '.join(key for key, _ in records)}", file=out)
    return []


def _select_still_backend() -> str | None:
    """Choose the OpenGL backend of the report's stills (before MuJoCo is imported); None, or why none works."""
    from mjpoincare.commands.render import RenderError, select_gl_backend

    try:
        select_gl_backend()
    except RenderError as err:
        return str(err)
    return None


def _report_still(name: str, assignments: dict[str, str], preset: str | None) -> bytes | str:
    """The report's still of scenario ``name`` (PNG bytes), or why it could not be rendered."""
    from mjpoincare.commands.render import RenderError, render_still

    try:
        return render_still(name, assignments, preset)
    except RenderError as err:
        return str(err)


def _cmd_bench(args: argparse.Namespace) -> int:
    from mjpoincare.commands.bench import run_bench, run_skips
    from mjpoincare.core.result import check_output_path, check_plot_path, distinct_outputs

    modes = [flag for flag in ("quick", "skips", "scaling", "paths") if getattr(args, flag)]
    if len(modes) > 1:
        raise ParameterError(f"bench takes one of --quick, --skips, --scaling, --paths (got --{' and --'.join(modes)})")
    if args.scaling and not args.param:
        raise ParameterError("bench --scaling needs --param NAME (the swept parameter or setting)")
    if args.param and not args.scaling:
        raise ParameterError(f"--param {args.param} is for bench --scaling only")
    if args.compare is not None and not args.paths:
        raise ParameterError(f"--compare {args.compare} is for bench --paths only")
    if args.values is not None and not args.scaling:
        raise ParameterError(f"--values {args.values} is for bench --scaling only (with --param NAME)")
    if args.scaling:
        from mjpoincare.commands.bench_scaling import run_scaling

        json_path = args.json if args.json != "renders/bench-{scenario}.json" else "renders/scaling-{scenario}.json"
        check_output_path(json_path and json_path.format(scenario=args.scenario), "--json")
        return run_scaling(args.scenario, args.param, args.values or SCALING_VALUES, parse_assignments(args.set),
                           json_path, workers=args.workers, repeats=args.repeats)
    if args.skips:
        json_path = args.json if args.json != "renders/bench-{scenario}.json" else "renders/skips-{scenario}.json"
        check_output_path(json_path and json_path.format(scenario=args.scenario), "--json")
        return run_skips(args.scenario, parse_assignments(args.set), json_path)
    if args.paths:
        json_path = args.json if args.json != "renders/bench-{scenario}.json" else "renders/paths-{scenario}.json"
        output = args.output if args.output != "renders/bench-{scenario}.png" else "renders/paths-{scenario}.png"
    else:
        json_path, output = args.json, args.output
    check_output_path(json_path and json_path.format(scenario=args.scenario), "--json")
    check_plot_path(output.format(scenario=args.scenario), "--output")
    distinct_outputs(json=json_path and json_path.format(scenario=args.scenario),
                     output=output.format(scenario=args.scenario))
    _require_viz("bench's plot", "matplotlib")
    if args.paths:
        from mjpoincare.commands.bench_paths import run_paths

        return run_paths(args.scenario, parse_assignments(args.set), output, json_path, args.compare)
    return run_bench(args.scenario, parse_assignments(args.set), args.output, args.json, quick=args.quick)


#: bench --scaling's values when --values is not given.
SCALING_VALUES = "0.08:0.2:16"

#: The most cells a region map's --grid may have without --allow-long (100 x 100: each cell is a trajectory).
MAX_GRID_CELLS = 10_000


def _cmd_sweep(args: argparse.Namespace) -> int:
    from mjpoincare import scenarios
    from mjpoincare.commands.sweep import run_own_sweep, run_region_map, run_sweep
    from mjpoincare.core.params import parse_values
    from mjpoincare.core.result import check_output_path, check_plot_path, distinct_outputs

    scenario = scenarios.get(args.scenario)
    check_output_path(args.json, "--json")
    if args.grid:
        facet = scenario.region_map
        if facet is None:
            with_map = [name for name in scenarios.loadable() if scenarios.REGISTRY[name].region_map]
            raise ParameterError(f"--grid: {scenario.name} has no region map (scenarios with one: "
                                 f"{', '.join(with_map)})")
        from mjpoincare.core.params import parse_grid

        cells = math.prod(len(v) for v in parse_grid(args.grid, facet.axes).values())
        if cells > MAX_GRID_CELLS and not args.allow_long:
            raise ParameterError(f"--grid gives {cells} cells, more than {MAX_GRID_CELLS} (each one a trajectory): "
                                 "use fewer points per axis, or give --allow-long")
        output = (args.output or facet.output).format(scenario=scenario.name)
        check_plot_path(output, "--output")
        distinct_outputs(json=args.json, output=output)
        _require_viz("sweep --grid", "matplotlib")
        return run_region_map(scenario.name, facet, args.grid, parse_assignments(args.set), args.preset, args.json,
                              output, workers=args.workers)
    if not (args.param and args.values):
        raise ParameterError("sweep needs --param and --values (or --grid)")
    if args.output and args.param in scenario.param_sweeps:
        raise ParameterError(f"--output {args.output}: {scenario.name}'s own sweep of {args.param} prints its table "
                             "and writes --json; the plot is for the generic one-parameter sweep and --grid")
    if args.output:
        check_plot_path(args.output, "--output")
        distinct_outputs(json=args.json, output=args.output)
        _require_viz("sweep -o", "matplotlib")
    values = parse_values(args.values)
    if any(a.split("=", 1)[0].strip() == args.param for a in args.set):
        raise ParameterError(f"--set {args.param} and --param {args.param}: the sweep sets {args.param} at each value; "
                             "drop the --set")
    if args.param not in scenario.param_sweeps:
        from mjpoincare.commands.validation import run_steps
        from mjpoincare.core.cost import refuse_long

        assignments = parse_assignments(args.set)
        ends = {values[0], values[len(values) // 2], values[-1]}  # a value's steps vary smoothly along the sweep
        steps = len(values) * max(run_steps(scenario.name, {**assignments, args.param: v}, args.preset) for v in ends)
        refuse_long(steps, f"sweep {scenario.name} over {len(values)} values", allow=args.allow_long)
    if args.param in scenario.param_sweeps:
        return run_own_sweep(scenario.name, args.param, scenario.param_sweeps[args.param], values,
                             parse_assignments(args.set), args.preset, args.json, resume=args.resume,
                             workers=args.workers)
    return run_sweep(args.scenario, args.param, values, parse_assignments(args.set), args.preset,
                     args.json, args.locate, workers=args.workers, engine=args.engine, scheduler=args.scheduler,
                     resume=args.resume, plot=args.output)


def _cmd_reproduce(args: argparse.Namespace) -> int:
    from mjpoincare.commands.reproduce import list_results, run_reproduce
    from mjpoincare.core.result import check_output_path

    check_output_path(args.json, "--json")
    check_output_path(args.output, "--output", directory=True)
    if args.list:
        return list_results(args.ids, args.paper, args.json)
    if args.output:
        _require_viz("reproduce -o", "matplotlib")
    return run_reproduce(args.ids, args.paper, args.preset, args.json, args.output, workers=args.workers,
                         engine=args.engine, scheduler=args.scheduler, resume=args.resume)


def _cmd_converge(args: argparse.Namespace) -> int:
    from mjpoincare.commands.converge import DEFAULT_AXES, run_converge
    from mjpoincare.core.result import check_output_path, distinct_outputs

    check_output_path(args.json, "--json")
    check_output_path(args.report, "--report", directory=True)
    distinct_outputs(json=args.json, report=args.report)
    if args.report:
        _require_viz("--report", "matplotlib")
    return run_converge(args.scenario, parse_assignments(args.set), args.preset, json_path=args.json,
                        report=args.report, axes=args.axis or DEFAULT_AXES, points=args.points, ratio=args.ratio,
                        seed=args.seed, workers=args.workers, engine=args.engine, scheduler=args.scheduler,
                        resume=args.resume, allow_long=args.allow_long)


def _cmd_stress(args: argparse.Namespace) -> int:
    from mjpoincare.commands.stress import run_stress
    from mjpoincare.core.result import check_output_path

    check_output_path(args.json, "--json")

    return run_stress(args.scenario, args.json, soak=args.soak, workers=args.workers, allow_long=args.allow_long)


def _cmd_margins(args: argparse.Namespace) -> int:
    import json

    from mjpoincare.core.result import check_output_path, write_json
    from mjpoincare.gate import environments as gate_environments
    from mjpoincare.gate import forms as gate

    check_output_path(args.json, "--json")
    cases = [c for c in gate.cases() if not args.case or any(k in c.label for k in args.case)]
    if not cases:
        raise ParameterError(f"--case matches no gate case; cases: {', '.join(c.label for c in gate.cases())}")
    if args.workers < 1:
        raise ParameterError(f"--workers must be >= 1 (got {args.workers})")
    offered = [e for e in gate_environments.ensemble() if e is not gate_environments.DEFAULT]
    if args.base_only or args.environments == "none":
        chosen = []
    elif args.environments == "all":
        chosen = offered
    else:
        wanted = args.environments.split(",")
        chosen = [e for e in offered if e.label in wanted]
        if len(chosen) != len(set(wanted)):
            raise ParameterError(f"--environments must be all, none or labels of {', '.join(e.label for e in offered)}"
                                 f" (got {args.environments})")
    recorded: dict[str, gate_environments.Errors] = {}
    for path in args.compare:
        try:
            other = json.loads(Path(path).read_text())["rows"]
        except (OSError, ValueError, KeyError) as err:
            raise ParameterError(f"--compare {path} is not a margins JSON file ({err})") from None
        recorded[f"--compare {Path(path).name}"] = gate_environments.errors_of(other)
    stamp = None
    if args.json:
        from mjpoincare.core.stamp import environment, git_state

        stamp = environment()  # the commit the run starts from; marked dirty if the tree changes while it runs
    environments = {**gate_environments.run_ensemble(chosen, [c.label for c in cases], workers=args.workers),
                    **recorded}
    rows = gate.margin_rows(cases, perturb=not args.base_only, environments=environments)
    if args.json != "-":
        print(gate.margin_table(rows))
    if stamp is not None:
        import mujoco

        from mjpoincare.analysis.checks import jsonable

        if git_state() != (stamp["git_sha"], False):
            stamp["git_dirty"] = True
        write_json(jsonable({"mujoco_version": mujoco.__version__, "margin": gate.MARGIN, "stamp": stamp,
                             "environments": ["this run", *(label for label, _, _ in gate.PERTURBATIONS
                                                            if not args.base_only), *environments],
                             "rows": rows}), args.json)
    return EXIT_PASS if all(r["holds"] for r in rows) else EXIT_FAIL


def _cmd_power(args: argparse.Namespace) -> int:
    from mjpoincare.core.result import check_output_path, write_json
    from mjpoincare.gate import forms as gate
    from mjpoincare.gate import power

    check_output_path(args.json, "--json")
    if args.workers < 1:
        raise ParameterError(f"--workers must be >= 1 (got {args.workers})")
    cases = [c for c in power.default_cases() if not args.case or any(k in c.label for k in args.case)]
    if not cases:
        raise ParameterError("--case matches no case; cases: " + ", ".join(c.label for c in power.default_cases()))
    chosen = [p for p in power.plants() if not args.change or p.change in ("none", *args.change)]
    unknown_changes = set(args.change) - {p.change for p in power.plants()}
    if unknown_changes:
        raise ParameterError(f"--change must be among {', '.join(sorted({p.change for p in power.plants()}))} "
                             f"(got {', '.join(sorted(unknown_changes))})")
    power.committed_baseline()
    stamp = None
    if args.json:
        from mjpoincare.core.stamp import environment

        stamp = environment()
    rows = power.power_rows(cases, chosen, args.workers)
    if args.json != "-":
        from mjpoincare.analysis.tables import text_table

        print(text_table(("case", "change", "verdict", "by the tolerance", "by the baseline"),
                         [(r["case"], power.Plant(r["change"], r["size"]).label, power.verdict(r),
                           r["raised"] or ",".join(r["tolerance"]), ",".join(r["baseline"])) for r in rows]))
    if stamp is not None:
        import mujoco

        from mjpoincare.analysis.checks import jsonable
        from mjpoincare.core.allowance import FLOOR, MULTIPLE

        write_json(jsonable({"mujoco_version": mujoco.__version__, "multiple": MULTIPLE, "floor": FLOOR,
                             "margin": gate.MARGIN,
                             "stamp": stamp, "rows": rows}), args.json)
    return EXIT_PASS if power.holds(rows) else EXIT_FAIL


def _cmd_tune(args: argparse.Namespace) -> int:
    from mjpoincare import scenarios
    from mjpoincare.commands.tune import STUDY_DIR, run_study, summary
    from mjpoincare.core.result import check_output_path, check_plot_path, distinct_outputs, write_json
    from mjpoincare.core.stamp import environment

    name = scenarios.get(args.scenario).name
    check_output_path(args.json, "--json")
    check_plot_path(args.plot, "--plot")
    distinct_outputs(json=args.json, plot=args.plot, study=args.study)
    if args.plot:
        _require_viz("tune --plot", "matplotlib")
    path = Path(args.study or STUDY_DIR / f"{name}.db")
    enqueue = [parse_assignments(item.split(",")) for item in args.enqueue]
    command = (f"mjpoincare tune {name} --target {args.target} --trials {args.trials}"
               + "".join(f" --enqueue {item}" for item in args.enqueue) + (" --resume" if args.resume else ""))
    study = run_study(name, args.target, trials=args.trials, workers=args.workers, path=path, resume=args.resume,
                      seed=args.seed, enqueue=enqueue, command=command)
    data = {**summary(study), "environment": environment()}
    print(f"{data['study']}: {len(data['trials'])} trials, Pareto front of {len(data['front'])} (study {path})")
    print(f"{'CPU s':>8} {'wall s':>8} {'worst ratio':>12}  worst check / settings")
    for row in data["front"]:
        print(f"{row['cpu_s']:8.3g} {row['wall_s']:8.3g} {row['worst_ratio']:12.3g}  {row['worst_check']}"
              f"  [{row['origin']}] {row['settings']}")
    chosen = data["chosen"]
    if data["holds"] != "margin":
        print(f"no trial holds every check within {data['preset_ratio']:g} of its {args.target} tolerance at every "
              "coverage point (the front above is the best found)")
    if chosen is None:
        print(f"no trial passes every check: no {args.target} preset in the searched space")
    else:
        print(f"preset {args.target}: trial {chosen['number']} ({chosen['cpu_s']:.3g} CPU s, worst ratio "
              f"{chosen['worst_ratio']:.3g} at {chosen['worst_check']}; {data['holds']}): {data['preset']}")
    if args.json:
        write_json(data, args.json)
    if args.plot:
        from mjpoincare.commands.tune_pages import plot_front

        plot_front(data, args.plot)
    return EXIT_PASS


def _cmd_render(args: argparse.Namespace) -> int:
    from mjpoincare.commands.render import (
        check_clip,
        check_media_path,
        parse_size,
        render_frames,
        select_gl_backend,
        write_media,
    )

    output = args.output or f"renders/{args.scenario}.mp4"
    check_media_path(output)
    size = parse_size(args.size)
    assignments = parse_assignments(args.set)
    check_clip(args.seconds, args.fps, 1.0)
    backend = select_gl_backend()  # before MuJoCo is imported
    from mjpoincare.commands.validation import resolve_inputs

    check_clip(args.seconds, args.fps, float(resolve_inputs(args.scenario, assignments, args.preset)[3]["timestep"]))
    from mjpoincare.core.result import check_output_path

    check_output_path(output, "--output")
    _require_viz("render", "mediapy", "imageio_ffmpeg")
    frames, timing = render_frames(args.scenario, assignments, args.preset, args.seconds, args.fps, size,
                                   last_only=output.lower().endswith(".png"))
    write_media(output, frames, args.fps)
    print(f"wrote {output}: {len(frames)} frames {size[0]}x{size[1]} with MUJOCO_GL={backend}; "
          f"simulate {timing['simulate_s']:.2f} s, render {timing['ms_per_frame']:.1f} ms/frame")
    return EXIT_PASS


class OneLineParser(argparse.ArgumentParser):
    """argparse's parser whose errors are one line on stderr, as every other refusal (``mjpoincare: error: ...``,
    exit 2), without the usage block argparse prints first; ``-h`` still shows the usage."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see {self.prog} -h)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (exposed for tests and docs)."""
    from importlib.metadata import version

    from mjpoincare import __version__

    parser = OneLineParser(prog="mjpoincare", description=__doc__)
    parser.add_argument("--version", action="version",
                        version=f"mjpoincare {__version__} (MuJoCo {version('mujoco')})")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    lst = sub.add_parser("list", help="list scenarios, their parameters and presets")
    lst.add_argument("scenario", nargs="*", help="scenario names (default: every scenario)")
    lst.add_argument("--ranges", action="store_true",
                     help="also find, by bisection of each scenario's own checks, the range of each numeric parameter "
                          "a run accepts with the others at their defaults (slow: seconds per parameter, minutes for "
                          "the bipeds, whose checks solve for the gait)")
    lst.set_defaults(func=_cmd_list)

    val = sub.add_parser("validate", help="run scenarios and check them against the analytic results")
    val.add_argument("scenario", nargs="*", help="scenario names (default: the default scenarios)")
    val.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                     help="set a parameter or simulator setting (repeatable)")
    val.add_argument("--preset", default=None, help="simulator preset: fast or accurate")
    val.add_argument("--json", metavar="PATH|-", help="write the result as JSON (- for stdout)")
    val.add_argument("--seed", type=int, default=0, help="seed of the bootstrap (same seed, same result)")
    val.add_argument("--workers", type=int, default=None, help="scenarios run side by side, each in its own process "
                     "with every core's rollout threads (default: this machine's cores, at most one per scenario; "
                     "results are the serial ones)")
    val.add_argument("--report", metavar="DIR", help="write a self-contained HTML report per scenario into DIR")
    val.add_argument("--baseline", metavar="PATH", help="compare each check's error with this baseline file's (exit "
                     "1 on a change beyond its allowance: 3 x its resolution, never below 1e-6 x its tolerance; or a "
                     "check missing or new; a file that does not exist is an error)")
    val.add_argument("--update-baseline", action="store_true", help="record this run into --baseline instead (kept: "
                     "its other runs), each check's resolution measured by re-running under the gate's perturbations")
    val.add_argument("--extrapolate", action="store_true", help="also run the timestep grids 2h and 4h and report "
                     "each scalar check's Richardson value and GCI band where its order is clean (not judged)")
    val.add_argument("--allow-long", action="store_true", help="run even when the run's estimated MuJoCo steps "
                     "exceed 1e9 (refused otherwise, before any simulation)")
    val.add_argument("--peer", choices=("drake",), help="add an outside simulator's value of each check (drake: "
                     "rimless-wheel and compass-biped; pip install 'mjpoincare[peers]')")
    val.set_defaults(func=_cmd_validate)

    bench = sub.add_parser("bench", help="run time against error over timestep, integrator and contact settings")
    bench.add_argument("scenario", help="scenario name")
    bench.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    bench.add_argument("-o", "--output", default="renders/bench-{scenario}.png", help="PNG plot path")
    bench.add_argument("--json", metavar="PATH|-", default="renders/bench-{scenario}.json",
                       help="bench table as JSON (the report's convergence plot reads the default path)")
    bench.add_argument("--quick", action="store_true", help="a small sweep (for tests)")
    bench.add_argument("--paths", action="store_true", help="instead: the error against the wall time of the fast "
                       "preset, the accurate preset and the fast preset with Richardson extrapolation, one plot")
    bench.add_argument("--compare", metavar="JSON", help="--paths: another build's bench --paths --json (an earlier "
                       "commit, another MuJoCo), drawn beside this one's, dashed")
    bench.add_argument("--skips", action="store_true", help="instead: what each skip (collision filtering, no "
                       "sensors, contact off, solver budget, threads) buys in speed, and the error with and without")
    bench.add_argument("--scaling", action="store_true", help="instead: a sweep's speedup from 1 to --workers "
                       "processes beside the machine's ceiling for independent MuJoCo work (best of --repeats)")
    bench.add_argument("--param", help="--scaling (required there): the swept parameter or setting")
    bench.add_argument("--values", help=f"--scaling: its values, v1,v2,... or START:STOP:N (default {SCALING_VALUES})")
    bench.add_argument("--workers", type=int, default=2, help="--scaling: processes to scale to")
    bench.add_argument("--repeats", type=int, default=3, help="--scaling: best of this many runs of each")
    bench.set_defaults(func=_cmd_bench)

    sweep = sub.add_parser("sweep", help="validate over a list of values of one parameter")
    sweep.add_argument("scenario", help="scenario name")
    sweep.add_argument("--param", help="parameter or setting to sweep (a scenario's own sweep where it has one: "
                       "mjpoincare list)")
    sweep.add_argument("--values", help="v1,v2,... or START:STOP:COUNT")
    sweep.add_argument("--grid", help="instead: the scenario's region map over two axes, AXIS=START:STOP:N,"
                       "AXIS=START:STOP:N (its axes: mjpoincare list)")
    sweep.add_argument("-o", "--output", help="PNG: with --grid, the region map (default: the scenario's, e.g. "
                       "renders/regions-{scenario}.png); with --param, each check's error over the values against "
                       "its tolerance and abs(lambda)max fitted beside analytic")
    sweep.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    sweep.add_argument("--preset", default=None)
    sweep.add_argument("--json", metavar="PATH|-", help="write the sweep table as JSON")
    sweep.add_argument("--locate", choices=("period-doubling", "stability-loss"),
                       help="locate where the lowest eigenvalue hits -1 (period-doubling) or |lambda|max hits 1")
    sweep.add_argument("--workers", type=int, default=1, help="values validated at once (processes; default 1)")
    sweep.add_argument("--engine", default="local", help="local (process pool) or dask (pip install "
                       "'mjpoincare[dask]')")
    sweep.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address (default: a local cluster "
                       "of --workers processes)")
    sweep.add_argument("--allow-long", action="store_true", help="run even when the sweep's estimated MuJoCo steps "
                       "exceed 1e9 (refused otherwise, before any simulation)")
    sweep.add_argument("--resume", action="store_true", help="skip the values the --json results file already holds")
    sweep.set_defaults(func=_cmd_sweep)

    conv = sub.add_parser("converge", help="observed order, Richardson value, GCI band and verdict of every scalar "
                          "check over timestep and contact-setting ladders")
    conv.add_argument("scenario", help="scenario name")
    conv.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    conv.add_argument("--preset", default=None, help="start values of the ladders (default: the scenario's)")
    conv.add_argument("--allow-long", action="store_true", help="run even when the ladders' estimated MuJoCo steps "
                      "exceed 1e9 (refused otherwise, before any simulation)")
    conv.add_argument("--axis", action="append", metavar="AXIS", help="timestep, solref_timeconst, "
                      "solref_dampratio or foot_radius (repeatable; default timestep and solref_timeconst)")
    conv.add_argument("--points", type=int, default=4, help="rungs per ladder (>= 3; 4+ gives the order's "
                      "uncertainty)")
    conv.add_argument("--ratio", type=float, default=2.0, help="refinement ratio between rungs")
    conv.add_argument("--seed", type=int, default=0, help="seed of the validation's bootstrap")
    conv.add_argument("--json", metavar="PATH|-", help="write rungs and analysis as JSON")
    conv.add_argument("--report", metavar="DIR", help="write a log-log convergence plot per check into DIR")
    conv.add_argument("--workers", type=int, default=1, help="rungs run at once (processes)")
    conv.add_argument("--engine", default="local", help="local (process pool) or dask")
    conv.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address")
    conv.add_argument("--resume", action="store_true", help="skip the rungs the --json file already holds")
    conv.set_defaults(func=_cmd_converge)

    rep = sub.add_parser("reproduce", help="run every result of the papers in MuJoCo (fixed points, multipliers, "
                         "bounds, figures' curves, bifurcations): paper value, analytic, MuJoCo, error, verdict")
    rep.add_argument("ids", nargs="*", help="result ids (default: all; --list shows them)")
    rep.add_argument("--paper", help="only this paper's results: 000, 001, 002 or 003")
    rep.add_argument("--list", action="store_true", help="print the ids and where each is in its paper; no simulation")
    rep.add_argument("--preset", default="fast", help="fast (default) or accurate (figures and brackets run at fast "
                     "only)")
    rep.add_argument("--json", metavar="PATH|-", help="write every result (and the resumable rows) as JSON")
    rep.add_argument("-o", "--output", metavar="DIR", help="write each figure's plot (theory curve, MuJoCo points with "
                     "their spread) into DIR")
    rep.add_argument("--workers", type=int, default=1, help="jobs run at once (processes or Dask workers)")
    rep.add_argument("--engine", default="local", help="local (process pool) or dask")
    rep.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address")
    rep.add_argument("--resume", action="store_true", help="skip the rows the --json file already holds")
    rep.set_defaults(func=_cmd_reproduce)

    stress = sub.add_parser("stress", help="push settings and parameters to the edges: stable or not, largest "
                            "stable timestep, soak drift")
    stress.add_argument("scenario", nargs="*", help="scenario names (default: the default scenarios)")
    stress.add_argument("--json", metavar="PATH|-", help="write the stress report as JSON (- for stdout)")
    stress.add_argument("--soak", type=int, default=10_000, help="impacts in the soak from the fixed point (0: none)")
    stress.add_argument("--workers", type=int, default=1, help="cases run at once (processes)")
    stress.add_argument("--allow-long", action="store_true", help="run a soak estimated past 1e9 MuJoCo steps")
    stress.set_defaults(func=_cmd_stress)

    margins = sub.add_parser("margins", help="the regression gate's checks over the environments this machine can "
                             "emulate (BLAS kernels, numpy's dispatch) and under perturbations that must not matter "
                             "(seed, threads, starts x(1+1e-12)): error, spread with the environment at each extreme, "
                             "tolerance, margin, and an expected miss's declared error beside its measured one")
    margins.add_argument("--case", action="append", default=[], metavar="TEXT", help="only cases whose label "
                         "contains TEXT (repeatable), e.g. rimless-wheel[fast")
    margins.add_argument("--json", metavar="PATH|-", help="write the margin table as JSON (- for stdout)")
    margins.add_argument("--compare", action="append", default=[], metavar="JSON", help="a margins JSON from another "
                         "environment (e.g. the oldest numpy/scipy): its errors count into the spread")
    margins.add_argument("--base-only", action="store_true", help="only each case's own run, no perturbations and no "
                         "other environments (to record this environment's errors for --compare)")
    margins.add_argument("--environments", default="all", metavar="all|none|LABEL,...", help="the environments this "
                         "machine can emulate, each in a process of its own (every OpenBLAS kernel the CPU runs, numpy "
                         "at its baseline): all (default), none, or labels such as OPENBLAS_CORETYPE=Prescott")
    margins.add_argument("--workers", type=int, default=2, help="environment processes at once")
    margins.set_defaults(func=_cmd_margins)

    pw = sub.add_parser("power", help="the gate's power: plant physics changes of known size into each scenario's "
                        "default gate case (its theory's parameters: slope, radius of gyration, gravity, hip mass, "
                        "friction; the simulator's: timestep, solref, impratio, cone, integrator, a contact pair; and "
                        "controls it cannot see); what the theory says each does to the checks, and which checks "
                        "catch it by tolerance and by baseline")
    pw.add_argument("--case", action="append", default=[], metavar="TEXT", help="only cases whose label contains TEXT")
    pw.add_argument("--change", action="append", default=[], metavar="CHANGE", help="only this change (repeatable; "
                    "the unplanted control always runs)")
    pw.add_argument("--json", metavar="PATH|-", help="write the rows as JSON (make power: "
                    "docs/results/gate/power.json)")
    pw.add_argument("--workers", type=int, default=2, help="planted runs at once (processes)")
    pw.set_defaults(func=_cmd_power)

    tune = sub.add_parser("tune", help="search the simulator settings for the cheapest that pass at every coverage "
                          "point (Optuna, multi-objective: CPU seconds against the worst error/tolerance)")
    tune.add_argument("scenario", help="scenario name")
    tune.add_argument("--target", default="accurate", help="the preset whose tolerances judge the trials: accurate "
                      "or fast (default accurate)")
    tune.add_argument("--trials", type=int, default=40, help="finished trials the study holds at the end (default 40; "
                      "with --resume, counting the stored ones)")
    tune.add_argument("--workers", type=int, default=machine_cores(), help="trials run at once, one process each "
                      "(default: this machine's cores)")
    tune.add_argument("--resume", action="store_true", help="continue the stored study instead of starting anew")
    tune.add_argument("--study", metavar="PATH", help="the study's SQLite file (default renders/tune/SCENARIO.db; "
                      "one file holds both targets' studies)")
    tune.add_argument("--json", metavar="PATH|-", help="write the trials, the Pareto front and the chosen preset")
    tune.add_argument("--plot", metavar="PNG", help="plot the front (needs the viz extra)")
    tune.add_argument("--seed", type=int, default=0, help="seed of the sampler (worker k uses seed + k)")
    tune.add_argument("--enqueue", action="append", default=[], metavar="NAME=VALUE,...", help="settings to try as "
                      "the next trial (repeatable; the searched settings it leaves out are sampled)")
    tune.set_defaults(func=_cmd_tune)

    render = sub.add_parser("render", help="render a scenario off-screen to a video (.mp4, .gif) or still (.png)")
    render.add_argument("scenario", help="scenario name")
    render.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    render.add_argument("--preset", default=None)
    render.add_argument("-o", "--output", default=None, help="output path (default renders/SCENARIO.mp4)")
    render.add_argument("--seconds", type=float, default=5.0)
    render.add_argument("--fps", type=int, default=30)
    render.add_argument("--size", default="640x480", help="WIDTHxHEIGHT")
    render.set_defaults(func=_cmd_render)
    check = sub.add_parser("check-plugin", help="the scenario contract and the gate's forms against an installed "
                           "scenario (a plugin's): one line per clause")
    check.add_argument("scenario", help="scenario name")
    check.set_defaults(func=_cmd_check_plugin)
    new = sub.add_parser("new-scenario", help="write a minimal working scenario plugin to start from (a folder with "
                         "its pyproject.toml, package, model and README)")
    new.add_argument("name", help="the scenario's name, lower-case words joined by hyphens")
    new.add_argument("--dir", default=None, help="the folder to write (default ./NAME; must not exist)")
    new.set_defaults(func=_cmd_new_scenario)
    return parser


def _cmd_check_plugin(args: argparse.Namespace) -> int:
    no_gl = _select_still_backend()  # before MuJoCo is imported: the stills' OpenGL backend
    from mjpoincare.commands.check_plugin import check_plugin

    if no_gl:
        print(f"note: {no_gl}: the still clauses will fail")
    return check_plugin(args.scenario)


def _cmd_new_scenario(args: argparse.Namespace) -> int:
    from mjpoincare.commands.new_scenario import write_scenario

    root = write_scenario(args.name, args.dir)
    print(f"wrote {root}/ (pyproject.toml, {args.name.replace('-', '_')}/, README.md): pip install -e {root} && "
          f"mjpoincare check-plugin {args.name}")
    return EXIT_PASS


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point: exit 0 when all checks pass, 1 when one fails, 2 on bad input. A plugin's use of an old name of
    the plugin API is shown once per place (Python hides a DeprecationWarning outside ``__main__``), within this call
    only."""
    args = build_parser().parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("default", PluginDeprecationWarning)
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    try:
        return int(args.func(args))
    except KeyboardInterrupt:  # Ctrl-C: one line, no traceback; a results file is written whole or not at all
        print("mjpoincare: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except ParameterError as err:
        print(f"mjpoincare: error: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except RuntimeError as err:  # RenderError: what to install
        if type(err).__name__ != "RenderError":
            raise
        print(f"mjpoincare: error: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())
