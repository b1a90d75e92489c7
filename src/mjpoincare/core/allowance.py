"""How far two runs of one check may differ: the one rule every comparison of two runs uses.

Two runs of a check (this CPU and a second BLAS kernel, this run and the recorded baseline, a declared miss and the
run that measured it, a watched check's declared spread and today's) differ through rounding: the BLAS kernel and
numpy's SIMD dispatch a CPU picks, the thread count, the last bits of the starts. The suite measures that difference
over an ensemble of environments one machine can emulate (``mjpoincare margins``), and allows

    allowance = max(MULTIPLE x spread, FLOOR x tolerance, ROUNDOFF x max(1, |error|))

- ``spread`` is the measured largest change of the check's error over the ensemble (its resolution);
- :data:`MULTIPLE` is the safety factor for an environment the ensemble did not sample. The spread is a sample's
  maximum; the margins page (``make margins``) leaves each environment of the ensemble out in turn (the cross
  product of OpenBLAS kernels, numpy dispatch levels and BLAS threads) and tables how far it landed from the
  reference run, in allowances of the others: the largest such ratio must stay well under 1;
- :data:`FLOOR` ties the allowance to what the check means: a change smaller than a millionth of its tolerance is
  one its own units cannot express (a verdict's margin moves by 1e-4 %), so it never fails CI however small the
  measured spread (a spread at the 1e-14 roundoff floor would otherwise make every last-bit change of MuJoCo or of
  the CPU a failure);
- :data:`ROUNDOFF` keeps a check with no tolerance (a count, a verdict) from an allowance of 0 in its own units.
"""

from __future__ import annotations

import math

#: The allowance's multiple of the measured spread: an environment left out of the ensemble must land within it, with
#: room for what no emulation reaches (another MuJoCo build, another architecture); the margins page measures it.
MULTIPLE = 3.0
#: The allowance's floor, as a fraction of the check's tolerance.
FLOOR = 1e-6
#: The allowance of a check with no tolerance, relative to max(1, |error|): double rounding's scale.
ROUNDOFF = 1e-12


def floor(tolerance: float, error: float = 0.0) -> float:
    """The smallest allowance a check is held to: :data:`FLOOR` of its ``tolerance``, at least :data:`ROUNDOFF` of
    max(1, |``error``|)."""
    scale = abs(error) if math.isfinite(error) else 1.0
    by_tolerance = FLOOR * tolerance if math.isfinite(tolerance) and tolerance > 0 else 0.0
    return max(by_tolerance, ROUNDOFF * max(1.0, scale))


def allowance(spread: float, tolerance: float, error: float = 0.0) -> float:
    """How far two runs of a check may set its error apart: :data:`MULTIPLE` x its measured ``spread``, never below
    :func:`floor` (inf where the spread is: a check whose error jitter made non-finite)."""
    if math.isnan(spread):
        return math.inf
    return max(MULTIPLE * spread, floor(tolerance, error))


def set_by_floor(spread: float, tolerance: float, error: float = 0.0) -> bool:
    """Whether the floor, not the spread, sets the check's allowance."""
    return MULTIPLE * spread < floor(tolerance, error)
