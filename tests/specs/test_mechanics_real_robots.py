"""mcar specs' joints and inertia sections on released robots, read in place from the
shared real-robots folder (SOURCES.md there): Kobuki's typed-in wheel inertias caught at
their lines, MiR's mesh-shaped base proven by MuJoCo, Create 3's wheel drops carried by
its springs."""

from __future__ import annotations

import pytest
from sim.test_sim_real_robots import FOLDER, needs_folder

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.specs.inertia import inertia_section
from mobile_car.specs.joints import joints_section

pytestmark = needs_folder


def checked(monkeypatch, relative: str):
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(FOLDER))
    result = check_input(RobotInput(FOLDER / relative))
    assert result.failure is None and not result.errors, result.diagnostics
    return result


def test_kobukis_wheel_inertias_are_w530_at_the_line_that_types_them(monkeypatch):
    found = inertia_section(checked(monkeypatch, "kobuki_description/urdf/"
                                                 "kobuki_standalone.urdf.xacro"))
    source = (FOLDER / "kobuki_description/urdf/kobuki.urdf.xacro").read_text().splitlines()
    flagged = {d.message.split("'")[1]: d for d in found.diagnostics}
    assert set(flagged) == {"wheel_left_link", "wheel_right_link", "caster_front_link",
                            "caster_back_link"}
    wheel = flagged["wheel_left_link"]
    assert wheel.file.endswith("kobuki_description/urdf/kobuki.urdf.xacro")
    assert "<inertia ixx=\"0.001\"" in source[wheel.line - 1]
    assert ("declared inertia [0.001, 0, 0, 0.001, 0, 0.001] kg m² is implausible: 293 "
            "times the geometry's") in wheel.message
    assert all(f.proof.agrees for f in found.figures)


def test_mirs_inertias_with_its_meshes_are_proven_by_mujoco(monkeypatch):
    found = inertia_section(checked(monkeypatch, "mir_description/urdf/mir.urdf.xacro"))
    assert len(found.figures) == 13
    assert all(f.proof.agrees for f in found.figures), \
        [(f.key, f.proof.detail) for f in found.figures if not f.proof.agrees]
    base = found.figure("inertia.base_link")
    assert "mesh" in base.source


def test_create3s_wheel_drops_are_carried_by_its_springs(monkeypatch):
    from mobile_car.sim.model import build_model

    result = checked(monkeypatch, "irobot_create_description/urdf/create3.urdf.xacro")
    loaded = result.loaded
    sim = build_model(loaded.urdf, result.file, loaded.base, loaded.search)
    found = joints_section(result, sim)
    assert {f.key for f in found.figures} == {
        f"joints.wheel_drop_{side}_joint.{what}" for side in ("left", "right")
        for what in ("gravity", "effort")}
    carried = found.figure("joints.wheel_drop_left_joint.gravity")
    assert carried.value == pytest.approx(9.97, abs=0.01)
    assert "400 N/m (<gazebo> springStiffness)" in carried.source
    assert not found.diagnostics
