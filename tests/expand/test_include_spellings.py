"""Every include xacro reads, mcar reads: ``./inner.xacro``, ``sub//inner.xacro``,
``../common/inner.xacro``, a symlinked include, and each of them from stdin (relative to
the working folder, as xacro reads them). xacro names an include as it is spelt; the
sandboxed build's check of the files the child says it read compares files, not
spellings. And an argument whose name only exists after evaluation
(``$(arg ${'v'+'ar'})``) is one the file reads, not an unknown one."""

from __future__ import annotations

from pathlib import Path

import pytest

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PACKAGE_XML = ('<package format="3"><name>spelt</name><version>0.0.0</version>'
               '<description>x</description><maintainer email="a@b.c">a</maintainer>'
               '<license>MIT</license></package>\n')


def _inner(link: str) -> str:
    return f'<robot {XACRO_NS} name="inner"><link name="{link}"/></robot>\n'


@pytest.fixture(scope="module")
def package(tmp_path_factory) -> Path:
    """spelt/ (a package): urdf/inner.xacro, urdf/sub/inner.xacro, common/inner.xacro,
    urdf/link.xacro -> real_inner.xacro; each inner file names its own link."""
    root = tmp_path_factory.mktemp("spellings") / "spelt"
    (root / "urdf" / "sub").mkdir(parents=True)
    (root / "common").mkdir()
    (root / "package.xml").write_text(PACKAGE_XML)
    (root / "urdf" / "inner.xacro").write_text(_inner("from_dot"))
    (root / "urdf" / "sub" / "inner.xacro").write_text(_inner("from_sub"))
    (root / "common" / "inner.xacro").write_text(_inner("from_up"))
    (root / "urdf" / "real_inner.xacro").write_text(_inner("from_link"))
    (root / "urdf" / "link.xacro").symlink_to("real_inner.xacro")
    return root


SPELLINGS = [("./inner.xacro", "from_dot"), ("sub//inner.xacro", "from_sub"),
             ("../common/inner.xacro", "from_up"), ("link.xacro", "from_link"),
             ("sub/../inner.xacro", "from_dot")]


def _top(package: Path, spelling: str) -> Path:
    name = "top_" + "".join(c if c.isalnum() else "_" for c in spelling) + ".xacro"
    top = package / "urdf" / name
    top.write_text(f'<robot {XACRO_NS} name="r"><xacro:include filename="{spelling}"/>'
                   '<link name="base"/></robot>\n')
    return top


@pytest.mark.parametrize(("spelling", "link"), SPELLINGS)
def test_an_include_builds_however_it_is_spelt(package, spelling, link, run_mcar):
    top = _top(package, spelling)
    result = run_mcar("build", top, "-o", "-")
    assert result.returncode == 0, result.stderr
    assert f'<link name="{link}"/>' in result.stdout
    assert '<link name="base"/>' in result.stdout


@pytest.mark.parametrize(("spelling", "link"), SPELLINGS)
def test_an_include_read_from_stdin_starts_at_the_working_folder(package, spelling, link,
                                                                  run_mcar):
    top = _top(package, spelling)
    result = run_mcar("build", "-", "-o", "-", cwd=top.parent, input=top.read_text())
    assert result.returncode == 0, result.stderr
    assert f'<link name="{link}"/>' in result.stdout


def test_an_include_from_stdin_elsewhere_is_missing_as_xacro_says(package, tmp_path,
                                                                   run_mcar):
    """The control: from another working folder the same text names no file."""
    top = _top(package, "./inner.xacro")
    result = run_mcar("build", "-", "-o", "-", cwd=tmp_path, input=top.read_text())
    assert result.returncode == 1
    assert "No such file or directory" in result.stderr, result.stderr
    assert "inner.xacro" in result.stderr


def test_a_symlinked_folder_on_the_input_path(package, tmp_path, run_mcar):
    """The input named through a link to its folder: xacro reads the include through the
    link, the build's roots are where the link leads."""
    link = tmp_path / "linked_urdf"
    link.symlink_to(package / "urdf", target_is_directory=True)
    _top(package, "./inner.xacro")
    result = run_mcar("build", link / "top___inner_xacro.xacro", "-o", "-",
                      cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert '<link name="from_dot"/>' in result.stdout


COMPUTED = f'<robot {XACRO_NS} name="r"><link name="$(arg ${{\'v\'+\'ar\'}})"/></robot>\n'


def test_an_argument_named_by_an_expression_is_read(tmp_path, run_mcar):
    robot = tmp_path / "computed.xacro"
    robot.write_text(COMPUTED)
    result = run_mcar("build", robot, "-o", "-", "var:=x")
    assert result.returncode == 0, result.stderr
    assert '<link name="x"/>' in result.stdout


def test_an_argument_nothing_reads_is_still_refused(tmp_path, run_mcar):
    """mcar's stricter rule stands for a name the expansion never looked up."""
    robot = tmp_path / "computed.xacro"
    robot.write_text(COMPUTED)
    result = run_mcar("build", "computed.xacro", "-o", "-", "var:=x", "vra:=1",
                      cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr == ("mcar: error: unknown xacro argument 'vra' (did you mean "
                             "'var'?); computed.xacro accepts: var\n")
    assert "Traceback" not in result.stderr


def test_an_argument_named_by_an_expression_from_stdin(tmp_path, run_mcar):
    result = run_mcar("build", "-", "-o", "-", "var:=y", cwd=tmp_path, input=COMPUTED)
    assert result.returncode == 0, result.stderr
    assert '<link name="y"/>' in result.stdout

