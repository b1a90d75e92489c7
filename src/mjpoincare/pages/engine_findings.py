"""The engines' findings: the wheels' default checks on MuJoCo C beside Drake's ``MultibodyPlant`` (the scenario's own
model translated, :mod:`mjpoincare.engines.backends.drake_plant`) under each of Drake's discrete contact approximations,
with the errors against the exact values, wall seconds and steps per second. Every tolerance is MuJoCo's: a page of
findings, not a ranking of engines.

``python -m mjpoincare.pages.engine_findings all --out DIR`` runs every case x preset x engine not yet in
``DIR/json/`` (``--workers`` at a time; resumable), then writes ``DIR/README.md`` from the JSON; ``... render DIR``
writes the page again from the JSON (no simulation). ``make engines`` writes ``docs/results/engines/`` this way.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Mapping, Sequence
from importlib import metadata
from pathlib import Path
from typing import Any

from mjpoincare.core.parallel import run_jobs
from mjpoincare.core.params import ParameterError, Value
from mjpoincare.core.result import write_json, write_text
from mjpoincare.pages.engine_findings_page import load, render

#: The engines, each as the settings that select it.
ENGINES: dict[str, Mapping[str, Value]] = {
    "mujoco": {},
    "drake-sap": {"backend": "drake", "drake_approximation": "sap"},
    "drake-tamsi": {"backend": "drake", "drake_approximation": "tamsi"},
    "drake-lagged": {"backend": "drake", "drake_approximation": "lagged"},
    "drake-similar": {"backend": "drake", "drake_approximation": "similar"},
    "drake-sap-hydroelastic": {"backend": "drake", "drake_approximation": "sap", "drake_contact": "hydroelastic"},
}
#: The cases: a scenario the Drake backend can run (the others need a mechanism it lacks: docs/engines.md) and its
#: ``--set`` values, by label. The planar wheel also with a hub of radius of gyration 0.3 leg lengths (its default
#: hub is nearly a point mass, kappa = 1e-4, which decides how its impact goes on each engine).
CASES: dict[str, tuple[str, Mapping[str, str]]] = {
    "rimless-wheel": ("rimless-wheel", {}),
    "rimless-wheel[gyration=0.3]": ("rimless-wheel", {"gyration": "0.3"}),
    "rimless-wheel-friction": ("rimless-wheel-friction", {}),
    "rimless-wheel-3d": ("rimless-wheel-3d", {}),
}
#: The engines at the accurate preset (its planar wheel takes 40 times the fast preset's steps: Drake's
#: approximations other than SAP are compared at the fast preset only).
ACCURATE_ENGINES = ("mujoco", "drake-sap")
#: Hydroelastic contact runs where the finding is made (the planar wheel's 0.1 mm feet, at the fast preset).
HYDROELASTIC_CASES = ("rimless-wheel",)
#: The result fields a record keeps (the checks, timing, divergence, warnings and the reported extras).
RESULT_FIELDS = ("passed", "settings", "mujoco_version", "checks", "timing", "warnings", "diverged_trajectories",
                 "reported")


def environment() -> dict[str, Any]:
    """:func:`mjpoincare.core.stamp.environment` with Drake's version."""
    from mjpoincare.core.stamp import environment as base

    try:
        drake = metadata.version("drake")
    except metadata.PackageNotFoundError:
        drake = "not installed"
    return {**base(), "drake": drake}


def run_one(case: str, preset: str, engine: str, out: str) -> str:
    """Validate ``case`` at ``preset`` on ``engine`` and write its record (the result, or the one-line refusal) to
    ``out/json/``; the path written."""
    from mjpoincare.commands.validation import run_validation

    scenario, assignments = CASES[case]
    record: dict[str, Any] = {"case": case, "scenario": scenario, "assignments": dict(assignments), "preset": preset,
                              "engine": engine, "environment": environment()}
    start = time.perf_counter()
    try:
        result = run_validation(scenario, {**assignments, **ENGINES[engine]}, preset)
    except ParameterError as refusal:
        record["refused"] = str(refusal)
    else:
        record.update({k: v for k, v in result.to_dict().items() if k in RESULT_FIELDS},
                      wall_s=time.perf_counter() - start)
    path = Path(out) / "json" / f"{case}-{preset}-{engine}.json"
    write_json(record, str(path))
    return str(path)


def planned(cases: Sequence[str], presets: Sequence[str], engines: Sequence[str]) -> list[tuple[str, str, str]]:
    """The (case, preset, engine) runs of the page: every engine at the fast preset, :data:`ACCURATE_ENGINES` at the
    accurate one, hydroelastic contact at the fast preset of :data:`HYDROELASTIC_CASES` only."""
    return [(c, p, e) for c in cases for p in presets for e in engines
            if (p == "fast" or e in ACCURATE_ENGINES)
            and (not e.endswith("hydroelastic") or (p == "fast" and c in HYDROELASTIC_CASES))]


def run_all(cases: Sequence[str], presets: Sequence[str], engines: Sequence[str], out: Path, *,
            workers: int = 1, again: bool = False) -> Path:
    """Every (case, preset, engine) run not yet in ``out/json/`` (all of them with ``again``), ``workers`` at a time,
    then the page; the page's path."""
    jobs = [(c, p, e, str(out)) for c, p, e in planned(cases, presets, engines)
            if again or not (out / "json" / f"{c}-{p}-{e}.json").exists()]
    for path in run_jobs(run_one, jobs, workers=workers):
        print(f"wrote {path}", flush=True)
    page = out / "README.md"
    write_text(render(load(out)), str(page))
    return page


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m mjpoincare.pages.engine_findings",
                                     description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    every = sub.add_parser("all", help="every case x preset x engine not yet in OUT/json, then the page")
    every.add_argument("--cases", nargs="*", choices=list(CASES), default=list(CASES))
    every.add_argument("--presets", nargs="*", choices=("fast", "accurate"), default=["fast", "accurate"])
    every.add_argument("--engines", nargs="*", choices=list(ENGINES), default=list(ENGINES))
    every.add_argument("--workers", type=int, default=1)
    every.add_argument("--again", action="store_true", help="run again what OUT/json already holds")
    every.add_argument("--out", type=Path, required=True)
    show = sub.add_parser("render", help="write OUT/README.md again from OUT/json (no simulation)")
    show.add_argument("out", type=Path)
    args = parser.parse_args(argv)
    if args.command == "render":
        write_text(render(load(args.out)), str(args.out / "README.md"))
        return 0
    if args.workers < 1:
        parser.error(f"--workers must be >= 1 (got {args.workers})")
    page = run_all(args.cases, args.presets, args.engines, args.out, workers=args.workers, again=args.again)
    print(f"wrote {page}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
