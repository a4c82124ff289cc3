"""The edges a new user hits (issue 14), one row each in edges/cases.txt: the exit code and
the exact first line of stderr; and what a row cannot say (every line of a report)."""

from __future__ import annotations

import shlex
import shutil
from pathlib import Path

import pytest
from conftest import REPO

HERE = Path(__file__).parent / "edges"


def _cases():
    for raw in (HERE / "cases.txt").read_text().splitlines():
        if raw.strip() and not raw.startswith("#"):
            name, words, code, first = (part.strip() for part in raw.split("|", 3))
            yield pytest.param(words.replace("{REPO}", str(REPO)), int(code), first, id=name)


@pytest.mark.parametrize("words, code, first", list(_cases()))
def test_edge(run_mcar, tmp_path, words, code, first):
    shutil.copytree(HERE / "files", tmp_path, dirs_exist_ok=True)
    words = shlex.split(words.replace("{HERE}", str(tmp_path)))
    first = first.replace("{HERE}", str(tmp_path))
    result = run_mcar(*words, cwd=tmp_path)
    lines = [line for line in result.stderr.splitlines() if not line.startswith("mcar: package")]
    assert (result.returncode, lines[0] if lines else "") == (code, first), result.stderr


def test_command_typo_suggests_the_command(run_mcar):
    result = run_mcar("chek")
    assert result.returncode == 2
    assert result.stderr.splitlines()[-1] == (
        "Error: No such command 'chek'. Did you mean 'check'? "
        "Commands: build, check, ci, config, init, new, render, tree.")


def test_every_missing_mesh_is_reported_by_check_and_by_render(run_mcar, tmp_path):
    """render reported only the first of two missing meshes; it goes through check now."""
    shutil.copytree(HERE / "files", tmp_path, dirs_exist_ok=True)
    missing = [f"two_missing_meshes.urdf:{line}: warning: mesh 'meshes/{name}' not found at "
               f"{tmp_path}/meshes/{name} (a relative filename starts at the input's folder) "
               "[W207]" for line, name in ((4, "absent.dae"), (5, "gone.stl"))]
    checked = run_mcar("check", "two_missing_meshes.urdf", cwd=tmp_path)
    assert checked.stderr.splitlines() == [*missing,
                                           "mcar check: 0 errors, 2 warnings in 1 file"]
    drawn = run_mcar("render", "two_missing_meshes.urdf", "-o", "x.png", "-q", cwd=tmp_path)
    assert (drawn.returncode, drawn.stderr.splitlines()) == (1, missing)
    assert not (tmp_path / "x.png").exists()
