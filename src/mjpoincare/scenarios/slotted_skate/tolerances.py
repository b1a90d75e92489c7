"""The tolerances of ``slotted-skate``'s checks per preset, and why each bound is what it is."""

from __future__ import annotations

from mjpoincare.scenarios.base import Tolerances

TOLERANCES: dict[str, Tolerances] = {
    "accurate": Tolerances(
        bounds={"sigma4": 1e-6, "energy_loss": 1e-5, "heading": 1e-4, "final_speed": 1e-4},
        why="the suite's targets (1e-6 on sigma4, 1e-5 on the energy per impact), with the stance ended by a "
            "fractional step; the preset is the cheapest setting a search found to hold them at every coverage point "
            "(docs/results/tune/slotted-skate.md)"
    ),
    "fast": Tolerances(
        bounds={"sigma4": 1e-3, "energy_loss": 1e-3, "heading": 0.01, "final_speed": 0.01},
        why="RK4 at 0.49 ms with a 3.9 ms peg contact: at the defaults (V0 = 1) it errs by 1e-8 on sigma4 and 4e-6 "
            "on the energy, but the bounds hold the preset at every coverage point, and the fast slide (V0 = 20: a "
            "few steps per stance) errs by 3.7e-4 on sigma4_backward (the search's worst ratio, 0.374); the preset "
            "is the cheapest setting a search found within half of the bounds there (docs/results/tune/"
            "slotted-skate.md)"
    ),
}
