"""Plain `mcar ci -v`, run inside each released package of the shared real-robots folder
(issue 26), exits 0 with every robot built, checked, simulated and drawn, and lists the
fragments it skipped. Those packages have no mcar.yaml, so their warnings (TurtleBot3's
castor inertias, waffle's missing base mesh, Husky's <axis rpy>) are shown, not failed;
`--strict` fails them, as an mcar.yaml's `ci: strict: true` does."""

from __future__ import annotations

import re

import pytest
from packages.test_discovery import FOLDER, REAL, needs_folder

pytestmark = needs_folder


def ci(run_mcar, package, tmp_path, *more):
    return run_mcar("ci", "-v", *more, "--package-path", FOLDER,
                    "--build-dir", tmp_path / "build", "--render-dir", tmp_path / "renders",
                    cwd=FOLDER / package, timeout=600)


@pytest.mark.parametrize("package", sorted(REAL))
def test_ci_passes_each_real_package_showing_its_warnings(package, run_mcar, tmp_path):
    robots, fragments = REAL[package]
    result = ci(run_mcar, package, tmp_path)
    assert result.returncode == 0, result.stderr
    lines = result.stderr.splitlines()
    # (", gazebo" where the Gazebo helper is installed)
    assert re.match(rf"mcar ci: {len(robots)} of {len(robots)} files passed "
                    r"\(build, check(, gazebo)?, sim, render\) in ", lines[-1]), lines[-1]
    rows = {row.split()[0]: row.split() for row in result.stdout.splitlines()[1:]}
    assert set(rows) == {name.removeprefix("urdf/") for name in robots}
    for row in rows.values():
        assert row[-1] == "ok" and row[-2].endswith(".png"), row
        assert (tmp_path / "renders" / row[-2].rsplit("/", 1)[-1]).stat().st_size > 1000
        assert any(kind in row for kind in ("differential", "skid-steer")), row
    for name, reason in fragments.items():
        assert f"mcar: skipped {name}: {reason}" in lines
    if package == "turtlebot3_description":  # warnings shown on their lines, not failed
        assert any("[W213]" in line and "caster_back_link" in line for line in lines)
        assert any("[W207]" in line and "waffle_base.stl" in line for line in lines)
        strict = ci(run_mcar, package, tmp_path, "--strict", "--no-render", "--no-sim")
        assert strict.returncode == 1
        assert "mcar ci: 0 of 3 files passed (build, check --strict" in strict.stderr
