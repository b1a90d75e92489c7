"""A peer's values beside the suite's: the ``peer`` object of ``validate --peer NAME`` and the peer rows of ``bench``.

Every peer value is set beside two analytic ones: the check's own (the scenario's model) and the suite's theory
evaluated for the peer's model (for the rimless wheel, kappa = 0: 003 eqs 3.11-3.13; for the compass gait, the same
biped: 003 eq 4.18). The first difference is what a user comparing the two tools sees, the second is the agreement
of the two codes on one model. Which peers a scenario has is its ``peers`` field
(:class:`mjpoincare.engines.peers.Peer`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mjpoincare.analysis.checks import Check
from mjpoincare.analysis.eigenvalues import match_eigenvalues
from mjpoincare.analysis.tables import markdown_table, text_table
from mjpoincare.core.params import ParameterError, Values
from mjpoincare.core.result import format_value
from mjpoincare.engines.peers import Peer

#: How each check a peer has a value for measures a difference (as the scenarios' checks do).
KINDS = {"omega_post_impact": "relative", "eigenvalue": "absolute", "impact_coefficient": "relative",
         "step_period": "relative", "fixed_point": "max-abs", "eigenvalues": "max-abs", "step_length": "relative"}


def difference(kind: str, value: Any, reference: Any) -> float:
    """|value - reference|, relative to |reference| for a ``relative`` check, the largest entry for a vector."""
    gap = float(np.max(np.abs(np.asarray(value) - np.asarray(reference))))
    return gap / float(np.max(np.abs(reference))) if kind == "relative" else gap


def compare(peer: Peer, params: Values, checks: Sequence[Check]) -> dict[str, Any]:
    """The ``peer`` object of the validation JSON: the peer's value of each check it has, its difference from the
    check's analytic value (the check's own error measure) and from the suite's theory for the peer's model."""
    values, result = peer.values(params, peer.reference_accuracy)
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
    return {"name": peer.name, "version": peer.version(), "scheme": peer.scheme, "accuracy": result.accuracy,
            "wall_s": result.wall_s, "model": peer.model_note(params), "checks": out}


def format_peer(block: dict[str, Any]) -> str:
    """The block printed under the check table: Drake's value of each check beside its differences."""
    head = (f"peer {block['name']} {block['version']} ({block['scheme']}, accuracy {block['accuracy']:g}, "
            f"{block['wall_s']:.2f} s): {block['model']}")
    rows = [(name, format_value(item["value"]), f"{item['difference']:.2g} {item['kind'][:3]}",
             format_value(item["analytic_peer_model"]), f"{item['difference_peer_model']:.2g} {item['kind'][:3]}")
            for name, item in block["checks"].items()]
    columns = ("check", "drake", "drake - analytic", "theory at drake's model", "drake - it")
    return f"{head}\n{text_table(columns, rows)}"


def bench_rows(peer: Peer, params: Values) -> list[dict[str, float]]:
    """The peer's run at each of its bench accuracies: wall time of the whole search and its errors against the
    suite's theory for the peer's model, named as the solve_ivp rows'."""
    rows = []
    for accuracy in peer.bench_accuracies:
        values, result = peer.values(params, accuracy)
        rows.append({"accuracy": accuracy, "wall_s": result.wall_s,
                     **{metric: difference(KINDS[check], *values[check])
                        for metric, check in peer.bench_metrics.items()}})
    return rows


def format_bench(peer: Peer, rows: list[dict[str, float]]) -> str:
    """The peer rows of the bench table."""
    metrics = list(peer.bench_metrics)
    header = [f"{peer.name.capitalize()} {peer.version()} hybrid simulation ({peer.scheme}; root + finite differences "
              f"of its step map; errors vs the theory for {peer.name.capitalize()}'s model, {peer.bench_model})",
              "wall s", *metrics]
    body = [[f"accuracy={row['accuracy']:g}", f"{row['wall_s']:.3f}", *(f"{row[k]:.2e}" for k in metrics)]
            for row in rows]
    return "\n\n" + markdown_table(header, body)


def bench_block(peers: Sequence[Peer], params: Values) -> tuple[str, dict[str, Any] | None]:
    """What ``bench`` prints for a scenario's first peer (its rows, or one line saying why there are none; nothing
    for a scenario without peers) and the JSON block of its rows (None without rows)."""
    if not peers:
        return "", None
    peer = peers[0]
    try:
        peer.check_params(params)
    except ParameterError as err:
        return f"\n\n{peer.name.capitalize()} row skipped: {err}", None
    rows = bench_rows(peer, params)
    return format_bench(peer, rows), {"name": peer.name, "version": peer.version(), "scheme": peer.scheme,
                                      "rows": rows}
