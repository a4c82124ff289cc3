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
    first = first.replace("{HERE}", str(tmp_path)).replace("{REPO}", str(REPO))
    result = run_mcar(*words, cwd=tmp_path)
    lines = [line for line in result.stderr.splitlines() if not line.startswith("mcar: package")]
    assert (result.returncode, lines[0] if lines else "") == (code, first), result.stderr


def test_command_typo_suggests_the_command(run_mcar):
    from mobile_car.cli.main import COMMANDS

    result = run_mcar("chek")
    assert result.returncode == 2
    assert "check" in COMMANDS and "chek" not in COMMANDS
    assert result.stderr.splitlines()[-1] == (
        "Error: No such command 'chek'. Did you mean 'check'? "
        f"Commands: {', '.join(sorted(COMMANDS))}.")
