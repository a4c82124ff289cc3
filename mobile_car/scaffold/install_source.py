"""Where a new package's CI installs mcar from: the place this mcar came from, read from
its installation record (PEP 610's ``direct_url.json``), so the scaffolded GitHub
workflow works as written whenever that place can be reached from CI.

* installed from a git repository (``pip install "mcar @ git+https://..."``): the same
  repository at the same commit;
* installed from an archive URL: that URL;
* installed from an index (no record): ``mcar==VERSION``;
* installed from a folder or file on this machine (``pip install .``, ``make install``):
  nothing CI could reach, so a marked placeholder, and a note that says what to replace.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

PLACEHOLDER = "mcar @ git+https://github.com/YOUR-ORG/mcar"


@dataclass(frozen=True)
class InstallSource:
    requirement: str       # what the workflow gives pip
    note: str | None = None  # what the user must do, when the requirement is a placeholder


def install_source() -> InstallSource:
    """The requirement that installs this mcar in CI (see the module's docstring)."""
    import importlib.metadata

    try:
        distribution = importlib.metadata.distribution("mcar")
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return _placeholder("mcar is not installed as a package here")
    text = distribution.read_text("direct_url.json")
    if not text:
        return InstallSource(f"mcar=={distribution.version}")
    return source_of(text, distribution.version)


def source_of(direct_url: str, version: str) -> InstallSource:
    """The requirement for a PEP 610 record (``direct_url.json``'s text)."""
    try:
        record = json.loads(direct_url)
        url = record["url"]
    except (ValueError, KeyError, TypeError):
        return InstallSource(f"mcar=={version}")
    vcs = record.get("vcs_info")
    if isinstance(vcs, dict) and vcs.get("vcs") == "git" and not url.startswith("file:"):
        commit = vcs.get("commit_id")
        return InstallSource(f"mcar @ git+{url}" + (f"@{commit}" if commit else ""))
    if isinstance(record.get("archive_info"), dict) and url.startswith("https://"):
        return InstallSource(f"mcar @ {url}")
    return _placeholder(f"mcar was installed from {url}, which CI cannot reach")


def _placeholder(why: str) -> InstallSource:
    return InstallSource(PLACEHOLDER, f"{why}: in .github/workflows/mcar.yml, replace "
                                      f"'{PLACEHOLDER}' with where your CI installs mcar from")
