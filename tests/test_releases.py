"""The MuJoCo release history: the range pyproject.toml admits is the history's, the committed page re-renders byte
for byte from its JSON and covers every minor line, a change is real only beyond its spread, and a bisection finds
the first patch release of a change (on a synthetic index: no simulation here)."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path
from typing import Any

import pytest

from mjpoincare import releases, scenarios
from mjpoincare.params import ParameterError

ROOT = Path(__file__).resolve().parent.parent
PAYLOADS = releases.load(ROOT / releases.OUT)


def test_the_range_pyproject_admits_starts_at_the_oldest_release_of_the_history() -> None:
    pin = re.search(r'^\s*"mujoco>=([\d.]+),<5",', (ROOT / "pyproject.toml").read_text(), re.M)
    assert pin is not None and pin.group(1) == releases.OLDEST
    assert releases.NEWEST.startswith("4.")
    assert list(releases.RELEASES) == sorted(releases.RELEASES, key=releases.version_key)


def test_the_history_holds_every_minor_line_once_with_the_oldest_admitted() -> None:
    lines = [releases.version_key(v)[:2] for v in releases.RELEASES[1:]]
    assert len(set(lines)) == len(lines)
    first, last = lines[0], lines[-1]
    minors = {(3, m) for m in range(first[1], 18)} | {(4, 0)}
    assert first == releases.version_key(releases.OLDEST)[:2] and last == (4, 0) and set(lines) == minors


def test_the_readme_ci_example_lists_releases_of_the_history() -> None:
    matrix = re.search(r"matrix: \{mujoco: \[(.*?)\]\}", (ROOT / "README.md").read_text())
    assert matrix is not None
    listed = re.findall(r'"([\d.]+)"', matrix.group(1))
    assert listed and set(listed) <= set(releases.RELEASES) and releases.OLDEST in listed


def test_committed_page_reproduces_from_its_json_and_covers_the_history() -> None:
    page = ROOT / releases.PAGE
    assert page.read_text() == releases.render(PAYLOADS), f"{page} is stale: run make releases-render"
    assert [p["mujoco"] for p in PAYLOADS] == list(releases.RELEASES)
    for payload in PAYLOADS:
        presets = {"fast", "accurate"} if payload["mujoco"] in releases.ACCURATE_ON else {"fast"}
        ran = {(r["scenario"], r["preset"]) for r in payload["runs"]}
        assert ran == {(n, p) for n in scenarios.DEFAULT_SCENARIOS for p in presets}, payload["mujoco"]
        assert payload["environment"]["mujoco"] == payload["mujoco"]


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


def _payload(version: str, value: float, spread: float, refused: str | None = None) -> dict[str, Any]:
    env = {"mujoco": version, "numpy": "2", "scipy": "1", "python": "3.11", "cpu": "CPU", "git_sha": "abc",
           "git_dirty": False, "date": "2026-01-01T00:00:00Z"}
    check = {"name": "eigenvalue", "analytic": 0.5, "simulated": value, "error": abs(value - 0.5),
             "error_kind": "absolute", "tolerance": 0.02, "passed": True, "spread": spread}
    run = ({"scenario": "toy", "preset": "fast", "refused": refused} if refused else
           {"scenario": "toy", "preset": "fast", "refused": None, "passed": True, "wall_s": 1.0, "warnings": [],
            "checks": [check]})
    return {"schema": releases.SCHEMA, "mujoco": version, "environment": env, "runs": [run]}


def test_a_change_is_real_only_beyond_the_larger_spread() -> None:
    payloads = [_payload("3.3.4", 0.5, 1e-6), _payload("3.4.0", 0.5000005, 1e-6), _payload("3.5.0", 0.5003, 1e-5),
                _payload("3.6.0", 0.5, 0.0, refused="harness: contact release and restore does not work")]
    found = releases.changes(payloads, "toy", "fast")
    assert [(c["to"], c["real"]) for c in found] == [("3.4.0", False), ("3.5.0", True)]
    assert found[1]["change"] == pytest.approx(2.995e-4) and found[1]["spread"] == 1e-5
    page = releases.render(payloads)
    assert "| toy | fast | eigenvalue | 3.5.0 | 3.4.0 | 0.0003 | 1e-05 | 30 | 0.015 |" in page
    assert "refused: harness: contact release and restore does not work" in page


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


def test_bad_input_exits_2_in_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert releases.main(["bisect", "4.0.0", "3.17.0", "--check", "rimless-wheel/eigenvalue"]) == 2
    assert releases.main(["bisect", "3.17.0", "4.0.0", "--check", "no-such-scenario/x"]) == 2
    assert releases.main(["bisect", "3.17.0", "4.0.0", "--check", "rimless-wheel"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 3 and "must be older than" in lines[0] and "unknown scenario" in lines[1]


def test_sessions_are_the_nox_sessions_of_the_history(capsys: pytest.CaptureFixture[str]) -> None:
    assert releases.main(["sessions"]) == 0
    assert capsys.readouterr().out.split() == [f"release(mujoco='{v}')" for v in releases.RELEASES]


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
    """``matrix`` (make releases) runs every release's nox session with its output in a log of its own, and
    returns the releases whose session failed."""
    calls = []

    def fake_run(command: list[str], *, stdout: Any, stderr: Any, check: bool) -> subprocess.CompletedProcess:
        calls.append(command)
        stdout.write(f"ran {command[-1]}\n")
        return subprocess.CompletedProcess(command, 1 if "3.9.0" in command[-1] else 0)

    monkeypatch.setattr(releases.subprocess, "run", fake_run)
    assert releases.run_matrix(2, tmp_path) == ["3.9.0"]
    assert sorted(c[-1] for c in calls) == sorted(f"release(mujoco='{v}')" for v in releases.RELEASES)
    assert (tmp_path / "3.9.0.log").read_text() == "ran release(mujoco='3.9.0')\n"
    assert releases.main(["matrix", "--workers", "0"]) == 2
