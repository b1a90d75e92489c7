"""Off-screen rendering (the backend CI has: EGL from Mesa) and the self-contained HTML report."""

from __future__ import annotations

import base64
import dataclasses
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from mjpoincare.analysis.checks import jsonable

from mjpoincare.cli import main
from mjpoincare.params import ParameterError
from mjpoincare.render import parse_size
from mjpoincare.report import eigenvalue_figure, return_map_figure
from mjpoincare.scenarios.base import ReturnMapPlot

pytestmark = pytest.mark.mujoco


def test_size_parsing() -> None:
    assert parse_size("640x480") == (640, 480)
    with pytest.raises(ParameterError, match="WIDTHxHEIGHT"):
        parse_size("big")


def test_render_frames_are_sized_not_blank_and_change(tmp_path: Path) -> None:
    code = (
        "import json, numpy as np\n"
        "from mjpoincare.render import select_gl_backend\n"
        "backend = select_gl_backend()\n"
        "from mjpoincare.render import render_frames\n"
        "frames, timing = render_frames('rimless-wheel', {}, None, 1.0, 10, (160, 120))\n"
        "np.save('frames.npy', frames)\n"
        "print(json.dumps({'backend': backend, **timing}))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}  # exercise the automatic choice
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=300, check=True)
    info = json.loads(out.stdout.strip().splitlines()[-1])
    assert info["backend"] in ("egl", "osmesa")
    frames = np.load(tmp_path / "frames.npy")
    assert frames.shape == (10, 120, 160, 3)
    assert all(f.std() > 5 for f in frames)  # not blank
    assert np.abs(frames[0].astype(int) - frames[-1].astype(int)).mean() > 1  # the wheel moved


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """The CLI in a fresh process: the OpenGL backend is chosen before MuJoCo is first imported."""
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}
    return subprocess.run([sys.executable, "-m", "mjpoincare.cli", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=300)


def test_render_cli_writes_video_and_still(tmp_path: Path) -> None:
    video = _cli("render", "rimless-wheel", "-o", "wheel.mp4", "--seconds", "0.5", "--fps", "10",
                 "--size", "160x120", cwd=tmp_path)
    assert video.returncode == 0, video.stderr
    assert "ms/frame" in video.stdout
    assert (tmp_path / "wheel.mp4").stat().st_size > 1000
    still = _cli("render", "rimless-wheel", "-o", "wheel.png", "--seconds", "0.2", "--size", "160x120", cwd=tmp_path)
    assert still.returncode == 0, still.stderr
    assert (tmp_path / "wheel.png").read_bytes()[:4] == b"\x89PNG"
    bad = _cli("render", "rimless-wheel", "--size", "huge", cwd=tmp_path)
    assert bad.returncode == 2 and "size must be WIDTHxHEIGHT" in bad.stderr


@pytest.mark.parametrize("scenario", ["compass-biped", "slotted-skate"])
def test_controlled_scenarios_render(scenario: str, tmp_path: Path) -> None:
    """Scenarios whose controller switches contacts or pegs render through their own event-driven clip."""
    out = _cli("render", scenario, "-o", "still.png", "--seconds", "0.3", "--size", "160x120", cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "still.png").stat().st_size > 1000


def test_report_table_matches_json(tmp_path: Path) -> None:
    assert main(["validate", "rimless-wheel", "--report", str(tmp_path / "report")]) in (0, 1)
    page = (tmp_path / "report" / "rimless-wheel.html").read_text()
    result = json.loads((tmp_path / "report" / "rimless-wheel.json").read_text())
    assert "http" not in page.replace("http-equiv", "")  # no network assets
    rows = re.findall(r"<tr class=(pass|fail)><td>([^<]+)</td>", page)
    assert [(("pass" if c["passed"] else "fail"), c["name"]) for c in result["checks"]] == rows
    assert page.count("data:image/png;base64,") >= 3


def test_plots_leave_the_callers_matplotlib_alone(tmp_path: Path) -> None:
    """A report draws through matplotlib's object API: pyplot is not imported and the backend is not switched."""
    import subprocess
    import sys

    # the raw rcParams entry: matplotlib.get_backend() itself would import pyplot to resolve it
    code = ("import sys, matplotlib; raw = lambda: dict.__getitem__(matplotlib.rcParams, 'backend'); before = raw(); "
            "from mjpoincare.report import write_report; "
            "from mjpoincare import api; r = api.validate('slotted-skate'); write_report(r.to_dict(), sys.argv[1]); "
            "assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported'; "
            "assert raw() == before, (before, raw())")
    done = subprocess.run([sys.executable, "-c", code, str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert list(tmp_path.glob("*.html"))


def test_return_map_plot_is_the_json_the_report_draws() -> None:
    """Each field under its own key, in the JSON's order and untouched; the report's figures draw from its JSON."""
    grid = np.linspace(0.1, 0.3, 5)
    plot = ReturnMapPlot(label="theta (rad)", x=np.array([0.1, 0.2, 0.3]), x_next=np.array([0.15, 0.22, 0.28]),
                         analytic_x=grid, analytic_y=np.where(grid < 0.3, 0.5 * grid, np.nan),
                         analytic_eigenvalues=[0.5, complex(0.1, 0.2)])
    entry = plot.to_dict()
    assert list(entry) == ["label", "x", "x_next", "analytic_x", "analytic_y", "analytic_eigenvalues"]
    assert all(entry[f.name] is getattr(plot, f.name) for f in dataclasses.fields(plot))
    data = json.loads(json.dumps(jsonable(entry)))
    assert data["x_next"] == [0.15, 0.22, 0.28] and data["analytic_y"][-1] is None
    assert data["analytic_eigenvalues"] == [0.5, [0.1, 0.2]]
    fit = {"eigenvalues": [[0.5, 0.0], [0.1, 0.2]], "eigenvalue_std": [[0.01, 0.0], [0.02, 0.02]]}
    for png in (return_map_figure(data), eigenvalue_figure(fit, data["analytic_eigenvalues"])):
        assert base64.b64decode(png)[:4] == b"\x89PNG"
