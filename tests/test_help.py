"""Every command's --help explains its inputs and ends with its exit codes (the way
sqlite-utils tests its documentation against its commands): a command added without
them fails here."""

from __future__ import annotations

import re

import pytest
from mobile_car.cli.main import COMMANDS

SHARED_OPTIONS = ("--set", "--config", "--package-path", "--color / --no-color")
# The commands that load robots; init and new write packages instead.
ROBOT_COMMANDS = sorted(set(COMMANDS) - {"init", "new"})


@pytest.mark.parametrize("name", [*sorted(COMMANDS), "new part"])
def test_help_ends_with_the_exit_codes(cli, name):
    result = cli(*name.split(), "--help", terminal_width=100)
    assert result.exit_code == 0
    lines = result.output.splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip() == "Exit codes:")
    end = lines.index("", start)
    block = lines[start + 1:end]
    codes = [int(m.group(1)) for line in block if (m := re.match(r"\s+(\d+)\s", line))]
    assert codes == [0, 1, 2, 130], block
    assert block[-1].strip() == "130  interrupted (Ctrl-C); 143 terminated"
    # The codes close the description: only the option list comes after them.
    assert lines[end + 1] == "Options:"


@pytest.mark.parametrize("name", ROBOT_COMMANDS)
def test_every_command_takes_the_same_inputs_and_options(cli, name):
    text = cli(name, "--help", terminal_width=100).output
    # config takes only the words that name a package (no stdin, no NAME:=VALUE): its
    # help says so instead of the common paragraph.
    assert ("INPUT (optional) names the package whose config.xacro to show" if name == "config"
            else "INPUT is what every command takes") in text
    usage = text.splitlines()[0]
    assert "[INPUT]" in usage, usage
    for option in SHARED_OPTIONS:
        assert option in text, (name, option)


def test_the_group_help_lists_the_exit_codes(cli):
    text = cli("--help").output
    assert "Exit codes (every command):" in text and "130  interrupted" in text
