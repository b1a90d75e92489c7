"""The backends' findings table: each scenario's default checks on MuJoCo C, MJX (x64 and float32) and MuJoCo Warp,
with compile time and steps per second.

``python -m mjpoincare.backends.findings run SCENARIO BACKEND PRECISION --preset P --out DIR`` validates one
scenario on one backend and writes ``DIR/SCENARIO-P-BACKEND-PRECISION.json`` (the result, the backend's compile
seconds, or the one-line refusal); ``python -m mjpoincare.backends.findings table DIR`` prints the markdown table of
every run in ``DIR``. One process per run, so that each compile time is a first compile.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mjpoincare.params import ParameterError

#: The columns of the table, in order: (backend, precision).
COLUMNS = (("mujoco", "float64"), ("mjx", "float64"), ("mjx", "float32"), ("warp", "float32"))


def run(scenario: str, backend: str, precision: str, preset: str) -> dict[str, Any]:
    """One validation of ``scenario`` at ``preset`` on ``backend`` in ``precision``: the result's checks and timing
    with the backend's compile seconds, or the refusal."""
    from mjpoincare.validation import run_validation

    start = time.perf_counter()
    try:
        result = run_validation(scenario, {"backend": backend, "precision": precision}, preset)
    except ParameterError as refusal:
        return {"scenario": scenario, "preset": preset, "backend": backend, "precision": precision,
                "refused": str(refusal)}
    return {"scenario": scenario, "preset": preset, "backend": backend, "precision": precision,
            "wall_s": time.perf_counter() - start, "compile_s": result.timing["compile_s"], **result.to_dict()}


def _error(check: dict[str, Any] | None) -> str:
    if check is None:
        return ""
    mark = "" if check["passed"] else " ✗"
    return f"{check['error']:.3g}{mark}"


def table(runs: Sequence[dict[str, Any]]) -> str:
    """Markdown: per scenario and preset, each check's error on every backend (✗: over its tolerance), then the
    compile seconds and the steps per second spent stepping; a refused run shows its reason."""
    heads = [f"{b} {p}" for b, p in COLUMNS]
    lines = ["| scenario | preset | check | tolerance | " + " | ".join(heads) + " |",
             "|---|---|---|---|" + "---|" * len(heads)]
    keyed = {(r["scenario"], r["preset"], r["backend"], r["precision"]): r for r in runs}
    for scenario, preset in sorted({(r["scenario"], r["preset"]) for r in runs}):
        row_runs = [keyed.get((scenario, preset, b, p)) for b, p in COLUMNS]
        names: list[str] = []
        for r in row_runs:
            for c in (r or {}).get("checks", []):
                if c["name"] not in names:
                    names.append(c["name"])
        by_name = [{c["name"]: c for c in (r or {}).get("checks", [])} for r in row_runs]
        for name in names:
            tolerance = next(b[name]["tolerance"] for b in by_name if name in b)
            cells = [_error(b.get(name)) if r and "refused" not in r else "" for r, b in zip(row_runs, by_name,
                                                                                               strict=True)]
            lines.append(f"| {scenario} | {preset} | {name} | {tolerance:.3g} | " + " | ".join(cells) + " |")
        lines.append(f"| {scenario} | {preset} | compile s | | " + " | ".join(
            "refused: " + r["refused"] if r and "refused" in r else (f"{r['compile_s']:.3g}" if r else "not run")
            for r in row_runs) + " |")
        lines.append(f"| {scenario} | {preset} | steps/s (stepping) | | " + " | ".join(
            f"{r['timing']['rollout_steps_per_s']:.3g}" if r and "timing" in r else "" for r in row_runs) + " |")
        lines.append(f"| {scenario} | {preset} | wall s | | " + " | ".join(
            f"{r['wall_s']:.3g}" if r and "wall_s" in r else "" for r in row_runs) + " |")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m mjpoincare.backends.findings", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    one = sub.add_parser("run", help="validate one scenario on one backend, write its JSON into --out")
    one.add_argument("scenario")
    one.add_argument("backend")
    one.add_argument("precision")
    one.add_argument("--preset", default="fast")
    one.add_argument("--out", required=True)
    show = sub.add_parser("table", help="print the markdown table of the runs in a directory")
    show.add_argument("directory")
    args = parser.parse_args(argv)
    if args.command == "run":
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        record = run(args.scenario, args.backend, args.precision, args.preset)
        path = out / f"{args.scenario}-{args.preset}-{args.backend}-{args.precision}.json"
        path.write_text(json.dumps(record, indent=1))
        print(f"wrote {path}" + (f" (refused: {record['refused']})" if "refused" in record else ""))
        return 0
    runs = [json.loads(p.read_text()) for p in sorted(Path(args.directory).glob("*.json"))]
    print(table(runs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
