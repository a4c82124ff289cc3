"""What other repositories and CI servers use: pre-commit hooks, the example workflow,
shell completion, colour rules, --version."""

from __future__ import annotations

import os
import pty
import re
import subprocess

import yaml
from conftest import MCAR, REPO


def test_pre_commit_manifest_is_valid_and_its_entries_run(tmp_path):
    from pre_commit.clientlib import load_manifest

    hooks = {hook["id"]: hook for hook in load_manifest(str(REPO / ".pre-commit-hooks.yaml"))}
    assert set(hooks) == {"mcar-check", "mcar-ci"}
    tracked = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True,
                             check=True).stdout.split()
    # The description's own files (the test corpus's broken files are broken on purpose).
    matched = [f for f in tracked
               if re.search(hooks["mcar-check"]["files"], f) and f.startswith("urdf/")]
    assert "urdf/wheel/test_wheel.urdf.xacro" in matched and "urdf/tutorial/03_color.urdf" \
        in matched
    entry = hooks["mcar-check"]["entry"].split()
    assert entry[0] == "mcar"
    done = subprocess.run([str(MCAR), *entry[1:], *matched], cwd=REPO, capture_output=True,
                          text=True, timeout=120)
    assert (done.returncode, done.stderr) == (0, "")
    assert hooks["mcar-ci"]["pass_filenames"] is False
    assert hooks["mcar-ci"]["args"] == ["."]  # the package is named, not left to chance
    entry = [*hooks["mcar-ci"]["entry"].split(), *hooks["mcar-ci"]["args"]]
    copy = tmp_path / "repo"
    subprocess.run(["git", "clone", "-q", str(REPO), str(copy)], check=True)
    done = subprocess.run([str(MCAR), *entry[1:]], cwd=copy, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert (copy / ".mcar-build" / "mobile_robot.urdf").is_file()


def readme_ci_commands() -> list[str]:
    readme = (REPO / "README.md").read_text()
    section = readme.split("## mcar in CI and in scripts", 1)[1]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    return [line.split("#")[0].strip() for line in block.splitlines() if line.strip()]


def test_example_workflow_runs_the_commands_the_readme_documents():
    workflow = yaml.safe_load((REPO / "examples" / "github-actions.yml").read_text())
    steps = workflow["jobs"]["mcar"]["steps"]
    runs = [line.strip() for step in steps if "run" in step
            for line in step["run"].splitlines() if line.strip()]
    mcar_runs = [line for line in runs if line.startswith("mcar ")]
    # The pull-request run adds the diff against the base branch (a GitHub expression);
    # docs/diff.md documents --against and --diff-report (and the README points there).
    against = re.compile(r" --against .+? --diff-report \S+$")
    assert all("--against" not in line or against.search(line) for line in mcar_runs)
    diff_page = (REPO / "docs" / "diff.md").read_text()
    assert "mcar ci --against" in diff_page and "--diff-report" in diff_page
    assert "mcar ci --against" in (REPO / "README.md").read_text()
    plain = {against.sub("", line) for line in mcar_runs}
    assert mcar_runs and plain <= set(readme_ci_commands())
    apt = next(line for line in runs if "apt-get install" in line)
    makefile = (REPO / "Makefile").read_text()
    for package in ("libegl1", "libegl-mesa0", "libgl1-mesa-dri", "libgl1"):
        assert package in apt.split() and package in makefile


def test_ci_example_command_writes_a_junit_file(run_mcar, tmp_path):
    result = run_mcar("ci", "--bundled", "--format", "github", "--junit-xml",
                      "mcar-junit.xml", "--no-render", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    from xml.etree import ElementTree as ET

    suite = ET.parse(tmp_path / "mcar-junit.xml").getroot().find("testsuite")
    assert suite.get("failures") == "0" and int(suite.get("tests")) > 10


def test_shell_completion_and_version(run_mcar):
    script = subprocess.run([str(MCAR)], env={**os.environ, "_MCAR_COMPLETE": "bash_source"},
                            capture_output=True, text=True).stdout
    assert "_mcar_completion" in script and "complete " in script
    words = subprocess.run([str(MCAR)], capture_output=True, text=True, env={
        **os.environ, "_MCAR_COMPLETE": "bash_complete", "COMP_WORDS": "mcar ch",
        "COMP_CWORD": "1"}).stdout
    assert "plain,check" in words.splitlines()
    assert run_mcar("--version").stdout == "mcar, version 0.1.0\n"


def run_on_a_terminal(args, env) -> str:
    """Run mcar with a pseudo-terminal as stdout and stderr; return what it wrote."""
    leader, follower = pty.openpty()
    process = subprocess.Popen([str(MCAR), *args], stdout=follower, stderr=follower,
                               env={**os.environ, **env}, close_fds=True)
    os.close(follower)
    output = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:
            break
        if not chunk:
            break
        output += chunk
    process.wait(timeout=60)
    os.close(leader)
    return output.decode()


def test_colour_only_on_a_terminal_and_never_with_no_color(run_mcar, tmp_path):
    missing = str(tmp_path / "nope.urdf")
    coloured = run_on_a_terminal(["build", missing], {"NO_COLOR": ""})  # empty: not set
    assert "\x1b[31m" in coloured and "error:" in coloured
    plain = run_on_a_terminal(["build", missing], {"NO_COLOR": "1"})
    assert "\x1b[" not in plain and "error: no such file" in plain
    piped = run_mcar("build", missing)
    assert "\x1b[" not in piped.stderr
