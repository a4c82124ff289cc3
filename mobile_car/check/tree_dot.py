"""The kinematic tree as a Graphviz digraph (``mcar tree --graphviz``).

Links are boxes and joints labelled edges. What moves must stand out: a robot such as PR2
has dozens of fixed joints (sensor frames, covers) around its few degrees of freedom, so
fixed joints are drawn dashed and grey, moving ones solid and bold. ``fold_fixed`` goes
further and merges each group of links held together by fixed joints into one box, named
after its top link, so that only the moving joints remain as edges.
"""

from __future__ import annotations

from ..names import shown
from .tree import KinematicTree, joint_summary

FIXED_STYLE = 'style=dashed, color="grey50", fontcolor="grey40"'
MOVING_STYLE = "style=solid, penwidth=2"
# A folded box lists the links it holds; beyond this many it says how many more.
_MAX_FOLDED_NAMES = 8


def graphviz_dot(robot_name: str, tree: KinematicTree, fold_fixed: bool = False) -> str:
    """A Graphviz digraph of a sound ``tree``, in tree order; ``fold_fixed``: one box per
    group of links joined by fixed joints, and only the moving joints as edges."""
    lines = [f"digraph {_dot_id(shown(robot_name))} {{",
             "  rankdir=TB;",
             '  node [shape=box, style="rounded", fontname="Helvetica"];',
             '  edge [fontname="Helvetica", fontsize=10];']
    order = tree.subtree(tree.root)
    head = _group_heads(tree, order) if fold_fixed else {link: link for link in order}
    members: dict[str, list[str]] = {}
    for link in order:
        members.setdefault(head[link], []).append(link)
    for top, group in members.items():
        lines.append(f"  {_dot_id(shown(top))}{_folded_label(group)};")
    for link in order:
        for joint in tree.children.get(link, ()):
            if fold_fixed and joint.type == "fixed":
                continue
            label = joint_summary(joint).replace(", ", "\n")
            style = FIXED_STYLE if joint.type == "fixed" else MOVING_STYLE
            lines.append(f"  {_dot_id(shown(head[link]))} -> {_dot_id(shown(joint.child))} "
                         f"[label={_dot_id(label)}, {style}];")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _group_heads(tree: KinematicTree, order: list[str]) -> dict[str, str]:
    """Each link's top link of its rigid group: the nearest ancestor (or itself) not
    carried by a fixed joint. ``order`` has parents before children, so one pass does."""
    head = {}
    for link in order:
        if link not in head:
            head[link] = link
        for joint in tree.children.get(link, ()):
            head[joint.child] = head[link] if joint.type == "fixed" else joint.child
    return head


def _folded_label(group: list[str]) -> str:
    """Nothing for a box of one link (its name is its label); else the links it holds."""
    if len(group) == 1:
        return ""
    names = [shown(name) for name in group[1:]]
    if len(names) > _MAX_FOLDED_NAMES:
        hidden = len(names) - _MAX_FOLDED_NAMES + 1
        names = names[:_MAX_FOLDED_NAMES - 1] + [f"... {hidden} more"]
    label = "\n".join([shown(group[0])] + [f"+ {name}" for name in names])
    return f" [label={_dot_id(label)}]"


def _dot_id(text: str) -> str:
    """A double-quoted Graphviz ID; line breaks become Graphviz's own escape."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped}"'
