"""Where a new package's CI installs mcar from: the place this mcar came from, read from
its installation record (PEP 610's ``direct_url.json``), so the scaffolded GitHub
workflow works as written whenever that place can be reached from CI.

* installed from a git repository (``pip install "mcar @ git+https://..."``): the same
  repository at the same commit;
* installed from an archive URL: that URL;
* installed from a folder or file on this machine (``pip install .``, ``make install``):
  nothing CI could reach, so a marked placeholder, and a note that says what to replace;
* no record (installed from an index) or a damaged one: the placeholder too, never
  ``mcar==VERSION``: mcar is not published on PyPI, whose name ``mcar`` may belong to
  another project, so that line would fail in CI or install someone else's code.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

PLACEHOLDER = "mcar @ git+https://github.com/YOUR-ORG/mcar"
WORKFLOW = ".github/workflows/mcar.yml"  # in the new package: the file that names it


@dataclass(frozen=True)
class InstallSource:
    requirement: str       # what the workflow gives pip
    note: str | None = None  # why the requirement is a placeholder, which the user replaces


def install_source() -> InstallSource:
    """The requirement that installs this mcar in CI (see the module's docstring)."""
    import importlib.metadata

    try:
        distribution = importlib.metadata.distribution("mcar")
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return _placeholder("mcar is not installed as a package here")
    text = distribution.read_text("direct_url.json")
    if not text:
        return _placeholder("mcar has no record of where it was installed from (a package "
                            "index: mcar is not published on PyPI)")
    return source_of(text)


def source_of(direct_url: str) -> InstallSource:
    """The requirement for a PEP 610 record (``direct_url.json``'s text)."""
    try:
        record = json.loads(direct_url)
        url = record["url"]
        if not isinstance(url, str):
            raise TypeError
    except (ValueError, KeyError, TypeError):
        return _placeholder("mcar's record of where it was installed from is damaged")
    vcs = record.get("vcs_info")
    if isinstance(vcs, dict) and vcs.get("vcs") == "git" and not url.startswith("file:"):
        commit = vcs.get("commit_id")
        return InstallSource(f"mcar @ git+{url}" + (f"@{commit}" if commit else ""))
    if isinstance(record.get("archive_info"), dict) and url.startswith("https://"):
        return InstallSource(f"mcar @ {url}")
    return _placeholder(f"mcar was installed from {url}, which CI cannot reach")


def _placeholder(why: str) -> InstallSource:
    return InstallSource(PLACEHOLDER, why)


def placeholder_line(workflow: str) -> int | None:
    """The number (from 1) of the workflow's line that names the placeholder."""
    for number, line in enumerate(workflow.splitlines(), 1):
        if PLACEHOLDER in line:
            return number
    return None
