"""A validation result: parameters, settings, checks, timings and captured warnings; table and JSON."""

from __future__ import annotations

import json
import math
import os
import secrets
import stat
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mjpoincare.analysis.checks import Check, jsonable
from mjpoincare.analysis.tables import text_table
from mjpoincare.core.outputs import (
    AnalyticValues,
    BasinMap,
    FitSummary,
    Reported,
    ReturnMapPlot,
    SectionConvergence,
)
from mjpoincare.core.params import ParameterError
from mjpoincare.core.version import VERSION


@dataclass
class Result:
    """Everything a run reports. ``passed`` is True only if every check passed.

    The typed outputs (``analytic`` to ``extrapolated``) are what the commands read; ``extras`` is the scenario's
    free-form data, kept apart (the JSON nests it under ``extras``) so that none of it overwrites a field.
    """

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
    analytic: AnalyticValues | None = None
    fit: FitSummary | None = None
    return_map: ReturnMapPlot | None = None
    section_convergence: SectionConvergence | None = None
    basins: BasinMap | None = None
    reported: dict[str, Reported] = field(default_factory=dict)
    #: MuJoCo's contact diagnostics (``--set diagnostics=1``): deepest penetration and kinetic energies.
    diagnostics: dict[str, float] | None = None
    #: ``--peer``: the outside simulator's value of each check (:func:`mjpoincare.engines.peers.compare.compare`).
    peer: dict[str, Any] | None = None
    #: ``--extrapolate``: the Richardson values of the checks (:func:`mjpoincare.commands.extrapolate.extrapolate`).
    extrapolated: dict[str, Any] | None = None

    @property
    def passed(self) -> bool:
        """All checks passed (a diverged run or a MuJoCo warning fails the ``stable`` check)."""
        return all(c.passed for c in self.checks)

    def to_document(self) -> dict[str, Any]:
        """The CLI's ``validate --json`` document of this one run (:func:`results_document`: ``schema``,
        ``mjpoincare``, ``mujoco`` and ``results``, whose one element is :meth:`to_dict`)."""
        return results_document([self])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (vectors as lists, complex numbers as ``[re, im]``): the run's fields, each typed output
        it has under its own key (``basins`` as ``basins`` and ``basin_bands``), and ``extras``
        (docs/result-json.md); one element of the ``validate --json`` document's ``results``."""
        out: dict[str, Any] = {
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
        }
        for name in ("analytic", "fit", "return_map", "section_convergence"):
            if (value := getattr(self, name)) is not None:
                out[name] = value.to_dict()
        if self.basins is not None:
            out["basins"], out["basin_bands"] = list(self.basins.table), list(self.basins.bands)
        if self.reported:
            out["reported"] = {name: item.to_dict() for name, item in self.reported.items()}
        for name in ("diagnostics", "peer", "extrapolated"):
            if (value := getattr(self, name)) is not None:
                out[name] = value
        out["extras"] = self.extras
        return jsonable(out)

    def table(self) -> str:
        """The check table a person reads: analytic, simulated, error, tolerance, verdict."""
        backend = self.settings.get("backend", "mujoco")
        engine = (f"MuJoCo {self.mujoco_version}" if backend == "mujoco"
                  else f"MuJoCo {self.mujoco_version} models on {backend} ({self.settings.get('precision')})")
        head = (f"{self.scenario}  preset={self.preset}  {engine}  "
                + " ".join(f"{k}={v}" for k, v in self.params.items()))
        rows = [(c.name, format_value(c.analytic), format_value(c.simulated),
                 f"{format_value(c.error)} {c.kind}", f"{c.tolerance:.3g}", "PASS" if c.passed else "FAIL")
                for c in self.checks]
        lines = [head, text_table(("check", "analytic", "simulated", "error", "tolerance", "verdict"), rows)]
        t = self.timing
        lines.append(f"wall {t['wall_s']:.2f} s, {t['steps']:.3g} steps, {t['steps_per_s']:.3g} steps/s "
                     f"(MuJoCo alone {t['rollout_steps_per_s']:.3g} steps/s)")
        for name, item in self.reported.items():  # figures a check table shows but does not judge
            lines.append(f"reported {name}: {format_value(float(item.value))} {item.unit} ({item.note})")
        if self.diverged:
            lines.append(f"DIVERGED trajectories: {self.diverged}")
        lines.extend(f"mujoco warning: {w}" for w in self.warnings)
        failed = [c for c in self.checks if not c.passed]
        if failed:
            lines.append(f"{len(failed)} of {len(self.checks)} checks failed:")
            lines.extend(f"  {c.name}: " + (f"error {format_value(c.error)} > tolerance {c.tolerance:.3g}"
                                             if math.isfinite(c.error) else "not measured") + f"; {c.why}"
                         for c in failed)
        return "\n".join(lines)


#: The version of the ``validate --json`` document's shape (:func:`results_document`); it changes when a reader
#: written for the old shape would misread the new one.
RESULTS_SCHEMA = 3


def results_document(results: list[Result]) -> dict[str, Any]:
    """``validate --json``'s document, one shape for one scenario or many: ``schema`` (:data:`RESULTS_SCHEMA`),
    ``mjpoincare`` (the package's version), ``mujoco`` (MuJoCo's) and ``results``, each run's
    :meth:`Result.to_dict` in the order they ran."""
    return {"schema": RESULTS_SCHEMA, "mjpoincare": VERSION,
            "mujoco": results[0].mujoco_version if results else None, "results": [r.to_dict() for r in results]}


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


def _in_place(target: Path) -> bool:
    """Whether ``target`` (symlinks followed) exists and is not a regular file or a folder: a device, FIFO or
    terminal, which an output is written into as it is, never replaced."""
    try:
        mode = target.stat().st_mode
    except OSError:
        return False
    return not (stat.S_ISREG(mode) or stat.S_ISDIR(mode))


def check_output_path(path: str | None, option: str, *, directory: bool = False) -> None:
    """Refuse an output path that cannot be written, before any simulation. A symlink is followed (the link stays, its
    target is written). A device, FIFO or terminal that exists is written in place (never replaced) and must be
    writable; a socket is refused. Otherwise the nearest existing folder on the way to ``path`` (``path`` itself when
    ``directory``) must be a directory that takes a new file: missing folders are created when the output is written.
    ``None`` and ``-`` (stdout) pass, except ``-`` for a folder (``directory``). Raises :class:`ParameterError`
    naming ``option``."""
    if path is None:
        return
    if path == "-":
        if directory:
            raise ParameterError(f"{option} -: {option} writes a folder of files, not a stream; give a folder")
        return
    target = Path(os.path.realpath(path))
    if not directory and target.is_dir():
        raise ParameterError(f"{option} {path} is a directory, not a file")
    if not directory and _in_place(target):
        if stat.S_ISSOCK(target.stat().st_mode):
            raise ParameterError(f"{option} {path} is a socket, not a file")
        if not os.access(target, os.W_OK):
            raise ParameterError(f"{option} {path} cannot be written: no write permission")
        return
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


#: The suffixes a plot (matplotlib's ``savefig``) is written as.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def check_plot_path(path: str | None, option: str) -> None:
    """:func:`check_output_path` for a plot, whose format its suffix chooses: one of :data:`PLOT_SUFFIXES`."""
    if path is not None and Path(path).suffix.lower() not in PLOT_SUFFIXES:
        raise ParameterError(f"{option} {path}: a plot is written as {', '.join(PLOT_SUFFIXES)} by its suffix "
                             f"(got {Path(path).suffix or 'none'!r})")
    check_output_path(path, option)


def distinct_outputs(**paths: str | None) -> None:
    """Refuse two outputs given one path (``--json out.json --report out.json``), before any simulation: options by
    keyword (``json="a.json"``, ``report="a.json"``); ``None`` and ``-`` are not compared. Symlinks are followed."""
    seen: dict[str, str] = {}
    for option, path in paths.items():
        if path is None or path == "-":
            continue
        real = os.path.realpath(path)
        flag = "--" + option.replace("_", "-")
        if real in seen:
            raise ParameterError(f"{seen[real]} and {flag} are both {path}: give each output its own path")
        seen[real] = flag


def write_json(payload: Any, path: str) -> None:
    """Write ``payload`` as JSON to ``path`` (:func:`write_bytes`); ``-`` is stdout."""
    write_text(json.dumps(payload, indent=2, allow_nan=False) + "\n", path)


def write_text(text: str, path: str) -> None:
    """Write ``text`` to ``path`` (:func:`write_bytes`); ``-`` is stdout."""
    if path == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    write_bytes(text.encode(), path)


def write_bytes(data: bytes, path: str) -> None:
    """Write ``data`` to ``path``. A regular file (or a new one) is written whole or not at all: a temp file beside it,
    then renamed over it; missing folders are created. A symlink is followed: its target is written and the link
    stays. A device, FIFO or terminal is written in place, never replaced (``/dev/null``, ``/dev/stdout``); a failed
    write there raises :class:`ParameterError` naming ``path``."""
    target = Path(os.path.realpath(path))
    if _in_place(target):
        try:
            with target.open("wb") as handle:
                handle.write(data)
        except OSError as err:  # /dev/full; a FIFO whose reader left
            raise ParameterError(f"cannot write {path}: {err.strerror or err}") from None
        return
    target.parent.mkdir(parents=True, exist_ok=True)
    while True:  # os.open with mode 0o666: the caller's umask applies, as to any new file, and is never changed
        tmp = target.parent / f".{target.name}.{secrets.token_hex(6)}.tmp"
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            break
        except FileExistsError:
            continue
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
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
