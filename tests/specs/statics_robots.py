"""Robots whose statics are known in closed form, and the one way the statics tests make
sim's model of a robot (check, then specs' model, as ``mcar specs`` does). Lengths in m, masses
in kg, angles in degrees."""

from __future__ import annotations

from pathlib import Path

from sim.robot_makers import box_inertia

from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions


def checked_and_sim(path: Path, package_paths=()):
    """(CheckResult, SimModel at rest) of the robot file ``path``: the model mcar specs
    computes its figures on (specs/model.specs_model)."""
    from mobile_car.check.checker import check_input
    from mobile_car.specs.model import specs_model

    checked = check_input(RobotInput(Path(path)),
                          LoadOptions(package_paths=[Path(p) for p in package_paths]))
    assert checked.failure is None and not checked.errors, checked.diagnostics
    sim, notes = specs_model(checked)
    assert sim is not None, notes
    return checked, sim


def _wheel(name, x, y, radius, width, mass, limit, mu):
    side = mass * (3 * radius * radius + width * width) / 12
    friction = (f'\n  <gazebo reference="{name}_link"><mu1>{mu:g}</mu1><mu2>{mu:g}</mu2>'
                '</gazebo>') if mu is not None else ""
    return f"""
  <joint name="{name}_joint" type="continuous">
    <parent link="base_link"/><child link="{name}_link"/>
    <origin xyz="{x:.6g} {y:.6g} 0"/><axis xyz="0 1 0"/>{limit}
  </joint>
  <link name="{name}_link">
    <collision><origin rpy="1.5707963 0 0"/>
      <geometry><cylinder radius="{radius:.6g}" length="{width:.6g}"/></geometry></collision>
    <inertial><mass value="{mass:.6g}"/><inertia ixx="{side:.6g}" ixy="0" ixz="0"
      iyy="{mass * radius * radius / 2:.6g}" iyz="0" izz="{side:.6g}"/></inertial>
  </link>{friction}"""


def box_on_wheels(wheelbase=0.4, track=0.4, radius=0.05, body_mass=9.6, wheel_mass=0.1,
                  body=(0.3, 0.2, 0.1), lift=0.0, com_x=0.0, effort=None, velocity=None,
                  mu=None, ends=("front", "rear")):
    """A box body on four wheels, all driven (skid-steer), the wheels' centres at the root
    origin's height; the body's mass at ``lift`` above the axles (its centre) and
    ``com_x`` ahead. The robot's centre of mass: x = body_mass·com_x / m, height
    radius + body_mass·lift / m above the floor; it tips over an axle or a side at
    atan(d / h), d from it to the wheels' contact lines. ``ends``: the axles it has
("rear" alone, with wheelbase 0: two wheels under the centre, no castor)."""
    limit = ""
    if effort is not None or velocity is not None:
        limit = (f'\n    <limit effort="{effort if effort is not None else 100:g}" '
                 f'velocity="{velocity if velocity is not None else 100:g}"/>')
    x, y, z = body
    parts = [f"""<?xml version="1.0"?>
<robot name="box_on_wheels">
  <link name="base_footprint"/>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 {radius:.6g}"/>
  </joint>
  <link name="base_link">
    <collision><origin xyz="0 0 {lift:.6g}"/>
      <geometry><box size="{x:.6g} {y:.6g} {z:.6g}"/></geometry></collision>
    <inertial><origin xyz="{com_x:.6g} 0 {lift:.6g}"/><mass value="{body_mass:.6g}"/>
      {box_inertia(body_mass, x, y, z)}</inertial>
  </link>"""]
    for end, wx in (("front", wheelbase / 2), ("rear", -wheelbase / 2)):
        if end not in ends:
            continue
        for side, sign in (("left", 1), ("right", -1)):
            parts.append(_wheel(f"{end}_{side}_wheel", wx, sign * track / 2, radius, 0.04,
                                wheel_mass, limit, mu))
    parts.append("\n</robot>\n")
    return "".join(parts)


def climb_proof(robot_text, tmp_path, grip_times: float = 1.0):
    """(statics.climb with its proof, the sim model, the stance) of the robot
    ``robot_text``, its figures computed with ``grip_times`` the wheels' grip and the
    motors' force (MuJoCo keeps the robot's own): a figure made wrong on purpose, for the
    proof to refute; the climb proof alone (no tilt proofs)."""
    import pytest

    from mobile_car.specs import statics as statics_module
    from mobile_car.specs.figures import Section
    from mobile_car.specs.proof_climb import prove_climb
    from mobile_car.specs.support import stance

    path = tmp_path / "robot.urdf"
    path.write_text(robot_text)
    _, sim = checked_and_sim(path)
    found = stance(sim, sim.friction, None)
    grip, motors = statics_module.grip_along, statics_module._motor_forces
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(statics_module, "grip_along",
                      lambda c, ux, uy: grip_times * grip(c, ux, uy))
        patch.setattr(statics_module, "_motor_forces", lambda sim: {
            body: (grip_times * force, wheel) for body, (force, wheel) in motors(sim).items()})
        statics = statics_module.Statics(found, sim)
        section = Section("statics", figures=statics.figures())
        prove_climb(sim, found, section, statics)
    return section.figure("statics.climb"), sim, found
