"""`mcar new part` says how to put the part into the robot: the include line and a macro
call, and the file to paste them into; pasted there, `mcar build` builds the part in."""

from __future__ import annotations


def test_new_part_prints_what_to_paste_and_pasting_it_builds_the_part_in(run_mcar, tmp_path):
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    package = tmp_path / "demo"
    part = run_mcar("new", "part", "arm", cwd=package)
    assert part.returncode == 0, part.stderr
    include = '<xacro:include filename="$(find demo)/urdf/arm/arm.xacro"/>'
    call = ['<xacro:arm name="left" reflect="1" parent="base_link">',
            '  <origin xyz="0 0 0.1" rpy="0 0 0"/>',
            "</xacro:arm>"]
    assert part.stdout.splitlines() == [
        "to use it, paste into urdf/demo.urdf.xacro, after its other includes:",
        f"  {include}",
        'and before its </robot>, once per use (a name each; reflect="-1" mirrors it; the '
        "origin: where on base_link):",
        *(f"  {line}" for line in call)]

    robot = package / "urdf/demo.urdf.xacro"
    # control: the robot as init wrote it has no arm
    built = run_mcar("build", str(robot), "-o", "-", cwd=package)
    assert built.returncode == 0, built.stderr
    assert "arm_left_link" not in built.stdout

    # paste as a person does: the include after the last one, the call before </robot>
    lines = robot.read_text().splitlines()
    last_include = max(n for n, line in enumerate(lines) if "<xacro:include" in line)
    lines.insert(last_include + 1, f"  {include}")
    end = lines.index("</robot>")
    lines[end:end] = [f"  {line}" for line in call]
    robot.write_text("\n".join(lines) + "\n")
    built = run_mcar("build", str(robot), "-o", "-", cwd=package)
    assert built.returncode == 0, built.stderr
    assert '<link name="arm_left_link">' in built.stdout
    assert '<parent link="base_link"/>' in built.stdout.split('name="arm_left_joint"')[1]


def test_new_part_outside_an_init_package_names_no_robot_file(run_mcar, tmp_path):
    (tmp_path / "package.xml").write_text(
        '<package format="2"><name>mine</name><version>0.0.0</version>'
        "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>MIT</license></package>")
    part = run_mcar("new", "part", "arm", cwd=tmp_path)
    assert part.returncode == 0, part.stderr
    assert part.stdout.splitlines()[:2] == [
        "to use it, paste into your robot's .urdf.xacro file, after its other includes:",
        '  <xacro:include filename="$(find mine)/urdf/arm/arm.xacro"/>']


def test_new_part_into_adds_the_part_to_the_robot(run_mcar, tmp_path):
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    package = tmp_path / "demo"
    part = run_mcar("new", "part", "arm", "--into", "urdf/demo.urdf.xacro", cwd=package)
    assert part.returncode == 0, part.stderr
    assert part.stdout == ""  # nothing left to paste
    assert part.stderr.splitlines()[-1] == (
        'added arm to urdf/demo.urdf.xacro: <xacro:include filename="$(find demo)/urdf/arm/'
        'arm.xacro"/> and <xacro:arm name="left" ...> on base_link')
    built = run_mcar("build", "urdf/demo.urdf.xacro", "-o", "-", cwd=package)
    assert built.returncode == 0, built.stderr
    assert '<link name="arm_left_link">' in built.stdout
    # a second time: the robot includes it already (and the part's files exist)
    again = run_mcar("new", "part", "arm", "--into", "urdf/demo.urdf.xacro", cwd=package)
    assert again.returncode == 2 and again.stderr.count("\n") == 1
    assert again.stderr.startswith("urdf/demo.urdf.xacro: error: it includes ")


def test_new_part_into_a_robot_it_cannot_change_writes_nothing(run_mcar, tmp_path):
    assert run_mcar("init", "demo", cwd=tmp_path).returncode == 0
    package = tmp_path / "demo"
    cut = package / "urdf/cut.urdf.xacro"
    cut.write_text('<?xml version="1.0"?>\n<robot name="cut">\n  <link name="base_link"/>\n')
    for robot, message in ((cut, "no <robot> ... </robot> to add the part into"),
                           (package / "urdf/absent.urdf.xacro",
                            "cannot read: No such file or directory")):
        part = run_mcar("new", "part", "arm", "--into", str(robot), cwd=package)
        assert (part.returncode, part.stdout) == (2, "")
        assert part.stderr == f"{robot.relative_to(package)}: error: {message}\n"
        assert not (package / "urdf/arm").exists()
    assert cut.read_text().endswith('<link name="base_link"/>\n')
