"""mcar.yaml, a package's own settings: which files are robots, which robots ci does not
simulate and why; every mistake in it a located error."""

from __future__ import annotations

from pathlib import Path

import pytest

from mobile_car.errors import EXIT_USAGE, InputError, UsageError
from mobile_car.packages.package_config import load_package_config


def package(tmp_path: Path, text: str | None) -> Path:
    (tmp_path / "package.xml").write_text("<package format='3'><name>p</name></package>")
    if text is not None:
        (tmp_path / "mcar.yaml").write_text(text)
    return tmp_path


def test_no_file_selects_everything_and_skips_nothing(tmp_path):
    config = load_package_config(package(tmp_path, None))
    assert config.path is None
    assert config.selects(tmp_path / "urdf" / "robot.urdf.xacro") == (True, None)
    assert config.sim_skip_reason(tmp_path / "urdf" / "robot.urdf.xacro") is None


def test_include_exclude_and_skip_by_glob(tmp_path):
    root = package(tmp_path, "robots:\n  include: ['urdf/*.xacro']\n"
                             "  exclude:\n    - 'urdf/accessories/*'\n"
                             "sim:\n  skip:\n    'urdf/arm*': '  an arm,\n   fixed base '\n")
    config = load_package_config(root)
    assert config.selects(root / "urdf" / "robot.urdf.xacro") == (True, None)
    # '*' crosses folders, as fnmatch does
    assert config.selects(root / "urdf" / "wheel" / "test_wheel.urdf.xacro") == (True, None)
    taken, why = config.selects(root / "urdf" / "empty.urdf")
    assert not taken and why == "not in robots.include of mcar.yaml:2"
    taken, why = config.selects(root / "urdf" / "accessories" / "lidar.urdf.xacro")
    assert not taken and why == "robots.exclude 'urdf/accessories/*' of mcar.yaml:3"
    assert config.sim_skip_reason(root / "urdf" / "arm.urdf.xacro") == "an arm, fixed base"
    assert config.sim_skip_reason(root / "urdf" / "robot.urdf.xacro") is None
    # a file outside the package is not the package's to select
    assert config.selects(tmp_path.parent / "elsewhere.urdf") == (True, None)


@pytest.mark.parametrize("text, strict", [(None, None), ("ci:\n  strict: true\n", True),
                                          ("ci:\n  strict: false\n", False), ("ci:\n", None)])
def test_ci_strict_is_what_the_file_says(tmp_path, text, strict):
    assert load_package_config(package(tmp_path, text)).strict is strict


def test_the_bundled_package_and_new_packages_ask_for_a_strict_ci(tmp_path):
    from conftest import REPO

    from mobile_car.scaffold import TEMPLATES

    assert load_package_config(REPO).strict is True
    (tmp_path / "mcar.yaml").write_text((TEMPLATES / "package" / "mcar.yaml").read_text())
    assert load_package_config(tmp_path).strict is True


def test_export_names_formats_for_the_robots_its_globs_take(tmp_path):
    root = package(tmp_path, "export:\n  formats: [urdf, mjcf, urdf]\n"
                             "  robots: ['urdf/*.urdf.xacro']\n")
    config = load_package_config(root)
    assert config.exports(root / "urdf" / "robot.urdf.xacro") == ("urdf", "mjcf")
    assert config.exports(root / "urdf" / "wheel.xacro") == ()
    (tmp_path / "b").mkdir()
    assert load_package_config(package(tmp_path / "b", "sim:\n")).exports(
        tmp_path / "b" / "x.urdf") == ()


@pytest.mark.parametrize("text, line, message", [
    ("robot:\n  include: []\n", 1,
     "unknown key 'robot': mcar.yaml takes robots, sim, export, ci, assets"),
    ("robots:\n  includes: ['x']\n", 2,
     "unknown key 'robots.includes': robots takes include, exclude"),
    ("robots:\n  include: urdf/*.xacro\n", 2,
     "robots.include: expected a list of globs, got 'urdf/*.xacro'"),
    ("sim:\n  skip: ['a.urdf']\n", 2,
     "sim.skip: expected a mapping of glob to reason (text), got ['a.urdf']"),
    ("sim:\n  skip:\n    a.urdf:\n", 2,
     "sim.skip: expected a mapping of glob to reason (text), got {'a.urdf': None}"),
    ("robots: [1]\n", 1, "robots: expected a mapping, got [1]"),
    ("export:\n  formats: [mjcf, gltf]\n", 2,
     "export.formats: unknown format 'gltf' (mcar export takes mjcf, usd, urdf, sdf)"),
    ("- 1\n", None, "expected a mapping with robots, sim, export, ci, assets, got [1]"),
    ("ci:\n  strict: yes please\n", 2, "ci.strict: expected true or false, got 'yes please'"),
    ("ci:\n  strict: 1\n", 2, "ci.strict: expected true or false, got 1"),
    ("assets:\n  paths: meshes\n", 2, "assets.paths: expected a list of folders, got 'meshes'"),
    ("robots:\n  include: []\n  include: []\n", 3, None),  # duplicate key
    ("robots: {include: [\n", 2, None),  # broken YAML
])
def test_mistakes_are_located_usage_errors(tmp_path, text, line, message):
    root = package(tmp_path, text)
    with pytest.raises(UsageError) as caught:
        load_package_config(root)
    error = caught.value
    assert error.exit_code == EXIT_USAGE
    assert error.file == str(root / "mcar.yaml")
    assert error.line == line
    if message is not None:
        assert error.message == message


def test_object_tags_are_refused_not_built(tmp_path):
    root = package(tmp_path, "robots: !!python/object/apply:os.system ['touch marker']\n")
    with pytest.raises(UsageError):
        load_package_config(root)
    assert not (tmp_path / "marker").exists()


def test_a_fifo_is_refused_without_waiting(tmp_path):
    import os

    root = package(tmp_path, None)
    os.mkfifo(root / "mcar.yaml")
    with pytest.raises(InputError) as caught:
        load_package_config(root)
    assert "FIFO" in caught.value.message


def test_an_empty_file_is_no_settings(tmp_path):
    config = load_package_config(package(tmp_path, "# nothing yet\n"))
    assert config.path is not None and config.include == () and config.sim_skip == ()
