"""A record in a checkout may have come with a pull request: mcar reuses only the records
its own user's key sealed (mobile_car/record_seal.py).

The attack: a robot that passes ``mcar ci``, its records kept; then the robot is broken
and the records forged to match it (stamps with the new file's size and sha256, sealed
with the attacker's own key), all committed. The victim's ``mcar ci`` must check the robot
and fail; the same forgery on the attacker's own machine (same key) is replayed, which is
the control that shows the forgery is a real one.
"""

from __future__ import annotations

import glob
import hashlib
import json
import os
from pathlib import Path

import pytest

GOOD = ('<robot name="r">\n  <link name="a"/>\n  <joint name="j" type="fixed">'
        '<parent link="a"/><child link="b"/></joint>\n  <link name="b"/>\n</robot>\n')
BROKEN = GOOD.replace('child link="b"', 'child link="missing"')


def _forge(package: Path, key_dir: Path) -> None:
    """Rewrite every stamp of urdf/r.urdf in the records to the broken file, and seal
    them again with the key in ``key_dir`` (what an attacker can do with their own)."""
    from mobile_car import record_seal

    source = package / "urdf" / "r.urdf"
    data = source.read_bytes()
    digest = hashlib.sha256(data).hexdigest()

    def fix(node):
        if isinstance(node, list) and len(node) == 3 and str(node[0]).endswith("urdf/r.urdf"):
            node[1:] = [[len(data), 0, 0, 0, 0], digest]  # [path, identity, sha256]
        for child in node.values() if isinstance(node, dict) else \
                node if isinstance(node, list) else ():
            fix(child)

    saved = os.environ.get(record_seal.CACHE_DIR_ENV)
    os.environ[record_seal.CACHE_DIR_ENV] = str(key_dir)
    try:
        for path in [package / "build" / ".mcar-ci.json",
                     *map(Path, glob.glob(str(package / "renders" / ".mcar-render.json")))]:
            document = json.loads(path.read_text())
            section = "items" if path.name == ".mcar-ci.json" else "outputs"
            fix(document[section])
            path.write_text(record_seal.sealed_text(section, document[section]))
    finally:
        if saved is None:
            os.environ.pop(record_seal.CACHE_DIR_ENV)
        else:
            os.environ[record_seal.CACHE_DIR_ENV] = saved


@pytest.fixture
def planted(run_mcar, tmp_path):
    """A package whose broken robot comes with records forged under the attacker's key."""
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>p</name></package>\n")
    source = package / "urdf" / "r.urdf"
    source.write_text(GOOD)
    attacker = tmp_path / "attacker-cache"
    first = run_mcar("ci", cwd=package, env={"MCAR_CACHE_DIR": str(attacker)})
    assert first.returncode == 0, first.stderr
    assert (package / "build" / ".mcar-ci.json").is_file()
    source.write_text(BROKEN)
    _forge(package, attacker)
    return package, attacker


def test_a_forged_record_from_elsewhere_is_not_replayed(run_mcar, planted, tmp_path):
    package, _ = planted
    result = run_mcar("ci", cwd=package, env={"MCAR_CACHE_DIR": str(tmp_path / "victim")})
    assert result.returncode == 1, result.stdout + result.stderr
    assert "FAILED (check)" in result.stdout
    assert "child link 'missing' is not defined" in result.stderr


def test_control_the_forgery_fools_the_key_that_sealed_it(run_mcar, planted):
    """Were the seal not checked (or the attacker's key ours), the forgery would pass."""
    package, attacker = planted
    check = run_mcar("check", "urdf/r.urdf", cwd=package)
    assert check.returncode == 1
    result = run_mcar("ci", cwd=package, env={"MCAR_CACHE_DIR": str(attacker)})
    assert result.returncode == 0, result.stdout + result.stderr


def test_an_unsealed_or_edited_record_is_ignored(tmp_path, monkeypatch):
    from mobile_car import record_seal
    from mobile_car.freshness import read_record, write_record

    monkeypatch.setenv(record_seal.CACHE_DIR_ENV, str(tmp_path / "cache"))
    record = tmp_path / "record.json"
    write_record(record, "items", {"a.urdf": {"check": {"passed": False}}})
    assert read_record(record, "items") == {"a.urdf": {"check": {"passed": False}}}
    key = tmp_path / "cache" / record_seal.KEY_NAME
    assert oct(key.stat().st_mode & 0o777) == "0o600" and len(key.read_bytes()) == 32

    edited = json.loads(record.read_text())
    edited["items"]["a.urdf"]["check"]["passed"] = True
    record.write_text(json.dumps(edited))
    assert read_record(record, "items") == {}
    del edited[record_seal.SEAL_FIELD]
    record.write_text(json.dumps(edited))
    assert read_record(record, "items") == {}


def test_without_a_place_for_the_key_nothing_is_reused(run_mcar, tmp_path):
    """A cache folder that cannot be made: the run works, and writes no record."""
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>p</name></package>\n")
    (package / "urdf" / "r.urdf").write_text(GOOD)
    env = {"MCAR_CACHE_DIR": str(blocker / "cache")}
    for _ in range(2):
        result = run_mcar("ci", cwd=package, env=env)
        assert result.returncode == 0, result.stderr
    assert not (package / "build" / ".mcar-ci.json").exists()
    assert (package / "renders" / "r.png").is_file()
