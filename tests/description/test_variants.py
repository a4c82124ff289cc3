"""Every accepted set of dimensions still makes a car that stands: the shipped variants,
and random valid overrides (hypothesis). Checked on the BUILT URDF by forward kinematics:
both wheels and the castor touch z = 0 within 1 mm, nothing else is lower, plates level."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import REPO, mcar_process, run_check_urdf
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

VARIANTS = sorted((REPO / "urdf" / "variants").glob("*.yaml"))
CONTACT_LINKS = {"wheel_left_link", "wheel_right_link", "caster_link"}
GROUND_TOLERANCE = 1e-3


def assert_stands_level(urdf, posed) -> None:
    collisions = posed(urdf, "collision")
    lowest = {}
    for element in collisions:
        lowest[element.link] = min(lowest.get(element.link, np.inf), element.lowest())
    for link in CONTACT_LINKS:
        assert abs(lowest[link]) <= GROUND_TOLERANCE, (link, lowest[link])
    others = {link: z for link, z in lowest.items() if link not in CONTACT_LINKS}
    assert min(others.values()) > 0, others
    for plate in ("body_link", "top_plate_link"):
        (element,) = [e for e in collisions if e.link == plate]
        assert np.allclose(element.transform[:3, 2], [0, 0, 1], atol=1e-12), plate


def test_there_are_a_smaller_and_a_larger_variant():
    assert [v.stem for v in VARIANTS] == ["large", "small"]


@pytest.mark.parametrize("variant", VARIANTS, ids=[v.stem for v in VARIANTS])
def test_variant_builds_checks_and_stands(variant, mcar_bin, tmp_path, check_urdf, load_urdf,
                                          posed):
    out = tmp_path / "build"
    done = mcar_process("build", REPO, "--config", variant, "-o", out, "-q", timeout=120)
    assert done.returncode == 0, done.stderr
    robot = out / "mobile_robot.urdf"
    strict = mcar_process("check", "--strict", "-q", "--config", variant,
                          *sorted(REPO.glob("urdf/**/*.urdf.xacro")),
                          REPO / "urdf" / "mobile_robot.xacro", timeout=120)
    assert (strict.returncode, strict.stderr) == (0, "")
    checked = run_check_urdf(check_urdf, robot)
    assert checked.returncode == 0, checked.stderr
    assert "root Link: base_footprint has 1 child(ren)" in checked.stdout
    urdf = load_urdf(robot)
    assert_stands_level(urdf, posed)
    wheel = urdf.link_map["wheel_left_link"].collisions[0].geometry.cylinder
    done = mcar_process("config", "--format", "json", "--config", variant)
    assert done.returncode == 0, done.stderr
    config = done.stdout
    import json

    assert wheel.radius == json.loads(config)["dimensions"]["wheel_radius"]["value"]


@st.composite
def dimensions(draw):
    """Dimensions of kit-car scale; not all fit together (the validator sorts them out)."""
    plate_width = draw(st.floats(0.115, 0.20))
    wheel_width = draw(st.floats(0.015, 0.04))
    # wheels just outside the plate, brackets just inside it (see config.xacro's checks)
    wheel_y = plate_width / 2 + wheel_width / 2 + draw(st.floats(0.0005, 0.0055))
    wheel_radius = draw(st.floats(0.015, 0.07))
    drop = draw(st.floats(0.013, 0.03))
    return {
        "wheel_radius": wheel_radius, "wheel_width": wheel_width, "plate_width": plate_width,
        "track_width": 2 * wheel_y, "bracket_axle_drop": drop,
        "plate_length": draw(st.floats(0.14, 0.30)), "chassis_x": draw(st.floats(-0.02, 0.08)),
        "standoff_length": draw(st.floats(0.015, 0.06)),
        "plate_thickness": draw(st.floats(0.002, 0.006)),
        "caster_ball_radius": draw(st.floats(0.004, 0.013)),
        "caster_unit_height": draw(st.floats(0.01, wheel_radius + drop)),
    }


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow],
          derandomize=True)
@given(dims=dimensions())
def test_random_valid_overrides_stand_level(dims, tmp_path_factory, load_urdf, posed):
    from mobile_car.config.overrides import evaluate, override_mappings
    from mobile_car.config.spec import config_file, load_spec
    from mobile_car.errors import UsageError
    from mobile_car.expand.xacro_build import build_file
    from mobile_car.packages.search import PackageSearch

    search = PackageSearch(origin=REPO / "urdf" / "mobile_robot.xacro")
    spec = load_spec(config_file(search))
    with override_mappings(dims) as mappings:
        try:
            evaluate(spec, mappings, search)
        except UsageError:
            assume(False)  # the validator refused them: nothing to build, nothing to check
        xml = build_file(REPO / "urdf" / "mobile_robot.xacro", mappings, search).xml
    path = tmp_path_factory.mktemp("random") / "mobile_robot.urdf"
    path.write_text(xml)
    urdf = load_urdf(path)
    assert_stands_level(urdf, posed)
    assert urdf.link_map["wheel_left_link"].collisions[0].geometry.cylinder.radius == \
        pytest.approx(dims["wheel_radius"])
