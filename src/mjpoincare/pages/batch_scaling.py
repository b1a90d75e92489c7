"""Batch-size scaling of a backend: seconds per batched step at batch sizes B, the measurement a GPU estimate rests
on (``python -m mjpoincare.pages.backend_findings scaling``).

A scenario's model and its first rollout batch's starts (:attr:`mjpoincare.scenarios.base.Scenario.validation_batches`),
tiled to B trajectories, stepped in plain chunks (no events: the timing of the stepping alone): one chunk to compile and
warm up, then one timed chunk. The line ``t(B) = latency + B * per_trajectory`` fitted to the times separates what a
batched step costs whatever its size (dispatch, kernel launches, the solver's sequential iterations) from what each
trajectory adds; a device that runs the B trajectories in parallel (a GPU, up to its width) pays mostly the first.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from mjpoincare.engines.backends import open_batch


def measure(scenario: str, backend: str, precision: str, sizes: Sequence[int], steps: int) -> dict[str, Any]:
    """Seconds per batched step of ``scenario``'s model on ``backend`` in ``precision`` at each batch size in
    ``sizes`` (``steps`` timed steps each, after a first chunk that compiles); the line through them is
    :func:`mjpoincare.pages.backend_findings_page.scaling_fit`."""
    from mjpoincare.commands.validation import resolve_inputs

    spec, _, params, settings = resolve_inputs(scenario, {"backend": backend, "precision": precision}, None)
    model, batches = spec.validation_batches(params, settings)
    state0 = batches[0][0]
    rows = []
    for size in sizes:
        starts = np.resize(state0, (size, state0.shape[1]))  # the design's starts repeated to ``size`` rows
        with open_batch(model, starts, threads=int(settings["threads"]), backend=backend,
                        precision=str(settings["precision"])) as batch:
            batch.run_chunk(steps)
            start = time.perf_counter()
            batch.run_chunk(steps)
            seconds = time.perf_counter() - start
        rows.append({"batch": int(size), "seconds_per_step": seconds / steps, "steps_per_s": size * steps / seconds,
                     "compile_s": batch.report.compile_s})
    return {"scenario": scenario, "backend": backend, "precision": str(settings["precision"]), "steps": steps,
            "sizes": rows}
