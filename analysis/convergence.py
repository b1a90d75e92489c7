"""Observed order of accuracy, Richardson extrapolation and the grid convergence index (numpy/scipy only).

A ladder of step sizes ``h_1 < h_2 < ... < h_N`` (index 1 the finest, as in Celik et al. 2008) gives values
``f_i`` of one scalar quantity. Asymptotically ``f_i = f_inf + C h_i^p``.

Three-grid method (Roache 1994, 1998; Celik et al. 2008; ASME V&V 20-2009). With ``eps21 = f2 - f1``,
``eps32 = f3 - f2`` and ``r21 = h2/h1``, ``r32 = h3/h2``, the order ``p`` solves

    eps32 / eps21 = r21^p (r32^p - 1) / (r21^p - 1),

which is Celik et al.'s apparent-order equation (``p = ln|eps32/eps21| / ln r21 + q(p) / ln r21`` with
``q = ln((r21^p - s)/(r32^p - s))``) for ``s = +1``, solved here by bracketing (Brent) instead of their fixed-point
iteration; for a constant ratio ``r`` it is ``p = ln(eps32/eps21) / ln r``. The ratio's sign and size classify the
ladder: ``eps32/eps21 < 0`` is oscillatory, a solution ``p <= 0`` is divergent, else monotone. The Richardson value
is ``f_inf = (r21^p f1 - f2) / (r21^p - 1)`` (Celik et al.'s extrapolated value) and the fine-grid GCI, as an
absolute band in the units of ``f``, is ``Fs |eps21| / (r21^p - 1)`` (Roache 1994; Celik et al.'s GCI_fine is the
same divided by ``|f1|``).

Safety factor rule (Roache 1998; ASME V&V 20-2009):

- monotone with ``p`` in :data:`SANE_ORDER` = [0.5, 4]: ``Fs = 1.25`` (three or more grids, observed order used);
- monotone with ``p`` outside that range: ``Fs = 3`` and ``p`` replaced by the formal order (1: MuJoCo's
  integrators and its soft contact are first order in the step and the time constant) above the range, by the
  range's lower end below it (a slower order must not narrow the band); the result's ``note`` says so;
- oscillatory or divergent: no order; the verdict is "does not converge in range", with the noise floor.

Least squares over the whole ladder (``N >= 4``): ``f = f_inf + C h^p`` by ``scipy.optimize.curve_fit``; the
square roots of its covariance's diagonal are the uncertainties of ``p`` and ``f_inf`` (with three points the fit is
exact and has none). Separately, the error against the analytic value is fitted as ``|f - f_an| = C h^q`` on a
log-log line (the slope drawn in convergence plots); ``q`` equals ``p`` only when ``f_inf = f_an``.

Noise floor (for a ladder that does not converge): the values are fitted by ``f = a + b h`` (the formal order);
the floor is the root mean square of the residuals of the three finest values, and its scaling the slope of
``log |residual|`` against ``log h`` over the ladder (four points or more).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum

import numpy as np
from scipy.optimize import OptimizeWarning, brentq, curve_fit

FORMAL_ORDER = 1.0
SANE_ORDER = (0.5, 4.0)
FS_CLEAN, FS_NOISY = 1.25, 3.0
#: Rounding allowance of an analytic value, relative to max(|value|, 1): the extrapolated value is "at" the analytic
#: one when it is within its GCI band plus this floor.
ANALYTIC_FLOOR = 1e-9
_ORDER_BRACKET = (-30.0, 30.0)


class Verdict(str, Enum):
    """What a ladder converges to."""

    ANALYTIC = "converges to analytic"
    OTHER = "converges to another value"
    NONE = "does not converge in range"


@dataclass(frozen=True)
class ThreeGrid:
    """Celik et al. (2008) three-grid estimate from the three finest grids.

    Attributes:
        pattern: ``monotone``, ``oscillatory``, ``divergent`` or ``constant`` (the three values equal to the floor).
        observed_order: the solved ``p`` (NaN unless monotone or divergent).
        order: the ``p`` used for the extrapolation and the band (see the module's safety factor rule).
        safety_factor: ``Fs`` (NaN when there is no band).
        ratio_fine: ``r21 = h2 / h1``.
        ratio_coarse: ``r32 = h3 / h2``.
        extrapolated: the Richardson value ``f_inf`` (the finest value ``f1`` where there is no order).
        gci: the fine-grid band ``Fs |eps21| / (r21^p - 1)`` in the units of ``f``.
        note: how the order and the safety factor were chosen.
    """

    pattern: str
    observed_order: float
    order: float
    safety_factor: float
    ratio_fine: float
    ratio_coarse: float
    extrapolated: float
    gci: float
    note: str


@dataclass(frozen=True)
class PowerFit:
    """Least-squares fit ``f = f_inf + C h^p`` over the whole ladder (NaN where it is not defined: fewer than four
    points, a failed fit, or values constant to the floor)."""

    order: float
    order_stderr: float
    extrapolated: float
    extrapolated_stderr: float


@dataclass(frozen=True)
class Convergence:
    """Everything :func:`analyze` reports for one quantity on one ladder.

    Attributes:
        h: step sizes, finest first.
        values: the simulated values in the same order.
        analytic: the analytic value.
        three_grid: the three-grid estimate (order, Richardson value, GCI band).
        fit: the least-squares fit over all points (order and limit with uncertainties).
        error_slope: slope ``q`` of ``log |f - f_an|`` against ``log h`` (NaN with fewer than two nonzero errors).
        error_slope_stderr: its standard error (NaN with fewer than three).
        bias: ``f_inf - analytic`` (the three-grid Richardson value).
        band: the GCI band plus the analytic floor (what the bias is judged against).
        noise_floor: root mean square residual of the three finest values about ``f = a + b h``.
        noise_exponent: slope of ``log |residual|`` against ``log h`` (how the noise scales with the step).
        verdict: :class:`Verdict`.
    """

    h: tuple[float, ...]
    values: tuple[float, ...]
    analytic: float
    three_grid: ThreeGrid
    fit: PowerFit
    error_slope: float
    error_slope_stderr: float
    bias: float
    band: float
    noise_floor: float
    noise_exponent: float
    verdict: Verdict


def _ratio_model(p: float, h1: float, h2: float, h3: float) -> float:
    """``(h3^p - h2^p) / (h2^p - h1^p)``: eps32/eps21 of ``f = f_inf + C h^p`` (its p -> 0 limit at 0)."""
    if abs(p) < 1e-12:
        return math.log(h3 / h2) / math.log(h2 / h1)
    return (h3**p - h2**p) / (h2**p - h1**p)


def solve_order(h1: float, h2: float, h3: float, ratio: float) -> float:
    """The order ``p`` with ``eps32/eps21 = ratio`` on steps ``h1 < h2 < h3`` (Celik et al. 2008, s = +1).

    The model ratio increases monotonically in ``p``; a ``ratio`` outside its range on :data:`_ORDER_BRACKET`
    gives the bracket's end (an order beyond +-30 is indistinguishable from it)."""
    low, high = _ORDER_BRACKET
    lo_val, hi_val = _ratio_model(low, h1, h2, h3), _ratio_model(high, h1, h2, h3)
    if ratio <= lo_val:
        return low
    if ratio >= hi_val:
        return high
    return float(brentq(lambda p: _ratio_model(p, h1, h2, h3) - ratio, low, high, xtol=1e-12))


def three_grid(h: Sequence[float], f: Sequence[float], floor: float = 0.0) -> ThreeGrid:
    """Celik et al. (2008) order and extrapolation, and the GCI, on the three finest of ``h`` (finest first), with
    the safety factor rule of the module docstring. Differences at or below ``floor`` count as zero."""
    h1, h2, h3 = (float(x) for x in h[:3])
    f1, f2, f3 = (float(x) for x in f[:3])
    r21, r32 = h2 / h1, h3 / h2
    eps21, eps32 = f2 - f1, f3 - f2
    if abs(eps21) <= floor and abs(eps32) <= floor:
        return ThreeGrid("constant", math.nan, math.nan, math.nan, r21, r32, f1, 0.0,
                         f"the three finest values agree to {floor:.2g}")
    if abs(eps21) <= floor:
        return ThreeGrid("oscillatory", math.nan, math.nan, math.nan, r21, r32, f1, math.nan,
                         "eps21 = 0 while eps32 is not: the values cross, no order")
    if eps32 / eps21 < 0:
        return ThreeGrid("oscillatory", math.nan, math.nan, math.nan, r21, r32, f1, math.nan,
                         "eps32/eps21 < 0: oscillatory (Celik s = -1); no order")
    observed = solve_order(h1, h2, h3, eps32 / eps21)
    if observed <= 0:
        return ThreeGrid("divergent", observed, math.nan, math.nan, r21, r32, f1, math.nan,
                         f"observed order {observed:.3g} <= 0: the change grows under refinement")
    low, high = SANE_ORDER
    if low <= observed <= high:
        order, fs, note = observed, FS_CLEAN, f"observed order in [{low:g}, {high:g}]: Fs = {FS_CLEAN:g}"
    else:
        order = FORMAL_ORDER if observed > high else low
        fs = FS_NOISY
        note = (f"observed order {observed:.3g} outside [{low:g}, {high:g}]: p = {order:g} "
                f"({'formal order' if observed > high else 'lower bound'}), Fs = {FS_NOISY:g}")
    gain = r21**order - 1.0
    return ThreeGrid("monotone", observed, order, fs, r21, r32, (r21**order * f1 - f2) / gain,
                     fs * abs(eps21) / gain, note)


def power_fit(h: Sequence[float], f: Sequence[float], p0: float) -> PowerFit:
    """Least squares ``f = f_inf + C h^p`` from the start order ``p0``; uncertainties from the covariance (NaN with
    fewer than four points or when the fit fails)."""
    nan = PowerFit(math.nan, math.nan, math.nan, math.nan)
    if len(h) < 4:
        return nan
    hs, fs = np.asarray(h, float), np.asarray(f, float)
    scale = hs[0]

    def model(x: np.ndarray, f_inf: float, c: float, p: float) -> np.ndarray:
        return f_inf + c * (x / scale) ** p

    start_p = p0 if math.isfinite(p0) and p0 > 0 else FORMAL_ORDER
    slope = (fs[-1] - fs[0]) / ((hs[-1] / scale) ** start_p - 1.0)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            popt, pcov = curve_fit(model, hs, fs, p0=[fs[0] - slope, slope, start_p], maxfev=10_000)
    except (RuntimeError, ValueError):
        return nan
    err = np.sqrt(np.abs(np.diag(pcov))) if np.all(np.isfinite(pcov)) else np.full(3, math.nan)
    return PowerFit(float(popt[2]), float(err[2]), float(popt[0]), float(err[0]))


def log_slope(h: Sequence[float], y: Sequence[float]) -> tuple[float, float]:
    """Slope of ``log |y|`` against ``log h`` over the nonzero ``y``, and its standard error (NaN where the points
    are too few: two for the slope, three for its error)."""
    ys = np.abs(np.asarray(y, float))
    keep = ys > 0
    if keep.sum() < 2:
        return math.nan, math.nan
    x, z = np.log(np.asarray(h, float)[keep]), np.log(ys[keep])
    slope, intercept = np.polyfit(x, z, 1)
    if keep.sum() < 3:
        return float(slope), math.nan
    resid = z - (slope * x + intercept)
    stderr = math.sqrt(float(resid @ resid) / (len(x) - 2) / float(((x - x.mean()) ** 2).sum()))
    return float(slope), stderr


def noise(h: Sequence[float], f: Sequence[float]) -> tuple[float, float]:
    """Noise floor (RMS residual of the three finest values about ``f = a + b h``) and its scaling exponent (NaN
    with three points: their residuals about a line have a fixed pattern, so the exponent would be an artefact)."""
    hs, fs = np.asarray(h, float), np.asarray(f, float)
    b, a = np.polyfit(hs, fs, 1)
    resid = fs - (a + b * hs)
    floor = float(np.sqrt(np.mean(resid[:3] ** 2)))
    return floor, log_slope(hs, resid)[0] if len(hs) >= 4 else math.nan


def analyze(h: Sequence[float], values: Sequence[float], analytic: float,
            analytic_floor: float = ANALYTIC_FLOOR) -> Convergence:
    """Order, Richardson value, GCI band and verdict of ``values`` on the ladder ``h`` (any order of points).

    The verdict: "converges to analytic" when the ladder converges (monotone, or constant to the floor) and
    ``|f_inf - analytic| <= GCI + floor``; "converges to another value" when it converges but the bias exceeds that;
    "does not converge in range" when it is oscillatory or divergent (then read ``noise_floor`` and
    ``noise_exponent``). ``floor = analytic_floor * max(|analytic|, 1)``.

    Raises:
        ValueError: fewer than three points, a step size <= 0 or repeated, or a non-finite value.
    """
    if len(h) != len(values) or len(h) < 3:
        raise ValueError(f"need >= 3 (step, value) pairs (got {len(h)} steps, {len(values)} values)")
    order = np.argsort(np.asarray(h, float))
    hs, fs = np.asarray(h, float)[order], np.asarray(values, float)[order]
    if not (np.all(np.isfinite(hs)) and hs[0] > 0 and np.all(np.diff(hs) > 0)):
        raise ValueError(f"step sizes must be finite, > 0 and distinct (got {list(hs)})")
    if not np.all(np.isfinite(fs)) or not math.isfinite(analytic):
        raise ValueError(f"values and the analytic value must be finite (got {list(fs)}, {analytic})")
    floor = analytic_floor * max(abs(analytic), 1.0)
    tg = three_grid(hs, fs, floor)
    fit = power_fit(hs, fs, tg.observed_order) if tg.pattern != "constant" else PowerFit(*[math.nan] * 4)
    slope, slope_err = log_slope(hs, fs - analytic)
    noise_floor, noise_exponent = noise(hs, fs)
    bias = tg.extrapolated - float(analytic)
    band = tg.gci + floor
    if tg.pattern in ("monotone", "constant"):
        verdict = Verdict.ANALYTIC if abs(bias) <= band else Verdict.OTHER
    else:
        verdict = Verdict.NONE
    return Convergence(h=tuple(hs.tolist()), values=tuple(fs.tolist()), analytic=float(analytic), three_grid=tg,
                       fit=fit, error_slope=slope, error_slope_stderr=slope_err, bias=bias, band=band,
                       noise_floor=noise_floor, noise_exponent=noise_exponent, verdict=verdict)
