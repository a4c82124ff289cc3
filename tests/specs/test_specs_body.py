"""The body figures of mcar specs on robots whose every figure can be worked out by hand
(tests/specs/robots.py): mass, centre of mass, footprint, radii, clearance, wheels, and
the loads on the wheels and castor, by statics on three supports and from MuJoCo's
contact forces on four; and what a robot MuJoCo cannot model still gets."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest
from sim.robot_makers import bicycle, box_inertia, castor_swivels
from specs import robots
from specs.robots import BALL_AT, BALL_MASS, BODY, BODY_AT, BODY_MASS, WHEEL_MASS

from mobile_car.check.checker import check_input
from mobile_car.load.inputs import RobotInput
from mobile_car.load.robot import LoadOptions
from mobile_car.specs.compute import compute
from mobile_car.specs.loads import by_statics
from mobile_car.specs.outline import hull, radii

G = 9.81


def specs_of(path, **options) -> dict:
    """key -> Figure of the body section, and the section itself under "section"."""
    checked = check_input(RobotInput(path), LoadOptions())
    assert not checked.errors, checked.diagnostics
    body = compute(checked, options)[0]
    assert body.name == "body"
    return {**{f.key: f for f in body.figures}, "section": body}


@pytest.fixture(scope="module")
def car(tmp_path_factory) -> dict:
    path = tmp_path_factory.mktemp("specs_car") / "car.urdf"
    path.write_text(robots.box_on_wheels())
    return specs_of(path)


MASS = BODY_MASS + 2 * WHEEL_MASS + BALL_MASS
COM = [(BODY_MASS * BODY_AT[i] + BALL_MASS * BALL_AT[i]) / MASS for i in range(3)]


def test_mass_and_centre_of_mass_are_the_links(car):
    assert car["body.mass"].value == pytest.approx(MASS, abs=1e-12)
    assert car["body.mass"].unit == "kg"
    assert car["body.com"].value == pytest.approx(COM, abs=1e-9)
    # the root frame is at the axle, the wheels' radius above the floor they rest on
    assert car["body.com_height"].value == pytest.approx(
        robots.WHEEL_RADIUS + COM[2], abs=1e-6)
    assert car["body.com_height"].assumption == ""  # level: the castor reaches the floor


def test_the_footprint_is_the_outline_of_body_and_wheels(car):
    half_y, wx = robots.WHEEL_Y + robots.WHEEL_WIDTH / 2, robots.WHEEL_RADIUS
    back, front = BODY_AT[0] - BODY[0] / 2, BODY_AT[0] + BODY[0] / 2
    side = BODY[1] / 2
    expected = [(back, -side), (-wx, -half_y), (wx, -half_y), (front, -side),
                (front, side), (wx, half_y), (-wx, half_y), (back, side)]
    got = car["body.footprint"].value
    assert len(got) == len(expected), got  # the ball, inside, adds no vertex
    for point, want in zip(got, expected, strict=True):
        assert point == pytest.approx(want, abs=1e-9)
    assert car["body.radius.circumscribed"].value == pytest.approx(math.hypot(front, side))
    assert car["body.radius.inscribed"].value == pytest.approx(-back)  # the rear edge


def test_clearance_is_the_body_not_a_wheel_or_the_castor(car):
    figure = car["body.clearance"]
    bottom = BODY_AT[2] - BODY[2] / 2 + robots.WHEEL_RADIUS
    assert figure.value == pytest.approx(bottom, abs=1e-6)
    assert "base_link" in figure.source


def test_clearance_leaves_out_castor_forks(tmp_path):
    """MiR's castors swivel in forks that reach 40 mm above the floor: they ride on the
    castor wheels, the clearance is the body's (72 mm: 20% of the 60 mm radius above
    the axle)."""
    path = tmp_path / "swivels.urdf"
    path.write_text(castor_swivels(radius=0.06))
    figure = specs_of(path)["body.clearance"]
    assert figure.value == pytest.approx(1.2 * 0.06, abs=1e-6)
    assert figure.source.startswith("lowest point of base_link")


def test_wheels(car):
    assert car["wheels.radius"].value == pytest.approx(robots.WHEEL_RADIUS)
    assert "wheel_left_joint, wheel_right_joint" in car["wheels.radius"].source
    assert car["wheels.track"].value == pytest.approx(2 * robots.WHEEL_Y)
    assert car["wheels.wheelbase"].value is None
    assert car["wheels.wheelbase"].source.startswith("one axle")


def test_three_supports_carry_the_weight_by_statics(car):
    weight = MASS * G
    castor = weight * COM[0] / BALL_AT[0]  # moments about the axle
    loads = {k: f.value for k, f in car.items() if k.startswith("loads.")}
    assert loads == pytest.approx({"loads.wheel_left_link": (weight - castor) / 2,
                                   "loads.wheel_right_link": (weight - castor) / 2,
                                   "loads.castor_link": castor}, abs=1e-9)
    assert sum(loads.values()) == pytest.approx(weight, abs=1e-9)
    assert car["loads.castor_link"].source.startswith("statics")
    assert car["loads.castor_link"].unit == "N"


def test_four_wheels_take_their_loads_from_mujoco(tmp_path):
    path = tmp_path / "four.urdf"
    path.write_text(robots.four_wheels_loaded())
    figures = specs_of(path)
    loads = {k.removeprefix("loads."): f for k, f in figures.items() if k.startswith("loads.")}
    assert len(loads) == 4
    assert all(f.source.startswith("MuJoCo contact forces") for f in loads.values())
    weight = figures["body.mass"].value * G
    assert sum(f.value for f in loads.values()) == pytest.approx(weight, rel=0.01)
    # Front against rear is determinate (left and right alike): moments about the centre
    # of the wheelbase put the payload's share on the front axle.
    com_x = robots.PAYLOAD_MASS * robots.PAYLOAD_X / figures["body.mass"].value
    front = sum(f.value for name, f in loads.items() if name.startswith("front"))
    assert front == pytest.approx(weight * (0.5 + com_x / 0.4), rel=0.01)
    assert figures["wheels.wheelbase"].value == pytest.approx(0.4)
    assert not figures["section"].notes


def test_a_robot_without_collision_keeps_its_mass_and_centre_of_mass(tmp_path):
    path = tmp_path / "ghost.urdf"
    path.write_text(robots.without_collisions(robots.box_on_wheels()))
    figures = specs_of(path)
    assert figures["body.mass"].value == pytest.approx(MASS)
    assert figures["body.com"].value == pytest.approx(COM, abs=1e-9)
    assert "(URDF)" in figures["body.com"].source
    for key in ("body.footprint", "body.clearance", "wheels.radius", "body.com_height"):
        assert figures[key].value is None and "MuJoCo" in figures[key].source
    assert not any(k.startswith("loads.") for k in figures)
    assert figures["section"].notes == [
        "not modelled in MuJoCo: no link has <collision> geometry: nothing can rest on the "
        "floor, the robot would fall through it"]


def test_an_inertia_mujoco_refuses_is_a_note_unless_mended(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = Path("refused.urdf")
    good = box_inertia(BODY_MASS, *BODY)
    path.write_text(robots.box_on_wheels().replace(good, re.sub(r'ixx="[^"]*"', 'ixx="9"', good)))
    refused = specs_of(path)
    notes = refused["section"].notes
    assert notes[0].startswith("E310 at refused.urdf:") and "base_link" in notes[0]
    assert notes[-1] == ("not modelled in MuJoCo: MuJoCo refuses 1 link (E305/E310 above); "
                         "--fix-inertia makes it physical")
    assert refused["body.mass"].value == pytest.approx(MASS)
    assert refused["body.footprint"].value is None
    mended = specs_of(path, fix_inertia=True)
    assert len(mended["body.footprint"].value) == 8
    assert mended["section"].notes[0].startswith("--fix-inertia: link base_link")


def test_hull_and_radii():
    square = [(1, 1), (-1, 1), (-1, -1), (1, -1), (0, 0), (0.5, 1), (1, 0)]
    assert hull(square) == [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    assert radii(hull(square)) == pytest.approx((math.sqrt(2), 1))
    # the floor frame's origin outside the outline: no inscribed circle about it
    assert radii(hull([(1, 1), (2, 1), (2, 2), (1, 2)])) == pytest.approx((math.sqrt(8), 0))
    assert hull([(0, 0), (1, 1), (2, 2)]) == [(0, 0), (2, 2)]  # collinear: its two ends


def test_statics_tells_one_two_and_three_supports_and_no_more():
    one, how = by_statics({"a": (0.3, 0.1)}, (0, 0), 10.0)
    assert one == {"a": 10.0} and how.startswith("statics: one support")
    two, how = by_statics({"rear": (-0.1, 0), "front": (0.3, 0)}, (0.0, 0.0), 8.0)
    assert two == pytest.approx({"rear": 6.0, "front": 2.0}) and "two supports" in how
    three, _ = by_statics({"l": (0, 0.1), "r": (0, -0.1), "c": (-0.2, 0)}, (-0.05, 0), 4.0)
    assert three == pytest.approx({"l": 1.5, "r": 1.5, "c": 1.0})
    # what statics cannot tell is MuJoCo's to measure, and the source says why
    assert by_statics({"l": (0, 0.1), "r": (0, -0.1), "c": (0.2, 0)}, (-0.05, 0), 4.0) == \
        (None, "the centre of mass is outside its supports")
    assert by_statics({"a": (0, 0), "b": (1, 0), "c": (2, 0)}, (1, 0), 1.0) == \
        (None, "3 supports in a line: statically indeterminate")
    four = {name: (x, y) for name, x, y in (("a", 1, 1), ("b", 1, -1), ("c", -1, 1),
                                            ("d", -1, -1))}
    assert by_statics(four, (0, 0), 1.0) == (None, "4 supports: statically indeterminate")


def test_a_bicycle_stands_on_two_supports_by_statics(tmp_path):
    path = tmp_path / "bicycle.urdf"
    path.write_text(bicycle())
    figures = specs_of(path)
    loads = [f for k, f in figures.items() if k.startswith("loads.")]
    assert len(loads) == 2 and all(f.source.startswith("statics: two supports") for f in loads)
    assert sum(f.value for f in loads) == pytest.approx(figures["body.mass"].value * G)
    assert figures["wheels.track"].value is None
