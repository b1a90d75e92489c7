"""Capture MuJoCo's warnings into the run's result, leaving the caller's process as it was.

MuJoCo's default warning handler prints to stdout and appends to ``MUJOCO_LOG.TXT`` in the current directory. While
at least one :func:`captured_mujoco_log` is open, MuJoCo's settable warning callback (``mju_user_warning``) is
pointed at a handler that hands each message to every open capture; when the last capture closes, the handler that
was set before (e.g. dm_control's, which logs) is restored. The previous handler is not called meanwhile: MuJoCo
raises warnings from its rollout worker threads, where an exception from foreign code would abort the process
(dm_control's ctypes handler raises when called from Python), and the run's result is where its warnings belong.
No working directory, file descriptor or stream is touched, and no file is written. MuJoCo also counts warnings per
``MjData`` (``data.warning``), which :mod:`mjpoincare.simulation.simulate` reads for each rollout's own data.

The callback is process-wide and MuJoCo raises it from its rollout worker threads, which do not say which
validation they serve: a message raised while two validations run in one process reaches both captures.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable, Iterator

import mujoco

_lock = threading.Lock()
_open: dict[int, list[str]] = {}
_previous: list[Callable[[str], None] | None] = []


def _handler(message: str) -> None:
    line = f"WARNING: {str(message).strip()}"
    with _lock:
        for sink in _open.values():
            if line not in sink:
                sink.append(line)


@contextlib.contextmanager
def captured_mujoco_log() -> Iterator[list[str]]:
    """Context manager yielding the list that receives MuJoCo's warning messages raised while it is open."""
    lines: list[str] = []
    with _lock:
        if not _open:
            _previous[:] = [mujoco.get_mju_user_warning()]
            mujoco.set_mju_user_warning(_handler)
        _open[id(lines)] = lines
    try:
        yield lines
    finally:
        with _lock:
            del _open[id(lines)]
            if not _open:
                mujoco.set_mju_user_warning(_previous[0] if _previous else None)
                _previous.clear()
