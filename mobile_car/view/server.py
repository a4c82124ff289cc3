"""The robot in a browser: a viser server with the robot, joint sliders and display toggles.

viser serves the page and keeps every open page in step with the Python objects here;
:class:`viser.extras.ViserUrdf` draws the yourdfpy model and moves its links. Link frames
are drawn as separate nodes at the links' world poses so that they can be shown while
the geometry is hidden.

Threads: viser calls the GUI callbacks on its own threads, while the command's main
thread rebuilds the robot when a file changes; one lock keeps them apart.

Trust: only the viewer's own page may load or connect (:mod:`.origin`), and every value it
sends is checked before viser or the model sees it (:mod:`.inbound`); what is refused is
said on stderr through ``warn``, one line per kind of refusal.
"""

from __future__ import annotations

import contextlib
import html
import io
import logging
import math
import threading
import warnings
from collections.abc import Callable

import numpy as np
import viser
import viser.transforms as vtf
from viser.extras import ViserUrdf

from ..errors import McarError, UsageError
from .dimensions import Dimensions
from .inbound import Inbound, UnreadableMessages
from .markers import THICKNESS_PX, marker_segments
from .model import MOVING, ViewModel, error_lines
from .origin import PageOrigin, guarding_requests
from .watch import FileWatch

ROBOT_NODE = "/robot"
FRAMES_NODE = "/frames"
MARKERS_NODE = "/joint_markers"
# Collision geometry has no colour in URDF: a see-through orange tells it from the visual.
COLLISION_RGBA = (0.95, 0.55, 0.15, 0.6)
# Where the camera looks from at start, as rviz's default view does: front-left-above.
CAMERA_DIRECTION = np.array([1.0, 0.8, 0.7])
CAMERA_FOV = math.radians(50)

# The error box: every line whole, wrapped at the panel's edge (a path or a message has no
# spaces to break at for long stretches), never behind a scroll bar.
ERROR_BOX_STYLE = ("white-space: pre-wrap; overflow-wrap: anywhere; font-family: monospace; "
                   "font-size: 0.75rem; line-height: 1.35; padding: 0 0.75rem 0.5rem")

# Rows of the control panel, top to bottom.
_ORDER = {"status": 0, "errors": 0.5, "visual": 1, "collision": 2, "frames": 3,
          "markers": 3.5, "reset": 4, "joints": 10, "dimensions": 20}


def url_of(host: str, port: int) -> str:
    shown = f"[{host}]" if ":" in host else host
    return f"http://{shown}:{port}/"


class RobotView:
    """Serves ``model`` at ``host``:``port`` (0: any free port) until :meth:`stop`;
    ``reload`` builds the robot anew when :meth:`reload_if_changed` sees an edit;
    ``dimensions`` (the robot's config.xacro, if it has one) gives a slider per dimension;
    ``warn`` says what was refused from a browser (a line of text; default: logged)."""

    def __init__(self, model: ViewModel, reload: Callable[[], ViewModel],
                 host: str = "127.0.0.1", port: int = 8080,
                 dimensions: Dimensions | None = None,
                 warn: Callable[[str], None] | None = None):
        self._reload = reload
        self._inbound = Inbound(warn or logging.getLogger(__name__).warning)
        self._lock = threading.RLock()
        # One dimension change at a time, so that each builds on the last one accepted.
        self._dimension_lock = threading.RLock()  # (putting a slider back re-enters)
        self.dimensions = dimensions
        self.dimension_sliders: dict[str, viser.GuiSliderHandle] = {}  # (in shown units)
        self._dimension_items: dict = {}  # name -> its DimensionRange
        self.overrides_yaml = None  # the text area the copy button fills
        self.model: ViewModel | None = None
        self.errors: list[str] = []  # the last failed rebuild's lines; empty when current
        self.reloads = 0  # rebuilds shown (for the tests and the status line)
        self.sliders: dict[str, viser.GuiSliderHandle] = {}
        self.frames: dict[str, viser.FrameHandle] = {}
        self.markers: dict[str, viser.LineSegmentsHandle] = {}  # by joint name
        self._robot: ViserUrdf | None = None
        self._joints_folder = None
        self.watch = FileWatch()
        page = PageOrigin(host)
        with _quiet(), guarding_requests(page, self._refused) as guarded:
            # (viser prints a banner whatever verbose says; the command prints)
            self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self._unreadable = UnreadableMessages(self._inbound.warn)
        logging.getLogger("websockets.server").addFilter(self._unreadable)
        if not guarded:
            self.stop()
            raise UsageError(f"mcar view cannot check who connects to viser "
                             f"{viser.__version__}: install viser 1.x")
        # viser's share button opens a tunnel through a server on the internet: this page
        # is served to this machine only unless --host says otherwise, and stays so.
        self.server.request_share_url = _no_share_url
        try:
            self._inbound.install(self.server)
            self.server.gui.configure_theme(show_share_button=False)
            self._build_panel()
            self._add_ground(model)
            self.show(model)
            self._frame_camera(model)
        except BaseException:
            self.stop()
            raise

    @property
    def port(self) -> int:
        return self.server.get_port()

    @property
    def url(self) -> str:
        return url_of(self.server.get_host(), self.port)

    def stop(self) -> None:
        with _quiet():  # ("Server stopped", printed by viser's server thread)
            self.server.stop()
        logging.getLogger("websockets.server").removeFilter(self._unreadable)

    def _refused(self, reason: str) -> None:
        self._inbound.warn(("refused", reason), f"mcar view: refused a request (403): {reason}")

    # -- the control panel -------------------------------------------------------------

    def _build_panel(self) -> None:
        gui, accept = self.server.gui, self._inbound.accept
        self.status = gui.add_markdown("", order=_ORDER["status"])
        self.error_box = gui.add_html("", order=_ORDER["errors"], visible=False)
        self.show_visual = accept(gui.add_checkbox("Visual geometry", True,
                                                   order=_ORDER["visual"]))
        self.show_collision = accept(gui.add_checkbox("Collision geometry", False,
                                                      order=_ORDER["collision"]))
        self.show_frames = accept(gui.add_checkbox(
            "Link frames", False, order=_ORDER["frames"],
            hint="x/y/z axes (red/green/blue) of every link"))
        self.show_markers = accept(gui.add_checkbox(
            "Joint markers", True, order=_ORDER["markers"],
            hint="each moving joint's axis (amber) and a spoke that turns with it (magenta)"))
        self.reset = accept(gui.add_button("Reset joints", order=_ORDER["reset"],
                                           hint="Every joint back to zero (or its nearer limit)"))
        visibility = self._on_page(self._apply_visibility, "showing or hiding geometry")
        self.show_visual.on_update(visibility)
        self.show_collision.on_update(visibility)
        self.show_frames.on_update(visibility)
        self.show_markers.on_update(visibility)
        self.reset.on_click(self._on_page(self.reset_joints, "resetting the joints"))
        if self.dimensions is not None and self.dimensions.ranges:
            self._build_dimension_panel()

    def _on_page(self, action: Callable[[], object], what: str) -> Callable:
        """A callback for viser that runs ``action``; a failure is one warning line (viser
        would print a traceback for each event)."""
        return self._inbound.guarded(lambda _event: action(), what)

    def _apply_visibility(self) -> None:
        with self._lock:
            if self._robot is not None:
                self._robot.show_visual = self.show_visual.value
                if self.model.has_collision:  # (else ViserUrdf loaded none: nothing to show)
                    self._robot.show_collision = self.show_collision.value
            for frame in self.frames.values():
                frame.visible = self.show_frames.value
            for marker in self.markers.values():
                marker.visible = self.show_markers.value

    def _set_status(self) -> None:
        model = self.model
        name = model.urdf.robot.name if model is not None else "?"
        lines = [f"**{name}**: {len(model.urdf.robot.links)} links, "
                 f"{len(model.joints)} movable joints"]
        if self.reloads:
            lines[0] += f"; reloaded {self.reloads}×"
        if self.errors:
            lines.append("**The last change does not build; showing the last good model:**")
        self.status.content = "\n\n".join(lines)
        self.error_box.content = error_box_html(self.errors)
        self.error_box.visible = bool(self.errors)

    # -- the robot ---------------------------------------------------------------------

    def show(self, model: ViewModel) -> None:
        """Put ``model`` on the page in place of the one shown, keeping the joint values
        of joints it still has (within their new limits)."""
        with self._lock, self.server.atomic():
            kept = {name: slider.value for name, slider in self.sliders.items()}
            if self._robot is not None:
                with warnings.catch_warnings():  # it removes children its parents took along
                    warnings.simplefilter("ignore", UserWarning)
                    self._robot.remove()
            for node in [*self.frames.values(), *self.markers.values()]:
                node.remove()
            if self._joints_folder is not None:
                self._inbound.forget(self.sliders.values())
                self._joints_folder.remove()
            self.model = model
            self.errors = []
            self._robot = ViserUrdf(self.server, model.urdf, root_node_name=ROBOT_NODE,
                                    load_meshes=True, load_collision_meshes=model.has_collision,
                                    collision_mesh_color_override=COLLISION_RGBA)
            self._add_frames(model)
            self._add_markers(model)
            self._add_sliders(model, kept)
            self._pose()
            self._apply_visibility()
            self.watch.watch(model.files)
            self._set_status()

    def _add_frames(self, model: ViewModel) -> None:
        size = _robot_size(model)
        self.frames = {}
        for index, link in enumerate(model.urdf.robot.links):
            # Node names are paths: a link's name may hold a slash, its index cannot.
            self.frames[link.name] = self.server.scene.add_frame(
                f"{FRAMES_NODE}/{index}", axes_length=0.15 * size, axes_radius=0.006 * size,
                visible=False)

    def _add_markers(self, model: ViewModel) -> None:
        """A marker on every joint that moves (mimic joints too: they move with theirs)."""
        size = _robot_size(model)
        self.markers = {}
        for index, joint in enumerate(model.urdf.robot.joints):
            if joint.type not in MOVING:
                continue
            axis = joint.axis if joint.axis is not None else (1.0, 0.0, 0.0)
            points, colours = marker_segments(axis, joint.type, size)
            self.markers[joint.name] = self.server.scene.add_line_segments(
                f"{MARKERS_NODE}/{index}", points, colours, thickness=THICKNESS_PX,
                thickness_units="screen")

    def _add_sliders(self, model: ViewModel, kept: dict[str, float]) -> None:
        self.sliders = {}
        self._joints_folder = self.server.gui.add_folder("Joints", order=_ORDER["joints"])
        with self._joints_folder:
            for joint in model.joints:
                unit = "m" if joint.kind == "prismatic" else "rad"
                value = min(max(kept.get(joint.name, joint.home), joint.lower), joint.upper)
                slider = self.server.gui.add_slider(
                    joint.name, min=joint.lower, max=joint.upper,
                    step=(joint.upper - joint.lower) / 1000 or 0.001, initial_value=value,
                    hint=f"{joint.kind}, {joint.lower:g} to {joint.upper:g} {unit}")
                slider.on_update(self._on_page(self._pose, f"moving joint {joint.name!r}"))
                self.sliders[joint.name] = self._inbound.accept(slider)

    def joint_values(self) -> dict[str, float]:
        return {name: float(slider.value) for name, slider in self.sliders.items()}

    def reset_joints(self) -> None:
        with self._lock:
            for joint in self.model.joints:
                self.sliders[joint.name].value = joint.home

    def _pose(self) -> None:
        """Move the links to the sliders' values (mimic joints follow, by yourdfpy)."""
        with self._lock:
            if self._robot is None:
                return
            values = self.joint_values()
            if values:
                self._robot.update_cfg(values)  # yourdfpy takes {joint name: value} too
            urdf = self.model.urdf
            for name, frame in self.frames.items():
                _place(frame, urdf.get_transform(name, urdf.base_link))
            for name, marker in self.markers.items():  # in the joint's frame: its child's
                _place(marker, urdf.get_transform(urdf.joint_map[name].child, urdf.base_link))

    def _add_ground(self, model: ViewModel) -> None:
        """A grid under the robot at start, with round spacing, for scale."""
        size = _robot_size(model)
        bounds = _bounds(model)
        cell = 10 ** math.floor(math.log10(size / 4))
        self.server.scene.add_grid("/ground", width=8 * size, height=8 * size, cell_size=cell,
                                   section_size=10 * cell,
                                   position=(0.0, 0.0, 0.0 if bounds is None else bounds[0][2]))

    def _frame_camera(self, model: ViewModel) -> None:
        """Start every page looking at the whole robot (viser's default camera stands
        metres away, where a 30 cm robot is a speck)."""
        centre, size = _robot_centre(model), _robot_size(model)
        distance = 0.75 * size / math.tan(CAMERA_FOV / 2)
        direction = CAMERA_DIRECTION / np.linalg.norm(CAMERA_DIRECTION)
        camera = self.server.initial_camera
        camera.fov = CAMERA_FOV
        camera.near = size / 1000
        camera.far = size * 1000
        camera.look_at = centre
        camera.position = centre + distance * direction
        camera.up = (0.0, 0.0, 1.0)

    # -- dimensions --------------------------------------------------------------------

    def _build_dimension_panel(self) -> None:
        gui, dims, accept = self.server.gui, self.dimensions, self._inbound.accept
        with gui.add_folder("Dimensions", order=_ORDER["dimensions"], expand_by_default=False):
            copy = accept(gui.add_button("Copy overrides as --config YAML",
                                         hint="mcar build --config FILE builds this robot"))
            self.overrides_yaml = accept(gui.add_text("--config YAML", "", multiline=True,
                                                      visible=False))
            copy.on_click(self._on_page(self.show_overrides_yaml, "showing the overrides"))
            for item in dims.ranges:
                value = min(max(dims.value(item.name), item.low), item.high)
                start, end, step = item.neighbourhood(value)
                unit = "" if item.shown_unit in ("1", "count") else f" {item.shown_unit}"
                slider = gui.add_slider(
                    item.label, min=start, max=end, step=step, initial_value=item.shown(value),
                    hint=f"{item.meaning} (default {item.shown(item.default):g}{unit}; "
                         f"the slider spans half to twice the value, the box takes any "
                         f"value of {item.plausible})")
                slider.on_update(self._inbound.guarded(
                    lambda event, item=item: self._slid(item, event.target),
                    f"setting dimension {item.name!r}"))
                self.dimension_sliders[item.name] = accept(slider, bounds=item.bounds())
                self._dimension_items[item.name] = item

    def _slid(self, item, slider) -> None:
        # Dragging sends values faster than the robot builds: each callback, once its turn
        # comes, builds the slider's newest value, and the ones queued behind it see it built.
        with self._dimension_lock:
            shown = slider.value
            if shown != item.shown(self.dimensions.value(item.name)):
                self.set_dimension(item.name, shown * item.factor)

    def set_dimension(self, name: str, value: float) -> McarError | None:
        """Rebuild with dimension ``name`` at ``value``, validated as ``--set`` is. A value
        refused (by its range or config.xacro's cross-checks) leaves the model and the
        overrides as they were, shows why, and puts the slider back; returns that error."""
        with self._dimension_lock:
            dims = self.dimensions
            try:
                values = dims.with_value(name, value)
            except McarError as error:
                return self._refuse_dimension(name, error)
            if values == dims.values:  # (as after putting a slider back)
                return None
            error = self.rebuild(lambda: dims.load(values))
            if error is not None:
                return self._refuse_dimension(name, error)
            self._span(name)
            if self.overrides_yaml is not None and self.overrides_yaml.visible:
                self.show_overrides_yaml()
            return None

    def _refuse_dimension(self, name: str, error: McarError) -> McarError:
        with self._lock:
            self.errors = error_lines(error)
            self._set_status()
        slider = self.dimension_sliders.get(name)
        if slider is not None:  # put back (a typed value may have been past its end)
            self._span(name)
            slider.value = self._dimension_items[name].shown(self.dimensions.value(name))
        return error

    def _span(self, name: str) -> None:
        """A dimension built at a value past its slider's ends (typed in the box): the
        slider spans the neighbourhood of that value instead. (Its value is left alone:
        a drag may have sent newer ones, which are on their way.)"""
        slider, item = self.dimension_sliders.get(name), self._dimension_items.get(name)
        value = self.dimensions.value(name)
        if slider is not None and not slider.min <= item.shown(value) <= slider.max:
            slider.min, slider.max, slider.step = item.neighbourhood(value)

    def show_overrides_yaml(self) -> str:
        """Show the overrides as a ``--config`` file in the page, to copy from (a page
        served without https may not write the clipboard)."""
        text = self.dimensions.yaml()
        self.overrides_yaml.value = text
        self.overrides_yaml.visible = True
        return text

    # -- live reload -------------------------------------------------------------------

    def reload_if_changed(self) -> tuple[list, McarError | None]:
        """Rebuild if a file of the robot changed: (the changed files, the error that
        kept the last good model on the page, or None)."""
        changed = self.watch.changed()
        if not changed:
            return [], None
        return changed, self.rebuild()

    def rebuild(self, build: Callable[[], ViewModel] | None = None) -> McarError | None:
        """Build the robot anew (by ``build``, else as a reload does) and show it; on
        failure, keep the model shown and show the error above it. Returns that error."""
        try:
            model = (build or self._reload)()
        except McarError as error:
            with self._lock:
                self.errors = error_lines(error)
                self._set_status()
            return error
        with self._lock:
            self.reloads += 1
            self.show(model)
        return None


def _place(node, pose: np.ndarray) -> None:
    node.wxyz = vtf.SO3.from_matrix(pose[:3, :3]).wxyz
    node.position = pose[:3, 3]


def error_box_html(lines: list[str]) -> str:
    """The error lines as the page shows them: text, never markup (a message quotes the
    files' names and contents), each line whole and wrapped.

    (A markdown code block, as before, kept a long line on one row behind a scroll bar.)"""
    if not lines:
        return ""
    text = html.escape("\n".join(lines), quote=True)
    return f'<div class="mcar-errors" style="{ERROR_BOX_STYLE}">{text}</div>'


def _no_share_url(*args, **kwargs) -> None:
    return None


@contextlib.contextmanager
def _quiet():
    with contextlib.redirect_stdout(io.StringIO()):
        yield


def _bounds(model: ViewModel) -> np.ndarray | None:
    for scene in (model.urdf.scene, model.urdf.collision_scene):
        if scene is not None and scene.geometry:
            bounds = scene.bounds
            if bounds is not None and np.isfinite(bounds).all():
                return bounds
    return None


def _robot_size(model: ViewModel) -> float:
    """The robot's bounding box diagonal in metres (1 m when it has no geometry)."""
    bounds = _bounds(model)
    size = float(np.linalg.norm(bounds[1] - bounds[0])) if bounds is not None else 0.0
    return size if size > 1e-6 else 1.0


def _robot_centre(model: ViewModel) -> np.ndarray:
    bounds = _bounds(model)
    return np.zeros(3) if bounds is None else (bounds[0] + bounds[1]) / 2
