"""``validate --extrapolate``: the Richardson value of every scalar check from three cheap grids.

A validation runs on its preset's timestep h; this adds the two coarser grids 2h and 4h (the contact time constant
scaled with the step, as ``mjpoincare converge``'s timestep ladder holds it at a fixed number of steps), which cost
a half and a quarter of the plain run. Each scalar component of each check is then analysed on the three grids by
:func:`mjpoincare.analysis.convergence.analyze` (Celik et al. 2008 three-grid order and fine-grid GCI; Roache 1998;
ASME V&V 20-2009). Where the order is clean -- monotone convergence with the observed order in
:data:`~mjpoincare.analysis.convergence.SANE_ORDER`, safety factor 1.25 -- the Richardson value and its GCI band are
reported beside the plain value, marked extrapolated; elsewhere the reason there is none. The checks themselves are
the plain run's: an extrapolated value is information, never a verdict.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

from mjpoincare.analysis.checks import Check
from mjpoincare.analysis.convergence import analyze
from mjpoincare.commands.converge import components, ladder_rung
from mjpoincare.commands.validation import resolve_inputs

#: The coarser grids, as multiples of the preset's timestep (and contact time constant).
COARSENING = (2.0, 4.0)
#: The safety factor of a clean three-grid order (Roache; ASME V&V 20-2009): the only one reported as extrapolated.
CLEAN_SAFETY_FACTOR = 1.25


@dataclass(frozen=True)
class Extrapolated:
    """One scalar component's plain and extrapolated values.

    Attributes:
        component: the check (``name``, ``name[i]`` or ``name.re``/``.im``, as ``converge`` names them).
        analytic: the analytic value.
        plain: the value on the preset's grid h.
        extrapolated: the Richardson value from h, 2h, 4h (NaN where the order is not clean).
        band: its fine-grid GCI band (NaN likewise).
        order: the observed three-grid order (NaN where there is none).
        error_plain: |plain - analytic|.
        error_extrapolated: |extrapolated - analytic| (NaN where there is no extrapolated value).
        note: why there is no extrapolated value ("" where there is one).
    """

    component: str
    analytic: float
    plain: float
    extrapolated: float
    band: float
    order: float
    error_plain: float
    error_extrapolated: float
    note: str


def coarse_grids(name: str, assignments: Mapping[str, str], preset: str | None) -> list[dict[str, str]]:
    """The setting overrides of the coarser grids (:data:`COARSENING`), checked like any input (refused with one
    line, before any simulation, where a coarser grid leaves a setting's bounds)."""
    settings = resolve_inputs(name, assignments, preset)[3]
    grids = [{"timestep": f"{float(settings['timestep']) * c:.12g}",
              "solref_timeconst": f"{float(settings['solref_timeconst']) * c:.12g}"} for c in COARSENING]
    for grid in grids:
        resolve_inputs(name, {**assignments, **grid}, preset)
    return grids


def extrapolate(name: str, assignments: Mapping[str, str], preset: str | None, seed: int, checks: Sequence[Check],
                plain_wall_s: float) -> dict[str, Any]:
    """Run the coarser grids of scenario ``name`` and extrapolate every scalar component of the plain run's
    ``checks``; the ``extrapolated`` entry of the result (JSON-ready): the grids, the wall time of all three
    (``plain_wall_s`` for the plain one) and each :class:`Extrapolated`."""
    grids = coarse_grids(name, assignments, preset)
    start = time.perf_counter()
    rows = [ladder_rung(name, grid, assignments, preset, seed) for grid in grids]
    coarse_wall = time.perf_counter() - start
    plain, _ = components(checks)
    h = [1.0, *COARSENING]
    out = []
    for component, (analytic, value) in plain.items():
        ladder = [value, *(row["components"].get(component, [math.nan, math.nan])[1] for row in rows)]
        out.append(asdict(_component(component, float(analytic), [float(v) for v in ladder], h, rows)))
    failed = [row["failed"] for row in rows if row["failed"]]
    return {"grids": [{"timestep": "preset"}, *grids], "wall_s": plain_wall_s + coarse_wall,
            "plain_wall_s": plain_wall_s, "failed_grids": failed, "components": out}


def _component(component: str, analytic: float, ladder: list[float], h: list[float], rows: list[dict[str, Any]]
               ) -> Extrapolated:
    plain = ladder[0]
    nan = math.nan
    bad = [row["failed"] or f"{row['diverged']} diverged" for row in rows if row["failed"] or row["diverged"]]
    if bad or not all(math.isfinite(v) for v in ladder) or not math.isfinite(analytic):
        note = "a coarser grid failed: " + "; ".join(bad) if bad else "a value is not finite"
        return Extrapolated(component=component, analytic=analytic, plain=plain, extrapolated=nan, band=nan,
                            order=nan, error_plain=abs(plain - analytic), error_extrapolated=nan, note=note)
    result = analyze(h, ladder, analytic)
    tg = result.three_grid
    clean = tg.pattern == "monotone" and tg.safety_factor == CLEAN_SAFETY_FACTOR
    note = "" if clean else f"no clean order on h, 2h, 4h ({tg.pattern}; {tg.note})"
    return Extrapolated(component=component, analytic=analytic, plain=plain,
                        extrapolated=tg.extrapolated if clean else nan, band=tg.gci if clean else nan,
                        order=tg.observed_order, error_plain=abs(plain - analytic),
                        error_extrapolated=abs(tg.extrapolated - analytic) if clean else nan, note=note)


def table(entry: Mapping[str, Any]) -> str:
    """The extrapolated values as a person reads them, after the check table."""
    lines = [f"extrapolated (Richardson from timestep h, 2h, 4h; {entry['wall_s']:.2f} s for the three grids, "
             f"{entry['plain_wall_s']:.2f} s for h alone):",
             f"  {'component':<24} {'analytic':>12} {'plain':>12} {'extrapolated':>12} {'band':>9} {'order':>6} "
             f"{'error plain':>11} {'error extr.':>11}"]
    for c in entry["components"]:
        if c["note"]:
            lines.append(f"  {c['component']:<24} {c['analytic']:>12.6g} {c['plain']:>12.6g}  {c['note']}")
            continue
        lines.append(f"  {c['component']:<24} {c['analytic']:>12.6g} {c['plain']:>12.6g} {c['extrapolated']:>12.6g} "
                     f"{c['band']:>9.2g} {c['order']:>6.2f} {c['error_plain']:>11.3g} {c['error_extrapolated']:>11.3g}")
    lines.extend(f"  coarser grid failed: {f}" for f in entry["failed_grids"])
    return "\n".join(lines)
