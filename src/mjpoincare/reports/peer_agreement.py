"""``python -m mjpoincare.reports.peer_agreement``: each peer against the suite's theory for the peer's model.

For every registered scenario with a peer (:class:`mjpoincare.peers.Peer`) and each of the peer's agreement cases:
the peer's value of each check, its difference from the suite's theory evaluated for the peer's model (the checks'
error measures) and the peer's wall time; then the rimless wheel's kappa-floor shift (002 eqs 12, 14: the checks'
analytic wheel has a floored hub inertia, Drake's has none).
"""

from __future__ import annotations

from mjpoincare import scenarios
from mjpoincare.analysis.tables import markdown_table
from mjpoincare.analysis.theory import rimless_wheel as rimless_theory
from mjpoincare.peers.compare import KINDS, difference
from mjpoincare.result import format_value
from mjpoincare.scenarios.rimless_wheel import wheel
from mjpoincare.scenarios.rimless_wheel_drake import point_mass_wheel
from mjpoincare.validation import resolve_inputs


def agreement_table() -> str:
    """Markdown: per scenario, peer and agreement case, each check's peer value and its difference from the suite's
    theory for the peer's model; then the rimless wheel's kappa-floor shift."""
    lines: list[str] = []
    rows = []
    for scenario in scenarios.REGISTRY.values():
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
    rimless = scenarios.get("rimless-wheel")
    p = resolve_inputs(rimless.name, {}, None)[2]
    floored = rimless_theory.rolling_fixed_point(wheel(p))
    shift = rimless_theory.rolling_fixed_point(point_mass_wheel(p)) - floored
    drake_omega = rimless.peers[0].values(p, rimless.peers[0].reference_accuracy)[0]["omega_post_impact"][0]
    lines += ["", f"rimless-wheel defaults: Drake's omega+ minus the scenario's analytic omega+ (kappa = "
              f"{wheel(p).kappa:g}) = {drake_omega - floored:.3e} rad/s; the theory's own shift from kappa = "
              f"{wheel(p).kappa:g} to kappa = 0 = {shift:.3e} rad/s"]
    return "\n".join(lines)


if __name__ == "__main__":
    print(agreement_table())
