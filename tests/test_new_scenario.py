"""``mjpoincare new-scenario NAME`` writes a plugin that ``mjpoincare check-plugin NAME`` passes as written, from a
folder outside the checkout (a distribution to importlib.metadata through its dist-info, as tests/plugin_example/);
the checks of the contract fail, one line each, where the plugin breaks them."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from mjpoincare.cli import main

pytestmark = pytest.mark.mujoco
NAME = "toy-drop"


def _install_on_path(root: Path) -> None:
    """The metadata pip would write, beside the package: the folder on PYTHONPATH is then the installed plugin."""
    info = root / "toy_drop-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: toy-drop\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(f"[mjpoincare.scenarios]\n{NAME} = toy_drop:SCENARIO\n")


def _mjpoincare(root: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(root), os.environ.get("PYTHONPATH", "")]),
           "PYTHONDONTWRITEBYTECODE": "1", "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    script = Path(sys.executable).with_name("mjpoincare")
    return subprocess.run([str(script), *args], cwd=root, env=env, capture_output=True, text=True, timeout=300)


@pytest.fixture
def plugin(tmp_path: Path) -> Path:
    assert main(["new-scenario", NAME, "--dir", str(tmp_path / NAME)]) == 0
    root = tmp_path / NAME
    assert {p.name for p in root.iterdir()} == {"pyproject.toml", "toy_drop", "README.md"}
    _install_on_path(root)
    return root


def test_the_scaffold_passes_the_contract_as_written(plugin: Path) -> None:
    run = _mjpoincare(plugin, "check-plugin", NAME)
    lines = run.stdout.strip().splitlines()
    assert run.returncode == 0, run.stdout + run.stderr
    assert lines[-1] == f"{NAME}: every clause holds" and all(line.startswith("ok    ") for line in lines[:-1])
    assert sum("a still renders" in line for line in lines) == 2  # both presets


def test_a_broken_clause_is_one_failing_line(plugin: Path) -> None:
    """The scaffold's gate case at the accurate preset made to gate a check the run does not report: the clause
    fails in one line naming the check, the others hold, exit 1."""
    module = plugin / "toy_drop" / "__init__.py"
    text = module.read_text()
    module.write_text(text.replace('GateCase.of("toy-drop", "accurate", ("fall_time", "stable"))',
                                   'GateCase.of("toy-drop", "accurate", ("stable",))'))
    run = _mjpoincare(plugin, "check-plugin", NAME)
    failed = [line for line in run.stdout.splitlines() if line.startswith("FAIL")]
    assert run.returncode == 1 and failed == [
        "FAIL  gate case toy-drop[accurate]: AssertionError: checks in no form (gated, watched or a declared miss): "
        "fall_time"], run.stdout


@pytest.mark.parametrize(("name", "said"), [("Toy", "lower-case words joined by hyphens"),
                                            ("toy-drop", "exists: new-scenario writes a new folder")])
def test_new_scenario_refuses_a_bad_name_or_an_existing_folder(name: str, said: str, tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "toy-drop").mkdir()
    assert main(["new-scenario", name, "--dir", str(tmp_path / name)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and said in err[0]
