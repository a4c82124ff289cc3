"""``mcar sim --record run.gif``: the scenarios as a person would watch them to find what
went wrong, rendered offscreen by MuJoCo (EGL, headless) over the checkered floor.

While the scenarios run, the recorder keeps the robot's state and its wheel commands
every 1/FPS simulated second, nothing else. Then each scenario's states are drawn at
SIZE (640 x 480 unless asked otherwise), lit by a brighter headlight and a directional
light from above (the floor's one spotlight alone leaves a robot that has driven away in
the dark), from a camera that follows the robot's root body at a distance fitted to the
robot's own reach and height: the robot stays in the middle of every picture, large
enough to see a wheel lift or a castor drag, and the floor's squares passing under it
show how it moves. A side view of a long path (drive, turn), three-quarters on for a
short one (drop, spin). Over each driven wheel an arrow shows its command: the way the
wheel is told to roll the robot, as long as the command is fast (none while it stands).
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
SIZE = (640, 480)  # pixels, width x height: a wheel of a small robot is tens of pixels
LARGEST = 1280  # pixels a side --record-size allows: a frame (a byte a pixel) is kept per
# state, 1.6 MB each at most, about 200 MB for the ~130 of drop, drive and spin
FORMATS = (".gif",)
AZIMUTH, ELEVATION = -70.0, -35.0  # degrees; a short path (drop, spin) is seen so
SIDE_ANGLE = 25.0  # degrees off the side of a long path (drive, turn)
MARGIN = 2.0  # the picture over the robot (perspective: near parts grow; some floor shows)
HEADLIGHT = ((0.35, 0.35, 0.35), (0.55, 0.55, 0.55))  # ambient, diffuse
SUN = ((0.3, -0.4, -1.0), (0.45, 0.45, 0.45))  # a directional light's direction, diffuse
ARROW_RGBA = (1.0, 0.85, 0.0, 1.0)  # yellow: on neither the grey floor nor a usual robot
ARROW_WIDTH = 0.06  # of the robot's reach


class RecordError(McarError):
    """The recording cannot be made on this machine (no EGL): exit 2."""


def parse_size(text: str) -> tuple[int, int]:
    """``WIDTHxHEIGHT`` (``640x480``) as pixels; UsageError if it is not one."""
    words = text.lower().split("x")
    try:
        width, height = (int(w) for w in words)
    except ValueError:
        raise UsageError(f"--record-size {text}: give WIDTHxHEIGHT in pixels, e.g. "
                         "640x480") from None
    if not (16 <= width <= LARGEST and 16 <= height <= LARGEST):
        raise UsageError(f"--record-size {text}: each side from 16 to {LARGEST} pixels")
    return width, height


def require_format(path: str) -> None:
    suffix = Path(path).suffix.lower()
    if suffix == ".mp4":
        raise UsageError(f"--record {path}: no MP4 encoder is available here (mcar ships no "
                         "video codec); record a .gif instead")
    if suffix not in FORMATS:
        raise UsageError(f"--record {path}: mcar sim records .gif animations")


class Recorder:
    """A frame callback for :class:`mobile_car.sim.run.Run`: keeps the state and the wheel
    commands every 1/FPS simulated second, one segment per scenario (each Run has its own
    MjData)."""

    def __init__(self, sim, scenarios=(), size: tuple[int, int] | None = None):
        mj = mujoco()
        self.mj = mj
        model = sim.model
        self.width, self.height_px = size or SIZE
        model.vis.global_.offwidth = max(model.vis.global_.offwidth, self.width)
        model.vis.global_.offheight = max(model.vis.global_.offheight, self.height_px)
        model.vis.headlight.ambient, model.vis.headlight.diffuse = HEADLIGHT
        try:
            self.renderer = mj.Renderer(model, self.height_px, self.width)
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
        self.root = int(model.jnt_bodyid[model.joint("mcar_free").id])
        self.reach, self.height = _robot_reach(mj, model, self.free)
        self.motors = _wheel_motors(sim)
        self.every = max(1, round(1 / (FPS * model.opt.timestep)))
        self.count = 0
        self.segments: list[list[tuple[np.ndarray, np.ndarray]]] = []
        self._data = None

    def __call__(self, model, data) -> None:
        if data is not self._data:  # a new scenario's run
            self._data, self.count = data, 0
            self.segments.append([])
        self.count += 1
        if self.count % self.every == 0:
            self.segments[-1].append((data.qpos.copy(), data.ctrl.copy()))

    def frames(self) -> list[np.ndarray]:
        """Every kept state drawn, each segment from a camera that follows the robot."""
        return [self._draw(*shot) for shot in self._shots()]

    def _shots(self) -> list[tuple]:
        """(data, camera, qpos, ctrl, fastest command) for every kept state, in order."""
        data = self.mj.MjData(self.model)
        fastest = max((abs(float(c[a])) for states in self.segments for _, c in states
                       for a, _ in self.motors), default=0.0)
        return [(data, camera, qpos, ctrl, fastest) for states in self.segments
                for camera in [self.camera_for(np.array([q[self.free:self.free + 3]
                                                         for q, _ in states]))]
                for qpos, ctrl in states]

    def _draw(self, data, camera, qpos, ctrl, fastest: float) -> np.ndarray:
        data.qpos[:] = qpos
        self.mj.mj_kinematics(self.model, data)
        camera.lookat[:] = [*data.xpos[self.root][:2], self.height / 2]
        self.renderer.update_scene(data, camera=camera)
        self._add_sun()
        self._add_arrows(data, ctrl, fastest)
        return self.renderer.render().copy()

    def camera_for(self, path: np.ndarray):
        """A camera for the segment whose root moved along ``path`` (N x 3): from the side
        of a long path (three-quarters on, so the travel crosses the picture's wider
        dimension), far enough back that the robot's reach and height fit MARGIN times;
        ``frames`` moves it with the robot."""
        mj = self.mj
        camera = mj.MjvCamera()
        camera.type = mj.mjtCamera.mjCAMERA_FREE
        along = path[-1, :2] - path[0, :2]
        long_path = float(np.linalg.norm(along)) > self.reach
        azimuth = (math.degrees(math.atan2(along[1], along[0])) + 90 - SIDE_ANGLE
                   if long_path else AZIMUTH)
        el = math.radians(ELEVATION)
        half_width = self.reach
        half_height = self.reach * abs(math.sin(el)) + self.height * math.cos(el) / 2
        fovy = math.radians(self.model.vis.global_.fovy) / 2
        fovx = math.atan(math.tan(fovy) * self.width / self.height_px)
        camera.lookat[:] = [path[0][0], path[0][1], self.height / 2]
        camera.distance = MARGIN * max(half_width / math.tan(fovx),
                                       half_height / math.tan(fovy))
        camera.azimuth, camera.elevation = azimuth, ELEVATION
        return camera

    def _add_sun(self) -> None:
        """A directional light from above and aside, after the scene's own lights."""
        scene = self.renderer.scene
        if scene.nlight >= len(scene.lights):
            return
        light = scene.lights[scene.nlight]
        light.type = self.mj.mjtLightType.mjLIGHT_DIRECTIONAL
        light.dir[:] = SUN[0]
        light.pos[:] = [0, 0, 10]
        light.diffuse[:] = SUN[1]
        light.ambient[:] = 0
        light.specular[:] = 0.1
        light.headlight = 0
        light.castshadow = 0
        scene.nlight += 1

    def _add_arrows(self, data, ctrl, fastest: float) -> None:
        """An arrow over each driven wheel, above the robot, the way its command rolls the
        robot (the wheel's axis x up, by the sign of the command), as long as the robot's
        reach at the fastest command; none for a wheel told to stand still."""
        scene, mj = self.renderer.scene, self.mj
        up = np.array([0.0, 0.0, 1.0])
        for actuator, wheel in self.motors:
            command = float(ctrl[actuator])
            if fastest <= 0 or abs(command) < 1e-3 * fastest or scene.ngeom >= scene.maxgeom:
                continue
            way = np.cross(data.xaxis[wheel.joint_id], up) * math.copysign(1.0, command)
            norm = float(np.linalg.norm(way))
            if norm < 1e-6:  # an axis standing upright rolls nothing forward
                continue
            length = self.reach * abs(command) / fastest
            # over the wheel, above the whole robot: no body hides it from any side
            middle = np.array([*data.xpos[wheel.body_id][:2], self.height + 0.15 * self.reach])
            start = middle - way / norm * length / 2
            geom = scene.geoms[scene.ngeom]
            mj.mjv_initGeom(geom, mj.mjtGeom.mjGEOM_ARROW, np.zeros(3), np.zeros(3),
                            np.zeros(9), np.array(ARROW_RGBA, dtype=np.float32))
            mj.mjv_connector(geom, mj.mjtGeom.mjGEOM_ARROW, ARROW_WIDTH * self.reach,
                             start, start + way / norm * length)
            scene.ngeom += 1

    def gif(self) -> bytes:
        from PIL import Image

        shots = self._shots()
        if not shots:
            raise UsageError("nothing was simulated to record")
        # One palette for the whole animation (the middle picture's): the floor's squares
        # do not flicker; each picture is reduced to it as it is drawn, one byte a pixel
        # kept instead of three.
        palette = Image.fromarray(self._draw(*shots[len(shots) // 2])).quantize(colors=255)
        frames = [Image.fromarray(self._draw(*shot)).quantize(palette=palette,
                                                              dither=Image.Dither.NONE)
                  for shot in shots]
        out = io.BytesIO()
        frames[0].save(out, format="GIF", save_all=True, append_images=frames[1:],
                       duration=round(1000 / FPS), loop=0)
        return out.getvalue()

    def close(self) -> None:
        self.renderer.close()


def _wheel_motors(sim) -> list[tuple[int, object]]:
    """(actuator id, wheel) of each driven wheel's velocity motor."""
    if sim.drive is None:
        return []
    return [(w.actuator_id, w) for w in sim.drive.driven if w.actuator_id >= 0]


def _robot_reach(mj, model, free: int) -> tuple[float, float]:
    """(how far the robot's geometry reaches from its root in the floor's plane, its
    height), at rest with every joint at 0 (m): the corners of each geom's own bounding
    box (a geom's bounding sphere would make a flat box twice as tall as it is)."""
    data = mj.MjData(model)
    mj.mj_kinematics(model, data)
    root = data.qpos[free:free + 3]
    signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
    corners = [data.geom_xpos[g] + (model.geom_aabb[g][:3] + signs * model.geom_aabb[g][3:])
               @ data.geom_xmat[g].reshape(3, 3).T
               for g in range(model.ngeom) if model.geom_bodyid[g] != 0]
    if not corners:
        return 0.05, 0.1
    points = np.concatenate(corners)
    reach = float(np.linalg.norm(points[:, :2] - root[:2], axis=1).max())
    return max(reach, 0.05), max(float(points[:, 2].max() - points[:, 2].min()), 0.05)
