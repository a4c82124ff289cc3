"""Which of its control package's controller files a robot runs, where the package ships
one per variant of the robot and the robot names none (no ``<parameters>``): the
package's launch chooses, by the same argument it passes to xacro. ROSbot 2's
``controller.launch.py``::

    controller_config_name = PythonExpression(
        ["'mecanum_drive_controller.yaml' if ", mecanum, " else 'diff_drive_controller.yaml'"])
    ... Command([... "rosbot.urdf.xacro", " mecanum:=", mecanum, ...])

so the robot built with ``mecanum:=true`` runs the first file, at its default (``false``)
the second. mcar reads that choice from the launch files' text (a Python launch's
``PythonExpression``), never runs them, and takes the argument's value from the build:
the ``NAME:=VALUE`` given, else the default the robot's xacro declares. Where it finds no
such choice, or cannot tell the value, it does not pick: :func:`variants` says which
files it could not tell apart.
"""

from __future__ import annotations

import re
from pathlib import Path

MAX_LAUNCH_FILES = 20  # launch files looked at in one package
# "'A.yaml' if ", VAR, " else 'B.yaml'" in a PythonExpression's list
_CHOICE = re.compile(r"""['"]([\w.-]+\.ya?ml)['"]\s*if\s*['"]\s*,\s*([A-Za-z_]\w*)\s*,"""
                     r"""\s*['"]\s*else\s*['"]([\w.-]+\.ya?ml)['"]""")
_TRUE, _FALSE = ("true", "1"), ("false", "0", "")


def launch_choice(loaded, root: Path, files: list[Path],
                  consulted: list | None = None) -> list[Path]:
    """``files`` (a control package's YAML, ``root`` its folder) without those the
    package's launch gives to another variant than the robot as built; all of them where
    no launch says, or the build's value of its argument cannot be told. The launch files
    read are added to ``consulted`` (a check's record depends on them)."""
    if len(files) < 2:
        return files
    names = {path.name for path in files}
    for path, text in _launch_texts(root):
        if consulted is not None:
            consulted.append(path)
        for chosen_if, variable, chosen_else in _CHOICE.findall(text):
            if not {chosen_if, chosen_else} <= names:
                continue
            argument = re.search(rf"""(\w+):=\s*['"]\s*,\s*{variable}\b""", text)
            value = _argument(loaded, argument.group(1)) if argument else None
            if value is None:
                continue
            other = chosen_else if value else chosen_if
            return [path for path in files if path.name != other]
    return files


def _argument(loaded, name: str) -> bool | None:
    """The build's value of xacro argument ``name`` as a launch condition reads it (None:
    not a plain true or false, or not known)."""
    value = getattr(loaded, "mappings", {}).get(name)
    if value is None:
        value = _declared_default(loaded, name)
    if value is None:
        return None
    value = value.strip().lower()
    return True if value in _TRUE else False if value in _FALSE else None


def _declared_default(loaded, name: str) -> str | None:
    from ..load.bounded import read_text_quietly

    declared = re.compile(rf"""<xacro:arg\s+name=["']{re.escape(name)}["']\s+"""
                          r"""default=["']([^"'$]*)["']""")
    for path in loaded.deps:  # (the files xacro read: a .urdf that uses xacro too)
        found = declared.search(read_text_quietly(Path(path)) or "")
        if found:
            return found.group(1)
    return None


def _launch_texts(root: Path) -> list[tuple[Path, str]]:
    """The package's Python launch files (``launch/``) and their text, read within
    limits; a link out of the repository holding the package is not read."""
    from ..load.bounded import read_text_quietly
    from ..packages.asset_roots import link_out_of, repository_of

    repository = repository_of(root)
    paths = sorted((root / "launch").glob("*.py"))[:MAX_LAUNCH_FILES]
    return [(path, text) for path in paths if link_out_of(path, repository) is None
            for text in [read_text_quietly(path)] if text]
