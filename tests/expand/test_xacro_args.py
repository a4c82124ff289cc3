"""NAME:=VALUE as the ``xacro`` command reads it: the same URDF from `mcar build` as from
`xacro` for every case in xacro_args/cases.txt (empty values, private names, whitespace,
repeats). Where mcar is stricter (a word it cannot read as one argument, an argument no
file declares) it says so with exit 2 instead of dropping the word silently."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent / "xacro_args"
ROBOT = HERE / "args.urdf.xacro"
XACRO = Path(sys.executable).parent / "xacro"
CASES = [line for line in (HERE / "cases.txt").read_text().splitlines()
         if line.strip() and not line.startswith("#")]
BANNER = re.compile(r"<!-- =+ -->\n(?:<!-- \|.*\| -->\n)+<!-- =+ -->\n")


def _without_banner(text: str) -> str:
    return BANNER.sub("", text)


@pytest.mark.skipif(not XACRO.exists() and shutil.which("xacro") is None,
                    reason="the xacro command is not installed next to this Python")
@pytest.mark.parametrize("case", CASES)
def test_mcar_reads_arguments_as_the_xacro_command_does(case, run_mcar):
    words = case.split(" ; ")
    peer = subprocess.run([str(XACRO), str(ROBOT), *words], capture_output=True, text=True)
    ours = run_mcar("build", ROBOT, *words)
    assert (ours.returncode == 0) == (peer.returncode == 0), (peer.stderr, ours.stderr)
    assert peer.returncode == 0, peer.stderr
    assert _without_banner(ours.stdout) == _without_banner(peer.stdout)


@pytest.mark.parametrize("word", [":=3", "a:=b:=c", "1a:=2"])
def test_a_word_that_is_not_one_argument_is_a_usage_error(word, run_mcar):
    result = run_mcar("build", ROBOT, word)
    assert result.returncode == 2
    assert f"argument '{word}' is not of the form NAME:=VALUE" in result.stderr
