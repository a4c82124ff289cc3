"""mcar export --to usd: the OpenUSD asset urdf-usd-converter writes from mcar's bounded
copies, completed with drives, opened here with pxr after the source packages are gone:
metres, kilograms and Z-up, the URDF's total mass and moving joints, a velocity drive on
each drive wheel, the base free. The bundled car, whose base_link has no mass, is what
the converter makes no rigid body of: its children are re-hung on body_link first, in
the same places (yourdfpy's reading), and it verifies."""

from __future__ import annotations

import importlib.util
import json
import shutil

import pytest
from export.test_export_verify import REAL, _invoke, _urdf_facts
from sim.test_sim_real_robots import FOLDER, needs_folder

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("pxr") is None or
    importlib.util.find_spec("urdf_usd_converter") is None,
    reason='the usd extra is not installed (pip install "mcar[usd]")')


@pytest.fixture(scope="session")
def usd_exports(tmp_path_factory):
    """robot -> (exit code, stderr, URDF mass, moving joints, folder), sources deleted."""
    work = tmp_path_factory.mktemp("usd")
    done = {}
    for robot, (packages, path) in REAL.items() if FOLDER is not None else ():
        source = work / f"{robot}_src"
        for package in packages:
            shutil.copytree(FOLDER / package, source / package)
        built = work / f"{robot}.urdf"
        assert _invoke("build", "--package-path", source, source / path, "-o",
                       built).exit_code == 0
        given = built if path.endswith(".urdf") else source / path
        result = _invoke("export", "--package-path", source, given, "--to", "usd", "-o",
                         work / robot, "--verify")
        done[robot] = (result.exit_code, result.stderr, *_urdf_facts(built), work / robot)
        shutil.rmtree(source)
    return done


@needs_folder
@pytest.mark.parametrize("robot", sorted(REAL))
def test_a_real_robot_opens_in_pxr_with_its_packages_gone(usd_exports, robot):
    from pxr import Usd, UsdGeom, UsdPhysics

    code, stderr, mass, moving, folder = usd_exports[robot]
    assert code == 0, stderr
    assert "Status:" not in stderr  # USD's own chatter is kept off stderr
    manifest = json.loads((folder / "mcar-export.json").read_text())
    stage = Usd.Stage.Open(str(folder / manifest["robot_file"]))
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0 and UsdGeom.GetStageUpAxis(stage) == "Z"
    assert UsdPhysics.GetStageKilogramsPerUnit(stage) == 1.0
    masses = [UsdPhysics.MassAPI(p).GetMassAttr().Get() or 0.0 for p in stage.Traverse()
              if p.HasAPI(UsdPhysics.MassAPI)]
    assert sum(masses) == pytest.approx(mass, rel=1e-3)
    joints = [p for p in stage.Traverse() if p.IsA(UsdPhysics.Joint) and p.IsActive()]
    assert sorted(p.GetName() for p in joints if not p.IsA(UsdPhysics.FixedJoint)) == moving
    drive = manifest["drive"]
    for name in drive["left"] + drive["right"]:
        prim = stage.GetPrimAtPath(next(p.GetPath() for p in joints if p.GetName() == name))
        api = UsdPhysics.DriveAPI(prim, "angular")
        assert api.GetTypeAttr().Get() == "force" and api.GetDampingAttr().Get() > 0
    assert any(p.IsA(UsdGeom.Mesh) for p in stage.Traverse())
    assert all(p.HasAPI(UsdPhysics.RigidBodyAPI) for p in stage.Traverse()
               if p.HasAPI(UsdPhysics.ArticulationRootAPI))


@needs_folder
@pytest.mark.parametrize("robot, note", [
    # Jackal's own URDF joint from its empty base_link: not the converter's.
    ("jackal", "joint base_link_joint (the URDF's fixed joint from base_link, a link with "
               "nothing in it, which the converter ties to the stage)"),
    # Husky's base_link has a body: the converter adds root_joint of its own.
    ("husky", "joint root_joint (the converter's weld of the root link to the stage)"),
])
def test_the_joint_freed_for_a_floating_base_is_said_to_be_whose_it_is(usd_exports, robot,
                                                                       note):
    code, stderr, *_ = usd_exports[robot]
    assert code == 0, stderr
    assert [line for line in stderr.splitlines() if "deactivated" in line] == [
        f"mcar export: {note} deactivated: the base floats"]


@pytest.fixture(scope="module")
def car_usd(tmp_path_factory):
    """The bundled car exported to USD with --verify from a copy of its package, the
    copy then deleted: (result, folder, built URDF)."""
    from conftest import REPO

    work = tmp_path_factory.mktemp("car_usd")
    package = work / "src" / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, package / name)
    shutil.copy(REPO / "package.xml", package / "package.xml")
    built = work / "car.urdf"
    assert _invoke("build", package / "urdf/mobile_robot.xacro", "-o", built).exit_code == 0
    result = _invoke("export", package / "urdf/mobile_robot.xacro", "--to", "usd", "-o",
                     work / "usd", "--verify")
    shutil.rmtree(work / "src")
    return result, work / "usd", built


def test_the_car_whose_base_link_has_no_mass_exports_and_verifies(car_usd):
    from pxr import Usd, UsdPhysics

    result, folder, built = car_usd
    assert result.exit_code == 0, result.stderr
    assert ("joints wheel_left_joint, wheel_right_joint, caster_joint, laser_joint re-hung "
            "from base_link" in result.stderr)
    assert "verified: mass 0.70564 kg, the description's 0.70564 kg" in result.stderr
    mass, moving = _urdf_facts(built)
    stage = Usd.Stage.Open(str(folder / "mobile_robot.usda"))
    masses = [UsdPhysics.MassAPI(p).GetMassAttr().Get() or 0.0 for p in stage.Traverse()
              if p.HasAPI(UsdPhysics.MassAPI)]
    assert sum(masses) == pytest.approx(mass, rel=1e-3)
    joints = {p.GetName(): UsdPhysics.Joint(p) for p in stage.Traverse()
              if p.IsA(UsdPhysics.Joint) and p.IsActive()}
    assert sorted(n for n, j in joints.items()
                  if not j.GetPrim().IsA(UsdPhysics.FixedJoint)) == moving
    for name in moving + ["caster_joint", "laser_joint"]:  # each hangs on a body now
        body0 = stage.GetPrimAtPath(joints[name].GetBody0Rel().GetTargets()[0])
        assert body0.GetName() == "body_link" and body0.HasAPI(UsdPhysics.RigidBodyAPI)


def test_the_car_links_stay_where_the_description_puts_them(car_usd):
    import yourdfpy
    from pxr import Usd, UsdGeom

    _, folder, built = car_usd
    stage = Usd.Stage.Open(str(folder / "mobile_robot.usda"))
    urdf = yourdfpy.URDF.load(str(built), load_meshes=False)
    cache = UsdGeom.XformCache()
    checked = 0
    for prim in stage.Traverse():
        if prim.GetName() in urdf.link_map and prim.IsA(UsdGeom.Xform):
            placed = cache.GetLocalToWorldTransform(prim)
            expected = urdf.get_transform(prim.GetName(), urdf.base_link)
            assert list(placed.ExtractTranslation()) == pytest.approx(
                list(expected[:3, 3]), abs=1e-9), prim.GetName()
            rotation = [placed[c][r] for r in range(3) for c in range(3)]  # USD: row vectors
            assert rotation == pytest.approx(expected[:3, :3].ravel().tolist(), abs=1e-9)
            checked += 1
    assert checked == len(urdf.link_map)


def test_rehanging_keeps_turned_children_in_place():
    """A frame turned and shifted on its root, its massed child turned again: the
    children moved onto that child keep their world poses (yourdfpy's reading)."""
    import io

    import yourdfpy
    from lxml import etree

    from mobile_car.export.massless import rehang_on_bodies

    inertial = ('<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" '
                'ixz="0" iyz="0"/></inertial>')
    text = f"""<robot name="r"><link name="root"/><link name="frame"/>
      <link name="body">{inertial}</link><link name="arm">{inertial}</link>
      <link name="tag"><visual><geometry><box size="1 1 1"/></geometry></visual></link>
      <joint name="a" type="fixed"><parent link="root"/><child link="frame"/>
        <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 1.0"/></joint>
      <joint name="b" type="fixed"><parent link="frame"/><child link="body"/>
        <origin xyz="0.5 -0.1 0.05" rpy="1.1 0.4 -0.7"/></joint>
      <joint name="c" type="revolute"><parent link="frame"/><child link="arm"/>
        <origin xyz="-0.2 0.3 0.1" rpy="0 0.5 0.25"/><axis xyz="0 1 0"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="d" type="fixed"><parent link="frame"/><child link="tag"/></joint>
    </robot>"""
    before = yourdfpy.URDF.load(io.StringIO(text), load_meshes=False)
    root = etree.fromstring(text)
    notes = rehang_on_bodies(root)
    assert notes == ["joints c, d re-hung from frame (no mass: a frame, no body in the "
                     "converter) on body, fixed to it, in the same place"]
    assert {j.get("name"): j.find("parent").get("link") for j in root.iter("joint")} == \
        {"a": "root", "b": "frame", "c": "body", "d": "body"}
    after = yourdfpy.URDF.load(io.StringIO(etree.tostring(root, encoding="unicode")),
                               load_meshes=False)
    for config in ({"c": 0.0}, {"c": 0.7}):
        before.update_cfg(config)
        after.update_cfg(config)
        for link in ("body", "arm", "tag"):
            assert after.get_transform(link, "root") == pytest.approx(
                before.get_transform(link, "root"), abs=1e-12), link


def test_a_usd_that_weighs_nothing_fails_verify_and_writes_nothing(run_mcar, tmp_path):
    """urdf_tutorial's 06-flexible.urdf (no <inertial> anywhere) made a 0 kg USD that
    --verify passed: its mass equalled the description's 0 kg. A physics asset of no mass
    now fails; the same car with its masses verifies."""
    from sim.robot_makers import massless, two_wheeler

    (tmp_path / "ghost.urdf").write_text(massless(two_wheeler()))
    result = run_mcar("export", "ghost.urdf", "--to", "usd", "-o", "out", "--verify",
                      cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[-1] == (
        "out: error: total mass 0 kg: no rigid body of the stage has a mass (the description "
        "gives no link an <inertial> mass), so a physics engine would make every mass up "
        "from the colliders' volume")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ghost.urdf"]
    (tmp_path / "car.urdf").write_text(two_wheeler())
    control = run_mcar("export", "car.urdf", "--to", "usd", "-o", "out", "--verify",
                       cwd=tmp_path)
    assert control.returncode == 0, control.stderr
    assert "verified: mass 0.7 kg, the description's 0.7 kg" in control.stderr
