"""The compass biped's fixed-point error against the hip-to-leg mass ratio m_h / m_l (m_h = 10 kg), at both presets,
and at m_h / m_l = 1e4 under a nearly hard (solimp 0.99-0.999) and a soft (0.5-0.6) contact impedance: the evidence
for ``MAX_MASS_RATIO`` in ``src/mjpoincare/scenarios/compass_biped/__init__.py``. The refusal is lifted for this
study only, to measure past it. Prints a markdown table: the error, or the run's failure, per ratio and preset.

usage: .venv/bin/python docs/scripts/cb_mass_ratio.py"""
import math

import mjpoincare
from mjpoincare.scenarios import compass_biped

compass_biped.MAX_MASS_RATIO = math.inf  # measure past the refusal
RATIOS = (1e2, 3e2, 1e3, 1e4, 1e5, 1e6)
IMPEDANCES = ({"solimp_dmin": 0.99, "solimp_dmax": 0.999}, {"solimp_dmin": 0.5, "solimp_dmax": 0.6})


def cell(preset: str, **values: float) -> str:
    result = mjpoincare.validate("compass-biped", preset, m_l=10.0 / values.pop("ratio"), **values)
    check = next(c for c in result.checks if c.name == "fixed_point")
    if not math.isfinite(check.error):
        return "falls (no gait to fit, or none the exact model reaches)"
    return f"{check.error:.2g}" + ("" if check.passed else " (FAIL)")


print("| m_h / m_l | fast | accurate |")
print("|---|---|---|")
for ratio in RATIOS:
    print(f"| {ratio:g} | {cell('fast', ratio=ratio)} | {cell('accurate', ratio=ratio)} |")
for impedance in IMPEDANCES:
    text = f"{impedance['solimp_dmin']:g}-{impedance['solimp_dmax']:g}"
    print(f"| 1e4, solimp {text} | {cell('fast', ratio=1e4, **impedance)} | |")
