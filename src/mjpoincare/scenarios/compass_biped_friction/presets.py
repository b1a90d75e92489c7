"""The simulator presets of ``compass-biped-friction`` (docs/scenarios/compass-biped-friction.md, "Presets")."""

from __future__ import annotations

from mjpoincare.scenarios.compass_biped.runs import BIPED_IMPEDANCE

#: Not searched yet (``mjpoincare tune compass-biped-friction`` runs its six gaits per trial): the settings the compass
#: biped's presets had before their search, which this scenario's gate and findings were measured at.
#: Read off the preset search's studies (docs/results/tune/compass-biped-friction.md; judged at Gaits A and I, the
#: others reported): neither target has a setting within half of every tolerance, and each preset is the cheapest
#: that passes. The accurate one is the preset the scenario had before the search (nothing cheaper passed). Both
#: take compass-biped's foot impedance (BIPED_IMPEDANCE), set after the search.
PRESETS: dict[str, dict[str, float | int | str]] = {
    "fast": {"timestep": 0.00012274320508, "solref_timeconst": 0.000296056801637, "solref_dampratio": 3.60987087888,
             "integrator": "implicitfast", "cone": "pyramidal", "impratio": 1.17848215382, "noslip_iterations": 10,
             "foot_radius": 0.0014960227089, "iterations": 50, "tolerance": 2.25234824327e-07, **BIPED_IMPEDANCE},
    "accurate": {"timestep": 2e-05, "solref_timeconst": 0.0002, "solref_dampratio": 10.0, "integrator": "implicitfast",
                 "cone": "elliptic", "impratio": 10.0, "noslip_iterations": 0, "foot_radius": 0.0005,
                 "iterations": 100, "tolerance": 1e-10, **BIPED_IMPEDANCE},
}
