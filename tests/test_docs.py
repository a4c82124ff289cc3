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


def makefile_apt_packages() -> list[str]:
    """Every Debian package the Makefile installs: its *APT_PACKAGES lists, and what each
    target adds to them (`test: APT_PACKAGES += ...`), continuation lines joined."""
    makefile = (REPO / "Makefile").read_text().replace("\\\n", " ")
    lists = re.findall(r"^(?:[\w-]+:\s*)?\w*APT_PACKAGES\s*[:+]?=\s*(.+)$", makefile, re.M)
    return [word for words in lists for word in words.split() if not word.startswith("$(")]


def test_makefile_installs_the_debian_packages_the_readme_names():
    packages = makefile_apt_packages()
    assert {"liburdfdom-tools", "chromium", "rviz", "xvfb", "time",
            "libsdformat-dev"} <= set(packages)
    readme = (REPO / "README.md").read_text()
    section = readme.split("## Set-up on a fresh machine", 1)[1].split("\n## ", 1)[0]
    named = {word for span in re.findall(r"`([^`]+)`", section) for word in span.split()}
    missing = [package for package in packages if package not in named]
    assert not missing, f"the README's set-up section does not name {missing} (in `...`)"
