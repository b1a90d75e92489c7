"""Tables as text: markdown for the generated pages and the commands' printed tables, space-aligned columns for the
terminal's check tables.

Both renderers write the cells as given: formatting a value and escaping it for markdown (:func:`table_cell`) are
the caller's."""

from __future__ import annotations

from collections.abc import Iterable, Sequence, Sized
from typing import TypeVar

_Row = TypeVar("_Row", bound=Sequence[str | None])


def markdown_table(header: Sequence[str | None], rows: Iterable[Sequence[str | None]]) -> str:
    """A markdown table: the header line, the ``|---|`` rule under it, then one line per row.

    Each cell is written between ``| `` and `` |``. ``None`` is a cell a column leaves blank for this row (a
    column that does not apply), written ``| |``; an empty string is an empty value and keeps its padding,
    ``|  |``.

    Args:
        header: the columns' titles.
        rows: the rows, each with one cell per column.

    Returns:
        The table's lines joined by newlines, without a trailing newline.

    Raises:
        ValueError: if a row has more or fewer cells than the header.
    """
    lines = [_markdown_line(header), "|" + "---|" * len(header)]
    lines += [_markdown_line(row) for row in _checked(header, rows)]
    return "\n".join(lines)


def _markdown_line(cells: Sequence[str | None]) -> str:
    return "|" + "".join(" |" if cell is None else f" {cell} |" for cell in cells)


def _checked(header: Sized, rows: Iterable[_Row]) -> list[_Row]:
    """``rows`` as a list, each row checked to have one cell per column of ``header``."""
    rows = list(rows)
    for row in rows:
        if len(row) != len(header):
            raise ValueError(f"a row of {len(row)} cells in a table of {len(header)} columns: {row!r}")
    return rows


def table_cell(text: str) -> str:
    """``text`` safe inside a markdown table cell (pipes escaped, one line)."""
    return " ".join(text.split()).replace("|", "\\|")


def text_table(header: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """Columns aligned with spaces: each cell left-justified to its column's widest cell (the header's included),
    two spaces between columns, no trailing spaces.

    Args:
        header: the columns' titles, the first line.
        rows: the rows, each with one cell per column.

    Returns:
        The table's lines joined by newlines, without a trailing newline.

    Raises:
        ValueError: if a row has more or fewer cells than the header.
    """
    lines = [header, *_checked(header, rows)]
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
                     for line in lines)
