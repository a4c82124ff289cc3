"""``mcar specs``' sensors section: what each lidar and camera sees of the robot itself.

For every lidar (:mod:`.sensor_list`: declared by a ``<gazebo><sensor>``, else a link named
like one, with stated defaults): its pose in the root frame at rest, range, field of view,
and the sectors of its scan the robot blocks, found by casting each sample's ray against
the robot's visual and collision geometry (:mod:`.self_view`) and proven by MuJoCo's own
ray casting on the same geometry (:mod:`.ray_proof`); for every camera, the share of its
image the robot covers. Without proofs (``options["proof"]`` False) MuJoCo's cast is the
figure and trimesh is not imported. W520 warns of a lidar blocked over more than
DEFAULT_BLOCKED_SHARE of its samples. :func:`laser_filters_fragment` turns the sectors
into a laser_filters chain that removes exactly them.

Keys: ``sensors.<name>.pose`` [x, y, z, yaw_deg], ``.range`` [min, max] m, ``.fov``
[min_deg, max_deg], ``.blocked`` [[from_deg, to_deg], ...] (sensor frame, 0 = its x axis,
counter-clockwise, in the scan's own angles), ``.blocked_share``, ``.covered`` (cameras).
A sector spans its blocked samples and half a sample's step either side: each sample
stands for the directions nearer to it than to its neighbours.
"""

from __future__ import annotations

import math

from ..check.diagnostics import Diagnostic
from .figures import Figure, Proof, Section
from .sensor_list import find_sensors

# A lidar blocked over more of its samples than this raises W520 (options
# "sensor_blocked_share" changes it).
DEFAULT_BLOCKED_SHARE = 0.10
# The camera's covered share agrees with MuJoCo's within this (grid cells on an edge).
COVERED_TOLERANCE = 0.02
# The pose agrees with MuJoCo's kinematics within this, in m and in degrees.
POSE_TOLERANCE = 1e-4
FILTER_TYPE = "laser_filters/LaserScanAngularBoundsFilterInPlace"
DIGITS = 4  # degrees and shares are given to this many decimals
# Rays cast for one robot, every sensor's together (twice: trimesh, then MuJoCo): the
# sensors and their samples come from the description, so their sum is bounded too.
MAX_RAYS = 200_000


def section(context) -> Section:
    """The sensors section of :class:`~mobile_car.specs.context.SpecsContext`."""
    return sensors_section(context.checked, context.sim, context.options)


def sensors_section(checked, sim, options: dict | None = None) -> Section:
    """The sensors of ``checked`` (a CheckResult), the geometry posed as ``sim`` (a
    SimModel) rests: every joint at 0, its springs at their rest. ``options``: "proof"
    (False: no MuJoCo), "sensor_blocked_share" (W520's threshold, 0..1)."""
    options = options or {}
    result = Section("sensors")
    sensors, result.notes = find_sensors(checked.robot, checked.where)
    if not sensors:  # (an empty section: a robot without sensors is nothing to note)
        return result
    from .self_view import camera_grid

    start = dict(getattr(sim, "start", None) or {})
    cast, proof = _casts(checked, start, options.get("proof", True) is not False,
                         result.notes, sensors)
    if cast is None:
        return result
    threshold = float(options.get("sensor_blocked_share", DEFAULT_BLOCKED_SHARE))
    rays = 0
    for sensor in sensors:
        if not cast.placed(sensor.link):
            result.notes.append(f"sensor {sensor.name}: link {sensor.link} is not placed")
            continue
        count = sensor.samples if sensor.kind == "lidar" else math.prod(camera_grid(sensor))
        if rays + count > MAX_RAYS:
            result.notes.append(f"sensor {sensor.name}: left out, its {count:,} rays past "
                                f"the {MAX_RAYS:,} cast for one robot")
            continue
        rays += count
        if sensor.kind == "lidar":
            result.figures += _lidar(sensor, cast, proof, threshold, checked, result)
        else:
            result.figures += _camera(sensor, cast, proof)
    return result


def _casts(checked, start, proving: bool, notes: list[str], sensors):
    """(what casts the figures' rays, what casts the proof's or None). With proofs:
    trimesh's cast on render's assembly (:mod:`.self_view`), MuJoCo's the proof. Without:
    MuJoCo's alone, already a complete cast of the same geometry, sparing trimesh's
    import (and scipy's through it: ~0.5 s of a cold ``mcar specs --no-proof``); trimesh's
    where MuJoCo cannot make the model or refuses a mesh trimesh would see.
    (None, None) where neither can read the geometry (a note says why). trimesh's is told
    where ``sensors`` sit, to make each link that may house one ray-ready on its own."""
    if not proving:
        cast = _mujoco_cast(checked, start, None)
        if cast is not None and not cast.refused:
            notes += [f"sensors: {note}" for note in cast.notes]
            return cast, None
    from .self_view import robot_surface

    try:
        surface = robot_surface(checked.loaded, start)
    except Exception as error:  # yourdfpy and trimesh raise anything on what they refuse
        notes.append(f"the robot's geometry could not be read for its sensors: "
                     f"{type(error).__name__}: {error}")
        return None, None
    notes += surface.notes
    surface.keep_apart([(sensor.link, surface.frame(sensor)[:3, 3]) for sensor in sensors
                        if surface.placed(sensor.link)])
    return surface, (_mujoco_cast(checked, start, notes) if proving else None)


def _mujoco_cast(checked, start, notes):
    """MuJoCo's model of the robot's visual and collision geometry, or None where it
    cannot be made (said in ``notes``, the proof's, unless None)."""
    from .ray_proof import ProofUnavailable, RayProof

    try:
        cast = RayProof(checked.loaded, start)
    except ProofUnavailable as why:
        if notes is not None:
            notes.append(f"no MuJoCo proof of the sensors' figures: MuJoCo cannot make the "
                         f"robot's model with its visuals: {why}")
        return None
    if notes is not None:
        notes += [f"sensors' proof: {note}" for note in cast.notes]
    return cast


def _pose_figure(sensor, frame, proof) -> Figure:
    figure = Figure(f"sensors.{sensor.name}.pose", f"{sensor.name} pose (x, y, z, yaw)",
                    _pose(frame), "m, deg", sensor.source,
                    "root frame at rest: every joint at 0, springs at their rest")
    if proof is not None:
        placed = proof.frame(sensor)
        measured = _pose(placed)
        # The orientation is compared whole: the yaw of an x axis pointing straight down
        # (Baxter's hand cameras) is atan2 of two rounding errors, 26.56° in one and
        # 26.57° in the other of two frames that agree to 1e-12.
        agrees = all(abs(a - b) <= POSE_TOLERANCE for a, b in zip(
            measured[:3], figure.value[:3], strict=True)) and \
            _turned(frame, placed) <= POSE_TOLERANCE
        figure.proof = Proof(measured, agrees, f"{POSE_TOLERANCE:g} m and degree",
                             "MuJoCo's kinematics of the same URDF place the sensor's link")
    return figure


def _turned(frame, other) -> float:
    """The angle (deg) of the rotation between two frames' orientations (4x4), well
    conditioned near 0: the Frobenius norm of their difference is 2√2·sin(θ/2)."""
    import numpy as np

    difference = np.asarray(frame)[:3, :3] - np.asarray(other)[:3, :3]
    chord = min(1.0, float(np.linalg.norm(difference)) / (2 * math.sqrt(2)))
    return math.degrees(2 * math.asin(chord))


def _pose(frame) -> list[float]:
    yaw = math.degrees(math.atan2(frame[1, 0], frame[0, 0]))
    return [round(float(v), 6) for v in frame[:3, 3]] + [round(yaw, DIGITS)]


def _lidar(sensor, cast, proof, threshold, checked, result) -> list[Figure]:
    from .self_view import lidar_rays

    frame = cast.frame(sensor)
    housing = cast.housing(sensor.link, frame[:3, 3])
    hits = cast.blocked(sensor, frame[:3, 3], lidar_rays(sensor, frame), housing)
    azimuths = sensor.azimuths()
    sectors = blocked_sectors(hits, azimuths, sensor.step)
    share = round(float(hits.mean()), DIGITS)
    key = f"sensors.{sensor.name}"
    method = (f"{sensor.samples} rays cast in the scan plane against the robot's visual and "
              f"collision geometry{_cast_by(cast, housing)}")
    seen = ("each ray starts at range min, as Gazebo's: a part nearer is not seen (a real "
            "scanner reports no range there)")
    if sensor.layers > 1:
        seen += f"; a 3D lidar of {sensor.layers} layers: its horizontal plane only"
    figures = [
        _pose_figure(sensor, frame, proof),
        Figure(f"{key}.range", f"{sensor.name} range", [sensor.range_min, sensor.range_max],
               "m", sensor.source),
        Figure(f"{key}.fov", f"{sensor.name} field of view",
               [round(math.degrees(sensor.min_angle), DIGITS),
                round(math.degrees(sensor.max_angle), DIGITS)], "deg", sensor.source),
        Figure(f"{key}.blocked", f"{sensor.name} sectors the robot blocks", sectors, "deg",
               method, seen),
        Figure(f"{key}.blocked_share", f"{sensor.name} share of samples blocked", share, "",
               method, seen),
    ]
    if proof is not None:
        mj_frame = proof.frame(sensor)
        mj_hits = proof.blocked(sensor, mj_frame[:3, 3], lidar_rays(sensor, mj_frame), housing)
        around = sensor.max_angle - sensor.min_angle + 1.5 * sensor.step >= 2 * math.pi
        agrees = within_one_sample(hits, mj_hits, around)
        differ = int((hits != mj_hits).sum())
        detail = (f"MuJoCo mj_multiRay from the same origin and azimuths: {differ} of "
                  f"{sensor.samples} samples differ")
        tolerance = f"one sample ({math.degrees(sensor.step):.3g}°) at each sector edge"
        figures[3].proof = Proof(blocked_sectors(mj_hits, azimuths, sensor.step), agrees,
                                 tolerance, detail)
        figures[4].proof = Proof(round(float(mj_hits.mean()), DIGITS), agrees, tolerance,
                                 detail)
    if share > threshold:
        shown = ", ".join(f"{a:g}..{b:g}°" for a, b in sectors)
        result.diagnostics.append(Diagnostic(
            "W520", sensor.file or checked.file, sensor.line,
            f"lidar {sensor.name}: the robot blocks {share:.0%} of its samples, over "
            f"{threshold:.0%} of its field of view: sectors {shown}"))
    return figures


def _camera(sensor, cast, proof) -> list[Figure]:
    from .self_view import camera_grid, camera_rays

    frame = cast.frame(sensor)
    housing = cast.housing(sensor.link, frame[:3, 3])
    hits = cast.blocked(sensor, frame[:3, 3], camera_rays(sensor, frame), housing)
    columns, rows = camera_grid(sensor)
    half = round(math.degrees(sensor.hfov) / 2, DIGITS)
    figure = Figure(f"sensors.{sensor.name}.covered", f"{sensor.name} share of its image "
                    "the robot covers", round(float(hits.mean()), DIGITS), "",
                    f"{sensor.source}; a {columns}x{rows} grid of rays through the image "
                    f"cast against the robot's visual and collision geometry"
                    f"{_cast_by(cast, housing)}",
                    f"from the lens to the far clip, {sensor.range_max:g} m (a near clip "
                    "bounds Gazebo's drawing, not the lens); the camera looks along its "
                    "frame's x")
    if proof is not None:
        mj_frame = proof.frame(sensor)
        measured = float(proof.blocked(sensor, mj_frame[:3, 3], camera_rays(sensor, mj_frame),
                                       housing).mean())
        figure.proof = Proof(round(measured, DIGITS),
                             abs(measured - figure.value) <= COVERED_TOLERANCE,
                             f"{COVERED_TOLERANCE:g} of the image",
                             "MuJoCo mj_multiRay through the same grid")
    return [_pose_figure(sensor, frame, proof),
            Figure(f"sensors.{sensor.name}.fov", f"{sensor.name} horizontal field of view",
                   [-half, half], "deg", sensor.source), figure]


def _cast_by(cast, housing: list[str]) -> str:
    """What cast the rays and what it left out, for a figure's source: " (its housing
    left out: link ...)", MuJoCo's cast (without proofs) named and said unchecked."""
    left_out = f"its housing left out: link{'s' if len(housing) > 1 else ''} {', '.join(housing)}"
    if getattr(cast, "engine", None) != "mujoco":
        return f" ({left_out})"
    return (f" by MuJoCo's ray casting (mj_multiRay; {left_out}); not cross-checked: "
            "--no-proof")


def blocked_sectors(hits, azimuths, step: float) -> list[list[float]]:
    """[[from_deg, to_deg], ...] of each run of blocked samples, widened by half a step
    either side (the directions each sample stands for)."""
    sectors, start = [], None
    for index, hit in enumerate(list(hits) + [False]):
        if hit and start is None:
            start = index
        elif not hit and start is not None:
            low, high = azimuths[start] - step / 2, azimuths[index - 1] + step / 2
            sectors.append([round(math.degrees(low), DIGITS),
                            round(math.degrees(high), DIGITS)])
            start = None
    return sectors


def within_one_sample(ours, theirs, around: bool = False) -> bool:
    """Every sample blocked in one is blocked in the other or next to one that is: the
    sectors' edges agree within one sample. ``around``: the scan goes all the way round,
    its last sample next to its first."""
    import numpy as np

    def grown(hits):
        if around:
            return hits | np.roll(hits, 1) | np.roll(hits, -1)
        out = hits.copy()
        out[1:] |= hits[:-1]
        out[:-1] |= hits[1:]
        return out

    ours, theirs = np.asarray(ours, dtype=bool), np.asarray(theirs, dtype=bool)
    return bool(not (ours & ~grown(theirs)).any() and not (theirs & ~grown(ours)).any())


def laser_filters_fragment(sections, ros: int = 2) -> dict:
    """laser_filters' configuration removing every blocked sector of every lidar: one
    ``LaserScanAngularBoundsFilterInPlace`` a sector, its ``lower_angle``/``upper_angle``
    in radians, the scan's own angles (the filter removes the readings strictly between
    them, so each bound lies half a sample outside the blocked ones). ``ros`` 2: the
    ``scan_to_scan_filter_chain`` node's parameters (``ros__parameters``, ``filter1``...);
    1: the ``scan_filter_chain`` list ROS 1's node reads. Several lidars: one chain each,
    named ``<sensor>_filter_chain``. Empty when no lidar is blocked."""
    sensors = next((s for s in sections if s.name == "sensors"), None)
    chains = {}
    for figure in sensors.figures if sensors is not None else ():
        name = figure.key.removeprefix("sensors.").removesuffix(".blocked")
        if not figure.key.endswith(".blocked") or not figure.value:
            continue
        chains[name] = [{"name": f"{name}_blocked_{number}", "type": FILTER_TYPE,
                         "params": {"lower_angle": round(math.radians(low), 6),
                                    "upper_angle": round(math.radians(high), 6)}}
                        for number, (low, high) in enumerate(figure.value, 1)]
    if not chains:
        return {}
    fragment = {}
    for name, chain in chains.items():
        if ros == 1:
            key = "scan_filter_chain" if len(chains) == 1 else f"{name}_filter_chain"
            fragment[key] = chain
        else:
            key = "scan_to_scan_filter_chain" if len(chains) == 1 else f"{name}_filter_chain"
            fragment[key] = {"ros__parameters": {f"filter{number}": entry for number, entry
                                                 in enumerate(chain, 1)}}
    return fragment
