"""Links with the same content are checked once: never at the cost of a missed problem."""

from __future__ import annotations

import json

SAME = '<visual><geometry><box size="1 1 1"/></geometry><material name="grey"/></visual>'
BAD = '<visual><geometry><box size="1 -1 1"/></geometry></visual>'
HEAVY = ('<inertial><mass value="1"/>'
         '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>')


def _joint(name, parent, child, kind="fixed"):
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
            f'<child link="{child}"/></joint>')


ROBOT = "\n".join([
    '<robot name="repeats">',                                   # 1
    '<material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>',
    f'<link name="root">{HEAVY}</link>',                        # 3: W208, the root
    f'<link name="a">{SAME}</link>',                            # 4: clean, fixed
    f'<link name="b">{SAME}</link>',                            # 5: same content, moving: W206
    f'<link name="c" colour="red">{SAME}</link>',               # 6: same content, W202
    f'<link name="d">{BAD}</link>',                             # 7: E113
    f'<link name="e">{BAD}</link>',                             # 8: E113 again
    f'<link name="f">{HEAVY}</link>',                           # 9: as the root's, not root
    '<link name="g"><visual><geometry><box size="1 1 1"/></geometry>'
    '<material name="blue"/></visual></link>',                  # 10: W216, blue undefined yet
    '<link name="h"><visual><geometry><box size="1 1 1"/></geometry>'
    '<material name="blue"><color rgba="0 0 1 1"/></material></visual></link>',
    '<link name="i"><visual><geometry><box size="1 1 1"/></geometry>'
    '<material name="blue"/></visual></link>',                  # 12: blue defined by h now
    _joint("ja", "root", "a"), _joint("jb", "root", "b", "continuous"),
    _joint("jc", "root", "c"), _joint("jd", "root", "d"), _joint("je", "root", "e"),
    _joint("jf", "root", "f"), _joint("jg", "root", "g"), _joint("jh", "root", "h"),
    _joint("ji", "root", "i"),
    "</robot>"])


def test_repeated_link_contents_are_judged_in_their_own_role(cli, tmp_path):
    path = tmp_path / "repeats.urdf"
    path.write_text(ROBOT)
    result = cli("check", "--format", "json", path)
    found = sorted((d["rule"], d["line"]) for d in
                   json.loads(result.stdout)["files"][0]["diagnostics"])
    assert found == [("E113", 7), ("E113", 8), ("W202", 6), ("W206", 5), ("W208", 3),
                     ("W216", 10)]
    assert result.exit_code == 1
