"""Every command over every input kind: the same inputs, the same refusals, the same words.

The table is tests/load/every_command.txt (its header says how to read it). Each command
runs as a user runs it, as its own process in an empty folder (started through
tests/zygote.py).
"""

from __future__ import annotations

import re
import shlex
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import REPO, clean_environ, mcar_process

HERE = Path(__file__).resolve().parent
TABLE = HERE / "every_command.txt"
COMMANDS = ("build", "check", "tree", "render", "ci", "config")
# Options that keep the run fast and its outputs inside the folder; not the subject here.
EXTRA = {"render": ["--size", "160x120"],
         "ci": ["--no-render", "--no-sim", "--no-gazebo"]}
DIAGNOSTIC = re.compile(r"^.+: (error|warning): .+ \[[EW]\d{3}\]$")


@dataclass
class Row:
    kind: str
    words: list[str]
    stdin: Path | None
    codes: dict[str, str]  # command -> "0", "2!", "1=", ...
    message: str
    line: int


def _rows() -> list[Row]:
    rows = []
    for number, text in enumerate(TABLE.read_text().splitlines(), start=1):
        if not text.strip() or text.startswith("#"):
            continue
        kind, words, codes, message = (cell.strip() for cell in text.split("|"))
        words = words.replace("{REPO}", str(REPO)).replace("{HERE}", str(HERE))
        stdin = None
        if "<" in words:
            words, _, source = words.partition("<")
            stdin = Path(source.strip())
        cells = codes.split()
        assert len(cells) == len(COMMANDS), f"every_command.txt:{number}: {len(cells)} codes"
        rows.append(Row(kind, shlex.split(words), stdin, dict(zip(COMMANDS, cells, strict=True)),
                        message.replace("{REPO}", str(REPO)), number))
    return rows


ROWS = _rows()


def run(command: str, row: Row, cwd: Path) -> subprocess.CompletedProcess:
    env = {k: v for k, v in clean_environ().items() if k != "NO_COLOR"}
    data = row.stdin.read_bytes() if row.stdin else None
    return mcar_process(command, *row.words, *EXTRA.get(command, []), cwd=cwd, input=data,
                        env=env, timeout=180, text=False)


@pytest.mark.parametrize("row", ROWS, ids=[f"{r.line}-{r.kind}" for r in ROWS])
def test_every_command_takes_and_refuses_the_same(row, tmp_path):
    results = {}
    for command in COMMANDS:
        folder = tmp_path / command
        folder.mkdir()
        results[command] = run(command, row, folder)
    shown = {command: (result.returncode, result.stderr.decode(errors="replace"))
             for command, result in results.items()}
    got = {command: code for command, (code, _) in shown.items()}
    expected = {command: int(cell.rstrip("!=")) for command, cell in row.codes.items()}
    assert got == expected, f"every_command.txt:{row.line}: " + "\n".join(
        f"{command}: {err.strip()[:300]}" for command, (_, err) in shown.items())
    for command, (_, err) in shown.items():
        assert "Traceback" not in err and "internal error" not in err, (command, err)

    refusing = [c for c, cell in row.codes.items() if cell.endswith("!")]
    first_lines = {c: shown[c][1].splitlines()[0] if shown[c][1] else "" for c in refusing}
    for command, line in first_lines.items():
        assert line.startswith(row.message), (command, line)
    assert len(set(first_lines.values())) <= 1, first_lines

    same_as_check = [c for c, cell in row.codes.items() if cell.endswith("=")]
    if same_as_check:
        def diagnostics(err: str) -> list[str]:
            return [line for line in err.splitlines() if DIAGNOSTIC.match(line)]

        reference = diagnostics(shown["check"][1])
        assert any(": error: " in line for line in reference)
        for command in same_as_check:
            assert diagnostics(shown[command][1]) == reference, command
        assert not list(tmp_path.rglob("*.png")), "a rejected robot was drawn"
    if row.kind == "bad":
        expected_rules = re.findall(r"<!-- expect: (\w+) -->", row.words[0] and
                                    Path(row.words[0]).read_text())
        found = re.findall(r"\[(\w+)\]$", shown["check"][1], re.M)
        assert sorted(found) == sorted(expected_rules)
