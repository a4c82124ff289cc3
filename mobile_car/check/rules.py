"""The rules ``mcar check`` applies, each with a stable id, like a linter's.

``E1xx`` are errors (the file is wrong: exit 1), ``W2xx`` are warnings (doubtful: exit 0,
or 1 with ``--strict``), ``N4xx`` are notes (information: never a failure); ``W5xx`` and
``E5xx`` are what ``mcar specs`` finds in what the robot can do (W501 joints, W502-W506
and E503 statics, W51x the package's ROS YAML, W52x sensors, W530 inertia). Ids never
change meaning; a retired rule keeps its number. The ``E15x``, ``W23x`` and ``N40x`` rules
are what Gazebo's libsdformat changes in the robot, found by ``mcar check --gazebo``.
``urdfdom`` says what Debian's ``check_urdf`` (urdfdom 3.0) does with the same problem:
``rejects`` (exit 255), ``ignores`` (logs an error or nothing, still exits 0, drops the
element), or ``hangs`` (prints the tree forever, then crashes).

The rule table of docs/rules.md is generated from :data:`RULES`
(``tests/check/test_rules.py`` keeps the two equal).
"""

from __future__ import annotations

from ..values import Value

ERROR = "error"
WARNING = "warning"
NOTE = "note"
_SEVERITIES = {"E": ERROR, "W": WARNING, "N": NOTE}


class Rule(Value):
    _fields = __slots__ = ("id", "name", "summary", "urdfdom")
    id: str
    name: str
    summary: str
    urdfdom: str

    def __init__(self, id: str, name: str, summary: str, urdfdom: str):
        self._set(id, name, summary, urdfdom)

    @property
    def severity(self) -> str:
        return _SEVERITIES[self.id[0]]

    @property
    def blocks_tree(self) -> bool:
        """True if the kinematic tree cannot be drawn while this problem is present."""
        return self.id in _TREE_BLOCKERS


_TABLE = [
    # The document
    Rule("E100", "xml-syntax", "not well-formed XML", "rejects, but for a misspelt "
         "`<?xml ...?>` declaration, or one after a comment, which its TinyXML skips"),
    Rule("E101", "no-robot", "the root element is not `<robot>`", "rejects"),
    Rule("E102", "robot-name", "`<robot>` has no name, or an empty one", "rejects if absent"),
    Rule("E103", "urdf-version", "`version` is not `1.0` (the only version urdfdom 3.0 reads)",
         "rejects"),
    Rule("E104", "dtd-subset", "a DOCTYPE with an internal subset (entity declarations)",
         "rejects"),
    Rule("E105", "xacro-unexpanded", "xacro left in a URDF: `<xacro:...>` elements, `${...}` "
         "or `$(...)` in values (build it first)", "ignores or rejects"),
    Rule("E106", "no-links", "the robot has no `<link>`", "rejects"),
    Rule("E107", "missing-name", "a link, joint or material without a name (or an empty one)",
         "rejects for joints, ignores otherwise"),
    Rule("E108", "duplicate-name", "two links, two joints or two materials with the same name",
         "rejects"),
    # Links: geometry, inertia, materials
    Rule("E110", "geometry-missing", "`<visual>`/`<collision>` without `<geometry>`, or an "
         "empty `<geometry>`", "ignores"),
    Rule("E111", "geometry-unknown", "an unknown geometry type (urdfdom 3.0 knows box, "
         "cylinder, sphere, mesh)", "ignores"),
    Rule("E112", "geometry-size-missing", "a box without `size`, a cylinder without `radius` "
         "and `length`, a sphere without `radius`, a mesh without `filename`", "ignores"),
    Rule("E113", "geometry-size-nonpositive", "a size, radius or length <= 0, or a mesh scale "
         "of 0", "accepts"),
    Rule("E114", "bad-number", "a value urdfdom cannot read as numbers: not a number, the "
         "wrong count (xyz, rpy, size, scale need 3), a tab or line break between "
         "numbers (a colour's rgba: W217)", "rejects in joints, ignores in links"),
    Rule("E115", "inertial-incomplete", "`<inertial>` without `<mass value>` or `<inertia>`, "
         "or an inertia missing one of ixx ixy ixz iyy iyz izz", "ignores"),
    Rule("E117", "number-out-of-range", "a number urdfdom reads but no robot has, which "
         "overflows when drawn or simulated: a coordinate (origin xyz), size, radius or length "
         "beyond 1e6 m, an angle (rpy) beyond 1e6 rad, an axis component beyond 1e6, a mesh "
         "scale beyond 1e6 (1e6 m of mesh times it still fits float32), a mass beyond 1e6 kg, "
         "an inertia moment beyond 1e18 kg m² (nan, inf, 1e999: E114)", "accepts"),
    Rule("E118", "mass-negative", "a negative mass, on any link (a fixed link's mass counts "
         "in the robot's total; a massless frame has 0)", "accepts"),
    Rule("E119", "mass-implausible", "a mass no built robot has: a wheel (a link a "
         "continuous joint turns) over 5 times the robot without its wheels, or a link denser than "
         "25 000 kg/m³ (osmium: 22 590) or, over 1 g, lighter than 1 kg/m³ (air: 1.2) in the "
         "volume of its collision shapes (a link with none not judged; a mesh by its box; shapes "
         "that fit in a 2 cm cube are a placeholder, not judged; shapes all under 2 mm thick are "
         "a contact surface, not called too dense; nor is a link whose visual shapes have room "
         "for its mass)",
         "accepts"),
    # Joints
    Rule("E120", "joint-type", "a joint without a type, or of an unknown type", "rejects"),
    Rule("E121", "joint-link-missing", "a joint without `<parent link>` or `<child link>`",
         "rejects"),
    Rule("E122", "joint-link-undefined", "a joint naming a link that is not defined",
         "rejects"),
    Rule("E123", "joint-limit-missing", "a revolute or prismatic joint without `<limit>`, or "
         "a `<limit>` without `effort` and `velocity`", "rejects"),
    Rule("E124", "limit-order", "a `<limit>` with lower > upper", "accepts"),
    Rule("E125", "axis-zero", "a joint axis of length 0 (`<axis>` without `xyz` is 0 0 0 in "
         "urdfdom)", "accepts"),
    Rule("E126", "mimic", "a `<mimic>` without `joint`, naming an unknown joint, or itself",
         "rejects if no joint, accepts otherwise"),
    Rule("E127", "joint-element-incomplete", "`<dynamics>` with neither damping nor friction, "
         "`<safety_controller>` without `k_velocity`", "rejects"),
    # The kinematic tree
    Rule("E130", "two-parents", "a link that is the child of two joints", "accepts"),
    Rule("E131", "cycle", "joints that form a cycle, reachable from the root or detached",
         "hangs if reachable from the root, accepts if detached, rejects if no root is left"),
    Rule("E132", "self-loop", "a joint whose parent and child are the same link", "hangs"),
    Rule("E133", "disconnected", "a link not connected to the tree (a second root)",
         "rejects"),
    # Inputs that are built first
    Rule("E140", "xacro-error", "a `.xacro` input that xacro cannot expand", "n/a"),
    # What Gazebo changes (mcar check --gazebo)
    Rule("E150", "gazebo-link-dropped", "a link Gazebo leaves out: libsdformat drops a link "
         "without mass (no `<inertial>`, or mass 0) and everything that moves below it; "
         "reported at the massless link, with each link lost and their mass", "n/a"),
    Rule("E151", "gazebo-load-error", "libsdformat (Gazebo's URDF reader) returns an error "
         "loading the robot (in its Errors list, as its own load gives it), or makes no "
         "model of it; named with its version", "n/a"),
    Rule("E152", "gazebo-include", "an `<include>` (in a `<gazebo>` block): libsdformat would "
         "read the file or model folder it names (a path, `file://`, `model://`) into the "
         "robot, and mcar's Gazebo helper reads no file; refused before libsdformat runs",
         "n/a"),
    # Warnings
    Rule("W201", "unknown-element", "an element URDF does not define (a typo such as "
         "`<visul>`, `<limits>`), with a did-you-mean", "ignores"),
    Rule("W202", "unknown-attribute", "an attribute URDF does not define (a typo such as "
         "`xzy=`), with a did-you-mean", "ignores"),
    Rule("W203", "mass-nonpositive", "mass 0 on a moving link (child of a non-fixed joint); "
         "a negative mass is E118",
         "accepts"),
    Rule("W204", "inertia-not-positive-definite", "an inertia tensor that is not positive "
         "definite", "accepts"),
    Rule("W205", "inertia-triangle", "principal moments that break the triangle inequality "
         "(no rigid body has them)", "accepts"),
    Rule("W206", "inertial-missing", "a moving link with no `<inertial>`", "accepts"),
    Rule("W207", "mesh-unreadable", "a mesh that cannot be found or loaded (package://, "
         "file:// and relative paths resolved like `mcar build`): drawn as a magenta box",
         "accepts"),
    Rule("W208", "root-inertia", "a root link with an inertia: KDL (robot_state_publisher, "
         "MoveIt) ignores it", "accepts"),
    Rule("W209", "duplicate-element", "a second `<origin>`, `<geometry>`, `<limit>`, ... "
         "where urdfdom reads only the first", "ignores"),
    Rule("W210", "mesh-over-limit", "a mesh over `MCAR_MAX_MESH_MB` (file or decompressed) "
         "or `MCAR_MAX_MESH_FACES` (its declared vertex or face count): not read, drawn as "
         "a magenta box", "accepts"),
    Rule("W211", "robot-huge", "the robot is more than 20 m across in its rest pose, larger "
         "than a building (a mesh in millimetres or inches read as metres?)", "accepts"),
    Rule("W212", "mesh-scale", "a mesh more than 100 times larger, or under 1/1000 the size "
         "of the rest of the robot (its other shapes and its link frames): a unit mistake",
         "accepts"),
    Rule("W213", "inertia-size", "an inertia over 10 times, or under 1/10, what a solid of "
         "the link's mass filling its one collision box, cylinder or sphere has (1/100 for "
         "the box around several shapes or a mesh); compared by the sum of the principal "
         "moments", "accepts"),
    Rule("W214", "wheel-inertia", "a wheel (turned by a continuous joint, round about its "
         "axis) whose moment about the axle is over 1.25 m r² (a ring has m r²) or under "
         "0.05 m r² (a tenth of a solid disc)", "accepts"),
    Rule("W215", "file-outside-roots", "a mesh or `<texture>` whose file (every symlink "
         "followed) lies outside the package folders, the input's folder and the "
         "`--asset-path`/`assets.paths` folders, or in a version-control folder (`.git`), "
         "or a URL other than `package://` and `file://` (RViz would fetch it): never read "
         "nor exported, drawn as a magenta box", "accepts"),
    Rule("W216", "material-undefined", "a material used by name but never defined with a "
         "`<color>` or `<texture>`, or defined with neither (was E116: only the look "
         "changes; drawn in the default grey)", "warns"),
    Rule("W217", "material-colour", "a `<color rgba>` urdfdom cannot read: not four numbers, "
         "or a component outside 0..1 (was part of E114; urdfdom drops the colour, the part "
         "is drawn in the default grey)", "ignores (logs an error)"),
    Rule("W220", "xacro-warning", "xacro printed a warning while expanding a `.xacro` input",
         "n/a"),
    Rule("W230", "gazebo-warning", "libsdformat warns while loading the robot", "n/a"),
    Rule("W231", "gazebo-reference-dangling", "a `<gazebo reference>` naming no link or joint "
         "Gazebo has: none of the robot's, a link it leaves out, or a fixed joint it lumps "
         "away", "n/a"),
    Rule("W232", "gazebo-plugin-joint", "a `<gazebo>` plugin naming a joint Gazebo does not "
         "have, in `<joint>`, `<joint_name>`, `<left_joint>`, `<leftJoint>`, `<jointName>` "
         "and the like", "n/a"),
    # What mcar specs finds in what the robot can do
    Rule("W501", "effort-under-gravity", "`mcar specs`: a joint whose `<limit effort>` is under "
         "the torque (revolute) or force (prismatic) gravity asks of it in its worst pose "
         "within its limits and those of the joints beyond it, an effort of 0 included "
         "(MuJoCo's gravity load, the figures in the message; a suspension a spring carries "
         "is not judged)", "n/a"),
    # The package's own ROS configuration against the robot (mcar check, mcar specs)
    # What the robot can do (mcar specs): statics
    Rule("E503", "cannot-drive", "the drive motors cannot move the robot on flat ground: "
         "their effort (less the wheel joints' declared friction) over the wheel radius "
         "does not beat the castors' drag (mcar specs' statics.climb is 0)", "n/a"),
    Rule("W502", "tips-climbing", "the motors climb a slope (statics.climb) on which the "
         "robot tips over backward driving up it, or forward reversing up it (statics.tip."
         "backward, statics.tip.forward)", "n/a"),
    Rule("W503", "weak-climb", "the robot cannot climb a 5° ramp: its motors or its driven "
         "wheels' grip give out first (statics.climb, which says which)", "n/a"),
    Rule("W504", "tips-across", "the motors climb a slope on which the robot, turned across "
         "it, tips over sideways (statics.tip.left or right under statics.climb): its track "
         "is too narrow or its centre of mass too high", "n/a"),
    Rule("W505", "no-static-stability", "the centre of mass is not inside the polygon the "
         "robot stands on at rest (statics.tip.min 0°): it stands only balanced", "n/a"),
    Rule("W506", "proof-disagrees", "MuJoCo's proof of a statics figure (the tilt and climb "
         "runs) disagrees with the computed figure beyond its tolerance", "n/a"),
    Rule("W510", "stack-wheel-separation", "the control package's drive controller gives a "
         "`wheel_separation` (times its `wheel_separation_multiplier`: the effective "
         "figure) more than 1% off the drive wheels' spacing (a skid-steer robot's may "
         "rightly be larger, its wheels scrub), a `wheelbase` (`wheel_separation_h`) more "
         "than 1% off an Ackermann or bicycle drive's, or a mecanum controller's "
         "`sum_of_robot_center_projection_on_X_Y_axis` more than 1% off its wheels' lx + ly",
         "n/a"),
    Rule("W511", "stack-wheel-radius", "the drive controller's `wheel_radius` (times its "
         "radius multiplier), `*_wheels_radius`, `*_wheel_radius` or mecanum's "
         "`kinematics.wheels_radius` more than 1% off the drive wheels' collision radius",
         "n/a"),
    Rule("W512", "stack-wheel-names", "the drive controller names, among its left, right or "
         "mecanum corners, a joint that is not that drive wheel of the robot (missing, "
         "another side's or corner's, not a wheel)", "n/a"),
    Rule("W513", "stack-footprint", "Nav2's `footprint` leaves part of the robot's outline "
         "on the floor out (by over 1 mm), or, with no footprint, its `robot_radius` is "
         "under the robot's circumscribed radius", "n/a"),
    Rule("W514", "stack-laser-filter", "a laser_filters chain whose angular bounds filters "
         "leave part of a sector the robot's own body blocks in the scan (mcar specs, "
         "with the sensors section)", "n/a"),
    Rule("W520", "lidar-blocked", "`mcar specs`: the robot's own geometry (visual or "
         "collision) blocks a lidar over more than 10 % of its samples; the message names "
         "the sectors", "n/a"),
    Rule("W530", "inertia-implausible", "`mcar specs`: a declared inertia MuJoCo refuses, or "
         "over 3 times or under 1/3 what the link's geometry (collision, else visual) gives "
         "with its mass about a principal axis; the message gives the `<inertial>` to write "
         "instead", "n/a"),
    # Notes
    Rule("N401", "gazebo-lumped", "a link Gazebo lumps into its parent by a fixed joint: "
         "one body with the parent's mass, collisions and visuals", "n/a"),
    Rule("N402", "gazebo-reference-lumped", "a `<gazebo reference>` naming a lumped link: "
         "what it sets, sensors included, goes to the link it is lumped into", "n/a"),
    Rule("N403", "gazebo-mass", "the links and mass Gazebo simulates, against the URDF's",
         "n/a"),
    Rule("N404", "gazebo-console-error", "an error libsdformat printed on its console but "
         "did not return: it loaded the robot past it", "n/a"),
    Rule("N405", "stack-variant-unknown", "W510-W512's finding on one of several controller "
         "files the control package ships for the robot's variants, where the robot names "
         "none in `<parameters>` and no launch of the package chooses one by an argument "
         "of this build: mcar cannot tell the file is the one this variant runs", "n/a"),
]

RULES: dict[str, Rule] = {rule.id: rule for rule in _TABLE}

# Ids no longer reported, and the rule that took their place: an id never comes back
# with another meaning (a CI that filtered E116 must not silently filter something new).
RETIRED: dict[str, str] = {"E116": "W216"}

_TREE_BLOCKERS = {"E100", "E101", "E102", "E104", "E106", "E107", "E108", "E120", "E121",
                  "E122", "E130", "E131", "E132", "E133", "E140"}


def markdown_table() -> str:
    """The rule table as Markdown, for docs/rules.md."""
    lines = ["| id | name | what it finds | check_urdf |", "|---|---|---|---|"]
    for rule in _TABLE:
        lines.append(f"| {rule.id} | {rule.name} | {rule.summary} | {rule.urdfdom} |")
    return "\n".join(lines)
