"""The installed distribution's version (``mjpoincare.__version__``, ``--version`` and the result documents)."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    VERSION = version("mjpoincare")
except PackageNotFoundError:  # a source tree on sys.path, not installed
    VERSION = "0+unknown"
