"""A tag left open is reported at the line it opened, not only where expat noticed it
(often the file's last line), by every command that builds; never naming mcar's own
temporary files."""

from __future__ import annotations

import importlib.util

import pytest

BROKEN_LINE = 72
OPEN_TAG = ('<xacro:property> opened here is never closed (the parser noticed at line 167: '
            'mismatched tag)')


@pytest.fixture
def broken_config(package_copy):
    """The package with the ``/`` of line 72's ``<xacro:property …/>`` removed."""
    config = package_copy / "urdf" / "config.xacro"
    lines = config.read_text().splitlines(keepends=True)
    assert len(lines) == 167 and '<xacro:property name="plate_length"' in lines[BROKEN_LINE - 1]
    lines[BROKEN_LINE - 1] = lines[BROKEN_LINE - 1].replace('"/>', '">', 1)
    config.write_text("".join(lines))
    return package_copy


def test_build_names_the_line_the_tag_opened(run_mcar, broken_config):
    result = run_mcar("build", "urdf/mobile_robot.xacro", "-o", "out.urdf", cwd=broken_config)
    assert result.returncode == 1
    assert result.stderr.splitlines() == [
        f"urdf/config.xacro:{BROKEN_LINE}: error: XML parse error: {OPEN_TAG}",
        "  when processing file: urdf/config.xacro",
        "  included from: urdf/mobile_robot.xacro"]
    assert not (broken_config / "out.urdf").exists()


def test_check_names_the_line_the_tag_opened(run_mcar, broken_config):
    result = run_mcar("check", "urdf/mobile_robot.xacro", cwd=broken_config)
    assert result.returncode == 1
    first = result.stderr.splitlines()[0]
    assert first.startswith(f"urdf/config.xacro:{BROKEN_LINE}: error: XML parse error: "
                            f"{OPEN_TAG}; ")
    assert "mcar-probe" not in result.stderr


def test_view_names_the_line_the_tag_opened(run_mcar, broken_config):
    if importlib.util.find_spec("viser") is None:
        pytest.skip('viser is not installed (pip install "mcar[view]")')
    # A robot that does not build is refused before anything is served: no browser needed.
    result = run_mcar("view", "--no-browser", "--port", "0", "urdf/mobile_robot.xacro",
                      cwd=broken_config, timeout=60)
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr.startswith(f"urdf/config.xacro:{BROKEN_LINE}: error: XML parse "
                                    f"error: {OPEN_TAG}")
    assert "mcar-probe" not in result.stderr


@pytest.mark.parametrize("text, message", [
    ('<robot name="r">\n <link name="a">\n </link>\n</robt>\n',
     "x.urdf.xacro:4: error: XML parse error: </robt> closes no open element (expected "
     "</robot>, opened at line 1; mismatched tag, column 3)"),
    ('<robot name="r">\n <link name="a">\n  <visual>\n </link>\n</robot>\n',
     "x.urdf.xacro:3: error: XML parse error: <visual> opened here is never closed (the "
     "parser noticed at line 4: mismatched tag)"),
    ('<robot name="r">\n <link name="a"/>\n',
     "x.urdf.xacro:1: error: XML parse error: <robot> opened here is never closed (the "
     "parser noticed at line 3: no element found)"),
    # Not a nesting mistake: said where expat says it, as before.
    ('<robot name="r">\n <link name="a" name="b"/>\n</robot>\n',
     "x.urdf.xacro:2: error: XML parse error: duplicate attribute (column 17)"),
], ids=["misspelt-end-tag", "inner-tag-left-open", "file-ends-open", "other-error"])
def test_nesting_mistakes_are_said_where_they_were_made(run_mcar, tmp_path, text, message):
    (tmp_path / "x.urdf.xacro").write_text(text)
    result = run_mcar("build", "x.urdf.xacro", "-o", "out.urdf", cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines()[0] == message


def test_an_error_in_config_xacro_does_not_name_the_probe(run_mcar, package_copy):
    # mcar evaluates the dimensions through a temporary probe file that includes
    # config.xacro: before, its path (gone by then) ended the "included from" chain.
    config = package_copy / "urdf" / "config.xacro"
    config.write_text(config.read_text().replace('name="plate_length" value="0.200"',
                                                 'name="plate_length" value="${nope * 2}"', 1))
    result = run_mcar("config", cwd=package_copy)
    assert result.returncode == 1
    lines = result.stderr.splitlines()
    assert lines[1].startswith(f"urdf/config.xacro:{BROKEN_LINE}: error: name 'nope' is not "
                               "defined")
    assert lines[2:] == ["  when processing file: urdf/config.xacro"]
