"""`mcar diff --specs`: the figures of two robots compared, asserted on the exact text,
markdown and JSON; the Sections are built by hand (what mcar specs would compute)."""

from __future__ import annotations

import json

import pytest
from markdown_it import MarkdownIt

from mobile_car.check.diagnostics import Diagnostic
from mobile_car.diff import specs
from mobile_car.specs.figures import Figure, Section

OLD = {"body.mass": (12.5, "kg", "mass"), "statics.tip.left": (24.1, "deg", "tip-over left"),
       "statics.tip.forward": (31.02, "deg", "tip-over forward"),
       "body.com": ([0.03, 0.0, 0.12], "m", "centre of mass"),
       "body.footprint": ([[0.2, -0.15], [0.2, 0.15], [-0.2, 0.15]], "m", "footprint"),
       "statics.climb": (18.0, "deg", "climb"),
       "sensors.sonar.range": ([0.02, 4.0], "m", "sonar range")}


def sections(values: dict, diagnostics=(), sources=None) -> list[Section]:
    by_part: dict[str, Section] = {}
    for key, (value, unit, label) in values.items():
        part = key.split(".")[0]
        source = (sources or {}).get(key, "collision geometry")
        by_part.setdefault(part, Section(part)).figures.append(
            Figure(key, label, value, unit, source))
    for diagnostic in diagnostics:
        by_part.setdefault("statics", Section("statics")).diagnostics.append(diagnostic)
    return list(by_part.values())


def changed(**values) -> dict:
    new = dict(OLD)
    for key, value in values.items():
        key = key.replace("__", ".")
        if value is None:
            del new[key]
        else:
            new[key] = (value, *OLD.get(key, (None, "deg", "tip-over right"))[1:])
    return new


NEW = changed(statics__tip__left=19.3, statics__tip__forward=31.04,
              body__com=[0.03, 0.01, 0.15], sensors__sonar__range=None,
              statics__tip__right=22.5)
WARNING = Diagnostic("W503", "robot.urdf", None, "tips over left on a 20° slope")


@pytest.fixture
def diff():
    return specs.compare_specs(
        sections(OLD), sections(NEW, [WARNING], {"statics.climb": "default friction 1.0"}),
        1e-9, "old.urdf", "new.urdf")


def test_the_text_names_each_changed_figure_old_to_new(diff):
    assert specs.text(diff) == (
        "Specs old.urdf → new.urdf: 3 of 6 figures changed, 1 added, 1 removed, "
        "1 new warning\n"
        "  centre of mass [0.03, 0, 0.12] m → [0.03, 0.01, 0.15] m (0, +0.01, +0.03 m)"
        "  [body.com]\n"
        "  tip-over left 24.1° → 19.3° (-4.8°)  [statics.tip.left]\n"
        "  tip-over forward 31.02° → 31.04° (+0.02°)  [statics.tip.forward]\n"
        "  added tip-over right: 22.5°  [statics.tip.right]\n"
        "  removed sonar range (was [0.02, 4] m)  [sensors.sonar.range]\n"
        "  new W503: tips over left on a 20° slope\n")


def test_equal_figures_are_no_change_whatever_their_source():
    same = specs.compare_specs(sections(OLD), sections(OLD, sources={"body.mass": "other"}))
    assert not same.changed
    assert specs.text(same) == "Specs old → new: no figure changed (7 compared)\n"


def test_the_tolerance_hides_smaller_moves(diff):
    loose = specs.compare_specs(sections(OLD), sections(NEW), 0.05)
    assert [c.key for c in loose.changes] == ["statics.tip.left", "statics.tip.right",
                                              "sensors.sonar.range"]  # not forward: 0.02°


def test_a_small_change_is_never_shown_as_zero():
    # TurtleBot3 burger to waffle: each value rounds to a different tenth, their change
    # to none
    diff = specs.compare_specs(sections(OLD), sections(changed(statics__climb=18.04)))
    assert specs.text(diff).splitlines()[1] == (
        "  climb 18° → 18.04° (+0.04°)  [statics.climb]")
    diff = specs.compare_specs(sections(changed(statics__climb=9.9434)),
                               sections(changed(statics__climb=9.9723)))
    assert specs.text(diff).splitlines()[1] == (
        "  climb 9.9° → 10° (+0.03°)  [statics.climb]")


def test_a_figure_one_side_could_not_compute_says_why():
    new = sections(changed(statics__climb=None) | {"statics.climb": (None, "deg", "climb")},
                   sources={"statics.climb": "no drive: the robot has no driven wheels"})
    diff = specs.compare_specs(sections(OLD), new)
    assert specs.text(diff).splitlines()[1] == (
        "  climb 18° → not computed (no drive: the robot has no driven wheels)  "
        "[statics.climb]")


def test_a_polygon_that_moved_says_by_how_much():
    moved = changed(body__footprint=[[0.2, -0.15], [0.25, 0.15], [-0.2, 0.15]])
    diff = specs.compare_specs(sections(OLD), sections(moved))
    assert specs.text(diff).splitlines()[1] == (
        "  footprint 3 items → 3 items (each number moved up to 0.05 m)  [body.footprint]")


def test_the_markdown_is_one_table(diff):
    document = specs.markdown(diff)
    assert document.splitlines()[:4] == [
        "#### Specs: 3 of 6 figures changed, 1 added, 1 removed, 1 new warning", "",
        "| Figure | Old | New | Change |", "|---|---|---|---|"]
    tokens = MarkdownIt().enable("table").parse(document)
    cells = [t.content for t in tokens if t.type == "inline"]
    assert cells[9:13] == ["tip-over left `statics.tip.left`", "24.1°", "19.3°", "-4.8°"]
    right = cells.index("tip-over right `statics.tip.right`")
    assert cells[right:right + 4] == ["tip-over right `statics.tip.right`", "(absent)", "22.5°",
                                      "added"]
    assert document.endswith("- new W503: tips over left on a 20° slope\n")


def test_the_json_keeps_values_and_units(diff):
    document = json.loads(json.dumps(specs.as_json(diff)))
    assert document["changed"] is True and document["compared"] == 6
    first = document["figures"][1]
    assert first == {"key": "statics.tip.left", "label": "tip-over left", "unit": "deg",
                     "status": "changed", "old": 24.1, "new": 19.3,
                     "delta": pytest.approx(-4.8), "old_source": "collision geometry",
                     "new_source": "collision geometry"}
    assert [f["status"] for f in document["figures"]] == ["changed", "changed", "changed",
                                                          "added", "removed"]
    assert document["diagnostics"] == {
        "new": [{"rule": "W503", "message": "tips over left on a 20° slope"}], "gone": []}


# mcar diff --specs, in-process, mcar specs' computation replaced by the hand-built
# Sections: the wider robot tips over left at a smaller angle.
ROBOT = """<?xml version="1.0"?>
<robot name="small">
  <link name="base_link">
    <inertial><mass value="2.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
    <visual><geometry><box size="0.4 {width} 0.1"/></geometry></visual>
  </link>
</robot>
"""


@pytest.fixture
def robots(tmp_path, monkeypatch):
    (tmp_path / "old.urdf").write_text(ROBOT.format(width="0.3"))
    (tmp_path / "new.urdf").write_text(ROBOT.format(width="0.25"))
    (tmp_path / "same.urdf").write_text(ROBOT.format(width="0.3"))

    def fake_sections(loaded, options=None):
        narrow = b'"0.4 0.25 0.1"' in loaded.urdf
        return sections(changed(statics__tip__left=19.3) if narrow else OLD)

    monkeypatch.setattr(specs, "specs_sections", fake_sections)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_diff_specs_adds_the_figures_to_the_text(cli, robots):
    result = cli("diff", "--specs", "old.urdf", "new.urdf")
    assert result.exit_code == 1
    assert result.output.endswith(
        "\nSpecs old.urdf → new.urdf: 1 of 7 figures changed\n"
        "  tip-over left 24.1° → 19.3° (-4.8°)  [statics.tip.left]\n")


def test_diff_specs_json_and_markdown(cli, robots):
    result = cli("diff", "--specs", "--format", "json", "old.urdf", "new.urdf")
    robot = json.loads(result.output)["robots"][0]
    assert robot["specs"]["figures"][0]["new"] == 19.3
    result = cli("diff", "--specs", "--format", "markdown", "old.urdf", "new.urdf")
    assert "| tip-over left `statics.tip.left` | 24.1° | 19.3° | -4.8° |" in result.output


def test_diff_without_specs_does_not_compute_them(cli, robots, monkeypatch):
    def refuse(loaded, options=None):
        raise AssertionError("computed")

    monkeypatch.setattr(specs, "specs_sections", refuse)
    result = cli("diff", "--format", "json", "old.urdf", "new.urdf")
    assert "specs" not in json.loads(result.output)["robots"][0]


def test_diff_specs_of_equal_robots_exits_0(cli, robots):
    result = cli("diff", "--specs", "old.urdf", "same.urdf")
    assert result.exit_code == 0
    assert result.output.endswith(
        "Specs old.urdf → same.urdf: no figure changed (7 compared)\n")
