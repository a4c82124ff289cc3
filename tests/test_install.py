"""The wheel: what it ships, and the installed `mcar` from anywhere."""

from __future__ import annotations

import subprocess
import sys
import zipfile

import pytest
from conftest import REPO


@pytest.fixture(scope="module")
def wheel_names(tmp_path_factory) -> list[str]:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", str(out),
                    str(REPO)], check=True, capture_output=True, timeout=300)
    (wheel,) = out.glob("mcar-*.whl")
    return zipfile.ZipFile(wheel).namelist()


def test_wheel_ships_the_description_and_no_top_level_cli(wheel_names):
    tops = {name.split("/")[0] for name in wheel_names}
    assert tops == {"mobile_car", next(t for t in tops if t.endswith(".dist-info"))}
    for needed in ("mobile_car/cli/main.py", "mobile_car/cli/build.py",
                   "mobile_car/description/package.xml",
                   "mobile_car/description/urdf/tutorial/04_xacro.xacro"):
        assert needed in wheel_names
    repo_urdf = {str(p.relative_to(REPO)) for p in (REPO / "urdf").rglob("*") if p.is_file()}
    shipped = {n[len("mobile_car/description/"):] for n in wheel_names
               if n.startswith("mobile_car/description/urdf/")}
    assert shipped == repo_urdf
    repo_meshes = {str(p.relative_to(REPO)) for p in (REPO / "meshes").rglob("*") if p.is_file()}
    assert repo_meshes <= {n[len("mobile_car/description/"):] for n in wheel_names}


def test_installed_mcar_runs_from_any_folder(run_mcar, tmp_path):
    result = run_mcar("--version", cwd=tmp_path)
    assert result.returncode == 0
    assert result.stdout.strip() == "mcar, version 0.1.0"
    help_text = run_mcar("--help", cwd=tmp_path).stdout
    assert "build" in help_text and "Exit codes" in help_text


def test_every_command_has_help(run_mcar):
    from mobile_car.cli.main import COMMANDS

    for name in COMMANDS:
        result = run_mcar(name, "--help")
        assert result.returncode == 0, name
        assert f"Usage: mcar {name}" in result.stdout
        assert len(result.stdout.splitlines()) > 5, f"{name} --help explains too little"


def test_library_never_uses_click_print_or_exit():
    import re

    for path in (REPO / "mobile_car").rglob("*.py"):
        text = path.read_text()
        for banned in (r"^\s*(import|from) click\b", r"(?<![\w.])print\(", r"\bsys\.exit\("):
            assert not re.search(banned, text, re.M), f"{path.relative_to(REPO)} uses {banned}"


def test_startup_does_not_import_heavy_modules(tmp_path):
    """`mcar --version` and `--help` stay fast: no numpy, trimesh, GL, xacro or lxml."""
    code = ("import sys\nfrom mobile_car.cli.main import main\n"
            "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
            "print('HEAVY:' + ','.join(m for m in ('numpy', 'trimesh', 'yourdfpy', 'moderngl',"
            " 'lxml', 'xacro', 'yaml') if m in sys.modules))")
    # cwd away from the checkout, whose source mobile_car/ (no cli/) would shadow the wheel.
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[-1] == "HEAVY:"
