"""Output paths keep what they are: a FIFO, a device and a symlink given as an output are written through, never
replaced by a regular file; a missing folder is created; two outputs to one path, a socket and a folder are refused
before any simulation (:mod:`mjpoincare.core.result`)."""

from __future__ import annotations

import json
import os
import socket
import stat
import threading
from pathlib import Path

import pytest

from mjpoincare.cli import main
from mjpoincare.core.params import ParameterError
from mjpoincare.core.result import check_output_path, distinct_outputs, write_json


def test_a_fifo_is_written_in_place(tmp_path: Path) -> None:
    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    read: list[bytes] = []
    reader = threading.Thread(target=lambda: read.append(fifo.read_bytes()))
    reader.start()
    check_output_path(str(fifo), "--json")
    write_json({"a": 1}, str(fifo))
    reader.join(timeout=10)
    assert json.loads(read[0]) == {"a": 1}
    assert stat.S_ISFIFO(fifo.lstat().st_mode)


def test_a_device_is_written_in_place() -> None:
    check_output_path("/dev/null", "--json")
    write_json({"a": 1}, "/dev/null")
    assert stat.S_ISCHR(Path("/dev/null").lstat().st_mode)


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full on this system")
def test_a_full_device_is_one_line_naming_the_path_and_stays_a_device() -> None:
    with pytest.raises(ParameterError, match="cannot write /dev/full"):
        write_json({"a": 1}, "/dev/full")
    assert stat.S_ISCHR(Path("/dev/full").lstat().st_mode)


def test_a_symlink_is_written_through_and_stays_a_link(tmp_path: Path) -> None:
    target, link = tmp_path / "real.json", tmp_path / "link.json"
    target.write_text("old")
    link.symlink_to(target)
    write_json({"a": 1}, str(link))
    assert link.is_symlink() and json.loads(target.read_text()) == {"a": 1}


def test_missing_folders_are_created_and_the_file_written_whole(tmp_path: Path) -> None:
    path = tmp_path / "new" / "deeper" / "out.json"
    check_output_path(str(path), "--json")
    write_json({"a": 1}, str(path))
    assert json.loads(path.read_text()) == {"a": 1}
    assert [p.name for p in path.parent.iterdir()] == ["out.json"]  # no temp file left beside it


def test_a_socket_and_a_folder_are_refused(tmp_path: Path) -> None:
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(tmp_path / "s.sock"))
        with pytest.raises(ParameterError, match="is a socket, not a file"):
            check_output_path(str(tmp_path / "s.sock"), "--json")
    with pytest.raises(ParameterError, match="is a directory, not a file"):
        check_output_path(str(tmp_path), "--json")


def test_two_outputs_to_one_path_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(ParameterError, match="--json and --report are both"):
        distinct_outputs(json=str(tmp_path / "a"), report=str(tmp_path / "a"))
    assert main(["validate", "rimless-wheel", "--json", str(tmp_path / "x"), "--report", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "give each output its own path" in err
    assert not (tmp_path / "x").exists()
