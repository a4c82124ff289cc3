"""The calibration behind the mecanum climb proof (mobile_car/specs/proof_grip.py,
docs/specs.md "Mecanum climb"): on the contact parameters sim gives a mecanum wheel and the
proof's options, MuJoCo's contact is Coulomb's — a capsule gripping at 45° to the slope
holds to tan θ = μ/√2 and slides past it — while a lone wheel driven at its grip climbs
with a share of it, the share the proof expects a robot to reach."""

from __future__ import annotations

import math

import pytest
from sim.robot_makers import PLANAR_MOVE, mecanum_wheels
from specs.statics_robots import checked_and_sim

from mobile_car.specs.proof_climb import DRIVE, MEASURE, PROGRESS, SERVO_STIFFER_MECANUM
from mobile_car.specs.proof_grip import driven_share
from mobile_car.specs.proof_tilt import proof_model
from mobile_car.specs.support import stance

COULOMB = math.degrees(math.atan(math.hypot(1.0, 0.01) / math.sqrt(2)))  # 35.266°


@pytest.fixture(scope="module")
def robot(tmp_path_factory):
    """(the proof model, sim, its stance) of a 10 kg X-pattern robot as linorobot2
    declares its wheels (planar_move, <mu1> 0.01: sim grips at 1 along, 0.01 across)."""
    path = tmp_path_factory.mktemp("grip") / "mecanum.urdf"
    path.write_text(mecanum_wheels(wheel_mu=0.01, extra=PLANAR_MOVE))
    _, sim = checked_and_sim(path)
    found = stance(sim, sim.friction, None)
    model, _ = proof_model(sim, found, resting=False)
    return model, sim, found


def _slides(model, wheel, slope_deg: float) -> float:
    """How far (m) a capsule with ``wheel``'s contact pair, lying at 45° to the slope on a
    10 kg carriage that moves only along it and up off the floor, slides down ``slope_deg``
    in 1 s."""
    from mobile_car.sim.engine import mujoco

    mj = mujoco()
    pair = model.pair(f"mcar_grip_{wheel.joint}").id
    numbers = {name: " ".join(f"{v:.9g}" for v in values) for name, values in (
        ("friction", model.pair_friction[pair]), ("solref", model.pair_solref[pair]),
        ("solimp", model.pair_solimp[pair]))}
    rig = mj.MjModel.from_xml_string(f"""<mujoco>
      <option timestep="{model.opt.timestep:.9g}" cone="elliptic"
              impratio="{model.opt.impratio:.9g}"/>
      <worldbody><geom name="floor" type="plane" size="1 1 1" contype="0" conaffinity="0"/>
        <body pos="0 0 {wheel.radius:.9g}">
          <joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 0 1"/>
          <geom name="capsule" type="capsule" zaxis="1 1 0" mass="10" contype="0"
                conaffinity="0" size="{wheel.radius:.9g} {0.1 * wheel.radius:.9g}"/>
        </body></worldbody>
      <contact><pair geom1="capsule" geom2="floor" condim="3" friction="{numbers['friction']}"
                     solref="{numbers['solref']}" solimp="{numbers['solimp']}"/></contact>
    </mujoco>""")
    data = mj.MjData(rig)
    theta = math.radians(slope_deg)
    rig.opt.gravity[:] = [-9.81 * math.sin(theta), 0.0, -9.81 * math.cos(theta)]
    mj.mj_step(rig, data, nstep=int(0.5 / rig.opt.timestep))
    start = float(data.qpos[0])
    mj.mj_step(rig, data, nstep=int(1.0 / rig.opt.timestep))
    return start - float(data.qpos[0])


def test_mujocos_contact_on_a_mecanum_wheels_parameters_is_coulombs(robot):
    model, sim, _ = robot
    wheel = sim.drive.driven[0]
    assert list(model.pair_friction[model.pair(f"mcar_grip_{wheel.joint}").id][:2]) == [
        1.0, 0.01]
    assert _slides(model, wheel, COULOMB - 0.1) < 1e-4  # it creeps µm
    assert _slides(model, wheel, COULOMB + 0.1) > 5e-3  # it slides


def test_a_lone_wheel_driven_at_its_grip_climbs_with_a_share_of_it(robot):
    """The share the climb proof expects: a few per cent short of the grip (the rig's
    resolution is 0.05°, a share of 0.002)."""
    model, sim, found = robot
    wheel = sim.drive.driven[0]
    gain = float(model.actuator_gainprm[wheel.actuator_id][0]) * SERVO_STIFFER_MECANUM
    share = driven_share(model, wheel, found.mass / 4, 0.05 / wheel.radius, gain,
                         (DRIVE, MEASURE, PROGRESS))
    assert 0.95 < share < 0.99, share
