"""The quick paths of ``mcar check`` find exactly what the full checks find.

Three shortcuts make a clean robot cheaper to check: links and joints written the usual
way are proved clean (``mobile_car.check.plain_links``, ``check_joints._plainly_sound``) instead
of going through every check with its messages, and numbers are read with ``float`` and
their spelling proved afterwards (``Reporter.numbers_confirmed``). Each test here checks
a document twice, with the shortcuts and with all of them turned off, and requires the
same diagnostics; the documents are a realistic robot, that robot with one thing broken
or oddly spelled, and the whole check corpus. The mutated robots must also really be
reported, so a test cannot pass by both ways finding nothing.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from mobile_car.check import checker, joint_skeletons, link_bodies, urdf_reader
from mobile_car.check import context as check_context
from mobile_car.check import joints as check_joints
from mobile_car.packages.search import PackageSearch

CORPUS = Path(__file__).resolve().parents[1] / "check_corpus"
BASE = CORPUS / "valid"  # meshes/cube.stl is there

ROBOT = b"""<?xml version="1.0"?>
<robot name="arm">
  <material name="grey"><color rgba="0.6 0.6 0.6 1"/></material>
  <link name="base_link"/>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.01" ixy="0.001" ixz="0" iyy="0.012" iyz="0" izz="0.004"/>
    </inertial>
    <visual name="shell">
      <origin xyz="0 0 0.1" rpy="0 1.5708 0"/>
      <geometry><cylinder radius="0.03" length="0.2"/></geometry>
      <material name="orange"><color rgba="1 0.4 0 1"/></material>
    </visual>
    <visual>
      <geometry><box size="0.05 0.05 0.02"/></geometry>
      <material name="orange"/>
    </visual>
    <collision>
      <origin xyz="0 0 0.1"/>
      <geometry><mesh filename="meshes/cube.stl" scale="5 5 10"/></geometry>
    </collision>
  </link>
  <link name="tool">
    <inertial>
      <mass value="0.2"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/>
    </inertial>
    <visual>
      <geometry><sphere radius="0.02"/></geometry>
      <material name="grey"/>
    </visual>
  </link>
  <link name="camera">
    <visual><geometry><box size="0.02 0.06 0.02"/></geometry></visual>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>
  </joint>
  <joint name="wrist" type="continuous">
    <parent link="upper"/><child link="tool"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="camera_mount" type="fixed">
    <parent link="upper"/><child link="camera"/>
  </joint>
</robot>
"""


def _check(data: bytes, quick: bool, monkeypatch, base: Path = BASE,
           large: bool = False) -> list[tuple]:
    """Every diagnostic of ``data`` as (rule, line, message), with or without shortcuts;
    with them, links are proved plain both once per skeleton (link_skeletons.py, on
    however few links, later ones given the first one's elements as twins; joints read
    by theirs, joint_skeletons.py) and link by link, and must be found alike, the
    robot's size too (the numbers each way read).
    ``large``: the rest pose worked out as for a large robot (rest_pose_arrays.py)."""
    with monkeypatch.context() as patch:
        if large:
            patch.setattr(checker, "LARGE_ROBOT", 0)
        return _check_each_way(data, quick, patch, base)


def _check_each_way(data: bytes, quick: bool, monkeypatch, base: Path) -> list[tuple]:
    if quick:
        by_skeleton = _checked(data, base, monkeypatch, skeletons_from=0)
        assert by_skeleton == _checked(data, base, monkeypatch, skeletons_from=10 ** 9)
        return by_skeleton[0]
    with monkeypatch.context() as patch:
        patch.setattr(link_bodies, "plainly_clean", lambda *args: False)
        patch.setattr(check_joints, "_plainly_sound", lambda *args: False)
        full = checker._check_document

        def never_quick(*args, quick_numbers):
            return full(*args, quick_numbers=False)

        patch.setattr(checker, "_check_document", never_quick)
        return _checked(data, base, patch, skeletons_from=10 ** 9)[0]


def _checked(data: bytes, base: Path, monkeypatch, skeletons_from: int) -> tuple:
    """(every diagnostic as (rule, line, message), the robot's extents)."""
    with monkeypatch.context() as patch:
        patch.setattr(check_context, "_CLEAN", set())  # no verdicts from earlier tests
        patch.setattr(link_bodies, "SKELETONS_FROM", skeletons_from)
        patch.setattr(link_bodies, "TWINS_FROM", skeletons_from)
        patch.setattr(urdf_reader, "SKELETONS_FROM", skeletons_from)
        result = checker.check_urdf_data(data, "robot.urdf", base=base,
                                         search=PackageSearch(origin=base / "robot.urdf"))
    return [(d.rule, d.line, d.message) for d in result.diagnostics], result.extents


def _mutated(change) -> bytes:
    root = etree.fromstring(ROBOT)
    change(root)
    return etree.tostring(root)


def test_the_robot_is_clean_and_its_links_are_proved_so_quickly(monkeypatch):
    assert _check(ROBOT, True, monkeypatch) == _check(ROBOT, False, monkeypatch) == []
    from mobile_car.check.context import Reporter
    from mobile_car.check.plain_links import plainly_clean

    root = etree.fromstring(ROBOT)
    report = Reporter("robot.urdf")
    materials = {"grey"}
    proved = [plainly_clean(link, report, materials, {"grey"}, moving=name != "camera",
                            is_root=False)
              for name in ("upper", "tool", "camera")
              for link in root.iterfind(f"link[@name='{name}']")]
    assert None not in proved and len(proved) == 3
    # What a link holds comes back read, for the rest pose (mobile_car/check/rest_pose.py).
    upper = proved[0]
    assert [(kind, shape.tag, xyz, rpy, dims) for kind, shape, xyz, rpy, dims in upper.bodies] \
        == [("visual", "cylinder", (0, 0, 0.1), (0, 1.5708, 0), (0.03, 0.2)),
            ("visual", "box", (0, 0, 0), (0, 0, 0), (0.05, 0.05, 0.02)),
            ("collision", "mesh", (0, 0, 0.1), (0, 0, 0), (5, 5, 10))]
    assert upper.inertial[1:] == (1.5, (0.01, 0.001, 0, 0.012, 0, 0.004), (0, 0, 0))
    assert materials == {"grey", "orange"}  # the colour upper's visual defines
    assert report.diagnostics == [] and report.numbers_confirmed()


def _set(path: str, attr: str, value: str):
    return lambda root: root.find(path).set(attr, value)


def _drop_attr(path: str, attr: str):
    return lambda root: root.find(path).attrib.pop(attr)


def _remove(path: str):
    return lambda root: root.find(path).getparent().remove(root.find(path))


def _append(path: str, xml: str):
    return lambda root: root.find(path).append(etree.fromstring(xml))


def _duplicate(path: str):
    def change(root):
        element = root.find(path)
        element.addnext(etree.fromstring(etree.tostring(element, with_tail=False)))
    return change


def _move_inertial_to_root(root):
    inertial = root.find("link[@name='tool']/inertial")
    root.find("link[@name='base_link']").append(inertial)


UPPER = "link[@name='upper']"
INERTIAL = f"{UPPER}/inertial"
SHELL = f"{UPPER}/visual[@name='shell']"
STRUCTURE = {
    "mass missing": _remove(f"{INERTIAL}/mass"),
    "inertia missing": _remove(f"{INERTIAL}/inertia"),
    "ixy missing": _drop_attr(f"{INERTIAL}/inertia", "ixy"),
    "mass value missing": _drop_attr(f"{INERTIAL}/mass", "value"),
    "geometry missing": _remove(f"{SHELL}/geometry"),
    "geometry empty": _remove(f"{SHELL}/geometry/cylinder"),
    "two shapes": _append(f"{SHELL}/geometry", "<box size='1 1 1'/>"),
    "unknown shape": _append(f"{UPPER}/visual[2]/geometry", "<capsule radius='1'/>"),
    "box without size": _drop_attr(f"{UPPER}/visual[2]/geometry/box", "size"),
    "cylinder without length": _drop_attr(f"{SHELL}/geometry/cylinder", "length"),
    "mesh without filename": _drop_attr(f"{UPPER}/collision/geometry/mesh", "filename"),
    "mesh not found": _set(f"{UPPER}/collision/geometry/mesh", "filename", "meshes/no.stl"),
    "unknown element in link": _append(UPPER, "<visul/>"),
    "unknown element in visual": _append(SHELL, "<colour/>"),
    "material in collision": _append(f"{UPPER}/collision", "<material name='grey'/>"),
    "unknown attribute": _set(f"{SHELL}/origin", "xzy", "0 0 0"),
    "unknown link attribute": _set(UPPER, "type", "arm"),
    "unknown geometry attribute": _set(f"{SHELL}/geometry", "kind", "x"),
    "unknown inertial attribute": _set(INERTIAL, "frame", "x"),
    "second origin": _duplicate(f"{SHELL}/origin"),
    "second inertial": _duplicate(INERTIAL),
    "second mass": _duplicate(f"{INERTIAL}/mass"),
    "child inside origin": _append(f"{SHELL}/origin", "<xyz/>"),
    "child inside a shape": _append(f"{SHELL}/geometry/cylinder", "<radius/>"),
    "material without name": _drop_attr(f"{SHELL}/material", "name"),
    "material never defined": _set(f"{UPPER}/visual[2]/material", "name", "blue"),
    "material used before its colour": lambda root: root.find(UPPER).insert(
        1, etree.fromstring("<visual><geometry><sphere radius='1'/></geometry>"
                            "<material name='orange'/></visual>")),
    "colour without rgba": _drop_attr(f"{SHELL}/material/color", "rgba"),
    "rgba above 1": _set(f"{SHELL}/material/color", "rgba", "1.5 0 0 1"),
    "rgba below 0": _set(f"{SHELL}/material/color", "rgba", "-0.1 0 0 1"),
    "moving link without inertial": _remove("link[@name='tool']/inertial"),
    "mass 0 on a moving link": _set(f"{INERTIAL}/mass", "value", "0"),
    "negative mass on a moving link": _set(f"{INERTIAL}/mass", "value", "-1"),
    "negative mass on a fixed link": _append(
        "link[@name='camera']", "<inertial><mass value='-1'/><inertia ixx='1e-4' ixy='0' "
        "ixz='0' iyy='1e-4' iyz='0' izz='1e-4'/></inertial>"),
    "rgba not 4 numbers": _set(f"{SHELL}/material/color", "rgba", "1 0 0"),
    "inertia not positive definite": _set(f"{INERTIAL}/inertia", "ixx", "-1"),
    "triangle inequality broken": lambda root: root.find(f"{INERTIAL}/inertia").attrib.update(
        {"ixx": "1", "ixy": "0", "iyy": "1", "izz": "3"}),
    "inertia on the root": _move_inertial_to_root,
    "zero box": _set(f"{UPPER}/visual[2]/geometry/box", "size", "0.05 0 0.02"),
    "negative radius": _set(f"{SHELL}/geometry/cylinder", "radius", "-0.03"),
    "mesh scale 0": _set(f"{UPPER}/collision/geometry/mesh", "scale", "1 0 1"),
    "xacro left in a value": _set(f"{SHELL}/geometry/cylinder", "radius", "${r}"),
    "origin beyond 1e6 m": _set(f"{SHELL}/origin", "xyz", "1e300 0 0"),
    "rpy beyond 1e6 rad": _set(f"{SHELL}/origin", "rpy", "0 -2e6 0"),
    "inertial origin beyond 1e6 m": _set(f"{INERTIAL}/origin", "xyz", "0 0 1.5e6"),
    "box beyond 1e6 m": _set(f"{UPPER}/visual[2]/geometry/box", "size", "1 1e7 1"),
    "cylinder beyond 1e6 m": _set(f"{SHELL}/geometry/cylinder", "length", "1e300"),
    "sphere beyond 1e6 m": _set("link[@name='tool']/visual/geometry/sphere", "radius", "2e6"),
    "mesh scale beyond 1e6": _set(f"{UPPER}/collision/geometry/mesh", "scale", "1 1 1e308"),
    "mass beyond 1e6 kg": _set(f"{INERTIAL}/mass", "value", "1e7"),
    "inertia beyond 1e18": _set(f"{INERTIAL}/inertia", "ixy", "-1e300"),
}


@pytest.mark.parametrize("name", sorted(STRUCTURE))
def test_a_broken_link_is_reported_alike_either_way(name, monkeypatch):
    data = _mutated(STRUCTURE[name])
    quick = _check(data, True, monkeypatch)
    assert quick, f"{name}: nothing reported; the mutation does not break anything"
    assert quick == _check(data, False, monkeypatch)


SHOULDER = "joint[@name='shoulder']"
WRIST = "joint[@name='wrist']"
JOINTS = {
    "unknown joint type": _set(SHOULDER, "type", "ball"),
    "no joint type": _drop_attr(SHOULDER, "type"),
    "parent link undefined": _set(f"{SHOULDER}/parent", "link", "torso"),
    "child link name empty": _set(f"{WRIST}/child", "link", ""),
    "child link name empty, as a link's": lambda root: [
        root.insert(0, etree.fromstring("<link name=''/>")),
        _set(f"{WRIST}/child", "link", "")(root)],
    "no parent element": _remove(f"{WRIST}/parent"),
    "revolute without limit": _remove(f"{SHOULDER}/limit"),
    "limit without effort": _drop_attr(f"{SHOULDER}/limit", "effort"),
    "limit lower above upper": _set(f"{SHOULDER}/limit", "lower", "2"),
    "missing upper read as 0": lambda root: [_set(f"{SHOULDER}/limit", "lower", "0.5")(root),
                                             _drop_attr(f"{SHOULDER}/limit", "upper")(root)],
    "continuous limit upside down": _append(
        WRIST, "<limit lower='1' upper='-1' effort='1' velocity='1'/>"),
    "limit velocity unreadable": _set(f"{SHOULDER}/limit", "velocity", "fast"),
    "zero axis": _set(f"{WRIST}/axis", "xyz", "0 0 0"),
    "axis without xyz": _drop_attr(f"{WRIST}/axis", "xyz"),
    "axis unreadable": _set(f"{WRIST}/axis", "xyz", "0 0"),
    "origin unreadable": _set(f"{SHOULDER}/origin", "rpy", "0 0 x"),
    "empty dynamics": _append(WRIST, "<dynamics/>"),
    "dynamics unreadable": _append(WRIST, "<dynamics damping='a lot'/>"),
    "mimic of nothing": _append(WRIST, "<mimic joint='elbow'/>"),
    "mimics itself": _append(WRIST, "<mimic joint='wrist'/>"),
    "safety controller without k_velocity": _append(
        SHOULDER, "<safety_controller soft_lower_limit='-1'/>"),
    "calibration unreadable": _append(SHOULDER, "<calibration rising='up'/>"),
    "second origin in a joint": _duplicate(f"{SHOULDER}/origin"),
    "joint origin beyond 1e6 m": _set(f"{SHOULDER}/origin", "xyz", "1e300 0 0"),
    "joint rpy beyond 1e6 rad": _set(f"{SHOULDER}/origin", "rpy", "1e7 0 0"),
    "axis beyond 1e6": _set(f"{WRIST}/axis", "xyz", "0 0 1e300"),
    "fixed joint axis beyond 1e6": _append("joint[@name='camera_mount']",
                                           "<axis xyz='1e300 0 0'/>"),
    "unknown joint attribute": _set(SHOULDER, "kind", "x"),
}


@pytest.mark.parametrize("name", sorted(JOINTS))
def test_a_broken_joint_is_reported_alike_either_way(name, monkeypatch):
    data = _mutated(JOINTS[name])
    quick = _check(data, True, monkeypatch)
    assert quick, f"{name}: nothing reported; the mutation does not break anything"
    assert quick == _check(data, False, monkeypatch)


# Written unusually but sound: the full checks decide these, and find nothing.
UNUSUAL = {
    "comment inside geometry": lambda root: root.find(f"{SHELL}/geometry").insert(
        0, etree.Comment("a note")),
    "comment inside a link": lambda root: root.find(UPPER).insert(0, etree.Comment("n")),
    "material with a texture too": _append(f"{SHELL}/material", "<texture filename='t.png'/>"),
    "material defined only by a texture": lambda root: root.find(f"{SHELL}/material").replace(
        root.find(f"{SHELL}/material/color"), etree.fromstring("<texture filename='t.png'/>")),
    "colour defined in a later link's visual": lambda root: root.find(
        "link[@name='camera']/visual").append(etree.fromstring("<material name='orange'/>")),
    "no origin anywhere": lambda root: [origin.getparent().remove(origin)
                                        for origin in root.findall("link/*/origin")],
    "fixed joint with a zero axis": _append("joint[@name='camera_mount']", "<axis xyz='0 0 0'/>"),
    "fixed joint with an axis without xyz": _append("joint[@name='camera_mount']", "<axis/>"),
    "a mimic": lambda root: root.find(WRIST).append(
        etree.fromstring("<mimic joint='shoulder' multiplier='2' offset='0.1'/>")),
    "a safety controller": _append(SHOULDER, "<safety_controller k_velocity='10'/>"),
    "continuous joint with a limit": _append(WRIST, "<limit effort='1' velocity='2'/>"),
    "limit with only effort and velocity on a revolute": lambda root: [
        root.find(f"{SHOULDER}/limit").attrib.pop(a) for a in ("lower", "upper")],
}


@pytest.mark.parametrize("name", sorted(UNUSUAL))
def test_an_unusual_sound_link_is_sound_either_way(name, monkeypatch):
    data = _mutated(UNUSUAL[name])
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch) == []


NUMBER_PLACES = {  # where a single number goes, and where a list of three
    "mass": (f"{INERTIAL}/mass", "value"),
    "ixx": (f"{INERTIAL}/inertia", "ixx"),
    "radius": (f"{SHELL}/geometry/cylinder", "radius"),
    "sphere": ("link[@name='tool']/visual/geometry/sphere", "radius"),
    "limit": ("joint[@name='shoulder']/limit", "upper"),
    "lower": ("joint[@name='shoulder']/limit", "lower"),
    "effort": ("joint[@name='shoulder']/limit", "effort"),
}
LIST_PLACES = {
    "inertial origin": (f"{INERTIAL}/origin", "xyz"),
    "visual origin": (f"{SHELL}/origin", "rpy"),
    "box": (f"{UPPER}/visual[2]/geometry/box", "size"),
    "scale": (f"{UPPER}/collision/geometry/mesh", "scale"),
    "axis": ("joint[@name='wrist']/axis", "xyz"),
    "joint origin": ("joint[@name='shoulder']/origin", "xyz"),
    "joint rpy": ("joint[@name='shoulder']/origin", "rpy"),
}
ODD_NUMBERS = ["nan", "inf", "-inf", "1e400", "1e-400", "1_0", " 1", "1 ", "0x1", "1,5", "",
               "+.5", "1.", ".e1", "1e", "\u0661", "\uff11", "1\t", "\t1", "-0", "1e+2"]
ODD_LISTS = ["1 2", "1 2 3 4", "1\t2 3", "1  2 3", " 1 2 3", "1 2 3 ", "nan 0 0", "1e400 0 0",
             "1 2 inf", "1_0 1 1", "1 \u0662 3", "1\u00a02 3", "1 2\n3", "0.1 0.1 -0.1",
             "1,2,3", "+1 -1 .5"]


@pytest.mark.parametrize("place", sorted(NUMBER_PLACES))
@pytest.mark.parametrize("text", ODD_NUMBERS, ids=repr)
def test_an_oddly_spelled_number_is_read_as_urdfdom_reads_it(place, text, monkeypatch):
    data = _mutated(_set(*NUMBER_PLACES[place], text))
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch)


@pytest.mark.parametrize("place", sorted(LIST_PLACES))
@pytest.mark.parametrize("text", ODD_LISTS, ids=repr)
def test_an_oddly_spelled_list_is_read_as_urdfdom_reads_it(place, text, monkeypatch):
    data = _mutated(_set(*LIST_PLACES[place], text))
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch)


# A link's lists are read together (Reporter.triples): two that miscount alike, one short
# and one long, make the right count between them, and must still be reported.
MISCOUNTED = {
    "origin xyz short, rpy long": lambda root: root.find(f"{SHELL}/origin").attrib.update(
        {"xyz": "0 0", "rpy": "0.1 0 1.5708 0"}),
    "inertial origin long, box short": lambda root: [
        _set(f"{INERTIAL}/origin", "xyz", "0 0 0.1 0")(root),
        _set(f"{UPPER}/visual[2]/geometry/box", "size", "0.05 0.05")(root)],
    "scale short, collision origin long": lambda root: [
        _set(f"{UPPER}/collision/geometry/mesh", "scale", "5 5")(root),
        _set(f"{UPPER}/collision/origin", "xyz", "0 0 0.1 1")(root)],
}


@pytest.mark.parametrize("name", sorted(MISCOUNTED))
def test_lists_that_miscount_each_other_out_are_reported_alike_either_way(name, monkeypatch):
    data = _mutated(MISCOUNTED[name])
    quick = _check(data, True, monkeypatch)
    assert [rule for rule, _line, _message in quick] == ["E114", "E114"]
    assert quick == _check(data, False, monkeypatch)


def test_lists_that_miscount_each_other_out_fail_the_proof_of_the_quick_reading():
    """The control: read together, the two lists do give six numbers; the proof is what
    sends the document to urdfdom's reading."""
    from mobile_car.check.context import Reporter

    report = Reporter("robot.urdf")
    assert report.triples(["0 0", "0.1 0 1.5708 0"]) == (0, 0, 0.1, 0, 1.5708, 0)
    assert not report.numbers_confirmed()
    sound = Reporter("robot.urdf")
    assert sound.triples(["0 0 0.1", "0 1.5708 0"]) == (0, 0, 0.1, 0, 1.5708, 0)
    assert sound.numbers_confirmed()


@pytest.mark.parametrize(("texts", "proved"), [
    (["0 0 0.1", "0 1.5708 0"], True), (["0  0 0.1", "0 1 0"], True),
    ([" 0 0 0.1", "0 1 0"], True), (["0 0 0.1 ", "0 1 0"], True), (["1e400 0 0"], True),
    (["0 0 0", ""], True), ([], True), (["0\t0 0.1", "0 1 0"], False),
    (["0 0 0.1\t", "0 1 0"], False), (["0 0 0.1\n"], False),
    (["0 0", "0.1 0 1.5708 0"], False)], ids=repr)
def test_lists_read_together_are_read_as_urdfdom_reads_them_or_fail_the_proof(texts, proved):
    """Read together (cut at each space), lists of three give urdfdom's numbers (a number
    beyond any bound, which the caller refuses, aside), or the proof of the quick reading
    fails and the document is read urdfdom's way."""
    from mobile_car.check.context import MAX_LENGTH, Reporter, within

    quick, strict = Reporter("robot.urdf"), Reporter("robot.urdf", quick_numbers=False)
    read, wanted = quick.triples(texts), strict.triples(texts)
    assert quick.numbers_confirmed() == proved
    if proved:
        assert read == wanted or (wanted is None and not within(read, MAX_LENGTH))


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # _check undoes its patches
@given(place=st.sampled_from(sorted(NUMBER_PLACES) + sorted(LIST_PLACES)),
       text=st.text(alphabet="0123456789.eE+- _\tnaif\u0661,", min_size=0, max_size=9))
def test_any_spelling_is_read_as_urdfdom_reads_it(place, text, monkeypatch):
    data = _mutated(_set(*{**NUMBER_PLACES, **LIST_PLACES}[place], text))
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch)


@pytest.mark.parametrize("case", sorted(CORPUS.glob("*/*.urdf")),
                         ids=lambda p: f"{p.parent.name}/{p.name}")
def test_the_check_corpus_is_reported_alike_either_way(case, monkeypatch):
    data = case.read_bytes()
    assert _check(data, True, monkeypatch, case.parent) == \
        _check(data, False, monkeypatch, case.parent)


# Links written by one macro share a skeleton (link_skeletons.py): the first one's proof
# holds for the others, whose values alone are read. A later link whose values are wrong
# must be reported as the full checks report it.
VALUE_CHANGES = ["mesh not found", "material never defined", "rgba above 1", "rgba below 0",
                 "rgba not 4 numbers", "mass 0 on a moving link",
                 "negative mass on a moving link", "inertia not positive definite",
                 "triangle inequality broken", "zero box", "negative radius",
                 "mesh scale 0", "xacro left in a value", "origin beyond 1e6 m",
                 "rpy beyond 1e6 rad", "inertial origin beyond 1e6 m", "box beyond 1e6 m",
                 "cylinder beyond 1e6 m", "mesh scale beyond 1e6", "mass beyond 1e6 kg",
                 "inertia beyond 1e18"]
MORE_VALUE_CHANGES = {
    "escaped name never defined": _set(f"{UPPER}/visual[2]/material", "name", "a&b"),
    # Serialised, the name is a&amp;b: what is defined is that text, not the name.
    "name defined only as its escaped text": lambda root: [
        root.insert(0, etree.fromstring('<material name="a&amp;amp;b"><color rgba="1 0 0 1"/>'
                                        '</material>')),
        _set(f"{UPPER}/visual[2]/material", "name", "a&b")(root)],
    "newline inside a list": _set(f"{SHELL}/origin", "xyz", "0\n0 0.1"),
    "quote inside a number": _set(f"{INERTIAL}/mass", "value", '1"5'),
    "lists miscounted": MISCOUNTED["origin xyz short, rpy long"],
}


def _repeated(change=None, copies: int = 3, prepare=None) -> bytes:
    """ROBOT (``prepare`` applied) with ``copies`` more links written as 'upper' is, before
    it (each mass its own), on revolute joints; then ``change`` applied: 'upper' is the
    last of its kind."""
    root = etree.fromstring(ROBOT)
    if prepare is not None:
        prepare(root)
    upper = root.find(UPPER)
    for number in range(copies):
        link = etree.fromstring(etree.tostring(upper))
        link.set("name", f"upper_{number}")
        link.find("inertial/mass").set("value", f"{1 + number / 10:g}")
        upper.addprevious(link)
        root.append(etree.fromstring(
            f'<joint name="turn_{number}" type="revolute"><parent link="tool"/>'
            f'<child link="upper_{number}"/><origin xyz="0 0 0.{number + 1}" rpy="0 0 0"/>'
            f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" '
            f'velocity="{number + 1}"/><dynamics damping="0.1"/></joint>'))
    if change is not None:
        change(root)
    return etree.tostring(root)


def _skeleton(link) -> str:
    return re.sub(r'"[^"]*"', '""', etree.tostring(link, encoding="unicode", with_tail=False))


@pytest.mark.parametrize("large", [False, True], ids=["rest pose", "rest pose arrays"])
def test_links_that_share_a_skeleton_are_clean_and_read_once_each(large, monkeypatch):
    data = _repeated()
    root = etree.fromstring(data)
    assert len({_skeleton(link) for link in root.iterfind("link[@name]")
                if link.get("name").startswith("upper")}) == 1
    assert len({etree.tostring(link) for link in root.iterfind("link")}) == 7  # no twins
    assert _check(data, True, monkeypatch, large=large) == \
        _check(data, False, monkeypatch, large=large) == []
    from mobile_car.check.context import Reporter
    from mobile_car.check.link_skeletons import Skeletons
    from mobile_car.check.plain_links import plainly_clean

    skeletons, report = Skeletons(), Reporter("robot.urdf")
    for link in root.iterfind("link"):
        if not link.get("name").startswith("upper"):
            continue
        text = etree.tostring(link, encoding="unicode", with_tail=False)
        by_skeleton = skeletons.clean(link, text, report, {"grey"}, {"grey"}, True, False)
        walked = plainly_clean(link, report, {"grey"}, {"grey"}, True, False)
        assert by_skeleton is not None
        assert by_skeleton.bodies == walked.bodies  # the same elements, the same numbers
        assert by_skeleton.inertial == walked.inertial
        assert by_skeleton.bodies[0][1] is walked.bodies[0][1]
    assert len(skeletons._plans) == 1


@pytest.mark.parametrize("large", [False, True], ids=["rest pose", "rest pose arrays"])
@pytest.mark.parametrize("name", VALUE_CHANGES + sorted(MORE_VALUE_CHANGES))
def test_a_link_whose_skeleton_was_proved_is_still_judged_by_its_values(name, large,
                                                                         monkeypatch):
    change = MORE_VALUE_CHANGES.get(name) or STRUCTURE[name]
    data = _repeated(change)
    root = etree.fromstring(data)
    kept, changed = root.find("link[@name='upper_0']"), root.find(UPPER)
    assert _skeleton(kept) == _skeleton(changed) or name == "quote inside a number"
    quick = _check(data, True, monkeypatch, large=large)
    assert [line for _rule, line, _message in quick
            if line is not None and line >= changed.sourceline], \
        f"{name}: nothing reported in the changed link"
    assert quick == _check(data, False, monkeypatch, large=large)


@pytest.mark.parametrize("place", sorted(name for name, (path, _attr)
                                         in {**NUMBER_PLACES, **LIST_PLACES}.items()
                                         if path.startswith(UPPER)))
@pytest.mark.parametrize("text", ["1e400", "1_0", " 1", "nan", "0x1", "1 2", "1  2 3"],
                         ids=repr)
def test_an_odd_spelling_in_a_later_link_of_a_skeleton_is_read_as_urdfdom_reads_it(
        place, text, monkeypatch):
    data = _repeated(_set(*{**NUMBER_PLACES, **LIST_PLACES}[place], text))
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch)


# Written unusually, the same skeleton notwithstanding: read link by link.
UNUSUAL_REPEATS = {
    "a quote in a comment": lambda root: root.find(UPPER).insert(
        0, etree.Comment(' a "note" ')),
    "a quote in a text": lambda root: setattr(root.find(f"{UPPER}/inertial"), "tail", ' " '),
    "a name with an escaped character": lambda root: [
        root.insert(0, etree.fromstring('<material name="a&amp;b"><color rgba="1 0 0 1"/>'
                                        '</material>')),
        _set(f"{UPPER}/visual[2]/material", "name", "a&b")(root)],
    "a namespace declared in the link": lambda root: root.find(UPPER).append(
        etree.fromstring('<visual xmlns:x="urn:x"><geometry><box size="1 1 1"/>'
                         '</geometry></visual>')),
}


@pytest.mark.parametrize("name", sorted(UNUSUAL_REPEATS))
def test_repeated_links_written_unusually_are_sound_either_way(name, monkeypatch):
    data = _repeated(UNUSUAL_REPEATS[name])
    assert _check(data, True, monkeypatch) == _check(data, False, monkeypatch)


@pytest.mark.parametrize("odd", ["comment", "text"])
def test_a_link_with_a_quote_outside_its_values_is_left_to_the_walk(odd):
    """Its values cannot be told from its quotes: not read by skeleton at all, even where
    (at its end) the quote would not shift them."""
    from mobile_car.check.context import Reporter
    from mobile_car.check.link_skeletons import Skeletons

    def clean(link):
        text = etree.tostring(link, encoding="unicode", with_tail=False)
        return Skeletons().clean(link, text, Reporter("robot.urdf"), {"grey"}, {"grey"},
                                 True, False)

    upper = etree.fromstring(ROBOT).find(UPPER)
    # Every xyz and rpy written: no value that is absent is read (from past the last).
    upper.find("visual[2]").insert(0, etree.fromstring('<origin xyz="0 0 0"/>'))
    for origin in upper.iter("origin"):
        origin.set("rpy", origin.get("rpy", "0 0 0"))
    assert clean(upper) is not None  # the control
    if odd == "comment":
        upper.append(etree.Comment(' "a note" '))
    else:
        upper[-1].tail = ' "a note" '
    assert clean(upper) is None


@pytest.mark.parametrize("large", [False, True], ids=["rest pose", "rest pose arrays"])
def test_a_message_on_a_later_link_of_a_skeleton_names_its_own_line(large, monkeypatch):
    """Sound but implausible (a mass no solid of its size has: E119, W213), the last link
    of the skeleton is named at its own lines, not at the first link's, whose elements it
    was given (its twin; not where a mesh is: its file's bounds are known by its own)."""
    box = etree.fromstring('<box size="0.1 0.1 0.2"/>')
    data = _repeated(_set(f"{INERTIAL}/mass", "value", "50000"), prepare=lambda root: (
        root.find(f"{UPPER}/collision/geometry").replace(
            root.find(f"{UPPER}/collision/geometry/mesh"), box)))
    inertial = etree.fromstring(data).find(INERTIAL)
    quick = _check(data, True, monkeypatch, large=large)
    assert [(rule, line) for rule, line, _message in quick] == \
        [("E119", inertial.find("mass").sourceline), ("W213", inertial.find("inertia").sourceline)]
    assert quick == _check(data, False, monkeypatch, large=large)


# Joints read by their skeleton (joint_skeletons.py): the last of three alike, changed.
TURN = "joint[@name='turn_2']"
JOINT_VALUE_CHANGES = {
    "limit lower above upper": lambda root: root.find(f"{TURN}/limit").attrib.update(
        {"lower": "2", "upper": "1"}),
    "velocity unreadable": _set(f"{TURN}/limit", "velocity", "fast"),
    "effort spelled with an underscore": _set(f"{TURN}/limit", "effort", "1_0"),
    "zero axis": _set(f"{TURN}/axis", "xyz", "0 0 0"),
    "axis unreadable": _set(f"{TURN}/axis", "xyz", "0 0"),
    "origin beyond 1e6 m": _set(f"{TURN}/origin", "xyz", "1e300 0 0"),
    "rpy unreadable": _set(f"{TURN}/origin", "rpy", "0 0 x"),
    "rpy infinite": _set(f"{TURN}/origin", "rpy", "0 0 1e400"),
    "dynamics unreadable": _set(f"{TURN}/dynamics", "damping", "a lot"),
    "parent undefined": _set(f"{TURN}/parent", "link", "torso"),
    "parent named with an escape": _set(f"{TURN}/parent", "link", "tool&"),
    "child empty": _set(f"{TURN}/child", "link", ""),
    "unknown type": _set(TURN, "type", "ball"),
    "name taken": _set(TURN, "name", "turn_0"),
}


@pytest.mark.parametrize("large", [False, True], ids=["rest pose", "rest pose arrays"])
@pytest.mark.parametrize("name", sorted(JOINT_VALUE_CHANGES))
def test_a_joint_read_by_its_skeleton_is_judged_by_its_values(name, large, monkeypatch):
    data = _repeated(JOINT_VALUE_CHANGES[name])
    root = etree.fromstring(data)
    kept, changed = root.find("joint[@name='turn_0']"), root.findall("joint")[-1]
    assert _skeleton(kept) == _skeleton(changed)
    quick = _check(data, True, monkeypatch, large=large)
    assert [line for _rule, line, _message in quick
            if line is not None and line >= changed.sourceline], \
        f"{name}: nothing reported at the changed joint"
    assert quick == _check(data, False, monkeypatch, large=large)


def test_joints_read_by_their_skeleton_hold_what_lxml_reads(monkeypatch):
    """Names, parts and the texts the quick proof reads, as the element-by-element
    reading has them; a joint written otherwise (a quote in a comment) is read so."""
    root = etree.fromstring(_repeated(lambda root: root.find(
        "joint[@name='turn_1']").append(etree.Comment(' "a note" '))))
    monkeypatch.setattr(urdf_reader, "SKELETONS_FROM", 0)
    by_skeleton = urdf_reader.read_robot(root).joints
    monkeypatch.setattr(urdf_reader, "SKELETONS_FROM", 10 ** 9)
    by_element = urdf_reader.read_robot(root).joints
    assert [joint.tags is not None for joint in by_skeleton] == \
        [True, True, True, True, False, True]  # shoulder, wrist, mount, turn_0, 1, 2
    for joint, control in zip(by_skeleton, by_element, strict=True):
        assert (joint.name, joint.type, joint.parent, joint.child) == \
            (control.name, control.type, control.parent, control.child)
        assert joint.parts == control.parts
        if joint.tags is not None:
            assert joint.tags == set(control.parts)
            assert joint.texts == tuple(None if part not in control.parts else
                                        control.parts[part].get(attr)
                                        for part, attr in joint_skeletons.TEXTS)
