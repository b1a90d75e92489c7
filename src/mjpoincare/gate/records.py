"""Where the gate's committed records are found: the ensemble measurement (``margins.json``, ``make margins``) and the
regression baseline (``baseline.json``, ``make baseline``).

Both are generated into ``docs/results/gate/`` of the source tree. The distribution ships that folder's two files in
the package, as ``mjpoincare/gate/results/`` (``pyproject.toml``'s ``package-dir``), so a command finds them through
the package: from an installed wheel there, from a checkout (an editable install) in its ``docs/results/gate/``.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

#: The record files.
BASELINE = "baseline.json"
MARGINS = "margins.json"
#: The folder of the records in the installed package, and in the source tree (relative to its root).
PACKAGED = "results"
SOURCE = Path("docs/results/gate")


def committed(name: str) -> Path:
    """The committed record ``name`` (:data:`BASELINE` or :data:`MARGINS`): the installed package's copy, or the
    checkout's where the package is the source tree."""
    packaged = Path(str(resources.files("mjpoincare.gate").joinpath(PACKAGED, name)))
    return packaged if packaged.is_file() else Path(__file__).resolve().parents[3] / SOURCE / name
