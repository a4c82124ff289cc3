"""Fixtures every test module shares: the installed mcar, the real check_urdf, the repo."""

from __future__ import annotations

import gc
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

REPO = Path(__file__).resolve().parent.parent
TESTS = REPO / "tests"
# The installed console script next to the interpreter running the tests (the venv's).
MCAR = Path(sys.executable).parent / "mcar"


def pytest_configure(config):
    """The run's own cache folder (records' seal key, mesh facts, check results): the
    tests neither read what the developer's mcar kept nor leave anything in it.

    Python's cyclic garbage collector is off while the tests are collected: collecting
    makes a million objects that live to the end (modules, rewritten asserts, items), and
    the collector walked them again and again, a third of each worker's collection CPU
    (2.3 of 7.3 s, measured); pytest_collection_finish turns it back on. (The parallel
    run's controller collects nothing: it keeps its collector.)"""
    if hasattr(config, "workerinput") or not config.getoption("numprocesses", None):
        gc.disable()
    if "MCAR_CACHE_DIR" not in os.environ:
        import tempfile

        os.environ["MCAR_CACHE_DIR"] = _OWN_CACHE[0] = tempfile.mkdtemp(
            prefix="mcar-tests-cache-")


def pytest_unconfigure(config):
    if _OWN_CACHE[0] is not None:
        shutil.rmtree(_OWN_CACHE[0], ignore_errors=True)
        os.environ.pop("MCAR_CACHE_DIR", None)
        _OWN_CACHE[0] = None


_OWN_CACHE: list = [None]


def pytest_collection_finish(session):
    """What collection made is kept to the end: frozen, later collections skip it."""
    gc.collect()
    gc.freeze()
    gc.enable()


def pytest_itemcollected(item):
    """A test sharing a module-scoped fixture is marked with its module's xdist_group as
    it is collected (before xdist reads the marks)."""
    if _shares_module_fixture(item):
        item.add_marker(pytest.mark.xdist_group(item.module.__name__))


def pytest_collection_modifyitems(config, items):
    """The order and grouping `make test`'s parallel workers (pytest-xdist, --dist
    loadgroup) take the tests in: a module whose tests share a module-scoped fixture (a
    sweep, a simulated robot) goes whole to one worker, which makes the fixture once; and
    the slowest tests and groups start first (tests/durations.txt), so that no worker is
    left alone at the end with one long test begun last."""
    seconds = _durations()
    weight: dict[str, float] = {}
    for item in items:
        key = _group(item)
        took = seconds.get(_plain_id(item), 0.0)
        weight[key] = weight.get(key, 0.0) + took
        if took >= SLOW_SECONDS:  # `make test-quick` (-m "not slow") leaves it out
            item.add_marker(pytest.mark.slow)
    order = {item.nodeid: i for i, item in enumerate(items)}

    def key(item):
        group = _group(item)
        return (-weight[group], group if group != item.nodeid else "", order[item.nodeid])

    items.sort(key=key)


SLOW_SECONDS = 5.0  # alone, in tests/durations.txt


def _group(item) -> str:
    """The xdist group pytest_itemcollected gave the test, else its own id."""
    mark = item.get_closest_marker("xdist_group")
    return mark.args[0] if mark is not None else item.nodeid


def _plain_id(item) -> str:
    """The test's id without the "@group" xdist's loadgroup may have added."""
    head, at, group = item.nodeid.rpartition("@")
    return head if at and "]" not in group and "::" not in group else item.nodeid


def _shares_module_fixture(item) -> bool:
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return False
    return any(definition.scope == "module" for definitions in info.name2fixturedefs.values()
               for definition in definitions)


def _durations() -> dict[str, float]:
    found = {}
    for line in (TESTS / "durations.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            number, nodeid = line.split(" ", 1)
            found[nodeid] = float(number)
    return found


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def mcar_bin() -> Path:
    if not MCAR.exists():
        pytest.fail(f"mcar is not installed next to {sys.executable}; run `make install`")
    return MCAR


@pytest.fixture(scope="session", autouse=True)
def _launcher():
    """The process mcar runs are forked from (tests/zygote.py): started before the first
    test can change the environment, ended with the session."""
    import zygote

    zygote.start_shared(MCAR)
    yield
    zygote.close_shared()


def clean_environ() -> dict:
    """This environment without ROS's package variables (a test gives them when it wants)."""
    return {name: value for name, value in os.environ.items()
            if name not in ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH")}


def mcar_process(*args, cwd=None, input=None, env=None, timeout=120, text=True):
    """`mcar ARGS` as its own process, as a user runs it, started through tests/zygote.py;
    what subprocess.run(..., capture_output=True) returns. ``env``: the whole environment
    (default: clean_environ())."""
    from zygote import run_mcar_process

    return run_mcar_process(MCAR, args, cwd=cwd, input=input,
                            env=clean_environ() if env is None else dict(env),
                            timeout=timeout, text=text)


@pytest.fixture
def run_mcar(mcar_bin):
    """Run the installed `mcar` as its own process: run_mcar("build", "x.xacro", cwd=...),
    ``env`` adding to the environment; what subprocess.run(..., capture_output=True,
    text=True) returns."""

    def run(*args, cwd=None, input=None, env=None, timeout=120):
        return mcar_process(*args, cwd=cwd, input=input, env={**clean_environ(), **(env or {})},
                            timeout=timeout)

    return run


@pytest.fixture
def cli():
    """Invoke the click group in-process; returns click's Result (output, exit_code)."""
    from mobile_car.cli.main import main

    runner = CliRunner()

    def invoke(*args, **kwargs):
        return runner.invoke(main, [str(a) for a in args], catch_exceptions=False, **kwargs)

    return invoke


@pytest.fixture(scope="session")
def gl_reason() -> str | None:
    """Why OpenGL cannot run here, or None (the same probe mcar render uses)."""
    from mobile_car.render.backend import GLProbe

    return GLProbe().wait()


@pytest.fixture
def quiet_renderer(gl_reason) -> tuple[str, ...]:
    """Arguments that pick a renderer without a fallback warning: the default where OpenGL
    works, else the ray caster by name (for tests about output, not about renderers)."""
    return () if gl_reason is None else ("--renderer", "raycast")


@pytest.fixture
def package_copy(tmp_path) -> Path:
    """A scratch copy of mobile_car_description that a test may edit."""
    import shutil

    copy = tmp_path / "mobile_car_description"
    for name in ("urdf", "meshes"):
        shutil.copytree(REPO / name, copy / name)
    for name in ("package.xml", "mcar.yaml"):
        shutil.copy(REPO / name, copy / name)
    return copy


@pytest.fixture(scope="session")
def check_urdf() -> str:
    """Path of urdfdom's check_urdf; `make test` installs it (Debian liburdfdom-tools)."""
    path = shutil.which("check_urdf")
    if path is None:
        pytest.skip("check_urdf not installed (Debian package liburdfdom-tools; `make test` "
                    "installs it with apt-get)")
    return path


def run_check_urdf(check_urdf: str, path: Path, timeout=60) -> subprocess.CompletedProcess:
    return subprocess.run([check_urdf, str(path)], capture_output=True, text=True,
                          timeout=timeout)


# The Gazebo helper: the one mcar finds (make test builds it beside mcar), else one built
# here from helpers/mcar-sdformat.cc with the Makefile's own rule, into a session folder;
# skipped, saying why, only where libsdformat-dev is not installed.
def sdformat_installed() -> bool:
    return bool(shutil.which("g++") and shutil.which("pkg-config")) and subprocess.run(
        ["pkg-config", "--exists", "sdformat12"]).returncode == 0


@pytest.fixture(scope="session")
def gazebo_helper(tmp_path_factory) -> Path:
    from mobile_car.errors import GazeboUnavailable
    from mobile_car.gazebo.helper import find_helper

    try:
        return find_helper()
    except GazeboUnavailable:
        pass
    if not sdformat_installed():
        pytest.skip("the Gazebo helper cannot be built here: g++, pkg-config or "
                    "libsdformat-dev (sdformat 12) is missing (`make test` installs them)")
    built = tmp_path_factory.mktemp("helper") / "mcar-sdformat"
    done = subprocess.run(["make", "-s", "-C", str(REPO), "gazebo-helper",
                           f"GAZEBO_HELPER={built}"], capture_output=True, text=True, timeout=600)
    assert built.is_file(), done.stdout + done.stderr
    return built


@pytest.fixture
def gazebo(gazebo_helper, monkeypatch) -> dict:
    """The environment that names the helper: set here (in-process runs) and returned
    (for run_mcar's env=)."""
    monkeypatch.setenv("MCAR_SDFORMAT", str(gazebo_helper))
    return {"MCAR_SDFORMAT": str(gazebo_helper)}


def line_of(source, text: str) -> int:
    """The number of the first line of ``source`` (a file's Path, or the text itself)
    holding ``text``: where a test expects a message to point."""
    content = source.read_text() if isinstance(source, Path) else source
    return next(n for n, line in enumerate(content.splitlines(), 1) if text in line)
