"""A no-op `mcar ci` (the pre-commit hook) replays its record: the same report, JUnit and
exit code, without expanding or checking anything; what changed or went missing is
built again."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

from conftest import clean_environ, mcar_process

HEAVY = ("xacro", "lxml", "numpy", "trimesh", "moderngl", "yourdfpy", "PIL", "mujoco")
MAIN = "import sys; from mobile_car.cli.main import main; sys.argv[0] = 'mcar'; main()"
EFFORT = ('effort="${motor_stall_torque}"', 'effort="0"')  # the drive's motors, none
USES_MOTOR = {"motor/test_motor.urdf", "mobile_robot.urdf", "variants/large/mobile_robot.urdf",
              "variants/small/mobile_robot.urdf"}


def run_ci(package: Path, work: Path, junit: str, trace: bool = False):
    """`mcar ci` of ``package``; ``trace``: in a new interpreter that reports each module it
    imports (`python -X importtime`), else started as run_mcar starts runs."""
    args = ["ci", str(package), "--build-dir", "out", "--render-dir", "pictures",
            "--junit-xml", junit]
    if not trace:
        return mcar_process(*args, cwd=work, timeout=300)
    return subprocess.run([sys.executable, "-X", "importtime", "-c", MAIN, *args], cwd=work,
                          env=clean_environ(), capture_output=True, text=True, timeout=300)


def report(done, work: Path, junit: str):
    """What a run showed, with times (the only thing allowed to differ) blanked."""
    stderr = [line for line in done.stderr.splitlines() if not line.startswith("import time:")]
    stderr = [re.sub(r" in \d+\.\d s$", " in T s", line) for line in stderr]
    xml = re.sub(r' time="[\d.]+"', ' time="T"', (work / junit).read_text())
    return done.returncode, done.stdout, stderr, xml


def mtimes(folder: Path) -> dict[str, int]:
    return {p.relative_to(folder).as_posix(): p.stat().st_mtime_ns
            for p in folder.rglob("*") if p.is_file()}


def test_a_no_op_ci_prints_the_same_report_without_loading_anything(package_copy, tmp_path):
    # A broken part, so that the report has diagnostics, failures and exit 1 to replay.
    wheel = package_copy / "urdf/wheel/wheel.xacro"
    wheel.write_text(wheel.read_text().replace("<visual>", "<visul>", 1)
                     .replace("</visual>", "</visul>", 1))
    first = run_ci(package_copy, tmp_path, "first.xml")
    assert first.returncode == 1, first.stderr
    assert "warning: unknown element <visul>" in first.stderr
    built = mtimes(tmp_path / "out") | mtimes(tmp_path / "pictures")

    again = run_ci(package_copy, tmp_path, "again.xml", trace=True)
    assert report(again, tmp_path, "again.xml") == report(first, tmp_path, "first.xml")
    modules = {line.split("|")[-1].strip() for line in again.stderr.splitlines()
               if line.startswith("import time:")}
    assert "mobile_car.ci.cache" in modules
    assert not {m for m in modules if m.split(".")[0] in HEAVY}
    assert mtimes(tmp_path / "out") | mtimes(tmp_path / "pictures") == built


def test_deleted_outputs_and_an_edited_part_are_built_again_and_only_they(package_copy,
                                                                          tmp_path):
    first = run_ci(package_copy, tmp_path, "first.xml")
    assert first.returncode == 0, first.stderr
    expected = report(first, tmp_path, "first.xml")
    out = tmp_path / "out"

    (out / "wheel/test_wheel.urdf").unlink()
    (tmp_path / "pictures/laser/test_laser.png").unlink()
    before = mtimes(out)
    again = run_ci(package_copy, tmp_path, "again.xml")
    assert report(again, tmp_path, "again.xml") == expected
    assert (out / "wheel/test_wheel.urdf").is_file()
    assert (tmp_path / "pictures/laser/test_laser.png").is_file()
    after = mtimes(out)
    records = {".mcar-ci.json", ".mcar-build.json"}
    assert {name for name in after if after[name] != before.get(name)} - records \
        == {"wheel/test_wheel.urdf", "laser/test_laser.urdf"}

    motor = package_copy / "urdf/motor/motor.xacro"
    motor.write_text(motor.read_text() + "<!-- edited -->\n")
    before = mtimes(out)
    edited = run_ci(package_copy, tmp_path, "edited.xml")
    assert report(edited, tmp_path, "edited.xml") == expected
    after = mtimes(out)
    records = {".mcar-ci.json", ".mcar-build.json"}
    assert {name for name in after if after[name] != before.get(name)} - records \
        == USES_MOTOR


def test_a_no_op_run_replays_the_sim_step_without_the_engine(package_copy, tmp_path):
    wheel = package_copy / "urdf/wheel/wheel.xacro"
    wheel.write_text(wheel.read_text().replace(*EFFORT))
    first = run_ci(package_copy, tmp_path, "first.xml")
    assert first.returncode == 1, first.stderr
    assert "sim drive failed" in first.stderr
    assert (tmp_path / "first.xml").read_text().count(
        '<failure message="drove short; likely cause: the motors') == 3
    again = run_ci(package_copy, tmp_path, "again.xml", trace=True)
    assert report(again, tmp_path, "again.xml") == report(first, tmp_path, "first.xml")
    modules = {line.split("|")[-1].strip() for line in again.stderr.splitlines()
               if line.startswith("import time:")}
    assert not {m for m in modules if m.split(".")[0] in HEAVY}
    # Repaired, the car is simulated again and passes.
    wheel.write_text(wheel.read_text().replace(EFFORT[1], EFFORT[0]))
    repaired = run_ci(package_copy, tmp_path, "repaired.xml")
    assert repaired.returncode == 0, repaired.stderr
