"""A name defined twice points at both places it was written (issue 30, item 4).

In a robot built from xacro, "first at line 309" named a line of the expanded URDF,
which nobody wrote. Now both places are source lines, with the macro calls that made
them: two calls of one macro with the same name are told apart by their calls. The
robot is tests/check_xacro/duplicates/; a comment ``at: NAME`` marks each line named.
"""

from __future__ import annotations

import re
from pathlib import Path

FOLDER = Path(__file__).resolve().parents[1] / "check_xacro" / "duplicates"


def _at() -> dict[str, str]:
    """Marker name -> "file:line"."""
    found = {}
    for path in sorted(FOLDER.iterdir()):
        for number, text in enumerate(path.read_text().splitlines(), start=1):
            match = re.search(r"<!-- at: (.+?) -->", text)
            if match:
                found[match.group(1)] = f"{path.name}:{number}"
    return found


def test_a_name_defined_twice_names_both_source_lines(cli, monkeypatch):
    monkeypatch.chdir(FOLDER)
    result = cli("check", "robot.urdf.xacro")
    at = _at()
    left = f"in xacro:bracket called at {at['left call']}"
    right = f"in xacro:bracket called at {at['right call']}"
    link, joint = at["bracket link"], at["bracket joint"]
    assert result.exit_code == 1
    assert result.stderr.splitlines() == [
        f"{link}: error: link 'left_bracket_link' is defined twice "
        f"(first at {link}, {left}) ({right}) [E108]",
        f"{joint}: error: joint 'left_bracket_joint' is defined twice "
        f"(first at {joint}, {left}) ({right}) [E108]",
        f"{joint}: error: link 'left_bracket_link' has two parents: it is the child of joints "
        f"'left_bracket_joint' ({joint}, {left}), 'left_bracket_joint' ({joint}, {right}) "
        f"({right}) [E130]",
        f"{at['second sensor']}: error: link 'sensor_link' is defined twice "
        f"(first at {at['first sensor']}) [E108]",
        "mcar check: 4 errors, 0 warnings in 1 file",
    ]


def test_a_plain_urdf_still_says_the_line(cli, tmp_path, monkeypatch):
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r">\n  <link name="a"/>\n  <link name="a"/>\n</robot>\n')
    monkeypatch.chdir(tmp_path)
    result = cli("check", "robot.urdf")
    assert result.exit_code == 1
    assert result.stderr.splitlines()[0] == \
        "robot.urdf:3: error: link 'a' is defined twice (first at line 2) [E108]"
