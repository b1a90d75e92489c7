"""Drake's values beside the suite's: the ``peer`` object of ``validate --peer drake`` and the Drake rows of ``bench``.

Every Drake value is set beside two analytic ones: the check's own (the scenario's model; for the rimless wheel its
hub inertia is floored at kappa = 1e-4, see :data:`mjpoincare.scenarios.rimless_wheel.MIN_GYRATION`) and the suite's
theory evaluated for Drake's model (kappa = 0 for the rimless wheel, 003 eqs 3.11-3.13; the same biped for the
compass gait, 003 eq 4.18). The first difference is what a user comparing the two tools sees, the second is the
agreement of the two codes on one model.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import Check
from mjpoincare.analysis.eigenvalues import match_eigenvalues
from mjpoincare.analysis.theory import compass_biped as compass_theory
from mjpoincare.analysis.theory import rimless_wheel as rimless_theory
from mjpoincare.params import ParameterError
from mjpoincare.peers import drake
from mjpoincare.result import format_value
from mjpoincare.scenarios.base import Values
from mjpoincare.scenarios.compass_biped import biped
from mjpoincare.scenarios.rimless_wheel import wheel

#: Drake's accuracy settings of the bench rows (runge_kutta5).
BENCH_ACCURACIES = (1e-4, 1e-6, 1e-8)
#: How each check Drake has a value for measures a difference (as the scenarios' checks do).
KINDS = {"omega_post_impact": "relative", "eigenvalue": "absolute", "impact_coefficient": "relative",
         "step_period": "relative", "fixed_point": "max-abs", "eigenvalues": "max-abs", "step_length": "relative"}
#: Bench metric -> the check whose value it compares, as the solve_ivp reference rows.
BENCH_METRICS = {
    "rimless-wheel": {"omega_post_impact_error": "omega_post_impact", "eigenvalue_error": "eigenvalue"},
    "compass-biped": {"fixed_point_error": "fixed_point", "eigenvalues_error": "eigenvalues"},
}
#: Drake's model, as the bench rows' header names it.
BENCH_MODEL = {"rimless-wheel": "point-mass hub, kappa = 0", "compass-biped": "the scenario's biped"}


def check_peer(peer: str, scenario: str, p: Values) -> None:
    """Refuse, before any simulation, an unknown peer, a scenario it has no model of, a missing install or a
    parameter it cannot represent (one line each)."""
    if peer != drake.NAME:
        raise ParameterError(f"--peer must be {drake.NAME} (got {peer})")
    drake.check_params(scenario, p)


def difference(kind: str, value: Any, reference: Any) -> float:
    """|value - reference|, relative to |reference| for a ``relative`` check, the largest entry for a vector."""
    gap = float(np.max(np.abs(np.asarray(value) - np.asarray(reference))))
    return gap / float(np.max(np.abs(reference))) if kind == "relative" else gap


def peer_values(scenario: str, p: Values, accuracy: float = drake.REFERENCE_ACCURACY
                ) -> tuple[dict[str, tuple[Any, Any]], drake.RimlessWheelGait | drake.CompassGaitCycle]:
    """{check name: (Drake's value, the suite's theory for Drake's model)} and Drake's result."""
    if scenario == "rimless-wheel":
        gait = drake.rimless_wheel(p, accuracy=accuracy)
        w = drake.point_mass_wheel(p)
        star = rimless_theory.rolling_fixed_point(w)
        return {"omega_post_impact": (gait.omega_post_impact, star),
                "eigenvalue": (gait.multiplier, rimless_theory.rolling_multiplier(w)),
                "impact_coefficient": (gait.impact_coefficient, w.beta),
                "step_period": (gait.step_period, rimless_theory.step_period(w, star))}, gait
    cycle = drake.compass_gait(p, accuracy=accuracy)
    bp = biped(p)
    x_star = compass_theory.fixed_point(bp)
    lam = compass_theory.eigenvalues(bp, x_star)
    return {"fixed_point": (np.array(cycle.fixed_point), x_star),
            "eigenvalues": (match_eigenvalues(lam, np.array(cycle.eigenvalues)), lam),
            "step_period": (cycle.step_period, compass_theory.step_period(bp, x_star)),
            "step_length": (cycle.step_length, compass_theory.step_length(bp, x_star))}, cycle


def model_note(scenario: str, p: Values) -> str:
    """How Drake's model differs from the one the checks' analytic values are for."""
    if scenario == "rimless-wheel":
        return (f"Drake's RimlessWheel has a point-mass hub (kappa = 0); the checks' analytic values use the "
                f"scenario's floor kappa = {wheel(p).kappa:.3g}")
    return "Drake's CompassGait is the checks' model (003 Ch. 4)"


def compare(scenario: str, p: Values, checks: Sequence[Check]) -> dict[str, Any]:
    """The ``peer`` object of the validation JSON: Drake's value of each check it has, its difference from the
    check's analytic value (the check's own error measure) and from the suite's theory for Drake's model."""
    values, result = peer_values(scenario, p)
    out: dict[str, Any] = {}
    for check in checks:
        if check.name not in values:
            continue
        value, analytic_peer_model = values[check.name]
        if check.name == "eigenvalues":
            value = match_eigenvalues(np.asarray(check.analytic), np.asarray(value))
        out[check.name] = {"value": value, "difference": difference(check.kind, value, check.analytic),
                           "analytic_peer_model": analytic_peer_model,
                           "difference_peer_model": difference(check.kind, value, analytic_peer_model),
                           "kind": check.kind}
    return {"name": drake.NAME, "version": drake.version(), "scheme": drake.SCHEME, "accuracy": result.accuracy,
            "wall_s": result.wall_s, "model": model_note(scenario, p), "checks": out}


def format_peer(block: dict[str, Any]) -> str:
    """The block printed under the check table: Drake's value of each check beside its differences."""
    head = (f"peer {block['name']} {block['version']} ({block['scheme']}, accuracy {block['accuracy']:g}, "
            f"{block['wall_s']:.2f} s): {block['model']}")
    rows = [("check", "drake", "drake - analytic", "theory at drake's model", "drake - it")]
    for name, item in block["checks"].items():
        kind = item["kind"][:3]
        rows.append((name, format_value(item["value"]), f"{item['difference']:.2g} {kind}",
                     format_value(item["analytic_peer_model"]), f"{item['difference_peer_model']:.2g} {kind}"))
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return "\n".join([head] + ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)).rstrip() for r in rows])


def bench_rows(scenario: str, p: Values) -> list[dict[str, float]]:
    """Drake's hybrid simulation at each of BENCH_ACCURACIES: wall time of the whole search (root + finite
    differences) and its errors against the suite's theory for Drake's model, named as the solve_ivp rows'."""
    rows = []
    for accuracy in BENCH_ACCURACIES:
        values, result = peer_values(scenario, p, accuracy)
        rows.append({"accuracy": accuracy, "wall_s": result.wall_s,
                     **{metric: difference(KINDS[check], *values[check])
                        for metric, check in BENCH_METRICS[scenario].items()}})
    return rows


def format_bench(scenario: str, rows: list[dict[str, float]]) -> str:
    """The Drake rows of the bench table."""
    metrics = list(BENCH_METRICS[scenario])
    lines = [f"\n\n| Drake {drake.version()} hybrid simulation ({drake.SCHEME}; root + finite differences of its step "
             f"map; errors vs the theory for Drake's model, {BENCH_MODEL[scenario]}) | wall s | "
             + " | ".join(metrics) + " |",
             "|" + "---|" * (2 + len(metrics))]
    for row in rows:
        lines.append(f"| accuracy={row['accuracy']:g} | {row['wall_s']:.3f} | "
                     + " | ".join(f"{row[k]:.2e}" for k in metrics) + " |")
    return "\n".join(lines)


def bench_block(scenario: str, p: Values) -> tuple[str, dict[str, Any] | None]:
    """What ``bench`` prints for Drake (its rows, or one line saying why there are none; nothing for a scenario
    Drake has no model of) and the JSON block of its rows (None without rows)."""
    if scenario not in drake.SCENARIOS:
        return "", None
    if not drake.available():
        return f"\n\nDrake row: needs pydrake, {drake.INSTALL}", None
    try:
        drake.check_params(scenario, p)
    except ParameterError as err:
        return f"\n\nDrake row skipped: {err}", None
    rows = bench_rows(scenario, p)
    return format_bench(scenario, rows), {"name": drake.NAME, "version": drake.version(), "scheme": drake.SCHEME,
                                          "rows": rows}


#: The parameter sets of the agreement table (and of tests/test_peer_drake.py): the defaults and others per system.
AGREEMENT_CASES: tuple[tuple[str, dict[str, str]], ...] = (
    ("rimless-wheel", {}), ("rimless-wheel", {"spokes": "6", "slope": "0.2"}),
    ("rimless-wheel", {"spokes": "12", "slope": "0.1", "leg_length": "2", "mass": "3"}),
    ("rimless-wheel", {"spokes": "32", "slope": "0.05", "gravity": "3.7"}),
    ("compass-biped", {}), ("compass-biped", {"slope": "0.0523599"}),
    ("compass-biped", {"a": "0.6", "b": "0.4", "slope": "0.05"}), ("compass-biped", {"m_h": "15"}),
    ("compass-biped", {"tau_hip": "0.1"}),
)


def agreement_table() -> str:
    """Markdown: for each of AGREEMENT_CASES, Drake's value of each check and its difference from the suite's theory
    for Drake's model (the checks' error measures), Drake's wall time; then the rimless wheel's kappa-floor shift."""
    from mjpoincare.validation import resolve_inputs

    lines = [f"Drake {drake.version()}, {drake.SCHEME} at accuracy {drake.REFERENCE_ACCURACY:g}; difference = "
             "|drake - theory for Drake's model| (relative for scalars, largest entry for vectors)", "",
             "| scenario | parameters | check | drake | difference | drake wall s |", "|---|---|---|---|---|---|"]
    for scenario, assignments in AGREEMENT_CASES:
        p = resolve_inputs(scenario, assignments, None)[2]
        values, result = peer_values(scenario, p)
        label = " ".join(f"{k}={v}" for k, v in assignments.items()) or "defaults"
        for name, (value, reference) in values.items():
            lines.append(f"| {scenario} | {label} | {name} | {format_value(value)} | "
                         f"{difference(KINDS[name], value, reference):.1e} {KINDS[name][:3]} | {result.wall_s:.3f} |")
    p = resolve_inputs("rimless-wheel", {}, None)[2]
    floored = rimless_theory.rolling_fixed_point(wheel(p))
    shift = rimless_theory.rolling_fixed_point(drake.point_mass_wheel(p)) - floored
    drake_omega = peer_values("rimless-wheel", p)[0]["omega_post_impact"][0]
    lines += ["", f"rimless-wheel defaults: Drake's omega+ minus the scenario's analytic omega+ (kappa = "
              f"{wheel(p).kappa:g}) = {drake_omega - floored:.3e} rad/s; the theory's own shift from kappa = "
              f"{wheel(p).kappa:g} to kappa = 0 = {shift:.3e} rad/s"]
    return "\n".join(lines)


if __name__ == "__main__":
    print(agreement_table())
