"""Structure rules: names, duplicates, and the kinematic tree (two parents, cycles,
self-loops, links left out of the tree).
"""

from __future__ import annotations

from .context import Reporter
from .tree import KinematicTree
from .urdf_reader import Robot


def check_names(robot: Robot, report: Reporter) -> None:
    if not robot.links:
        report.add("E106", robot.element, "the robot has no <link>")
    groups = (("link", [(link.name, link.element) for link in robot.links]),
              ("joint", [(joint.name, joint.element) for joint in robot.joints]),
              ("material", [(m.get("name"), m) for m, _ in robot.materials]))
    for kind, named in groups:
        first_seen: dict[str, object] = {}
        for name, element in named:
            if name is None:
                report.add("E107", element, f"<{kind}> without a name=\"...\"")
            elif not name.strip():
                report.add("E107", element, f"<{kind}> with an empty name")
            elif name in first_seen:
                report.add("E108", element, f"{kind} '{name}' is defined twice (first at "
                                            f"{report.place(first_seen[name])})")
            else:
                first_seen[name] = element


MOVING_TYPES = frozenset({"revolute", "continuous", "prismatic", "floating", "planar"})


def moving_links(tree: KinematicTree) -> frozenset[str]:
    """Links carried by a joint that is not fixed: these need mass and inertia. Worked out
    once per tree: the link checks, the masses and the plausibility rules all ask (a
    hundredth of a second each on a 20,000-link tree)."""
    moving = tree.__dict__.get("_moving_links")
    if moving is None:
        moving = tree._moving_links = frozenset([
            child for child, joints in tree.parent_joints.items() for joint in joints
            if joint.type in MOVING_TYPES])
    return moving


def check_tree(robot: Robot, tree: KinematicTree, report: Reporter) -> None:
    for joint in tree.self_loops:
        report.add("E132", joint.element, f"joint '{joint.name}' connects link '{joint.parent}' "
                                          "to itself")
    line = report.line_of
    for link, joints in tree.two_parents.items():
        joints = sorted(joints, key=lambda j: line(j.element))
        names = ", ".join(f"'{j.name}' ({report.place(j.element)})" for j in joints)
        report.add("E130", joints[1].element, f"link '{link}' has two parents: it is the child "
                                              f"of joints {names}")
    for path in tree.cycles:
        edges = list(zip(path, path[1:], strict=False))
        joints = [next(j for j in tree.children[a] if j.child == b) for a, b in edges]
        first = min(joints, key=lambda j: line(j.element))
        shown = " -> ".join(path) if len(path) <= 12 else \
            " -> ".join(path[:10]) + f" -> ... ({len(path) - 1} links)"
        report.add("E131", first.element, f"joints {_names(joints)} form a cycle: {shown}")
    if tree.root is None or len(tree.roots) < 2:
        return
    # A link named as child by a joint with a broken parent is E121/E122 already.
    claimed = {j.child for j in robot.joints if j.child}
    elements = {link.name: link.element for link in robot.links}
    for root in tree.roots:
        if root == tree.root or root in claimed:
            continue
        below = len(tree.subtree(root)) - 1
        extra = f" (nor are the {below} links below it)" if below else ""
        report.add("E133", elements[root], f"link '{root}' is not connected to the tree of "
                   f"'{tree.root}': no joint has it as child{extra}")


def _names(joints) -> str:
    names = [f"'{j.name}'" for j in joints]
    return ", ".join(names) if len(names) <= 6 else ", ".join(names[:5]) + ", ..."
