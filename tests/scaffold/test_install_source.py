"""The GitHub workflow `mcar init` writes installs mcar from where this mcar came from
(PEP 610's direct_url.json), so it works as written; from a local folder or an index,
which CI cannot use, it writes a marked placeholder and init prints FILE:LINE of the one
line to change. The workflow's other steps pass in the new package as written."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from mobile_car.scaffold.install_source import PLACEHOLDER, install_source, source_of


@pytest.mark.parametrize("record, requirement", [
    ({"url": "https://github.com/acme/mcar.git",
      "vcs_info": {"vcs": "git", "commit_id": "0123abc", "requested_revision": "main"}},
     "mcar @ git+https://github.com/acme/mcar.git@0123abc"),
    ({"url": "https://example.org/mcar-0.1.0-py3-none-any.whl",
      "archive_info": {"hashes": {"sha256": "00"}}},
     "mcar @ https://example.org/mcar-0.1.0-py3-none-any.whl"),
])
def test_a_reachable_source_is_written_as_it_is(record, requirement):
    source = source_of(json.dumps(record))
    assert (source.requirement, source.note) == (requirement, None)


@pytest.mark.parametrize("text", [json.dumps({"url": "file:///home/me/mcar", "dir_info": {}}),
                                  json.dumps({"url": "file:///tmp/mcar.whl",
                                              "archive_info": {}})])
def test_a_local_source_is_a_placeholder_with_a_note(text):
    source = source_of(text)
    assert source.requirement == PLACEHOLDER
    assert source.note == f"mcar was installed from {json.loads(text)['url']}, which CI " \
                          "cannot reach"


@pytest.mark.parametrize("text", ["{not json", "[]", json.dumps({"url": 7})])
def test_a_damaged_record_is_the_placeholder_never_a_pypi_name(text):
    # (PyPI's `mcar` is not this project: `mcar==0.1.0` would fail or install another's)
    source = source_of(text)
    assert (source.requirement, source.note) == (
        PLACEHOLDER, "mcar's record of where it was installed from is damaged")


def _workflow_steps(package: Path) -> list[dict]:
    workflow = yaml.safe_load((package / ".github/workflows/mcar.yml").read_text())
    return workflow["jobs"]["mcar"]["steps"]


def test_init_writes_the_workflow_that_installs_this_mcar(run_mcar, tmp_path):
    made = run_mcar("init", "bot", cwd=tmp_path)
    assert made.returncode == 0, made.stderr
    install = next(step["run"] for step in _workflow_steps(tmp_path / "bot")
                   if step.get("name") == "Install mcar")
    # The requirement this very installation's record gives (the tests import the
    # installed mcar: the same record the mcar process read).
    expected = install_source()
    assert f'pip install "{expected.requirement}"\n' in install
    if expected.note is None:  # installed from git or an https URL: nothing to change
        assert made.stdout == ""
        return
    # `make install` installs from this checkout, a folder: the placeholder, and stdout
    # names the file and line to change
    assert expected.requirement == PLACEHOLDER
    lines = (tmp_path / "bot/.github/workflows/mcar.yml").read_text().splitlines()
    number = next(n for n, line in enumerate(lines, 1) if PLACEHOLDER in line)
    assert made.stdout == (f"bot/.github/workflows/mcar.yml:{number}: replace '{PLACEHOLDER}' "
                           f"with where your CI installs mcar from ({expected.note}), or CI "
                           "fails installing it\n")
    assert "note" not in made.stderr


def test_the_workflows_own_steps_pass_in_the_new_package(run_mcar, tmp_path):
    """The newcomer's first push: init, git init, commit; then each `run:` of the workflow
    but the install (done: this mcar), as GitHub runs it, in the package's checkout."""
    made = run_mcar("init", "demo_description", cwd=tmp_path)
    assert made.returncode == 0, made.stderr
    package = tmp_path / "demo_description"
    if shutil.which("git") is None:
        pytest.skip("git is not installed (the checkout CI runs in is a git one)")
    git = ["git", "-c", "user.name=t", "-c", "user.email=t@example.org"]
    for args in (["init", "-q"], ["add", "-A"], ["commit", "-qm", "first"]):
        subprocess.run([*git, *args], cwd=package, check=True, capture_output=True)
    runs = [step["run"] for step in _workflow_steps(package)
            if "run" in step and step.get("name") != "Install mcar"]
    assert runs == ["mcar ci . --format github --junit-xml mcar-junit.xml"]
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    env.pop("ROS_PACKAGE_PATH", None)
    env.pop("AMENT_PREFIX_PATH", None)
    for run in runs:
        # GitHub runs a step with `bash -e {0}`
        done = subprocess.run(["bash", "-e", "-c", run], cwd=package, env=env,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout + done.stderr
    assert "mcar ci: 3 of 3 files passed" in done.stderr
    # the files the upload step names are there
    assert (package / "mcar-junit.xml").is_file() and (package / "renders").is_dir()
