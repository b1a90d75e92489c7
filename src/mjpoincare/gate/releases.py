"""``python -m mjpoincare.gate.releases``: the MuJoCo release history, generated, never typed.

Four steps, each a subcommand:

- ``discover``: ask the package index (:data:`INDEX`) which MuJoCo releases exist and keep, in
  ``releases/index.json``, the history's releases among them (:func:`history`: the oldest that ``pyproject.toml``
  admits, the newest patch of every minor line, and every patch of the newest line) with the date of the question.
- ``run``: in an environment with one MuJoCo release installed (the nox session ``release`` of ``noxfile.py``, uv as
  the installer), the default validation of every built-in scenario of the registry (:func:`history_scenarios`: the
  default scenarios and those left to their own command) at ``fast`` (and ``accurate`` on the oldest release of the
  history and those of its newest line), each run again under :data:`SPREAD` (seed, threads, start perturbations up
  to 1e-9); per check the value, the error and the spread (the largest change of the value under those
  perturbations) go to ``json/mujoco-<release>.json``, stamped with the environment, written whole after each
  scenario. A run resumes from the scenarios its file already holds when that file was run at the same commit, and
  starts the file again otherwise (one file, one version of the suite). A scenario whose seam self-test refuses the
  release is recorded as refused.
- ``matrix`` (``make releases``): ``discover``, then ``run`` for each release of the history whose file lacks a run
  (a new release, a new scenario, or a file of another commit), a few at a time.
- ``render``: ``docs/results/mujoco-releases.md`` from that JSON and the index file (a pure function of them and of
  the built-in scenarios, naming the releases and scenarios the runs lack; re-rendered byte for byte).
  Between consecutive releases run at the same commit, a change of a check's value is **real** (:func:`is_real`)
  when it exceeds both :data:`mjpoincare.core.allowance.MULTIPLE` (3) times the larger of the spreads measured on the
  two releases and the roundoff floor (:func:`roundoff_floor`: :data:`mjpoincare.core.allowance.ROUNDOFF`, 1e-12,
  of max(1, the larger magnitude of the two values)), and **jitter** otherwise; each real change names the first
  release where it appears. Between releases run at different commits a change is not MuJoCo's alone, and is
  marked so, never called real or jitter.
- ``bisect``: two releases and one check; the patch releases between them (from the package index) are run one at a
  time through the nox session ``release_point`` until the first release with a real change (the same rule) is found.
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import re
import subprocess
import sys
import urllib.request
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from mjpoincare.analysis.tables import markdown_table, table_cell
from mjpoincare.core.allowance import MULTIPLE, ROUNDOFF, floor
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import format_value, write_json, write_text
from mjpoincare.gate.forms import PERTURBATIONS

#: The oldest release ``pyproject.toml`` admits: ``MjSpec.delete``, which the models' builds use, first ships in 3.3.4.
OLDEST = "3.3.4"
#: Perturbations that must not change a result (label, seed, extra settings): the gate's (seed 1, one thread, the
#: starts scaled by 1 + 1e-12 and 1 + 1e-9).
SPREAD = PERTURBATIONS
#: Where ``make releases`` writes, relative to the repository root.
OUT = Path("docs/results/releases")
PAGE = Path("docs/results/mujoco-releases.md")
#: The package index's answer, under :data:`OUT`: the releases it listed, the history among them and the date.
INDEX_FILE = "index.json"
#: Where a bisection's runs of releases outside the history go.
BISECT_OUT = Path("renders/releases-bisect")
SCHEMA = 1
INDEX = "https://pypi.org/simple/mujoco/"
#: A final release's version: three numbers.
FINAL = re.compile(r"\d+\.\d+\.\d+")


def version_key(version: str) -> tuple[int, ...]:
    """``"3.10.0"`` -> ``(3, 10, 0)``, the order of releases."""
    return tuple(int(part) for part in version.split("."))


def history(versions: Iterable[str], oldest: str = OLDEST) -> list[str]:
    """The history's releases among ``versions`` (the package index's), oldest first: ``oldest``, the newest patch of
    every minor line from ``oldest``'s on, and every patch of the newest minor line (the releases a user upgrades
    from and to today). Pre-releases, development releases and older lines are left out."""
    finals = sorted((v for v in set(versions) if FINAL.fullmatch(v) and version_key(v) >= version_key(oldest)),
                    key=version_key)
    newest_of_line = {version_key(v)[:2]: v for v in finals}
    newest_line = [v for v in finals if version_key(v)[:2] == version_key(finals[-1])[:2]] if finals else []
    return sorted({oldest, *newest_of_line.values(), *newest_line}, key=version_key)


def accurate_on(releases: Sequence[str]) -> tuple[str, ...]:
    """The releases on which the accurate preset runs too: the history's oldest and those of its newest minor line."""
    newest = version_key(releases[-1])[:2]
    return releases[0], *(v for v in releases[1:] if version_key(v)[:2] == newest)


def discover(fetch: Callable[[], list[str]] | None = None) -> dict[str, Any]:
    """The package index's final MuJoCo releases (``fetch``, by default :data:`INDEX`) and the :func:`history` among
    them, with the date of the question."""
    from datetime import datetime, timezone

    versions = sorted((v for v in (fetch or _index_versions)() if FINAL.fullmatch(v)), key=version_key)
    if OLDEST not in versions:
        raise ParameterError(f"the package index {INDEX} does not list MuJoCo {OLDEST}, the oldest admitted")
    return {"schema": SCHEMA, "index": INDEX, "queried": datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "versions": versions, "history": history(versions)}


def load_index(out: Path = OUT) -> dict[str, Any]:
    """The last :func:`discover` answer kept under ``out`` (``make releases`` writes it)."""
    path = out / INDEX_FILE
    if not path.exists():
        raise ParameterError(f"{path} is missing: run make releases (it asks the package index for the releases)")
    return json.loads(path.read_text())


def lacking(index: dict[str, Any], payloads: Sequence[dict[str, Any]], sha: str | None) -> list[str]:
    """The history's releases whose runs the page lacks: no file, a file of another commit than ``sha`` (the
    checkout's), or a file without one of the runs :func:`run_release` would make."""
    held = {p["mujoco"]: p for p in payloads}
    wanted_scenarios = history_scenarios()
    out = []
    for release in index["history"]:
        payload = held.get(release)
        presets = ("fast", "accurate") if release in accurate_on(index["history"]) else ("fast",)
        if (payload is None or payload["environment"]["git_sha"] != sha
                or {(n, p) for n in wanted_scenarios for p in presets} - {(r["scenario"], r["preset"])
                                                                          for r in payload["runs"]}):
            out.append(release)
    return out


def _flat(value: Any) -> list[float] | str | None:
    """A JSON value as a flat list of numbers (complex values are [re, im] pairs), a string as itself, null as None."""
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, bool):
        return [float(value)]
    if isinstance(value, int | float):
        return [float(value)]
    out: list[float] = []
    for item in value:
        flat = _flat(item)
        if not isinstance(flat, list):
            return None if flat is None else str(value)
        out += flat
    return out


def distance(a: Any, b: Any) -> float:
    """How far apart two JSON values of one check are: the largest absolute difference of their numbers (0 or inf
    for labels and for values of different shapes; a missing number is inf away from a number)."""
    fa, fb = _flat(a), _flat(b)
    if fa is None and fb is None:
        return 0.0
    if isinstance(fa, list) and isinstance(fb, list) and len(fa) == len(fb):
        return max((abs(x - y) for x, y in zip(fa, fb, strict=True)), default=0.0)
    return 0.0 if fa == fb else math.inf


def roundoff_floor(a: Any, b: Any) -> float:
    """The smallest change between two values of one check that is not roundoff: :data:`ROUNDOFF` of max(1, the
    largest magnitude of their finite numbers) (:func:`mjpoincare.core.allowance.floor` without a tolerance)."""
    magnitudes = [abs(x) for value in (a, b) if isinstance(flat := _flat(value), list) for x in flat
                  if math.isfinite(x)]
    return floor(0.0, max(magnitudes, default=0.0))


def is_real(change: float, spread: float, floor: float) -> bool:
    """Whether a change of a check's value between two releases is real: beyond :data:`MULTIPLE` times ``spread``
    (the larger of the two releases' spreads; inf when one is unknown) and beyond ``floor``
    (:func:`roundoff_floor`)."""
    return change > MULTIPLE * spread and change > floor


def _check_rows(base: dict[str, Any], variants: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    rows = []
    for check in base["checks"]:
        others = [next((c for c in v["checks"] if c["name"] == check["name"]), None) for v in variants]
        spread = max((distance(check["simulated"], o["simulated"]) if o else math.inf for o in others), default=0.0)
        rows.append({"name": check["name"], "analytic": check["analytic"], "simulated": check["simulated"],
                     "error": check["error"], "error_kind": check["error_kind"], "tolerance": check["tolerance"],
                     "passed": check["passed"], "spread": spread if math.isfinite(spread) else None})
    return rows


def history_scenarios() -> list[str]:
    """The scenarios the history runs: every one the registry lists that this distribution declares (the default
    validation's and those left to their own command; a plugin's scenarios are its own to track)."""
    from mjpoincare.scenarios import REGISTRY

    return [name for name in REGISTRY if REGISTRY.distribution(name) == "mjpoincare"]


def run_scenario(name: str, preset: str) -> dict[str, Any]:
    """One scenario's default validation at ``preset`` on the loaded MuJoCo, with its :data:`SPREAD` runs: the
    verdict, the wall time and each check's value, error and spread; or the refusal of its seam self-test."""
    from mjpoincare.commands.validation import run_validation
    from mjpoincare.simulation.seam_check import MechanismFailed

    try:
        base = run_validation(name, {}, preset, 0)
    except MechanismFailed as refusal:
        return {"scenario": name, "preset": preset, "refused": str(refusal)}
    variants = [run_validation(name, extra, preset, seed).to_dict() for _, seed, extra in SPREAD]
    return {"scenario": name, "preset": preset, "refused": None, "passed": base.passed,
            "wall_s": base.timing["wall_s"], "warnings": base.warnings,
            "checks": _check_rows(base.to_dict(), variants)}


def run_release(out: Path, presets: Sequence[str] | None = None, names: Sequence[str] | None = None) -> Path:
    """The history's runs on the loaded MuJoCo into ``out/json/mujoco-<version>.json``, resuming from what that file
    holds when it was run at this commit and starting it again otherwise (a file from another MuJoCo or schema is
    refused); returns its path. ``presets`` default to ``fast``, and ``accurate`` too on the releases
    :func:`accurate_on` names in the history ``out``'s index file holds. The file's environment stamp is that of its
    latest run: a file to which nothing is added is left as it is."""
    import mujoco

    from mjpoincare import scenarios
    from mjpoincare.core.stamp import environment

    version = mujoco.__version__
    if not presets:
        index_path = out / INDEX_FILE
        ends = accurate_on(load_index(out)["history"]) if index_path.exists() else (OLDEST,)
        presets = ["fast", "accurate"] if version in ends else ["fast"]
    names = list(names or history_scenarios())
    for name in names:
        scenarios.get(name).preset(presets[0])
    path = out / "json" / f"mujoco-{version}.json"
    payload: dict[str, Any] = {"schema": SCHEMA, "mujoco": version, "environment": environment(), "runs": []}
    if path.exists():
        held = json.loads(path.read_text())
        if held.get("schema") != SCHEMA or held.get("mujoco") != version:
            raise ParameterError(f"--out: {path} holds another MuJoCo's or schema's runs; remove it to run again")
        if held["environment"]["git_sha"] == payload["environment"]["git_sha"]:
            payload["environment"], payload["runs"] = held["environment"], held["runs"]
        else:
            print(f"MuJoCo {version}: {path} was run at commit {str(held['environment']['git_sha'])[:12]}; "
                  "running every scenario again at this one", flush=True)
    done = {(r["scenario"], r["preset"]) for r in payload["runs"]}
    for preset in presets:
        for name in names:
            if (name, preset) in done:
                continue
            run = run_scenario(name, preset)
            print(f"MuJoCo {version} {name} [{preset}]: "
                  f"{run['refused'] or ('PASS' if run['passed'] else 'FAIL')}", flush=True)
            payload["runs"].append(run)
            payload["environment"] = environment()
            write_json(payload, str(path))
    if not path.exists():
        write_json(payload, str(path))
    return path


def load(out: Path = OUT) -> list[dict[str, Any]]:
    """Every release's payload under ``out/json``, oldest first."""
    payloads = [json.loads(p.read_text()) for p in (out / "json").glob("mujoco-*.json")]
    return sorted(payloads, key=lambda p: version_key(p["mujoco"]))


def changes(payloads: Sequence[dict[str, Any]], scenario: str, preset: str) -> list[dict[str, Any]]:
    """Between each pair of consecutive releases that ran ``scenario`` at ``preset``: per check, the change of its
    value, the larger of the two spreads, whether the two ran at the same commit (``same_commit``), and whether the
    change is real (:func:`is_real`: beyond :data:`MULTIPLE` times that spread and the roundoff floor; never across
    commits, where the suite changed too) or jitter."""
    runs = [(p["mujoco"], _commit(p), _run(p, scenario, preset)) for p in payloads]
    runs = [(v, sha, r) for v, sha, r in runs if r is not None and not r["refused"]]
    out = []
    for (before, sha_a, a), (after, sha_b, b) in itertools.pairwise(runs):
        checks_a = {c["name"]: c for c in a["checks"]}
        for check in b["checks"]:
            old = checks_a.get(check["name"])
            if old is None:
                continue
            change = distance(old["simulated"], check["simulated"])
            spreads = [s if s is not None else math.inf for s in (old["spread"], check["spread"])]
            spread = max(spreads)
            floor = roundoff_floor(old["simulated"], check["simulated"])
            same = sha_a == sha_b
            out.append({"check": check["name"], "from": before, "to": after, "change": change, "spread": spread,
                        "tolerance": check["tolerance"], "same_commit": same,
                        "real": same and is_real(change, spread, floor)})
    return out


def _commit(payload: dict[str, Any]) -> str:
    env = payload["environment"]
    return f"{env['git_sha']}{'+' if env['git_dirty'] else ''}"


def _run(payload: dict[str, Any], scenario: str, preset: str) -> dict[str, Any] | None:
    return next((r for r in payload["runs"] if r["scenario"] == scenario and r["preset"] == preset), None)


def _number(x: float | None, digits: int = 3) -> str:
    return "nan" if x is None else ("inf" if math.isinf(x) else f"{x:.{digits}g}")


def render(payloads: Sequence[dict[str, Any]], index: dict[str, Any]) -> str:
    """``docs/results/mujoco-releases.md`` from the releases' payloads, oldest first, and the package index's answer
    (:func:`discover`): a pure function of them and of the built-in scenarios (:func:`history_scenarios`), naming the
    releases of the history and the scenarios the payloads lack."""
    held = {r["scenario"] for p in payloads for r in p["runs"]}
    missing = [name for name in history_scenarios() if name not in held]
    ran = {p["mujoco"] for p in payloads}
    unrun = [v for v in index["history"] if v not in ran]
    commits = list(dict.fromkeys(_commit(p) for p in payloads))
    lines = ["<!-- generated by `make releases` (python -m mjpoincare.gate.releases render) from releases/json/: "
             "do not edit -->", "", "# MuJoCo release history", "",
             "The default validation of every built-in scenario on each release the suite admits (the oldest, then the "
             "newest patch of each minor line, and every patch of the newest line), at the `fast` preset, and at "
             "`accurate` on the oldest and the newest line. "
             "Each release ran in its own environment (`noxfile.py`, session `release`, uv as the installer). A "
             "check's **spread** is the largest change of its value under seed 1, one rollout thread and the starts "
             "scaled by 1 + 1e-12 and 1 + 1e-9 on that release. Between consecutive releases run at the same commit, "
             f"a change is **real** when it exceeds both {MULTIPLE:g} times the larger of the two spreads and the "
             f"roundoff floor, {ROUNDOFF:g} of max(1, the larger magnitude of the two values); **jitter** otherwise. "
             "Values are the simulated ones (complex numbers as [re, im]); errors are against the analytic values, of "
             "the kind the scenario pages state.", "",
             f"The releases were found, not typed: the package index ({index['index']}) listed "
             f"{len(index['versions'])} MuJoCo releases on {index['queried']}, from {index['versions'][0]} to "
             f"{index['versions'][-1]}; the history among them is {', '.join(index['history'])}.", ""]
    if unrun:
        lines += [f"Not run yet: MuJoCo {', '.join(unrun)} (`make releases` runs what the page lacks).", ""]
    if missing:
        lines += [f"Not in this history yet: {', '.join(missing)} (the runs predate the history running every "
                  "built-in scenario; `make releases` runs what each release's file lacks).", ""]
    if len(commits) > 1:
        lines += [f"The releases ran at {len(commits)} commits of the suite: a change between two releases run at "
                  "different commits is marked *other commit*, not real or jitter (the suite changed too).", ""]
    lines += ["## Releases", ""]
    releases = []
    for p in payloads:
        env = p["environment"]
        sha = (env["git_sha"] or "unknown")[:12] + ("+" if env["git_dirty"] else "")
        verdicts = ", ".join(f"{r['scenario']} {_verdict(r)}" for r in p["runs"] if r["preset"] == "fast")
        releases.append((p["mujoco"], f"{env['numpy']} / {env['scipy']} / {env['python']}", table_cell(verdicts),
                         sha, table_cell(env["cpu"]), env["date"]))
    lines += [markdown_table(("MuJoCo", "numpy / scipy / Python", "verdicts (fast)", "git commit", "CPU",
                              "date (UTC)"), releases),
              "", "A `+` after the commit: the run had uncommitted changes to tracked files.", ""]
    all_real: list[tuple[str, str, dict[str, Any]]] = []
    for preset in ("fast", "accurate"):
        names = list(dict.fromkeys(r["scenario"] for p in payloads for r in p["runs"] if r["preset"] == preset))
        for name in names:
            found = changes(payloads, name, preset)
            all_real += [(name, preset, c) for c in found if c["real"]]
            lines += _scenario_section(payloads, name, preset, found)
    lines += ["## Real changes", "",
              f"Every real change (beyond {MULTIPLE:g} spreads and the roundoff floor), with the first release where "
              "it appears (`python -m mjpoincare.gate.releases bisect` finds the patch release within a minor line). "
              "Real is not large: the last column is the change against the check's tolerance.", ""]
    if all_real:
        rows = []
        for name, preset, c in all_real:
            ratio = c["change"] / c["spread"] if c["spread"] > 0 else math.inf
            to_tol = c["change"] / c["tolerance"] if c["tolerance"] > 0 else math.inf
            rows.append((name, preset, c["check"], c["to"], c["from"], _number(c["change"]), _number(c["spread"]),
                         _number(ratio), _number(to_tol)))
        lines.append(markdown_table(("scenario", "preset", "check", "first in", "after", "change", "spread",
                                     "change / spread", "change / tolerance"), rows))
    else:
        lines.append("None.")
    lines.append("")
    return "\n".join(lines)


def _verdict(run: dict[str, Any]) -> str:
    if run["refused"]:
        return "refused"
    return f"{'PASS' if run['passed'] else 'FAIL'} {sum(c['passed'] for c in run['checks'])}/{len(run['checks'])}"


def _scenario_section(payloads: Sequence[dict[str, Any]], name: str, preset: str, found: list[dict[str, Any]]
                      ) -> list[str]:
    runs = [(p["mujoco"], _run(p, name, preset)) for p in payloads]
    runs = [(v, r) for v, r in runs if r is not None]
    checks = list(dict.fromkeys(c["name"] for _, r in runs if not r["refused"] for c in r["checks"]))
    flag = {(c["to"], c["check"]): c for c in found}
    lines = [f"## {name} [{preset}]", "",
             "Each cell: the simulated value, then `err` the error (`FAIL` when beyond the tolerance), `±` the spread "
             "on that release, and **real**, jitter or identical (bit for bit) for the change from the release "
             "above (*other commit* when the two ran at different commits of the suite).", ""]
    rows: list[tuple[str | None, ...]] = []
    for version, run in runs:
        if run["refused"]:
            rows.append((version, f"refused: {table_cell(run['refused'])}", *[None] * len(checks)))
            continue
        by_name = {c["name"]: c for c in run["checks"]}
        cells = []
        for check in checks:
            c = by_name.get(check)
            if c is None:
                cells.append("not available")
                continue
            change = flag.get((version, check))
            mark = ("" if change is None else " **real**" if change["real"]
                    else " identical" if change["change"] == 0
                    else " jitter" if change["same_commit"] else " other commit")
            fail = "" if c["passed"] else " FAIL"
            cells.append(f"{format_value(c['simulated'], from_json=True)}<br>err {_number(c['error'])}{fail} "
                         f"±{_number(c['spread'], 2)}{mark}")
        rows.append((version, _verdict(run), *(table_cell(x) for x in cells)))
    lines.append(markdown_table(("MuJoCo", "verdict", *checks), rows))
    tolerances = {c["name"]: c["tolerance"] for _, r in runs if not r["refused"] for c in r["checks"]}
    lines += ["", "Tolerances: " + ", ".join(f"{k} {_number(v)}" for k, v in tolerances.items()) + ".", ""]
    return lines


def patch_releases(low: str, high: str, fetch: Callable[[], list[str]] | None = None) -> list[str]:
    """The MuJoCo releases on the package index after ``low`` up to and including ``high``, oldest first."""
    versions = (fetch or _index_versions)()
    return sorted((v for v in versions if version_key(low) < version_key(v) <= version_key(high)), key=version_key)


def _index_versions() -> list[str]:
    request = urllib.request.Request(INDEX, headers={"Accept": "application/vnd.pypi.simple.v1+json"})
    with urllib.request.urlopen(request, timeout=60) as response:
        versions = json.load(response)["versions"]
    return [v for v in versions if all(part.isdigit() for part in v.split("."))]


def bisect(low: str, high: str, scenario: str, preset: str, check: str,
           value_at: Callable[[str], tuple[Any, float]]) -> dict[str, Any]:
    """The first release after ``low`` up to ``high`` whose value of ``check`` really differs from ``low``'s
    (:func:`is_real`: beyond :data:`MULTIPLE` times the larger spread and the roundoff floor); ``value_at(release) ->
    (value, spread)`` runs it. Assumes one change between them (a bisection)."""
    candidates = patch_releases(low, high)
    if not candidates or candidates[-1] != high:
        raise ParameterError(f"bisect: {high} is not a release after {low} on the package index")
    base, base_spread = value_at(low)
    probed = {low: (base, base_spread)}

    def changed(release: str) -> bool:
        value, spread = probed.setdefault(release, value_at(release))
        return is_real(distance(base, value), max(base_spread, spread), roundoff_floor(base, value))

    if not changed(high):
        return {"scenario": scenario, "preset": preset, "check": check, "low": low, "high": high, "first": None,
                "probed": {k: list(v) for k, v in probed.items()}}
    lo, hi = -1, len(candidates) - 1  # candidates[hi] changed; candidates[lo] (or low itself) did not
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if changed(candidates[mid]):
            hi = mid
        else:
            lo = mid
    return {"scenario": scenario, "preset": preset, "check": check, "low": low, "high": high,
            "first": candidates[hi], "probed": {k: list(v) for k, v in probed.items()}}


def _nox_point(out: Path, scenario: str, preset: str, check: str) -> Callable[[str], tuple[Any, float]]:
    """``value_at`` for :func:`bisect`: a release's run from the history (:data:`OUT`) when it holds the scenario at
    ``preset``, else from ``out`` or through the nox session ``release_point`` into ``out``."""

    def held(release: str) -> dict[str, Any] | None:
        for folder in (OUT, out):
            path = folder / "json" / f"mujoco-{release}.json"
            if path.exists():
                payload = json.loads(path.read_text())
                run = _run(payload, scenario, preset)
                if run is not None:
                    return run
        return None

    def value_at(release: str) -> tuple[Any, float]:
        run = held(release)
        if run is None:
            subprocess.run([sys.executable, "-m", "nox", "-s", "release_point", "--", release, "--out", str(out),
                            "--scenario", scenario, "--preset", preset], check=True)
            run = held(release)
        if run is None or run["refused"]:
            raise ParameterError(f"bisect: MuJoCo {release} refused {scenario}: {run and run['refused']}")
        found = next((c for c in run["checks"] if c["name"] == check), None)
        if found is None:
            raise ParameterError(f"--check: {scenario} has no check {check!r} on MuJoCo {release}")
        return found["simulated"], found["spread"] if found["spread"] is not None else math.inf

    return value_at


def run_matrix(workers: int, logs: Path, out: Path = OUT) -> tuple[list[str], list[str]]:
    """Ask the package index for the releases (:func:`discover`, kept in ``out``'s index file), then run the nox
    session ``release`` (``noxfile.py``: a uv venv per release running ``run``) of every release whose runs the page
    lacks (:func:`lacking`), ``workers`` at a time, with a progress bar; each session's output goes to
    ``logs/<release>.log``. Returns the releases run and those whose session failed."""
    from concurrent.futures import ThreadPoolExecutor

    from mjpoincare.core import progress
    from mjpoincare.core.stamp import git_state

    if workers < 1:
        raise ParameterError(f"--workers must be >= 1 (got {workers})")
    index = discover()
    write_json(index, str(out / INDEX_FILE))
    todo = lacking(index, load(out), git_state()[0])
    logs.mkdir(parents=True, exist_ok=True)
    nox = Path(sys.executable).parent / "nox"
    ends = accurate_on(index["history"])

    def session(release: str) -> int:
        presets = ["fast", "accurate"] if release in ends else ["fast"]
        args = [arg for preset in presets for arg in ("--preset", preset)]
        with (logs / f"{release}.log").open("w") as log:
            return subprocess.run([str(nox), "-s", f"release(mujoco='{release}')", "--", "--out", str(out), *args],
                                  stdout=log, stderr=subprocess.STDOUT, check=False).returncode

    failed = []
    with progress.bar(len(todo), "MuJoCo releases", unit="release") as bar, \
            ThreadPoolExecutor(max_workers=workers) as pool:
        for release, code in zip(todo, pool.map(session, todo), strict=True):
            if code:
                failed.append(release)
            bar.set_postfix_str(f"{release}: {'failed' if code else 'done'}")
            bar.update(1)
    return todo, failed


def main(argv: Sequence[str] | None = None) -> int:
    """``run`` | ``render`` | ``matrix`` | ``bisect``; exit 2 with one line on bad input."""
    parser = argparse.ArgumentParser(prog="python -m mjpoincare.gate.releases", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="the history's runs on the loaded MuJoCo into OUT/json/")
    run.add_argument("--out", type=Path, default=OUT)
    run.add_argument("--preset", action="append", help="presets (default: fast; + accurate on the oldest and newest)")
    run.add_argument("--scenario", action="append", help="scenarios (default: every built-in scenario of the registry)")
    render_cmd = sub.add_parser("render", help="docs/results/mujoco-releases.md from OUT/json/")
    render_cmd.add_argument("--out", type=Path, default=OUT)
    render_cmd.add_argument("--page", type=Path, default=PAGE)
    found = sub.add_parser("discover", help="ask the package index for the releases; keep the history in OUT")
    found.add_argument("--out", type=Path, default=OUT)
    matrix = sub.add_parser("matrix", help="discover, then the nox session of each release the page lacks, WORKERS at "
                                           "a time (make releases)")
    matrix.add_argument("--workers", type=int, default=2)
    matrix.add_argument("--logs", type=Path, default=Path("renders/releases"), help="one log per session")
    matrix.add_argument("--out", type=Path, default=OUT)
    bis = sub.add_parser("bisect", help="the first patch release between two releases where a check really changes")
    bis.add_argument("low")
    bis.add_argument("high")
    bis.add_argument("--check", required=True, help="SCENARIO/CHECK, e.g. rimless-wheel/eigenvalue")
    bis.add_argument("--preset", default="fast")
    bis.add_argument("--out", type=Path, default=BISECT_OUT, help="where runs outside the history go")
    bis.add_argument("--json", help="write the bisection's result here")
    args = parser.parse_args(argv)
    try:
        if args.command == "run":
            print(f"wrote {run_release(args.out, args.preset, args.scenario)}")
        elif args.command == "render":
            write_text(render(load(args.out), load_index(args.out)), str(args.page))
            print(f"wrote {args.page}")
        elif args.command == "discover":
            index = discover()
            write_json(index, str(args.out / INDEX_FILE))
            print(f"the package index lists {len(index['versions'])} MuJoCo releases; the history: "
                  f"{', '.join(index['history'])}")
        elif args.command == "matrix":
            ran, failed = run_matrix(args.workers, args.logs, args.out)
            print(f"ran MuJoCo {', '.join(ran) or 'none (the page lacks no run)'}")
            if failed:
                print(f"python -m mjpoincare.gate.releases: sessions failed: {', '.join(failed)} (logs in {args.logs})",
                      file=sys.stderr)
                return 1
        else:
            return _cmd_bisect(args)
    except ParameterError as err:
        print(f"python -m mjpoincare.gate.releases: error: {err}", file=sys.stderr)
        return 2
    return 0


def _cmd_bisect(args: argparse.Namespace) -> int:
    from mjpoincare import scenarios

    scenario, _, check = args.check.partition("/")
    scenarios.get(scenario).preset(args.preset)
    if not check:
        raise ParameterError(f"--check must be SCENARIO/CHECK (got {args.check!r})")
    if version_key(args.low) >= version_key(args.high):
        raise ParameterError(f"bisect: {args.low} must be older than {args.high}")
    value_at = _nox_point(args.out, scenario, args.preset, check)
    result = bisect(args.low, args.high, scenario, args.preset, check, value_at)
    print(f"{args.check} [{args.preset}]: first real change after {args.low} in {result['first'] or 'none'} "
          f"(probed {', '.join(result['probed'])})")
    if args.json:
        write_json(result, args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
