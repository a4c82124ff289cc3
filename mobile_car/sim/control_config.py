"""The ``wheel_separation_multiplier`` a skid-steer robot's control package ships, which
spin's measured multiplier is compared with.

A robot's description lives in a package ``X_description``; its controllers, by the ROS
convention Clearpath, ROBOTIS and others follow, in ``X_control``, whose YAML files
configure ``diff_drive_controller`` (ROS 1: ``controller: {wheel_separation_multiplier:
1.875}``; ROS 2: the same under ``ros__parameters``). The description package is the one
holding the robot file, else one its ``package://`` paths name (a URDF built elsewhere).
Nothing here fails a simulation: a file that cannot be read is said in the finding, and a
robot without such a package simply has no figure to compare with.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import McarError
from ..load.inputs import display_path

SUFFIX = "_description"
KEY = "wheel_separation_multiplier"
MAX_FILES = 20  # YAML files looked at in one control package
_PACKAGE_URI = re.compile(rb"package://([A-Za-z0-9_]+" + SUFFIX.encode() + rb")/")


@dataclass(frozen=True)
class ControlConfig:
    multiplier: float
    file: Path
    line: int | None

    @property
    def where(self) -> str:
        name = display_path(self.file)
        return f"{name}:{self.line}" if self.line else name


def find_control_config(loaded, joints) -> tuple[ControlConfig | None, list[str]]:
    """(the multiplier of the controller driving ``joints`` (else the first one found),
    the sentences saying which files could not be read)."""
    problems: list[str] = []
    for name in _description_packages(loaded):
        control = name[: -len(SUFFIX)] + "_control"
        try:
            root = loaded.search.find(control)
        except McarError:
            continue
        files = sorted(root.glob("config/*.yaml")) + sorted(root.glob("*.yaml"))
        found = []
        for path in files[:MAX_FILES]:
            found += _multipliers(path, problems)
        if found:
            wanted = set(joints)
            best = next((f for f in found if f[1] & wanted), found[0])
            return best[0], problems
    return None, problems


def _description_packages(loaded) -> list[str]:
    from ..packages.search import enclosing_package

    names = []
    if loaded.input.path is not None:
        own = enclosing_package(loaded.input.path)
        if own is not None and own[0].endswith(SUFFIX):
            names.append(own[0])
    names += [m.decode() for m in _PACKAGE_URI.findall(loaded.urdf)]
    return list(dict.fromkeys(names))


def _multipliers(path: Path, problems: list[str]) -> list[tuple[ControlConfig, set[str]]]:
    """(config, the wheel joints its controller names) of every mapping in the file that
    sets the multiplier to a number."""
    import yaml

    from ..config.bounded_yaml import compose_and_load
    from ..load.bounded import read_input

    try:
        node, _ = compose_and_load(read_input(path, str(path)).decode("utf-8"))
    except (OSError, McarError, UnicodeDecodeError, yaml.YAMLError) as error:
        problems.append(f"{display_path(path)}: not read ({_reason(error)})")
        return []
    found = []
    todo = [node] if node is not None else []
    while todo:
        current = todo.pop()
        if isinstance(current, yaml.SequenceNode):
            todo += current.value
        if not isinstance(current, yaml.MappingNode):
            continue
        keys = {k.value: (k, v) for k, v in current.value if isinstance(k, yaml.ScalarNode)}
        if KEY in keys:
            key, value = keys[KEY]
            number = _number(value)
            if number is not None and number > 0:
                wheels = set()
                for side in ("left_wheel", "right_wheel", "left_wheel_names",
                             "right_wheel_names"):
                    wheels |= _names(keys.get(side, (None, None))[1])
                found.append((ControlConfig(number, path, key.start_mark.line + 1), wheels))
        todo += [v for _, v in current.value]
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
    import yaml

    if isinstance(node, yaml.ScalarNode):
        return {node.value}
    if isinstance(node, yaml.SequenceNode):
        return {n.value for n in node.value if isinstance(n, yaml.ScalarNode)}
    return set()


def _reason(error) -> str:
    if isinstance(error, McarError):
        return error.message
    if isinstance(error, OSError):
        return error.strerror or str(error)
    return " ".join(str(error).split())[:120]
