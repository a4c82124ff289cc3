"""``mcar check --gazebo`` and ``mcar build --format sdf`` on the bundled car, and what
both say where the Gazebo helper is not installed."""

from __future__ import annotations

import json
import re

import pytest
from conftest import REPO, line_of
from lxml import etree

CAR = REPO / "urdf" / "mobile_robot.xacro"
GAZEBO_FILE = REPO / "urdf" / "mobile_robot.gazebo.xacro"
CAR_MASS = 0.70564  # kg: docs/diff.md's example
DROPPING = REPO / "tests" / "gazebo" / "cases" / "massless_middle_link.urdf"




@pytest.fixture(scope="module")
def car_sdf(gazebo_helper, tmp_path_factory):
    """The car built to SDF once, by a real mcar process: (the run, the file)."""
    import subprocess

    from conftest import MCAR

    out = tmp_path_factory.mktemp("sdf") / "car.sdf"
    run = subprocess.run([str(MCAR), "build", "--format", "sdf", str(CAR), "-o", str(out)],
                         capture_output=True, text=True, timeout=120,
                         env={"PATH": "/usr/bin:/bin", "MCAR_SDFORMAT": str(gazebo_helper)})
    return run, out


def test_the_sdf_libsdformat_writes_loads_back_as_three_links_of_the_cars_mass(car_sdf,
                                                                               gazebo_helper):
    from mobile_car.gazebo.helper import run_helper

    run, out = car_sdf
    assert run.returncode == 0, run.stderr
    assert run.stderr == ""
    root = etree.parse(str(out)).getroot()
    assert root.tag == "sdf"
    [model] = root.findall("model")
    assert model.get("name") == "mobile_robot"
    assert [link.get("name") for link in model.findall("link")] == \
        ["base_footprint", "wheel_left_link", "wheel_right_link"]
    assert [joint.get("name") for joint in model.findall("joint")] == \
        ["wheel_left_joint", "wheel_right_joint"]
    # the lidar and the drive plugin went with the lumped links, where Gazebo reads them
    assert model.find("link[@name='base_footprint']/sensor").get("type") == "gpu_lidar"
    assert model.find("plugin[@name='gz::sim::systems::DiffDrive']") is not None
    again = run_helper(out.read_bytes(), str(out), helper=gazebo_helper)
    assert again.errors == () and again.warnings == ()
    assert [link.name for link in again.model.links] == \
        ["base_footprint", "wheel_left_link", "wheel_right_link"]
    assert again.model.mass == pytest.approx(CAR_MASS, abs=1e-9)
    footprint = again.model.links[0]
    assert (footprint.collisions, footprint.sensors) == (13, 1)


def test_check_gazebo_on_the_car_reports_lumping_as_notes_at_their_source_lines(cli, gazebo):
    result = cli("check", "--gazebo", CAR)
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert not [line for line in lines if ": error:" in line or ": warning:" in line]
    lumped = [line for line in lines if line.endswith("[N401]")]
    assert len(lumped) == 13  # 16 links, 3 of them Gazebo's
    base = line_of(CAR, '<link name="base_link"')
    laser = line_of(GAZEBO_FILE, 'reference="laser_link"')
    call = line_of(GAZEBO_FILE, 'surface_friction link="caster_link"')
    assert f"urdf/mobile_robot.xacro:{base}: note: link 'base_link' is lumped into " \
           "'base_footprint' by its fixed joint 'base_joint'" in result.stderr
    assert f"urdf/mobile_robot.gazebo.xacro:{laser}: note: <gazebo reference=\"laser_link\">: " \
           "Gazebo lumps link 'laser_link' into 'base_footprint'" in result.stderr
    # a block a macro makes is found where the macro writes it, with the call that named
    # its link (issue 26's exact locations)
    block = line_of(GAZEBO_FILE, '<gazebo reference="${link}">')
    made = [line for line in lines if 'reference="caster_link"' in line]
    assert len(made) == 1 and made[0].startswith(
        f"urdf/mobile_robot.gazebo.xacro:{block}: note: <gazebo reference=\"caster_link\">")
    assert f"(in xacro:surface_friction called at urdf/mobile_robot.gazebo.xacro:{call}," \
        in made[0]
    assert re.search(r"note: Gazebo simulates 3 links: 0\.7056 kg, as in the URDF "
                     r"\(libsdformat \d+\.\d+\.\d+\) \[N403\]", result.stderr)
    assert result.stdout.startswith("robot name is: ")  # check_urdf's tree, as without it


def test_check_gazebo_quiet_prints_problems_only_no_notes(cli, gazebo):
    loud = cli("check", "--gazebo", CAR)
    assert loud.stderr.count(": note: ") > 13  # 13 lumped links, blocks, the mass
    result = cli("check", "-q", "--gazebo", CAR)
    assert result.exit_code == 0
    assert result.stdout == "" and result.stderr == ""
    # problems still show: the dropped links' error and the missing inertial's warning
    dropping = cli("check", "-q", "--gazebo", DROPPING)
    assert dropping.exit_code == 1
    assert "[E150]" in dropping.stderr and "[W206]" in dropping.stderr
    assert ": note: " not in dropping.stderr


def test_check_gazebo_json_and_github(cli, gazebo):
    document = json.loads(cli("check", "--gazebo", "--format", "json", DROPPING).stdout)
    [file] = document["files"]
    view = file["gazebo"]
    assert view["links"] == ["base_footprint"]
    assert view["lumped"] == {"base_link": "base_footprint"}
    assert view["lost"] == {"arm": "arm", "tip": "arm", "tip2": "arm"}
    assert (view["urdf_mass"], view["gazebo_mass"]) == (1.75, 1.0)
    assert document["exit_code"] == 1 and not file["ok"]
    notes = [d for d in file["diagnostics"] if d["severity"] == "note"]
    assert {d["rule"] for d in notes} == {"N401", "N403"}
    github = cli("check", "--gazebo", "--format", "github", DROPPING).stdout.splitlines()
    assert any(line.startswith("::notice file=") and "title=N401 gazebo-lumped" in line
               for line in github)
    assert any(line.startswith("::error file=") and ",line=24," in line
               and "title=E150 gazebo-link-dropped" in line for line in github)


def test_check_without_gazebo_is_unchanged(cli, gazebo):
    result = cli("check", "-q", DROPPING)
    assert result.exit_code == 0
    assert "[W206]" in result.stderr and "[E150]" not in result.stderr
    assert "note:" not in result.stderr


def test_build_sdf_keeps_an_earlier_output_when_libsdformat_cannot_load_the_robot(
        cli, gazebo, tmp_path):
    out = tmp_path / "robot.sdf"
    out.write_text("earlier")
    result = cli("build", "--format", "sdf", REPO / "urdf" / "tutorial" / "01_skeleton.urdf",
                 "-o", out)
    assert result.exit_code == 1
    first = result.stderr.splitlines()[0]
    assert re.search(r"01_skeleton\.urdf: error: libsdformat \d+\.\d+\.\d+ cannot make a "
                     r"Gazebo model of it: A model must have at least one link\.$", first), first
    assert out.read_text() == "earlier"


def test_build_sdf_warns_of_the_links_gazebo_leaves_out(cli, gazebo, tmp_path):
    out = tmp_path / "robot.sdf"
    result = cli("build", "--format", "sdf", DROPPING, "-o", out)
    assert result.exit_code == 0
    assert "warning: Gazebo leaves out 3 links of the URDF (arm, tip, tip2)" in result.stderr
    names = [link.get("name") for link in etree.parse(str(out)).getroot().iter("link")]
    assert names == ["base_footprint"]


def test_build_sdf_of_a_folder_names_files_sdf(cli, gazebo, tmp_path):
    result = cli("build", "--format", "sdf", REPO / "urdf" / "laser", "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    built = [p.relative_to(tmp_path / "out").as_posix() for p in (tmp_path / "out").rglob("*.*")]
    assert sorted(built) == [".mcar-build.json", "laser/test_laser.sdf"]  # and its build record


@pytest.fixture
def no_helper(monkeypatch, tmp_path):
    """A machine without the helper: no MCAR_SDFORMAT, none beside mcar, none on PATH."""
    import mobile_car.gazebo.helper as helper

    monkeypatch.delenv("MCAR_SDFORMAT", raising=False)
    monkeypatch.setattr(helper, "helper_places", lambda: [tmp_path])
    monkeypatch.setenv("PATH", str(tmp_path))


HINT = re.compile(r"^mcar: error: the Gazebo helper mcar-sdformat is not installed: it is "
                  r"built from mcar's source with g\+\+, pkg-config and libsdformat-dev "
                  r"\(sudo apt-get install g\+\+ pkg-config libsdformat-dev\), by `make "
                  r"gazebo-helper`.*; or set MCAR_SDFORMAT to a built mcar-sdformat$")


@pytest.mark.parametrize("command", [("check", "--gazebo"), ("build", "--format", "sdf")])
def test_without_the_helper_gazebo_says_how_to_install_it(cli, no_helper, command, tmp_path):
    result = cli(*command, CAR, "-o" if command[0] == "build" else "-q",
                 *([tmp_path / "car.sdf"] if command[0] == "build" else []))
    assert result.exit_code == 2
    assert HINT.match(result.stderr.strip()), result.stderr
    assert not (tmp_path / "car.sdf").exists()


def test_without_the_helper_nothing_else_changes(cli, no_helper, tmp_path):
    assert cli("check", "-q", CAR).exit_code == 0
    result = cli("ci", REPO / "urdf" / "laser", "--no-render", "--no-sim", "--format", "junit",
                 "--build-dir", tmp_path / "build")
    assert result.exit_code == 0, result.output
    assert "mcar.gazebo" not in result.stdout
    assert "mcar.check" in result.stdout


def test_a_helper_named_by_mcar_sdformat_must_be_there(cli, monkeypatch, tmp_path):
    monkeypatch.setenv("MCAR_SDFORMAT", str(tmp_path / "nowhere"))
    for command in (("check", "--gazebo", CAR), ("ci", REPO / "urdf" / "laser", "--no-render")):
        result = cli(*command)
        assert result.exit_code == 2
        assert result.stderr.startswith(f"mcar: error: MCAR_SDFORMAT={tmp_path / 'nowhere'}: "
                                        "not an executable file; it is built from mcar's source")


def test_the_helper_make_installs_beside_mcar_is_found_from_any_folder(run_mcar, tmp_path):
    from conftest import MCAR

    if not (MCAR.parent / "mcar-sdformat").is_file():
        pytest.skip("no mcar-sdformat beside mcar: `make install` builds it there where "
                    "libsdformat-dev is installed")
    result = run_mcar("check", "--gazebo", CAR, cwd=tmp_path,
                      env={"MCAR_SDFORMAT": "", "PATH": "/usr/bin:/bin"})
    assert result.returncode == 0, result.stderr
    assert "note: Gazebo simulates 3 links: 0.7056 kg, as in the URDF (libsdformat " \
        in result.stderr


def test_an_empty_model_is_not_blamed_on_the_joint_frame_bug(cli, gazebo, tmp_path):
    # ABB's and KUKA's arms declare no mass: Gazebo leaves out every link, and libsdformat
    # 12.3.0 returns error code 24 of an empty frame graph too. Its hint named the bug of
    # SDF <joint>s in <gazebo> blocks (fixed in 12.6.0), which these URDFs do not have.
    robot = tmp_path / "bare_arm.urdf"
    robot.write_text("""<?xml version="1.0"?>
<robot name="bare_arm">
  <link name="base_link"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
  </link>
  <joint name="joint_1" type="revolute">
    <parent link="base_link"/><child link="link_1"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="0" velocity="1"/>
  </joint>
  <link name="link_1"><visual><geometry><box size="0.05 0.05 0.3"/></geometry></visual>
  </link>
</robot>
""")
    result = cli("check", "--gazebo", robot)
    assert result.exit_code == 1
    e151 = [line for line in result.stderr.splitlines() if line.endswith("[E151]")]
    assert any("(error code 24) [E151]" in line for line in e151), e151
    assert not [line for line in e151 if "maybe a bug" in line]
