"""`mcar render` as a user runs it: outputs, skipping unchanged pictures, errors, exit codes."""

from __future__ import annotations

import os
import pty
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

PKG = Path(__file__).parent / "pkg"
REPO = Path(__file__).parents[2]
PICTURES = ["caster/test_caster.png", "chassis/steps/step_1_plate.png",
            "chassis/test_chassis.png", "motor/test_motor.png", "wheel/test_wheel.png"]
SMALL = ("--size", "160x120")


@pytest.fixture
def pkg_copy(tmp_path) -> Path:
    """A private copy of the test package, free to edit."""
    copy = tmp_path / "render_test_parts"
    shutil.copytree(PKG, copy)
    return copy


def tree(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_package_folder_is_mirrored_with_a_contact_sheet(cli, pkg_copy, tmp_path, px,
                                                         monkeypatch, needs_gl):
    monkeypatch.chdir(tmp_path)
    result = cli("render", pkg_copy, *SMALL)
    assert result.exit_code == 0, result.output
    assert sorted(tree(tmp_path / "renders")) == sorted(
        PICTURES + ["index.png", ".mcar-render.json"])
    assert re.fullmatch(r"5 pictures in renders: 5 rendered \+ renders/index\.png "
                        r"\(\d+\.\d\d s, OpenGL [^\n]*\)\n", result.stderr)
    assert result.stdout == ""
    for name in PICTURES:
        assert px.read_png(tmp_path / "renders" / name).shape == (120, 160, 3)
    sheet = px.read_png(tmp_path / "renders/index.png").astype(int)
    # Five thumbnails in a 3-column grid (two rows), showing each part's colour.
    assert sheet.shape[1] > 3 * 300 and sheet.shape[0] > 2 * 240
    blue = (sheet[..., 2] > sheet[..., 0] + 60) & (sheet[..., 2] > sheet[..., 1] + 40)
    orange = (sheet[..., 0] > 200) & (sheet[..., 1] > 80) & (sheet[..., 1] < 160) & (
        sheet[..., 2] < 60)
    brass = (sheet[..., 0] > 150) & (sheet[..., 1] > 110) & (sheet[..., 2] < 80) & ~orange
    assert blue.sum() > 1000 and orange.sum() > 1000 and brass.sum() > 1000


def test_second_run_skips_unchanged_pictures_and_a_mesh_change_redraws_one(
        cli, pkg_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli("render", pkg_copy, *SMALL).exit_code == 0
    first = tree(tmp_path / "renders")
    stamps = {name: (tmp_path / "renders" / name).stat().st_mtime_ns for name in PICTURES}

    again = cli("render", pkg_copy, *SMALL)
    assert again.exit_code == 0
    assert "5 pictures in renders: 0 rendered, 5 unchanged" in again.stderr
    assert tree(tmp_path / "renders") == first
    assert stamps == {n: (tmp_path / "renders" / n).stat().st_mtime_ns for n in PICTURES}

    # The motor's mesh changes (same shape, one more byte in the STL header): only the
    # motor picture depends on it.
    stl = pkg_copy / "meshes/motor.stl"
    stl.write_bytes(b"X" + stl.read_bytes()[1:])
    changed = cli("render", pkg_copy, *SMALL)
    assert "5 pictures in renders: 1 rendered, 4 unchanged" in changed.stderr

    # Other options are other pictures; --force redraws everything, to the same bytes.
    assert "5 rendered" in cli("render", pkg_copy, "--size", "161x120").stderr
    assert "5 rendered" in cli("render", pkg_copy, "--size", "161x120", "--force").stderr


def test_contact_sheet_is_the_same_from_fresh_or_stored_pictures(cli, pkg_copy, tmp_path,
                                                                 monkeypatch):
    """A lost sheet is made again from the pictures on disk, to the same bytes as when it was
    made from freshly drawn ones (full size, where the sheet's reduction matters)."""
    monkeypatch.chdir(tmp_path)
    assert cli("render", pkg_copy).exit_code == 0
    sheet = tmp_path / "renders/index.png"
    fresh = sheet.read_bytes()
    sheet.unlink()
    assert "0 rendered, 5 unchanged" in cli("render", pkg_copy).stderr
    assert sheet.read_bytes() == fresh


def test_a_picture_edited_by_hand_is_drawn_again(cli, pkg_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli("render", pkg_copy, *SMALL).exit_code == 0
    wheel = tmp_path / "renders/wheel/test_wheel.png"
    good = wheel.read_bytes()
    wheel.write_bytes(b"not a picture")
    assert "1 rendered, 4 unchanged" in cli("render", pkg_copy, *SMALL).stderr
    assert wheel.read_bytes() == good


def test_part_names_select_part_folders(cli, pkg_copy, tmp_path, monkeypatch):
    # Standing in a checkout whose package is mobile_car_description, as a user would.
    xml = pkg_copy / "package.xml"
    xml.write_text(xml.read_text().replace("render_test_parts</name>",
                                           "mobile_car_description</name>"))
    monkeypatch.chdir(pkg_copy)
    result = cli("render", "wheel", "chassis", *SMALL, "--package-path", PKG)
    assert result.exit_code == 0, result.output
    assert sorted(tree(pkg_copy / "renders")) == sorted(
        ["chassis/steps/step_1_plate.png", "chassis/test_chassis.png",
         "wheel/test_wheel.png", "index.png", ".mcar-render.json"])

    unknown = cli("render", "wheels", *SMALL, "--package-path", PKG)
    assert unknown.exit_code == 2
    assert unknown.stderr.startswith("mcar: error: no file or part named 'wheels'; parts of ")
    assert unknown.stderr.rstrip().endswith("caster, chassis, motor, wheel")


def test_one_file_with_output_and_default_output(cli, in_repo, tmp_path, px, monkeypatch):
    out = tmp_path / "car.png"
    result = cli("render", "urdf/tutorial/04_xacro.xacro", "-o", out, "--size", "120x90")
    assert result.exit_code == 0, result.output
    assert px.read_png(out).shape == (90, 120, 3)
    assert f"1 picture in {out.parent}: 1 rendered" in result.stderr
    monkeypatch.chdir(tmp_path)
    result = cli("render", REPO / "urdf/tutorial/03_color.urdf", *SMALL)
    assert result.exit_code == 0
    assert px.read_png(tmp_path / "renders/03_color.png").shape == (120, 160, 3)


def test_output_dash_writes_the_png_to_stdout(run_mcar, repo, tmp_path, quiet_renderer):
    result = subprocess.run([str(Path(sys.executable).parent / "mcar"), "render",
                             "urdf/tutorial/03_color.urdf", "-o", "-", *SMALL, "-q",
                             *quiet_renderer],
                            cwd=repo, capture_output=True, timeout=120, check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(b"\x89PNG\r\n\x1a\n") and result.stderr == b""
    assert not (tmp_path / "renders").exists()


def test_missing_mesh_is_check_s_line_naming_file_and_line(run_mcar, repo, tmp_path, px):
    """The picture is drawn, a magenta box where the mesh belongs; the warning is check's."""
    source = "tests/render/pkg/models/missing_mesh.urdf"
    result = run_mcar("render", source, "-o", tmp_path / "x.png", *SMALL, cwd=repo)
    assert result.returncode == 0, result.stderr
    lines = result.stderr.splitlines()
    assert lines[0] == (f"{source}:7: warning: mesh 'package://render_test_parts/meshes/"
                        f"no_such_mesh.stl' not found at {repo}/tests/render/pkg/meshes/"
                        "no_such_mesh.stl (package 'render_test_parts' found first in the "
                        f"package holding {source}; search order: the package holding "
                        f"{source} (render_test_parts); ROS_PACKAGE_PATH (unset); "
                        "AMENT_PREFIX_PATH (unset); the bundled mobile_car_description) [W207]")
    checked = run_mcar("check", "-q", source, cwd=repo)
    assert lines[0] in checked.stderr.splitlines()  # the very line mcar check prints
    assert "Traceback" not in result.stderr
    pixels = px.read_png(tmp_path / "x.png").astype(int)
    red, green, blue = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    assert ((red > 120) & (blue > 120) & (green < 0.5 * np.minimum(red, blue))).sum() > 50


def test_a_failed_render_keeps_the_earlier_picture(cli, pkg_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    source = pkg_copy / "urdf/wheel/test_wheel.urdf.xacro"
    out = tmp_path / "wheel.png"
    assert cli("render", source, "-o", out, *SMALL).exit_code == 0
    good = out.read_bytes()
    source.write_text(source.read_text().replace('radius="0.033"', 'radius="${nope}"'))
    result = cli("render", source, "-o", out, *SMALL)
    assert result.exit_code == 1
    assert result.stderr.startswith("render_test_parts/urdf/wheel/test_wheel.urdf.xacro:7: "
                                    "error: name 'nope' is not defined")
    assert "Traceback" not in result.stderr
    assert out.read_bytes() == good
    assert sorted(p.name for p in tmp_path.iterdir() if p.is_file()) == [
        ".mcar-render.json", "wheel.png"]


@pytest.mark.parametrize("text, said", [
    ("", "broken.urdf:1: error: not well-formed XML: Document is empty [E100]"),
    ('<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
     '<child link="b"/></joint></robot>', "broken.urdf:1: error: joint 'j': child link 'b' "
     "is not defined; add <link name=\"b\"/> or fix the name [E122]")])
def test_one_broken_robot_is_answered_before_anything_is_imported_to_draw_it(
        tmp_path, text, said):
    """No drawing process started, no numpy, trimesh, PIL or GL: the check's error and the
    summary, as when the robot failed among others."""
    from render.test_noop_render import imported_modules, run_traced

    (tmp_path / "broken.urdf").write_text(text)
    result = run_traced("render", "broken.urdf", "-o", "out/broken.png", cwd=tmp_path)
    assert result.returncode == 1
    shown = [line for line in result.stderr.splitlines() if not line.startswith("import time")]
    assert shown[0] == said
    assert re.fullmatch(r"1 picture in out: 0 rendered, 1 failed \(\d+\.\d\d s\)", shown[1])
    assert len(shown) == 2
    loaded = imported_modules(result.stderr)
    assert not loaded & {"numpy", "trimesh", "moderngl", "yourdfpy", "PIL.Image",
                         "mobile_car.render.drawing", "mobile_car.render.session"}
    assert "mobile_car.render.jobs" in loaded  # (the trace sees mcar's modules)
    assert not (tmp_path / "out").exists() or list((tmp_path / "out").iterdir()) == []


def test_a_failing_file_does_not_stop_the_others(cli, pkg_copy, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    motor = pkg_copy / "urdf/motor/test_motor.urdf.xacro"
    motor.write_text(motor.read_text().replace("motor.stl", "${gone}.stl"))
    result = cli("render", pkg_copy, *SMALL)
    assert result.exit_code == 1
    assert "5 pictures in renders: 4 rendered, 1 failed" in result.stderr
    assert re.search(r"test_motor\.urdf\.xacro:\d+: error: name 'gone' is not defined",
                     result.stderr)
    assert not (tmp_path / "renders/motor/test_motor.png").exists()
    assert (tmp_path / "renders/index.png").exists()


@pytest.mark.parametrize("args, message", [
    (["--size", "big"], "Invalid value for '--size': 'big' is not WIDTHxHEIGHT"),
    (["--size", "10x10"], "out of range"),
    (["--background", "notacolour"], "Invalid value for '--background'"),
    (["--view", "below"], "Invalid value for '--view'"),
    (["--renderer", "vulkan"], "Invalid value for '--renderer'"),
])
def test_bad_options_exit_2(cli, in_repo, args, message):
    result = cli("render", "urdf/tutorial/03_color.urdf", *args)
    assert result.exit_code == 2 and message in result.stderr


def test_missing_input_file_exits_2(cli, in_repo):
    result = cli("render", "urdf/nothing_here.urdf")
    assert result.exit_code == 2
    assert result.stderr.splitlines()[0] == "urdf/nothing_here.urdf: error: no such file"


def test_ctrl_c_exits_130_and_leaves_only_whole_pictures(cli, pkg_copy, tmp_path, monkeypatch,
                                                          px):
    from mobile_car.render import session

    real_draw = session.draw_views
    calls = []

    def interrupted_on_the_third_picture(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real_draw(*args, **kwargs)

    monkeypatch.setattr(session, "draw_views", interrupted_on_the_third_picture)
    monkeypatch.chdir(tmp_path)
    result = cli("render", pkg_copy, *SMALL)
    assert result.exit_code == 130
    assert result.stderr.endswith("mcar: interrupted\n")
    written = tree(tmp_path / "renders")
    assert sorted(written) == [".mcar-render.json", "caster/test_caster.png",
                               "chassis/steps/step_1_plate.png"]
    for name in ("caster/test_caster.png", "chassis/steps/step_1_plate.png"):
        assert px.read_png(written[name]).shape == (120, 160, 3)
    # The two finished pictures count as done for the next run.
    monkeypatch.setattr(session, "draw_views", real_draw)
    assert "3 rendered, 2 unchanged" in cli("render", pkg_copy, *SMALL).stderr


def test_quiet_prints_nothing_on_success(cli, pkg_copy, tmp_path, monkeypatch, quiet_renderer):
    monkeypatch.chdir(tmp_path)
    result = cli("render", pkg_copy, *SMALL, "-q", *quiet_renderer)
    assert result.exit_code == 0 and result.output == ""


def run_on_a_terminal(args, cwd) -> tuple[int, str]:
    """Run mcar with stderr on a pseudo-terminal; returns (exit code, what it printed)."""
    leader, follower = pty.openpty()
    process = subprocess.Popen([str(Path(sys.executable).parent / "mcar"), *map(str, args)],
                               cwd=cwd, stdout=subprocess.DEVNULL, stderr=follower)
    os.close(follower)
    chunks = []
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the terminal closes when mcar exits
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(leader)
    return process.wait(timeout=120), b"".join(chunks).decode(errors="replace")


def test_progress_bar_only_on_a_terminal(pkg_copy, tmp_path, run_mcar, quiet_renderer):
    code, printed = run_on_a_terminal(["render", pkg_copy, *SMALL, *quiet_renderer],
                                      cwd=tmp_path)
    assert code == 0
    assert "rendering" in printed and "5/5" in printed
    assert "5 pictures in renders: 5 rendered" in printed

    piped = run_mcar("render", pkg_copy, *SMALL, "--force", *quiet_renderer, cwd=tmp_path)
    assert piped.returncode == 0
    assert len(piped.stderr.splitlines()) == 1 and "rendering" not in piped.stderr


def test_help_names_views_renderer_and_packages(cli):
    result = cli("render", "--help")
    assert result.exit_code == 0
    for word in ("iso", "front", "side", "top", "--collision", "--renderer", "MCAR_RENDERER",
                 "libegl1 libegl-mesa0 libgl1-mesa-dri libgl1", "renders/index.png"):
        assert word in result.output


def test_help_does_not_import_numpy_or_gl(repo):
    code = ("import sys\n"
            "from click.testing import CliRunner\n"
            "from mobile_car.cli.main import main\n"
            "assert CliRunner().invoke(main, ['render', '--help']).exit_code == 0\n"
            "heavy = {'numpy', 'trimesh', 'moderngl', 'yourdfpy', 'PIL.Image'} & set(sys.modules)\n"
            "print(sorted(heavy))\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=60, cwd=repo / "tests", check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"


def test_a_real_ctrl_c_mid_run_exits_130_with_whole_pictures_only(pkg_copy, tmp_path, px,
                                                                  quiet_renderer):
    """SIGINT as soon as the first picture appears: four more are still to come."""
    process = subprocess.Popen(
        [str(Path(sys.executable).parent / "mcar"), "render", pkg_copy, "--size", "1600x1200",
         *quiet_renderer], cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        text=True)
    deadline = time.monotonic() + 60
    while not list((tmp_path / "renders").rglob("*.png")) and time.monotonic() < deadline:
        time.sleep(0.005)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 130, stderr
    assert stderr.endswith("mcar: interrupted\n")
    written = [p for p in (tmp_path / "renders").rglob("*") if p.is_file()]
    pictures = [p for p in written if p.suffix == ".png"]
    assert 1 <= len(pictures) < 5 and not (tmp_path / "renders/index.png").exists()
    assert all(p.suffix == ".png" or p.name == ".mcar-render.json" for p in written)
    for picture in pictures:
        assert px.read_png(picture).shape == (1200, 1600, 3)


def test_output_ending_in_a_slash_is_a_folder_and_other_formats_are_refused(
        cli, tmp_path, px, monkeypatch):
    """-o newdir/ wrote a file named newdir; -o r.jpg wrote PNG bytes into r.jpg."""
    monkeypatch.chdir(tmp_path)
    source = REPO / "urdf/tutorial/03_color.urdf"
    result = cli("render", source, "-o", "newdir/", *SMALL)
    assert result.exit_code == 0, result.output
    assert px.read_png(tmp_path / "newdir/03_color.png").shape == (120, 160, 3)
    refused = cli("render", source, "-o", "r.jpg", *SMALL)
    assert (refused.exit_code, refused.stderr) == (2, (
        "mcar: error: -o r.jpg: mcar render writes PNG pictures, not .jpg; name it r.png, "
        "or end a folder's name with /\n"))
    assert not (tmp_path / "r.jpg").exists()
