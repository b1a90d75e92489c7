"""Independent jobs (sweep points, stress cases) spread over processes or a Dask cluster.

``mujoco.rollout`` already threads across the initial states of one job; this module runs whole jobs
side by side, for work a single rollout cannot batch (different models, Python event controllers).
Local jobs run in ``spawn``-ed processes (MuJoCo's thread pools and a forked parent do not mix); with
``engine="dask"`` they go to a Dask cluster: ``scheduler`` names a running one, or a local cluster of
``workers`` processes is started for the call. Results are yielded as jobs finish.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Any

from mjpoincare.params import ParameterError

ENGINES = ("local", "dask")


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
        with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=get_context("spawn")) as pool:
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
