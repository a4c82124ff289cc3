"""Every shell example of README.md and of the reference pages in docs/, and every `mcar`
step of examples/, runs as written.

The examples of a page are run in order, like a reader following it, in one copy of the
repository with the files of readme/ beside it (the `my_robot.xacro`, `my_car.yaml` and
`broken.urdf` the examples name) and `path/to/...` folders holding copies of the package.

- A ```sh block: each line is a command (a trailing `# comment` is dropped); it must exit
  0, or N when its comment says `exit N`. `cd DIR` moves the following lines of the block.
- A transcript (```` ``` ```` lines starting `$ `): the command's stdout and stderr must be
  the lines shown, up to a `...` line; its exit code is 1 if one of them reports an
  `error:`, else 0.
- A line that is one `mcar` command of plain words runs as the one process bash would
  start for it, through tests/zygote.py; any other line runs in bash.
- Lines that only set up or measure (make, the venv, the benchmarks) are listed in
  NOT_RUN with the reason; anything else in a block is run. Examples of `--gazebo` and
  `--format sdf` (and `export --to sdf`) need the Gazebo helper (`make test` builds it):
  where it is not installed they are left out, as tests/gazebo/ is skipped; `export --to
  usd` likewise without the usd extra.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import REPO, mcar_process

README = REPO / "README.md"
FIXTURES = Path(__file__).parent / "readme"
# Prefixes of lines that are not examples to run here, and why.
NOT_RUN = {
    "make ": "the set-up commands themselves; `make test` runs this test",
    ". .venv/bin/activate": "the tests run with the venv's mcar on PATH already",
    ".venv/bin/python bench/": "benchmarks take minutes; `make bench` runs them",
    "mcar view": "serves until Ctrl-C; tests/view/test_cli_view.py runs it",
    "ROS_PACKAGE_PATH=": "opens RViz until it is closed; tests/ros/test_display_launch.py "
                         "runs it under Xvfb",
}
PACKAGE_COPIES = ("path/to/package", "path/to/other_description")
_COMMENT = re.compile(r"\s+#(?:\s.*)?$")
_EXIT = re.compile(r"#.*\bexit (\d+)\b")


def _blocks(text: str):
    """(kind, first line number, lines) of every fenced block; kind is the info string."""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            kind, start, body = lines[i][3:].strip(), i + 2, []
            i += 1
            while not lines[i].startswith("```"):
                body.append(lines[i])
                i += 1
            yield kind, start, body
        i += 1


def _steps(text: str):
    """Every example of the README as (line number, command, expected exit, expected
    output lines or None, cd-folder for the command)."""
    for kind, start, body in _blocks(text):
        if kind == "sh":
            folder = "."
            for number, line in enumerate(body, start):
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
                command = _COMMENT.sub("", line).strip()
                if any(command.startswith(prefix) for prefix in NOT_RUN):
                    continue
                if command.startswith("cd "):
                    folder = os.path.normpath(os.path.join(folder, command[3:].strip()))
                    continue
                wanted = _EXIT.search(line)
                yield number, command, int(wanted.group(1)) if wanted else 0, None, folder
        elif kind == "" and body and body[0].startswith("$ "):
            for offset, line in enumerate(body):
                if line.startswith("$ "):
                    shown = []
                    for out in body[offset + 1:]:
                        if out.startswith("$ "):
                            break
                        shown.append(out)
                    code = 1 if any(" error: " in out for out in shown) else 0
                    yield start + offset, line[2:], code, shown, "."


def _workspace(tmp: Path) -> Path:
    copy = tmp / "mcar"
    shutil.copytree(REPO, copy, ignore=shutil.ignore_patterns(
        ".git", ".venv", "build", "renders", "__pycache__", "*.egg-info", ".pytest_cache"))
    shutil.copytree(FIXTURES, copy, dirs_exist_ok=True)
    for folder in PACKAGE_COPIES:
        target = copy / folder
        target.mkdir(parents=True)
        for part in ("package.xml", "urdf", "meshes"):
            source = REPO / part
            if source.is_dir():
                shutil.copytree(source, target / part)
            else:
                shutil.copy(source, target / part)
    return copy


def _gazebo_helper_installed() -> bool:
    from mobile_car.errors import GazeboUnavailable
    from mobile_car.gazebo.helper import find_helper

    try:
        find_helper()
    except GazeboUnavailable:
        return False
    return True


def test_readme_examples_run_as_written(tmp_path):
    steps = list(_steps(README.read_text(encoding="utf-8")))
    assert len(steps) >= 20  # the parser found the examples
    _run_steps(tmp_path, steps, "README.md")


# Reference pages under docs/ whose examples run as the README's do (from the repository's
# root, in a copy of it), with how many examples each has at least (the parser found them).
DOC_PAGES = {
    "docs/build.md": 5,
    "docs/check.md": 3,
    "docs/ci.md": 5,
    "docs/config.md": 5,
    "docs/gazebo.md": 1,  # its transcript needs the Gazebo helper: skipped where missing
    "docs/init.md": 3,
    "docs/plausibility.md": 1,
    "docs/render.md": 6,
    "docs/security.md": 1,
    "docs/sim.md": 6,
    "docs/specs.md": 4,
    "docs/sweep.md": 3,
    "docs/view.md": 1,
}
# Pages whose examples are not run here, and why.
DOC_PAGES_NOT_RUN = {
    "docs/locations.md": "illustrations: robot.urdf.xacro and error_in_nested_macro.xacro "
                        "are made up; tests/check/test_locations.py holds the rules",
    "docs/rviz.md": "roslaunch opens RViz; tests/ros/test_display_launch_init.py runs them "
                    "under Xvfb",
}


@pytest.mark.parametrize("page", sorted(DOC_PAGES))
def test_docs_examples_run_as_written(tmp_path, page):
    steps = list(_steps((REPO / page).read_text(encoding="utf-8")))
    assert len(steps) >= DOC_PAGES[page]  # the parser found the examples
    if not _gazebo_helper_installed():
        steps = _without_gazebo(steps)
    if not steps:
        pytest.skip(f"{page}: its examples need the Gazebo helper (`make test` builds it)")
    _run_steps(tmp_path, steps, page)


def test_every_docs_page_with_examples_runs_them():
    """A page that gains an example is run here, or says where it is run."""
    with_examples = {f"docs/{page.name}" for page in (REPO / "docs").glob("*.md")
                     if list(_steps(page.read_text(encoding="utf-8")))}
    assert with_examples <= set(DOC_PAGES) | set(DOC_PAGES_NOT_RUN)
    assert set(DOC_PAGES) | set(DOC_PAGES_NOT_RUN) <= {
        f"docs/{page.name}" for page in (REPO / "docs").glob("*.md")}


def _without_gazebo(steps):
    return [step for step in steps
            if "--gazebo" not in step[1] and "--format sdf" not in step[1]
            and "--to sdf" not in step[1]]


def _run_steps(tmp_path, steps, page: str) -> None:
    if not _gazebo_helper_installed():
        steps = _without_gazebo(steps)
    if importlib.util.find_spec("pxr") is None:  # the usd extra: tests/export skip too
        steps = [step for step in steps if "--to usd" not in step[1]]
    workspace = _workspace(tmp_path)
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    env["NO_COLOR"] = "1"
    failures = []
    for number, command, code, shown, folder in steps:
        result = _run_line(command, workspace / folder, env)
        problem = None
        if result.returncode != code:
            problem = f"exit {result.returncode}, {page} says {code}"
        elif shown is not None:
            printed = (result.stdout + result.stderr).splitlines()
            expected = shown[:shown.index("...")] if "..." in shown else shown
            got = printed[:len(expected)] if "..." in shown else printed
            if got != expected:
                problem = "printed:\n    " + "\n    ".join(printed[:len(expected) + 2])
        if problem:
            failures.append(f"{page}:{number}: {command}\n  {problem}\n  stderr: "
                            f"{result.stderr.strip()[-400:]}")
    assert not failures, "\n".join(failures)


# What makes a line more than one command with its words: the shell runs it.
_SHELL = re.compile(r"""[|&;<>()$`*?~{}\[\]'"\\]""")


def _run_line(command: str, cwd: Path, env: dict) -> subprocess.CompletedProcess:
    """One example line, as bash runs it: a plain `mcar WORDS` line as the one process
    bash would start (through tests/zygote.py), anything else by bash itself."""
    words = command.split()
    if words[0] == "mcar" and not _SHELL.search(command):
        return mcar_process(*words[1:], cwd=cwd, env=env, timeout=300)
    return subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)


# A pull request's base branch, as actions/checkout with fetch-depth: 0 leaves it.
BASE_REF = ("${{ github.base_ref }}", "main")


def _git_clone_with_base_branch(folder: Path) -> None:
    """``folder`` as a git clone whose origin/main is its one commit (for --against)."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed: the examples compare with a git revision")
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com",
               GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@example.com")
    for args in (["init", "-q"], ["add", "."], ["commit", "-qm", "base"],
                 ["update-ref", "refs/remotes/origin/main", "HEAD"]):
        subprocess.run(["git", *args], cwd=folder, env=env, check=True, capture_output=True)


def test_examples_mcar_steps_run_as_written(run_mcar, tmp_path):
    """examples/github-actions.yml's `mcar` steps, in a package made by `mcar init`, in a
    git repository whose origin/main is the pull request's base branch."""
    steps = []
    for example in sorted((REPO / "examples").glob("*.yml")):
        for line in example.read_text(encoding="utf-8").splitlines():
            match = re.match(r"\s*(?:- )?run: (mcar .*)$", line)
            if match:
                steps.append((example.name, match.group(1)))
    assert steps
    assert run_mcar("init", "my_robot_description", cwd=tmp_path).returncode == 0
    _git_clone_with_base_branch(tmp_path)
    for name, command in steps:
        result = run_mcar(*command.replace(*BASE_REF).split()[1:], cwd=tmp_path)
        assert result.returncode == 0, f"{name}: {command}\n{result.stderr}"
