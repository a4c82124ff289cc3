"""``mcar tree`` and the tree module: the rich tree, Graphviz output, structural errors."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]
EVERY_JOINT = TESTS / "check_corpus" / "valid" / "every_joint_type.urdf"
BROKEN = TESTS / "check_corpus" / "broken"

EVERY_JOINT_TREE = """\
base_link
├── free_body  (floating_joint: floating, xyz 0 0 0, rpy 0 0 0)
├── puck  (planar_joint: planar, xyz 0 0 0, rpy 0 0 0, axis 0 0 1)
├── sliding  (prismatic_joint: prismatic, xyz 0 0 0.2, rpy 0 0 0, axis 1 0 0, limits 0..0.3)
│   └── bolted  (fixed_joint: fixed, xyz 0 0 -0.05, rpy 0 0 0)
└── revolving  (revolute_joint: revolute, xyz 0 0 0.1, rpy 0 0 1.5708, axis 0 0 1, limits -1.57..1.57)
    └── spinning  (continuous_joint: continuous, xyz 0.1 0 0, rpy 0 0 0, axis 0 1 0)
"""


def test_rich_tree_shows_joint_type_origin_axis_and_limits(cli):
    result = cli("tree", EVERY_JOINT)
    assert (result.exit_code, result.stderr) == (0, "")
    assert result.stdout == EVERY_JOINT_TREE


def test_tree_of_a_xacro_input(cli):
    result = cli("tree", TESTS / "check_xacro" / "robot.urdf.xacro", "wheel_radius:=0.07")
    assert result.exit_code == 0
    assert result.stdout == (
        "base_link\n"
        "├── caster_link  (caster_joint: fixed, xyz 0.1 0 -0.02, rpy 0 0 0)\n"
        "└── wheel_left  (wheel_left_joint: continuous, xyz 0 0 0, rpy 0 0 0, axis 0 1 0)\n")


@pytest.mark.parametrize("case, rule", [("two_parents.urdf", "E130"),
                                        ("cycle_reachable_from_root.urdf", "E131"),
                                        ("self_loop.urdf", "E132"),
                                        ("link_not_connected.urdf", "E133")])
def test_no_tree_when_the_structure_is_broken(case, rule, cli):
    result = cli("tree", BROKEN / case)
    assert result.exit_code == 1
    assert result.stdout == ""
    assert f"[{rule}]" in result.stderr
    assert result.stderr.splitlines()[-1].endswith("has no single kinematic tree")


def test_tree_ignores_problems_that_are_not_structural(cli):
    result = cli("tree", BROKEN / "box_negative_size.urdf")
    assert (result.exit_code, result.stdout, result.stderr) == (0, "base\n", "")


def test_graphviz_dot_file(cli, tmp_path):
    out = tmp_path / "diagram" / "tree.dot"
    result = cli("tree", "-q", EVERY_JOINT, "--graphviz", out)
    assert result.exit_code == 0
    assert result.stdout == ""
    assert result.stderr == f"wrote {out}\n"
    text = out.read_text()
    assert text.startswith('digraph "every_joint_type" {\n')
    assert ('  "sliding" -> "bolted" [label="fixed_joint: fixed\\nxyz 0 0 -0.05\\nrpy 0 0 0", '
            'style=dashed, color="grey50", fontcolor="grey40"];') in text.splitlines()
    assert text.count(" -> ") == 6
    assert text.count(";\n") == 3 + 7 + 6  # settings, links, joints


def test_graphviz_svg_drawn_by_dot(cli, tmp_path):
    if shutil.which("dot") is None:
        pytest.skip("Graphviz's dot is not installed (Debian package graphviz)")
    out = tmp_path / "tree.svg"
    result = cli("tree", "-q", EVERY_JOINT, "--graphviz", out)
    assert result.exit_code == 0
    svg = out.read_text()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg
    for name in ("base_link", "spinning", "prismatic_joint: prismatic"):
        assert name in svg


def test_graphviz_without_dot_writes_nothing_and_says_so(run_mcar, tmp_path):
    out = tmp_path / "tree.svg"
    out.write_text("an earlier diagram")
    # A PATH holding everything mcar needs but dot.
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    result = run_mcar("tree", "-q", EVERY_JOINT, "--graphviz", out,
                      env={"PATH": str(bin_dir)})
    assert result.returncode == 2
    assert result.stderr == (f"{out}: error: cannot draw tree.svg: the `dot` tool (Debian "
                             "package graphviz) is not installed; write a .dot file instead\n")
    assert out.read_text() == "an earlier diagram"


def test_graphviz_unknown_suffix_is_a_usage_error(cli, tmp_path):
    result = cli("tree", EVERY_JOINT, "--graphviz", tmp_path / "tree.jpeg")
    assert result.exit_code == 2
    assert "the name must end in .dot, .gv, .svg, .png, .pdf" in result.stderr
    assert not (tmp_path / "tree.jpeg").exists()


def test_tree_takes_one_input(cli):
    result = cli("tree", EVERY_JOINT, EVERY_JOINT)
    assert result.exit_code == 2
    assert result.stderr == ("mcar: error: mcar tree works on one robot, and 2 were named: "
                             "name one INPUT\n")


def test_deep_chain_needs_no_recursion():
    from mobile_car.check.tree import build_tree, check_urdf_text, rich_text
    from mobile_car.check.urdf_model import parse_xml
    from mobile_car.check.urdf_reader import read_robot

    depth = 3000  # far beyond Python's recursion limit
    text = "<robot name='c'>" + "".join(f"<link name='l{i}'/>" for i in range(depth)) + "".join(
        f"<joint name='j{i}' type='fixed'><parent link='l{i - 1}'/><child link='l{i}'/></joint>"
        for i in range(1, depth)) + "</robot>"
    tree = build_tree(read_robot(parse_xml(text.encode())))
    assert tree.is_sound and tree.root == "l0"
    lines = check_urdf_text("c", tree).splitlines()
    assert len(lines) == 3 + depth - 1
    assert lines[-1] == " " * 4 * (depth - 1) + f"child(1):  l{depth - 1}"
    assert rich_text(tree).splitlines()[-1].endswith(f"└── l{depth - 1}  (j{depth - 1}: fixed, "
                                                     "xyz 0 0 0, rpy 0 0 0)")


def test_cycle_path_and_roots():
    from mobile_car.check.tree import build_tree
    from mobile_car.check.urdf_model import parse_xml
    from mobile_car.check.urdf_reader import read_robot

    text = b"""<robot name='r'>
      <link name='base'/><link name='a'/><link name='b'/><link name='c'/><link name='stray'/>
      <joint name='1' type='fixed'><parent link='base'/><child link='a'/></joint>
      <joint name='2' type='fixed'><parent link='a'/><child link='b'/></joint>
      <joint name='3' type='fixed'><parent link='b'/><child link='c'/></joint>
      <joint name='4' type='fixed'><parent link='c'/><child link='a'/></joint>
    </robot>"""
    tree = build_tree(read_robot(parse_xml(text)))
    assert tree.cycles == [["a", "b", "c", "a"]]
    assert tree.roots == ["base", "stray"]
    assert tree.root == "base"  # the root of the bigger tree
    assert set(tree.two_parents) == {"a"}
    assert not tree.is_sound


def test_graphviz_draws_fixed_joints_apart_from_moving_ones(cli, tmp_path):
    out = tmp_path / "tree.dot"
    assert cli("tree", "-q", EVERY_JOINT, "--graphviz", out).exit_code == 0
    edges = [line for line in out.read_text().splitlines() if " -> " in line]
    fixed = [edge for edge in edges if ": fixed\\n" in edge]
    assert fixed == ['  "sliding" -> "bolted" [label="fixed_joint: fixed\\nxyz 0 0 -0.05'
                     '\\nrpy 0 0 0", style=dashed, color="grey50", fontcolor="grey40"];']
    moving = [edge for edge in edges if edge not in fixed]
    assert len(moving) == 5 and all(edge.endswith(", style=solid, penwidth=2];")
                                    for edge in moving)


def _chain_urdf(tmp_path: Path, joints: list[tuple[str, str, str]]) -> Path:
    """A URDF of ``joints`` (parent, child, type), each link defined once."""
    links = dict.fromkeys(name for parent, child, _ in joints for name in (parent, child))
    body = "".join(f'<link name="{name}"/>' for name in links)
    for parent, child, kind in joints:
        limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' \
            if kind == "revolute" else ""
        body += (f'<joint name="{child}_joint" type="{kind}"><parent link="{parent}"/>'
                 f'<child link="{child}"/>{limit}</joint>')
    path = tmp_path / "chain.urdf"
    path.write_text(f'<robot name="chain">{body}</robot>')
    return path


def test_fold_fixed_leaves_one_box_per_rigid_group_and_only_moving_joints(cli, tmp_path):
    robot = _chain_urdf(tmp_path, [("base", "plate", "fixed"), ("plate", "sensor", "fixed"),
                                   ("base", "arm", "revolute"), ("arm", "tool", "fixed"),
                                   ("tool", "finger", "revolute")])
    out = tmp_path / "folded.dot"
    result = cli("tree", "-q", robot, "--graphviz", out, "--fold-fixed")
    assert (result.exit_code, result.stderr) == (0, f"wrote {out}\n")
    lines = out.read_text().splitlines()
    assert [line for line in lines if line.startswith('  "') and " -> " not in line] == [
        '  "base" [label="base\\n+ plate\\n+ sensor"];',
        '  "arm" [label="arm\\n+ tool"];',
        '  "finger";']
    # The moving joint below a folded link starts at the box holding it.
    assert [line.split(" [")[0] for line in lines if " -> " in line] == [
        '  "base" -> "arm"', '  "arm" -> "finger"']
    assert "fixed" not in out.read_text()


def test_fold_fixed_says_how_many_more_a_big_group_holds(cli, tmp_path):
    # Children come in urdfdom's order, by joint name: letters keep it the counting order.
    robot = _chain_urdf(tmp_path, [("base", f"frame_{chr(97 + i)}", "fixed")
                                   for i in range(12)])
    out = tmp_path / "folded.dot"
    assert cli("tree", "-q", robot, "--graphviz", out, "--fold-fixed").exit_code == 0
    label = "\\n".join(["base"] + [f"+ frame_{chr(97 + i)}" for i in range(7)] + ["+ ... 5 more"])
    assert f'  "base" [label="{label}"];' in out.read_text().splitlines()


def test_fold_fixed_without_graphviz_is_a_usage_error(cli):
    result = cli("tree", EVERY_JOINT, "--fold-fixed")
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr == ("mcar: error: --fold-fixed folds the --graphviz drawing: give "
                             "--graphviz OUT too\n")
