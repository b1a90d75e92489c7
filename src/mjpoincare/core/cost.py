"""A run's cost before it runs: its MuJoCo steps (from the scenario's own rollout plan) and the memory a chunk
needs, against this machine's memory.

Two checks, both before any step is taken:

* :func:`refuse_long`: the command line refuses a run (or a sweep of runs) of more than :data:`LONG_STEPS` steps
  (:func:`mjpoincare.commands.validation.run_steps`) in one line giving the estimate, unless ``--allow-long`` is given;
* :func:`check_chunk`: every native chunk's arrays are sized before they are allocated; a chunk larger than the
  memory this machine has available is refused in one line giving both, whoever called (the API too).
"""

from __future__ import annotations

import os

from mjpoincare.core.params import ParameterError

#: Steps beyond which the command line asks for ``--allow-long``: about an hour at 3e5 steps/s, the rate of MuJoCo's
#: own stepping of these models measured on a 2-core AMD EPYC (``mjpoincare bench``).
LONG_STEPS = 1e9
#: Bytes per recorded state value (float64), and the arrays of a chunk alive at once (the rollout's states, the
#: chunk with its first row, the divergence mask): 3 arrays of (batch, nstep, nstate) at most.
VALUE_BYTES, CHUNK_ARRAYS = 8, 3
#: Chunks up to this many bytes are not checked (a usual chunk is far smaller; any machine has this much).
SMALL_CHUNK = 256 * 2**20


def available_memory() -> int:
    """Bytes of memory available to a new allocation (``MemAvailable`` of ``/proc/meminfo``; elsewhere the free
    physical pages)."""
    try:
        with open("/proc/meminfo") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def refuse_long(steps: float, what: str, *, allow: bool, remedy: str = "raise timestep, or give --allow-long"
                ) -> None:
    """Refuse ``what`` (e.g. ``"validate rimless-wheel"``) of ``steps`` steps beyond :data:`LONG_STEPS` unless
    ``allow`` (``--allow-long``), in one line with the estimate and ``remedy``."""
    if steps > LONG_STEPS and not allow:
        hours = steps / 3e5 / 3600
        raise ParameterError(f"{what} would take {steps:.3g} MuJoCo steps (about {hours:.3g} h at 3e5 steps/s), "
                             f"more than {LONG_STEPS:.0e}: {remedy}")


def check_chunk(batch: int, nstep: int, nstate: int) -> None:
    """Refuse a native chunk of ``batch`` trajectories x ``nstep`` steps x ``nstate`` values whose arrays would not
    fit in the memory available, before they are allocated, in one line with both sizes."""
    need = CHUNK_ARRAYS * VALUE_BYTES * batch * (nstep + 1) * nstate
    if need <= SMALL_CHUNK:  # every chunk of a usual run: no read of the machine's memory per chunk
        return
    have = available_memory()
    if need > have:
        raise ParameterError(f"timestep: a rollout chunk of {batch} trajectories x {nstep} steps needs "
                             f"{need / 2**30:.3g} GiB, more than the {have / 2**30:.3g} GiB available: raise timestep")
