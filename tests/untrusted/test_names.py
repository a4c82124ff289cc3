"""Names are data (issue 32, item 6), tried as an attacker would.

A file name may hold a newline or a terminal escape sequence (an OSC that retitles the
terminal, a CSI that recolours it); a URDF name may hold ``&#13;`` or a C1 control; a
record under build/ or renders/ may have been written by anyone. Every command must show
such names escaped, keep running, and never be broken by what an earlier run stored; a
name that cannot make a file is refused before anything is written.
"""

from __future__ import annotations

import json
import re
import shutil
import unicodedata
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from mobile_car.names import shown

NEWLINE = "evil\nname"
ESCAPES = "t\x1b]0;pwned\x07x\x1b[31mred"
# Their escaped forms, as every message, table and caption must show them.
NEWLINE_SHOWN = "evil\\nname"
ESCAPES_SHOWN = "t\\x1b]0;pwned\\x07x\\x1b[31mred"
_BIDI = set("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def raw_controls(text: str) -> list[str]:
    """Characters that act on a terminal instead of showing: controls but the line end,
    line separators, bidi controls."""
    return [c for c in text if c != "\n" and (unicodedata.category(c) in ("Cc", "Zl", "Zp", "Cs")
                                              or c in _BIDI)]


def assert_clean(result, *expected: str) -> None:
    both = result.stdout + result.stderr
    assert "internal error" not in both and "Traceback" not in both, result.stderr
    assert raw_controls(both) == [], both
    for text in expected:
        assert text in both, (text, both)


@pytest.fixture
def hostile_package(run_mcar, tmp_path) -> Path:
    """A package from `mcar init` with two more robot files: one whose name holds a
    newline, one an OSC title sequence and a CSI colour code."""
    assert run_mcar("init", "pkg", cwd=tmp_path).returncode == 0
    package = tmp_path / "pkg"
    robot = package / "urdf" / "pkg.urdf.xacro"
    for name in (NEWLINE, ESCAPES):
        shutil.copy(robot, package / "urdf" / f"{name}.urdf.xacro")
    return package


def test_shown_escapes_controls_and_nothing_else():
    assert shown("base_link") == "base_link"
    assert shown("rädchen/車輪 — x.urdf") == "rädchen/車輪 — x.urdf"
    assert shown(ESCAPES) == ESCAPES_SHOWN
    assert shown("a\nb\r\tc\x7f\x9b\u202ed\u2028") == "a\\nb\\r\\tc\\x7f\\x9b\\u202ed\\u2028"
    assert shown("bad\udcffbyte") == "bad\\xffbyte"  # a byte that is not UTF-8
    assert shown(shown(ESCAPES)) == shown(ESCAPES)  # layers may each escape


def test_ci_shows_hostile_names_escaped_and_draws_the_sheet(run_mcar, hostile_package):
    ci = run_mcar("ci", "--no-sim", cwd=hostile_package)
    assert ci.returncode == 0, ci.stderr
    # the three robots and the package's two part test files (wheel, castor)
    assert_clean(ci, NEWLINE_SHOWN, ESCAPES_SHOWN, "mcar ci: 5 of 5 files passed")
    table = [line for line in ci.stdout.splitlines() if line.startswith(ESCAPES_SHOWN)]
    assert len(table) == 1 and table[0].endswith("ok")
    from PIL import Image

    with Image.open(hostile_package / "renders" / "index.png") as sheet:
        assert sheet.width > 2 * 320  # three pictures, two columns: not the empty sheet
    assert (hostile_package / "renders" / f"{NEWLINE}.png").is_file()


def test_junit_and_github_outputs_stay_well_formed(run_mcar, hostile_package):
    junit = run_mcar("ci", "--no-sim", "--no-render", "--format", "junit", cwd=hostile_package)
    assert junit.returncode == 0, junit.stderr
    assert_clean(junit)
    names = {case.get("name") for case in ET.fromstring(junit.stdout).iter("testcase")}
    assert names == {"pkg.urdf.xacro", f"{NEWLINE_SHOWN}.urdf.xacro",
                     f"{ESCAPES_SHOWN}.urdf.xacro", "wheel/test_wheel.urdf.xacro",
                     "castor/test_castor.urdf.xacro"}
    (hostile_package / "urdf" / f"{ESCAPES}.urdf.xacro").write_text("<robot name='x'><link")
    github = run_mcar("check", "--format", "github", cwd=hostile_package)
    assert github.returncode == 1
    assert_clean(github, f"::error file=urdf/{ESCAPES_SHOWN}.urdf.xacro")


@pytest.mark.parametrize("command", ["check", "build", "render"])
def test_commands_show_hostile_names_escaped(run_mcar, hostile_package, command):
    result = run_mcar(command, cwd=hostile_package)
    assert result.returncode == 0, result.stderr
    assert_clean(result, NEWLINE_SHOWN, ESCAPES_SHOWN) if command != "render" else \
        assert_clean(result, "5 pictures in renders: 5 rendered")


def test_an_error_about_a_hostile_file_is_one_escaped_line(run_mcar, hostile_package):
    bad = hostile_package / "urdf" / f"{NEWLINE}.urdf.xacro"
    bad.write_text("<robot name='x' xmlns:xacro='http://www.ros.org/wiki/xacro'>"
                   "<xacro:nope/></robot>")
    built = run_mcar("build", str(bad), cwd=hostile_package)
    assert built.returncode == 1
    assert_clean(built)
    first = built.stderr.splitlines()[0]
    assert first.startswith(f"urdf/{NEWLINE_SHOWN}.urdf.xacro:1: error: ")


def test_a_name_removed_after_a_run_does_not_break_the_next(run_mcar, hostile_package):
    assert run_mcar("ci", "--no-sim", cwd=hostile_package).returncode == 0
    (hostile_package / "urdf" / f"{NEWLINE}.urdf.xacro").unlink()
    # Its picture and its records stay behind; the sheet must be drawn again with them.
    (hostile_package / "renders" / "index.png").unlink()
    again = run_mcar("ci", "--no-sim", cwd=hostile_package)
    assert again.returncode == 0, again.stderr
    assert_clean(again, "mcar ci: 4 of 4 files passed")  # and the wheel's, the castor's
    assert (hostile_package / "renders" / "index.png").is_file()


def test_link_and_robot_names_are_shown_escaped(run_mcar, tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text("""<robot name="r&#x202e;x">
      <link name="a&#13;b&#x9b;31m"/><link name="c&#10;d"/>
      <joint name="j&#x85;" type="fixed"><parent link="a&#13;b&#x9b;31m"/>
        <child link="c&#10;d"/></joint>
    </robot>""")
    check = run_mcar("check", "r.urdf", cwd=tmp_path)
    assert check.returncode == 0, check.stderr
    assert_clean(check, "robot name is: r\\u202ex\n", "root Link: a\\rb\\x9b31m has 1",
                 "child(1):  c\\nd\n")
    tree = run_mcar("tree", "r.urdf", cwd=tmp_path)
    assert_clean(tree, "c\\nd  (j\\x85: fixed")
    document = run_mcar("check", "--format", "json", "r.urdf", cwd=tmp_path)
    assert_clean(document)
    assert json.loads(document.stdout)["files"][0]["robot"] == "r\u202ex"  # same data


def _mangle(record: dict, how: str) -> None:
    entry = record["items"]["pkg.urdf"]
    if how == "failed check, no diagnostics":
        entry["check"] = {"passed": False, "diagnostics": []}
    elif how == "testcases that are not testcases":
        entry["sim"] = {"status": "failed", "message": "m", "exit_code": 1, "cases": [1],
                        "problems": [], "diagnostics": []}
    elif how == "an unknown rule":
        entry["check"]["diagnostics"] = [{"rule": "E999", "file": "x", "line": 1,
                                          "message": "m"}]
        entry["check"]["passed"] = False
    elif how == "wrong types everywhere":
        entry.update(check=[1], deps={"a": 1}, links="many", sim="yes")


@pytest.mark.parametrize("how", ["failed check, no diagnostics",
                                 "testcases that are not testcases", "an unknown rule",
                                 "wrong types everywhere"])
def test_a_forged_ci_record_is_rebuilt_not_trusted(run_mcar, tmp_path, how):
    assert run_mcar("init", "pkg", cwd=tmp_path).returncode == 0
    package = tmp_path / "pkg"
    assert run_mcar("ci", "--no-render", cwd=package).returncode == 0
    path = package / "build" / ".mcar-ci.json"
    record = json.loads(path.read_text())
    _mangle(record, how)
    path.write_text(json.dumps(record))
    again = run_mcar("ci", "--no-render", "--format", "junit", cwd=package)
    assert again.returncode == 0, again.stderr
    assert_clean(again)
    assert ET.fromstring(again.stdout).get("failures") == "0"
    rebuilt = json.loads(path.read_text())["items"]["pkg.urdf"]
    assert rebuilt["check"] == {"passed": True, "diagnostics": []}


def test_a_manifest_cannot_put_a_picture_from_elsewhere_on_the_sheet(run_mcar, tmp_path):
    from PIL import Image

    assert run_mcar("init", "pkg", cwd=tmp_path).returncode == 0
    package = tmp_path / "pkg"
    assert run_mcar("ci", "--no-sim", cwd=package).returncode == 0
    with Image.open(package / "renders" / "index.png") as sheet:
        own = sheet.size  # the package's own pictures
    Image.new("RGB", (64, 48), (255, 0, 0)).save(tmp_path / "elsewhere.png")
    path = package / "renders" / ".mcar-render.json"
    record = json.loads(path.read_text())
    for key in (str(tmp_path / "elsewhere.png"), "../../elsewhere.png", "a\u0000.png"):
        record["outputs"][key] = {"input": "x", "png": "0" * 64, "caption": "c"}
    path.write_text(json.dumps(record))
    (package / "renders" / "index.png").unlink()
    again = run_mcar("ci", "--no-sim", cwd=package)
    assert again.returncode == 0, again.stderr
    with Image.open(package / "renders" / "index.png") as sheet:
        assert sheet.size == own  # the package's own pictures only


@pytest.mark.parametrize("length, longest", [(300, 311), (255, 266), (245, 256)])
def test_init_with_a_name_too_long_writes_nothing(run_mcar, tmp_path, length, longest):
    name = "a" * length
    made = run_mcar("init", name, cwd=tmp_path)
    assert made.returncode == 2
    assert made.stderr.count("\n") == 1, made.stderr
    assert made.stderr.startswith("mcar: error: cannot make the file 'aaaaaaaaaaaaaaaaaaaa…")
    assert made.stderr.endswith(f".urdf.xacro': it is {longest} bytes long, and a file name "
                                "holds at most 255 bytes; give a package name of at most "
                                "244 characters (--name)\n")
    assert list(tmp_path.iterdir()) == []


def test_init_at_the_longest_name_makes_a_package_ci_passes(run_mcar, tmp_path):
    name = "d" * 244
    assert run_mcar("init", name, cwd=tmp_path).returncode == 0, "244 characters fit"
    ci = run_mcar("ci", "--no-sim", "--no-render", cwd=tmp_path / name)
    assert ci.returncode == 0, ci.stderr


def test_init_into_a_path_that_cannot_be_made_writes_nothing(run_mcar, tmp_path):
    made = run_mcar("init", f"{'x' * 300}/pkg", cwd=tmp_path)
    assert made.returncode == 2 and made.stderr.count("\n") == 1
    assert "cannot make the folder 'xxxxxxxxxxxxxxxxxxxx…xxxxxxxxxxxxxxxxxxxx': it is 300 " \
           "bytes long" in made.stderr
    assert list(tmp_path.iterdir()) == []
    # A folder that exists, where a file of the package cannot go: nothing is left in it.
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "urdf").write_text("a file, not a folder")
    (folder / "README").write_text("mine")
    made = run_mcar("init", "mine", cwd=tmp_path)
    assert made.returncode == 2 and made.stderr.count("\n") == 1
    assert made.stderr.startswith("mine/urdf/define.xacro: error: cannot write: Not a "
                                  "directory; nothing was written"), made.stderr
    assert sorted(p.name for p in folder.iterdir()) == ["README", "urdf"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine"]  # no staging folder left


@pytest.fixture
def package(run_mcar, tmp_path) -> Path:
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    return tmp_path / "demo"


@pytest.mark.parametrize("name", ["include", "macro", "property", "arg", "if", "unless",
                                  "insert_block", "element", "attribute", "call"])
def test_new_part_refuses_xacro_keywords(run_mcar, package, name):
    made = run_mcar("new", "part", name, cwd=package)
    assert made.returncode == 2
    assert made.stderr == (f"mcar: error: a part cannot be called '{name}': <xacro:{name}> is "
                           "xacro's own element, so the part's macro could never be called; "
                           "choose another name\n")
    assert not (package / "urdf" / name).exists()


def test_new_part_refuses_names_that_clash_with_the_robot(run_mcar, package):
    inertial = run_mcar("new", "part", "box_inertial", cwd=package)
    assert inertial.returncode == 2
    assert inertial.stderr == ("mcar: error: a part cannot be called 'box_inertial': "
                               "urdf/define.xacro already defines the macro "
                               "xacro:box_inertial, which the part's macro would replace; "
                               "choose another name\n")
    robot = package / "urdf" / "demo.urdf.xacro"
    robot.write_text(robot.read_text().replace("</robot>",
                                               '<link name="arm_right_link"/></robot>'))
    arm = run_mcar("new", "part", "arm", cwd=package)
    assert arm.returncode == 2
    assert "its link arm_right_link would clash with the link arm_right_link of " \
           "urdf/demo.urdf.xacro" in arm.stderr
    assert sorted(p.name for p in (package / "urdf").iterdir()) == [
        "castor", "config.xacro", "define.xacro", "demo.urdf.xacro", "wheel"]


def test_new_part_name_length_counts_its_test_file(run_mcar, package):
    long = run_mcar("new", "part", "p" * 240, cwd=package)
    assert long.returncode == 2 and long.stderr.count("\n") == 1
    assert "it is 256 bytes long" in long.stderr and "at most 239 characters" in long.stderr
    assert not (package / "urdf" / ("p" * 240)).exists()
    assert run_mcar("new", "part", "p" * 239, cwd=package).returncode == 0


def test_the_keyword_list_is_xacros_own():
    import xacro

    from mobile_car.scaffold.part_names import XACRO_KEYWORDS

    source = Path(xacro.__file__).read_text(encoding="utf-8")
    # Every 'xacro:NAME' the expander compares a tag with; xacro:name is the attribute of
    # <xacro:element>, not an element.
    tags = set(re.findall(r"'xacro:([a-z_]+)'", source)) - {"name"}
    assert tags == XACRO_KEYWORDS
