"""`mcar build --bundled`, outside any package, builds the description bundled in the
installed wheel: every robot file of urdf/ into build/, mirroring the tree."""

from __future__ import annotations

from lxml import etree

from tests.description.conftest import URDF, built_name


def robot_files_of_checkout() -> set[str]:
    """Built names of the checkout's robot files: .urdf files, and .xacro files whose
    <robot> has a name."""
    names = {path.relative_to(URDF).as_posix() for path in URDF.rglob("*.urdf")}
    for path in URDF.rglob("*.xacro"):
        if etree.parse(str(path)).getroot().get("name"):
            names.add(built_name(path.relative_to(URDF)).as_posix())
    return names


def test_build_without_arguments_writes_every_robot_file(run_mcar, tmp_path, built_dir):
    done = run_mcar("build", "--bundled", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout == ""
    out = tmp_path / "build"
    written = {p.relative_to(out).as_posix() for p in out.rglob("*")
               if p.is_file() and p.name != ".mcar-build.json"}  # (the build record)
    expected = robot_files_of_checkout()
    assert written == expected
    assert f"{len(expected)} of {len(expected)} files built" in done.stderr
    # The wheel carries the checkout's description, not an older copy.
    for name in sorted(expected):
        assert (out / name).read_text() == (built_dir / name).read_text(), (
            f"the installed {name} differs from the checkout's: reinstall (`make install`)")
