"""``mcar ci --against REV``: what the change under test does to each robot, for the report.

Each robot file of the run is compared (as ``mcar diff REV FILE`` would) with the same
file at the git revision REV, unpacked into a temporary folder; the result goes on the
item (a JUnit property) and into a markdown report. A difference is not a failure: the
CI verdict stays the build's, check's and render's. Variant items (``FILE @ variant``)
are built from a variant file that REV may not have: they are not compared.

The diff is computed on every run, never replayed from the CI record: REV moves (a
base branch gains commits) while the files under test stay the same.
"""

from __future__ import annotations

import subprocess
from dataclasses import dataclass
from pathlib import Path

from ..errors import McarError, UsageError
from ..load.inputs import RobotInput
from ..load.robot import LoadOptions, load_robot
from .pipeline import CiItem


@dataclass
class ItemDiff:
    item: CiItem
    summary: str  # the JUnit property: "3 changes", "no change", "not compared: ..."
    diff: object = None  # the RobotDiff, when both sides were compared


@dataclass(frozen=True)
class Revision:
    name: str  # as the user gave it (origin/main)
    commit: str  # the full commit id it named when the run started
    top: Path  # the top of the git work tree

    @property
    def short(self) -> str:
        return self.commit[:12]


def resolve_revision(name: str, folder: Path) -> Revision:
    """The commit ``name`` names in the repository holding ``folder``; UsageError if none."""
    from ..diff.revisions import repository_top

    top = repository_top(folder)
    if top is None:
        raise UsageError(f"--against {name}: {folder} is not in a git repository")
    result = subprocess.run(["git", "rev-parse", "--verify", "--quiet", "--end-of-options",
                             f"{name}^{{commit}}"], cwd=top, capture_output=True, text=True,
                            check=False)
    if result.returncode != 0 or not result.stdout.strip():
        raise UsageError(f"--against {name}: not a commit of the git repository {top} "
                         "(in CI, fetch it first: fetch-depth: 0)")
    return Revision(name, result.stdout.strip(), top.resolve())


def change_count(diff) -> int:
    """How many things changed: each addition, removal, rename, changed field, total and
    dimension (and the robot's own name)."""
    return (len(diff.added) + len(diff.removed) + len(diff.renamed) + len(diff.changes)
            + len(diff.changed_totals) + len(diff.dimensions or ())
            + (diff.old.name != diff.new.name))


def _summary(diff) -> str:
    count = change_count(diff)
    if not diff.changed:
        return "no change"
    return f"{count} change{'s' if count != 1 else ''}"


def diff_items(items: list[CiItem], revision: Revision, options: LoadOptions,
               tolerance: float = 1e-9) -> list[ItemDiff]:
    """Compare every item but the variants with its file at ``revision``; each item's
    ``diff`` is set to its summary."""
    from ..diff import compare, describe
    from ..diff.revisions import revision_tree

    mappings = options.overrides.mappings if options.overrides else {}
    found = []
    with revision_tree(revision.commit, revision.top) as tree:
        for item in items:
            if item.variant is not None:
                continue
            try:
                relative = item.source.resolve().relative_to(revision.top)
            except ValueError:
                found.append(ItemDiff(item, "not compared: outside the git repository"))
                continue
            old_file = tree / relative
            if not old_file.exists():
                found.append(ItemDiff(item, f"added since {revision.name}"))
                continue
            try:
                new = item.checked.loaded if item.checked is not None else \
                    load_robot(item.input, options)
                old = load_robot(RobotInput(old_file), options)
                facts = [describe(old, f"{item.label}@{revision.name}", mappings),
                         describe(new, item.label, mappings)]
            except McarError as error:
                found.append(ItemDiff(item, f"not compared: {_first_line(error)}"))
                continue
            diff = compare(*facts, tolerance)
            found.append(ItemDiff(item, _summary(diff), diff))
    for entry in found:
        entry.item.diff = entry.summary
    return found


def _first_line(error: McarError) -> str:
    text = str(error).strip().splitlines()
    return text[0] if text else type(error).__name__


def markdown_report(found: list[ItemDiff], revision: Revision) -> str:
    """The whole report: a heading, one section per changed robot, then one line for the
    unchanged ones and the files not compared."""
    from ..diff.report import markdown

    lines = [f"## mcar diff against `{revision.name}` ({revision.short})", ""]
    changed = [entry for entry in found if entry.diff is not None and entry.diff.changed]
    same = [entry.item.label for entry in found if entry.diff is not None
            and not entry.diff.changed]
    others = [entry for entry in found if entry.diff is None]
    if not changed:
        lines += ["**No robot changed.**", ""]
    for entry in changed:
        lines += [markdown(entry.diff).rstrip("\n"), ""]
    if same:
        lines += ["No change: " + ", ".join(f"`{label}`" for label in same), ""]
    lines += [f"- `{entry.item.label}`: {entry.summary}" for entry in others]
    return "\n".join(lines).rstrip("\n") + "\n"
