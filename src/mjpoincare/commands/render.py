"""Off-screen videos and stills of any scenario with :class:`mujoco.Renderer`, written with mediapy.

The trajectory is simulated first (one ``mujoco.rollout`` call, no rendering in the loop), then
replayed frame by frame: ``mj_setState`` + ``mj_forward`` + render. The camera tracks the
scenario's main body; contact points and forces are drawn. Models whose slope is made by tilting
gravity look flat in the world frame, so each frame is rotated by the slope angle (the ground then
falls to the right, as in the papers' figures).

The OpenGL backend is chosen before MuJoCo is imported (:func:`select_gl_backend`): the user's
``MUJOCO_GL`` if set, else the first of ``egl`` and ``osmesa`` that can open a context.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Mapping
from pathlib import Path

import numpy as np

BACKENDS = ("egl", "osmesa")
INSTALL_HINT = ("no off-screen OpenGL backend works here: install Mesa's EGL (apt-get install libegl1 "
                "libgl1-mesa-dri) for MUJOCO_GL=egl, or OSMesa (apt-get install libosmesa6) for MUJOCO_GL=osmesa")
_PROBE = "import mujoco; m = mujoco.MjModel.from_xml_string('<mujoco/>'); mujoco.Renderer(m, 8, 8).render()"


class RenderError(RuntimeError):
    """Rendering is impossible here; the message says what to install."""


def select_gl_backend() -> str:
    """Set ``MUJOCO_GL`` (if unset) to a backend that works; must run before ``import mujoco``.

    A ``MUJOCO_GL`` the user set is kept when it works; when it does not, the error names the backends that do work
    here (so ``osmesa`` without OSMesa says to use ``egl`` rather than that nothing works)."""
    chosen = os.environ.get("MUJOCO_GL")
    if chosen and _works(chosen):
        return chosen
    working = [b for b in BACKENDS if b != chosen and _works(b)]
    if not chosen and working:
        os.environ["MUJOCO_GL"] = working[0]
        return working[0]
    if chosen and working:
        raise RenderError(f"MUJOCO_GL={chosen} does not work here, but MUJOCO_GL={working[0]} does: set "
                          f"MUJOCO_GL={working[0]} or unset MUJOCO_GL")
    where = f"MUJOCO_GL={chosen} does not work" if chosen else "neither MUJOCO_GL=egl nor osmesa works"
    raise RenderError(f"{where}; {INSTALL_HINT}")


def _works(backend: str) -> bool:
    """A child process with ``MUJOCO_GL=backend`` opens a context and renders one frame."""
    env = {**os.environ, "MUJOCO_GL": backend}
    return subprocess.run([sys.executable, "-c", _PROBE], env=env, capture_output=True, timeout=120).returncode == 0


def parse_size(text: str) -> tuple[int, int]:
    """``640x480`` -> (width, height)."""
    from mjpoincare.core.params import ParameterError

    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise ParameterError(f"size must be WIDTHxHEIGHT, e.g. 640x480 (got {text!r})") from None
    if not (16 <= width <= 4096 and 16 <= height <= 4096):
        raise ParameterError(f"size must be between 16x16 and 4096x4096 (got {text!r})")
    return width, height


#: The formats ``render`` writes, by file suffix.
MEDIA_SUFFIXES = (".mp4", ".gif", ".png")


#: The longest clip ``render`` makes, s (every frame is kept in memory until the file is written).
MAX_SECONDS = 600.0


def check_clip(seconds: float, fps: int, timestep: float) -> None:
    """Refuse, before any simulation, a clip outside (0, :data:`MAX_SECONDS`] s or [1, 240] frames per second, or one
    whose MuJoCo steps (``seconds / timestep``) exceed :data:`mjpoincare.core.cost.LONG_STEPS`."""
    from mjpoincare.core.cost import refuse_long
    from mjpoincare.core.params import ParameterError

    if not 0 < seconds <= MAX_SECONDS or not 1 <= fps <= 240:
        raise ParameterError(f"--seconds must be in (0, {MAX_SECONDS:g}] and --fps in [1, 240] (got {seconds}, {fps})")
    refuse_long(seconds / timestep, f"render ({seconds:g} s at timestep {timestep:g} s)", allow=False,
                remedy="raise timestep or shorten --seconds")


def check_media_path(path: str) -> None:
    """Refuse, before any simulation, an output whose suffix is not one of :data:`MEDIA_SUFFIXES`."""
    from mjpoincare.core.params import ParameterError

    if Path(path).suffix.lower() not in MEDIA_SUFFIXES:
        raise ParameterError(f"--output {path}: the format is chosen by the suffix, one of "
                             f"{', '.join(MEDIA_SUFFIXES)} (got {Path(path).suffix or 'none'!r})")


def render_frames(name: str, assignments: Mapping[str, str], preset: str | None, seconds: float, fps: int,
                  size: tuple[int, int], *, last_only: bool = False) -> tuple[np.ndarray, dict[str, float]]:
    """Frames (n, height, width, 3) of ``seconds`` of the scenario at ``fps``, and timings; ``last_only``: only the
    last of them, (1, height, width, 3) (a still: the clip is simulated whole, one frame is drawn)."""
    import mujoco
    from scipy import ndimage

    from mjpoincare.commands.validation import resolve_inputs
    from mjpoincare.core.cost import check_chunk

    scenario, _, params, settings = resolve_inputs(name, assignments, preset)
    model = scenario.build(params, settings)
    dt = model.opt.timestep
    frame_every = max(1, round(1.0 / (fps * dt)))
    nframes = max(1, round(seconds * fps))
    check_chunk(1, nframes * frame_every, mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    start = time.perf_counter()
    clip = scenario.video_states(params, settings, model, nframes * frame_every)
    states, mocap = clip if isinstance(clip, tuple) else (clip, None)
    sim_wall = time.perf_counter() - start
    tilt = float(params[scenario.frame_tilt]) if scenario.frame_tilt else 0.0
    width, height = size
    pad = 1.0 + abs(np.sin(tilt)) * 1.2  # render larger, rotate, crop back to the requested size
    big_w, big_h = int(width * pad) // 2 * 2, int(height * pad) // 2 * 2
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, big_w)
    model.vis.global_.offheight = max(model.vis.global_.offheight, big_h)
    data = mujoco.MjData(model)
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_TRACKING
    camera.trackbodyid = model.body(scenario.track_body).id
    camera.distance, camera.elevation, camera.azimuth = scenario.camera_distance, scenario.camera_elevation, 90.0
    option = mujoco.MjvOption()
    option.flags[mujoco.mjtVisFlag.mjVIS_CONTACTPOINT] = True  # the active contacts, drawn as red discs
    model.vis.scale.contactwidth, model.vis.scale.contactheight = 0.06, 0.02
    model.vis.rgba.contactpoint[:] = (1.0, 0.15, 0.1, 1.0)
    model.vis.quality.offsamples = 0  # software (Mesa) rendering: multisampling costs more than it shows
    drawn = range(nframes - 1, nframes) if last_only else range(nframes)
    frames = np.empty((len(drawn), height, width, 3), np.uint8)
    start = time.perf_counter()
    with mujoco.Renderer(model, big_h, big_w) as renderer:
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False
        for i, frame in enumerate(drawn):
            row = (frame + 1) * frame_every - 1
            mujoco.mj_setState(model, data, states[row], mujoco.mjtState.mjSTATE_FULLPHYSICS)
            if mocap is not None:
                data.mocap_pos[:] = mocap[row]
            mujoco.mj_forward(model, data)
            renderer.update_scene(data, camera, option)
            image = renderer.render()
            if tilt:
                image = ndimage.rotate(image, -np.degrees(tilt), reshape=False, order=1, mode="nearest")
            top, left = (big_h - height) // 2, (big_w - width) // 2
            frames[i] = image[top : top + height, left : left + width]
    render_wall = time.perf_counter() - start
    return frames, {"frames": float(len(drawn)), "simulate_s": sim_wall, "render_s": render_wall,
                    "ms_per_frame": 1e3 * render_wall / len(drawn)}


def render_still(name: str, assignments: Mapping[str, str], preset: str | None, size: tuple[int, int] = (480, 360),
                 seconds: float = 0.7) -> bytes:
    """The frame of the scenario's clip nearest ``seconds`` (of those at 10 frames/s), as PNG bytes (the report's
    still).

    Raises :class:`RenderError` when no OpenGL context opens (choose the backend with :func:`select_gl_backend`
    before MuJoCo is imported).
    """
    import io

    import mujoco
    from matplotlib.image import imsave

    try:
        frames, _ = render_frames(name, assignments, preset, seconds, 10, size, last_only=True)
    except mujoco.FatalError as err:
        raise RenderError(f"MUJOCO_GL={os.environ.get('MUJOCO_GL', '')}: {err}; {INSTALL_HINT}") from None
    buffer = io.BytesIO()
    imsave(buffer, frames[-1], format="png")
    return buffer.getvalue()


def write_media(path: str, frames: np.ndarray, fps: int) -> None:
    """Write a video (``.mp4``/``.gif``) or, for ``.png``, the last frame, through
    :func:`mjpoincare.core.result.write_bytes` (whole or not at all; a device, FIFO or symlink's target is written,
    never replaced): encoded in a temporary folder first."""
    import tempfile

    import mediapy

    from mjpoincare.core.result import write_bytes

    suffix = Path(path).suffix.lower()
    with tempfile.TemporaryDirectory() as folder:
        tmp = Path(folder) / f"media{suffix}"
        if suffix == ".png":
            mediapy.write_image(tmp, frames[-1])
        else:
            import imageio_ffmpeg

            mediapy.set_ffmpeg(imageio_ffmpeg.get_ffmpeg_exe())
            mediapy.write_video(tmp, frames, fps=fps)
        write_bytes(tmp.read_bytes(), path)
