"""``mcar sim --record run.gif``: the scenarios as a person would watch them, from a fixed
camera over the checkered floor, rendered offscreen by MuJoCo (EGL, headless)."""

from __future__ import annotations

import io
from pathlib import Path

from ..errors import McarError, UsageError
from .engine import mujoco

FPS = 15
WIDTH, HEIGHT = 320, 240
FORMATS = (".gif",)


class RecordError(McarError):
    """The recording cannot be made on this machine (no EGL): exit 2."""


def require_format(path: str) -> None:
    suffix = Path(path).suffix.lower()
    if suffix == ".mp4":
        raise UsageError(f"--record {path}: no MP4 encoder is available here (mcar ships no "
                         "video codec); record a .gif instead")
    if suffix not in FORMATS:
        raise UsageError(f"--record {path}: mcar sim records .gif animations")


class Recorder:
    """A frame callback for :class:`mobile_car.sim.scenarios.Run`: every 1/FPS simulated
    second, a picture of the scene from the camera that sees the whole run."""

    def __init__(self, sim, reach: float):
        mj = mujoco()
        self.mj = mj
        model = sim.model
        model.vis.global_.offwidth = max(model.vis.global_.offwidth, WIDTH)
        model.vis.global_.offheight = max(model.vis.global_.offheight, HEIGHT)
        try:
            self.renderer = mj.Renderer(model, HEIGHT, WIDTH)
        except Exception as error:  # MuJoCo raises plain exceptions for a missing GL
            raise RecordError(f"cannot render offscreen ({type(error).__name__}: {error}); "
                              "install Mesa's EGL (Debian: libegl1 libegl-mesa0 "
                              "libgl1-mesa-dri)") from None
        camera = mj.MjvCamera()
        camera.type = mj.mjtCamera.mjCAMERA_FREE
        camera.lookat[:] = [reach / 2, 0.0, 0.0]
        camera.distance = max(0.6, 1.1 * reach)
        camera.azimuth, camera.elevation = -70.0, -35.0
        self.camera = camera
        # Shadows and reflections cost most of llvmpipe's time per frame and show nothing
        # the scenarios are about.
        flags = self.renderer.scene.flags
        flags[mj.mjtRndFlag.mjRND_SHADOW] = flags[mj.mjtRndFlag.mjRND_REFLECTION] = 0
        self.every = max(1, round(1 / (FPS * model.opt.timestep)))
        self.count = 0
        self.frames = []

    def __call__(self, model, data) -> None:
        self.count += 1
        if self.count % self.every:
            return
        self.renderer.update_scene(data, camera=self.camera)
        self.frames.append(self.renderer.render().copy())

    def gif(self) -> bytes:
        from PIL import Image

        images = [Image.fromarray(frame) for frame in self.frames]
        if not images:
            raise UsageError("nothing was simulated to record")
        # One palette for the whole animation: the floor's squares do not flicker.
        palette = images[len(images) // 2].quantize(colors=255)
        frames = [image.quantize(palette=palette, dither=Image.Dither.NONE) for image in images]
        out = io.BytesIO()
        frames[0].save(out, format="GIF", save_all=True, append_images=frames[1:],
                       duration=round(1000 / FPS), loop=0)
        return out.getvalue()

    def close(self) -> None:
        self.renderer.close()
