"""MuJoCo's proofs of the statics: tilted towards forward, left, backward and right on
braked wheels, a robot slides or tips within 1° of the computed angle; driven up a slope
1° under its climb angle it climbs, 1° over it does not. On boxes whose figures are known
in closed form (test_statics.py checks them), and on TurtleBot3 burger and Husky from
the shared real-robots folder when it is there."""

from __future__ import annotations

import math
import time

import pytest
from sim.robot_makers import castor_swivels
from sim.test_sim_real_robots import FOLDER, needs_folder
from specs.statics_robots import box_on_wheels, checked_and_sim

from mobile_car.specs.statics import Statics, statics_section

TILTED = ("statics.tip.forward", "statics.tip.left", "statics.tip.backward",
          "statics.tip.right", "statics.slide", "statics.stand")
ROBOTS = {
    # slides at atan(0.6) = 31.0° in every direction before it tips (54°)
    "slides": box_on_wheels(lift=0.1, mu=0.6, effort=2),
    # tips over each axle and side at 20.7° (h 0.53 m) long before it slides (50°)
    "tips": box_on_wheels(lift=0.5, mu=1.2, effort=2, body=(0.3, 0.1, 0.1)),
    # narrow and nose-heavy: tips sideways at 18.3°, forward at 32.1°, slides backward
    # at 45°; its motors (0.3 N·m) climb 14.2°, the limit of its motors
    "narrow": box_on_wheels(lift=0.2, track=0.16, body=(0.3, 0.08, 0.1), com_x=0.05,
                            effort=0.3),
    # μ 0.5: its grip, not its motors (3 N·m), limits its climb to 26.6°
    "slippery": box_on_wheels(lift=0.1, mu=0.5, effort=3, velocity=10),
}


def _proven(path, package_paths=()):
    checked, sim = checked_and_sim(path, package_paths)
    started = time.perf_counter()
    section = statics_section(checked, sim, {})
    return section, {f.key: f for f in section.figures}, time.perf_counter() - started


@pytest.fixture(scope="module")
def proven(tmp_path_factory):
    folder = tmp_path_factory.mktemp("proofs")
    out = {}
    for name, text in ROBOTS.items():
        path = folder / f"{name}.urdf"
        path.write_text(text)
        out[name] = _proven(path)
    return out


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_tilting_slides_or_tips_within_1_degree_of_the_figures(proven, robot):
    section, fig, _seconds = proven[robot]
    for key in TILTED:
        proof = fig[key].proof
        assert proof is not None and proof.agrees, (key, fig[key].value, proof)
        if proof.measured is not None:
            assert abs(proof.measured - fig[key].value) <= 1.0
    assert not [d for d in section.diagnostics if d.rule == "W506"]


def test_each_tilt_measures_the_event_the_figures_expect(proven):
    _section, slides, _ = proven["slides"]
    assert "it slides at" in slides["statics.slide"].proof.detail
    assert slides["statics.tip.left"].proof.measured is None  # it slid before it could tip
    assert "before it could tip (slide computed 30.96°)" in slides["statics.tip.left"].proof.detail
    _section, tips, _ = proven["tips"]
    for key in TILTED[:4]:
        assert "it tips at" in tips[key].proof.detail
        assert tips[key].proof.measured == pytest.approx(tips[key].value, abs=1.0)
    tipping, _, _ = proven["tips"]  # its motors climb 50°: the climb cannot be shown
    assert tips["statics.climb"].proof is None
    assert "statics.climb not proven: the robot tips over backward at 20.7° (W502), before " \
           "the 50.2° its motors climb" in tipping.notes
    _section, narrow, _ = proven["narrow"]
    assert narrow["statics.tip.left"].value == pytest.approx(18.29, abs=0.01)
    assert narrow["statics.stand"].proof.measured == pytest.approx(18.29, abs=1.0)


@pytest.mark.parametrize("robot, limit", [("narrow", "the motors"), ("slippery", "traction")])
def test_it_climbs_1_degree_under_its_climb_angle_and_not_1_over(proven, robot, limit):
    _section, fig, _ = proven[robot]
    climb = fig["statics.climb"]
    assert climb.source.startswith(f"limited by {limit}:")
    assert climb.proof.agrees, climb.proof
    under, over = climb.proof.detail.split("; ")
    if limit == "traction":  # 1° under the slope its wheels reach at the share of their
        # grip a lone one climbs with (docs/specs.md, "Grip-bound climb"): 0.978, 26.0°
        assert climb.proof.tolerance.startswith("climbs 1° under the 26.0° its wheels "
                                                "reach at the 0.97"), climb.proof.tolerance
        assert climb.proof.measured == pytest.approx(25.04, abs=0.05)
    else:
        assert climb.proof.measured == pytest.approx(climb.value - 1.0)
    assert under.startswith(f"at {climb.proof.measured:.1f}° it went up at ")
    assert over.startswith(f"at {climb.value + 1:.1f}° -")  # it went down


def test_no_proof_without_mujoco_runs(tmp_path):
    path = tmp_path / "box.urdf"
    path.write_text(ROBOTS["slides"])
    checked, sim = checked_and_sim(path)
    section = statics_section(checked, sim, {"proof": False})
    assert all(f.proof is None for f in section.figures)


@pytest.mark.parametrize("azimuth", [0, 90])
def test_on_swivel_castor_wheels_it_slides_where_its_braked_wheels_let_go(tmp_path, azimuth):
    """MiR's shape (castor_swivels): the castor wheels roll every way and hold nothing,
    so the two braked wheels carry the slope's whole pull. MuJoCo's soft contacts give a
    contact that slips more normal force the faster it slips (the elliptic cone's middle
    zone), and its friction creeps: the robot crept down at 0.5 mm/s with its wheels'
    loads swollen to hold it, under the 5 mm/s a slide was taken at, and "held" 2-4°
    past the figure (left: neither slid nor tipped by 38.8°, computed 34.8°). With
    MuJoCo's noslip pass nothing creeps while the friction holds, and the slip is
    measured where the wheels touch."""
    from lxml import etree

    from mobile_car.sim.model import gazebo_friction
    from mobile_car.specs.proof_tilt import tilt
    from mobile_car.specs.support import stance

    path = tmp_path / "swivels.urdf"
    path.write_text(castor_swivels())
    checked, sim = checked_and_sim(path)
    found = stance(sim, gazebo_friction(etree.fromstring(checked.loaded.urdf)), None)
    statics = Statics(found, sim)
    slide, tip = math.degrees(statics.slide(azimuth)), math.degrees(statics.tip(azimuth))
    assert slide < tip - 20
    run = tilt(sim, found, azimuth, slide)
    assert run.event == "slides", run
    assert run.angle == pytest.approx(slide, abs=1.0)


@pytest.fixture(scope="module")
def real(tmp_path_factory):
    """TurtleBot3 burger (its .urdf expanded as xacro) and Husky, proven once."""
    return {"burger": _proven(FOLDER / "turtlebot3_description" / "urdf" /
                              "turtlebot3_burger.urdf", [FOLDER]),
            "husky": _proven(FOLDER / "husky_description" / "urdf" / "husky.urdf.xacro",
                             [FOLDER])}


@needs_folder
@pytest.mark.parametrize("robot", ["burger", "husky"])
def test_real_robots_tilt_and_climb_as_computed(real, robot):
    """Forward, left, backward, right, the worst direction and the climb within 1°."""
    section, fig, _seconds = real[robot]
    for key in (*TILTED, "statics.climb"):
        assert fig[key].proof is not None and fig[key].proof.agrees, (key, fig[key].proof)
    slide = fig["statics.slide"]
    assert abs(slide.proof.measured - slide.value) <= 1.0, slide.proof
    assert not [d for d in section.diagnostics if d.rule == "W506"]


@needs_folder
def test_burger_tips_forward_at_7_degrees_on_a_slope_its_motors_climb(real):
    """Its centre of mass 4 mm behind its axle, 31 mm up, no castor ahead: W502."""
    section, fig, _ = real["burger"]
    assert fig["statics.tip.forward"].value == pytest.approx(7.43, abs=0.01)
    assert "tips at" in fig["statics.tip.forward"].proof.detail
    assert fig["statics.climb"].value == pytest.approx(9.94, abs=0.01)  # sim's default motor
    (w502,) = [d for d in section.diagnostics if d.rule == "W502"]
    assert w502.text().endswith("its motors climb 9.9° but it tips over forward at 7.4°: "
                                "driving down such a slope it falls [W502]")
