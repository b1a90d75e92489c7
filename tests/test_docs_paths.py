"""The repository's text refers to nothing outside it: no absolute path into a machine's files, no relative path
that climbs out of the repository.

Scanned: README.md, every docs/**/*.md (generated pages included), src/**/*.py, analysis/**/*.py and every text file
under models/. A hit fails with its file and line:

* an absolute path into a machine's files: /tmp/, /work/, /home/, /root/, /Users/, /mnt/ (at the start of a path,
  not inside a URL or a relative path), a Windows drive path such as C:\\, a file:/// URL to one of those, or a
  .venv/bin path with an absolute prefix (/..., ~/..., a drive);
* a relative path or markdown link starting with ../ that, resolved from the file's own directory, leaves the
  repository root (../results/x.md from docs/scenarios/ stays inside and is fine).
"""

from __future__ import annotations

import posixpath
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: The scanned file groups: README.md, the docs pages, the package sources, the analysis layer and the models.
GROUPS: dict[str, list[Path]] = {
    "README.md": [ROOT / "README.md"],
    "docs/**/*.md": sorted(ROOT.glob("docs/**/*.md")),
    "src/**/*.py": sorted(ROOT.glob("src/**/*.py")),
    "analysis/**/*.py": sorted(ROOT.glob("analysis/**/*.py")),
    "models/**": sorted(p for p in ROOT.glob("models/**/*") if p.is_file()),
}

#: Directories that only exist on a particular machine, at the start of an absolute path (not after a word
#: character, a dot or a slash: "https://host/home/", "../home/" and "a/tmp/" are not absolute paths).
MACHINE_DIR = re.compile(r"(?<![\w./])/(?:tmp|work|home|root|Users|mnt)(?![\w-])")
#: A file URL into one of those directories (its third slash follows a slash, so MACHINE_DIR skips it).
FILE_URL = re.compile(r"file:///(?:tmp|work|home|root|Users|mnt)(?![\w-])")
#: A Windows drive path: an upper-case drive letter, a colon and a backslash, at the start of a word.
DRIVE = re.compile(r"(?<![\w\\])[A-Z]:\\")
#: A virtual environment's bin directory behind an absolute prefix (/, ~/ or a drive); ".venv/bin/python" alone is a
#: path relative to the repository and fine.
VENV = re.compile(r"""(?<![\w.])(?:/|~/|[A-Za-z]:[\\/])[^\s"'`()<>]*\.venv[\\/]bin""")
#: A relative path starting with ../ (also as a markdown link target); the rest of the path up to a delimiter.
UP = re.compile(r"""(?<![\w./-])((?:\.\./)+[^\s"'`()<>\[\]#|,;]*)""")


def _text(path: Path) -> str | None:
    """The file's text, or None for a binary file (a NUL byte, or not UTF-8)."""
    data = path.read_bytes()
    if b"\0" in data:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def absolute_paths(line: str) -> list[str]:
    """The absolute machine paths in ``line``."""
    hits = [m.group(0) for pattern in (MACHINE_DIR, FILE_URL, DRIVE, VENV) for m in pattern.finditer(line)]
    return hits


def escaping_paths(line: str, directory: str) -> list[str]:
    """The ../ paths in ``line`` that, resolved from ``directory`` (POSIX, relative to the repository root), leave
    the repository."""
    out = []
    for m in UP.finditer(line):
        target = posixpath.normpath(posixpath.join(directory or ".", m.group(1)))
        if target == ".." or target.startswith("../"):
            out.append(m.group(1))
    return out


def offences(path: Path) -> list[str]:
    """``file:line: what`` for every offending path in ``path``."""
    text = _text(path)
    if text is None:
        return []
    relative = path.relative_to(ROOT)
    directory = relative.parent.as_posix()
    out = []
    for number, line in enumerate(text.splitlines(), start=1):
        for hit in absolute_paths(line):
            out.append(f"{relative}:{number}: absolute path {hit!r}")
        for hit in escaping_paths(line, "" if directory == "." else directory):
            out.append(f"{relative}:{number}: {hit!r} leaves the repository")
    return out


@pytest.mark.parametrize("group", list(GROUPS))
def test_no_path_outside_the_repository(group: str) -> None:
    files = GROUPS[group]
    assert files, f"{group} matches no file"
    found = [hit for path in files for hit in offences(path)]
    assert not found, "paths outside the repository:\n" + "\n".join(found)


@pytest.mark.parametrize(
    "line",
    [
        "see /tmp/run.json",
        "python /work/main/x.py",
        "`/home/user/data`",
        "cd /root",
        "open /Users/me/file",
        "(/mnt/data/x)",
        "path C:\\Users\\me",
        "file:///home/me/x.html",
        "/opt/proj/.venv/bin/python -m pytest",
        "~/proj/.venv/bin/python",
    ],
)
def test_absolute_paths_are_found(line: str) -> None:
    assert absolute_paths(line)


@pytest.mark.parametrize(
    "line",
    [
        ".venv/bin/python docs/scripts/rw_map.py",
        "https://example.org/home/page",
        "docs/tmp/x and ../home/y",
        "and/or a square/root",
        "x = f'{a}:\\n'",
        "tmp_path / 'work'",
    ],
)
def test_ordinary_text_is_not_an_absolute_path(line: str) -> None:
    assert not absolute_paths(line)


@pytest.mark.parametrize(
    ("line", "directory", "escapes"),
    [
        ("[results](../results/x.md)", "docs/scenarios", False),
        ("[x](../../../x.md)", "docs", True),
        ("../shared/seeds/000.txt", "", True),
        ("`../shared/x`", "docs/theory", False),
        ("see ../../../../shared/x", "docs/theory", True),
        ('f"../scenarios/{name}.md"', "src/mjpoincare", False),
        ("a/../b and ..", "docs", False),
    ],
)
def test_escaping_relative_paths(line: str, directory: str, escapes: bool) -> None:
    assert bool(escaping_paths(line, directory)) is escapes
