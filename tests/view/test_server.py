"""The viewer through viser's own API: sliders move the links, edits reload the robot, and
an edit that does not build keeps the last good robot on the page with its error."""

from __future__ import annotations

import html
import math
import os

import numpy as np
import pytest

viser = pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]";'
                                            " `make test` installs it)")
from viser.transforms import SO3  # noqa: E402


def _rotation(frame) -> np.ndarray:
    return SO3(np.asarray(frame.wxyz)).as_matrix()


def _about_y(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _edit(path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))
    # A later stamp than the one recorded even on a coarse clock.
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))


def test_the_page_offers_a_slider_per_movable_joint_within_its_limits(served):
    sliders = served.sliders
    assert list(sliders) == ["shoulder", "wrist"]  # elbow mimics shoulder: no slider
    assert (sliders["shoulder"].min, sliders["shoulder"].max) == (-1.5, 1.5)
    assert (sliders["wrist"].min, sliders["wrist"].max) == (-math.pi, math.pi)  # continuous
    assert served.url == f"http://127.0.0.1:{served.port}/"


def test_a_slider_turns_its_link_and_the_mimic_joint_follows(served):
    frames = served.frames
    assert np.allclose(_rotation(frames["upper_arm"]), np.eye(3))
    served.sliders["shoulder"].value = 0.5
    assert np.allclose(_rotation(frames["upper_arm"]), _about_y(0.5), atol=1e-6)
    # elbow mimics shoulder with multiplier -2: the forearm turns back by twice as much.
    assert np.allclose(_rotation(frames["forearm"]), _about_y(0.5 - 1.0), atol=1e-6)
    # The forearm hangs at the end of the upper arm (0.3 m from the shoulder, 5 cm up).
    expected = np.array([0.0, 0.0, 0.05]) + _about_y(0.5) @ np.array([0.3, 0.0, 0.0])
    assert np.allclose(frames["forearm"].position, expected, atol=1e-6)


def test_every_moving_joint_has_a_marker_that_turns_with_it(served):
    from mobile_car.view.markers import AXIS_RGB, SPOKE_RGB

    markers = served.markers
    assert list(markers) == ["shoulder", "elbow", "wrist"]  # the mimic joint moves too
    assert all(marker.visible for marker in markers.values())  # on from the start
    shoulder = markers["shoulder"]
    segments = np.asarray(shoulder.points)
    # along the shoulder's axis (y) through the joint, then a spoke square to it at each end
    axis = segments[0]
    assert np.allclose(axis[:, [0, 2]], 0) and axis[1, 1] == -axis[0, 1] > 0
    for start, end in segments[1:]:
        assert np.allclose(start[[0, 2]], 0) and np.allclose((end - start)[:2], 0)
    assert [tuple(c[0]) for c in np.asarray(shoulder.colors)] == [AXIS_RGB] + [SPOKE_RGB] * 2
    # In the child's frame: it turns with the upper arm (and the elbow's with the forearm).
    served.sliders["shoulder"].value = 0.5
    assert np.allclose(_rotation(shoulder), _about_y(0.5), atol=1e-6)
    assert np.allclose(_rotation(markers["elbow"]), _about_y(0.5 - 1.0), atol=1e-6)
    assert np.allclose(markers["elbow"].position, served.frames["forearm"].position)
    served.show_markers.value = False
    assert not any(marker.visible for marker in markers.values())


def test_reset_puts_every_joint_back_to_zero(served):
    served.sliders["shoulder"].value = -1.0
    served.sliders["wrist"].value = 2.0
    served.reset_joints()
    assert served.joint_values() == {"shoulder": 0.0, "wrist": 0.0}
    assert np.allclose(_rotation(served.frames["forearm"]), np.eye(3))


def test_switches_show_and_hide_the_geometry_and_the_frames(served):
    frames = list(served.frames.values())
    assert not any(frame.visible for frame in frames)
    served.show_frames.value = True
    assert all(frame.visible for frame in frames)
    assert served.show_visual.value is True and served.show_collision.value is False


def test_an_edit_to_an_included_file_reloads_the_robot(served, arm_copy):
    served.sliders["shoulder"].value = 0.5
    assert served.reload_if_changed() == ([], None)  # nothing changed: nothing rebuilt
    macro = arm_copy.parent / "arm_link.xacro"
    _edit(macro, 'value="0.3"', 'value="0.45"')
    changed, error = served.reload_if_changed()
    assert (changed, error) == ([macro], None)
    assert served.reloads == 1
    assert served.joint_values()["shoulder"] == 0.5  # the pose is kept across the reload
    expected = np.array([0.0, 0.0, 0.05]) + _about_y(0.5) @ np.array([0.45, 0.0, 0.0])
    assert np.allclose(served.frames["forearm"].position, expected, atol=1e-6)
    assert "reloaded 1×" in served.status.content


def test_an_edit_that_does_not_build_keeps_the_last_good_robot(served, arm_copy):
    shown = served.model
    macro = arm_copy.parent / "arm_link.xacro"
    _edit(macro, "</robot>", "</robt>")
    changed, error = served.reload_if_changed()
    assert changed == [macro] and error is not None
    assert served.model is shown and served.reloads == 0
    assert len(served.errors) == 1
    assert served.errors[0].startswith(f"{macro}:") and served.errors[0].endswith("[E140]")
    assert "mismatched tag" in served.errors[0]
    assert html.escape(served.errors[0]) in served.error_box.content  # (as text: escaped)
    assert served.error_box.visible
    assert "showing the last good model" in served.status.content
    # Mended, it reloads and the error goes.
    _edit(macro, "</robt>", "</robot>")
    assert served.reload_if_changed() == ([macro], None)
    assert served.errors == [] and "last good" not in served.status.content
    assert not served.error_box.visible and served.error_box.content == ""


def test_an_edit_that_check_rejects_shows_check_s_diagnostic(served, arm_copy):
    shown = served.model
    _edit(arm_copy, 'upper="1.5"', 'upper="-2"')  # upper below lower
    changed, error = served.reload_if_changed()
    assert changed == [arm_copy] and error is not None
    assert served.model is shown
    # check's diagnostics, as `mcar check` prints them (its warning about the root too)
    assert [line.split(": ", 2)[:2] for line in served.errors] == [
        [f"{arm_copy}:16", "warning"], [f"{arm_copy}:28", "error"]]
    assert "upper" in served.errors[1] and served.errors[1].endswith("]")
