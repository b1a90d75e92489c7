"""Shared fixtures: every test runs in a temporary working directory (MUJOCO_LOG.TXT would show there)."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

# dm_control (the environments' tests) opens a GLFW context at import unless told otherwise; off-screen EGL works here
os.environ.setdefault("MUJOCO_GL", "egl")


@pytest.fixture(autouse=True)
def _in_tmp_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    monkeypatch.chdir(tmp_path)
    yield tmp_path
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists(), "MuJoCo wrote MUJOCO_LOG.TXT into the working directory"


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The backend tests run last: they load JAX and Warp, whose native threads make every later process pool spawn
    its workers instead of forking them (:func:`mjpoincare.parallel.start_method`), which costs the sweeps and
    convergence ladders after them their start-up time."""
    items.sort(key=lambda item: item.nodeid.startswith("tests/test_backends.py"))
