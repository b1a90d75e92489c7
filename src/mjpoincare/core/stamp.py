"""The stamp of a generated page: the environment a run happened in (MuJoCo, numpy, scipy, Python, platform, CPU,
git commit and whether the tree was clean, date) and the table the pages print it as."""

from __future__ import annotations

import os
import platform
import subprocess
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path
from typing import Any

from mjpoincare.analysis.tables import markdown_table, table_cell


def _git(*args: str) -> str:
    """``git args`` run in this module's source tree; empty when git or the repository is not there."""
    try:
        out = subprocess.run(["git", *args], cwd=Path(__file__).resolve().parent, capture_output=True, text=True,
                             check=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return ""
    return out.stdout.strip()


def _cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo`` on Linux, else :func:`platform.processor`)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def git_state() -> tuple[str | None, bool]:
    """The commit checked out and whether a tracked file other than the results themselves differs from it (the
    JSON this command writes must not mark the next scenario's run as dirty)."""
    return _git("rev-parse", "HEAD") or None, bool(
        _git("status", "--porcelain", "--untracked-files=no", "--", ".", ":(top,exclude)docs/results"))


def environment() -> dict[str, Any]:
    """The environment a run happens in, as the results pages are stamped with it. ``git_dirty`` is True when a
    tracked file differs from the commit ``git_sha`` (the run then is not that commit's)."""
    import mujoco

    sha, dirty = git_state()
    return {
        "mujoco": mujoco.__version__,
        "numpy": metadata.version("numpy"),
        "scipy": metadata.version("scipy"),
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpu": _cpu_model(),
        "logical_cpus": os.cpu_count(),
        "git_sha": sha,
        "git_dirty": dirty,
        "date": datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
    }


def stamp_table(env: dict[str, Any]) -> str:
    """The run-stamp table of a generated page: MuJoCo, numpy/scipy/Python, git commit, CPU and date."""
    sha = env["git_sha"] or "unknown"
    if env["git_dirty"]:
        sha += " (with uncommitted changes)"
    return markdown_table(("run", None), [
        ("MuJoCo", env["mujoco"]),
        ("numpy / scipy / Python", f"{env['numpy']} / {env['scipy']} / {env['python']}"),
        ("git commit", sha),
        ("CPU", f"{table_cell(env['cpu'])} ({env['logical_cpus']} logical CPUs), {table_cell(env['platform'])}"),
        ("date (UTC)", env["date"]),
    ])
