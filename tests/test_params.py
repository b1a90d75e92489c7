"""Parameter declarations: coercion, ranges, and the one-line messages users see."""

from __future__ import annotations

import numpy as np
import pytest

from mjpoincare.core.params import Param, ParameterError, grid_syntax, parse_assignments, parse_grid, resolve, unknown

SPOKES = Param("spokes", 8, "spokes", int, 3, 64)
SLOPE = Param("slope", 0.08, "slope", float, 0.0, 1.5, True, True)
CONE = Param("cone", "elliptic", "cone", str, choices=("pyramidal", "elliptic"))


def test_coerce_converts_text() -> None:
    assert SPOKES.coerce("10") == 10
    assert SLOPE.coerce("0.1") == pytest.approx(0.1)
    assert CONE.coerce(" pyramidal ") == "pyramidal"


def test_a_choice_is_case_sensitive_and_a_bool_is_no_number() -> None:
    """MJCF's own values are case-sensitive; ``Pyramidal`` is refused with the hint, not guessed."""
    with pytest.raises(ParameterError, match=r"cone must be one of .* values are case-sensitive"):
        CONE.coerce("Pyramidal")
    with pytest.raises(ParameterError, match="spokes must be a number"):
        SPOKES.coerce(True)


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
    assert parse_assignments(["spokes=10", "slope = 0.1"]) == {"spokes": "10", "slope": "0.1"}
    with pytest.raises(ParameterError, match=r"--set spokes is given twice \('10' and '12'\)"):
        parse_assignments(["spokes=10", "slope = 0.1", "spokes=12"])
    with pytest.raises(ParameterError, match="name=value"):
        parse_assignments(["spokes"])
    with pytest.raises(ParameterError, match="unknown parameter 'spoke'"):
        unknown(["spoke"], (SPOKES, SLOPE))
    values = resolve((SPOKES, SLOPE), {"spokes": 8, "slope": 0.08}, {"slope": "0.1", "other": "x"})
    assert values == {"spokes": 8, "slope": 0.1}


GRID = (Param("x", 0.0, "l0/delta", float), Param("y", 1.0, "1/delta^2", float, 0.0, low_open=True))


def test_parse_grid_gives_each_axis_its_values_in_the_axes_order() -> None:
    assert grid_syntax(GRID) == "x=START:STOP:N,y=START:STOP:N"
    grid = parse_grid("y=0.5:1:2, x = -1:1:3", GRID)
    assert list(grid) == ["x", "y"]
    np.testing.assert_array_equal(grid["x"], [-1.0, 0.0, 1.0])
    np.testing.assert_array_equal(grid["y"], [0.5, 1.0])
    assert parse_grid("x=0:1:8,y=1:2:2", GRID)["x"][1] == 0.1428571429  # 10 significant digits, as --values


@pytest.mark.parametrize(("text", "needle"), [
    ("x=0:1:3", "--grid expects x=START:STOP:N,y=START:STOP:N with N >= 2 (got 'x=0:1:3')"),
    ("x=0:1:3,y=0.1:1:3,z=0:1:2", "--grid expects x=START:STOP:N,y=START:STOP:N"),
    ("x=0:1:1,y=0.1:1:3", "--grid x expects START:STOP:N with numbers START, STOP and an integer N >= 2 (got x=0:1:1)"),
    ("x=a:1:3,y=0.1:1:3", "--grid x expects START:STOP:N"),
    ("x=0.5,y=0.1:1:3", "--grid x expects START:STOP:N"),
    ("x=0:1:3,y=0.1:inf:3", "--grid y expects START:STOP:N"),
    ("x=0:1:3,y=0:1:3", "--grid y = 1/delta^2 must be > 0 (got 0)"),
    ("x=0:1:3,y=-1:1:3", "--grid y = 1/delta^2 must be > 0 (got -1)"),
])
def test_bad_grids_name_the_axis_and_the_bound(text: str, needle: str) -> None:
    with pytest.raises(ParameterError) as err:
        parse_grid(text, GRID)
    assert needle in str(err.value)
    assert "\n" not in str(err.value)
