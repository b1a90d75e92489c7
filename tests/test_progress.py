"""The long commands' progress bar (mjpoincare.core.progress): shown on a terminal, silent in pipes and under CI."""

from __future__ import annotations

import io
import sys

import pytest

from mjpoincare.core import progress


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize(("tty", "ci", "shown"), [(True, "", True), (True, "true", False), (True, "1", False),
                                                  (False, "", False), (True, "false", True)])
def test_the_bar_is_shown_only_on_a_terminal_outside_ci(monkeypatch: pytest.MonkeyPatch, tty: bool, ci: str,
                                                        shown: bool) -> None:
    stream = _Terminal() if tty else io.StringIO()
    monkeypatch.setattr(sys, "stderr", stream)
    monkeypatch.setenv("CI", ci)
    with progress.bar(3, "sweep slope", unit="point", initial=1) as bar:
        bar.set_postfix_str("slope=0.1: pass")
        bar.update(2)
    out = stream.getvalue()
    assert progress.quiet() is not shown
    assert ("sweep slope" in out and "3/3" in out) if shown else out == ""
