"""The MuJoCo release history: the range pyproject.toml admits is the history's, the committed page re-renders byte
for byte from its JSON and covers every minor line, a change is real only beyond three spreads and roundoff (the
page's real changes recomputed from the JSON's raw values), and a bisection finds the first patch release of a
change (on a synthetic index: no simulation here)."""

from __future__ import annotations

import importlib.util
import itertools
import json
import math
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from mjpoincare import scenarios
from mjpoincare.core import allowance, stamp
from mjpoincare.core.params import ParameterError
from mjpoincare.gate import releases

ROOT = Path(__file__).resolve().parent.parent
PAYLOADS = releases.load(ROOT / releases.OUT)
INDEX = releases.load_index(ROOT / releases.OUT)
#: The rule the page states, written out again: a change is real beyond MULTIPLE times the larger spread and beyond
#: ROUNDOFF of max(1, the larger magnitude of the two values).
MULTIPLE, ROUNDOFF = 3.0, 1e-12


def test_the_range_pyproject_admits_starts_at_the_oldest_release_of_the_history() -> None:
    pin = re.search(r'^\s*"mujoco>=([\d.]+),<5",', (ROOT / "pyproject.toml").read_text(), re.M)
    assert pin is not None and pin.group(1) == releases.OLDEST
    assert INDEX["history"][0] == releases.OLDEST and INDEX["history"] == releases.history(INDEX["versions"])


def test_the_history_is_found_on_the_index_not_typed() -> None:
    """The oldest admitted, the newest patch of every minor line, every patch of the newest line; no pre-release."""
    index = ["3.3.3", "3.3.4", "3.3.5", "3.4.0rc1", "3.4.0", "3.4.1", "3.10.0", "4.0.0", "4.0.1", "4.1.0.dev1"]
    assert releases.history(index, "3.3.4") == ["3.3.4", "3.3.5", "3.4.1", "3.10.0", "4.0.0", "4.0.1"]
    assert releases.accurate_on(releases.history(index, "3.3.4")) == ("3.3.4", "4.0.0", "4.0.1")
    found = releases.discover(fetch=lambda: index)
    assert found["history"] == releases.history(index) and found["versions"][-1] == "4.0.1"
    with pytest.raises(ParameterError, match=r"does not list MuJoCo 3\.3\.4"):
        releases.discover(fetch=lambda: ["4.0.0"])
    # the committed answer: every minor line from the oldest's to the newest release's, each once but the newest's
    lines = [releases.version_key(v)[:2] for v in INDEX["history"][1:]]
    newest = lines[-1]
    assert len(set(lines)) == len(lines) - (lines.count(newest) - 1)
    assert set(lines) == {releases.version_key(v)[:2] for v in INDEX["versions"]
                          if releases.version_key(v) >= releases.version_key(releases.OLDEST)}


def test_the_readme_ci_example_lists_releases_of_the_history() -> None:
    matrix = re.search(r"matrix: \{mujoco: \[(.*?)\]\}", (ROOT / "README.md").read_text())
    assert matrix is not None
    listed = re.findall(r'"([\d.]+)"', matrix.group(1))
    assert listed and set(listed) <= set(INDEX["history"]) and releases.OLDEST in listed


def test_committed_page_reproduces_from_its_json_and_covers_the_history() -> None:
    page = ROOT / releases.PAGE
    assert page.read_text() == releases.render(PAYLOADS, INDEX), f"{page} is stale: run make releases-render"
    assert [p["mujoco"] for p in PAYLOADS] == INDEX["history"]
    built_in = releases.history_scenarios()
    held = {r["scenario"] for p in PAYLOADS for r in p["runs"]}
    assert set(scenarios.default_scenarios()) <= held <= set(built_in)
    if missing := [n for n in built_in if n not in held]:  # named on the page until make releases runs them
        assert f"Not in this history yet: {', '.join(missing)} " in page.read_text()
    for payload in PAYLOADS:
        presets = {"fast", "accurate"} if payload["mujoco"] in releases.accurate_on(INDEX["history"]) else {"fast"}
        ran = {(r["scenario"], r["preset"]) for r in payload["runs"]}
        assert ran == {(n, p) for n in held for p in presets}, payload["mujoco"]
        assert payload["environment"]["mujoco"] == payload["mujoco"]


@pytest.fixture(scope="module")
def noxfile() -> Any:
    """``noxfile.py`` as a module, loaded once (nox refuses a session registered twice)."""
    spec = importlib.util.spec_from_file_location("noxfile", ROOT / "noxfile.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(ROOT)
        spec.loader.exec_module(module)
    return module


def test_a_release_session_frees_every_package_that_follows_mujoco(tmp_path: Path, noxfile: Any,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    """mujoco 4 pins mujoco-core and mujoco-studio at its own version: a constraint left from the lock would make
    every other release uninstallable."""
    monkeypatch.chdir(ROOT)  # the session reads requirements/lock.txt from the working directory, as nox runs it
    installed: list[tuple[str, ...]] = []

    class Session:
        def create_tmp(self) -> str:
            return str(tmp_path)

        def install(self, *args: str) -> None:
            installed.append(args)

    noxfile._install(Session(), "4.0.1")
    kept = [line.split("==")[0].strip() for line in (tmp_path / "constraints.txt").read_text().splitlines()
            if "==" in line]
    assert kept and not [p for p in kept if p.startswith("mujoco") or p == "dm-control"]
    assert installed[-1][-1] == "mujoco==4.0.1"


def test_the_history_and_the_oldest_job_run_every_built_in_scenario(monkeypatch: pytest.MonkeyPatch,
                                                                    tmp_path: Path, noxfile: Any) -> None:
    """Not only the default validation's scenarios: the registry's, the biped with friction among them."""
    built_in = releases.history_scenarios()
    assert set(scenarios.default_scenarios()) | {"compass-biped-friction"} <= set(built_in)
    monkeypatch.chdir(ROOT)

    class Session:
        def __init__(self) -> None:
            self.runs: list[tuple[str, ...]] = []

        def create_tmp(self) -> str:
            return str(tmp_path)

        def install(self, *args: str) -> None:
            pass

        def chdir(self, path: str) -> None:
            pass

        def run(self, *args: str) -> None:
            self.runs.append(args)

    session = Session()
    noxfile.oldest(session)
    assert session.runs[-1] == ("mjpoincare", "validate", *built_in)


@pytest.mark.parametrize("payload", PAYLOADS, ids=[p["mujoco"] for p in PAYLOADS])
def test_every_admitted_release_passes_the_default_validation_or_refuses_with_the_mechanism(
        payload: dict[str, Any]) -> None:
    for run in payload["runs"]:
        if run["preset"] == "fast":
            assert run["refused"] is None, run["refused"]  # every release of the history has every mechanism
            failed = [c["name"] for c in run["checks"] if not c["passed"]]
            assert not failed, f"MuJoCo {payload['mujoco']} {run['scenario']}: {failed}"


@pytest.mark.parametrize(("a", "b", "expected"), [
    (0.5, 0.5001, 1e-4), ([1.0, [0.0, 2.0]], [1.0, [0.0, 2.5]], 0.5), ("B", "B", 0.0), ("B", "C", float("inf")),
    (None, None, 0.0), (None, 1.0, float("inf")), ([1.0, 2.0], [1.0], float("inf")), (3, 3, 0.0)])
def test_distance_of_check_values(a: Any, b: Any, expected: float) -> None:
    assert releases.distance(a, b) == pytest.approx(expected, rel=1e-9)


def _payload(version: str, value: float, spread: float, refused: str | None = None, sha: str = "abc"
             ) -> dict[str, Any]:
    env = {"mujoco": version, "numpy": "2", "scipy": "1", "python": "3.11", "cpu": "CPU", "git_sha": sha,
           "git_dirty": False, "date": "2026-01-01T00:00:00Z"}
    check = {"name": "eigenvalue", "analytic": 0.5, "simulated": value, "error": abs(value - 0.5),
             "error_kind": "absolute", "tolerance": 0.02, "passed": True, "spread": spread}
    run = ({"scenario": "toy", "preset": "fast", "refused": refused} if refused else
           {"scenario": "toy", "preset": "fast", "refused": None, "passed": True, "wall_s": 1.0, "warnings": [],
            "checks": [check]})
    return {"schema": releases.SCHEMA, "mujoco": version, "environment": env, "runs": [run]}


def _index(payloads: list[dict[str, Any]]) -> dict[str, Any]:
    versions = [p["mujoco"] for p in payloads]
    return {"index": releases.INDEX, "queried": "2026-01-01T00:00:00Z", "versions": versions, "history": versions}


def _change(a: Any, b: Any) -> tuple[float, float]:
    """The change of a check's value and its roundoff floor: the largest difference of their numbers (inf for labels
    that differ or another shape), and ROUNDOFF of max(1, the largest magnitude)."""
    def numbers(value: Any) -> list[Any]:
        return [x for item in value for x in numbers(item)] if isinstance(value, list) else [value]

    xa, xb = numbers(a), numbers(b)
    if len(xa) != len(xb) or not all(isinstance(x, int | float) for x in xa + xb):
        return (0.0 if xa == xb else math.inf), ROUNDOFF
    change = max((abs(x - y) for x, y in zip(xa, xb, strict=True)), default=0.0)
    return change, ROUNDOFF * max([1.0, *map(abs, xa + xb)])


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in re.split(r"(?<!\\)\|", line.strip())[1:-1]]


def test_the_pages_real_changes_are_those_the_raw_values_give() -> None:
    """Each verdict recomputed from the committed JSON's simulated values and spreads, apart from the renderer: the
    page's table of real changes and its **real** marks are exactly those."""
    expected = set()
    for scenario, preset in {(r["scenario"], r["preset"]) for p in PAYLOADS for r in p["runs"]}:
        runs = [(p["mujoco"], r) for p in PAYLOADS for r in p["runs"]
                if (r["scenario"], r["preset"]) == (scenario, preset) and not r["refused"]]
        for (before, a), (after, b) in itertools.pairwise(runs):
            old = {c["name"]: c for c in a["checks"]}
            for c in b["checks"]:
                if c["name"] in old:
                    change, floor = _change(old[c["name"]]["simulated"], c["simulated"])
                    spread = max(math.inf if s is None else s for s in (old[c["name"]]["spread"], c["spread"]))
                    if change > MULTIPLE * spread and change > floor:
                        expected.add((scenario, preset, c["name"], after, before))
    page = (ROOT / releases.PAGE).read_text()
    table = [_cells(line) for line in page.split("\n## Real changes\n")[1].splitlines() if line.startswith("| ")]
    listed = {tuple(row[:5]) for row in table[1:]}
    marked = set()
    for section in re.finditer(r"^## (\S+) \[(\w+)\]\n(.*?)(?=^## )", page, re.M | re.S):
        rows = [_cells(line) for line in section[3].splitlines() if line.startswith("| ")]
        marked |= {(section[1], section[2], check, row[0]) for row in rows[1:]
                   for check, cell in zip(rows[0][2:], row[2:], strict=True) if "**real**" in cell}
    assert listed == expected
    assert marked == {key[:4] for key in expected}
    assert ("slotted-skate", "fast", "final_speed", "3.11.0", "3.10.0") not in expected  # 4.4e-16, spread 0
    assert (releases.MULTIPLE, releases.ROUNDOFF) == (allowance.MULTIPLE, allowance.ROUNDOFF) == (MULTIPLE, ROUNDOFF)
    assert "exceeds both 3 times the larger of the two spreads and the roundoff floor, 1e-12 of max(1," in page


@pytest.mark.parametrize(("after", "spread", "real"), [
    (1.00947 + 4.4e-16, 0.0, False),  # roundoff: two ulps, no spread measured
    (1.00947 + 1.7e-6, 1e-6, False),  # 1.7 spreads
    (1.00947 + 3.5e-6, 1e-6, True),  # 3.5 spreads, far above the floor
    (1.00947 + 3.5e-14, 1e-14, False),  # 3.5 spreads, under the floor
], ids=["roundoff", "1.7-spreads", "3.5-spreads", "3.5-spreads-under-roundoff"])
def test_a_change_is_real_only_beyond_three_spreads_and_roundoff(monkeypatch: pytest.MonkeyPatch, after: float,
                                                                 spread: float, real: bool) -> None:
    """The page and a bisection apply one rule to a hand-built pair of releases."""
    payloads = [_payload("3.10.0", 1.00947, spread), _payload("3.11.0", after, spread)]
    (found,) = releases.changes(payloads, "toy", "fast")
    assert found["real"] is real and found["change"] > 0 and found["spread"] == spread
    assert ("| toy | fast | eigenvalue | 3.11.0 | 3.10.0 |" in releases.render(payloads, _index(payloads))) is real
    monkeypatch.setattr(releases, "_index_versions", lambda: ["3.10.0", "3.11.0"])
    values = {"3.10.0": 1.00947, "3.11.0": after}
    result = releases.bisect("3.10.0", "3.11.0", "toy", "fast", "eigenvalue", lambda v: (values[v], spread))
    assert result["first"] == ("3.11.0" if real else None)


def test_a_change_is_real_only_beyond_the_larger_spread() -> None:
    payloads = [_payload("3.3.4", 0.5, 1e-6), _payload("3.4.0", 0.5000005, 1e-6), _payload("3.5.0", 0.5003, 1e-5),
                _payload("3.6.0", 0.5, 0.0, refused="harness: contact release and restore does not work")]
    found = releases.changes(payloads, "toy", "fast")
    assert [(c["to"], c["real"]) for c in found] == [("3.4.0", False), ("3.5.0", True)]
    assert found[1]["change"] == pytest.approx(2.995e-4) and found[1]["spread"] == 1e-5
    page = releases.render(payloads, _index(payloads))
    assert "| toy | fast | eigenvalue | 3.5.0 | 3.4.0 | 0.0003 | 1e-05 | 30 | 0.015 |" in page
    assert "refused: harness: contact release and restore does not work" in page


def test_a_change_across_commits_is_never_called_real_or_jitter() -> None:
    """Two releases run at different commits of the suite: the change is not MuJoCo's alone."""
    payloads = [_payload("4.0.0", 0.5, 1e-6, sha="old"), _payload("4.0.1", 0.6, 1e-6, sha="new"),
                _payload("4.1.0", 0.5000001, 1e-6, sha="new")]
    found = releases.changes(payloads, "toy", "fast")
    assert [(c["to"], c["same_commit"], c["real"]) for c in found] == [("4.0.1", False, False), ("4.1.0", True, True)]
    index = _index(payloads) | {"history": ["4.0.0", "4.0.1", "4.1.0", "4.1.1"]}
    page = releases.render(payloads, index)
    assert "other commit" in page and "The releases ran at 2 commits of the suite" in page
    assert "Not run yet: MuJoCo 4.1.1 " in page
    assert "| toy | fast | eigenvalue | 4.1.0 | 4.0.1 |" in page and "| 4.0.1 | 4.0.0 |" not in page


def test_the_matrix_runs_what_the_page_lacks() -> None:
    """A release without a file, with a file of another commit, or missing a run; not one that holds them all."""
    names = releases.history_scenarios()

    def payload(version: str, sha: str, presets: tuple[str, ...]) -> dict[str, Any]:
        return {"mujoco": version, "environment": {"git_sha": sha},
                "runs": [{"scenario": n, "preset": p} for n in names for p in presets]}

    index = {"history": ["3.3.4", "3.4.0", "3.5.0", "4.0.0", "4.0.1"]}
    payloads = [payload("3.3.4", "head", ("fast", "accurate")), payload("3.4.0", "head", ("fast",)),
                payload("3.5.0", "older", ("fast",)), payload("4.0.0", "head", ("fast",))]
    assert releases.lacking(index, payloads, "head") == ["3.5.0", "4.0.0", "4.0.1"]


def test_bisect_finds_the_first_patch_release_of_a_change(monkeypatch: pytest.MonkeyPatch) -> None:
    index = ["3.3.2", "3.3.3", "3.3.4", "3.3.5", "3.3.6", "3.3.7", "3.4.0", "3.10.0"]
    monkeypatch.setattr(releases, "_index_versions", lambda: index)
    values = {"3.3.3": 1.0, "3.3.4": 1.0, "3.3.5": 1.0, "3.3.6": 1.2, "3.3.7": 1.2, "3.4.0": 1.2}
    asked: list[str] = []

    def value_at(release: str) -> tuple[float, float]:
        asked.append(release)
        return values[release], 1e-3

    result = releases.bisect("3.3.3", "3.4.0", "toy", "fast", "eigenvalue", value_at)
    assert result["first"] == "3.3.6" and len(asked) < len(values)
    values["3.4.0"] = values["3.3.6"] = values["3.3.7"] = 1.0005  # within the spread: no change
    assert releases.bisect("3.3.3", "3.4.0", "toy", "fast", "eigenvalue", value_at)["first"] is None
    with pytest.raises(ParameterError, match=r"3\.9\.9 is not a release after 3\.3\.3"):
        releases.bisect("3.3.3", "3.9.9", "toy", "fast", "eigenvalue", value_at)
    assert releases.patch_releases("3.3.7", "3.10.0", fetch=lambda: index) == ["3.4.0", "3.10.0"]


def test_a_release_file_is_stamped_by_its_latest_run_and_left_alone_when_nothing_is_added(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """A resumed matrix that runs nothing new for a release leaves its file byte for byte; one that adds a run
    stamps the file with that run's environment."""
    import mujoco


    dates = iter(f"2026-01-0{day}T00:00:00Z" for day in range(1, 10))
    sha = "head"
    monkeypatch.setattr(stamp, "environment", lambda: {"date": next(dates), "mujoco": mujoco.__version__,
                                                      "git_sha": sha})
    monkeypatch.setattr(releases, "run_scenario", lambda name, preset: {"scenario": name, "preset": preset,
                                                                     "refused": None, "passed": True})
    path = releases.run_release(tmp_path, ["fast"], ["rimless-wheel"])
    first = path.read_bytes()
    assert json.loads(first)["environment"]["date"] == "2026-01-02T00:00:00Z"  # the run's, not the opening's
    assert releases.run_release(tmp_path, ["fast"], ["rimless-wheel"]) == path
    assert path.read_bytes() == first
    releases.run_release(tmp_path, ["fast"], ["rimless-wheel", "slotted-skate"])
    held = json.loads(path.read_text())
    assert [r["scenario"] for r in held["runs"]] == ["rimless-wheel", "slotted-skate"]
    assert held["environment"]["date"] == "2026-01-05T00:00:00Z"
    sha = "next"  # a file of another commit is run again, whole: one file, one version of the suite
    releases.run_release(tmp_path, ["fast"], ["slotted-skate"])
    held = json.loads(path.read_text())
    assert [r["scenario"] for r in held["runs"]] == ["slotted-skate"] and held["environment"]["git_sha"] == "next"


def test_bad_input_exits_2_in_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert releases.main(["bisect", "4.0.0", "3.17.0", "--check", "rimless-wheel/eigenvalue"]) == 2
    assert releases.main(["bisect", "3.17.0", "4.0.0", "--check", "no-such-scenario/x"]) == 2
    assert releases.main(["bisect", "3.17.0", "4.0.0", "--check", "rimless-wheel"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 3 and "must be older than" in lines[0] and "unknown scenario" in lines[1]


def test_the_nox_sessions_are_the_history_the_index_gave(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    listed = subprocess.run([sys.executable, "-m", "nox", "-l"], capture_output=True, text=True, check=True).stdout
    assert re.findall(r"^[-*] release\(mujoco='([\d.]+)'\)", listed, re.M) == INDEX["history"]


def test_a_bisection_reads_the_history_then_runs_a_release_point(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """A release the history holds is read from it; one it does not is run through the nox session release_point
    into the bisection's own folder (never into the history's)."""
    history, out = tmp_path / "history", tmp_path / "bisect"
    for folder, version, value in ((history, "3.3.4", 0.5), (out, "3.3.5", 0.6)):
        (folder / "json").mkdir(parents=True, exist_ok=True)
        (folder / "json" / f"mujoco-{version}.json").write_text(json.dumps(_payload(version, value, 1e-6)))
    monkeypatch.setattr(releases, "OUT", history)
    calls: list[list[str]] = []

    def fake_nox(command: list[str], check: bool) -> None:
        calls.append(command)
        (out / "json" / "mujoco-3.3.6.json").write_text(json.dumps(_payload("3.3.6", 0.7, 1e-6)))

    monkeypatch.setattr(releases.subprocess, "run", fake_nox)
    value_at = releases._nox_point(out, "toy", "fast", "eigenvalue")
    assert value_at("3.3.4") == (0.5, 1e-6) and value_at("3.3.5") == (0.6, 1e-6) and not calls
    assert value_at("3.3.6") == (0.7, 1e-6)
    assert calls[0][1:] == ["-m", "nox", "-s", "release_point", "--", "3.3.6", "--out", str(out), "--scenario", "toy",
                            "--preset", "fast"]


def test_the_matrix_runs_one_nox_session_per_release_and_names_the_failed_ones(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """``matrix`` (make releases) asks the index, keeps its answer, runs the nox session of every release the page
    lacks with its output in a log of its own (accurate too on the oldest and the newest line), and returns the
    releases run and those whose session failed."""
    calls = []

    def fake_run(command: list[str], *, stdout: Any, stderr: Any, check: bool) -> subprocess.CompletedProcess:
        calls.append(command)
        stdout.write(f"ran {command[2]}\n")
        return subprocess.CompletedProcess(command, 1 if "3.9.0" in command[2] else 0)

    index = ["3.3.4", "3.3.7", "3.9.0", "4.0.0", "4.0.1"]
    monkeypatch.setattr(releases, "_index_versions", lambda: index)
    monkeypatch.setattr(stamp, "git_state", lambda: ("head", False))
    monkeypatch.setattr(releases.subprocess, "run", fake_run)
    out = tmp_path / "history"
    assert releases.run_matrix(2, tmp_path / "logs", out) == (releases.history(index), ["3.9.0"])
    assert releases.load_index(out)["history"] == releases.history(index)
    sessions = {c[2]: c[4:] for c in calls}
    assert sessions == {f"release(mujoco='{v}')": ["--out", str(out), "--preset", "fast",
                                                   *(["--preset", "accurate"] if v in ("3.3.4", "4.0.0", "4.0.1")
                                                     else [])] for v in releases.history(index)}
    assert (tmp_path / "logs" / "3.9.0.log").read_text() == "ran release(mujoco='3.9.0')\n"
    assert releases.main(["matrix", "--workers", "0"]) == 2
