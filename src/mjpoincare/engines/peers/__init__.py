"""Outside peers: simulators nobody here wrote, run on the same parameters as a scenario, to check the suite's
analytic values (and to set the row a user would pick instead of MuJoCo beside the bench's MuJoCo rows).

A scenario names its peers in its ``peers`` field (:class:`Peer`, one per outside model of its system). One peer so
far, :mod:`mjpoincare.engines.peers.drake` (the optional extra ``mjpoincare[peers]``);
:mod:`mjpoincare.engines.peers.compare` sets its values beside a validation's checks.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol

from mjpoincare.core.params import Values


class PeerRun(Protocol):
    """What a peer's run reports beside its values: the accuracy it ran at and its wall time, s."""

    accuracy: float
    wall_s: float


#: A peer's values: {check name: (the peer's value, the suite's theory evaluated for the peer's model)}, and its run.
PeerValues = tuple[dict[str, tuple[Any, Any]], PeerRun]


@dataclass(frozen=True)
class Peer:
    """An outside simulator's model of one scenario's system.

    Attributes:
        name: the ``--peer`` name, e.g. ``drake``.
        version: ``() -> str``, the installed tool's version.
        scheme: the tool's integration scheme, as tables name it.
        install: how to install the tool (the one-line refusal when it is missing says it).
        reference_accuracy: the accuracy of a validation's peer values.
        check_params: ``(params) -> None``: refuses (ParameterError, one line) a missing tool or a parameter its
            model cannot represent, before any simulation.
        values: ``(params, accuracy) -> PeerValues``.
        model_note: ``(params) -> str``: how the peer's model differs from the one the checks' analytic values are
            for.
        bench_accuracies: the accuracies of the bench's peer rows.
        bench_metrics: bench metric -> the check whose value it compares (as the solve_ivp reference rows).
        bench_model: the peer's model, as the bench rows' header names it.
        agreement_cases: ``--set``-style parameter sets of the agreement table (the defaults and others).
        model_shift: ``(params, values) -> str``: the agreement table's line on how much of the peer's difference from
            the checks' analytic values its model's difference explains, from the peer's ``values`` at ``params``
            (None: no such line).
    """

    name: str
    version: Callable[[], str]
    scheme: str
    install: str
    reference_accuracy: float
    check_params: Callable[[Values], None]
    values: Callable[[Values, float], PeerValues]
    model_note: Callable[[Values], str]
    bench_accuracies: tuple[float, ...]
    bench_metrics: Mapping[str, str]
    bench_model: str
    agreement_cases: tuple[Mapping[str, str], ...] = ({},)
    model_shift: Callable[[Values, dict[str, tuple[Any, Any]]], str] | None = None
