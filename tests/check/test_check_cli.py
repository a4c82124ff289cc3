"""``mcar check`` from the command line: inputs, formats, exit codes, xacro locations."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]
REPO = TESTS.parent
TUTORIAL = TESTS.parent / "urdf" / "tutorial"
XACRO = TESTS / "check_xacro"
BROKEN = TESTS / "check_corpus" / "broken"
SKELETON = TUTORIAL / "01_skeleton.urdf"
SKELETON_TREE = (
    "robot name is: test_robot\n"
    "---------- Successfully Parsed XML ---------------\n"
    "root Link: base_link has 4 child(ren)\n"
    "    child(1):  wheel_1\n"
    "    child(2):  wheel_2\n"
    "    child(3):  wheel_3\n"
    "    child(4):  wheel_4\n")


@pytest.mark.parametrize("name", sorted(p.name for p in TUTORIAL.iterdir()))
def test_tutorial_car_checks_clean_and_as_check_urdf(name, run_mcar, check_urdf, tmp_path):
    path = TUTORIAL / name
    if path.suffix == ".xacro":
        built = tmp_path / "built.urdf"
        assert run_mcar("build", path, "-o", built).returncode == 0
        reference = built
    else:
        reference = path
    theirs = subprocess.run([check_urdf, str(reference)], capture_output=True, text=True)
    ours = run_mcar("check", path)
    # On stderr, no problem: only the car's size, where it has shapes (01 is a skeleton).
    size = "" if name.startswith("01_") else "size: 0.25 x 0.30 x 0.15 m\n"
    assert (ours.returncode, ours.stderr) == (0, size)
    assert ours.stdout == theirs.stdout == SKELETON_TREE


def test_xacro_problems_point_into_the_xacro_sources(cli):
    result = cli("check", XACRO / "robot.urdf.xacro", "wheel_radius:=-0.05", "body_height:=0")
    lines = result.stderr.splitlines()
    robot = str((XACRO / "robot.urdf.xacro").relative_to(Path.cwd())) \
        if XACRO.is_relative_to(Path.cwd()) else str(XACRO / "robot.urdf.xacro")
    # Each element where it is written: the <box> in the robot file...
    assert f"{robot}:11: error: link 'base_link' <visual>: <box size=\"0.3 0.2 0\"> must be > 0 " \
           "[E113]" in lines
    # ...the <cylinder> in the macro that made wheel_${side}, with the call that did.
    parts = robot.replace("robot.urdf.xacro", "parts.xacro")
    assert f"{parts}:8: error: link 'wheel_left' <visual>: <cylinder radius=\"-0.05\"> must " \
           f"be > 0 (in xacro:wheel called at {robot}:16) [E113]" in lines
    assert result.exit_code == 1
    assert result.stdout == ""


def test_xacro_literal_name_in_an_included_macro_file_is_found_there(tmp_path, cli):
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text((XACRO / "robot.urdf.xacro").read_text())
    parts = (XACRO / "parts.xacro").read_text().replace('xyz="0.1 0 -0.02"', 'xyz="0.1 0"')
    (tmp_path / "parts.xacro").write_text(parts)
    # The joint is found by its literal name, then its <origin> below it.
    line = next(i for i, text in enumerate(parts.splitlines(), 1) if 'xyz="0.1 0"' in text)
    result = cli("check", "--format", "json", robot)
    [diagnostic] = json.loads(result.stdout)["files"][0]["diagnostics"]
    assert (diagnostic["rule"], diagnostic["line"]) == ("E114", line)
    assert Path(diagnostic["file"]).resolve() == (tmp_path / "parts.xacro").resolve()
    assert result.exit_code == 1


def test_xacro_that_does_not_expand_is_E140_at_the_faulty_line(cli):
    result = cli("check", XACRO / "broken_expansion.urdf.xacro")
    assert result.exit_code == 1
    [line, summary] = result.stderr.splitlines()
    assert "broken_expansion.urdf.xacro:5: error: name 'undefined_width' is not defined" in line
    assert line.endswith("[E140]")
    assert summary == "mcar check: 1 error, 0 warnings in 1 file"


def test_unknown_xacro_argument_is_a_usage_error(cli):
    result = cli("check", XACRO / "robot.urdf.xacro", "whel_radius:=1")
    assert result.exit_code == 2
    assert "unknown xacro argument 'whel_radius' (did you mean 'wheel_radius'?)" in result.stderr


def test_name_value_without_a_xacro_input_is_a_usage_error(cli):
    result = cli("check", SKELETON, "width:=2")
    assert result.exit_code == 2
    assert "NAME:=VALUE, --set and --config apply to .xacro inputs" in result.stderr


def test_json_document(cli):
    result = cli("check", "--format", "json", TUTORIAL / "03_color.urdf")
    assert result.exit_code == 0
    document = json.loads(result.stdout)
    assert (document["errors"], document["warnings"], document["exit_code"]) == (0, 0, 0)
    [file] = document["files"]
    assert (file["robot"], file["root"], file["ok"], file["diagnostics"]) == \
        ("test_robot", "base_link", True, [])
    assert file["tree"] == {"base_link": ["wheel_1", "wheel_2", "wheel_3", "wheel_4"]}
    assert [link["name"] for link in file["links"]] == \
        ["base_link", "wheel_1", "wheel_2", "wheel_3", "wheel_4"]
    assert file["links"][1] == {"name": "wheel_1", "file": file["file"], "line": 21,
                                "parent_joint": "joint_base_wheel1", "children": []}
    assert file["joints"][0] == {
        "name": "joint_base_wheel1", "type": "fixed", "parent": "base_link",
        "child": "wheel_1", "file": file["file"], "line": 61,
        "origin": {"xyz": [0.0, 0.0, 0.0], "rpy": [0.0, 0.0, 0.0]}, "axis": None,
        "limit": None}


def test_json_diagnostics_and_failures(cli, tmp_path):
    missing = tmp_path / "missing.urdf"
    result = cli("check", "--format", "json", BROKEN / "box_without_size.urdf", missing)
    assert result.exit_code == 2  # a file that cannot be read outranks problems found
    document = json.loads(result.stdout)
    broken, absent = document["files"]
    assert broken["diagnostics"] == [{
        "rule": "E112", "severity": "error", "file": broken["file"], "line": 7,
        "message": "link 'base' <visual>: <box> has no size"}]
    assert (broken["ok"], broken["errors"]) == (False, 1)
    assert absent["failure"] == {"message": "no such file", "exit_code": 2}
    assert (document["errors"], document["exit_code"]) == (1, 2)


def test_github_annotations(cli):
    result = cli("check", "--format", "github", BROKEN / "box_without_size.urdf",
                 BROKEN / "typo_attribute_xzy.urdf")
    assert result.exit_code == 1
    lines = result.stdout.splitlines()
    assert len(lines) == 2
    assert lines[0].startswith("::error file=")
    assert lines[0].endswith("box_without_size.urdf,line=7,title=E112 geometry-size-missing::"
                             "link 'base' <visual>: <box> has no size")
    assert lines[1].endswith("typo_attribute_xzy.urdf,line=7,title=W202 unknown-attribute::"
                             "<origin> has unknown attribute 'xzy'; did you mean 'xyz'?")
    assert lines[1].startswith("::warning file=")


def test_github_annotation_escapes_what_would_end_the_command():
    from mobile_car.check.diagnostics import Diagnostic

    text = Diagnostic("E114", "a,b:c.urdf", 3, "50% of\nit").github()
    assert text == "::error file=a%2Cb%3Ac.urdf,line=3,title=E114 bad-number::50%25 of%0Ait"


def test_many_inputs_each_get_a_header_and_the_worst_exit_code(cli, tmp_path):
    result = cli("check", SKELETON, BROKEN / "joint_type_unknown.urdf", tmp_path / "none.urdf")
    assert result.exit_code == 2
    assert result.stdout == f"==> {_shown(SKELETON)} <==\n" + SKELETON_TREE
    assert f"{_shown(tmp_path / 'none.urdf')}: error: no such file" in result.stderr
    assert "has unknown type 'hinge'" in result.stderr
    assert result.stderr.splitlines()[-1] == "mcar check: 1 error, 0 warnings, 1 not checked " \
                                             "in 3 files"


def _shown(path: Path) -> str:
    try:
        return str(path.relative_to(Path.cwd()))
    except ValueError:
        return str(path)


def test_a_folder_means_its_urdf_files(cli, tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "a.urdf").write_text(SKELETON.read_text())
    (tmp_path / "b.urdf").write_text((BROKEN / "axis_zero.urdf").read_text())
    (tmp_path / "notes.txt").write_text("not a robot")
    result = cli("check", "--format", "json", tmp_path)
    files = [Path(f["file"]).name for f in json.loads(result.stdout)["files"]]
    assert files == ["b.urdf", "a.urdf"]
    assert result.exit_code == 1


def test_stdin(run_mcar, check_urdf):
    ours = run_mcar("check", "-", input=SKELETON.read_text())
    assert (ours.returncode, ours.stdout, ours.stderr) == (0, SKELETON_TREE, "")
    broken = run_mcar("check", "-", input=(BROKEN / "two_parents.urdf").read_text())
    assert broken.returncode == 1
    assert broken.stderr.startswith("<stdin>:15: error: link 'b' has two parents")


@pytest.mark.parametrize("case", sorted(XACRO.glob("stdin_*.urdf")), ids=lambda p: p.name)
def test_xacro_left_in_a_urdf_from_stdin_is_E105_at_its_line(case, cli):
    """A file that uses xacro is expanded (tests/load/test_xacro_in_urdf.py); a URDF on
    stdin is read as it is, and xacro left in it is reported where it is [E105]."""
    import re

    expected = [int(line) for line in re.findall(r"<!-- expect: E105 line=(\d+) -->",
                                                 case.read_text())]
    result = cli("check", "-q", "-", input=case.read_bytes())
    assert result.exit_code == 1
    found = [line for line in result.stderr.splitlines() if line.endswith("[E105]")]
    assert [int(line.split(":")[1]) for line in found] == expected
    assert all(line.startswith("<stdin>:") for line in found)


def test_missing_file_and_folder_without_robots_exit_2(cli, tmp_path):
    result = cli("check", tmp_path / "nope.urdf")
    assert result.exit_code == 2
    assert result.stderr.splitlines()[0] == f"{_shown(tmp_path / 'nope.urdf')}: error: no such file"
    empty = cli("check", tmp_path)
    assert empty.exit_code == 2
    assert empty.stderr == (
        f"{_shown(tmp_path)}: error: no robot files in this folder (looked in "
        "urdf/, robots/, xacro/, description/ or the folder itself)\n")
    # No INPUT means the package, as for every command: the bundled robot files.
    whole = cli("check", "-q")
    assert whole.exit_code == 0, whole.stderr


def test_strict_and_quiet(cli):
    warned = BROKEN / "moving_link_without_inertial.urdf"
    loose = cli("check", warned)
    assert loose.exit_code == 0
    assert loose.stdout.startswith("robot name is: r\n")
    assert "[W206]" in loose.stderr
    strict = cli("check", "--strict", "-q", warned)
    assert (strict.exit_code, strict.stdout) == (1, "")
    assert "[W206]" in strict.stderr


def test_help_documents_exit_codes(cli):
    text = cli("check", "--help").stdout
    for line in ("0  every input is sound", "1  problems found", "2  usage or I/O error"):
        assert line in text
    assert "check" in cli("--help").stdout and "tree" in cli("--help").stdout


@pytest.mark.parametrize("content", [
    b"\x00\xff\xfe garbage \x89PNG",
    b"<robot name='r'>" + b"<link name='a'>" * 5000,
    b"<robot name='r'>" + b"<a>" * 300 + b"</a>" * 300 + b"</robot>",
    b"<?xml version='1.0' encoding='latin-1'?><robot name='r\xe9'><link name='\xe9'/></robot>",
    b"<robot name='r'><link name='" + b"x" * 2_000_000 + b"'/></robot>",
], ids=["binary", "unclosed", "deep-nesting", "latin-1", "huge-name"])
def test_odd_inputs_never_crash(content, run_mcar, tmp_path):
    path = tmp_path / "odd.urdf"
    path.write_bytes(content)
    result = run_mcar("check", "-q", path)
    assert "Traceback" not in result.stderr and "internal error" not in result.stderr
    assert result.returncode in (0, 1)
    if result.returncode == 1:
        assert f"{_shown(path)}:" in result.stderr.splitlines()[0]


def test_a_100000_link_chain_and_a_cycle_finish(run_mcar, tmp_path):
    links = 100_000
    text = ['<robot name="snake">'] + [f'<link name="l{i}"/>' for i in range(links)]
    text += [f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/>'
             '</joint>' for i in range(1, links)]
    text += ['<joint name="back" type="fixed"><parent link="l99999"/><child link="l5"/></joint>',
             "</robot>"]
    path = tmp_path / "snake.urdf"
    path.write_text("\n".join(text))
    result = run_mcar("check", "-q", path, timeout=60)
    assert result.returncode == 1
    assert "link 'l5' has two parents" in result.stderr
    assert "form a cycle: l5 -> l6 -> l7 -> l8" in result.stderr


def test_xacro_warning_is_W220_and_fails_only_with_strict(cli, tmp_path):
    source = tmp_path / "w.urdf.xacro"
    source.write_text('<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                      '  <xacro:property name="pi" value="3"/>\n  <link name="base"/>\n'
                      '</robot>\n')
    result = cli("check", "-q", source)
    assert result.exit_code == 0
    [warning, summary] = result.stderr.splitlines()
    assert warning.startswith(f"{_shown(source)}: warning: xacro: redefining global symbol: "
                              "pi (when processing file: ")
    assert warning.endswith(") [W220]")
    assert summary == "mcar check: 0 errors, 1 warning in 1 file"
    assert cli("check", "-q", "--strict", source).exit_code == 1


def test_every_robot_file_of_the_description_checks_clean(cli, repo):
    """Every .urdf and robot .xacro under urdf/: no error, no warning, check_urdf's tree."""
    result = cli("check", "--format", "json", "--strict", repo / "urdf")
    document = json.loads(result.stdout)
    assert document["files"]
    problems = [f"{d['file']}:{d['line']}: {d['message']} [{d['rule']}]"
                for file in document["files"] for d in file["diagnostics"]]
    assert problems == []
    assert all(file["ok"] and file["root"] for file in document["files"])
    assert result.exit_code == 0


def test_mesh_that_exists_but_does_not_load_is_W207(cli, tmp_path):
    (tmp_path / "cut_short.stl").write_text("solid s\n facet normal 0 0 1\n  outer loop\n")
    (tmp_path / "good.stl").write_bytes(
        (TESTS / "check_corpus" / "valid" / "meshes" / "cube.stl").read_bytes())
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r">\n  <link name="base">\n'
                     '    <visual><geometry><mesh filename="cut_short.stl"/></geometry></visual>\n'
                     '    <collision><geometry><mesh filename="file://'
                     f'{tmp_path}/good.stl"/></geometry></collision>\n  </link>\n</robot>\n')
    result = cli("check", "-q", robot)
    assert result.exit_code == 0
    assert result.stderr.splitlines() == [
        f"{_shown(robot)}:3: warning: mesh 'cut_short.stl' cannot be loaded: it holds no "
        "geometry [W207]", "mcar check: 0 errors, 1 warning in 1 file"]


def test_a_xacro_macro_library_is_refused_as_by_every_command(cli):
    result = cli("check", "-q", XACRO / "parts.xacro")
    assert result.exit_code == 2
    shown = _shown(XACRO / "parts.xacro")
    assert result.stderr.splitlines()[0] == (
        f"mcar: error: {shown} is a macro file: include it from a robot file, or build its "
        "test file")


def test_a_urdf_without_robot_name_is_pointed_at_its_robot_tag_with_a_hint(cli):
    result = cli("check", "-q", "-", input=b'<?xml version="1.0"?>\n<robot>\n</robot>\n')
    assert result.exit_code == 1
    name_error, no_links, _ = result.stderr.splitlines()
    assert name_error == ("<stdin>:2: error: <robot> has no name=\"...\" (and no link: a "
                          "xacro macro library? check the robot files that include it) [E102]")
    assert no_links == "<stdin>:2: error: the robot has no <link> [E106]"


def test_binary_stl_cut_short_is_W207_and_a_sound_one_needs_no_trimesh(run_mcar, tmp_path):
    good = (REPO / "meshes" / "motor.stl").read_bytes()
    (tmp_path / "short.stl").write_bytes(good[: len(good) - 50 * 3 - 7])
    (tmp_path / "good.stl").write_bytes(good)
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r">\n  <link name="base">\n'
                     '    <visual><geometry><mesh filename="short.stl"/></geometry></visual>\n'
                     '    <collision><geometry><mesh filename="good.stl"/></geometry></collision>'
                     '\n  </link>\n</robot>\n')
    result = run_mcar("check", "-q", robot)
    assert result.returncode == 0
    (warning,) = [line for line in result.stderr.splitlines() if "W207" in line]
    assert warning.startswith(f"{robot}:3: warning: mesh 'short.stl' cannot be loaded")
    # A sound binary STL is vouched for by its length: no numpy/trimesh start-up cost.
    code = ("import sys\nfrom mobile_car.check.meshes import load_problem\n"
            f"from pathlib import Path\nprint(load_problem(Path({str(tmp_path / 'good.stl')!r})),"
            " 'trimesh' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=tmp_path)
    assert done.stdout.split() == ["None", "False"], done.stderr


def test_gathered_write_finishes_after_partial_writes(monkeypatch):
    """os.writev may write less than asked (a signal, a full pipe): the rest follows, in
    order, across chunks, after what was already buffered on stdout."""
    import os

    from mobile_car.cli import streams

    real_writev = os.writev

    def short_writev(fd, buffers):  # at most 7 bytes per call, often mid-buffer
        data = b"".join(buffers)[:7]
        return real_writev(fd, [data])

    monkeypatch.setattr(os, "writev", short_writev)
    monkeypatch.setattr(streams, "CHUNK_LINES", 2)  # three lines: two chunks
    lines = [b"robot name is: r\n", b"    child(1):  a\n", b"        child(1):  b\n"]
    read_end, write_end = os.pipe()
    with open(write_end, "w", encoding="utf-8") as out:
        monkeypatch.setattr(sys, "stdout", out)
        out.write("==> r.urdf <==\n")  # buffered, not yet written: must still come first
        streams.write_lines(iter(lines))
        monkeypatch.undo()
    with os.fdopen(read_end, "rb") as pipe:
        assert pipe.read() == b"==> r.urdf <==\n" + b"".join(lines)


def test_json_is_written_in_pieces_byte_for_byte():
    """--format json's text is json.dumps's, made safe (escapes and all), UTF-8, written
    in pieces of about 64 KB instead of dumps's one string, built from a list of every
    token (a million small strings, ~80 MB, for a 10,000-link robot)."""
    from mobile_car.cli.check import _json_pieces

    from mobile_car.names import json_safe

    document = {"files": [{"robot": "r\u202e", "links": [
        {"name": f"l{i}\x85é", "line": i, "origin": {"xyz": [0.0, 0.1, -2e-3]}, "axis": None}
        for i in range(3000)]}], "errors": 0, "exit_code": 0}
    expected = json_safe(json.dumps(document, indent=1, ensure_ascii=False)).encode() + b"\n"
    pieces = list(_json_pieces(document))
    assert b"".join(pieces) == expected
    assert b"\\u0085" in expected and b"\\u202e" in expected  # the escapes are in play
    assert len(pieces) > 5
    # Cut after the token that passes 64 KB: "\x85" grows six-fold once escaped.
    assert max(len(piece) for piece in pieces) < 6 * (1 << 16) + 100
