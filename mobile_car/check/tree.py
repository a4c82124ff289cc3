"""The kinematic tree of a robot: root, children, and what keeps it from being a tree.

Children are ordered as urdfdom orders them: by joint name (urdfdom keeps joints in a
``std::map``, so byte order of the UTF-8 names, which is Python's ``str`` order), not
by their order in the file. Every walk here is iterative: a 100,000-link chain or a
cycle can neither overflow the stack nor loop.

Two views of a sound tree: :func:`check_urdf_text` (byte for byte what ``check_urdf``
prints) and :func:`rich_text` (joints with type, origin, axis, limits); the Graphviz
diagram is :mod:`.tree_dot`'s. Both grow with the square of a chain's depth (its
indentation), so each is also a generator of lines, :func:`check_urdf_lines` and
:func:`rich_lines`, that the command writes as they come: the whole text is never held.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator
from operator import attrgetter

from ..names import shown
from .urdf_model import axis_of, first_child, origin_of, parse_number
from .urdf_reader import Joint, Robot


class KinematicTree:
    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, links: list[str], root: str | None, roots: list[str],
                 children: dict[str, list[Joint]], parent_joints: dict[str, list[Joint]],
                 self_loops: list[Joint] | None = None, cycles: list[list[str]] | None = None):
        self.links = links  # defined link names, document order
        self.root = root  # the root urdfdom would pick, or the biggest tree's
        self.roots = roots  # every link with no parent joint, by name
        self.children = children  # parent link -> joints to its children, urdfdom order
        self.parent_joints = parent_joints  # child link -> joints naming it as child
        self.self_loops = [] if self_loops is None else self_loops
        self.cycles = [] if cycles is None else cycles  # each a closed path: a, b, ..., a

    @property
    def two_parents(self) -> dict[str, list[Joint]]:
        # Worked out once (nothing changes a tree once built): a check asks five times,
        # each a pass over every link of the robot.
        found = self.__dict__.get("_two_parents")
        if found is None:
            found = self._two_parents = {link: joints for link, joints
                                         in self.parent_joints.items() if len(joints) > 1}
        return found

    @property
    def is_sound(self) -> bool:
        return (self.root is not None and len(self.roots) == 1 and not self.self_loops
                and not self.cycles and not self.two_parents)

    def subtree(self, start: str) -> list[str]:
        """Links reachable from ``start`` (itself first), each once, in urdfdom's print order."""
        order, seen, stack = [], {start}, [start]
        while stack:
            link = stack.pop()
            order.append(link)
            for joint in reversed(self.children.get(link, ())):
                if joint.child not in seen:
                    seen.add(joint.child)
                    stack.append(joint.child)
        return order


def build_tree(robot: Robot) -> KinematicTree:
    """The tree of the joints whose parent and child are defined links."""
    links = [link.name for link in robot.links if link.name is not None]
    defined = set(links)
    usable = [j for j in robot.joints
              if j.name is not None and j.parent in defined and j.child in defined]
    usable.sort(key=attrgetter("name"))
    children: dict[str, list[Joint]] = defaultdict(list)
    parent_joints: dict[str, list[Joint]] = defaultdict(list)
    self_loops = []
    for joint in usable:
        parent_joints[joint.child].append(joint)
        if joint.parent == joint.child:
            self_loops.append(joint)
        else:
            children[joint.parent].append(joint)
    roots = sorted({name for name in links if name not in parent_joints})
    tree = KinematicTree(links=links, root=None, roots=roots, children=dict(children),
                         parent_joints=dict(parent_joints), self_loops=self_loops)
    reached: set[str] = set()
    sizes = {}
    for root in roots:
        below = tree.subtree(root)
        reached.update(below)
        sizes[root] = len(below)
    if len(roots) == 1:
        tree.root = roots[0]
    elif roots:
        # urdfdom refuses two roots; naming the biggest tree's root makes the others the
        # "not connected" ones, which is what a user means by a stray link.
        position = {name: i for i, name in enumerate(links)}
        tree.root = max(roots, key=lambda r: (sizes[r], -position[r]))
    # Without a link of two parents, a cycle cannot be reached from a root: look only
    # at what no root reaches.
    suspects = links if tree.two_parents else [n for n in links if n not in reached]
    tree.cycles = _cycles(suspects, tree.children)
    return tree


def _cycles(nodes: list[str], children: dict[str, list[Joint]]) -> list[list[str]]:
    """One closed path per strongly connected component of more than one link (Tarjan)."""
    wanted = set(nodes)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components = []
    for start in nodes:
        if start in index:
            continue
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        work = [(start, iter(children.get(start, ())))]
        while work:
            node, edges = work[-1]
            for joint in edges:
                nxt = joint.child
                if nxt not in wanted:
                    continue
                if nxt not in index:
                    index[nxt] = low[nxt] = len(index)
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(children.get(nxt, ()))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        components.append(_closed_path(component, children))
    return components


def _closed_path(component: list[str], children: dict[str, list[Joint]]) -> list[str]:
    """A cycle inside a strongly connected component, as link names a, b, ..., a, starting
    from the member found last by the search, which is the first one in the file."""
    start = component[-1]
    component = set(component)
    path, seen = [start], {start: 0}
    node = start
    while True:
        node = next(j.child for j in children[node] if j.child in component)
        if node in seen:
            return path[seen[node]:] + [node]
        seen[node] = len(path)
        path.append(node)


def check_urdf_text(robot_name: str, tree: KinematicTree) -> str:
    """What ``check_urdf`` prints on stdout for a sound robot, byte for byte."""
    return b"".join(check_urdf_lines(robot_name, tree)).decode("utf-8")


def check_urdf_lines(robot_name: str, tree: KinematicTree) -> Iterator[bytes]:
    """:func:`check_urdf_text` line by line, each line UTF-8 with its newline.

    The text of a deep chain grows with the square of its depth: each generation is
    indented four more spaces, so a 10,000-link chain prints 200 MB, nearly all of it
    spaces. It is therefore made as it is written, one line at a time: what is held is
    one shared run of spaces and the walk's stack, never the text.
    """
    root = tree.root
    kids = {link: [joint.child for joint in joints] for link, joints in tree.children.items()}
    # Names escaped (a no-op for every name check_urdf could print cleanly): "&#13;" or a
    # C1 control in a link name must not rewrite the terminal (see mobile_car.names).
    yield f"robot name is: {shown(robot_name)}\n".encode()
    yield b"---------- Successfully Parsed XML ---------------\n"
    yield f"root Link: {shown(root)} has {len(kids.get(root, ()))} child(ren)\n".encode()
    spaces = memoryview(b" " * 4096)
    # A stack of iterators over (number, child): depth-first, in order, without recursion.
    stack = [enumerate(kids.get(root, ()), start=1)]
    while stack:
        for number, link in stack[-1]:
            # check_urdf indents two spaces per level and adds two levels per generation.
            indent = 4 * len(stack)
            if indent > len(spaces):
                spaces = memoryview(b" " * (2 * indent))
            yield b"".join((spaces[:indent], f"child({number}):  {shown(link)}\n".encode()))
            below = kids.get(link)
            if below:
                stack.append(enumerate(below, start=1))
            break
        else:
            stack.pop()


def _numbers(values) -> str:
    return " ".join(f"{v + 0.0:g}" if v != 0 else "0" for v in values)


def joint_summary(joint: Joint) -> str:
    """``name: type, xyz 0 0 0.1, rpy 0 0 0, axis 0 0 1, limits -1..1``."""
    origin = origin_of(joint.element)
    parts = [f"{shown(joint.name)}: {joint.type}", f"xyz {_numbers(origin['xyz'])}",
             f"rpy {_numbers(origin['rpy'])}"]
    axis = axis_of(joint)
    if axis is not None:
        parts.append(f"axis {_numbers(axis)}")
    limit = first_child(joint.element, "limit")
    if limit is not None and joint.type in ("revolute", "prismatic"):
        lower = parse_number(limit.get("lower", "0"))
        upper = parse_number(limit.get("upper", "0"))
        if lower is not None and upper is not None:
            parts.append(f"limits {_numbers([lower])}..{_numbers([upper])}")
    return ", ".join(parts)


def rich_text(tree: KinematicTree) -> str:
    """The tree drawn with box characters; each link shows the joint that carries it."""
    return b"".join(rich_lines(tree)).decode("utf-8")


_TEE, _ELBOW = "├── ".encode(), "└── ".encode()
_BAR, _GAP = "│   ".encode(), b"    "


def rich_lines(tree: KinematicTree) -> Iterator[bytes]:
    """:func:`rich_text` line by line, each line UTF-8 with its newline.

    Like check_urdf's, this text grows with the square of the depth, and so would a
    drawn prefix kept per waiting sibling (a deep tree with a branch at every level
    holds one per level). One prefix is kept instead, cut back to a depth's length
    when the walk climbs back to it: memory follows the depth, not the text.
    """
    yield f"{shown(tree.root)}\n".encode()
    prefix = bytearray()  # what is drawn left of the current depth's branches
    cuts: list[int] = []  # the prefix's length for each depth above the current one
    # A stack of (iterator over (number, joint), the last number): depth-first, in order.
    kids = tree.children.get(tree.root, ())
    stack = [(enumerate(kids), len(kids) - 1)]
    while stack:
        siblings, final = stack[-1]
        for number, joint in siblings:
            last = number == final
            yield b"".join((prefix, _ELBOW if last else _TEE,
                            f"{shown(joint.child)}  ({joint_summary(joint)})\n".encode()))
            below = tree.children.get(joint.child)
            if below:
                cuts.append(len(prefix))
                prefix += _GAP if last else _BAR
                stack.append((enumerate(below), len(below) - 1))
            break
        else:
            stack.pop()
            if cuts:
                del prefix[cuts.pop():]
