"""xacro's own test suite (ros/xacro ``test/test_xacro.py``, used in place from
``../shared/upstream-suites/xacro/test/``) with its document helpers routed through
mcar's expansion: the sandboxed child `mcar build` uses (``build_file``, sandbox on).

Upstream builds every document with ``quick_xacro`` (text, read as from stdin, relative
includes starting at the test folder), ``run_xacro`` (the ``xacro`` command) and
``xacro.process``; here they call ``build_file`` and ``mcar build``. Every upstream test
must pass but those listed in xacro_expected_differences.txt, each with its reason (and
in docs/build.md): they are marked xfail(strict=True), so a listed test that starts
passing fails, and the list cannot rot. Nothing of upstream is copied into the project.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
import xml.dom.minidom
from pathlib import Path

import pytest
import xacro
import xacro.cli
from conftest import REPO, mcar_process

SUITE = REPO.parent / "shared" / "upstream-suites" / "xacro" / "test"
DIFFERENCES = Path(__file__).resolve().parent / "xacro_expected_differences.txt"

if not (SUITE / "test_xacro.py").is_file():
    pytest.skip(f"xacro's suite is not at {SUITE} (../shared/upstream-suites)",
                allow_module_level=True)


def expected_differences() -> dict[str, str]:
    """``Class::test`` -> why mcar differs from xacro there."""
    found = {}
    for line in DIFFERENCES.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            test, _, reason = line.partition(" ")
            found[test] = reason.strip()
    return found


def _load_upstream():
    spec = importlib.util.spec_from_file_location("upstream_test_xacro",
                                                  SUITE / "test_xacro.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


upstream = _load_upstream()


def _xacro_error(error: Exception) -> xacro.XacroException:
    """mcar's one-line error as the exception upstream expects of a document it refuses."""
    return xacro.XacroException(str(error))


_PACKAGES: list[Path] = []  # --package-path of every build (see _xacro_package)


def _build(path, mappings, text=None):
    from mobile_car.errors import McarError
    from mobile_car.expand.xacro_build import build_file
    from mobile_car.packages.search import PackageSearch

    try:
        result = build_file(path, dict(mappings or {}), text=text,
                            search=PackageSearch(package_paths=list(_PACKAGES)))
    except McarError as error:
        raise _xacro_error(error) from None
    for warning in result.warnings:  # xacro writes them to stderr; upstream reads them
        print(warning, file=sys.stderr)
    return result.xml


class ThroughMcar:
    """upstream's helpers, each a build by mcar."""

    def quick_xacro(self, xml, cli=None, **kwargs):
        args = {}
        if cli:
            opts, _ = xacro.cli.process_args(cli, require_input=False)
            args.update(vars(opts))
        args.update(kwargs)
        text = xml.read() if hasattr(xml, "read") else xml
        data = text.encode("utf-8") if isinstance(text, str) else text
        return xml_dom(_build(None, args.get("mappings"), text=data))

    def run_xacro(self, input_path, *args):
        mcar_process("build", *(f"--package-path={path}" for path in _PACKAGES),
                     input_path, *args, cwd=SUITE)


def xml_dom(text: str):
    return xml.dom.minidom.parseString(text.encode("utf-8"))


def _process(input_file_name, just_deps=False, xacro_ns=True, verbosity=1, mappings=None):
    """``xacro.process``: the URDF text of a file."""
    return _build(input_file_name, mappings)


def _through_mcar(cls, differences: dict[str, str]):
    """``cls`` with mcar's helpers; its listed tests marked xfail(strict=True), each on a
    method of its own (a test two classes share may differ in one only)."""
    namespace = {"__module__": __name__, "__qualname__": cls.__name__}
    for test, reason in differences.items():
        owner, _, method = test.partition("::")
        if owner == cls.__name__:
            if not callable(getattr(cls, method, None)):
                raise LookupError(f"{DIFFERENCES.name}: {test} is no upstream test")
            namespace[method] = pytest.mark.xfail(strict=True, reason=reason)(
                _own_copy(getattr(cls, method)))
    return type(cls.__name__, (ThroughMcar, cls), namespace)


def _own_copy(method):
    def test(self):
        return method(self)

    test.__name__ = test.__qualname__ = method.__name__
    return test


# Every TestCase of upstream's module, under its own name; the ones that build documents
# build them through mcar (the others test xacro's functions and run as they are).
_DIFFERENCES = expected_differences()
for _name, _cls in vars(upstream).copy().items():
    if isinstance(_cls, type) and _name.startswith("Test") and \
            issubclass(_cls, upstream.unittest.TestCase):
        globals()[_name] = _through_mcar(_cls, _DIFFERENCES)
del _name, _cls


@pytest.fixture(scope="session")
def _xacro_package(tmp_path_factory) -> Path:
    """Upstream finds ``$(find xacro)`` (the PR2 test) through ROS's package index; mcar
    through ``--package-path``: a folder holding a package ``xacro`` whose ``test`` is
    upstream's test folder (a link: its files are read in place)."""
    share = tmp_path_factory.mktemp("packages")
    (share / "xacro").mkdir()
    (share / "xacro" / "package.xml").write_text(
        "<package format=\"3\"><name>xacro</name></package>\n")
    (share / "xacro" / "test").symlink_to(SUITE, target_is_directory=True)
    return share


@pytest.fixture(autouse=True)
def _as_upstream_runs(monkeypatch, _xacro_package):
    """Upstream runs in its test folder (its CMake test does). Its direct calls of xacro's
    functions (``xacro.load_yaml``) find xacro's file stack as any of its document builds
    leaves it in upstream's process; here the builds run in a child, so it is set so."""
    monkeypatch.chdir(SUITE)
    monkeypatch.setattr(xacro, "process", _process)
    monkeypatch.setattr(xacro, "filestack", [None])
    monkeypatch.setattr(xacro, "root_dir", os.curdir)
    monkeypatch.setattr(sys.modules[__name__], "_PACKAGES", [_xacro_package])


def test_the_differences_are_the_ones_docs_build_lists():
    """docs/build.md shows the same list, so a change to one shows in the other."""
    page = (REPO / "docs" / "build.md").read_text()
    section = page.split("## xacro's own test suite", 1)[1].split("\n## ", 1)[0]
    documented = re.findall(r"^\| `(Test\w+::test_\w+)` \|", section, re.M)
    assert sorted(documented) == sorted(expected_differences())
    passing = 143 - len(documented)
    assert f"{passing} pass; these {len(documented)} differ" in section

