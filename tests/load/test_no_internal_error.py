"""No bad input in the repository's corpora reaches "internal error" through any command.

"mcar: internal error" is for bugs in mcar; every broken robot, bad xacro and bad URDF
we keep (check_corpus/broken, build_errors, load/bad) must instead end in a located
message and exit 1 or 2, from every command. And no command uses a robot that check
rejects: where check finds an error, render and ci exit 1 (or 2) too.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import TESTS

CASES = sorted([*(TESTS / "check_corpus" / "broken").glob("*.urdf"),
                *(TESTS / "build_errors").glob("*.xacro"),
                *(TESTS / "load" / "bad").glob("*.urdf")])
COMMANDS = {"build": ["-o", "out.urdf"], "check": [], "tree": [],
            "render": ["--renderer", "raycast", "--size", "160x120"],
            "ci": ["--no-render", "--no-sim", "--no-gazebo"],
            "config": []}


@pytest.mark.parametrize("case", CASES, ids=[f"{c.parent.name}/{c.name}" for c in CASES])
def test_no_bad_input_reaches_internal_error(case: Path, cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    codes = {}
    for command, extra in COMMANDS.items():
        result = cli(command, case, *extra)
        assert "internal error" not in result.stderr, (command, result.stderr)
        assert "Traceback" not in result.stderr, (command, result.stderr)
        assert result.exit_code in (0, 1, 2), (command, result.exit_code)
        codes[command] = result.exit_code
    if codes["check"]:
        assert codes["render"] and codes["ci"], codes
        assert not list(tmp_path.rglob("*.png")), "a robot check rejects was drawn"
