"""Outputs never destroy inputs (issue 13, item 2): an output that is a file the run reads,
or two inputs written to one output, is refused (exit 2, naming both) and every input is
left byte for byte as it was."""

from __future__ import annotations

import pytest

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


@pytest.fixture
def tree(tmp_path):
    (tmp_path / "incd").mkdir()
    (tmp_path / "incd" / "props.xacro").write_text(
        f'<robot {XACRO}><xacro:property name="w" value="0.1"/></robot>\n')
    (tmp_path / "self.xacro").write_text(
        f'<robot name="r" {XACRO}><xacro:include filename="incd/props.xacro"/>'
        '<link name="base"><visual><geometry><box size="${w} 0.1 0.1"/></geometry></visual>'
        "</link></robot>\n")
    (tmp_path / "t.urdf").write_text(
        '<robot name="t"><link name="base"><visual><geometry><box size="0.1 0.1 0.1"/>'
        "</geometry></visual></link></robot>\n")
    return tmp_path


def _snapshot(folder):
    return {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}


@pytest.mark.parametrize("args, overwritten", [
    (["build", "self.xacro", "-o", "self.xacro"], "self.xacro"),
    (["build", "self.xacro", "-o", "incd/props.xacro"], "incd/props.xacro"),
    (["render", "t.urdf", "-o", "t.urdf", "--renderer", "raycast"], "t.urdf"),
    # A picture is refused a name that is not .png before the includes are known.
    (["render", "self.xacro", "-o", "incd/props.xacro", "--renderer", "raycast"],
     "-o incd/props.xacro: mcar render writes PNG pictures, not .xacro"),
    (["ci", "self.xacro", "--no-render", "--junit-xml", "self.xacro"], "self.xacro"),
    (["ci", "self.xacro", "--no-render", "--junit-xml", "incd/props.xacro"],
     "incd/props.xacro"),
])
def test_an_output_over_a_file_the_run_reads_is_refused(args, overwritten, tree, run_mcar):
    before = _snapshot(tree)
    result = run_mcar(*args, cwd=tree)
    assert result.returncode == 2, result.stderr
    message = (overwritten if overwritten.startswith("-o ")
               else f"would overwrite {overwritten}, a file this run reads")
    assert f"error: {message}" in result.stderr
    assert {path: path.read_bytes() for path in before} == before


@pytest.mark.parametrize("command", ["build", "render", "ci"])
def test_two_inputs_written_to_one_output_are_refused(command, tree, run_mcar):
    robots = tree / "robots"
    robots.mkdir()
    for name in ("a.xacro", "a.urdf.xacro"):
        (robots / name).write_text(f'<robot name="a" {XACRO}><link name="base"/></robot>\n')
    extra = {"render": ["--renderer", "raycast"],
             "ci": ["--no-render", "--no-sim", "--no-gazebo"]}.get(command, [])
    result = run_mcar(command, "robots", *extra, cwd=tree)
    assert result.returncode == 2, result.stderr
    assert ("robots/a.urdf.xacro and robots/a.xacro would both be written to this file"
            in result.stderr), result.stderr
    assert not (tree / "build").exists() and not (tree / "renders").exists()
