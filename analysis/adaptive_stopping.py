"""Adaptive stopping of a fitting batch: end the run once more steps no longer sharpen the return-map fit.

A batch of perturbed starts is stepped gait step by gait step, and each trajectory leaves one sample per step on
the Poincaré section. After every round of samples (each trajectory has ``k`` of them, ``k >= min_samples``) the
return map is fitted from the first ``k`` samples of every trajectory, and its bootstrap spread is set against the
checks' tolerances:

    u_k = max over the fitted quantities q of  2 std_q / tol_q

(the half-width of the fit's 95 % interval, in tolerances; the quantities are the fixed point's coordinates and the
multipliers, :func:`fit_spread`). The run stops at the first ``k`` where

- ``u_k <= settled``: the interval lies within that fraction of every tolerance, so further samples cannot move a
  verdict by more than it; or
- ``u_k > gain * u_{k-1}``: the last round narrowed the interval by less than ``1 - gain``. The offsets of the
  starts decay by the multipliers at every step, so the later samples all lie near the fixed point and add no
  leverage on the Jacobian; only more starts would narrow the interval further.

The decision uses only the samples and the fit's own spread, never the analytic values the checks compare with. A
trajectory that stops producing samples (diverged, stalled) holds ``k`` back, so its batch runs its full length.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from mjpoincare.analysis.returnmap import ReturnMapFit, fit_return_map, sample_pairs

__all__ = ["FitSettling", "StoppingRule", "fit_spread", "return_map_settling"]


@dataclass(frozen=True)
class StoppingRule:
    """When a fitting batch has enough samples.

    Attributes:
        min_samples: samples per trajectory before the first look (enough pairs for the fit's coefficients).
        settled: stop once the fit's 95 % half-width is at most this fraction of every tolerance.
        gain: stop once a round of samples shrinks that half-width by less than ``1 - gain``.
    """

    min_samples: int
    settled: float = 0.25
    gain: float = 0.9


def fit_spread(fit: ReturnMapFit, fixed_point_tolerance: float, eigenvalue_tolerance: float, *,
               relative: bool = False) -> float:
    """``u``: the largest 95 % bootstrap half-width (2 std) of the fitted fixed point's coordinates and multipliers,
    each over its tolerance (``inf`` when the bootstrap gave no spread). With ``relative``, the fixed point's
    tolerance is relative: it is scaled by the fitted fixed point's largest coordinate magnitude."""
    scale = float(np.max(np.abs(fit.fixed_point))) if relative else 1.0
    point = 2.0 * float(np.max(fit.fixed_point_std)) / (fixed_point_tolerance * scale)
    multipliers = 2.0 * float(np.max(np.abs(fit.eigenvalue_std))) / eigenvalue_tolerance
    spread = max(point, multipliers)
    return spread if np.isfinite(spread) else np.inf


@dataclass
class FitSettling:
    """The stop test of one batch under ``rule``: call it with the samples so far, it answers whether to stop.

    Attributes:
        rule: the stopping rule.
        spread: ``u`` of a fit of the given sequences (each ``(k, d)``); a ``ValueError`` counts as ``inf``.
        history: ``(k, u_k)`` of every look, in order.
        reason: why the batch stopped: ``"settled"``, ``"no gain"``, or ``"full design"`` while it has not.
    """

    rule: StoppingRule
    spread: Callable[[list[np.ndarray]], float]
    history: list[tuple[int, float]] = field(default_factory=list)
    reason: str = "full design"

    def __call__(self, sequences: Sequence[np.ndarray]) -> bool:
        """Whether the batch whose per-trajectory samples are ``sequences`` (each ``(n_b, d)``) may stop now."""
        k = min((len(s) for s in sequences), default=0)
        if k < self.rule.min_samples or (self.history and k == self.history[-1][0]):
            return False
        try:
            u = float(self.spread([np.asarray(s[:k]) for s in sequences]))
        except ValueError:
            u = np.inf
        previous = self.history[-1][1] if self.history else None
        self.history.append((k, u))
        if u <= self.rule.settled:
            self.reason = "settled"
        elif previous is not None and np.isfinite(previous) and u > self.rule.gain * previous:
            self.reason = "no gain"
        else:
            return False
        return True

    def to_dict(self) -> dict[str, object]:
        """The decision as JSON data: the rule, every look and the reason."""
        return {"min_samples": self.rule.min_samples, "settled": self.rule.settled, "gain": self.rule.gain,
                "looks": [{"samples": k, "spread": u if np.isfinite(u) else None} for k, u in self.history],
                "reason": self.reason}


def return_map_settling(rule: StoppingRule, *, degree: int, seed: int, fixed_point_tolerance: float,
                        eigenvalue_tolerance: float, relative: bool = False) -> FitSettling:
    """The stop test of a batch whose samples feed :func:`~mjpoincare.analysis.returnmap.fit_return_map` at
    ``degree`` (bootstrap seed ``seed``): its :func:`fit_spread` against the two tolerances (``relative``: as
    there)."""
    return FitSettling(rule, lambda sequences: fit_spread(
        fit_return_map(*sample_pairs(sequences), degree=degree, seed=seed), fixed_point_tolerance,
        eigenvalue_tolerance, relative=relative))
