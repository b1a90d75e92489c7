"""Progress of the long commands (sweep, converge, bench, tune, the friction wheel's mu sweep): one tqdm bar on
stderr, silent off a terminal and under CI, so pipes, logs and JSON on stdout carry none of it."""

from __future__ import annotations

import os
import sys
from typing import Any

from tqdm import tqdm

__all__ = ["bar", "quiet"]


def quiet() -> bool:
    """True when progress is not shown: stderr is not a terminal, or ``CI`` is set to a true value."""
    return not sys.stderr.isatty() or os.environ.get("CI", "").lower() in ("1", "true", "yes")


def bar(total: int, label: str, *, unit: str = "run", initial: int = 0) -> Any:
    """A progress bar over ``total`` items, ``initial`` of them done (resumed); use it as a context manager, call
    ``update(n)`` per finished item and ``set_postfix_str(text)`` for the last one's outcome."""
    return tqdm(total=total, initial=initial, desc=label, unit=unit, disable=quiet(), file=sys.stderr,
                dynamic_ncols=True)
