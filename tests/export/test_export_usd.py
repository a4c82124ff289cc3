"""mcar export --to usd: the OpenUSD asset urdf-usd-converter writes from mcar's bounded
copies, completed with drives, opened here with pxr after the source packages are gone:
metres, kilograms and Z-up, the URDF's total mass and moving joints, a velocity drive on
each drive wheel, the base free. The bundled car, whose base_link has no mass, is what
the converter cannot make a floating robot of: --verify refuses it, naming the joint."""

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


def test_the_car_with_a_massless_base_link_is_refused_by_verify(run_mcar, package_copy,
                                                               tmp_path):
    result = run_mcar("export", package_copy / "urdf/mobile_robot.xacro", "--to", "usd",
                      "-o", tmp_path / "usd", "--verify")
    assert result.returncode == 1
    assert result.stderr.endswith(
        "usd: error: joint wheel_left_joint moves no rigid body at /mobile_robot\n")
    assert not (tmp_path / "usd").exists()
