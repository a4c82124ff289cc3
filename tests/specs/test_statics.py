"""mcar specs' statics on robots whose answers are known in closed form: a box on four
wheels (tip-over angles atan(d / h) to each axle and side, slide atan(μ) from a declared
<mu1>, --friction or MuJoCo's default, climb asin(Σ effort/r / m·g) from a declared
effort), an Ackermann car's turning radius from its steering limits, top speed from the
velocity limit; and the rules the figures raise (W502-W506, E503), with their numbers.
No MuJoCo run here (proof False): test_statics_proofs.py runs them."""

from __future__ import annotations

import math

import pytest
from sim.robot_makers import ackermann
from specs.statics_robots import box_on_wheels, checked_and_sim

from mobile_car.check.diagnostics import Diagnostic
from mobile_car.specs.figures import Figure, Proof, Section
from mobile_car.specs.statics import statics_section
from mobile_car.specs.statics_rules import judge

R, WHEEL_MASS, BODY_MASS = 0.05, 0.1, 9.6
MASS = BODY_MASS + 4 * WHEEL_MASS


def _statics(tmp_path, name, text, **options):
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    checked, sim = checked_and_sim(path)
    section = statics_section(checked, sim, {"proof": False, **options})
    return section, {f.key: f for f in section.figures}


def _height(lift):
    """The box robot's centre of mass above the floor: the wheels' at r, the body's
    ``lift`` above them."""
    return R + BODY_MASS * lift / MASS


@pytest.fixture(scope="module")
def offset_box(tmp_path_factory):
    """Wheelbase 0.4, track 0.3, the body 0.15 up and 0.04 ahead, tyres of μ 0.6."""
    folder = tmp_path_factory.mktemp("statics")
    return _statics(folder, "offset", box_on_wheels(track=0.3, lift=0.15, com_x=0.04,
                                                    mu=0.6, effort=0.3, velocity=10))


def test_tip_angles_are_atan_of_the_distance_to_each_edge_over_the_height(offset_box):
    section, fig = offset_box
    h, ahead = _height(0.15), BODY_MASS * 0.04 / MASS
    expected = {"forward": math.atan2(0.2 - ahead, h), "backward": math.atan2(0.2 + ahead, h),
                "left": math.atan2(0.15, h), "right": math.atan2(0.15, h)}
    for name, angle in expected.items():
        assert fig[f"statics.tip.{name}"].value == pytest.approx(math.degrees(angle), abs=1e-3)
        assert fig[f"statics.tip.{name}"].unit == "deg"
    assert sorted(map(tuple, fig["statics.support"].value)) == pytest.approx(
        sorted([(-0.2, -0.15), (-0.2, 0.15), (0.2, -0.15), (0.2, 0.15)]), abs=1e-6)
    # The nearest edge is a side (0.15 m) before the front axle (0.2 - 0.038 m)
    least = fig["statics.tip.min"]
    assert least.value == pytest.approx(math.degrees(math.atan2(0.15, h)), abs=1e-3)
    assert "towards azimuth 90.0°" in least.source or "towards azimuth 270.0°" in least.source


def test_the_tip_polar_goes_round_every_15_degrees_to_the_edge_its_ray_crosses(offset_box):
    _section, fig = offset_box
    polar = fig["statics.tip.polar"].value
    assert [a for a, _ in polar] == list(range(0, 360, 15))
    h, ahead = _height(0.15), BODY_MASS * 0.04 / MASS
    for azimuth, angle in polar:
        a = math.radians(azimuth)
        reaches = []  # from the centre of mass (ahead, 0) to x = ±0.2, y = ±0.15 along a
        if math.cos(a) > 1e-9:
            reaches.append((0.2 - ahead) / math.cos(a))
        if math.cos(a) < -1e-9:
            reaches.append((-0.2 - ahead) / math.cos(a))
        if abs(math.sin(a)) > 1e-9:
            reaches.append(0.15 / abs(math.sin(a)))
        assert angle == pytest.approx(math.degrees(math.atan2(min(reaches), h)), abs=1e-3)


def test_slide_is_atan_of_the_declared_mu_and_stand_the_least_of_tip_and_slide(offset_box):
    _section, fig = offset_box
    slide = fig["statics.slide"]
    assert slide.value == pytest.approx(math.degrees(math.atan(0.6)), abs=1e-3)
    assert '<gazebo reference="front_left_wheel_link"> mu1' in slide.source
    # The side tips at 39.6° first: slides at 31.0° in every direction.
    assert fig["statics.stand"].value == pytest.approx(slide.value, abs=1e-3)
    assert "slides towards" in fig["statics.stand"].source


def test_slide_falls_back_on_the_friction_option_then_on_mujocos_default(tmp_path):
    _section, given = _statics(tmp_path, "given", box_on_wheels(lift=0.1), friction=0.8)
    assert given["statics.slide"].value == pytest.approx(math.degrees(math.atan(0.8)), abs=1e-3)
    assert "μ 0.8 (--friction)" in given["statics.slide"].source
    _section, default = _statics(tmp_path, "default", box_on_wheels(lift=0.1))
    assert default["statics.slide"].value == pytest.approx(45.0, abs=1e-3)
    assert "MuJoCo's default 1 (no <mu1> given)" in default["statics.slide"].source


def test_climb_is_what_the_declared_efforts_push_against_the_weight(offset_box):
    _section, fig = offset_box
    climb = fig["statics.climb"]
    # Σ effort / r = 4 × 0.3 / 0.05 = 24 N against m·g = 98.1 N; μ 0.6 grips to 31°.
    assert climb.value == pytest.approx(math.degrees(math.asin(24 / (MASS * 9.81))), abs=1e-3)
    assert climb.source.startswith("limited by the motors:")
    assert "Σ effort/r = 24 N of m·g = 98.1 N; effort 0.3 N·m (joint <limit effort>)" \
        in climb.source


def test_top_speed_is_the_velocity_limit_at_the_rim_unless_a_placeholder(offset_box, tmp_path):
    _section, fig = offset_box
    speed = fig["statics.top_speed"]
    assert (speed.value, speed.unit) == (pytest.approx(0.5), "m/s")
    assert speed.source == "10 rad/s (joint <limit velocity> of front_left_wheel_joint) × " \
                           "wheel radius 0.05 m"
    _section, fast = _statics(tmp_path, "fast", box_on_wheels(effort=1, velocity=200))
    assert fast["statics.top_speed"].value is None
    assert "a placeholder: 200 rad/s is 10 m/s at the rim" in fast["statics.top_speed"].source


def test_turning_radius_is_0_in_place_and_an_ackermann_cars_from_its_limits(offset_box,
                                                                            tmp_path):
    _section, fig = offset_box
    assert fig["statics.turning_radius"].value == 0.0
    assert fig["statics.turning_radius"].source == "turns in place (skid-steer drive)"
    _section, car = _statics(tmp_path, "car", ackermann(wheelbase=0.5, track=0.4,
                                                         steer_limit=0.6))
    # The inner pivot (0.2 m from the centre line) at 0.6 rad, 0.5 m ahead of the rear axle
    radius = car["statics.turning_radius"]
    assert radius.value == pytest.approx(0.5 / math.tan(0.6) + 0.2, abs=1e-4)
    assert "front_left_steering_joint 34.4°" in radius.source


def test_a_narrow_track_is_caught_with_its_figures(tmp_path):
    """A long tall box on a 0.12 m track, whose motors climb 45°: it tips sideways at 11.7°
    (over its axles at 54°)."""
    section, fig = _statics(tmp_path, "narrow", box_on_wheels(
        wheelbase=0.8, track=0.12, body=(0.7, 0.06, 0.3), lift=0.25, effort=3))
    h = _height(0.25)
    side = math.degrees(math.atan2(0.06, h))
    assert fig["statics.tip.left"].value == pytest.approx(side, abs=1e-3)
    texts = [d.text() for d in section.diagnostics]
    line = next(t for t in texts if t.endswith("[W504]"))
    assert f"its motors climb 45.0° but across a slope it tips over left at {side:.1f}° " \
           "(track too narrow or centre of mass too high) [W504]" in line
    assert line.startswith(f"{tmp_path / 'narrow.urdf'}:")  # located at a wheel joint
    assert not any(t.endswith("[W502]") for t in texts)  # 54° forward and back: over 45°


def test_a_robot_that_tips_on_a_slope_it_climbs_is_w502(tmp_path):
    section, fig = _statics(tmp_path, "tall", box_on_wheels(lift=0.6, effort=3))
    back = fig["statics.tip.backward"].value
    assert back == pytest.approx(math.degrees(math.atan2(0.2, _height(0.6))), abs=1e-3)
    messages = [d.text() for d in section.diagnostics]
    assert any(f"its motors climb 45.0° but it tips over backward at {back:.1f}°: driving up "
               "such a slope it falls [W502]" in m for m in messages), messages


def test_weak_motors_are_w503_and_motors_that_cannot_move_it_e503(tmp_path):
    section, fig = _statics(tmp_path, "weak", box_on_wheels(lift=0.1, effort=0.05))
    climb = fig["statics.climb"].value  # asin(4 N / 98.1 N) = 2.34°
    assert climb == pytest.approx(math.degrees(math.asin(4 / (MASS * 9.81))), abs=1e-3)
    (weak,) = [d for d in section.diagnostics if d.rule == "W503"]
    assert weak.text().endswith(f"it climbs {climb:.1f}° at most, less than a 5° ramp: "
                                f"{fig['statics.climb'].source} [W503]")
    section, fig = _statics(tmp_path, "dead", box_on_wheels(lift=0.1, effort=0))
    assert fig["statics.climb"].value == 0
    (dead,) = [d for d in section.diagnostics if d.rule.startswith("E")]
    assert dead.is_error and dead.text().endswith("[E503]")
    assert "the motors cannot move the robot on flat ground: limited by the motors" in dead.text()


def test_a_centre_of_mass_outside_what_it_stands_on_is_w505(tmp_path):
    """Two wheels under the centre and no castor: the robot stands on a line, balanced."""
    section, fig = _statics(tmp_path, "line", box_on_wheels(lift=0.1, wheelbase=0.0,
                                                            ends=("rear",)))
    assert fig["statics.tip.forward"].value == 0 and fig["statics.tip.min"].value == 0
    assert len(fig["statics.support"].value) == 2
    assert any(d.text().endswith("it stands only balanced [W505]") for d in section.diagnostics)


def test_a_proof_that_disagrees_is_w506_never_hidden():
    class Checked:
        file, robot, where = "robot.urdf", None, None

    class Sim:
        drive = None

    section = Section("statics", figures=[Figure(
        "statics.tip.left", "tip-over angle left", 20.0, "deg", "atan(d / h)",
        proof=Proof(12.5, False, "±1°", "tilted towards azimuth 90° it tips at 12.50°"))])
    (found,) = judge(Checked(), Sim(), section)
    assert isinstance(found, Diagnostic)
    assert found.text() == ("robot.urdf: warning: statics.tip.left 20.0 deg but MuJoCo "
                            "measured 12.50 deg (±1°): tilted towards azimuth 90° it tips at "
                            "12.50° [W506]")


def test_loads_share_by_the_lever_and_by_the_contacts_stiffness():
    from mobile_car.specs.slopes import loads

    # three contacts: exact, whatever their stiffness (the lever rule)
    three = [(0.0, 0.1), (0.0, -0.1), (-0.2, 0.0)]
    assert loads(three, (-0.05, 0.0)) == pytest.approx([0.375, 0.375, 0.25])
    assert loads(three, (-0.05, 0.0), [5, 5, 1]) == pytest.approx([0.375, 0.375, 0.25])
    # six, symmetric: by stiffness (MiR's wheels 31 % each in MuJoCo, its castors 9 %)
    six = [(0, 0.2), (0, -0.2), (0.3, 0.2), (0.3, -0.2), (-0.3, 0.2), (-0.3, -0.2)]
    assert loads(six, (0.0, 0.0), [30, 30, 5, 5, 5, 5]) == \
        pytest.approx([0.375, 0.375, 0.0625, 0.0625, 0.0625, 0.0625])
    # past a contact the plane would pull, it lifts and the others carry it all
    assert loads(three, (0.05, 0.0)) == pytest.approx([0.5, 0.5, 0.0])


def test_the_entry_specs_calls_takes_its_context(tmp_path):
    """section(context): specs-core's SpecsContext (checked, sim, body, options)."""
    from types import SimpleNamespace

    from mobile_car.specs.statics import section

    path = tmp_path / "box.urdf"
    path.write_text(box_on_wheels(lift=0.1, mu=0.6))
    checked, sim = checked_and_sim(path)
    context = SimpleNamespace(checked=checked, sim=sim, body=None, options={"proof": False})
    result = section(context)
    assert result.name == "statics"
    assert [f.key for f in result.figures] == [
        "statics.support", "statics.tip.polar", "statics.tip.forward", "statics.tip.left",
        "statics.tip.backward", "statics.tip.right", "statics.tip.min", "statics.slide",
        "statics.stand", "statics.climb", "statics.top_speed", "statics.turning_radius"]
    assert all(f.proof is None for f in result.figures)


def _askew_castor(roll: str) -> str:
    """Two wheels under the centre and TurtleBot3 burger's castor block behind them (its
    collision box 30 x 9 x 20 mm turned by ``roll`` about x), 1 mm over the floor and the
    centre of mass 3 cm back: the robot leans back onto the block's back bottom edge."""
    castor = f"""
  <joint name="caster_back_joint" type="fixed">
    <parent link="base_link"/><child link="caster_back_link"/>
    <origin xyz="-0.15 0 {-R + 0.0055:.6g}" rpy="{roll} 0 0"/>
  </joint>
  <link name="caster_back_link">
    <collision><geometry><box size="0.030 0.009 0.020"/></geometry></collision>
    <inertial><mass value="0.005"/><inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0"
      izz="1e-6"/></inertial>
  </link>
</robot>
"""
    return box_on_wheels(wheelbase=0.0, ends=("rear",), com_x=-0.03).replace(
        "\n</robot>\n", castor)


def test_a_castor_block_touches_by_the_corners_that_reach_the_floor(tmp_path):
    """burger's block is turned -1.57 about x, not -π/2: one corner of its bottom edge is
    16 µm over the other, and MuJoCo, sinking 2 µm under the castor's load, carries it on
    the lower one alone. The stance counts that corner only (its wheels' shares then
    differ, as MuJoCo's do); turned by exactly π/2 the block touches by both."""
    from mobile_car.specs.support import stance

    shown = {}
    for name, roll in (("askew", "-1.57"), ("square", f"{-math.pi / 2!r}")):
        path = tmp_path / f"{name}.urdf"
        path.write_text(_askew_castor(roll))
        _checked, sim = checked_and_sim(path)
        shown[name] = [(round(c.x, 4), round(c.y, 4)) for c in stance(sim, {}, None).contacts
                       if c.link == "caster_back_link"]
    (corner,) = shown["askew"]
    assert corner[0] == pytest.approx(-0.165, abs=1e-3) and abs(corner[1]) == pytest.approx(0.01)
    assert sorted(y for _x, y in shown["square"]) == pytest.approx([-0.01, 0.01])
