"""The Python API: ``mjpoincare.validate(scenario, preset=None, seed=0, **values) -> Result``.

The command line (:mod:`mjpoincare.cli`) is a thin layer over this function: the same inputs give the same
:class:`~mjpoincare.core.result.Result`, and ``Result.to_document()`` is the CLI's ``--json`` output (``to_dict()`` its
one run).
"""

from __future__ import annotations

from mjpoincare import scenarios
from mjpoincare.commands.validation import run_validation
from mjpoincare.core import settings as sim_settings
from mjpoincare.core.params import ParameterError, Value, typed
from mjpoincare.core.result import Result


def validate(scenario: str, preset: str | None = None, seed: int = 0, *, peer: str | None = None,
             **values: Value) -> Result:
    """Run ``scenario``'s validation and check it against the analytic results.

    Args:
        scenario: a registered name (``mjpoincare list``), e.g. ``"rimless-wheel"``.
        preset: simulator preset (``"fast"``, ``"accurate"``, ...); None is the scenario's default.
        seed: seed of the experiment design's random parts (same seed, same result on any thread count).
        peer: an outside simulator (``"drake"``, for rimless-wheel and compass-biped; the extra
            ``mjpoincare[peers]``) whose value of each check the result's ``peer`` carries.
        **values: physical parameters and simulator settings, typed (``spokes=8``, ``timestep=2e-4``,
            ``integrator="rk4"``): text for a number (``spokes="8"``) is refused, as is a bool.

    Returns:
        The :class:`~mjpoincare.core.result.Result`: ``passed`` (bool) and ``checks`` (name, analytic, simulated,
        error, tolerance, passed, why each).

    Raises:
        ParameterError: (a ``ValueError``) any bad input, before any simulation; the message is one line naming
            the parameter and its bound.
    """
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ParameterError(f"seed must be an integer >= 0 (got {seed!r})")
    typed([*scenarios.get(scenario).params, *sim_settings.SETTINGS], values)
    return run_validation(scenario, values, preset, seed, peer=peer)
