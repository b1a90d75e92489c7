"""The resumable job loop: rows kept in the results file after every job, resumed from it, refused for another run."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mjpoincare.core.parallel import ResumableRows
from mjpoincare.core.params import ParameterError

HEADER = {"run": "squares"}


def _square(k: int) -> dict[str, float]:
    return {"k": k, "square": k * k}


def _squares(*ks: int) -> list[dict[str, float]]:
    return [_square(k) for k in ks]


def test_rows_are_written_whole_after_every_job_and_resumed_in_the_keys_order(tmp_path: Path) -> None:
    path = tmp_path / "rows.json"
    files: list[dict] = []

    def snapshot(new: list[dict]) -> str:
        files.append(json.loads(path.read_text()))
        return f"{len(new)} rows"

    first = ResumableRows.open(HEADER, str(path), "k", [3, 1, 2], resume=False)
    assert first.todo == [3, 1, 2]
    assert first.run(_square, [(3,), (1,)], label="squares", unit="row", describe=snapshot) == _squares(3, 1)
    assert files == [{**HEADER, "rows": _squares(3)}, {**HEADER, "rows": _squares(3, 1)}]
    again = ResumableRows.open(HEADER, str(path), "k", [1, 2, 4, 3, 1], resume=True)
    assert again.keys == [1, 2, 4, 3] and again.todo == [2, 4]
    assert again.run(_squares, [(2, 4)], label="squares", unit="row", describe=snapshot) == _squares(1, 2, 4, 3)
    assert files[-1] == {**HEADER, "rows": _squares(1, 2, 4, 3)}
    fresh = ResumableRows.open(HEADER, str(path), "k", [1, 5], resume=False)
    assert fresh.todo == [1, 5] and fresh.ordered() == []


def test_resumed_rows_are_restored_and_only_the_wanted_ones_kept(tmp_path: Path) -> None:
    path = tmp_path / "rows.json"
    path.write_text(json.dumps({**HEADER, "rows": [{"k": 1, "square": None}, {"k": 9, "square": 81}]}))
    run = ResumableRows.open(HEADER, str(path), "k", [1, 2], resume=True,
                             restore=lambda row: {k: math.nan if v is None else v for k, v in row.items()})
    assert run.todo == [2] and list(run.rows) == [1] and math.isnan(run.rows[1]["square"])


@pytest.mark.parametrize(("path", "needle"), [(None, "--resume needs --json PATH"),
                                              ("-", "--resume needs --json PATH"),
                                              ("other", "holds a different sweep (run differ)"),
                                              ("broken", "--resume: cannot read")])
def test_resume_is_refused_without_a_file_of_the_same_run(path: str | None, needle: str, tmp_path: Path) -> None:
    (tmp_path / "other").write_text(json.dumps({"run": "cubes", "rows": []}))
    (tmp_path / "broken").write_text("{")
    target = path if path in (None, "-") else str(tmp_path / path)
    with pytest.raises(ParameterError, match=needle.replace("(", r"\(").replace(")", r"\)")):
        ResumableRows.open(HEADER, target, "k", [1], resume=True)
