"""The time between two section crossings at a map's fixed point, regressed on the states the return spans (numpy
only): the step period of a rimless wheel's gait from mid-stance samples (Kiša 2020 Sec. 3, Gamus & Or 2015
eq 16), where no sample lies exactly on the fixed point."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


def period_at(star: float, before: Sequence[np.ndarray], after: Sequence[np.ndarray],
              dts: Sequence[np.ndarray]) -> float:
    """Crossing-to-crossing time at the fixed point ``star``: quadratic least squares in (omega_k, omega_k+1)
    over every trajectory's pairs (``before`` omega_k, ``after`` omega_k+1, ``dts`` the times between them),
    taken at omega_k = omega_k+1 = ``star``."""
    u = np.concatenate(before) - star
    v = np.concatenate(after) - star
    design = np.stack([np.ones_like(u), u, v, u * u, u * v, v * v], axis=1)
    coef, *_ = np.linalg.lstsq(design, np.concatenate(dts), rcond=None)
    return float(coef[0])
