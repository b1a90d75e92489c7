"""Parameter declarations: coercion, ranges, and the one-line messages users see."""

from __future__ import annotations

import pytest

from mjpoincare.params import Param, ParameterError, parse_assignments, resolve, unknown

SPOKES = Param("spokes", 8, "spokes", int, 3, 64)
SLOPE = Param("slope", 0.08, "slope", float, 0.0, 1.5, True, True)
CONE = Param("cone", "elliptic", "cone", str, choices=("pyramidal", "elliptic"))


def test_coerce_converts_text() -> None:
    assert SPOKES.coerce("10") == 10
    assert SLOPE.coerce("0.1") == pytest.approx(0.1)
    assert CONE.coerce("Pyramidal") == "pyramidal"


@pytest.mark.parametrize(
    ("param", "value", "needle"),
    [
        (SPOKES, "2", "spokes must be in [3, 64] (got 2)"),
        (SPOKES, "8.5", "spokes must be an integer"),
        (SLOPE, "-0.1", "slope must be in (0, 1.5) (got -0.1)"),
        (SLOPE, "0", "slope must be in (0, 1.5)"),
        (SLOPE, "abc", "slope must be a number in (0, 1.5) (got 'abc')"),
        (SLOPE, "nan", "slope must be a finite number"),
        (CONE, "round", "cone must be one of pyramidal, elliptic"),
    ],
)
def test_bad_values_name_parameter_and_range(param: Param, value: str, needle: str) -> None:
    with pytest.raises(ParameterError) as err:
        param.coerce(value)
    assert needle in str(err.value)
    assert "\n" not in str(err.value)


def test_assignments_and_unknown_names() -> None:
    assert parse_assignments(["spokes=10", "slope = 0.1", "spokes=12"]) == {"spokes": "12", "slope": "0.1"}
    with pytest.raises(ParameterError, match="name=value"):
        parse_assignments(["spokes"])
    with pytest.raises(ParameterError, match="unknown parameter 'spoke'"):
        unknown(["spoke"], (SPOKES, SLOPE))
    values = resolve((SPOKES, SLOPE), {"spokes": 8, "slope": 0.08}, {"slope": "0.1", "other": "x"})
    assert values == {"spokes": 8, "slope": 0.1}
