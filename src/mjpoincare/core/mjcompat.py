"""What differs between the MuJoCo releases the suite admits, in one place: every other module reads MuJoCo through
the names that are the same on all of them, or through this module."""

from __future__ import annotations

import mujoco
import numpy as np


def efc_diag_inverse_inertia(data: mujoco.MjData) -> np.ndarray:
    """MuJoCo's diagonal approximation of the inverse inertia of each constraint row (nefc,), the ``A_ii`` its
    regulariser ``R = (1 - d) / d A_ii`` is built on (MuJoCo docs, "Computation", "Soft contact model"): the field
    ``efc_diagA`` from MuJoCo 3.10 on and ``efc_diagApprox`` before (the same quantity, renamed)."""
    field = data.efc_diagA if hasattr(data, "efc_diagA") else data.efc_diagApprox
    return np.asarray(field)
