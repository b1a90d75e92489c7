"""The wheel, as a new user gets it: built from this checkout, installed with the lock into a fresh venv, run from
another directory. It ships no generic top-level module, finds its MJCF files as package data, and its pytest plugin
gates a throwaway project that has only the wheel and pytest."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import pytest
from conftest import all_gated

REPO = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.install


def _run(args: list[str | Path], cwd: Path, **kwargs: object) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    return subprocess.run([str(a) for a in args], cwd=cwd, env=env, capture_output=True, text=True, timeout=900,
                          **kwargs)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("dist")
    built = _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", out, REPO], cwd=out)
    assert built.returncode == 0, built.stderr
    (path,) = out.glob("mjpoincare-*.whl")
    return path


@pytest.fixture(scope="module")
def env_bin(wheel: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh venv with the wheel (and pytest, for the plugin) installed through the lock, by the locked uv as
    ``make validate`` installs it (a wheel installs the same by either installer; uv takes seconds where pip took
    half a minute)."""
    root = tmp_path_factory.mktemp("venv")
    venv.create(root)
    bin_dir = root / "bin"
    from uv import find_uv_bin  # the dev extra's uv

    done = _run([find_uv_bin(), "pip", "install", "--quiet", "--compile-bytecode", "--python", bin_dir / "python",
                 "--constraint", REPO / "requirements" / "lock.txt", wheel, "pytest"], cwd=root)
    assert done.returncode == 0, done.stderr
    return bin_dir


def test_wheel_ships_no_generic_top_level_name(wheel: Path) -> None:
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
    assert {n.split("/")[0] for n in names} == {"mjpoincare", wheel.name.split("-")[0] + "-" +
                                                wheel.name.split("-")[1] + ".dist-info"}
    models = REPO / "models"  # the models and the files they include (common/)
    assert {f"mjpoincare/mjcf/{m.relative_to(models).as_posix()}" for m in models.rglob("*.xml")} <= set(names)
    assert "mjpoincare/analysis/returnmap.py" in names
    assert {"mjpoincare/gate/results/baseline.json", "mjpoincare/gate/results/margins.json"} <= set(names)


def test_installed_cli_runs_from_another_directory(env_bin: Path, tmp_path: Path) -> None:
    listed = _run([env_bin / "mjpoincare", "list"], cwd=tmp_path)
    assert listed.returncode == 0 and "rimless-wheel" in listed.stdout, listed.stderr
    scenario = all_gated("rimless-wheel-friction[fast]")  # every check gated: the run passes with margin
    ran = _run([env_bin / "mjpoincare", "validate", scenario], cwd=tmp_path)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    api = _run([env_bin / "python", "-c", f"import mjpoincare; print(mjpoincare.validate({scenario!r}).passed)"],
               cwd=tmp_path)
    assert api.stdout.strip() == "True", api.stderr
    assert list(tmp_path.iterdir()) == []  # no MUJOCO_LOG.TXT, nothing else


def test_installed_power_finds_the_gates_committed_baseline_through_the_package(env_bin: Path, tmp_path: Path) -> None:
    """``mjpoincare power`` compares with the committed baseline, which the wheel ships in the package
    (:mod:`mjpoincare.gate.records`): it runs outside any checkout, and its unplanted control is caught by nothing."""
    ran = _run([env_bin / "mjpoincare", "power", "--case", "rimless-wheel[", "--change", "none"], cwd=tmp_path)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert any(line.split()[:3] == ["rimless-wheel[fast]", "none", "-"] for line in ran.stdout.splitlines()), ran.stdout


def test_plugin_gates_a_throwaway_project(env_bin: Path, tmp_path: Path) -> None:
    """Only the wheel and pytest: a wholly gated scenario's defaults pass; a 10 ms step (11x the fast preset's) fails
    with exit 1 and the failing check's analytic value, simulated value and tolerance in the report."""
    scenario = all_gated("rimless-wheel-friction[fast]")
    passing = _run([env_bin / "pytest", "-q", "--mjpoincare", scenario], cwd=tmp_path)
    assert passing.returncode == 0, passing.stdout[-3000:]
    assert "rimless-wheel::eigenvalue" in _run([env_bin / "pytest", "-q", "--collect-only", "--mjpoincare",
                                                "rimless-wheel"], cwd=tmp_path).stdout
    failing = _run([env_bin / "pytest", "-q", "--mjpoincare", "rimless-wheel,slotted-skate", "--mjpoincare-set",
                    "timestep=0.01"], cwd=tmp_path)
    assert failing.returncode == 1, failing.stdout[-3000:]
    assert "analytic" in failing.stdout and "tolerance" in failing.stdout


def test_the_readmes_install_lines_name_what_exists(wheel: Path) -> None:
    """No package index serves mjpoincare: the README installs from a clone or a built wheel, never by a bare name,
    and every wheel it names is the one this checkout builds."""
    readme = (REPO / "README.md").read_text()
    assert not re.search(r"pip install (?:'|\")?mjpoincare\b(?![-./\w])", readme)
    named = set(re.findall(r"mjpoincare-[\w.]+-py3-none-any\.whl", readme))
    assert named == {wheel.name}
