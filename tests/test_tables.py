"""The table renderers every page and command writes its tables with, and the value formatter of their cells."""

from __future__ import annotations

import numpy as np
import pytest
from mjpoincare.analysis.tables import markdown_table, table_cell, text_table

from mjpoincare.core.result import format_value


def test_markdown_table_writes_header_rule_and_rows() -> None:
    table = markdown_table(("check", "error"), [("eigenvalue", "0.02"), ("stable", "0")])
    assert table == "| check | error |\n|---|---|\n| eigenvalue | 0.02 |\n| stable | 0 |"


def test_markdown_table_tells_a_blank_column_from_an_empty_value() -> None:
    table = markdown_table(("run", None), [("compile s", None), ("wall s", "")])
    assert table.splitlines() == ["| run | |", "|---|---|", "| compile s | |", "| wall s |  |"]


def test_markdown_table_without_rows_is_its_header() -> None:
    assert markdown_table(("a", "b", "c"), []) == "| a | b | c |\n|---|---|---|"


@pytest.mark.parametrize("row", [("one",), ("one", "two", "three")])
def test_tables_refuse_a_row_of_another_width(row: tuple[str, ...]) -> None:
    with pytest.raises(ValueError, match="columns"):
        markdown_table(("a", "b"), [row])
    with pytest.raises(ValueError, match="columns"):
        text_table(("a", "b"), [row])


def test_table_cell_escapes_pipes_and_joins_lines() -> None:
    assert table_cell("|lambda|  from\nthe fit") == "\\|lambda\\| from the fit"


def test_text_table_aligns_columns_and_strips_line_ends() -> None:
    table = text_table(("check", "error", "verdict"), [("eigenvalue", "0.02", "PASS"), ("x", "1e-05", "")])
    assert table.splitlines() == ["check       error  verdict",
                                  "eigenvalue  0.02   PASS",
                                  "x           1e-05"]


def test_format_value_spells_values_as_the_run_or_its_json_holds_them() -> None:
    assert format_value(np.array([0.5, 1 / 3])) == "[0.5, 0.333333]"
    assert format_value(complex(0.25, -0.5)) == "0.25-0.5j"
    assert format_value(complex(0.25, 0.0)) == "0.25"
    assert [format_value(v) for v in (None, True, float("nan"))] == ["None", "True", "nan"]
    assert format_value([None, True, 1 / 3, 2], from_json=True) == "[nan, true, 0.333333, 2]"
