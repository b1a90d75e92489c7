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
from mjpoincare.analysis.returnmap import fit_drifting_cycle, fit_return_map

from mjpoincare.cli import main
from mjpoincare.commands import report
from mjpoincare.commands.render import parse_size
from mjpoincare.commands.report import eigenvalue_figure, return_map_figure, write_index, write_report
from mjpoincare.core.params import ParameterError
from mjpoincare.scenarios.base import ReturnMapPlot

pytestmark = pytest.mark.mujoco


def test_size_parsing() -> None:
    assert parse_size("640x480") == (640, 480)
    with pytest.raises(ParameterError, match="WIDTHxHEIGHT"):
        parse_size("big")


def test_render_frames_are_sized_not_blank_and_change(tmp_path: Path) -> None:
    code = (
        "import json, numpy as np\n"
        "from mjpoincare.commands.render import select_gl_backend\n"
        "backend = select_gl_backend()\n"
        "from mjpoincare.commands.render import render_frames\n"
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


def test_a_chosen_backend_that_fails_names_the_one_that_works(tmp_path: Path) -> None:
    """A ``MUJOCO_GL`` that cannot open a context here (a name MuJoCo does not know stands in for a missing OSMesa)
    is refused in one line naming the backend that does work, not with "no off-screen backend works"."""
    env = {**os.environ, "MUJOCO_GL": "no-such-gl"}
    out = subprocess.run([sys.executable, "-m", "mjpoincare.cli", "render", "rimless-wheel", "-o", "w.png"],
                         cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 2
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr
    assert re.search(r"MUJOCO_GL=no-such-gl does not work here, but MUJOCO_GL=(egl|osmesa) does", out.stderr)
    assert not list(tmp_path.iterdir())


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
    code = main(["validate", "rimless-wheel", "--report", str(tmp_path / "report")])
    page = (tmp_path / "report" / "rimless-wheel.html").read_text()
    result = json.loads((tmp_path / "report" / "rimless-wheel.json").read_text())
    assert code == (0 if result["passed"] else 1)
    assert "http" not in page.replace("http-equiv", "")  # no network assets
    rows = re.findall(r"<tr class=(pass|fail)><td>([^<]+)</td>", page)
    assert [(("pass" if c["passed"] else "fail"), c["name"]) for c in result["checks"]] == rows
    assert page.count("data:image/png;base64,") >= 3
    index = (tmp_path / "report" / "index.html").read_text()  # one scenario gets its index page too
    assert f"<a href='rimless-wheel.html'>rimless-wheel</a></td><td>{'PASS' if result['passed'] else 'FAIL'}" in index


def test_plots_leave_the_callers_matplotlib_alone(tmp_path: Path) -> None:
    """A report draws through matplotlib's object API: pyplot is not imported and the backend is not switched."""
    import subprocess
    import sys

    # the raw rcParams entry: matplotlib.get_backend() itself would import pyplot to resolve it
    code = ("import sys, matplotlib; raw = lambda: dict.__getitem__(matplotlib.rcParams, 'backend'); before = raw(); "
            "from mjpoincare.commands.report import write_report; "
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


def _result(name: str, verdicts: dict[str, bool], **extras: object) -> dict[str, object]:
    """A small synthetic result dict of the JSON's shape."""
    checks = [{"name": n, "analytic": 1.0, "simulated": 1.0, "error": 0.0 if ok else 1.0, "tolerance": 0.1,
               "passed": ok, "why": "synthetic"} for n, ok in verdicts.items()]
    return {"scenario": name, "preset": "fast", "passed": all(verdicts.values()), "params": {"slope": 0.1},
            "mujoco_version": "test", "timing": {"wall_s": 1.0, "steps_per_s": 1e5}, "warnings": [],
            "checks": checks, **extras}


def _figures_drawn(monkeypatch: pytest.MonkeyPatch) -> list[object]:
    """The report's figures, kept as they are encoded (``report._png`` is replaced)."""
    drawn: list[object] = []
    monkeypatch.setattr(report, "_png", lambda fig: drawn.append(fig) or base64.b64encode(b"\x89PNG").decode())
    return drawn


def _legend_texts(fig: object) -> list[str]:
    """The entries of every legend of ``fig`` (its axes' and its own)."""
    legends = [ax.get_legend() for ax in fig.axes] + list(fig.legends)  # type: ignore[attr-defined]
    return [t.get_text() for legend in legends if legend for t in legend.get_texts()]


def test_index_lists_every_scenario_and_verdict(tmp_path: Path) -> None:
    results = [_result("wheel", {"eigenvalue": True, "stable": True}),
               _result("biped", {"fixed_point": False, "stable": True})]
    page = write_index(results, str(tmp_path)).read_text()
    rows = re.findall(r"<tr class=(pass|fail)><td><a href='([^']+)'>([^<]+)</a></td><td>(PASS|FAIL)</td>(.*?)</tr>",
                      page)
    assert [(cls, href, name, verdict) for cls, href, name, verdict, _ in rows] == [
        ("pass", "wheel.html", "wheel", "PASS"), ("fail", "biped.html", "biped", "FAIL")]
    for (*_, cells), result in zip(rows, results, strict=True):
        chips = re.findall(r"<span class='v (pass|fail)'[^>]*>([^<]+)</span>", cells)
        assert chips == [("pass" if c["passed"] else "fail", c["name"]) for c in result["checks"]]
    assert "1 of 2 scenarios FAILED" in page


def test_complex_values_are_shown_as_complex_numbers(tmp_path: Path) -> None:
    """An eigenvalue check's values ([re, im] pairs in the JSON) read as a+bj on the page, not as a list of reals;
    a real vector of two stays two reals."""
    from mjpoincare.analysis.checks import absolute

    check = absolute("eigenvalue", complex(0.25, -0.5), complex(0.2501, -0.4999), 1e-3, "", "synthetic").to_dict()
    vector = {**check, "name": "fixed_point", "analytic": [0.25, -0.5], "simulated": [0.25, -0.5], "complex": False}
    result = {**_result("biped", {}), "checks": [check, vector]}
    page = write_report(result, str(tmp_path)).read_text()
    assert check["complex"] is True
    assert "<td>0.25-0.5j</td><td>0.2501-0.4999j</td>" in page
    assert "<td>0.25, -0.5</td><td>0.25, -0.5</td>" in page


def test_still_is_embedded_or_its_absence_said(tmp_path: Path) -> None:
    png = b"\x89PNG\r\n\x1a\nstill"
    page = write_report(_result("wheel", {"stable": True}), str(tmp_path / "a"), png).read_text()
    encoded = base64.b64encode(png).decode()
    assert f"<img class=still alt='still of wheel' src='data:image/png;base64,{encoded}'>" in page
    page = write_report(_result("wheel", {"stable": True}), str(tmp_path / "b"), "no OpenGL here").read_text()
    assert "<img class=still" not in page
    assert [line for line in page.splitlines() if "class=still" in line] == [
        "wall 1.00 s, 1e+05 steps/s</p><p class=still>No still of the model: no OpenGL here</p>"]


def test_fit_json_holds_the_bootstrap_eigenvalues() -> None:
    """Every kept replicate's multipliers, matched to the fit's and rounded to float32 precision: their spread is the
    reported std."""
    rng = np.random.default_rng(3)
    x = rng.normal(size=(60, 2))
    x_next = x @ np.array([[0.5, 0.2], [-0.3, 0.4]]) + 0.01 * rng.normal(size=(60, 2))
    fit = fit_return_map(x, x_next, bootstrap=50)
    cloud = np.array(json.loads(json.dumps(fit.to_dict()))["eigenvalue_replicates"])
    assert cloud.shape == (50, 2, 2)
    assert np.allclose(cloud[..., 0].std(axis=0, ddof=1), fit.eigenvalue_std.real, rtol=1e-4)
    assert np.allclose(cloud[..., 1].std(axis=0, ddof=1), fit.eigenvalue_std.imag, rtol=1e-4)
    drifting = fit_drifting_cycle(x, x_next, np.array([1.0, 0.0]), 0.0, degree=1, bootstrap=20)
    assert drifting.eigenvalue_replicates.shape == (drifting.replicates, 2)


def test_eigenvalue_cloud_is_drawn_from_the_replicates(monkeypatch: pytest.MonkeyPatch) -> None:
    drawn = _figures_drawn(monkeypatch)
    replicates = [[[0.55, 0.1], [0.55, -0.1]], [[0.45, 0.12], [0.45, -0.12]], [[0.5, 0.08], [0.5, -0.08]]]
    fit = {"eigenvalues": [[0.5, 0.1], [0.5, -0.1]], "eigenvalue_std": [[0.05, 0.02], [0.05, 0.02]],
           "eigenvalue_replicates": replicates}
    eigenvalue_figure(fit, [[0.52, 0.11], [0.52, -0.11]])
    main = drawn[0].axes[0]  # type: ignore[attr-defined]
    lines = {line.get_label(): line for line in main.get_lines()}
    cloud = lines["bootstrap replicates (3)"]
    assert list(cloud.get_xdata()) == [v[0] for row in replicates for v in row]
    assert list(cloud.get_ydata()) == [v[1] for row in replicates for v in row]
    assert cloud.get_alpha() < 0.5 and cloud.get_zorder() < lines["MuJoCo fit"].get_zorder()
    assert list(lines["analytic"].get_xdata()) == [0.52, 0.52]
    assert len(drawn[0].axes) == 2  # type: ignore[attr-defined]  # the plane and one zoom (one of the pair)
    eigenvalue_figure({k: v for k, v in fit.items() if k != "eigenvalue_replicates"}, [])
    assert _legend_texts(drawn[1]) == ["MuJoCo fit"]  # no cloud, no analytic values: neither in the legend


def test_biped_panel_is_section_convergence_without_analytic_map(monkeypatch: pytest.MonkeyPatch) -> None:
    """A return map with no 1-D analytic map: per section coordinate, |x_k - x*| against k on a log scale."""
    drawn = _figures_drawn(monkeypatch)
    star = [0.2, 1.0, -0.5]
    sequences = [[[0.3, 1.2, -0.4], [0.25, 1.1, -0.45], [0.22, 1.04, -0.48]], [[0.1, 0.9, -0.6], [0.15, 0.95, -0.55]]]
    fit = {"eigenvalues": [[0.5, 0.0]], "eigenvalue_std": [[0.0, 0.0]], "fixed_point": [0.2001, 1.001, -0.5002]}
    result = _result("compass-biped", {"stable": True}, fit=fit,
                     return_map={"label": "theta", "x": [0.3], "x_next": [0.25], "analytic_x": [0.1, 0.3],
                                 "analytic_y": [None, None], "analytic_eigenvalues": [0.5]},
                     section_convergence={"labels": ["a", "b", "c"], "fixed_point": star, "sequences": sequences})
    titles = [title for title, _ in report._figures(result)]
    assert titles[0] == "Convergence toward the analytic fixed point, per section coordinate"
    assert "Empirical return map" not in titles
    panels = drawn[0].axes  # type: ignore[attr-defined]
    assert len(panels) == 3 and all(ax.get_yscale() == "log" for ax in panels)
    for i, ax in enumerate(panels):
        traces = [line for line in ax.get_lines() if line.get_alpha() == 0.35]
        for line, seq in zip(traces, sequences, strict=True):
            assert np.allclose(line.get_ydata(), [abs(row[i] - star[i]) for row in seq])
    assert _legend_texts(drawn[0]) == ["MuJoCo trajectories", "|fitted fixed point - x*|",
                                       "analytic rate |lambda|max^k = 0.5^k"]
    assert all("analytic map" not in text for fig in drawn for text in _legend_texts(fig))
    return_map_figure(result["return_map"])  # type: ignore[arg-type]
    assert _legend_texts(drawn[-1]) == ["x_k+1 = x_k", "MuJoCo samples"]


def test_report_of_several_scenarios_has_index_and_stills(tmp_path: Path) -> None:
    """The CLI in a fresh process: the backend is chosen for the stills, each page embeds its still (a PNG of the
    model), and the index links every page."""
    done = _cli("validate", "slotted-skate", "rimless-wheel-friction", "--report", "rep", cwd=tmp_path)
    index = (tmp_path / "rep" / "index.html").read_text()
    verdicts = []
    for name in ("slotted-skate", "rimless-wheel-friction"):
        page = (tmp_path / "rep" / f"{name}.html").read_text()
        verdict = "PASS" if "all checks passed" in page else "FAIL"
        verdicts.append(verdict)
        assert f"<a href='{name}.html'>{name}</a></td><td>{verdict}" in index
        still = re.search(r"<img class=still alt='still of [^']+' src='data:image/png;base64,([^']+)'>", page)
        assert still is not None and base64.b64decode(still.group(1))[:4] == b"\x89PNG"
        assert "<h2>Eigenvalues of the fitted return map</h2>" in page
    assert done.returncode == (0 if verdicts == ["PASS", "PASS"] else 1), done.stderr[-2000:]
