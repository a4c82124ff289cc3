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


# The README is what a newcomer reads in five minutes (issue 28); the reference is docs/.
README_MAX_LINES = 300
DOCS = REPO / "docs"
_LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


def _local_links(page) -> list[str]:
    """The targets of a page's Markdown links that are files of the repository."""
    return [target for target in _LINK.findall(page.read_text(encoding="utf-8"))
            if "://" not in target and not target.startswith("mailto:")]


def test_readme_is_short():
    lines = (REPO / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines"


def test_readme_opening_list_names_every_command():
    """Every command `mcar --help` lists, each on one line of the list before the set-up."""
    from mobile_car.cli.main import COMMANDS

    readme = (REPO / "README.md").read_text(encoding="utf-8")
    opening = readme.split("## Set-up on a fresh machine", 1)[0]
    for name in COMMANDS:  # `mcar new` as `mcar new part`, its one subcommand
        lines = [line for line in opening.splitlines()
                 if re.match(rf"^(?:\| |- )`mcar {name}(?: part)?`", line)]
        assert len(lines) == 1, f"the README's opening list has no line for mcar {name}"


def test_every_link_to_a_file_reaches_it():
    for page in [REPO / "README.md", *sorted(DOCS.glob("*.md"))]:
        for target in _local_links(page):
            assert (page.parent / target).exists(), f"{page.name}: {target} does not exist"


def test_every_docs_page_is_linked_from_the_readme():
    linked = {(REPO / target).resolve() for target in _local_links(REPO / "README.md")}
    pages = set(DOCS.glob("*.md"))
    assert pages, "docs/ has no pages"
    unlinked = sorted(page.name for page in pages if page.resolve() not in linked)
    assert not unlinked, f"the README links no docs/{unlinked}"


def test_every_mcar_variable_is_documented():
    """Each MCAR_* environment variable mcar reads is on docs/limits.md."""
    source = "\n".join(path.read_text(encoding="utf-8") for folder in ("mobile_car", "cli")
                       for path in (REPO / folder).rglob("*.py"))
    read = set(re.findall(r"[\"'](MCAR_[A-Z_]+)[\"']", source)) - {"MCAR_REQUIREMENT"}
    assert {"MCAR_MAX_INPUT_MB", "MCAR_XACRO_TIMEOUT", "MCAR_DEBUG"} <= read
    page = (DOCS / "limits.md").read_text(encoding="utf-8")
    missing = sorted(name for name in read if f"`{name}" not in page)
    assert not missing, f"docs/limits.md does not document {missing}"


def test_every_docs_page_the_code_names_exists():
    """Help texts, docstrings and comments send readers to docs/ pages: each one is there
    (mcar export --help named docs/exports.md before anyone wrote it)."""
    named = set()
    for folder in ("mobile_car", "cli", "bench", "scripts", "examples"):
        for path in (REPO / folder).rglob("*"):
            if path.is_file() and path.suffix in (".py", ".yml", ".yaml", ".md", ".cc"):
                named |= set(re.findall(r"docs/[\w.-]+\.(?:md|png)",
                                        path.read_text(encoding="utf-8", errors="replace")))
    assert named
    missing = sorted(name for name in named if not (REPO / name).is_file())
    assert not missing, f"named but not there: {missing}"


def _threat_table_rows() -> list[list[str]]:
    """The rows of docs/security.md's threat-model table, each a list of its cells."""
    page = (DOCS / "security.md").read_text(encoding="utf-8")
    section = page.split("## The threat model in one table", 1)[1].split("\n## ", 1)[0]
    lines = [line for line in section.splitlines() if line.startswith("| ")]
    return [[cell.strip() for cell in line.strip("|").split(" | ")] for line in lines[1:]]


def test_every_row_of_the_threat_model_names_tests_that_exist():
    """A boundary without a test is a bug (docs/security.md): each row names at least one
    test file or folder, and each one it names is there."""
    rows = _threat_table_rows()
    assert len(rows) >= 15, "docs/security.md's threat-model table lost its rows"
    for row in rows:
        assert len(row) == 5, f"docs/security.md: a row without 5 cells: {row[0]}"
        named = re.findall(r"`(tests/[^`]+)`", row[4])
        assert named, f"docs/security.md: the row '{row[0]}' names no test"
        for target in named:
            path = REPO / target.split("::")[0]
            assert path.exists(), f"docs/security.md: the row '{row[0]}' names {target}"


def test_the_readmes_promise_about_untrusted_input_points_at_the_threat_model():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Untrusted descriptions", 1)[1].split("\n## ", 1)[0]
    assert "docs/security.md" in section
