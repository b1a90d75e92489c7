"""Shared fixtures: every test runs in a temporary working directory (MUJOCO_LOG.TXT would show there); the backend
tests run last, and the MJX scenario validation and the gate's second-kernel run run in processes of their own beside
the rest of the suite."""

from __future__ import annotations

import fcntl
import functools
import hashlib
import json
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from importlib import metadata
from pathlib import Path
from typing import Any

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from mjpoincare.gate.environments import DEFAULT, Environment, runnable_kernels, start_environment

# dm_control (the environments' tests) opens a GLFW context at import unless told otherwise; off-screen EGL works here
os.environ.setdefault("MUJOCO_GL", "egl")
# JAX's persistent compilation cache (keyed by the compiled program, JAX's version and the device), for the MJX tests
# and every process they start: XLA's compiles of mjx.step are most of their time, and repeat across tests, processes
# and runs of the suite, as pip's and uv's downloads do (XDG's user cache, as theirs)
os.environ.setdefault("JAX_COMPILATION_CACHE_DIR", str(
    Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "mjpoincare" / "jax-compilation"))

#: The MJX validation of the rimless wheel (a minute on 2 CPU cores, in one XLA thread) that
#: ``tests/test_backends.py::test_rimless_wheel_on_mjx_passes_its_fast_checks`` reads: started when that test is
#: collected, so that it runs while the rest of the suite does.
MJX_RUN = ("rimless-wheel", "mjx", "float64", "fast")
MJX_TEST = "tests/test_backends.py::test_rimless_wheel_on_mjx_passes_its_fast_checks"
mjx_run_key = pytest.StashKey[tuple[subprocess.Popen[bytes], Path]]()
#: The gate's kernel-sensitive cases under a second OpenBLAS kernel, which
#: ``tests/test_gate_environments.py::test_the_gate_holds_under_a_second_blas_kernel`` reads: started when that test
#: is collected, so that it runs while the rest of the suite does.
KERNEL_TEST = "tests/test_gate_environments.py::test_the_gate_holds_under_a_second_blas_kernel"
kernel_run_key = pytest.StashKey[subprocess.Popen[str]]()
#: The committed ensemble measurement (``make margins``).
MARGINS = Path(__file__).parents[1] / "docs" / "results" / "gate" / "margins.json"


def second_kernel() -> Environment:
    """The second kernel the kernel-sensitive cases run under: Prescott (every x86-64 CPU runs it), unless this
    process already runs it (CI under ``OPENBLAS_CORETYPE=Prescott``), then the CPU's own choice."""
    if os.environ.get("OPENBLAS_CORETYPE") == "Prescott":
        return DEFAULT
    return Environment("OPENBLAS_CORETYPE=Prescott", {"OPENBLAS_CORETYPE": "Prescott"})


def kernel_sensitive_cases() -> list[str]:
    """The gate cases at the fast preset with a check that a second kernel could move beyond its allowance: the
    measured environments (the committed measurement's ``environments``: the OpenBLAS kernels crossed with numpy's
    dispatch levels) move its error beyond its allowance's floor (:func:`mjpoincare.core.allowance.floor`) and by at
    least its spread, so that the environments, not the rounding perturbations, set its allowance. A check whose spread
    the perturbations set far above what any kernel moved cannot fail the comparison; none without the measurement."""
    from mjpoincare.core.allowance import floor
    from mjpoincare.gate.forms import case
    from mjpoincare.pages.gate_page import environment_range

    if not MARGINS.exists():
        return []
    rows = json.loads(MARGINS.read_text())["rows"]
    return sorted({r["case"] for r in rows if case(r["case"]).preset == "fast"
                   and environment_range(r) > floor(r["tolerance"], r["error"])
                   and environment_range(r) >= r["spread"]})


#: The distribution that makes each optional backend (``mjpoincare.engines.backends.REQUIRES``) required in CI.
BACKEND_DISTRIBUTIONS = {"mjx": "mujoco-mjx", "warp": "mujoco-warp", "drake": "drake"}
#: The extras ``make test`` installs (CI runs ``make test``).
CI_EXTRAS = ("dev", "viz", "dask", "tune", "peers", "mjx", "warp")


def required_in_ci(distribution: str) -> bool:
    """Whether CI (``CI=true``) must have ``distribution``: one of mjpoincare's requirements under an extra that
    ``make test`` installs, whose environment marker admits this platform and Python (drake has no wheel for some
    platforms, MJX and Warp need Python 3.11)."""
    if os.environ.get("CI") != "true":
        return False
    for text in metadata.requires("mjpoincare") or []:
        requirement = Requirement(text)
        if canonicalize_name(requirement.name) == canonicalize_name(distribution) and (
                requirement.marker is None or any(requirement.marker.evaluate({"extra": e}) for e in CI_EXTRAS)):
            return True
    return False


def skip_unless_required(reason: str, distribution: str) -> None:
    """Skip the calling test for ``reason`` (something optional is missing), or fail it where CI must have
    ``distribution`` (:func:`required_in_ci`): a broken install never hides behind a skip."""
    if required_in_ci(distribution):
        pytest.fail(f"CI installs {distribution}, but: {reason}")
    pytest.skip(reason)


def require_module(module: str, distribution: str) -> None:
    """Import ``module`` or :func:`skip_unless_required`."""
    try:
        __import__(module)
    except ImportError as missing:
        skip_unless_required(f"{module} is not installed ({missing})", distribution)


def all_gated(label: str) -> str:
    """``label``, after asserting that every check of that gate case is gated (a test that needs a whole run to pass
    uses such a case, and leaves the margin to the gate)."""
    from mjpoincare.gate import forms as gate

    found = gate.case(label)
    assert not found.watched and not found.misses, f"{label} is not a wholly gated case"
    return found.scenario


def failed_gated_checks(label: str, checks: list[dict[str, object]]) -> list[str]:
    """The checks (JSON records) that gate case ``label`` gates and that failed in ``checks`` (a run of the same
    scenario and preset elsewhere: another backend, an installed copy)."""
    from mjpoincare.gate import forms as gate

    gated = set(gate.case(label).gated)
    return [str(c["name"]) for c in checks if c["name"] in gated and not c["passed"]]


@pytest.fixture(autouse=True, scope="session")
def _gate_runs_shared_by_workers(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
                                 ) -> Iterator[None]:
    """Under pytest-xdist, a gate case's run (:func:`mjpoincare.gate.forms.run_case`, keyed by scenario, preset, seed
    and settings) is made once per test session, not once per worker: the first worker to ask runs it and pickles the
    result into the session's shared temporary folder, under a lock the other worker waits on, and reads it from there
    the next time (each worker keeps its own per-process cache on top). Runs of other environments (the second-kernel
    process, installed copies) are their own processes and never read it."""
    if not hasattr(request.config, "workerinput"):
        yield
        return
    from mjpoincare.gate import forms as gate

    shared = tmp_path_factory.getbasetemp().parent / "gate-runs"
    shared.mkdir(exist_ok=True)
    run = gate._validate

    @functools.cache
    def validate_once(scenario: str, preset: str, seed: int, values: tuple[tuple[str, Any], ...]) -> Any:
        key = hashlib.sha256(repr((scenario, preset, seed, values)).encode()).hexdigest()[:24]
        path = shared / f"{key}.pickle"
        with open(shared / f"{key}.lock", "w") as lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if path.exists():
                return pickle.loads(path.read_bytes())
            result = run(scenario, preset, seed, values)
            partial = path.with_suffix(".partial")
            partial.write_bytes(pickle.dumps(result))
            partial.replace(path)
            return result

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(gate, "_validate", validate_once)
        yield


@pytest.fixture(autouse=True)
def _in_tmp_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    monkeypatch.chdir(tmp_path)
    yield tmp_path
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists(), "MuJoCo wrote MUJOCO_LOG.TXT into the working directory"


#: The xdist group of the second-kernel test and of every test of a kernel-sensitive gate case: that test runs those
#: cases in its own process beside their second-kernel run, and the gate's tests of them read its runs.
KERNEL_GROUP = "gate-kernel-sensitive"


def gate_group(nodeid: str, labels: list[str], sensitive: set[str]) -> str | None:
    """The xdist group of a test by its node id: :data:`KERNEL_GROUP` for the second-kernel test and the tests of a
    kernel-sensitive gate case, ``gate-<label>`` for the tests of another gate case (its label opens the test's
    parameter id), None for any other test. ``labels``: the gate cases' labels, longest first."""
    if nodeid == KERNEL_TEST:
        return KERNEL_GROUP
    label = next((label for label in labels if f"[{label}" in nodeid), None)
    if label is None:
        return None
    return KERNEL_GROUP if label in sensitive else f"gate-{label}"


def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """Under ``--dist loadgroup``, the tests of one gate case share a worker, and so its run
    (:func:`mjpoincare.gate.forms.run_case` caches a run per process); the kernel-sensitive cases, which the
    second-kernel test runs in its own process to compare, are one group with that test. The groups are read from the
    node ids (:func:`gate_group`): pytest-xdist 3.8 names the groups of ``xdist_group`` marks by renaming node ids
    through an attribute pytest 9.2 no longer reads, so marks would be ignored. Without xdist this hook is never
    called."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    from mjpoincare.gate import forms as gate

    labels = sorted((c.label for c in gate.cases()), key=len, reverse=True)
    sensitive = set(kernel_sensitive_cases())

    class GateCaseScheduling(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            return gate_group(nodeid, labels, sensitive) or nodeid

    return GateCaseScheduling(config, log)


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """The backend tests run last: they load JAX and Warp, whose native threads make every later process pool spawn
    its workers instead of forking them (:func:`mjpoincare.core.parallel.start_method`), which costs the sweeps and
    convergence ladders after them their start-up time. The MJX validation starts now, in a process of its own, when
    its test is selected and MJX is installed (its test reports a missing MJX). This hook runs last, after ``-m`` and
    ``-k`` have deselected what they deselect, and ``--collect-only`` starts nothing. Under pytest-xdist no worker
    starts either: each test starts its own run (the other worker is the concurrency)."""
    items.sort(key=lambda item: item.nodeid.startswith("tests/test_backends.py"))
    from mjpoincare.core.params import ParameterError
    from mjpoincare.engines.backends import check_installed

    selected = {item.nodeid for item in items}
    if config.option.collectonly or hasattr(config, "workerinput"):  # an xdist worker: each collects every item
        return
    if KERNEL_TEST in selected and "Prescott" in runnable_kernels() and kernel_sensitive_cases():
        config.stash[kernel_run_key] = start_environment(second_kernel(), kernel_sensitive_cases())
    if MJX_TEST not in selected:
        return
    try:
        check_installed("mjx")
    except ParameterError:
        return
    config.stash[mjx_run_key] = start_mjx_run()


def start_mjx_run() -> tuple[subprocess.Popen[bytes], Path]:
    """The MJX validation :data:`MJX_RUN` started in a process of its own (one XLA thread), and its output folder."""
    out = Path(tempfile.mkdtemp(prefix="mjpoincare-mjx-"))
    scenario, backend, precision, preset = MJX_RUN
    env = {**os.environ, "XLA_FLAGS": "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1"}
    process = subprocess.Popen([sys.executable, "-m", "mjpoincare.pages.backend_findings", "run", scenario, backend,
                                precision, "--preset", preset, "--out", str(out)], cwd=out, env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return process, out


def pytest_unconfigure(config: pytest.Config) -> None:
    """Stop the MJX validation and the second-kernel run if their tests did not wait for them, and remove the MJX
    run's directory."""
    if kernel_run_key in config.stash and config.stash[kernel_run_key].poll() is None:
        config.stash[kernel_run_key].kill()
        config.stash[kernel_run_key].communicate()
    if mjx_run_key in config.stash:
        process, out = config.stash[mjx_run_key]
        if process.poll() is None:
            process.kill()
            process.wait()
        shutil.rmtree(out, ignore_errors=True)
