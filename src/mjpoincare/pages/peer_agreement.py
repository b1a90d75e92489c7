"""``python -m mjpoincare.pages.peer_agreement``: each peer against the suite's theory for the peer's model.

For every registered scenario with a peer (:class:`mjpoincare.engines.peers.Peer`) and each of the peer's agreement
cases: the peer's value of each check, its difference from the suite's theory evaluated for the peer's model (the
checks' error measures) and the peer's wall time; then, for each peer that states one
(:attr:`mjpoincare.engines.peers.Peer.model_shift`), how much of its difference at the scenario's defaults its model's
difference explains (the rimless wheel's kappa floor: the checks' analytic wheel has a floored hub inertia, Drake's
has none). It reads the registry only.
"""

from __future__ import annotations

from mjpoincare import scenarios
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.core.result import format_value
from mjpoincare.engines.peers.compare import KINDS, difference


def agreement_table() -> str:
    """Markdown: per scenario, peer and agreement case, each check's peer value and its difference from the suite's
    theory for the peer's model; then each peer's model shift at its scenario's defaults."""
    lines: list[str] = []
    rows = []
    for scenario in map(scenarios.get, scenarios.loadable()):
        for peer in scenario.peers:
            if not lines:
                lines = [f"{peer.name.capitalize()} {peer.version()}, {peer.scheme} at accuracy "
                         f"{peer.reference_accuracy:g}; difference = |{peer.name} - theory for {peer.name.capitalize()}"
                         "'s model| (relative for scalars, largest entry for vectors)", ""]
            for assignments in peer.agreement_cases:
                p = resolve_inputs(scenario.name, assignments, None)[2]
                values, result = peer.values(p, peer.reference_accuracy)
                label = " ".join(f"{k}={v}" for k, v in assignments.items()) or "defaults"
                rows += [[scenario.name, label, name, format_value(value),
                          f"{difference(KINDS[name], value, reference):.1e} {KINDS[name][:3]}", f"{result.wall_s:.3f}"]
                         for name, (value, reference) in values.items()]
    lines.append(markdown_table(["scenario", "parameters", "check", "drake", "difference", "drake wall s"], rows))
    for scenario in map(scenarios.get, scenarios.loadable()):
        for peer in scenario.peers:
            if peer.model_shift is not None:
                p = resolve_inputs(scenario.name, {}, None)[2]
                lines += ["", f"{scenario.name} defaults: "
                          + peer.model_shift(p, peer.values(p, peer.reference_accuracy)[0])]
    return "\n".join(lines)


if __name__ == "__main__":
    print(agreement_table())
