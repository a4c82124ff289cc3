"""The one loader: a robot input (file or stdin), xacro arguments and dimension overrides in,
the expanded robot out (URDF bytes, the files read, a map back to source lines, warnings),
or a located error.

Every command loads through :func:`load_robot`, so they take the same inputs and refuse
the same things with the same words and exit codes:

* a missing, unreadable or directory input: :class:`~mobile_car.errors.InputError` (2);
* a ``.xacro`` macro file given as a robot: :class:`MacroFileError` (2);
* a ``.xacro`` that xacro cannot expand: :class:`~mobile_car.errors.BuildError` (1), with
  its file, line and macro/include stack;
* xacro arguments or overrides the input cannot take: :class:`~mobile_car.errors.UsageError` (2).

A plain URDF is read as it is (``mcar check`` has no size limit on regular files and never
imports xacro; stdin is read within ``MCAR_MAX_INPUT_MB`` by every command, and a FIFO,
socket or device is refused before it is opened);
with ``through_xacro`` (``mcar build``) it goes through xacro like a ``.xacro`` does. A
file not named ``.xacro`` that uses xacro (TurtleBot3's ``.urdf`` files) is expanded by
every command, as the ``xacro`` command would, with a note
(:mod:`mobile_car.load.xacro_use`).
"""

from __future__ import annotations

import functools
import os
from pathlib import Path

from ..errors import InputError, UsageError
from ..packages.search import PackageSearch
from .bounded import not_regular, read_input, read_open
from .inputs import RobotInput, display_path

# The xacro argument config.xacro reads overrides from (defined here, not in mobile_car.config,
# so that loading a robot without overrides imports none of the config code).
CONFIG_ARG = "config"


class MacroFileError(UsageError):
    """A ``.xacro`` whose ``<robot>`` has no name: it defines macros, it is not a robot."""


class LoadOptions:
    """How every input of one command is loaded."""

    # A plain class, not a dataclass (the last one a check of a plain URDF imported):
    # a dataclass costs every run that imports it the compiling of its methods, and the
    # dataclasses module its import (values.py). replace() makes a variant.
    _FIELDS = ("mappings", "package_paths", "overrides", "through_xacro", "size_limited")

    def __init__(self, mappings: dict[str, str] | None = None,
                 package_paths: list[Path] | None = None, overrides: object | None = None,
                 through_xacro: bool = False, size_limited: bool = False):
        self.mappings = {} if mappings is None else mappings  # NAME:=VALUE
        self.package_paths = [] if package_paths is None else package_paths
        # --set/--config, validated and written once: a mobile_car.config.overrides.
        # Overrides, made by the config stage before loading. The loader reads only its
        # xacro mappings (``.mappings``), so it depends on nothing of config: --set flows
        # CLI -> config -> here.
        self.overrides = overrides
        self.through_xacro = through_xacro  # a plain URDF goes through xacro too (build)
        # Refuse inputs over MCAR_MAX_INPUT_MB (xacro always does): for commands that hold
        # ~45x the file in memory (render); `mcar check` reads any size.
        self.size_limited = size_limited

    def replace(self, **changes) -> LoadOptions:
        """These options with ``changes`` (field name -> value), as dataclasses.replace."""
        unknown = set(changes) - set(self._FIELDS)
        if unknown:
            raise TypeError(f"LoadOptions has no field {sorted(unknown)[0]!r}")
        return LoadOptions(**{**{name: getattr(self, name) for name in self._FIELDS}, **changes})

    @property
    def has_arguments(self) -> bool:
        return bool(self.mappings) or self.overrides is not None


class LoadedRobot:
    """An expanded robot, ready to check and use."""

    # A plain class, not a dataclass: never compared, and a dataclass costs every run
    # that imports it the compiling of its methods (values.py).
    def __init__(self, input: RobotInput, urdf: bytes, search: PackageSearch,
                 deps: list[Path] | None = None, warnings: list[str] | None = None,
                 from_xacro: bool = False, origins: object = None,
                 mappings: dict[str, str] | None = None):
        self.input = input
        self.urdf = urdf
        self.search = search
        self.deps = [] if deps is None else deps  # the files read, the input first
        self.warnings = [] if warnings is None else warnings  # xacro's warnings
        self.from_xacro = from_xacro
        self.origins = origins  # expand.origins.Origins: where each element was written
        self.mappings = {} if mappings is None else mappings  # xacro's NAME:=VALUE given

    @property
    def label(self) -> str:
        return self.input.label

    @functools.cached_property
    def locate(self):
        """For an expanded file: a SourceLocator (built element -> the file, line and
        macro calls it was written at), made only when a check asks; else None."""
        if not self.from_xacro or self.input.path is None:
            return None
        from ..expand.source_map import SourceLocator

        return SourceLocator(self.input.path, self.origins)

    @property
    def base(self) -> Path:
        """The folder relative mesh and file paths are taken from."""
        return self.input.path.parent if self.input.path is not None else Path.cwd()


def load_robot(inp: RobotInput, options: LoadOptions, stdin=None) -> LoadedRobot:
    """Load one input; ``stdin`` is the binary stream ``-`` reads."""
    origin = inp.path if inp.path is not None else Path.cwd()
    search = PackageSearch(package_paths=list(options.package_paths), origin=origin)
    if inp.path is None:
        data = read_open(stdin, inp.label, options.size_limited) if stdin is not None else b""
        if not options.through_xacro:
            return LoadedRobot(inp, data, search)
        return _expand(inp, options, search, text=data)
    require_robot_file(inp)
    if inp.named_xacro:
        return _expand(inp, options, search)
    if options.through_xacro:  # mcar build: every file goes through xacro
        _note_xacro_use(inp, inp.xacro_use)
        return _expand(inp, options, search)
    try:
        data = read_input(inp.path, inp.label, limit_regular=options.size_limited)
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", file=inp.label) from None
    from .xacro_use import xacro_use

    use = xacro_use(data)
    if use is None:
        return LoadedRobot(inp, data, search, deps=[inp.path])
    _note_xacro_use(inp, use)
    return _expand(inp, options, search)


def _note_xacro_use(inp: RobotInput, use: str | None) -> None:
    if use is not None:
        from .xacro_use import note_expanded

        note_expanded(inp.label, use)


def _expand(inp: RobotInput, options: LoadOptions, search: PackageSearch,
            text: bytes | None = None) -> LoadedRobot:
    from ..expand.xacro_build import build_file

    mappings = dict(options.mappings)
    if options.overrides is not None:
        mappings.update(options.overrides.mappings)
    # The overrides' config:= is offered to every file of a package, and a file found in a
    # folder may leave config.xacro out; a config:= the user typed for a file they named
    # is refused, like any argument that file never declares.
    typed = CONFIG_ARG in options.mappings and inp.base is None
    optional = frozenset() if typed else frozenset({CONFIG_ARG})
    built = build_file(inp.path, mappings, search, optional_args=optional, text=text)
    _check_config_ranges(built.deps)
    # A file found in a folder may leave config.xacro out; one the user named may not.
    if options.overrides is not None and inp.base is None and CONFIG_ARG not in built.known_args:
        raise UsageError("--set/--config change config.xacro, which this file does not "
                         "include", file=inp.label)
    return LoadedRobot(inp, built.xml.encode("utf-8"), search, deps=built.deps,
                       warnings=built.warnings, from_xacro=True, origins=built.origins,
                       mappings=mappings)


def _check_config_ranges(deps: list[Path]) -> None:
    """A config.xacro the robot read must keep its own values inside the ranges its comments
    state (BuildError at the value's line, as ``mcar config`` says it). Its xacro.fatal
    cross-checks already ran in the expansion; the ranges are comments xacro never reads,
    so they are judged here, where every command loads, at the cost of parsing one small
    file and only after an expansion (an up-to-date build/render/ci never gets here). The
    config code is imported only for a robot that has a config.xacro."""
    configs = [dep for dep in deps if dep.name == "config.xacro"]
    if configs:
        from ..config.spec import check_own_ranges

        for path in configs:
            check_own_ranges(path)


def refuse_unused_arguments(inputs: list[RobotInput], options: LoadOptions,
                            overriding: bool = False) -> None:
    """UsageError (naming the file) when arguments are given and no input can take them:
    xacro arguments and dimension overrides (``overriding``) apply to ``.xacro`` files
    only; stdin, which ``mcar build`` expands, may take them."""
    if not (options.has_arguments or overriding):
        return
    if options.through_xacro and any(inp.path is None for inp in inputs):
        return
    if any(inp.is_xacro for inp in inputs):
        return
    first = inputs[0].label if inputs else None
    raise UsageError("NAME:=VALUE, --set and --config apply to .xacro inputs, and this is a "
                     "URDF: give the .xacro it was built from", file=first)


def require_robot_file(inp: RobotInput) -> None:
    """InputError unless the input is a readable file; MacroFileError for a macro file
    (a nameless ``<robot>`` that uses xacro)."""
    _require_readable(inp.path)
    if inp.is_xacro and is_macro_file(inp.path):
        raise MacroFileError(f"{inp.label} is a macro file: include it from a robot file, "
                             "or build its test file")


def _require_readable(path: Path) -> None:
    shown = display_path(path)
    if not path.exists():
        raise InputError("no such file", file=shown)
    if path.is_dir():
        raise InputError("is a directory, not a URDF or xacro file", file=shown)
    problem = not_regular(path)  # before anything opens it: a FIFO would block
    if problem:
        raise InputError(problem, file=shown)
    if not os.access(path, os.R_OK):
        raise InputError("permission denied", file=shown)


def is_macro_file(path: Path) -> bool:
    """True for a well-formed file whose root is a ``<robot>`` without a name."""
    from ..packages.discover import root_element

    root = root_element(path)
    return root is not None and root[0] == "robot" and not root[1]
