"""``mjpoincare converge``: observed order, Richardson value, GCI band and verdict of every scalar check.

Ladders. Each axis refines one setting from its start value (the preset's, or ``--set``'s) by the ratio ``r``
(default 2), ``points`` times:

- ``timestep``: the step and the contact time constant together (``solref_timeconst = k timestep`` with ``k`` the
  start ratio, so the contact is resolved by the same number of steps on every rung);
- ``solref_timeconst``: the time constant alone, at the ladder's finest timestep (so its finest rung is the
  timestep ladder's finest rung, run once), i.e. the limit of a rigid contact at that fixed step;
- ``solref_dampratio``, ``foot_radius``: that setting alone towards 0, everything else at the start values.

MuJoCo clamps the time constant to at least two steps; a ladder that would reach the clamp is refused. Each rung
is one validation (:func:`mjpoincare.commands.validation.run_validation`); every scalar check, and every component of a
vector or complex check (``name[i]``, ``name.re``/``name.im``; a complex simulated value whose analytic value is
real is compared by its real part), is analysed by :func:`mjpoincare.analysis.convergence.analyze` (Celik et al.
2008 three-grid order and GCI, least-squares order uncertainty; Roache 1998; ASME V&V 20-2009). Count, fraction and
category checks are listed as not applicable.

Scale-out and resume as in ``sweep``: ``--workers`` rungs at once (``--engine dask`` for a Dask cluster), each
finished rung written into the ``--json`` file at once (whole or not at all), ``--resume`` skips the rungs that file
holds. A rung that raised or diverged stays in the table and the file; the analysis uses the finite rungs.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Mapping, Sequence
from dataclasses import asdict
from pathlib import Path
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import Check, jsonable
from mjpoincare.analysis.convergence import ANALYTIC_FLOOR, SANE_ORDER, Verdict, analyze
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_inputs, run_steps, run_validation
from mjpoincare.core.cost import refuse_long
from mjpoincare.core.parallel import ResumableRows, check_engine, point_assignments
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import write_json

AXES = ("timestep", "solref_timeconst", "solref_dampratio", "foot_radius")
DEFAULT_AXES = ("timestep", "solref_timeconst")
MAX_POINTS = 8
MAX_RATIO = 4.0
MIN_TIMECONST_STEPS = 2.0  # MuJoCo: solref time constant >= 2 timesteps
NOT_SCALAR_KINDS = ("count", "fraction", "mismatch")


def _text(value: float) -> str:
    return f"{value:.12g}"


def rung_key(overrides: Mapping[str, str]) -> str:
    """The identity of a rung: its setting overrides, sorted (two axes sharing a rung run it once)."""
    return ",".join(f"{k}={overrides[k]}" for k in sorted(overrides))


def ladders(start: Mapping[str, Any], axes: Sequence[str], points: int, ratio: float
            ) -> dict[str, list[dict[str, str]]]:
    """Per axis, the overrides of each rung (all of :data:`AXES`, so that equal settings give equal rung keys),
    coarsest (the start values) first."""
    base = {a: float(start[a]) for a in AXES}
    scales = [ratio**-i for i in range(points)]
    out: dict[str, list[dict[str, str]]] = {}
    for axis in axes:
        if axis == "timestep":
            changes = [{"timestep": base["timestep"] * s, "solref_timeconst": base["solref_timeconst"] * s}
                       for s in scales]
        elif axis == "solref_timeconst":
            changes = [{"timestep": base["timestep"] * scales[-1], "solref_timeconst": base["solref_timeconst"] * s}
                       for s in scales]
        else:
            changes = [{axis: base[axis] * s} for s in scales]
        out[axis] = [{k: _text(v) for k, v in {**base, **c}.items()} for c in changes]
    return out


def check_request(name: str, assignments: Mapping[str, str], preset: str | None, axes: Sequence[str], points: int,
                  ratio: float, *, allow_long: bool = False) -> dict[str, list[dict[str, str]]]:
    """Refuse bad input before any simulation (one line naming the parameter and bound), and ladders whose runs add
    up to more than :data:`~mjpoincare.core.cost.LONG_STEPS` MuJoCo steps unless ``allow_long``; return the ladders."""
    bad_axes = [a for a in axes if a not in AXES]
    if bad_axes:
        raise ParameterError(f"--axis must be one of {', '.join(AXES)} (got {', '.join(bad_axes)})")
    twice = sorted({a for a in axes if list(axes).count(a) > 1})
    if twice:
        raise ParameterError(f"--axis {', '.join(twice)} is given more than once")
    if not 3 <= points <= MAX_POINTS:
        raise ParameterError(f"--points must be in [3, {MAX_POINTS}] (got {points})")
    if not 1.0 < ratio <= MAX_RATIO:
        raise ParameterError(f"--ratio must be in (1, {MAX_RATIO:g}] (got {ratio})")
    scenario, _, _, start = resolve_inputs(name, assignments, preset)
    if "foot_radius" in axes and scenario.foot is None:
        raise ParameterError(f"--axis foot_radius: {name} has no foot spheres (its model does not read foot_radius)")
    plan = ladders(start, axes, points, ratio)
    for axis, rungs in plan.items():
        for overrides in rungs:
            settings = resolve_inputs(name, {**assignments, **overrides}, preset)[3]
            steps = float(settings["solref_timeconst"]) / float(settings["timestep"])
            if steps < MIN_TIMECONST_STEPS * (1 - 1e-9):
                raise ParameterError(
                    f"--axis {axis}: solref_timeconst {settings['solref_timeconst']:.3g} s is below "
                    f"{MIN_TIMECONST_STEPS:g} x timestep {settings['timestep']:.3g} s at a rung (MuJoCo clamps it); "
                    "start from a larger solref_timeconst")
    runs = {rung_key(o): o for rungs in plan.values() for o in rungs}
    steps = sum(run_steps(name, {**assignments, **o}, preset) for o in runs.values())
    refuse_long(steps, f"converge {name} ({len(runs)} runs)", allow=allow_long)
    return plan


def _pairs(name: str, analytic: Any, simulated: Any) -> list[tuple[str, float, float]]:
    """(component name, analytic, simulated) of one scalar, complex or array check."""
    a, s = np.asarray(analytic), np.asarray(simulated)
    if a.ndim > 0:
        same = s.shape == a.shape
        return [p for i in range(a.shape[0]) for p in _pairs(f"{name}[{i}]", a[i], s[i] if same else math.nan)]
    if np.iscomplexobj(a):
        sc = complex(s) if np.isfinite(s) else complex(math.nan, math.nan)
        return [(f"{name}.re", float(a.real), sc.real), (f"{name}.im", float(a.imag), sc.imag)]
    return [(name, float(a), float(np.real(s)) if np.isfinite(s) else math.nan)]


def components(checks: Sequence[Check]) -> tuple[dict[str, list[float]], list[str]]:
    """``{component: [analytic, simulated]}`` of the scalar checks, and the names of the checks that are not."""
    out: dict[str, list[float]] = {}
    skipped = []
    for c in checks:
        numeric = np.asarray(c.analytic).dtype.kind in "iufc" and not isinstance(c.analytic, bool)
        if c.kind in NOT_SCALAR_KINDS or not numeric:
            skipped.append(c.name)
            continue
        out.update({n: [a, s] for n, a, s in _pairs(c.name, c.analytic, c.simulated)})
    return out, skipped


def ladder_rung(name: str, overrides: dict[str, str], assignments: Mapping[str, str], preset: str | None,
                seed: int) -> dict[str, Any]:
    """One rung: the validation at ``overrides`` reduced to its scalar components (a top-level function so that
    worker processes and Dask can run it). A rung that raises is a row with ``failed`` set, not a crash."""
    start = time.perf_counter()
    row: dict[str, Any] = {"key": rung_key(overrides), "overrides": overrides, "failed": None, "diverged": 0,
                           "warnings": 0, "components": {}, "not_applicable": []}
    try:
        result = run_validation(name, {**assignments, **overrides}, preset, seed)
    except Exception as err:  # reported in the table and the file, never dropped
        return {**row, "failed": f"{type(err).__name__}: {err}", "wall_s": time.perf_counter() - start}
    values, skipped = components(result.checks)
    return {**row, "diverged": len(result.diverged), "warnings": len(result.warnings), "components": values,
            "not_applicable": skipped, "wall_s": result.timing["wall_s"]}


def _cost(overrides: Mapping[str, str], start: Mapping[str, Any]) -> float:
    return float(start["timestep"]) / float(overrides.get("timestep", start["timestep"]))


def _finite(value: float | None) -> float | None:
    return value if value is not None and math.isfinite(value) else None


def _trouble(row: Mapping[str, Any]) -> str:
    """Why a rung is not clean ("" when it is): the exception, or its diverged trajectories and MuJoCo warnings."""
    if row["failed"]:
        return str(row["failed"])
    if row["diverged"] or row["warnings"]:
        return f"{row['diverged']} diverged trajectories, {row['warnings']} MuJoCo warnings"
    return ""


def _analyse_axis(axis: str, rungs: list[dict[str, str]], rows: Mapping[str, dict[str, Any]]) -> dict[str, Any]:
    """Per component of the axis's ladder: the analysis (or why there is none) and the rungs that failed."""
    ladder = [rows[rung_key(o)] for o in rungs]
    h = [float(o[axis]) for o in rungs]
    bad = [f"{axis}={o[axis]}: {_trouble(r)}" for o, r in zip(rungs, ladder, strict=True) if _trouble(r)]
    names = list(dict.fromkeys(n for r in ladder for n in r["components"]))
    out: dict[str, Any] = {"h": h, "bad_rungs": bad, "components": {}}
    for n in names:
        sims = [_finite(r["components"].get(n, [None, None])[1]) for r in ladder]
        analytics = [_finite(r["components"].get(n, [None, None])[0]) for r in ladder]
        known = [a for a in analytics if a is not None]
        # a check whose analytic value comes from the run itself (e.g. evaluated at the run's own heading or time
        # grid) changes along the ladder: then the error simulated - analytic is what converges, to 0
        varies = len(known) > 1 and max(known) - min(known) > ANALYTIC_FLOOR * max(1.0, *map(abs, known))
        if varies:
            sims = [None if v is None or a is None else v - a for v, a in zip(sims, analytics, strict=True)]
        analytic = 0.0 if varies else (known[0] if known else None)
        good = [(x, v) for x, v in zip(h, sims, strict=True) if v is not None]
        entry: dict[str, Any] = {"ladder_values": sims, "analysed": "error" if varies else "value"}
        if analytic is None:
            entry["verdict"] = "no finite analytic value"
        elif len(good) < 3:
            entry["verdict"] = f"too few finite rungs ({len(good)} of {len(h)})"
        else:
            result = analyze([g[0] for g in good], [g[1] for g in good], analytic)
            entry.update(asdict(result))
            entry["verdict"] = result.verdict.value
        out["components"][n] = entry
    return out


def converge(name: str, assignments: Mapping[str, str], preset: str | None = None, *,
             axes: Sequence[str] = DEFAULT_AXES, points: int = 4, ratio: float = 2.0, seed: int = 0,
             json_path: str | None = None, workers: int = 1, engine: str = "local", scheduler: str | None = None,
             resume: bool = False, allow_long: bool = False) -> dict[str, Any]:
    """Run the ladders (skipping rungs the ``json_path`` file holds when ``resume``) and analyse every axis.

    Returns the JSON payload: the header, ``rows`` (every rung, failed ones included), ``ladders`` (axis -> rung
    keys), ``analysis`` (axis -> component -> :class:`~mjpoincare.analysis.convergence.Convergence` fields and the
    verdict), ``not_applicable`` and the timing.
    """
    check_engine(workers, engine, scheduler)
    if seed < 0:
        raise ParameterError(f"--seed must be an integer >= 0 (got {seed})")
    # every rung runs the full experiment design, so that rungs differ in the refined setting alone
    assignments = {"adaptive_stopping": "0", **assignments}
    plan = check_request(name, assignments, preset, axes, points, ratio, allow_long=allow_long)
    _, preset, _, start_settings = resolve_inputs(name, assignments, preset)
    header = {"command": "converge", "scenario": name, "assignments": dict(assignments), "preset": preset,
              "seed": seed, "ratio": ratio}
    wanted = {rung_key(o): o for rungs in plan.values() for o in rungs}
    ladder = ResumableRows.open(header, json_path, "key", wanted, resume=resume)
    todo = sorted((wanted[k] for k in ladder.todo), key=lambda o: -_cost(o, start_settings))
    point_set = point_assignments(assignments, workers)
    began = time.perf_counter()
    rows = ladder.run(ladder_rung, [(name, o, point_set, preset, seed) for o in todo], label="converge", unit="rung",
                      describe=lambda new: f"{new[0]['key']}: {new[0]['failed'] or 'done'}", workers=workers,
                      engine=engine, scheduler=scheduler)
    skipped = sorted({n for r in rows for n in r["not_applicable"]})
    return jsonable({**header, "axes": list(axes), "points": points, "rows": rows,
                     "ladders": {a: [rung_key(o) for o in rungs] for a, rungs in plan.items()},
                     "analysis": {a: _analyse_axis(a, rungs, ladder.rows) for a, rungs in plan.items()},
                     "not_applicable": skipped, "rungs_run": len(todo), "rungs_resumed": len(wanted) - len(todo),
                     "wall_s": time.perf_counter() - began, "workers": workers, "engine": engine})


_AXIS_NOTES = {"timestep": " (solref_timeconst a fixed multiple of it)",
               "solref_timeconst": " (at the finest timestep: the limit and the bias include that step's error)"}


def _num(value: Any, spec: str = ".4g") -> str:
    return "—" if value is None else format(value, spec)


def _verdict_text(entry: Mapping[str, Any]) -> str:
    """The verdict, with the noise floor and its scaling exponent where the ladder does not converge."""
    if entry["verdict"] != Verdict.NONE.value:
        return str(entry["verdict"])
    scaling = "" if entry["noise_exponent"] is None else f", ~h^{entry['noise_exponent']:.2g}"
    return f"{entry['verdict']} (noise floor {_num(entry['noise_floor'], '.2g')}{scaling})"


def _fit_is_sound(fit: Mapping[str, Any]) -> bool:
    """The least-squares order is one (inside SANE_ORDER, its sigma below it), not a fit run off to p -> 0 or
    p -> infinity because the increments are not geometric."""
    order, sigma = fit["order"], fit["order_stderr"]
    return (order is not None and SANE_ORDER[0] <= order <= SANE_ORDER[1]
            and sigma is not None and sigma < order)


def _component_row(name: str, entry: Mapping[str, Any]) -> tuple[str, ...]:
    """One component's cells of an axis's table (dashes where the ladder gave no three-grid estimate)."""
    if "three_grid" not in entry:
        return (name, *["—"] * 6, str(entry["verdict"]))
    tg, fit = entry["three_grid"], entry["fit"]
    order = _num(tg["observed_order"], ".3g") + ("" if tg["safety_factor"] in (None, 1.25) else " *")
    fitted = "—" if fit["order"] is None else f"{fit['order']:.3g} ± {_num(fit['order_stderr'], '.2g')}"
    if fit["order"] is not None and not _fit_is_sound(fit):
        fitted += " †"
    return (f"{name} (error)" if entry.get("analysed") == "error" else name, order, fitted,
            _num(tg["extrapolated"], ".7g"), _num(entry["band"], ".2g"), _num(entry["analytic"], ".7g"),
            _num(entry["bias"], ".2g"), _verdict_text(entry))


def table(payload: Mapping[str, Any]) -> str:
    """Markdown tables, one per axis: order (three-grid; least squares ± 1 sigma), Richardson value, GCI band,
    analytic value, bias and verdict per component."""
    lines = [(f"{payload['scenario']}  preset={payload['preset']}  ratio={payload['ratio']:g}  "
             + " ".join(f"{k}={v}" for k, v in payload["assignments"].items())).rstrip()]
    for axis, res in payload["analysis"].items():
        lines += ["", f"axis {axis}: " + ", ".join(f"{h:.4g}" for h in res["h"]) + _AXIS_NOTES.get(axis, ""),
                  markdown_table(("component", "p (3-grid)", "p (fit ± σ)", "Richardson", "GCI band", "analytic",
                                  "bias", "verdict"), [_component_row(n, e) for n, e in res["components"].items()])]
        lines += [f"FAILED rung {b}" for b in res["bad_rungs"]]
    lines += ["", "* order outside [0.5, 4]: band with Fs = 3 at the formal order (analysis/convergence.py)",
              "† least-squares fit degenerate (order outside [0.5, 4] or its sigma above the order): not an order",
              "(error): the analytic value changes along the ladder (computed from each run): the error is analysed",
              f"not applicable (counts, fractions, categories): {', '.join(payload['not_applicable']) or 'none'}",
              f"{payload['rungs_run']} rungs run ({payload['rungs_resumed']} resumed) in {payload['wall_s']:.1f} s "
              f"wall, {payload['workers']} worker(s), {payload['engine']} engine"]
    return "\n".join(lines)


def write_plots(payload: Mapping[str, Any], directory: str) -> list[Path]:
    """One PNG per component: per axis, |f - analytic| against h on log-log axes with the fitted slope, and f
    against h with the Richardson value and its GCI band at h = 0 beside the analytic line."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(n for res in payload["analysis"].values() for n in res["components"]))
    paths = []
    for n in names:
        axes = [(a, res) for a, res in payload["analysis"].items() if n in res["components"]]
        fig, grid = plt.subplots(len(axes), 2, figsize=(9, 3.2 * len(axes)), squeeze=False)
        for (axis, res), (left, right) in zip(axes, grid, strict=True):
            _plot_axis(left, right, axis, res["h"], res["components"][n])
        fig.suptitle(f"{payload['scenario']}: {n}")
        fig.tight_layout()
        path = Path(directory) / f"converge-{payload['scenario']}-{re.sub(r'[^A-Za-z0-9_.-]', '_', n)}.png"
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        paths.append(path)
    return paths


#: Each axis's unit, for the plots' labels.
AXIS_UNITS = {"timestep": "s", "solref_timeconst": "s", "solref_dampratio": "", "foot_radius": "m"}


def _plot_axis(left: Any, right: Any, axis: str, h: list[float], entry: Mapping[str, Any]) -> None:
    from matplotlib.ticker import LogLocator, NullFormatter

    pts = [(x, v) for x, v in zip(h, entry["ladder_values"], strict=True) if v is not None]
    xs = np.array([p[0] for p in pts])
    ys = np.array([p[1] for p in pts])
    label = f"{axis}, {AXIS_UNITS[axis]}" if AXIS_UNITS.get(axis) else axis
    right.plot(xs, ys, "o-", label="simulated")
    right.set_xlabel(label)
    right.set_ylabel("value f (the check's unit)")
    left.set_xlabel(label)
    left.set_ylabel("|f - analytic|")
    if "three_grid" not in entry:
        left.set_title(entry["verdict"], fontsize=8)
        return
    analytic, err = entry["analytic"], np.abs(ys - entry["analytic"])
    keep = err > 0
    left.loglog(xs[keep], err[keep], "o", label="|f - analytic|")
    if entry["error_slope"] is not None and keep.sum() >= 2:
        coef = np.polyfit(np.log(xs[keep]), np.log(err[keep]), 1)
        left.loglog(xs, np.exp(np.polyval(coef, np.log(xs))), "--",
                    label=f"slope of |f - analytic|: {entry['error_slope']:.2f}\n(the table's p is of the rungs'\n"
                          "differences: a bias makes them differ)")
    for ax in (left,):
        ax.xaxis.set_major_locator(LogLocator(base=10.0, numticks=6))
        ax.xaxis.set_minor_formatter(NullFormatter())
    left.set_title(entry["verdict"], fontsize=8)
    left.legend(fontsize=6)
    right.axhline(analytic, color="k", lw=0.8, label="analytic")
    tg = entry["three_grid"]
    if tg["gci"] is not None:
        right.errorbar([0.0], [tg["extrapolated"]], yerr=[[entry["band"]], [entry["band"]]], fmt="s", capsize=4,
                       label="Richardson ± GCI")
    right.legend(fontsize=7)


def run_converge(name: str, assignments: Mapping[str, str], preset: str | None, *, json_path: str | None,
                 report: str | None, **options: Any) -> int:
    """The command: print the tables, write ``--json`` and the ``--report`` plots; exit 0, or 1 if a rung failed,
    diverged or warned."""
    payload = converge(name, assignments, preset, json_path=json_path, **options)
    if json_path != "-":
        print(table(payload))
    if json_path:
        write_json(payload, json_path)
    if report:
        for path in write_plots(payload, report):
            if json_path != "-":
                print(f"plot: {path}")
    bad = any(res["bad_rungs"] for res in payload["analysis"].values())
    return 1 if bad else 0
