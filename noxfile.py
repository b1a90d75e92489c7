"""The MuJoCo release matrix: one nox session per MuJoCo release, uv as the installer.

    nox -s "release(mujoco='3.3.7')"          the history's runs on MuJoCo 3.3.7, one of the releases the package
                                              index listed (make releases runs those the page lacks)
    nox -s release_point -- 3.3.5 [ARGS]      the same on any release, for python -m mjpoincare.gate.releases bisect
    nox -s oldest                             every built-in scenario's default validation on the oldest MuJoCo
                                              admitted (CI)

Each session installs the checkout (editable, so that its runs are stamped with the git commit) and one MuJoCo
release into its own environment, every other dependency pinned by requirements/lock.txt (so that a change between
releases is MuJoCo's); the resolver picks the dm-control release that admits that MuJoCo.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import nox

from mjpoincare.gate.releases import OLDEST, history_scenarios, load_index

nox.options.default_venv_backend = "uv"
nox.options.reuse_existing_virtualenvs = True
nox.options.sessions = ["oldest"]

def _follows_mujoco(package: str) -> bool:
    """Whether the lock's pin of ``package`` follows the MuJoCo release under test: MuJoCo's own packages (mujoco, and
    every mujoco-* one: mujoco-core and mujoco-studio, which mujoco 4 pins at its own version, mujoco-mjx,
    mujoco-warp) and dm-control."""
    return package in ("mujoco", "dm-control") or package.startswith("mujoco-")


def _install(session: nox.Session, mujoco: str, *, editable: bool = True) -> None:
    """The checkout and MuJoCo ``mujoco``, the rest of requirements/lock.txt as constraints."""
    lock = Path("requirements/lock.txt").read_text().splitlines()
    kept = [line for line in lock if not _follows_mujoco(line.split("==")[0].strip())]
    constraints = Path(session.create_tmp()) / "constraints.txt"
    constraints.write_text("\n".join(kept) + "\n")
    session.install("-c", str(constraints), *(["-e", "."] if editable else ["."]), f"mujoco=={mujoco}")


@nox.session
@nox.parametrize("mujoco", load_index()["history"])
def release(session: nox.Session, mujoco: str) -> None:
    """The release history's runs on one MuJoCo (``python -m mjpoincare.gate.releases run``; resumable)."""
    _install(session, mujoco)
    session.run("python", "-m", "mjpoincare.gate.releases", "run", *session.posargs)


@nox.session
def release_point(session: nox.Session) -> None:
    """Any MuJoCo release (the first argument), for a bisection between two releases of the history."""
    if not session.posargs:
        session.error("usage: nox -s release_point -- MUJOCO_VERSION [python -m mjpoincare.gate.releases run ARGS]")
    version, *rest = session.posargs
    _install(session, version)
    session.run("python", "-m", "mjpoincare.gate.releases", "run", *rest)


@nox.session
def oldest(session: nox.Session) -> None:
    """The default validation of every built-in scenario (the release history's, not only the default scenarios) on
    the oldest MuJoCo that pyproject.toml admits, installed from the checkout as a package, run from an empty
    directory: it must exit 0."""
    _install(session, OLDEST, editable=False)
    session.run("python", "-c", f"import mujoco; assert mujoco.__version__ == {OLDEST!r}, mujoco.__version__")
    with tempfile.TemporaryDirectory() as empty:
        session.chdir(empty)
        session.run("mjpoincare", "validate", *history_scenarios())
