"""Careless command-line input: every case is refused in ONE line on stderr naming the parameter or bound, with exit
code 2, no Traceback, nothing written in the working directory, and before any simulation.

Each case calls :func:`mjpoincare.cli.main` in-process in an empty working directory (``tmp_path``) under
:func:`no_simulation`: a rollout (``mujoco_c._native_chunk``), a new process (``multiprocessing``'s
``BaseProcess.start``, the pools' way to start one) or a subprocess (``subprocess.Popen``) fails the case; the GL probe
of ``render`` (a subprocess, not a simulation) is answered ``egl`` without running. argparse's own refusals
(``SystemExit``) count as their exit code.

Counts: 144 cases here; tests/test_cli.py covers 21 more (11 ``--set`` bounds, the unknown scenario and preset, 8
unwritable outputs under /proc), which this file does not repeat. The output paths that are legitimate (a FIFO,
/dev/null, a symlink, a missing folder) are tests/test_output_paths.py's.
"""

from __future__ import annotations

import contextlib
import multiprocessing.process
import subprocess
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from mjpoincare.cli import main

with contextlib.suppress(ImportError):  # Optuna's log handler keeps the sys.stderr of its import: not a case's capsys
    import optuna  # noqa: F401

RW = "rimless-wheel"
VAL = ("validate", RW)
S = "--set"


def _existing_dir(root: Path) -> None:
    (root / "existing").mkdir()


def _existing_file(root: Path) -> None:
    (root / "notadir.txt").write_text("x\n")


def _garbage_json(root: Path) -> None:
    (root / "garbage.json").write_text("not json at all\n")


Setup = Callable[[Path], None] | None


def case(argv: tuple[str, ...], *needles: str, setup: Setup = None, name: str | None = None) -> object:
    """One careless input: its argv, the text the one stderr line must hold, and what the case makes in the working
    directory first."""
    return pytest.param(argv, needles, setup, id=name or " ".join(argv)[:80])


CASES = [
    # --set: syntax, types and values (the 11 bounds of tests/test_cli.py are not repeated)
    case((*VAL, S, "integrator=RK4"), "integrator must be one of", "case-sensitive"),
    case((*VAL, S, "slope=0.1", S, "slope=0.12"), "--set slope is given twice"),
    case((*VAL, S, "spokes=8.5"), "spokes must be an integer"),
    case((*VAL, S, "spokes=eight"), "spokes must be a number", "'eight'"),
    case((*VAL, S, "spokes=1e10"), "spokes must be in [3, 64]"),
    case((*VAL, S, "slope=nan"), "slope must be a finite number"),
    case((*VAL, S, "slope=inf"), "slope must be a finite number"),
    case((*VAL, S, "slope=-inf"), "slope must be a finite number"),
    case((*VAL, S, "slope=1e400"), "slope must be a finite number"),
    case((*VAL, S, "slope="), "slope must be a number", "''"),
    case((*VAL, S, "slope"), "--set expects name=value", "'slope'"),
    case((*VAL, S, "=3"), "--set expects name=value", "'=3'"),
    case((*VAL, S, " =3"), "--set expects name=value"),
    case((*VAL, S, "slope=0.1rad"), "slope must be a number", "0.1rad"),
    case((*VAL, S, "slope=0,1"), "slope must be a number", "0,1"),
    case((*VAL, S, "Slope=0.1"), "unknown parameter 'Slope'"),
    case((*VAL, S, "kappa=0.3"), "unknown parameter 'kappa'", name="parameter of another scenario"),
    case((*VAL, S, "gait=a"), "unknown parameter 'gait'", name="parameter of another scenario (text)"),
    case((*VAL, S, "threads=0"), "threads must be in"),
    case((*VAL, S, "iterations=0"), "iterations must be in"),
    case((*VAL, S, "batch=-1"), "batch must be in"),
    case((*VAL, S, "start_perturbation=1"), "start_perturbation must be in"),
    case((*VAL, S, "precision=float16"), "precision must be one of"),
    case((*VAL, S, "precision=float32"), "precision must be float64 with backend=mujoco"),
    case((*VAL, S, "backend=bullet"), "backend must be one of"),
    case((*VAL, S, "timestep=-1e-3"), "timestep must be in (0, 0.05]"),
    case((*VAL, S, "timestep=1e-9"), "MuJoCo steps", "timestep"),
    case((*VAL, S, "timestep=1e-7"), "MuJoCo steps", "timestep"),
    case((*VAL, "--seed", "-1"), "seed", ">= 0"),
    case((*VAL, "--workers", "0"), "--workers must be >= 1"),
    # names
    case(("validate", "Rimless-Wheel"), "unknown scenario 'Rimless-Wheel'", "did you mean 'rimless-wheel'?"),
    case(("validate", "rimless_wheel"), "unknown scenario 'rimless_wheel'", "did you mean 'rimless-wheel'?"),
    case(("validate", RW, "spokes=8"), "unknown scenario 'spokes=8'", "--set spokes=8", name="a parameter as a name"),
    case((*VAL, S, "spoke=8"), "unknown parameter 'spoke'", "did you mean 'spokes'?"),
    case((*VAL, S, "slope=4.6"), "slope must be in (0, 1.5708) rad", "4.6 deg = 0.0802851 rad", name="degrees"),
    case(("bench", RW, "--values", "1,2"), "--values 1,2 is for bench --scaling only"),
    case((*VAL, "--json", "-", "--report", "-"), "--report -", "give a folder"),
    case((*VAL, "--preset", "Fast"), "preset must be one of fast, accurate", "'Fast'"),
    case(("validate", RW, "no-such-wheel"), "unknown scenario 'no-such-wheel'", name="second scenario unknown"),
    case(("stress", "no-such-wheel"), "unknown scenario 'no-such-wheel'"),
    case(("tune", "no-such-wheel"), "unknown scenario 'no-such-wheel'"),
    case(("render", "no-such-wheel", "-o", "out.png"), "unknown scenario 'no-such-wheel'"),
    case(("render", RW, "-o", "out.png", "--preset", "turbo"), "preset must be one of"),
    # outputs and inputs of validate
    case((*VAL, "--json", "existing"), "--json existing is a directory", setup=_existing_dir),
    case((*VAL, "--report", "notadir.txt"), "--report notadir.txt", setup=_existing_file),
    case((*VAL, "--json", "out.json", "--report", "out.json"), "--json and --report are both out.json"),
    case((*VAL, "--json", "b.json", "--baseline", "b.json", "--update-baseline"),
         "--json and --baseline are both b.json"),
    case((*VAL, "--baseline", "missing.json"), "--baseline missing.json does not exist"),
    case((*VAL, "--baseline", "garbage.json"), "--baseline garbage.json", setup=_garbage_json),
    case((*VAL, "--update-baseline"), "--update-baseline needs --baseline"),
    case(("validate", "slotted-skate", "--peer", "drake"), "--peer drake is for"),
    # sweep
    case(("sweep", RW, "--param", "slope", "--values", "0.07:0.06:0"), "COUNT >= 1", name="sweep empty range"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08:0.09:100000"), "--values", "100000",
         name="sweep huge range"),
    case(("sweep", RW, "--param", "timestep", "--values", "1e-9,1e-8"), "MuJoCo steps", name="sweep tiny timesteps"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08:0.09:1001"), "--values", "1001"),
    case(("sweep", RW, "--param", "nosuch", "--values", "1,2"), "unknown parameter 'nosuch'"),
    case(("sweep", RW, "--param", "slope", "--values", "abc,def"), "slope must be a number"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08:0.09:two"), "--values START:STOP:COUNT"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08:0.09:-3"), "--values START:STOP:COUNT"),
    case(("sweep", RW, "--param", "slope", "--values", ",,"), "--values needs at least one value"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.3"), "slope must be in (0.0682, 0.2621)"),
    case(("sweep", RW, "--param", "spokes", "--values", "8,8.5"), "spokes must be an integer"),
    case(("sweep", RW, "--param", "slope"), "sweep needs --param and --values"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--resume"), "--resume needs --json"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--workers", "0"), "--workers must be >= 1"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--engine", "spark"), "--engine", "spark"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--json", "existing"),
         "--json existing is a directory", setup=_existing_dir),
    case(("sweep", "rimless-wheel-friction", "--param", "mu", "--values", "0.1,-1"), "mu must be in [0, 1000]"),
    case(("sweep", "slotted-skate", "--grid", "x=1:2"), "--grid expects x=START:STOP:N,y=START:STOP:N"),
    case(("sweep", "slotted-skate", "--grid", "foo=1:2:3,y=0.1:0.5:2"), "--grid expects"),
    case(("sweep", "slotted-skate", "--grid", "x=-1:0:1,y=0.1:0.5:2"), "--grid x expects", "N >= 2"),
    case(("sweep", "slotted-skate", "--grid", "x=-1:0:2,y=-0.1:0.5:2"), "--grid y", "must be > 0"),
    case(("sweep", RW, "--grid", "x=-1:0:2,y=0.1:0.5:2"), "rimless-wheel has no region map"),
    case(("sweep", "slotted-skate", "--grid", "x=-1:0:2,y=0.1:0.5:2", "--json", "m.png", "-o", "m.png"),
         "--json and --output are both m.png"),
    # bench
    case(("bench", RW, "--scaling"), "bench --scaling needs --param"),
    case(("bench", RW, "--param", "slope"), "--param slope is for bench --scaling only"),
    case(("bench", RW, "--scaling", "--param", "slope", "--workers", "0"), "--workers must be >= 2"),
    case(("bench", RW, "--scaling", "--param", "slope", "--repeats", "0"), "--repeats >= 1"),
    case(("bench", RW, "--scaling", "--param", "nosuch"), "unknown parameter 'nosuch'"),
    case(("bench", RW, "--quick", S, "spokes=2"), "spokes must be in [3, 64]"),
    case(("bench", RW, "--quick", "--json", "b.png", "-o", "b.png"), "--json and --output are both b.png"),
    # stress, converge
    case(("stress", RW, "--workers", "0"), "--workers must be >= 1"),
    case(("converge", RW, "--points", "2"), "--points must be in [3, 8]"),
    case(("converge", RW, "--ratio", "1"), "--ratio must be in (1, 4]"),
    case(("converge", RW, "--ratio", "0.5"), "--ratio must be in (1, 4]"),
    case(("converge", RW, "--ratio", "nan"), "--ratio must be in (1, 4]"),
    case(("converge", RW, "--axis", "nosuch"), "--axis must be one of"),
    case(("converge", RW, "--workers", "0"), "--workers must be >= 1"),
    case(("converge", RW, "--engine", "spark"), "--engine", "spark"),
    case(("converge", RW, S, "spokes=2"), "spokes must be in [3, 64]"),
    case(("converge", RW, "--preset", "turbo"), "preset must be one of"),
    case(("converge", RW, "--resume"), "--resume needs --json"),
    case(("converge", RW, "--json", "c", "--report", "c"), "--json and --report are both c"),
    # tune, margins, power
    case(("tune", RW, "--target", "turbo"), "--target must be one of"),
    case(("tune", RW, "--trials", "0"), "--trials", ">= 1"),
    case(("tune", RW, "--workers", "0"), "--workers must be >= 1"),
    case(("tune", RW, "--enqueue", "nosuch=1"), "--enqueue", "nosuch"),
    case(("tune", RW, "--json", "t.db", "--study", "t.db"), "--json and --study are both t.db"),
    case(("margins", "--case", "no-such-case"), "--case matches no gate case"),
    case(("margins", "--workers", "0"), "--workers must be >= 1"),
    case(("margins", "--environments", "bogus"), "--environments must be all, none or labels"),
    case(("margins", "--compare", "missing.json", "--environments", "none"), "--compare missing.json"),
    case(("margins", "--compare", "garbage.json", "--environments", "none"), "--compare garbage.json",
         setup=_garbage_json),
    case(("power", "--change", "nosuch"), "--change must be among"),
    case(("power", "--workers", "0"), "--workers must be >= 1"),
    case(("power", "--case", "no-such-case"), "--case matches no case"),
    # render
    case(("render", RW, "-o", "out.txt"), "--output out.txt", ".mp4"),
    case(("render", RW, "-o", "out.avi"), "--output out.avi", ".mp4"),
    case(("render", RW, "-o", "out"), "--output out", "none"),
    case(("render", RW, "-o", "out.png", "--size", "10x10"), "size must be between 16x16 and 4096x4096"),
    case(("render", RW, "-o", "out.png", "--size", "big"), "size must be WIDTHxHEIGHT"),
    case(("render", RW, "-o", "out.png", "--size", "640x480x3"), "size must be WIDTHxHEIGHT"),
    case(("render", RW, "-o", "out.png", "--fps", "0"), "--fps in [1, 240]"),
    case(("render", RW, "-o", "out.png", "--fps", "1000"), "--fps in [1, 240]"),
    case(("render", RW, "-o", "out.png", "--seconds", "-1"), "--seconds", "-1"),
    case(("render", RW, "-o", "out.png", "--seconds", "nan"), "--seconds", "nan"),
    case(("render", RW, "-o", "out.png", S, "spokes=2"), "spokes must be in [3, 64]"),
    # refused since b4cbc79's survey began (findings of the first draft of this file, fixed in the source)
    case(("stress", RW, "--soak", "-5"), "--soak", "-5"),
    case(("stress", RW, "--soak", "1000000000"), "--soak", "1000000000"),
    case(("converge", RW, S, "timestep=1e-7"), "MuJoCo steps", "timestep"),
    case(("sweep", "rimless-wheel-friction", "--param", "mu", "--values", "0.3:1:100000"), "--values", "100000",
         name="own sweep (mu) over a huge range"),
    case(("sweep", "slotted-skate", "--grid", "x=-1:0:200,y=0.1:0.5:200"), "--grid", "40000 cells"),
    case(("sweep", "slotted-skate", "--grid", "x=-1:0:101,y=0.1:0.5:100"), "--grid", "10100 cells"),
    case(("render", RW, "-o", "out.png", S, "timestep=1e-9"), "MuJoCo steps", "timestep"),
    case(("render", RW, "-o", "out.png", "--seconds", "1e9"), "--seconds", "1000000000"),
    case(("render", RW, "-o", "out.png", "--seconds", "inf"), "--seconds", "inf"),
    case(("render", RW, "-o", "out.png", "--seconds", "601"), "--seconds", "601"),
    case(("tune", RW, "--plot", "front.txt", "--trials", "1", "--workers", "1"), "--plot front.txt", ".txt"),
    case(("bench", RW, "--quick", "-o", "plot.txt"), "--output plot.txt", ".txt"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "-o", "x.txt"), "--output x.txt"),
    case(("sweep", "rimless-wheel-friction", "--param", "mu", "--values", "0.3,0.4", "-o", "x.png"), "--output x.png",
         "own sweep of mu"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--scheduler", "tcp://127.0.0.1:1"),
         "--scheduler", "--engine dask"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.08"), "--values", "0.08", "more than once"),
    case((*VAL, RW), RW, "more than once", name="validate rimless-wheel rimless-wheel"),
    case(("converge", RW, "--axis", "timestep", "--axis", "timestep"), "--axis timestep", "more than once"),
    # argparse's own refusals: one line too (no usage block above it)
    case(("frobnicate", RW), "frobnicate", "invalid choice"),
    case((), "command", name="no command"),
    case((*VAL, "--seed", "abc"), "--seed", "abc"),
    case((*VAL, "--threads", "0"), "--threads", "unrecognized"),
    case((*VAL, "--json"), "--json", "expected one argument"),
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", "--workers", "two"), "--workers", "two"),
    # the cost of every run a command would make, counted before the first one
    case(("bench", RW, "--quick", S, "timestep=1e-9"), "MuJoCo steps", "timestep"),
    case(("bench", RW, "--scaling", "--param", "timestep", "--values", "1e-9,1e-8"), "MuJoCo steps", "timestep"),
    # a parameter both set and swept
    case(("sweep", RW, "--param", "slope", "--values", "0.08,0.09", S, "slope=0.1"), "--set slope", "--param slope"),
]


@pytest.fixture
def no_simulation(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """Fail the case on a rollout, a new process or a subprocess. The seam's self-test (a tiny model, cached per
    process) runs first, as any earlier validation in the process would have run it (tests/test_cli.py does the
    same)."""
    from mjpoincare.commands import render, tune
    from mjpoincare.engines.backends import mujoco_c
    from mjpoincare.simulation import seam_check

    seam_check.require(tuple(seam_check.MECHANISMS))

    def refuse(what: str) -> Callable[..., None]:
        def fail(*_: object, **__: object) -> None:
            raise AssertionError(f"{what} before the input was refused")

        return fail

    monkeypatch.setattr(mujoco_c, "_native_chunk", refuse("simulated"))
    monkeypatch.setattr(multiprocessing.process.BaseProcess, "start", refuse("started a process"))
    monkeypatch.setattr(subprocess.Popen, "__init__", refuse("started a subprocess"))
    monkeypatch.setattr(tune, "_work", refuse("started tune's trials"))  # in-process with --workers 1
    monkeypatch.setattr(render, "select_gl_backend", lambda: "egl")
    yield


def _files(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


def _run(argv: tuple[str, ...]) -> int:
    try:
        return main(list(argv))
    except SystemExit as exc:  # argparse's refusals
        return exc.code if isinstance(exc.code, int) else 1


@pytest.mark.parametrize(("argv", "needles", "setup"), CASES)
@pytest.mark.usefixtures("no_simulation")
def test_careless_input_exits_2_in_one_line_before_any_simulation(
        argv: tuple[str, ...], needles: tuple[str, ...], setup: Setup, tmp_path: Path,
        capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    if setup is not None:
        setup(tmp_path)
    made = _files(tmp_path)
    code = _run(argv)
    err = capsys.readouterr().err
    assert code == 2, err
    assert "Traceback" not in err, err
    assert err.count("\n") == 1 and len(err.splitlines()) == 1, err
    assert all(needle in err for needle in needles), (needles, err)
    assert _files(tmp_path) == made
