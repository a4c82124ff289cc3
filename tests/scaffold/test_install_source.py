"""The GitHub workflow `mcar init` writes installs mcar from where this mcar came from
(PEP 610's direct_url.json), so it works as written; from a local folder, which CI cannot
reach, it writes a marked placeholder and init says what to replace."""

from __future__ import annotations

import json

import pytest
import yaml

from mobile_car.scaffold.install_source import PLACEHOLDER, source_of


@pytest.mark.parametrize("record, requirement", [
    ({"url": "https://github.com/acme/mcar.git",
      "vcs_info": {"vcs": "git", "commit_id": "0123abc", "requested_revision": "main"}},
     "mcar @ git+https://github.com/acme/mcar.git@0123abc"),
    ({"url": "https://example.org/mcar-0.1.0-py3-none-any.whl",
      "archive_info": {"hashes": {"sha256": "00"}}},
     "mcar @ https://example.org/mcar-0.1.0-py3-none-any.whl"),
])
def test_a_reachable_source_is_written_as_it_is(record, requirement):
    source = source_of(json.dumps(record), "0.1.0")
    assert (source.requirement, source.note) == (requirement, None)


@pytest.mark.parametrize("text", [json.dumps({"url": "file:///home/me/mcar", "dir_info": {}}),
                                  json.dumps({"url": "file:///tmp/mcar.whl",
                                              "archive_info": {}})])
def test_a_local_source_is_a_placeholder_with_a_note(text):
    source = source_of(text, "0.1.0")
    assert source.requirement == PLACEHOLDER
    assert source.note.startswith("mcar was installed from file:///")
    assert source.note.endswith(f"replace '{PLACEHOLDER}' with where your CI installs "
                                "mcar from")


def test_a_damaged_record_falls_back_to_the_version():
    assert source_of("{not json", "0.1.0").requirement == "mcar==0.1.0"


def test_init_writes_the_workflow_that_installs_this_mcar(run_mcar, tmp_path):
    made = run_mcar("init", "bot", cwd=tmp_path)
    assert made.returncode == 0, made.stderr
    workflow = yaml.safe_load((tmp_path / "bot/.github/workflows/mcar.yml").read_text())
    steps = workflow["jobs"]["mcar"]["steps"]
    install = next(step["run"] for step in steps if step.get("name") == "Install mcar")
    # the test suite's mcar is installed from this checkout (make install): a folder CI
    # cannot reach, so the placeholder, and one note saying what to replace
    assert f'pip install "{PLACEHOLDER}"' in install
    notes = [line for line in made.stderr.splitlines() if line.startswith("mcar: note:")]
    assert len(notes) == 1 and "replace" in notes[0] and ".github/workflows/mcar.yml" in notes[0]
