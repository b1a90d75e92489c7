"""Independent jobs (sweep points, stress cases) spread over processes or a Dask cluster.

``mujoco.rollout`` already threads across the initial states of one job; this module runs whole jobs
side by side, for work a single rollout cannot batch (different models, Python event controllers).
Local jobs run in worker processes: ``fork``-ed on Linux, so that a worker starts with the parent's modules
already imported (``spawn`` re-imports numpy, scipy, mujoco in every worker: 1-2 s each, measured), which is
safe because the rollout thread pools live only inside ``with Rollout(...)`` blocks, never across a call to
:func:`run_jobs`; ``spawn``-ed elsewhere (macOS and Windows cannot fork safely), and on Linux too once a library
that keeps native threads of its own is loaded (JAX, Warp: the MJX and Warp backends), since forking a
multithreaded process can deadlock the child. With
``engine="dask"`` they go to a Dask cluster: ``scheduler`` names a running one, or a local cluster of
``workers`` processes is started for the call. Results are yielded as jobs finish.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Any

from mjpoincare.params import ParameterError

ENGINES = ("local", "dask")
#: Modules that start native threads when imported: a process holding them is not forked.
THREADED_MODULES = ("jax", "jaxlib", "warp")


def machine_cores() -> int:
    """The cores this process may run on (its CPU affinity where the system reports one, else the CPU count)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def start_method() -> str:
    """``fork`` on Linux while no :data:`THREADED_MODULES` is loaded in this process, ``spawn`` otherwise."""
    threaded = any(name in sys.modules for name in THREADED_MODULES)
    return "fork" if sys.platform.startswith("linux") and not threaded else "spawn"


def check_engine(workers: int, engine: str) -> None:
    """Refuse a worker count below 1 or an unknown engine."""
    if workers < 1 or engine not in ENGINES:
        raise ParameterError(f"--workers must be >= 1 and --engine one of {', '.join(ENGINES)} "
                             f"(got {workers}, {engine!r})")


def run_jobs(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], *, workers: int = 1, engine: str = "local",
             scheduler: str | None = None) -> Iterator[Any]:
    """``fn(*job)`` for every job (``fn`` must be a module-level function), yielded in completion order."""
    check_engine(workers, engine)
    if engine == "dask":
        yield from _dask(fn, jobs, workers, scheduler)
    elif workers == 1 or len(jobs) <= 1:
        for job in jobs:
            yield fn(*job)
    else:
        with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=get_context(start_method())) as pool:
            futures = [pool.submit(fn, *job) for job in jobs]
            for future in as_completed(futures):
                yield future.result()


def _dask(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], workers: int,
          scheduler: str | None) -> Iterator[Any]:
    try:
        from dask.distributed import Client, LocalCluster
        from dask.distributed import as_completed as dask_completed
    except ImportError:
        raise ParameterError("--engine dask needs the optional extra: pip install 'mjpoincare[dask]'") from None
    cluster = None if scheduler else LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                  dashboard_address=None)
    try:
        with Client(scheduler or cluster) as client:
            futures = [client.submit(fn, *job, pure=False) for job in jobs]
            for future in dask_completed(futures):
                yield future.result()
    finally:
        if cluster is not None:
            cluster.close()


def point_assignments(assignments: Mapping[str, str], workers: int) -> dict[str, str]:
    """Give each of ``workers`` concurrent points its share of the cores, unless threads were set."""
    if workers <= 1 or "threads" in assignments:
        return dict(assignments)
    return {**assignments, "threads": str(max(1, (os.cpu_count() or 1) // workers))}
