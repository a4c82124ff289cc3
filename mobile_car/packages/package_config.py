"""A package's own mcar settings: ``mcar.yaml`` at the package root (beside package.xml).

Everything in it is optional; a package without the file works as before. It says what
mcar cannot find out from the files themselves::

    robots:                 # which files are robots (globs, relative to the package root)
      include: ["urdf/*.urdf.xacro"]   # only these (default: every robot file found)
      exclude: ["urdf/custom_example.urdf"]
    sim:
      skip:                 # robots ci does not simulate, each with the reason it prints
        "urdf/arm.urdf.xacro": "an arm on a fixed base, not a vehicle"
      drive:                # the drive of robots whose declarations and geometry mislead
        "urdf/rover.urdf.xacro": {kind: skid-steer, left: [fl_joint, rl_joint],
                                  right: [fr_joint, rr_joint]}
    export:                 # folders ci exports (and verifies) as build artefacts
      formats: [mjcf, urdf] # any of mjcf, usd, urdf, sdf (mcar export --to)
      robots: ["urdf/*.urdf.xacro"]   # which robots (default: every robot ci builds)
    ci:
      strict: true          # a check warning fails ci too (default: only errors do)
    assets:
      paths: ["../meshes"]  # folders whose meshes and textures the robots may name

``assets.paths`` are relative to the package root and must lie, every symlink followed,
inside the repository holding the package (the nearest folder with ``.git``, else the
package itself): in CI the pull request writes this file, so it can never open the
runner's other folders to an export (see :mod:`.asset_roots`).

Globs are matched against the file's path relative to the package root, written with
``/``, by :func:`fnmatch.fnmatchcase`: ``*`` also matches across folders, so
``urdf/*.xacro`` takes ``urdf/wheel/test_wheel.urdf.xacro`` too.

The file is read like every other input, and only where its real path lies inside the
repository, like ``assets.paths`` (a link out of it is refused unread): a regular file
within the input size bound, by the bounded YAML loader (no object tags, no alias bombs,
no duplicate keys); an unknown key or a value of the wrong type is a one-line error naming
the file and line (exit 2), so a typo never silently changes what ci tests.
"""

from __future__ import annotations

import fnmatch
import os
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError, UsageError
from ..load.inputs import display_path

FILE_NAME = "mcar.yaml"
# Each section and the keys it takes; a list of globs or a mapping glob -> reason.
_SCHEMA = {"robots": {"include": list, "exclude": list},
           "sim": {"skip": dict, "drive": "drive"},
           "export": {"formats": list, "robots": list}, "ci": {"strict": bool},
           "assets": {"paths": list}}
EXPORT_FORMATS = ("mjcf", "usd", "urdf", "sdf")  # as mobile_car.export.FORMATS
# the drive kinds mcar sim drives (sim/drives.py), --drive and mcar.yaml sim.drive name
DRIVE_KINDS = ("differential", "skid-steer", "ackermann", "mecanum", "bicycle")
DRIVE_KEYS = ("kind", "left", "right")


@dataclass(frozen=True)
class PackageConfig:
    """The settings of one package; ``path`` is None when the package has no mcar.yaml."""

    root: Path
    path: Path | None = None
    include: tuple[str, ...] = ()
    exclude: tuple[str, ...] = ()
    sim_skip: tuple[tuple[str, str], ...] = ()  # (glob, reason), in the file's order
    sim_drive: tuple[tuple[str, dict], ...] = ()  # (glob, {kind, left, right}), in order
    export_formats: tuple[str, ...] = ()
    export_robots: tuple[str, ...] = ()  # globs; none: every robot
    strict: bool | None = None  # ci.strict; None: not said
    asset_paths: tuple[Path, ...] = ()  # assets.paths, real paths inside the repository
    lines: dict = field(default_factory=dict, compare=False)  # key path -> line

    def relative(self, path: Path) -> str | None:
        """``path`` relative to the package root, with ``/``; None outside the package."""
        try:
            return Path(path).resolve().relative_to(self.root.resolve()).as_posix()
        except ValueError:
            return None

    def selects(self, path: Path) -> tuple[bool, str | None]:
        """(taken as a robot, why not): ``include`` and ``exclude`` applied to ``path``."""
        name = self.relative(path)
        if name is None:
            return True, None
        if self.include and not any(fnmatch.fnmatchcase(name, g) for g in self.include):
            return False, f"not in robots.include of {self._where('robots', 'include')}"
        for glob in self.exclude:
            if fnmatch.fnmatchcase(name, glob):
                return False, f"robots.exclude '{glob}' of {self._where('robots', 'exclude')}"
        return True, None

    def sim_skip_reason(self, path: Path) -> str | None:
        """The reason the package gives for not simulating ``path``, or None."""
        name = self.relative(path)
        if name is None:
            return None
        for glob, reason in self.sim_skip:
            if fnmatch.fnmatchcase(name, glob):
                return reason
        return None

    def sim_drive_for(self, path: Path) -> tuple[dict, str] | None:
        """({kind, left, right} the package sets for ``path``'s drive (each may be
        missing), where it says so: ``mcar.yaml:LINE``), or None."""
        name = self.relative(path)
        if name is None:
            return None
        for glob, drive in self.sim_drive:
            if fnmatch.fnmatchcase(name, glob):
                line = self.lines.get(("sim", "drive", glob))
                shown = display_path(self.path) if self.path is not None else FILE_NAME
                return drive, f"{shown}:{line}" if line else shown
        return None

    def exports(self, path: Path) -> tuple[str, ...]:
        """The formats ci exports ``path`` to (none when the package asks for none)."""
        name = self.relative(path)
        if not self.export_formats or name is None:
            return ()
        if self.export_robots and not any(fnmatch.fnmatchcase(name, g)
                                          for g in self.export_robots):
            return ()
        return self.export_formats

    def _where(self, *keys: str) -> str:
        line = self.lines.get(keys)
        name = self.path.name if self.path is not None else FILE_NAME
        return f"{name}:{line}" if line else name


def load_package_config(root: Path) -> PackageConfig:
    """The settings of the package at ``root`` (empty when it has no mcar.yaml)."""
    path = Path(root) / FILE_NAME
    if not path.exists() and not path.is_symlink():
        return PackageConfig(root=Path(root))
    return _parse(Path(root), path)


def _parse(root: Path, path: Path) -> PackageConfig:
    import yaml

    from ..config.bounded_yaml import DuplicateKey, TooLarge, compose_and_load, short_repr
    from ..load.bounded import read_input
    from .asset_roots import link_out_of, repository_of

    shown = str(path)
    # A link out of the repository is refused before it is read: a pull request commits
    # mcar.yaml -> a token file, and the error quoting its first value printed the token.
    why = link_out_of(path, repository_of(root))
    if why is not None:
        raise UsageError(f"{why}: not read", file=shown)
    try:
        node, data = compose_and_load(read_input(path, shown).decode("utf-8"))
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read: {getattr(error, 'strerror', None) or error}",
                         file=shown) from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or "not valid YAML"
        if not isinstance(error, (TooLarge, DuplicateKey)):
            problem = f"not valid YAML: {problem}"
        raise UsageError(problem, file=shown, line=mark.line + 1 if mark else None) from None
    lines = _key_lines(node)
    if data is None:
        return PackageConfig(root=root, path=path, lines=lines)

    def fail(message: str, *keys: str):
        raise UsageError(message, file=shown, line=lines.get(keys))

    if not isinstance(data, dict):
        fail(f"expected a mapping with {', '.join(_SCHEMA)}, got {short_repr(data)}")
    found: dict[tuple[str, str], object] = {}
    for section, value in data.items():
        if section not in _SCHEMA:
            fail(f"unknown key '{section}': {FILE_NAME} takes {', '.join(_SCHEMA)}",
                 str(section))
        if value is None:
            continue
        if not isinstance(value, dict):
            fail(f"{section}: expected a mapping, got {short_repr(value)}", section)
        for key, entry in value.items():
            kind = _SCHEMA[section].get(key)
            if kind is None:
                fail(f"unknown key '{section}.{key}': {section} takes "
                     f"{', '.join(_SCHEMA[section])}", section, str(key))
            found[(section, key)] = _checked(entry, kind, f"{section}.{key}",
                                             lambda m, *more, k=(section, str(key)):
                                             fail(m, *k, *more))
    skip = found.get(("sim", "skip"), {})
    formats = found.get(("export", "formats"), [])
    unknown = [f for f in formats if f not in EXPORT_FORMATS]
    if unknown:
        fail(f"export.formats: unknown format '{unknown[0]}' (mcar export takes "
             f"{', '.join(EXPORT_FORMATS)})", "export", "formats")
    return PackageConfig(root=root, path=path,
                         include=tuple(found.get(("robots", "include"), ())),
                         exclude=tuple(found.get(("robots", "exclude"), ())),
                         sim_skip=tuple(skip.items()),
                         sim_drive=tuple(found.get(("sim", "drive"), {}).items()),
                         export_formats=tuple(dict.fromkeys(formats)),
                         export_robots=tuple(found.get(("export", "robots"), ())),
                         strict=found.get(("ci", "strict")),
                         asset_paths=_asset_paths(root, found.get(("assets", "paths"), []),
                                                  lambda m: fail(m, "assets", "paths")),
                         lines=lines)


def _asset_paths(root: Path, paths: list[str], fail) -> tuple[Path, ...]:
    """assets.paths as real folders, each inside the repository holding the package."""
    from .asset_roots import real_path, repository_of, within

    repository = repository_of(root)
    found = []
    for text in paths:
        if os.path.isabs(text):
            fail(f"assets.paths: '{text}' is absolute; name a folder relative to the package, "
                 f"inside {repository} (--asset-path names any folder)")
        real = real_path(Path(root) / text)
        if not within(real, [repository]):
            fail(f"assets.paths: '{text}' leads to {real}, outside {repository} "
                 "(--asset-path names any folder)")
        found.append(real)
    return tuple(dict.fromkeys(found))


def _checked(entry, kind, name: str, fail):
    from ..config.bounded_yaml import short_repr

    if kind == "drive":
        return {} if entry is None else _drive(entry, name, fail)
    if kind is bool:
        if not isinstance(entry, bool):
            fail(f"{name}: expected true or false, got {short_repr(entry)}")
        return entry
    if entry is None:
        return kind()
    if kind is list:
        if not isinstance(entry, list) or not all(isinstance(g, str) and g for g in entry):
            what = "folders" if name == "assets.paths" else "globs"
            fail(f"{name}: expected a list of {what}, got {short_repr(entry)}")
        return list(entry)
    if not isinstance(entry, dict) or not all(
            isinstance(g, str) and g and isinstance(r, str) and r.strip()
            for g, r in entry.items()):
        fail(f"{name}: expected a mapping of glob to reason (text), got {short_repr(entry)}")
    return {g: " ".join(r.split()) for g, r in entry.items()}


def _drive(entry, name: str, fail) -> dict:
    """sim.drive: glob -> {kind, left, right}, each side a joint or a list of joints."""
    from ..config.bounded_yaml import short_repr

    if not isinstance(entry, dict):
        fail(f"{name}: expected a mapping of glob to {{kind, left, right}}, got "
             f"{short_repr(entry)}")
    found = {}
    for glob, drive in entry.items():
        def fail_here(message, glob=glob):  # at the glob's line
            fail(message, str(glob))
        if not isinstance(glob, str) or not glob or not isinstance(drive, dict) or not drive:
            fail_here(f"{name}: expected a mapping of glob to {{kind, left, right}}, got "
                      f"{short_repr({glob: drive})}")
        unknown = [k for k in drive if k not in DRIVE_KEYS]
        if unknown:
            fail_here(f"{name} '{glob}': unknown key '{unknown[0]}' (it takes "
                 f"{', '.join(DRIVE_KEYS)})")
        if "kind" in drive and drive["kind"] not in DRIVE_KINDS:
            fail_here(f"{name} '{glob}': kind {short_repr(drive['kind'])} is not one of "
                 f"{', '.join(DRIVE_KINDS)}")
        sides = {}
        for side in ("left", "right"):
            joints = drive.get(side)
            joints = [joints] if isinstance(joints, str) else joints
            if joints is not None and (not isinstance(joints, list) or not joints or not all(
                    isinstance(j, str) and j.strip() for j in joints)):
                fail_here(f"{name} '{glob}': {side}: expected a joint or a list of joints, got "
                     f"{short_repr(drive.get(side))}")
            if joints:
                sides[side] = [j.strip() for j in joints]
        if len(sides) == 1:
            fail_here(f"{name} '{glob}': left and right go together: name the drive joints of "
                 "each side")
        found[glob] = {**({"kind": drive["kind"]} if "kind" in drive else {}), **sides}
    return found


def _key_lines(node) -> dict[tuple[str, ...], int]:
    """(section,) and (section, key) -> the line the key is written on."""
    import yaml

    lines: dict[tuple[str, ...], int] = {}
    if not isinstance(node, yaml.MappingNode):
        return lines
    for key, value in node.value:
        section = str(key.value)
        lines[(section,)] = key.start_mark.line + 1
        if isinstance(value, yaml.MappingNode):
            for inner, entries in value.value:
                lines[(section, str(inner.value))] = inner.start_mark.line + 1
                if isinstance(entries, yaml.MappingNode):  # sim.drive's globs
                    for glob, _ in entries.value:
                        lines[(section, str(inner.value), str(glob.value))] = \
                            glob.start_mark.line + 1
    return lines
