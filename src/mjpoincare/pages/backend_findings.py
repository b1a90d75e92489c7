"""The backends' findings: each scenario's default checks on MuJoCo C, MJX (x64 and float32) and MuJoCo Warp, beside
each other, with compile seconds and steps per second; and (``--maps``) the friction wheel's region map and mu sweep,
each in rollouts of the ``batch`` setting's size.

``python -m mjpoincare.pages.backend_findings all --out DIR`` runs every scenario x preset x backend not yet in
``DIR/json/`` (one process per run, so that each compile time is a first compile; resumable), then writes
``DIR/README.md`` from the JSON. ``make backends`` writes ``docs/results/backends/`` this way; ``make gpu-check`` is
the same command with a GPU's sizes (batches of thousands, both presets, the maps). ``... run SCENARIO BACKEND
PRECISION --preset P --out DIR``: one validation. ``... scaling SCENARIO BACKEND PRECISION --sizes B ...``: the
seconds per batched step against the batch size (:mod:`mjpoincare.pages.batch_scaling`). ``... render DIR``: the page
again from the JSON (no simulation).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from collections.abc import Sequence
from importlib import metadata
from pathlib import Path
from typing import Any

from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import write_json, write_text
from mjpoincare.pages.backend_findings_page import COLUMNS, PERTURBATIONS, load, render

#: The fields of a validation's result a record keeps (the scenario's extras, fits and plots stay out: the page
#: needs the checks, and the JSON of every run of ``make backends`` stays small enough for git).
RESULT_FIELDS = ("seed", "passed", "params", "settings", "mujoco_version", "checks", "timing", "warnings",
                 "diverged_trajectories", "reported")
#: The packages whose versions stamp a run, beside :func:`mjpoincare.core.stamp.environment`'s.
BACKEND_PACKAGES = ("jax", "jaxlib", "mujoco-mjx", "warp-lang", "mujoco-warp")
#: The maps ``--maps N`` runs per backend: the friction wheel's basin map over (theta_dot0, x_dot0), an N x N grid,
#: and its mu sweep, N mu values (each with its SWEEP_OFFSETS starts; each mu costs a reference run on the CPU).
MAP_AXES = "theta_dot0=0.02:1.3:{n},x_dot0=0:0.3:{n}"
MU_RANGE = "0.1:1.2:{count}"


def _versions() -> dict[str, str]:
    out = {}
    for name in BACKEND_PACKAGES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def _device(backend: str) -> str:
    """Where ``backend`` ran: JAX's or Warp's default device, the CPU for MuJoCo C."""
    if backend == "mjx":
        import jax

        return str(jax.devices()[0].platform)
    if backend == "warp":
        import warp

        return str(warp.get_device().alias)
    return "cpu"


def environment() -> dict[str, Any]:
    """:func:`mjpoincare.core.stamp.environment` with the backends' package versions."""
    from mjpoincare.core.stamp import environment as base

    return {**base(), "backend_packages": _versions()}


def _key(record: dict[str, Any]) -> str:
    if record["kind"] == "scaling":
        return f"scaling-{record['scenario']}-{record['backend']}-{record['precision']}"
    if record["kind"] == "map":
        return f"map-{record['map']}-{record['backend']}-{record['precision']}"
    perturbed = f"-p{record['start_perturbation']:g}" if record.get("start_perturbation") else ""
    return f"{record['scenario']}-{record['preset']}-{record['backend']}-{record['precision']}{perturbed}"


def run(scenario: str, backend: str, precision: str, preset: str, batch: int = 0, perturbation: float = 0.0
        ) -> dict[str, Any]:
    """One validation of ``scenario`` at ``preset`` on ``backend`` in ``precision`` (``batch``, ``perturbation``:
    the settings ``batch`` and ``start_perturbation``): the result with the wall and compile seconds and the device,
    or the one-line refusal."""
    from mjpoincare.commands.validation import run_validation

    head = {"kind": "validate", "scenario": scenario, "preset": preset, "backend": backend, "precision": precision,
            "batch": batch, "start_perturbation": perturbation, "environment": environment()}
    start = time.perf_counter()
    try:
        result = run_validation(scenario, {"backend": backend, "precision": precision, "batch": batch,
                                           "start_perturbation": perturbation}, preset)
    except ParameterError as refusal:
        return {**head, "refused": str(refusal)}
    kept = {k: v for k, v in result.to_dict().items() if k in RESULT_FIELDS}
    return {**head, "wall_s": time.perf_counter() - start, "compile_s": result.timing["compile_s"],
            "device": _device(backend), **kept}


def run_map(which: str, backend: str, precision: str, size: int, batch: int, out: Path) -> dict[str, Any]:
    """The friction wheel's basin map (``which`` = ``basins``, a ``size`` x ``size`` grid) or mu sweep (``mu``,
    ``size`` values) on ``backend``, through ``mjpoincare sweep`` in a process of its own, rollouts of ``batch``
    trajectories: its exit code, wall seconds and what it measured."""
    head = {"kind": "map", "map": which, "backend": backend, "precision": precision, "batch": batch, "size": size,
            "environment": environment()}
    raw = out / "maps" / f"{which}-{backend}-{precision}.json"
    settings = ["--set", f"backend={backend}", "--set", f"precision={precision}", "--set", f"batch={batch}"]
    if which == "basins":
        args = ["--grid", MAP_AXES.format(n=size), "-o", str(raw.with_suffix(".png"))]
    else:
        args = ["--param", "mu", "--values", MU_RANGE.format(count=size)]
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "mjpoincare.cli", "sweep", "rimless-wheel-friction", *args,
                           *settings, "--json", str(raw), "--workers", "1"], capture_output=True, text=True)
    head.update(exit_code=done.returncode, wall_s=time.perf_counter() - start, output=done.stdout[-2000:])
    if done.returncode not in (0, 1):
        return {**head, "failed": done.stderr.strip().splitlines()[-1:] or ["no output"]}
    payload = json.loads(raw.read_text())
    if which == "basins":
        return {**head, "starts": int(size * size), "region_disagreement": payload["region_disagreement"],
                "type_disagreement": payload["type_disagreement"], "diverged": payload["diverged"],
                "steps": payload["steps"], "rollout_wall_s": payload["rollout_wall_s"]}
    summary = payload["summary"]
    errors = [e for e in summary["max_eigenvalue_error_per_type"].values() if e == e]  # NaN: no gait of that type
    return {**head, "starts": len(payload["rows"]), "agreement": summary["agreement"],
            "agreement_without_d_plus": summary["agreement_without_d_plus"],
            "max_eigenvalue_error": max(errors, default=None)}


#: The scenario whose model and starts the batch-size scaling of ``all --scaling`` times.
SCALING_SCENARIO = "rimless-wheel"


def _jobs(scenarios: Sequence[str], presets: Sequence[str], batch: int, maps: int, scaling: Sequence[int]
          ) -> list[tuple[str, list[str]]]:
    """Every run, as (the name of its record, the arguments of its ``findings`` process)."""
    jobs = []
    for preset in presets:
        for s in scenarios:
            jobs += [(f"{s}-{preset}-{b}-{p}", ["run", s, b, p, "--preset", preset, "--batch", str(batch)])
                     for b, p in COLUMNS]
            jobs += [(f"{s}-{preset}-mujoco-float64-p{x:g}", ["run", s, "mujoco", "float64", "--preset", preset,
                                                             "--start-perturbation", str(x)]) for x in PERTURBATIONS]
    if maps:
        jobs += [(f"map-{which}-{b}-{p}", ["map", which, b, p, "--size", str(maps), "--batch", str(batch)])
                 for which in ("basins", "mu") for b, p in COLUMNS]
    if scaling:
        jobs += [(f"scaling-{SCALING_SCENARIO}-{b}-{p}", ["scaling", SCALING_SCENARIO, b, p, "--sizes",
                                                          *map(str, scaling)]) for b, p in COLUMNS]
    return jobs


def run_all(scenarios: Sequence[str], presets: Sequence[str], batch: int, maps: int, out: Path, *,
            scaling: Sequence[int] = (), workers: int = 1, again: bool = False) -> list[Path]:
    """Every (scenario, preset, backend) validation with MuJoCo C's perturbed runs, when ``maps`` > 0 both maps at
    that size on every backend, and when ``scaling`` gives batch sizes the batch-size scaling of every backend, each
    in a process of its own (``workers`` at a time), skipping those already in ``out/json/`` unless ``again``; then
    the page. Returns the files written."""
    commands = [[sys.executable, "-m", "mjpoincare.pages.backend_findings", *extra, "--out", str(out)]
                for name, extra in _jobs(scenarios, presets, batch, maps, scaling)
                if again or not (out / "json" / f"{name}.json").exists()]
    running: list[subprocess.Popen[bytes]] = []
    for command in commands:
        while len(running) >= workers:  # a slot frees when any run ends, not only the oldest
            time.sleep(0.5)
            running = [p for p in running if p.poll() is None]
        print(" ".join(command[3:]), flush=True)
        running.append(subprocess.Popen(command))
    for process in running:
        process.wait()
    page = out / "README.md"
    write_text(render(load(out)), str(page))
    return [page]


def main(argv: Sequence[str] | None = None) -> int:
    from mjpoincare import scenarios

    parser = argparse.ArgumentParser(prog="python -m mjpoincare.pages.backend_findings",
                                     description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    every = sub.add_parser("all", help="every scenario x preset x backend (and --maps) not yet in OUT/json, then "
                           "the page")
    every.add_argument("--scenarios", nargs="*", default=list(scenarios.REGISTRY))
    every.add_argument("--presets", nargs="*", default=["fast"])
    every.add_argument("--maps", type=int, default=0, help="the maps' size N (N x N grid, N mu values); 0: none")
    every.add_argument("--scaling", type=int, nargs="*", default=[],
                       help=f"batch sizes to time {SCALING_SCENARIO}'s batched step at on every backend")
    every.add_argument("--workers", type=int, default=1)
    every.add_argument("--again", action="store_true", help="run again what OUT/json already holds")
    one = sub.add_parser("run", help="validate one scenario on one backend, write its record into OUT/json")
    one.add_argument("scenario")
    one.add_argument("backend", choices=sorted({b for b, _ in COLUMNS}))
    one.add_argument("precision", choices=("float64", "float32"))
    one.add_argument("--preset", default="fast")
    one.add_argument("--start-perturbation", type=float, default=0.0, help="the start_perturbation setting")
    area = sub.add_parser("map", help="one map (basins or mu) on one backend, write its record into OUT/json")
    area.add_argument("which", choices=("basins", "mu"))
    area.add_argument("backend", choices=sorted({b for b, _ in COLUMNS}))
    area.add_argument("precision", choices=("float64", "float32"))
    area.add_argument("--size", type=int, required=True)
    for p in (every, one, area):
        p.add_argument("--batch", type=int, default=0, help="the batch setting (0: the scenarios' own)")
        p.add_argument("--out", type=Path, required=True)
    scale = sub.add_parser("scaling", help="seconds per batched step against the batch size, into OUT/json")
    scale.add_argument("scenario")
    scale.add_argument("backend", choices=sorted({b for b, _ in COLUMNS}))
    scale.add_argument("precision", choices=("float64", "float32"))
    scale.add_argument("--sizes", type=int, nargs="+", required=True)
    scale.add_argument("--steps", type=int, default=500)
    scale.add_argument("--out", type=Path, required=True)
    show = sub.add_parser("render", help="write OUT/README.md again from OUT/json (no simulation)")
    show.add_argument("out", type=Path)
    args = parser.parse_args(argv)
    for name in ("batch", "maps", "workers", "steps", "size"):
        low = 1 if name in ("workers", "steps", "size") else 0
        if getattr(args, name, low) < low:
            parser.error(f"--{name} must be >= {low} (got {getattr(args, name)})")
    for name in ("sizes", "scaling"):
        if min(getattr(args, name, None) or [1]) < 1:
            parser.error(f"--{name} must be >= 1 (got {min(getattr(args, name))})")
    names = args.scenarios if args.command == "all" else [args.scenario] if args.command in ("run", "scaling") else []
    try:  # an unknown scenario is refused before any simulation
        for name in names:
            scenarios.get(name)
    except ParameterError as error:
        parser.error(str(error))
    if args.command == "all":
        for path in run_all(args.scenarios, args.presets, args.batch, args.maps, args.out, scaling=args.scaling,
                            workers=args.workers, again=args.again):
            print(f"wrote {path}")
        return 0
    if args.command == "render":
        write_text(render(load(args.out)), str(args.out / "README.md"))
        return 0
    if args.command == "scaling":
        from mjpoincare.pages.batch_scaling import measure

        record = {"kind": "scaling", "environment": environment(), "device": _device(args.backend),
                  **measure(args.scenario, args.backend, args.precision, args.sizes, args.steps)}
    elif args.command == "run":
        record = run(args.scenario, args.backend, args.precision, args.preset, args.batch, args.start_perturbation)
    else:
        (args.out / "maps").mkdir(parents=True, exist_ok=True)
        record = run_map(args.which, args.backend, args.precision, args.size, args.batch, args.out)
    path = args.out / "json" / f"{_key(record)}.json"
    write_json(record, str(path))
    print(f"wrote {path}" + (f" (refused: {record['refused']})" if "refused" in record else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
