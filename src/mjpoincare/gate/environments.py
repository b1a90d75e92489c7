"""The environments one machine can emulate, for the regression gate's spread (:mod:`mjpoincare.gate.forms`).

A gate value differs between machines through the libraries' choice of code path by CPU, not only through the
perturbations of the starts: OpenBLAS picks a kernel per CPU (``OPENBLAS_CORETYPE`` picks another), numpy dispatches
its loops to the CPU's SIMD extensions (``NPY_DISABLE_CPU_FEATURES`` takes them down to AVX2 or to numpy's
baseline), and OpenBLAS may split a product over threads (``OPENBLAS_NUM_THREADS``). A real CPU picks a kernel and a
dispatch level together, so the ensemble is their cross product: every kernel with numpy at each level this CPU
offers, and the default with one BLAS thread. All act when the library loads, so each environment runs in a process
of its own: ``mjpoincare margins --base-only --json -`` with the environment's variables, the gate cases' errors read
back from its JSON.

Each kernel is offered only where this CPU has the instructions it needs (read from numpy's CPU feature table), since
OpenBLAS accepts a kernel name the CPU cannot run and then dies of an illegal instruction.
"""

from __future__ import annotations

import importlib
import json
import math
import os
import subprocess
import sys
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any

#: OpenBLAS kernels by the CPU features each needs (numpy's feature names), oldest first: Prescott (SSE3) runs on every
#: x86-64 CPU; Zen is offered beside Haswell although some OpenBLAS builds map it to the same kernels.
BLAS_KERNELS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("Prescott", ("SSE3",)),
    ("Nehalem", ("SSE42",)),
    ("Sandybridge", ("AVX",)),
    ("Haswell", ("AVX2", "FMA3")),
    ("Zen", ("AVX2", "FMA3")),
    ("SkylakeX", ("AVX512F", "AVX512CD", "AVX512BW", "AVX512DQ", "AVX512VL")),
)
#: The variables an environment sets; a run of the ensemble clears them first, so that the caller's own do not leak
#: into the default environment.
VARIABLES = ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", "OPENBLAS_NUM_THREADS")
#: Errors of a kernel-sensitive run: (case label, check) -> error.
Errors = dict[tuple[str, str], float]


@dataclass(frozen=True)
class Environment:
    """A process environment: ``label`` (how tables name it) and the ``variables`` it sets."""

    label: str
    variables: Mapping[str, str] = field(default_factory=dict)


DEFAULT = Environment("default")


def _multiarray() -> Any:
    """numpy's ``_multiarray_umath`` (``numpy._core`` from numpy 2, ``numpy.core`` before)."""
    try:
        return importlib.import_module("numpy._core._multiarray_umath")
    except ImportError:
        return importlib.import_module("numpy.core._multiarray_umath")


def cpu_features() -> dict[str, bool]:
    """numpy's table of this CPU's features (``__cpu_features__``)."""
    return dict(_multiarray().__cpu_features__)


def runnable_kernels(features: Mapping[str, bool] | None = None) -> tuple[str, ...]:
    """The :data:`BLAS_KERNELS` whose instructions this CPU (or ``features``) has; none off x86-64."""
    if features is None:
        features = cpu_features()
    if not features.get("SSE3"):
        return ()
    return tuple(name for name, needs in BLAS_KERNELS if all(features.get(f) for f in needs))


def numpy_dispatched() -> tuple[str, ...]:
    """The SIMD targets numpy dispatches to on this CPU above its baseline (what ``NPY_DISABLE_CPU_FEATURES`` can
    take away)."""
    features = cpu_features()
    return tuple(name for name in _multiarray().__cpu_dispatch__ if features.get(name))


def numpy_levels(dispatched: Sequence[str] | None = None) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """numpy's dispatch levels this CPU offers, each as (label, the dispatched targets it disables): the CPU's own
    (label ``""``, nothing disabled), AVX2 (every AVX-512 target disabled; where numpy dispatches both above and at
    AVX2) and numpy's baseline (every dispatched target disabled; where numpy dispatches to anything)."""
    if dispatched is None:
        dispatched = numpy_dispatched()
    above_avx2 = tuple(t for t in dispatched if "AVX512" in t or t == "X86_V4")
    levels: list[tuple[str, tuple[str, ...]]] = [("", ())]
    if above_avx2 and len(above_avx2) < len(dispatched):
        levels.append(("numpy AVX2", above_avx2))
    if dispatched:
        levels.append(("numpy baseline", tuple(dispatched)))
    return tuple(levels)


def ensemble() -> tuple[Environment, ...]:
    """The environments this machine can emulate: the default, every runnable OpenBLAS kernel with numpy at each of
    its dispatch levels (:func:`numpy_levels`; the cross product, as a CPU picks both), and the default with one BLAS
    thread."""
    out = [DEFAULT]
    for kernel in runnable_kernels():
        for level, disabled in numpy_levels():
            variables = {"OPENBLAS_CORETYPE": kernel, **({"NPY_DISABLE_CPU_FEATURES": " ".join(disabled)}
                                                          if disabled else {})}
            out.append(Environment(", ".join(x for x in (f"OPENBLAS_CORETYPE={kernel}", level) if x), variables))
    if not runnable_kernels():
        out += [Environment(level, {"NPY_DISABLE_CPU_FEATURES": " ".join(disabled)})
                for level, disabled in numpy_levels() if disabled]
    out.append(Environment("OPENBLAS_NUM_THREADS=1", {"OPENBLAS_NUM_THREADS": "1"}))
    return tuple(out)


def margins_command(labels: Sequence[str]) -> list[str]:
    """``mjpoincare margins --base-only --json -`` on the cases ``labels``, by this interpreter."""
    return [sys.executable, "-m", "mjpoincare.cli", "margins", "--base-only", "--json", "-",
            *(arg for label in labels for arg in ("--case", label))]


def start_environment(environment: Environment, labels: Sequence[str], *,
                      command: Callable[[Sequence[str]], list[str]] = margins_command) -> subprocess.Popen[str]:
    """Start the gate cases ``labels`` in a new process with ``environment``'s variables (and none of
    :data:`VARIABLES` the caller has set otherwise); ``command`` builds its command line (the margins command by
    default). :func:`read_environment` waits for it."""
    env = {k: v for k, v in os.environ.items() if k not in VARIABLES}
    env.update(environment.variables)
    return subprocess.Popen(command(labels), env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def read_environment(process: subprocess.Popen[str], environment: Environment, labels: Sequence[str]) -> Errors:
    """The errors a :func:`start_environment` process gives, once it ends: (case, check) -> error. Raises
    RuntimeError with the process's last lines when it fails to give a margins table (an exit of 1, some check not
    held, still gives one)."""
    stdout, stderr = process.communicate()
    try:
        rows = json.loads(stdout)["rows"]
    except (ValueError, KeyError):
        tail = "\n".join((stderr or stdout).strip().splitlines()[-5:])
        raise RuntimeError(f"{environment.label}: margins exited {process.returncode} without its table:\n{tail}"
                           ) from None
    wanted = set(labels)
    return errors_of(r for r in rows if r["case"] in wanted)


def errors_of(rows: Iterable[Mapping[str, Any]]) -> Errors:
    """A margins JSON's rows as (case, check) -> error (NaN where the JSON has none)."""
    return {(r["case"], r["check"]): math.nan if r["error"] is None else float(r["error"]) for r in rows}


def run_environment(environment: Environment, labels: Sequence[str], *,
                    command: Callable[[Sequence[str]], list[str]] = margins_command) -> Errors:
    """The gate cases ``labels`` run in a new process with ``environment``'s variables: (case, check) -> error
    (:func:`start_environment`, then :func:`read_environment`)."""
    return read_environment(start_environment(environment, labels, command=command), environment, labels)


def run_ensemble(environments: Iterable[Environment], labels: Sequence[str], *, workers: int = 2
                 ) -> dict[str, Errors]:
    """:func:`run_environment` for each environment, ``workers`` processes at a time: label -> errors."""
    envs = list(environments)
    with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        found = pool.map(lambda e: run_environment(e, labels), envs)
        return {e.label: errors for e, errors in zip(envs, found, strict=True)}
