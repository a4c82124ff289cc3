"""What a robot's control package configures: the controllers that drive it
(:func:`find_controllers`, the declarations :mod:`.declared` reads, which wheels drive
before any geometry is looked at) and the ``wheel_separation_multiplier`` a skid-steer
robot's controller ships, which spin's measured multiplier is compared with.

A robot's description lives in a package ``X_description`` (Hunter 2: ``X_base``); its
controllers, by the ROS convention Clearpath, ROBOTIS, AgileX and others follow, in
``X_control`` (or ``X_controller``, ``X_controllers``: Husarion), whose YAML files
configure ``diff_drive_controller`` (ROS 1: ``controller: {wheel_separation_multiplier:
1.875}``; ROS 2: the same under ``ros__parameters``), ``ackermann_steering_controller``
and others. The description package is the one holding the robot file, else one its
``package://`` paths name (a URDF built elsewhere). Nothing here fails a simulation: a
file that cannot be read is said in the finding, and a robot without such a package
simply has no controller to read.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from ..errors import McarError
from ..file_memo import FileMemo
from ..load.inputs import display_path
from ..values import Value

SUFFIX = "_description"
SUFFIXES = (SUFFIX, "_base")  # of a description package; the control package's:
CONTROL_SUFFIXES = ("_control", "_controller", "_controllers")
KEY = "wheel_separation_multiplier"
MAX_FILES = 20  # YAML files looked at in one control package
_PACKAGE_URI = re.compile(rb"package://([A-Za-z0-9_]+(?:_description|_base))/")
_PARAMETERS = re.compile(rb"<parameters>([^<]{1,4096})</parameters>")


class ControlConfig(Value):
    """A control package's wheel_separation_multiplier and where it is written (a Value,
    not a dataclass: every `mcar check` of a package imports this module)."""

    _fields = __slots__ = ("multiplier", "file", "line")
    multiplier: float
    file: Path
    line: int | None

    def __init__(self, multiplier: float, file: Path, line: int | None):
        self._set(multiplier, file, line)

    @property
    def where(self) -> str:
        name = display_path(self.file)
        return f"{name}:{self.line}" if self.line else name


def find_control_config(loaded, joints) -> tuple[ControlConfig | None, list[str]]:
    """(the multiplier of the controller driving ``joints`` (else the first one found),
    the sentences saying which files could not be read)."""
    problems: list[str] = []
    for files in control_packages(loaded, problems):
        found = []
        for path in files:
            found += _multipliers(path, problems)
        if found:
            wanted = set(joints)
            best = next((f for f in found if f[1] & wanted), found[0])
            return best[0], problems
    return None, problems


def find_controllers(loaded) -> tuple[list, list[str], list[Path]]:
    """(the drive controllers (:class:`.declared.Declaration`) the robot's control
    packages configure, in file order, the sentences saying which files could not be
    read, the files looked at)."""
    from .declared import in_yaml_mapping

    problems: list[str] = []
    found, read = [], []
    for files in control_packages(loaded, problems):
        read += files
        for path in files:
            shown = display_path(path)
            declared = [in_yaml_mapping(keys, shown, _names_in_order)
                        for keys in yaml_mappings(path, problems)]
            found += sorted((d for d in declared if d is not None), key=lambda d: d.line or 0)
    return found, problems, read


def control_packages(loaded, problems: list[str], suffixes=CONTROL_SUFFIXES,
                     folders=("config", ""), named_only: bool = True,
                     consulted: list | None = None, packages: list[str] | None = None):
    """Each control package's YAML files (at most MAX_FILES), nearest package first. A
    file that is a link out of the repository holding its package (or into its ``.git``)
    is not read, and said in ``problems``: a pull request commits
    ``X_control/config/c.yaml`` -> a token file, and the YAML error quoting its first line
    would print the token. ``suffixes``, ``folders``: the sibling packages looked in
    (``X`` + suffix; None: the description package itself) and their folders holding the
    YAML ("": the package's own folder), for the other readers of a robot's ROS
    configuration (Nav2's parameters in ``X_navigation/params``: specs.stack_check).

    ``named_only``: where the robot names some of a package's files as its controllers'
    parameters (``<parameters>`` of its ros2_control or Gazebo plugin), only those: the
    others configure another variant (ROSbot: mecanum_drive_controller.yaml beside the
    diff_drive_controller.yaml its plain wheels name); where it names none, those its
    launch runs for the variant built (:mod:`.control_variants`; the launch files it read
    are added to ``consulted``); and the files it names outside such packages, last
    (gz_ros2_control's demos keep theirs in gz_ros2_control_demos), each a YAML file within
    the folders a robot may name files in (:meth:`~mobile_car.packages.search.
    PackageSearch.confined`, as its meshes are). ``packages``: the robot's description
    packages (:func:`description_packages`), where the caller has them."""
    from ..packages.asset_roots import link_out_of, repository_of
    from .control_variants import launch_choice

    # The YAML the URDF names is looked for once a package is found, or once its text
    # holds a <parameters> at all: for a robot with neither, searching its text (a
    # 20,000-link URDF's 19 MB) would be for nothing.
    named = None
    seen: set[Path] = set()
    for name in description_packages(loaded) if packages is None else packages:
        stem = next(name[: -len(s)] for s in SUFFIXES if name.endswith(s))
        for suffix in suffixes:
            root = loaded.search.find_if_any(name if suffix is None else stem + suffix)
            if root is None:
                continue
            if named is None:
                named = _named_parameters(loaded) if named_only else set()
            files = [path for folder in folders
                     for path in sorted(root.glob(f"{folder}/*.yaml" if folder else "*.yaml"))]
            repository, kept = repository_of(root), []
            for path in files[:MAX_FILES]:
                why = link_out_of(path, repository)
                if why is None:
                    kept.append(path)
                else:
                    problems.append(f"{display_path(path)}: not read ({why})")
            chosen = [path for path in kept if path.resolve() in named]
            seen |= {path.resolve() for path in kept}
            yield chosen or (launch_choice(loaded, root, kept, consulted) if named_only
                             else kept)
    if named is None:
        named = (_named_parameters(loaded) if named_only and b"<parameters" in loaded.urdf
                 else set())
    outside = [path for path in sorted(named - seen) if _named_file(loaded, path, problems)]
    if outside:
        yield outside


def _named_file(loaded, path: Path, problems: list[str]) -> bool:
    """Whether a parameters file the robot names outside its control packages is read:
    a YAML file within the robot's allowed folders (else ``problems`` says why not)."""
    from ..packages.asset_roots import OutsideRootsError

    if path.suffix not in (".yaml", ".yml"):
        return False
    try:
        loaded.search.confined(str(path), path)
    except OutsideRootsError as error:
        problems.append(f"{display_path(path)}: not read ({error.message})")
        return False
    return path.is_file()


def _named_parameters(loaded) -> set[Path]:
    """The real paths of the YAML files the URDF's ``<parameters>`` name (an absolute
    path, as ``$(find PKG)`` writes it, or a ``package://`` URI)."""
    named = set()
    for text in _PARAMETERS.findall(loaded.urdf):
        value = text.decode("utf-8", "replace").strip()
        if value.startswith("package://"):
            name, _, inner = value[len("package://"):].partition("/")
            root = loaded.search.find_if_any(name)
            path = None if root is None else root / inner
        else:
            path = Path(value) if value.startswith("/") else None
        if path is not None:
            named.add(path.resolve())
    return named


def description_packages(loaded) -> list[str]:
    """The robot's own package (an X_description or X_base one) and those its URDF's
    ``package://`` URIs name (a search of its whole text)."""
    from ..packages.search import enclosing_package

    names = []
    if loaded.input.path is not None:
        own = enclosing_package(loaded.input.path)
        if own is not None and own[0].endswith(SUFFIXES):
            names.append(own[0])
    names += [m.decode() for m in _PACKAGE_URI.findall(loaded.urdf)]
    return list(dict.fromkeys(names))


def yaml_mappings(path: Path, problems: list[str], contains: str | None = None) -> list[dict]:
    """key -> (key node, value node) of every mapping in the YAML file (bounded read, the
    bounded composer; a key given twice keeps its last value, as ROS reads it);
    ``contains``: a word the file must hold to be parsed at all (most
    files of a control package name no controller a reader looks for). Each file is read
    and parsed once in a process while its stamp holds (:data:`_READ`): the declarations,
    mecanum, the multiplier and the stack's comparison all ask for the same files."""
    read = _read_yaml(path)
    if isinstance(read.text, BaseException):
        problems.append(f"{display_path(path)}: not read ({_reason(read.text)})")
        return []
    if contains is not None and contains not in read.text:
        return []
    if read.mappings is None:
        read.parse()
    if isinstance(read.mappings, BaseException):
        problems.append(f"{display_path(path)}: not read ({_reason(read.mappings)})")
        return []
    return list(read.mappings)


class _YamlFile:
    """A control file as read (its text, or why it could not be read) and, once asked
    for, its mappings (or why they could not be parsed)."""

    __slots__ = ("mappings", "text")

    def __init__(self, path: Path):
        import yaml

        from ..load.bounded import read_input

        self.mappings = None
        try:
            self.text = read_input(path, str(path)).decode("utf-8")
        except (OSError, McarError, UnicodeDecodeError, yaml.YAMLError) as error:
            self.text = error

    def parse(self) -> None:
        import yaml

        from ..config.bounded_yaml import compose

        try:
            node = compose(self.text)
        except yaml.YAMLError as error:
            self.mappings = error
            return
        found = []
        todo = [node] if node is not None else []
        while todo:
            current = todo.pop()
            if isinstance(current, yaml.SequenceNode):
                todo += current.value
            if not isinstance(current, yaml.MappingNode):
                continue
            keys = {k.value: (k, v) for k, v in current.value
                    if isinstance(k, yaml.ScalarNode)}
            found.append(keys)
            todo += [v for _, v in current.value]
        self.mappings = found


# each control file as read, within one process (a view server's reloads too): a file
# edited since is read again
_READ = FileMemo(256)


def _read_yaml(path: Path) -> _YamlFile:
    return _READ.get(path, lambda: _YamlFile(path))


def _multipliers(path: Path, problems: list[str]) -> list[tuple[ControlConfig, set[str]]]:
    """(config, the wheel joints its controller names) of every mapping in the file that
    sets the multiplier to a number."""
    found = []
    for keys in yaml_mappings(path, problems):
        if KEY in keys:
            key, value = keys[KEY]
            number = _number(value)
            if number is not None and number > 0:
                wheels = set()
                for side in ("left_wheel", "right_wheel", "left_wheel_names",
                             "right_wheel_names"):
                    wheels |= _names(keys.get(side, (None, None))[1])
                found.append((ControlConfig(number, path, key.start_mark.line + 1), wheels))
    return found


def _number(node) -> float | None:
    import yaml

    if not isinstance(node, yaml.ScalarNode):
        return None
    try:
        value = float(node.value)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _names(node) -> set[str]:
    return set(_names_in_order(node))


def _names_in_order(node) -> list[str]:
    import yaml

    if isinstance(node, yaml.ScalarNode):
        return [node.value] if node.value else []
    if isinstance(node, yaml.SequenceNode):
        return [n.value for n in node.value if isinstance(n, yaml.ScalarNode) and n.value]
    return []


def _reason(error) -> str:
    if isinstance(error, McarError):
        return error.message
    if isinstance(error, OSError):
        return error.strerror or str(error)
    return " ".join(str(error).split())[:120]
