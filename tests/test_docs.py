"""The README's promises: two set-up commands, and CI runs the test one."""

from __future__ import annotations

import re

from conftest import REPO


def setup_commands() -> list[str]:
    readme = (REPO / "README.md").read_text()
    section = readme.split("## Set-up on a fresh machine", 1)[1].split("\n## ", 1)[0]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    return [line.split("#")[0].strip() for line in block.splitlines() if line.strip()]


def test_readme_has_exactly_two_setup_commands():
    assert setup_commands() == ["make demo", "make test"]


def test_ci_runs_the_readme_test_command():
    lines = [line for line in (REPO / ".ci" / "run").read_text().splitlines()
             if line.strip() and not line.startswith("#") and not line.startswith(("set ", "cd "))]
    assert lines == [setup_commands()[1]]


def test_makefile_installs_the_debian_peer_the_readme_names():
    makefile = (REPO / "Makefile").read_text()
    # APT_PACKAGES := ... and the lines that add to it for every target (+=)
    apt = [package for line in re.findall(r"^APT_PACKAGES\s*[:+]=\s*(.+)$", makefile, re.M)
           for package in line.split()]
    assert "libsdformat-dev" in apt
    readme = (REPO / "README.md").read_text()
    for package in apt:
        assert package in readme, f"README does not name Debian package {package}"
