"""A validation result: parameters, settings, checks, timings and captured warnings; table and JSON."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mjpoincare.analysis.checks import Check, jsonable
from mjpoincare.analysis.tables import text_table
from mjpoincare.params import ParameterError


@dataclass
class Result:
    """Everything a run reports. ``passed`` is True only if every check passed."""

    scenario: str
    preset: str
    seed: int
    params: dict[str, Any]
    settings: dict[str, Any]
    mujoco_version: str
    checks: list[Check]
    timing: dict[str, float]
    warnings: list[str]
    diverged: list[int]
    extras: dict[str, Any] = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        """All checks passed (a diverged run or a MuJoCo warning fails the ``stable`` check)."""
        return all(c.passed for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (vectors as lists, complex numbers as ``[re, im]``)."""
        return jsonable({
            "scenario": self.scenario,
            "preset": self.preset,
            "seed": self.seed,
            "passed": self.passed,
            "params": self.params,
            "settings": self.settings,
            "mujoco_version": self.mujoco_version,
            "checks": [c.to_dict() for c in self.checks],
            "timing": self.timing,
            "warnings": self.warnings,
            "diverged_trajectories": self.diverged,
            **self.extras,
        })

    def table(self) -> str:
        """The check table a person reads: analytic, simulated, error, tolerance, verdict."""
        backend = self.settings.get("backend", "mujoco")
        engine = (f"MuJoCo {self.mujoco_version}" if backend == "mujoco"
                  else f"MuJoCo {self.mujoco_version} models on {backend} ({self.settings.get('precision')})")
        head = (f"{self.scenario}  preset={self.preset}  {engine}  "
                + " ".join(f"{k}={v}" for k, v in self.params.items()))
        rows = [(c.name, format_value(c.analytic), format_value(c.simulated),
                 f"{format_value(c.error)} {c.kind[:3]}", f"{c.tolerance:.3g}", "PASS" if c.passed else "FAIL")
                for c in self.checks]
        lines = [head, text_table(("check", "analytic", "simulated", "error", "tolerance", "verdict"), rows)]
        t = self.timing
        lines.append(f"wall {t['wall_s']:.2f} s, {t['steps']:.3g} steps, {t['steps_per_s']:.3g} steps/s "
                     f"(MuJoCo alone {t['rollout_steps_per_s']:.3g} steps/s)")
        for name, item in self.extras.get("reported", {}).items():  # figures a check table shows but does not judge
            lines.append(f"reported {name}: {format_value(float(item['value']))} {item['unit']} ({item['note']})")
        if self.diverged:
            lines.append(f"DIVERGED trajectories: {self.diverged}")
        lines.extend(f"mujoco warning: {w}" for w in self.warnings)
        return "\n".join(lines)


def format_value(value: Any, *, from_json: bool = False) -> str:
    """A value as the tables print it: 6 significant digits, arrays and lists element-wise, complex ``a+bj``.

    Args:
        value: a check's value, a parameter or a setting: as the run holds it, or as its JSON holds it
            (:meth:`Result.to_dict`, read back by the generated pages).
        from_json: ``value`` is JSON: ``null`` is a non-finite or missing number, written ``nan``, and booleans are
            written as JSON writes them, ``true`` and ``false`` (without it, ``None``, ``True`` and ``False``, as
            Python writes them).

    Returns:
        The text of the value.
    """
    if from_json and value is None:
        return "nan"
    if from_json and isinstance(value, bool):
        return str(value).lower()
    if hasattr(value, "tolist") and not isinstance(value, float | complex):
        value = value.tolist()
    if isinstance(value, list | tuple):
        return "[" + ", ".join(format_value(v, from_json=from_json) for v in value) + "]"
    if isinstance(value, complex):
        return f"{value.real:.5g}{value.imag:+.5g}j" if value.imag else f"{value.real:.6g}"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def check_output_path(path: str | None, option: str, *, directory: bool = False) -> None:
    """Refuse an output path that cannot be written, before any simulation: the nearest existing folder on the way
    to ``path`` (``path`` itself when ``directory``) must be a directory that takes a new file. ``None`` and ``-``
    (stdout) pass. Raises :class:`ParameterError` naming ``option``."""
    if path is None or path == "-":
        return
    target = Path(path)
    if not directory and target.is_dir():
        raise ParameterError(f"{option} {path} is a directory, not a file")
    folder = target if directory else target.parent
    while not folder.exists() and folder != folder.parent:
        folder = folder.parent
    if not folder.is_dir():
        raise ParameterError(f"{option} {path} cannot be written: {folder} is not a directory")
    try:
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:
        raise ParameterError(f"{option} {path} cannot be written: {err.strerror or err} in {folder}") from None


def write_json(payload: Any, path: str) -> None:
    """Write ``payload`` as JSON to ``path`` whole or not at all (temp file + rename); ``-`` is stdout."""
    write_text(json.dumps(payload, indent=2, allow_nan=False) + "\n", path)


def write_text(text: str, path: str) -> None:
    """Write ``text`` to ``path`` whole or not at all (temp file + rename); ``-`` is stdout."""
    if path == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)
    try:
        with os.fdopen(fd, "w") as handle:
            handle.write(text)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def resumed_rows(json_path: str | None, header: dict[str, Any]) -> list[dict[str, Any]]:
    """Rows of a previous run of the same sweep (same scenario, parameter, settings and preset)."""
    if not json_path or json_path == "-" or not Path(json_path).exists():
        return []
    try:
        previous = json.loads(Path(json_path).read_text())
    except (OSError, json.JSONDecodeError) as err:
        raise ParameterError(f"--resume: cannot read {json_path} ({err})") from None
    mismatch = [k for k, v in header.items() if previous.get(k) != v]
    if mismatch:
        raise ParameterError(f"--resume: {json_path} holds a different sweep ({', '.join(mismatch)} differ)")
    return list(previous.get("rows", []))
