"""``mcar view --rviz``: a robot in ROS 1's RViz, launched as the seed's command launches it.

It runs the bundled package's ``launch/display.launch`` with roslaunch, so the robot is
seen exactly as ``roslaunch mobile_car_description display.launch model:=FILE`` shows it:
robot_description from this same mcar (its folder first on PATH, where the launch's
``scripts/robot_description`` looks), with the same arguments; the robot's own package
and the --package-path folders on ROS_PACKAGE_PATH (RViz reads ``package://`` meshes
through it); and an RViz configuration made for this robot from ``rviz/urdf.rviz``: its
root link as the fixed frame, the camera on the centre of its visual bounds, 2.5 robot
sizes away, link axes and grid cells scaled to it (m). A robot with a mesh over mcar's
limits is not opened: RViz would read it unbounded. mcar needs no ROS; this does.
"""

from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import RenderError, UsageError
from ..load.inputs import RobotInput
from ..packages.bundled import description_dir
from ..packages.search import enclosing_package

# What a Debian 12 machine installs for it (the Makefile's `make rviz` installs these).
DEBIAN_PACKAGES = ("python3-roslaunch ros-robot-state-publisher joint-state-publisher "
                   "joint-state-publisher-gui rviz")
# A robot with nothing to draw is framed as one this size (m).
DEFAULT_SIZE = 0.2
# After Ctrl-C, roslaunch stops its nodes and its master; what is left this long after
# (mcar's own watchdog ends mcar 10 s after a signal) is killed with its process group.
STOP_SECONDS = 8.0


@dataclass
class RvizLaunch:
    """The roslaunch command line and environment for one robot."""

    argv: list[str]
    env: dict[str, str]


def require_roslaunch() -> str:
    """roslaunch's path; UsageError, before any robot is loaded, where there is none."""
    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        raise UsageError("mcar view --rviz needs ROS 1's roslaunch and RViz, which are not "
                         f"installed (Debian: apt-get install {DEBIAN_PACKAGES})")
    return roslaunch


def refuse_unbounded(inp: RobotInput, warnings) -> None:
    """RenderError where check found a mesh over mcar's limits (W210) or a mesh or texture
    outside the allowed folders (W215): mcar does not read it, and RViz, which reads every
    mesh with its own parsers, unbounded, is not given it."""
    over = [warning for warning in warnings if warning.rule == "W210"]
    if over:
        meshes = "a mesh" if len(over) == 1 else f"{len(over)} meshes"
        raise RenderError(f"not opened in RViz: {meshes} over mcar's limits (W210 above), "
                          "which RViz would read unbounded", file=inp.label)
    outside = [warning for warning in warnings if warning.rule == "W215"]
    if outside:  # RViz resolves file:// and links itself: it would read what mcar refused
        files = "a file" if len(outside) == 1 else f"{len(outside)} files"
        raise RenderError(f"not opened in RViz: {files} outside the folders a robot may "
                          "name files in (W215 above), which RViz would read",
                          file=inp.label)


def show(roslaunch: str, inp: RobotInput, model, options, sets, config_files) -> int:
    """Open ``inp`` (``model``: its checked ViewModel, loaded with ``options``) in RViz
    until RViz is closed; returns roslaunch's exit code. ``sets`` and ``config_files``
    are the command's --set and --config, which `mcar build` gets again."""
    import tempfile

    build_args = [f"{name}:={value}" for name, value in options.mappings.items()]
    build_args += [word for value in sets for word in ("--set", value)]
    build_args += [word for path in config_files
                   for word in ("--config", str(Path(path).resolve()))]
    # The --package-path folders reach mcar build through ROS_PACKAGE_PATH (plan), which
    # it searches in the same order: display.launch's args take dimension settings only.
    scene = model.urdf.scene
    bounds = scene.bounds if scene is not None else None
    with tempfile.TemporaryDirectory(prefix="mcar-rviz-") as folder:
        launch = plan(roslaunch, inp, model.urdf.base_link, bounds, build_args,
                      list(options.package_paths), Path(folder))
        return run(launch)


def plan(roslaunch: str, inp: RobotInput, root: str, bounds, build_args: list[str],
         package_paths: list[Path], folder: Path) -> RvizLaunch:
    """The launch of ``inp`` (its root link ``root``, visual ``bounds`` [[x, y, z] min,
    max] in the root's frame, or None), writing its RViz configuration into ``folder``.
    ``build_args`` are what `mcar build` gets besides the file (NAME:=VALUE, --set, ...)."""
    if inp.path is None:
        raise UsageError("mcar view --rviz shows a robot file, not standard input")
    config = folder / "urdf.rviz"
    model = _passable(inp.path.resolve(), inp.label)
    config.write_text(rviz_config(root, bounds), encoding="utf-8")
    bundled = description_dir()
    argv = [roslaunch, str(bundled / "launch" / "display.launch"),
            f"model:={model}", f"rvizconfig:={_passable(config, str(config))}",
            "args:=" + " ".join(launch_word(arg) for arg in build_args)]
    env = dict(os.environ)
    mcar_bin = str(Path(sys.executable).parent)  # this mcar's console script is there
    env["PATH"] = os.pathsep.join([mcar_bin, env.get("PATH", os.defpath)])
    found = enclosing_package(inp.path.resolve())
    folders = [*([found[1]] if found else []), *(p.resolve() for p in package_paths),
               bundled, *filter(None, env.get("ROS_PACKAGE_PATH", "").split(os.pathsep))]
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(dict.fromkeys(str(f) for f in folders))
    return RvizLaunch(argv, env)


def _passable(path: Path, label: str) -> str:
    """``path`` as a roslaunch argument's value; UsageError where roslaunch would not pass
    it on whole: it ignores an argument with a newline or a second ``:=`` (display.launch
    would silently show its default robot) and strips white space at the ends."""
    value = str(path)
    if "\n" in value or "\r" in value or ":=" in value or value != value.strip():
        raise UsageError("mcar view --rviz: roslaunch cannot pass this path on whole (a "
                         "newline, ':=' or white space at an end): rename it", file=label)
    return value


def rviz_config(root: str, bounds) -> str:
    """rviz/urdf.rviz, fitted to a robot: fixed frame, camera, axes and grid."""
    import yaml

    source = description_dir() / "rviz" / "urdf.rviz"
    config = yaml.safe_load(source.read_text(encoding="utf-8"))
    if bounds is None:
        centre, size = [0.0, 0.0, 0.0], DEFAULT_SIZE
    else:
        low, high = ([float(v) for v in corner] for corner in bounds)
        centre = [(a + b) / 2 for a, b in zip(low, high, strict=True)]
        size = max(max(b - a for a, b in zip(low, high, strict=True)), 0.01)
    manager = config["Visualization Manager"]
    manager["Global Options"]["Fixed Frame"] = root
    view = manager["Views"]["Current"]
    view["Distance"] = round(2.5 * size, 4)
    view["Focal Point"] = dict(zip("XYZ", (round(c, 4) for c in centre), strict=True))
    cell = 10.0 ** math.floor(math.log10(size))  # the car (0.2 m): 0.1 m cells
    for display in manager["Displays"]:
        if display["Class"] == "rviz/TF":
            display["Marker Scale"] = round(size / 2, 4)
        elif display["Class"] == "rviz/Grid":
            display["Cell Size"] = cell
    return yaml.safe_dump(config, sort_keys=False)


def run(launch: RvizLaunch) -> int:
    """Run roslaunch until RViz is closed; returns its exit code. roslaunch gets a process
    group of its own, so that however mcar is stopped (Ctrl-C, SIGTERM, SIGHUP), it stops
    roslaunch and everything it started, and leaves nothing behind."""
    process = subprocess.Popen(launch.argv, env=launch.env, stdin=subprocess.DEVNULL,
                               start_new_session=True)
    try:
        return process.wait()
    finally:
        _stop(process)  # after a normal end, only what roslaunch may have left


def _stop(process: subprocess.Popen) -> None:
    """SIGINT to roslaunch's group, as Ctrl-C (roslaunch stops its nodes and master);
    SIGKILL to what is left of it STOP_SECONDS later."""
    try:
        os.killpg(process.pid, signal.SIGINT)
        process.wait(timeout=STOP_SECONDS)
    except (ProcessLookupError, subprocess.TimeoutExpired):
        pass
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait()


def launch_word(arg: str) -> str:
    """One argument as display.launch's args takes it: words apart by spaces, each with
    %XX for its bytes that would split it (white space, non-printing), for % and for ``:``
    (roslaunch drops a command line argument with a second ``:=`` in it, and so did
    ``args:=prefix:=left_``), which scripts/robot_description decodes back to exactly
    ``arg``."""
    return "".join(c if c.isprintable() and not c.isspace() and c not in "%:"
                   else "".join(f"%{byte:02X}" for byte in c.encode("utf-8", "surrogateescape"))
                   for c in arg)
