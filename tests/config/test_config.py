"""Dimension config: config.xacro read by mcar, overridden by --set and --config, validated."""

from __future__ import annotations

import json
import re
import shutil

import pytest
import yaml
from conftest import REPO
from lxml import etree

ROBOT = REPO / "urdf" / "mobile_robot.xacro"


def links(xml_text: str) -> dict[str, etree._Element]:
    robot = etree.fromstring(xml_text.encode())
    return {link.get("name"): link for link in robot.iter("link")}


def wheel_radius_in(xml_text: str) -> float:
    cylinder = links(xml_text)["wheel_left_link"].find("collision/geometry/cylinder")
    return float(cylinder.get("radius"))


def joint_z(xml_text: str, joint: str) -> float:
    robot = etree.fromstring(xml_text.encode())
    element = next(j for j in robot.iter("joint") if j.get("name") == joint)
    return float(element.find("origin").get("xyz").split()[2])


def test_config_lists_every_dimension_with_unit_source_and_location(run_mcar):
    result = run_mcar("config", "--format", "json")
    assert result.returncode == 0, result.stderr
    table = json.loads(result.stdout)
    text = (REPO / "urdf" / "config.xacro").read_text().splitlines()
    assert "wheel_radius" in table["dimensions"] and "wheel_y" in table["derived"]
    for section in ("dimensions", "derived"):
        for name, item in table[section].items():
            path, _, line = item["defined"].rpartition(":")
            assert f'name="{name}"' in text[int(line) - 1], name
            assert item["unit"] and item["source"] and item["meaning"]
    radius = table["dimensions"]["wheel_radius"]
    assert (radius["value"], radius["unit"], radius["source"]) == (0.0325, "m", "listing")
    assert table["derived"]["wheel_y"]["expression"] == "track_width / 2"
    assert table["derived"]["wheel_y"]["value"] == table["dimensions"]["track_width"]["value"] / 2


def test_config_text_table_marks_overrides(run_mcar):
    result = run_mcar("config", "--set", "wheel_radius=40mm")
    assert result.returncode == 0, result.stderr
    rows = {line.split()[0]: line for line in result.stdout.splitlines() if line.strip()}
    assert rows["*wheel_radius"].split()[1:3] == ["0.04", "m"]
    # The meaning was written for the default: "65 mm diameter wheel" says so, in words.
    assert rows["*wheel_radius"].endswith(
        "65 mm diameter wheel (this describes the default, 0.0325 m)")
    assert "config.xacro:" in rows["*wheel_radius"]
    assert rows["axle_height"].split()[1] == "0.04"  # derived follows the override
    assert [line for line in result.stdout.splitlines() if line.startswith("*")] == \
        [rows["*wheel_radius"],
         "* overridden by --set or --config: its description is of the default value"]
    assert result.stdout.rstrip().endswith("Defined in urdf/config.xacro")


def test_config_text_table_without_overrides_has_no_legend(run_mcar):
    result = run_mcar("config")
    assert result.returncode == 0, result.stderr
    assert not [line for line in result.stdout.splitlines() if line.startswith("*")]
    assert "describes the default" not in result.stdout
    assert result.stdout.rstrip().splitlines()[-1] == "Defined in urdf/config.xacro"


def test_config_text_table_keeps_its_columns_apart(run_mcar):
    """Every row has its seven cells two or more spaces apart, the same as --format json
    gives them (a long range once ran into the file name: 10rpm..20000rpmconfig.xacro:67)."""
    text = run_mcar("config").stdout
    document = json.loads(run_mcar("config", "--format", "json").stdout)
    rows = [line for line in text.splitlines() if line.startswith(" ")]
    assert len(rows) == len(document["dimensions"]) + len(document["derived"])
    starts = None
    for row in rows:
        name = row.split()[0]
        entry = document["dimensions"].get(name) or document["derived"][name]
        cells = re.split(r"\s{2,}", row.strip(), maxsplit=5)
        expected = [name, f"{entry['value']:.6g}", entry["unit"], entry["source"]]
        if entry.get("range_text"):
            expected.append(entry["range_text"])
        assert cells[:len(expected)] == expected, row
        where = f"config.xacro:{entry['defined'].rpartition(':')[2]}"
        assert f"  {where}  " in row
        column = row.index(f"  {where}  ")
        if name in document["dimensions"]:  # one section: one column for every row
            starts = column if starts is None else starts
            assert column == starts, row


def test_json_output_round_trips_into_config(run_mcar, tmp_path):
    first = run_mcar("config", "--format", "json", "--set", "wheel_radius=0.04")
    saved = tmp_path / "car.json"
    saved.write_text(first.stdout)
    second = run_mcar("config", "--format", "json", "--config", saved)
    assert second.returncode == 0, second.stderr
    assert json.loads(second.stdout) == json.loads(first.stdout)
    yaml_out = run_mcar("config", "--format", "yaml", "--config", saved)
    assert yaml.safe_load(yaml_out.stdout) == json.loads(first.stdout)


def test_set_changes_the_built_urdf_and_rederives_the_castor(run_mcar):
    default = run_mcar("build", ROBOT).stdout
    bigger = run_mcar("build", ROBOT, "--set", "wheel_radius=0.04")
    assert bigger.returncode == 0, bigger.stderr
    assert wheel_radius_in(default) == 0.0325
    assert wheel_radius_in(bigger.stdout) == 0.04
    # base_link rises with the axle; the castor ball centre stays one ball radius up
    assert joint_z(bigger.stdout, "base_joint") == pytest.approx(0.04)
    ball = 0.0075
    for text, axle in ((default, 0.0325), (bigger.stdout, 0.04)):
        assert joint_z(text, "caster_joint") + axle == pytest.approx(ball)


def test_config_file_and_set_combine_set_wins(run_mcar, tmp_path):
    partial = tmp_path / "my_car.yaml"
    partial.write_text("wheel_radius: 45mm\ntrack_width: 0.17\nplate_width: 0.135\n")
    result = run_mcar("build", ROBOT, "--config", partial, "--set", "wheel_radius=0.05")
    assert result.returncode == 0, result.stderr
    assert wheel_radius_in(result.stdout) == 0.05
    wheel = next(j for j in etree.fromstring(result.stdout.encode()).iter("joint")
                 if j.get("name") == "wheel_left_joint")
    assert float(wheel.find("origin").get("xyz").split()[1]) == pytest.approx(0.085)


def test_overrides_apply_to_every_file_of_the_package(run_mcar, tmp_path):
    result = run_mcar("build", "--set", "wheel_radius=0.04", "-o", tmp_path / "out", "-q")
    assert result.returncode == 0, result.stderr
    assert wheel_radius_in((tmp_path / "out" / "wheel" / "test_wheel.urdf").read_text()) == 0.04
    assert wheel_radius_in((tmp_path / "out" / "mobile_robot.urdf").read_text()) == 0.04


@pytest.mark.parametrize("args, message", [
    (["--set", "wheel_radus=0.04"],
     "--set wheel_radus=0.04: unknown dimension 'wheel_radus' (did you mean 'wheel_radius'?)"),
    (["--set", "wheel_radius=-0.01"], "wheel_radius = -0.01 m is outside 5 mm..0.5 m"),
    (["--set", "wheel_mass=0"], "wheel_mass = 0 kg is outside 1 g..5 kg"),
    (["--set", "wheel_hub_clearance=-1mm"],
     "wheel_hub_clearance = -1mm (-0.001 m) is outside 0 m..20 mm"),
    (["--set", "wheel_radius=3kg"], "wheel_radius: '3kg' has the wrong unit: expected m, got kg"),
    (["--set", "wheel_radius=big"], "wheel_radius: 'big' is neither a number nor"),
    (["--set", "wheel_radius"], "--set wheel_radius: expected NAME=VALUE"),
    (["--set", "wheel_y=0.1"], "wheel_y is derived (track_width / 2), not set"),
    (["--set", "motor_can_length=0.02"], "motor_can_length is baked into a mesh"),
    (["--set", "wheel_radius=0.01"],
     "the wheels do not reach the ground below the motors: wheel_radius (0.01 m) must exceed "
     "motor_radius"),
    (["--set", "caster_unit_height=0.06"],
     "the castor cannot touch the ground: caster_unit_height (0.06 m) must not exceed"),
    (["--set", "laser_width=0.2"],
     "the laser is wider than the top plate: laser_length x laser_width (0.0968 x 0.2 m)"),
    (["--set", "track_width=0.14"],
     "the wheels overlap the chassis: their inner face at y = track_width / 2 - wheel_width / 2"
     " (0.057 m) must exceed plate_width / 2 (0.065 m)"),
    (["--set", "plate_width=0.12"], "the motor brackets stick out of the plate"),
    (["--set", "bracket_axle_drop=0.01"],
     "the gearbox hits the plate: bracket_axle_drop (0.01 m) must exceed motor_gearbox_radius"),
])
def test_bad_overrides_exit_2_naming_the_dimension(run_mcar, tmp_path, args, message):
    out = tmp_path / "robot.urdf"
    result = run_mcar("build", ROBOT, "-o", out, *args)
    assert result.returncode == 2
    assert message in result.stderr
    assert len(result.stderr.splitlines()) == 1 and "Traceback" not in result.stderr
    assert not out.exists(), "nothing is built when the numbers are refused"


@pytest.mark.parametrize("value, hint", [
    ("0.6", ""),  # 0.6cm would fit, but 0.6 m is just too big: no guessed unit
    ("32.5", "; did you mean 32.5mm?"),  # a thousand times off: a unit slip
])
def test_a_unit_is_suggested_only_for_a_slip(run_mcar, tmp_path, value, hint):
    result = run_mcar("build", ROBOT, "-o", tmp_path / "robot.urdf", "--set",
                      f"wheel_radius={value}")
    assert result.returncode == 2
    assert result.stderr == (f"mcar: error: --set wheel_radius={value}: wheel_radius = "
                             f"{value} m is outside 5 mm..0.5 m{hint}\n")


@pytest.mark.parametrize("content, message", [
    ("wheel_radus: 0.04\n", "my.yaml:1: unknown dimension 'wheel_radus' (did you mean"),
    ("# a comment\nwheel_radius: [1, 2]\n", "my.yaml:2: wheel_radius: expected a number"),
    ("- 1\n- 2\n", "my.yaml: error: expected a mapping of dimension names to values"),
    ("wheel_radius: : :\n", "my.yaml:1: error: not valid YAML"),
])
def test_bad_config_files_exit_2_naming_file_and_line(run_mcar, tmp_path, content, message):
    (tmp_path / "my.yaml").write_text(content)
    result = run_mcar("config", "--bundled", "--config", "my.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert message in result.stderr


def test_missing_config_file_is_an_io_error(run_mcar, tmp_path):
    result = run_mcar("build", ROBOT, "--config", tmp_path / "nope.yaml")
    assert result.returncode == 2
    assert "nope.yaml: error: no such file" in result.stderr


def test_overrides_on_a_file_without_config_are_refused(run_mcar):
    result = run_mcar("build", REPO / "urdf" / "tutorial" / "04_xacro.xacro",
                      "--set", "wheel_radius=0.04")
    assert result.returncode == 2
    assert "does not include" in result.stderr


def test_plain_xacro_users_can_pass_an_overrides_file(run_mcar, tmp_path):
    overrides = tmp_path / "ov.xacro"
    overrides.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                         '<xacro:property name="wheel_radius" value="0.045"/></robot>')
    result = run_mcar("build", ROBOT, f"config:={overrides}")
    assert result.returncode == 0, result.stderr
    assert wheel_radius_in(result.stdout) == 0.045


def test_check_takes_the_same_overrides(run_mcar):
    ok = run_mcar("check", "--strict", ROBOT, "--set", "wheel_radius=0.04")
    assert ok.returncode == 0, ok.stderr
    assert "root Link: base_footprint has 1 child(ren)" in ok.stdout
    bad = run_mcar("check", ROBOT, "--set", "wheel_radus=0.04")
    assert bad.returncode == 2
    assert "did you mean 'wheel_radius'?" in bad.stderr
    plain = run_mcar("check", REPO / "urdf" / "tutorial" / "01_skeleton.urdf",
                     "--set", "wheel_radius=0.04")
    assert plain.returncode == 2
    assert "apply to .xacro inputs" in plain.stderr


def test_a_dimension_whose_default_is_an_expression_is_shown_not_a_crash(run_mcar, tmp_path):
    """config.xacro may give a dimension with a range an expression for its default: the
    table shows it, and an override says the description is of that expression (it ended
    in 'internal error: ValueError: could not convert string to float')."""
    for name in ("urdf", "meshes", "package.xml"):
        copy = shutil.copytree if (REPO / name).is_dir() else shutil.copy
        copy(REPO / name, tmp_path / name)
    config = tmp_path / "urdf" / "config.xacro"
    text = config.read_text()
    assert '<xacro:property name="plate_length" value="0.200"/>' in text
    config.write_text(text.replace('<xacro:property name="plate_length" value="0.200"/>',
                                   '<xacro:property name="plate_length" value="${0.1 * 2}"/>'))
    plain = run_mcar("config", cwd=tmp_path)
    assert plain.returncode == 0, plain.stderr
    row = next(line for line in plain.stdout.splitlines() if line.startswith(" plate_length"))
    assert row.split()[1:3] == ["0.2", "m"]
    changed = run_mcar("config", "--set", "plate_length=25cm", cwd=tmp_path)
    assert changed.returncode == 0, changed.stderr
    row = next(line for line in changed.stdout.splitlines() if line.startswith("*plate_length"))
    assert row.split()[1:3] == ["0.25", "m"]
    assert row.endswith("(this describes the default, ${0.1 * 2})")
