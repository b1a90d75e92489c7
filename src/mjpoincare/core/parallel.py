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

A resumable run (a sweep's values, a convergence ladder's rungs) keeps its rows in a results file,
:class:`ResumableRows`: the rows a previous run of it left there are kept on ``--resume``, and the file is rewritten
whole after every finished job, so an interruption loses at most the jobs in flight.
"""

from __future__ import annotations

import os
import signal
import sys
from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from multiprocessing import get_context
from typing import Any

from mjpoincare.analysis.checks import jsonable
from mjpoincare.core import progress
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import resumed_rows, write_json

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


def check_engine(workers: int, engine: str, scheduler: str | None = None) -> None:
    """Refuse a worker count below 1, an unknown engine, or a scheduler for an engine that has none."""
    if workers < 1 or engine not in ENGINES:
        raise ParameterError(f"--workers must be >= 1 and --engine one of {', '.join(ENGINES)} "
                             f"(got {workers}, {engine!r})")
    if scheduler is not None and engine != "dask":
        raise ParameterError(f"--scheduler {scheduler} is the Dask engine's: give --engine dask "
                             f"(got --engine {engine})")


def run_jobs(fn: Callable[..., Any], jobs: Sequence[tuple[Any, ...]], *, workers: int = 1, engine: str = "local",
             scheduler: str | None = None) -> Iterator[Any]:
    """``fn(*job)`` for every job (``fn`` must be a module-level function), yielded in completion order."""
    check_engine(workers, engine, scheduler)
    if engine == "dask":
        yield from _dask(fn, jobs, workers, scheduler)
    elif workers == 1 or len(jobs) <= 1:
        for job in jobs:
            yield fn(*job)
    else:
        pool = ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=get_context(start_method()),
                                   initializer=_leave_interrupts_to_the_parent)
        try:
            futures = [pool.submit(fn, *job) for job in jobs]
            for future in as_completed(futures):
                yield future.result()
        except BaseException:  # Ctrl-C, an error, or the consumer stopped early: the workers stop now, not later
            for process in list(getattr(pool, "_processes", {}).values()):
                process.terminate()
            pool.shutdown(wait=False, cancel_futures=True)
            raise
        pool.shutdown()


def _leave_interrupts_to_the_parent() -> None:
    """A worker process ignores Ctrl-C (SIGINT reaches the whole process group): the parent stops the pool and says so
    in one line, instead of every worker printing its own KeyboardInterrupt traceback."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


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


Row = dict[str, Any]


@dataclass
class ResumableRows:
    """The rows of a resumable run and its results file (the rows under ``"rows"``, after the header).

    Attributes:
        header: what identifies the run (scenario, parameter, assignments, preset, ...): every write of the file
            starts with it, and a file with another header is refused on resume.
        path: the results file (None or ``-``: nothing is written while the run goes).
        key: the row field that identifies a row (the swept value, the rung).
        keys: the wanted rows' keys, in the order :meth:`ordered` lists the rows.
        rows: key -> row: the resumed rows, then each finished one.
    """

    header: dict[str, Any]
    path: str | None
    key: str
    keys: list[Hashable]
    rows: dict[Hashable, Row] = field(default_factory=dict)

    @classmethod
    def open(cls, header: Mapping[str, Any], path: str | None, key: str, keys: Iterable[Hashable], *, resume: bool,
             restore: Callable[[Row], Row] | None = None) -> ResumableRows:
        """A run of the rows ``keys`` (duplicates once), holding the rows ``path`` has of them when ``resume``.

        Args:
            header: as the attribute.
            path: the results file (needed when ``resume``).
            key: as the attribute.
            keys: the wanted rows' keys, in order.
            resume: keep the rows a previous run of the same header left in ``path``.
            restore: applied to each resumed row (e.g. JSON null back to NaN).

        Returns:
            The run, its :attr:`todo` the keys without a row.

        Raises:
            ParameterError: ``resume`` without a file, a file that cannot be read or one of another run.
        """
        if resume and (not path or path == "-"):
            raise ParameterError("--resume needs --json PATH (the results file to resume from)")
        wanted = list(dict.fromkeys(keys))
        held = resumed_rows(path, dict(header)) if resume else []
        rows = {row[key]: restore(row) if restore else row for row in held if row[key] in set(wanted)}
        return cls(dict(header), path, key, wanted, rows)

    @property
    def todo(self) -> list[Hashable]:
        """The wanted keys with no row yet, in order."""
        return [k for k in self.keys if k not in self.rows]

    def ordered(self) -> list[Row]:
        """The rows held, in the order of :attr:`keys`."""
        return [self.rows[k] for k in self.keys if k in self.rows]

    def run(self, fn: Callable[..., Row | list[Row]], jobs: Sequence[tuple[Any, ...]], *, label: str, unit: str,
            describe: Callable[[list[Row]], str], workers: int = 1, engine: str = "local",
            scheduler: str | None = None) -> list[Row]:
        """Run ``jobs`` (:func:`run_jobs`) and keep their rows: after each finished job, rewrite the results file whole
        and advance the progress bar over :attr:`keys` by its rows.

        Args:
            fn: module-level function, ``fn(*job)`` -> one row or a list of rows, each with its :attr:`key`.
            jobs: the arguments of each call (for the keys in :attr:`todo`).
            label: the progress bar's label.
            unit: what the bar counts (one per row).
            describe: the bar's note on a finished job, from its rows.
            workers: jobs run at once (processes, or Dask workers).
            engine: ``local`` or ``dask``.
            scheduler: a running Dask scheduler's address (None: a local cluster).

        Returns:
            Every row held, in the order of :attr:`keys`.
        """
        with progress.bar(len(self.keys), label, unit=unit, initial=len(self.rows)) as bar:
            for result in run_jobs(fn, jobs, workers=workers, engine=engine, scheduler=scheduler):
                new = result if isinstance(result, list) else [result]
                self.rows.update({row[self.key]: row for row in new})
                if self.path and self.path != "-":
                    write_json(jsonable({**self.header, "rows": self.ordered()}), self.path)
                bar.set_postfix_str(describe(new))
                bar.update(len(new))
        return self.ordered()
