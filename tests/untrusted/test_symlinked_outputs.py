"""A checkout may come with its output folders as links (mobile_car/load/default_outputs.py).

The attack: a pull request commits ``build`` and ``renders`` (or ``build/exports``, or a
record such as ``build/.mcar-ci.json``) as links to a folder outside the checkout; the
victim's ``mcar build``, ``render`` or ``ci`` wrote URDFs, pictures, exports and records
there, replacing files of the same names. Each is refused with one line naming the link
and where it leads (exit 2), and the outside folder keeps its listing and bytes. The
controls: the same link named with ``-o`` (the user's choice) is written through, which
shows that the link does lead where the writes would go; and a link that stays inside the
checkout is followed.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROBOT = ('<robot name="r">\n  <link name="a"/>\n  <joint name="j" type="fixed"><parent '
         'link="a"/><child link="b"/></joint>\n  <link name="b"/>\n</robot>\n')
PRECIOUS = b"the user's own file, not an output\n"
RENDER = ("render", "--renderer", "raycast", "--size", "64x48")
CI = ("ci", "--no-sim", "--no-gazebo", "--renderer", "raycast")


@pytest.fixture
def layout(tmp_path):
    """A package whose robot builds to build/r.urdf and draws to renders/r.png, and a
    folder outside it holding files of those names (and others) that must survive."""
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>p</name></package>\n")
    (package / "urdf" / "r.urdf").write_text(ROBOT)
    outside = tmp_path / "outside"
    outside.mkdir()
    for name in ("r.urdf", "r.png", "index.png", ".mcar-ci.json", "victim.txt"):
        (outside / name).write_bytes(PRECIOUS)
    return package, outside


def contents(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def refusal(link: str, outside: Path, package: Path, option: str) -> str:
    return (f"{link}: error: is a link to {outside}, outside {package}, the folder mcar "
            "writes its default outputs in: nothing was written there; remove the link, "
            f"or name the output folder with {option}\n")


def errors(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines(keepends=True) if " error: " in line]


@pytest.mark.parametrize("command, folder, option", [
    (("build",), "build", "-o"), (RENDER, "renders", "-o"),
    (CI, "build", "--build-dir"), (CI, "renders", "--render-dir")])
def test_a_linked_output_folder_is_refused_and_nothing_is_written_outside(
        run_mcar, layout, command, folder, option):
    package, outside = layout
    (package / folder).symlink_to(outside)
    before = contents(outside)
    result = run_mcar(*command, cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    assert errors(result.stderr) == [refusal(folder, outside, package, option)]
    assert contents(outside) == before


def test_named_with_o_the_same_link_is_the_users_choice(run_mcar, layout):
    """The control: the link leads where the default outputs would have gone."""
    package, outside = layout
    (package / "build").symlink_to(outside)
    (package / "renders").symlink_to(outside)
    built = run_mcar("build", "-o", "build/", cwd=package)
    assert built.returncode == 0, built.stderr
    drawn = run_mcar(*RENDER, "-o", "renders/", cwd=package)
    assert drawn.returncode == 0, drawn.stderr
    assert (outside / "r.urdf").read_text().startswith("<?xml")
    assert (outside / "r.png").read_bytes().startswith(b"\x89PNG")
    assert (outside / "victim.txt").read_bytes() == PRECIOUS


def test_a_linked_export_folder_below_build_is_refused(run_mcar, layout):
    package, outside = layout
    (package / "mcar.yaml").write_text('export:\n  formats: [urdf]\n  robots: ["urdf/r.urdf"]\n')
    (package / "build").mkdir()
    (package / "build" / "exports").symlink_to(outside)
    before = contents(outside)
    result = run_mcar(*CI, "--no-render", cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    # (found when the export step writes: ci's one line for a failed step)
    shown = refusal("build/exports", outside, package, "--build-dir")
    assert errors(result.stderr) == [shown.replace(": error: ", ": ", 1).replace(
        "build/exports", "r.urdf: error: export --to urdf: build/exports", 1)]
    assert "FAILED (export)" in result.stdout
    assert contents(outside) == before
    assert (package / "build" / "r.urdf").is_file()  # what stays inside is written

    # The control: with a real folder there, the export is written into it.
    (package / "build" / "exports").unlink()
    again = run_mcar(*CI, "--no-render", cwd=package)
    assert again.returncode == 0, again.stderr
    assert (package / "build/exports/r/urdf/mcar-export.json").is_file()


@pytest.mark.parametrize("command, record, option", [
    (CI, "build/.mcar-ci.json", "--build-dir"), (("build",), "build/.mcar-build.json", "-o"),
    (RENDER, "renders/.mcar-render.json", "-o")])
def test_a_record_that_is_a_link_out_is_refused_before_any_work(run_mcar, layout, command,
                                                                 record, option):
    package, outside = layout
    (package / record).parent.mkdir()
    (package / record).symlink_to(outside / ".mcar-ci.json")
    before = contents(outside)
    result = run_mcar(*command, cwd=package)
    assert result.returncode == 2, result.stdout + result.stderr
    shown = refusal(record, outside / ".mcar-ci.json", package, option)
    assert errors(result.stderr) == [shown]
    assert contents(outside) == before
    assert os.listdir(package / record.split("/")[0]) == [record.split("/")[1]]  # no work


def test_a_link_that_stays_inside_the_package_is_followed(run_mcar, layout):
    package, outside = layout
    (package / "out" / "urdf").mkdir(parents=True)
    (package / "build").symlink_to(Path("out") / "urdf")
    before = contents(outside)
    result = run_mcar("build", cwd=package)
    assert result.returncode == 0, result.stderr
    assert "built out/urdf/r.urdf" in result.stderr
    assert (package / "out/urdf/r.urdf").read_text().startswith("<?xml")
    assert contents(outside) == before
