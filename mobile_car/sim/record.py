"""``mcar sim --record run.gif``: the scenarios as a person would watch them, rendered
offscreen by MuJoCo (EGL, headless) over the checkered floor.

While the scenarios run, the recorder keeps the robot's state every 1/FPS simulated
second, nothing else. Then each scenario's states are drawn from a still camera fitted to
the whole path the robot took (grown by the robot's own reach and height), so the robot
stays in frame from the first picture to the last: a short path (drop, spin) with the
robot at the centre, a long one (drive, turn) seen from its side, crossing a still floor.
Lengths in m, angles in degrees.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np

from ..errors import McarError, UsageError
from .engine import mujoco

FPS = 15
WIDTH, HEIGHT = 320, 240
FORMATS = (".gif",)
AZIMUTH, ELEVATION = -70.0, -35.0  # degrees; a short path (drop, spin) is seen so
SIDE_ANGLE = 25.0  # degrees off the side of a long path (drive, turn)
MARGIN = 1.4  # the picture over what must fit in it (perspective: near parts grow)


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
    """A frame callback for :class:`mobile_car.sim.run.Run`: keeps the state every 1/FPS
    simulated second, one segment per scenario (each Run has its own MjData)."""

    def __init__(self, sim, scenarios=()):
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
        # Shadows and reflections cost most of llvmpipe's time per frame and show nothing
        # the scenarios are about.
        flags = self.renderer.scene.flags
        flags[mj.mjtRndFlag.mjRND_SHADOW] = flags[mj.mjtRndFlag.mjRND_REFLECTION] = 0
        self.model = model
        self.free = int(model.jnt_qposadr[model.joint("mcar_free").id])
        self.reach, self.height = _robot_reach(mj, model, self.free)
        self.every = max(1, round(1 / (FPS * model.opt.timestep)))
        self.count = 0
        self.segments: list[list[np.ndarray]] = []
        self._data = None

    def __call__(self, model, data) -> None:
        if data is not self._data:  # a new scenario's run
            self._data, self.count = data, 0
            self.segments.append([])
        self.count += 1
        if self.count % self.every == 0:
            self.segments[-1].append(data.qpos.copy())

    def frames(self) -> list[np.ndarray]:
        """Every kept state drawn, each segment from its own fitted camera."""
        data = self.mj.MjData(self.model)
        pictures = []
        for states in self.segments:
            camera = self.camera_for(np.array([q[self.free:self.free + 3] for q in states]))
            for qpos in states:
                data.qpos[:] = qpos
                self.mj.mj_kinematics(self.model, data)
                self.renderer.update_scene(data, camera=camera)
                pictures.append(self.renderer.render().copy())
        return pictures

    def camera_for(self, path: np.ndarray):
        """A still camera that sees the robot wherever it is along ``path`` (N x 3, its
        root's positions): aimed at the middle of the path, from the side of a long path
        (three-quarters on, so the path crosses the picture's wider dimension), far
        enough back that the path, the robot's reach and its height fit MARGIN times."""
        mj = self.mj
        camera = mj.MjvCamera()
        camera.type = mj.mjtCamera.mjCAMERA_FREE
        points = path[:, :2]
        along = points[-1] - points[0]
        long_path = float(np.linalg.norm(along)) > self.reach
        azimuth = (math.degrees(math.atan2(along[1], along[0])) + 90 - SIDE_ANGLE
                   if long_path else AZIMUTH)
        az, el = math.radians(azimuth), math.radians(ELEVATION)
        forward = np.array([math.cos(az), math.sin(az)])
        right = np.array([math.sin(az), -math.cos(az)])
        u, v = points @ right, points @ forward
        centre = right * (u.max() + u.min()) / 2 + forward * (v.max() + v.min()) / 2
        half_width = (u.max() - u.min()) / 2 + self.reach
        half_height = (((v.max() - v.min()) / 2 + self.reach) * abs(math.sin(el))
                       + self.height * math.cos(el) / 2)
        fovy = math.radians(self.model.vis.global_.fovy) / 2
        fovx = math.atan(math.tan(fovy) * WIDTH / HEIGHT)
        camera.lookat[:] = [centre[0], centre[1], self.height / 2]
        camera.distance = MARGIN * max(half_width / math.tan(fovx),
                                       half_height / math.tan(fovy))
        camera.azimuth, camera.elevation = azimuth, ELEVATION
        return camera

    def gif(self) -> bytes:
        from PIL import Image

        images = [Image.fromarray(frame) for frame in self.frames()]
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


def _robot_reach(mj, model, free: int) -> tuple[float, float]:
    """(how far the robot's geometry reaches from its root in the floor's plane, its
    height), at rest with every joint at 0 (m)."""
    data = mj.MjData(model)
    mj.mj_kinematics(model, data)
    root = data.qpos[free:free + 3]
    reach, top, bottom = 0.0, -math.inf, math.inf
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == 0:
            continue
        bound = float(model.geom_rbound[g])
        centre = data.geom_xpos[g]
        reach = max(reach, float(np.linalg.norm((centre - root)[:2])) + bound)
        top, bottom = max(top, centre[2] + bound), min(bottom, centre[2] - bound)
    return max(reach, 0.05), max(top - bottom, 0.05) if math.isfinite(top) else 0.1
