"""The xacro sources keep the description's rules: macro files say what they are and name
their parameters, every number lives once in config.xacro with its unit and source, derived
values are expressions, and config.xacro refuses numbers that cannot fit together."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from lxml import etree

from tests.description.conftest import URDF

XACRO_NS = "http://www.ros.org/wiki/xacro"
PROPERTY = f"{{{XACRO_NS}}}property"
MACRO = f"{{{XACRO_NS}}}macro"
# The tutorial's hand-written steps are the seed's, kept as they are; the rules are for the car.
SOURCES = sorted(p for p in URDF.rglob("*.xacro") if "tutorial" not in p.relative_to(URDF).parts)
# The comment grammar is mcar's own (`mcar config` reads it): one definition.
from mobile_car.config.spec import COMMENT_RE as CONFIG_COMMENT  # noqa: E402

DECIMAL = re.compile(r"(?<![\w.])\d*\.\d+|\d+(?:\.\d*)?[eE][-+]?\d+")


def parse(path: Path) -> etree._ElementTree:
    return etree.parse(str(path), etree.XMLParser(remove_blank_text=False))


def is_macro_file(tree: etree._ElementTree) -> bool:
    return tree.getroot().get("name") is None


def header(tree: etree._ElementTree) -> str:
    comments = [n.text for n in tree.getroot().itersiblings(preceding=True)
                if isinstance(n, etree._Comment)]
    return "\n".join(reversed(comments))


def macro_files():
    return [p for p in SOURCES if is_macro_file(parse(p))]


@pytest.mark.parametrize("path", macro_files(), ids=lambda p: p.relative_to(URDF).as_posix())
def test_macro_file_header_names_it_and_its_parameters(path):
    tree = parse(path)
    text = header(tree)
    assert "NOT a URDF" in text, f"{path.name}: the header must say it is not a URDF"
    for macro in tree.getroot().iter(MACRO):
        assert re.search(rf"\b{macro.get('name')}\b", text), macro.get("name")
        for param in macro.get("params").split():
            name = re.split(r":?=", param.lstrip("*"))[0]
            assert re.search(rf"\b{name}\b", text), f"{macro.get('name')}: {name} undocumented"


def test_robot_files_and_macro_files_are_told_apart_by_name():
    for path in SOURCES:
        robot_file = path.name.startswith("test_") or "steps" in path.relative_to(URDF).parts \
            or path.name == "mobile_robot.xacro"
        assert is_macro_file(parse(path)) != robot_file, path


def config_properties():
    root = parse(URDF / "config.xacro").getroot()
    return [(p, p.getnext()) for p in root.iter(PROPERTY)]


def test_every_config_property_states_unit_and_source():
    properties = config_properties()
    assert len(properties) > 40
    for prop, comment in properties:
        name, value = prop.get("name"), prop.get("value")
        assert isinstance(comment, etree._Comment), f"{name}: no comment on its line"
        assert comment.sourceline == prop.sourceline, f"{name}: comment not on its line"
        match = CONFIG_COMMENT.match(comment.text)
        assert match, f"{name}: comment {comment.text!r} is not 'UNIT LO..HI; SOURCE: note'"
        if match["source"] == "derived":
            assert value.startswith("${"), f"{name}: derived but typed in"
        else:
            float(value)  # a measured or chosen number is a plain literal


def test_config_has_no_blank_lines_that_would_leak_comments():
    text = (URDF / "config.xacro").read_text()
    body = text[text.index("<robot xmlns"):]
    assert "\n\n" not in body


def test_numbers_live_only_in_config():
    """Outside config.xacro no decimal is typed in (define.xacro's palette colours aside):
    a number written twice is a number that will one day disagree with itself."""
    offenders = []
    for path in SOURCES:
        if path.name == "config.xacro":
            continue
        tree = parse(path)
        for element in tree.getroot().iter(etree.Element):
            values = [v for k, v in element.attrib.items()
                      if not (path.name == "define.xacro" and k == "rgba")]
            values.append(element.text or "")
            for value in values:
                offenders += [(path.name, element.sourceline, n) for n in DECIMAL.findall(value)]
    assert offenders == []


def test_top_level_properties_are_defined_once_and_pi_is_xacros():
    seen: dict[str, str] = {}
    for path in SOURCES:
        root = parse(path).getroot()
        for prop in root.findall(PROPERTY):
            name = prop.get("name")
            assert name not in seen, f"{name} defined in {seen.get(name)} and {path.name}"
            seen[name] = path.name
        for prop in root.iter(PROPERTY):
            assert prop.get("name") != "pi", f"{path.name} redefines xacro's pi"
    assert set(seen.values()) <= {"config.xacro", "define.xacro"}


def test_config_total_mass_is_the_built_robots(complete_robot, tmp_path):
    from mobile_car.expand.xacro_build import build_file
    from mobile_car.packages.search import PackageSearch

    probe = tmp_path / "mass.urdf.xacro"
    probe.write_text(f'<robot name="mass" xmlns:xacro="{XACRO_NS}">'
                     f'<xacro:include filename="{URDF / "config.xacro"}"/>'
                     f'<mass value="${{robot_mass}}"/></robot>')
    # The checkout's package named to the search: the sandbox reads below package roots.
    search = PackageSearch(package_paths=[URDF.parent])
    stated = float(etree.fromstring(build_file(probe, search=search).xml.encode())
                   .find("mass").get("value"))
    built = sum(link.inertial.mass for link in complete_robot.robot.links if link.inertial)
    assert stated == pytest.approx(built, rel=1e-12)
    # the header states it too, to the gram
    assert f"{stated:.2f} kg" in header(parse(URDF / "config.xacro"))


@pytest.mark.parametrize("name, value, complaint", [
    ("caster_unit_height", "0.060", "the castor cannot touch the ground: caster_unit_height "
                                    "(0.06 m) must not exceed the plate's height"),
    ("track_width", "0.140", "the wheels overlap the chassis: their inner face at y = "
                             "track_width / 2 - wheel_width / 2 (0.057 m)"),
    ("plate_width", "0.120", "the motor brackets stick out of the plate: their outer face at "
                             "y = 0.0645 m"),
    ("bracket_axle_drop", "0.010", "the gearbox hits the plate: bracket_axle_drop (0.01 m) "
                                   "must exceed motor_gearbox_radius (0.0125 m)"),
    ("motor_can_length", "0.080", "the two motors overlap at the centre line: "
                                  "motor_body_length (0.105 m)"),
    ("wheel_radius", "0.010", "the wheels do not reach the ground below the motors"),
    ("laser_width", "0.150", "the laser is wider than the top plate"),
])
def test_config_refuses_numbers_that_cannot_fit(package_copy, run_mcar, name, value, complaint):
    config = package_copy / "urdf" / "config.xacro"
    text, count = re.subn(rf'(name="{name}" value=")[^"]*"', rf'\g<1>{value}"', config.read_text())
    assert count == 1
    config.write_text(text)
    done = run_mcar("build", package_copy / "urdf" / "mobile_robot.xacro", cwd=package_copy)
    assert done.returncode == 1
    assert done.stdout == ""
    first = done.stderr.splitlines()[0]
    assert first.startswith("urdf/config.xacro:"), first
    assert complaint in first


def test_reflect_typo_is_a_build_error(package_copy, run_mcar):
    robot = package_copy / "urdf" / "mobile_robot.xacro"
    robot.write_text(robot.read_text().replace(
        '<xacro:wheel name="right" reflect="-1"', '<xacro:wheel name="right" reflect="1-"', 1))
    done = run_mcar("build", robot, cwd=package_copy)
    assert done.returncode == 1
    assert "wheel: reflect must be 1 (left) or -1 (right), not '1-'" in done.stderr
    assert "Traceback" not in done.stderr
