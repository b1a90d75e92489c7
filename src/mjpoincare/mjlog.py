"""Capture MuJoCo's warnings instead of leaving them in the user's folder.

MuJoCo's default warning handler prints to the process's stdout and appends to
``MUJOCO_LOG.TXT`` in the current directory, from whatever (C++) thread raised it. While a
simulation runs under :func:`captured_mujoco_log`, the working directory is a private temporary
folder and file descriptors 1 and 2 point at a temporary file; both are read back into the
returned list afterwards. This keeps ``--json -`` output clean and leaves no file behind.
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path


@contextlib.contextmanager
def captured_mujoco_log() -> Iterator[list[str]]:
    """Context manager yielding a list that receives MuJoCo's warning lines on exit."""
    lines: list[str] = []
    cwd = Path.cwd()
    with tempfile.TemporaryDirectory(prefix="mjpoincare-") as tmp:
        sys.stdout.flush()
        sys.stderr.flush()
        capture_path = Path(tmp) / "stdio.txt"
        saved = [os.dup(1), os.dup(2)]
        with open(capture_path, "wb") as capture:
            os.dup2(capture.fileno(), 1)
            os.dup2(capture.fileno(), 2)
            os.chdir(tmp)
            try:
                yield lines
            finally:
                os.chdir(cwd)
                os.dup2(saved[0], 1)
                os.dup2(saved[1], 2)
                for fd in saved:
                    os.close(fd)
        log = Path(tmp) / "MUJOCO_LOG.TXT"
        text = log.read_text(errors="replace") if log.is_file() else ""
        printed = capture_path.read_text(errors="replace")
        seen = set()
        for line in (text + "\n" + printed).splitlines():
            line = line.strip()
            # the log file stamps each line with a date; the printed copy does not: keep one of each
            key = line.split(": ", 1)[-1]
            if line and key not in seen:
                seen.add(key)
                lines.append(line)
