"""End-state classification of simulated runs for region-of-attraction maps (numpy only)."""

from __future__ import annotations

import numpy as np

OUTCOMES = ("standing", "rolling", "runaway", "flight", "undetermined")


def classify_outcomes(omega: np.ndarray, clearance: np.ndarray, *, rest_speed: float, runaway_speed: float,
                      flight_clearance: float) -> np.ndarray:
    """Classify each run from its final window.

    ``omega`` (B, T) is the pitch rate and ``clearance`` (B, T) the height of the lowest foot over
    the final window. In order of precedence:

    * ``standing``: ``max |omega| < rest_speed`` (the Zeno rocking of 003 Sec. 3.3 has died out);
    * ``runaway``: ``max |omega| > runaway_speed`` (no stance can hold the wheel: for a point-mass hub
      the spoke force ``g cos(theta) - l omega^2`` is negative for ``omega^2 > g/l``);
    * ``flight``: some time with every foot more than ``flight_clearance`` above the ground;
    * ``rolling``: always rolling downhill (``omega > 0`` throughout the window);
    * ``undetermined`` otherwise (still rocking, rolling uphill, or a diverged run: NaN).
    """
    speed = np.nanmax(np.abs(omega), axis=1)
    out = np.full(omega.shape[0], "undetermined", dtype=object)
    finite = np.isfinite(omega).all(axis=1)
    flew = np.nanmax(clearance, axis=1) > flight_clearance
    rolling = (omega > 0).all(axis=1)
    out[finite & rolling & ~flew] = "rolling"
    out[finite & flew] = "flight"
    out[finite & (speed > runaway_speed)] = "runaway"
    out[finite & (speed < rest_speed)] = "standing"
    return out.astype(str)
