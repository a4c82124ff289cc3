"""mcar ci's export step: the folders a package's mcar.yaml asks for, verified, written
below build/exports/ for the robots its globs take (the car and its variants, not the
parts), made again on every run; a format whose engine is missing fails the step with
exit 2 and the error named."""

from __future__ import annotations

import json

CI = ("ci", "--no-render", "--no-sim", "--no-gazebo")


def test_the_package_asks_and_ci_exports_the_car_verified(run_mcar, package_copy):
    with (package_copy / "mcar.yaml").open("a") as config:  # after its ci: strict
        config.write('export:\n  formats: [mjcf, urdf]\n  robots: ["urdf/mobile_robot.xacro"]\n')
    exports = package_copy / "build" / "exports"
    for _ in (1, 2):  # the second run replaces the first run's folders
        result = run_mcar(*CI, cwd=package_copy)
        assert result.returncode == 0, result.stderr
        assert "passed (build, check --strict, export)" in result.stderr
        written = exports.glob("**/mcar-export.json")
        assert sorted(p.relative_to(exports).as_posix() for p in written) == [
            f"{robot}/{to}/mcar-export.json" for robot in
            ("mobile_robot", "variants/large/mobile_robot", "variants/small/mobile_robot")
            for to in ("mjcf", "urdf")]
    assert "mobile_robot.xacro: exported mjcf build/exports/mobile_robot/mjcf/ (0.70564 kg, " \
           "2 moving joints, verified); urdf build/exports/mobile_robot/urdf/" in result.stderr
    manifest = json.loads((exports / "mobile_robot/urdf/mcar-export.json").read_text())
    assert manifest["urdf_mass"] == manifest["model_mass"] and manifest["verified"]
    assert "package://" not in (exports / "mobile_robot/urdf/mobile_robot.urdf").read_text()
    assert (exports / "mobile_robot/mjcf/mobile_robot.xml").is_file()


def test_a_format_whose_engine_is_missing_fails_the_step(run_mcar, package_copy, tmp_path):
    (package_copy / "mcar.yaml").write_text(
        'export:\n  formats: [sdf]\n  robots: ["urdf/mobile_robot.xacro"]\n')
    result = run_mcar(*CI, "--format", "junit", cwd=package_copy,
                      env={"MCAR_SDFORMAT": str(tmp_path / "none")})
    assert result.returncode == 2
    assert result.stdout.count('<failure message="--to sdf: MCAR_SDFORMAT=') == 3
    assert 'classname="mcar.export" name="mobile_robot.xacro @ small"' in result.stdout
    assert not (package_copy / "build" / "exports").exists()
