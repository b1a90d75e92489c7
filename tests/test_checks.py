"""analysis.checks: verdicts with stated tolerances."""

from __future__ import annotations

import math

from mjpoincare.analysis import checks


def test_categorical_error_is_the_fraction_that_differ() -> None:
    check = checks.categorical("gait_type", "B", "", 1, 4, "why")
    assert (check.analytic, check.simulated, check.error, check.tolerance, check.kind) == ("B", "none", 0.25, 0.0,
                                                                                          "fraction")
    assert math.isnan(checks.categorical("gait_type", "B", "B", 0, 0, "why").error)


def test_most_common() -> None:
    assert checks.most_common(["a", "b", "b"]) == "b"
    assert checks.most_common([]) == ""
