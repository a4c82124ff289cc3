"""`mcar sweep` end to end, as a user runs it: the installed command over the bundled car,
results read back with pandas and compared with what config.xacro and `mcar sim` say."""

from __future__ import annotations

import itertools
import json
import math
import os
import signal
import subprocess
import tempfile
import time
from pathlib import Path

import pytest
from conftest import MCAR, REPO, clean_environ, mcar_process

pd = pytest.importorskip("pandas", reason="the sweep extra (pip install 'mcar[sweep]')")

ROBOT = str(REPO / "urdf" / "mobile_robot.xacro")
# The 60 points: 12 wheel radii by 5 track widths.
GRID = ["--vary", "wheel_radius=25mm..45mm:12", "--vary", "track_width=0.15..0.17:5"]
RADII = [0.025 + 0.02 * i / 11 for i in range(12)]
TRACKS = [0.15, 0.155, 0.16, 0.165, 0.17]
# Columns that say when and where a row was made, not what it found.
RUN_COLUMNS = ["worker", "validate_s", "build_s", "check_s", "sim_s", "total_s"]
KILL_WORKER = Path(__file__).parent / "kill_worker"
# Points of the sweeps a signal interrupts: the results file appears with the first row,
# and the signal follows it within 0.2 s, so six leave the sweep well under way (a point
# takes ~0.3 s or more).
SIGNALLED = 12  # points: enough that a SIGINT sent at the first row lands before the last


def sweep(*args, cwd, env=None, timeout=300):
    return mcar_process("sweep", *args, cwd=cwd, env={**clean_environ(), **(env or {})},
                        timeout=timeout)


def findings(frame):
    """What a row found: everything but where and when it ran."""
    return frame.drop(columns=RUN_COLUMNS).reset_index(drop=True)


@pytest.fixture(scope="module")
def grid_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    done = sweep(ROBOT, *GRID, "--jobs", "2", "-o", "results.parquet", "--plot", "plot.png",
                 cwd=folder)
    return done, pd.read_parquet(folder / "results.parquet"), folder


@pytest.fixture(scope="module")
def dimensions():
    done = subprocess.run([str(MCAR), "config", ROBOT, "--format", "json"],
                          capture_output=True, text=True, check=True)
    table = json.loads(done.stdout)
    return {name: entry["value"] for part in ("dimensions", "derived")
            for name, entry in table[part].items()}


def test_sixty_points_make_sixty_rows_in_grid_order(grid_run):
    done, frame, _ = grid_run
    assert done.returncode == 0, done.stderr
    assert list(frame["point"]) == list(range(60))
    expected = list(itertools.product(RADII, TRACKS))
    assert [(r, t) for r, t in zip(frame["wheel_radius"], frame["track_width"], strict=True)] \
        == [pytest.approx(pair, abs=1e-12) for pair in expected]
    assert set(frame["status"]) <= {"ok", "rejected"}


def test_rejections_name_the_constraint_config_xacro_states(grid_run, dimensions):
    """Which points config.xacro's checks refuse, worked out here from its numbers."""
    _, frame, _ = grid_run
    d = dimensions
    for row in frame.to_dict("records"):
        wheel_y = row["track_width"] / 2
        bracket_outer = wheel_y - d["wheel_width"] / 2 - d["wheel_hub_length"] - \
            d["wheel_hub_clearance"]
        if bracket_outer > d["plate_width"] / 2 + 1e-12:
            expected = "the motor brackets stick out of the plate"
        elif wheel_y - d["wheel_width"] / 2 <= d["plate_width"] / 2 + 1e-12:
            expected = "the wheels overlap the chassis"
        else:
            expected = ""
        assert (row["constraint"], row["valid"]) == (expected, not expected), row
        if expected:
            assert row["status"] == "rejected" and row["reason"].startswith(expected + ": ")
            assert math.isnan(row["speed_ratio"]) and math.isnan(row["build_s"])
    counts = frame["constraint"].value_counts().to_dict()
    assert counts == {"the wheels overlap the chassis": 24,
                      "the motor brackets stick out of the plate": 12, "": 24}


def test_valid_points_are_simulated_with_figures_that_follow_the_geometry(grid_run):
    _, frame, _ = grid_run
    ok = frame[frame["status"] == "ok"]
    assert len(ok) == 24
    assert (ok["speed_ratio"] - 1).abs().max() < 0.02
    assert (ok["yaw_ratio"] - 1).abs().max() < 0.05
    assert ok["tilt_deg"].max() < 1.0 and ok["height_error_m"].max() < 0.001
    for _, same_track in ok.groupby("track_width"):  # bigger wheels, faster car
        assert list(same_track["speed_m_s"]) == sorted(same_track["speed_m_s"])
    for column in ("build_s", "check_s", "sim_s", "validate_s", "mass_kg"):
        assert (ok[column] > 0).all()
    assert (ok["check_errors"] == 0).all() and (ok["check_warnings"] == 0).all()


def test_a_row_says_what_mcar_sim_says_of_that_point(grid_run):
    _, frame, _ = grid_run
    row = frame[frame["status"] == "ok"].iloc[3]
    done = subprocess.run(
        [str(MCAR), "sim", ROBOT, "--format", "json", "--set",
         f"wheel_radius={float(row['wheel_radius'])!r}", "--set",
         f"track_width={float(row['track_width'])!r}"],
        capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    scenarios = {s["name"]: {f["name"]: f["value"] for f in s["figures"]}
                 for s in json.loads(done.stdout)["files"][0]["scenarios"]}
    assert scenarios["drive"]["distance error"] == pytest.approx(
        100 * abs(row["speed_ratio"] - 1), rel=1e-5)
    assert scenarios["spin"]["yaw rate error"] == pytest.approx(
        100 * abs(row["yaw_ratio"] - 1), rel=1e-5)
    assert scenarios["drop"]["height error"] == pytest.approx(row["height_error_m"], rel=1e-5)


def test_the_summary_counts_the_rows(grid_run):
    done, _, _ = grid_run
    lines = done.stderr.splitlines()
    assert lines[0].startswith("mcar sweep: 60 points in ")
    assert lines[0].endswith("(2 local workers): 24 ok, 36 rejected")
    assert lines[1:] == ["  rejected 24x: the wheels overlap the chassis",
                         "  rejected 12x: the motor brackets stick out of the plate",
                         "mcar sweep: results in results.parquet, plot in plot.png"]


def test_the_plot_shows_the_sixty_points_over_the_two_dimensions(grid_run, tmp_path):
    """The PNG is the figure of the results table: drawn again from the file, it has the
    same bytes, and that figure's axes and points are what the sweep was."""
    from PIL import Image

    from mobile_car.sweep.plot import draw_sweep, plot_sweep

    _, frame, folder = grid_run
    units = {"wheel_radius": "m", "track_width": "m"}
    with Image.open(folder / "plot.png") as picture:
        assert picture.format == "PNG" and picture.size == (1080, 648)
    plot_sweep(frame, "wheel_radius", "track_width", "speed_m_s", units, tmp_path / "again.png")
    assert (tmp_path / "again.png").read_bytes() == (folder / "plot.png").read_bytes()
    figure = draw_sweep(frame, "wheel_radius", "track_width", "speed_m_s", units)
    axes = figure.axes[0]
    assert (axes.get_xlabel(), axes.get_ylabel()) == ("wheel_radius (mm)", "track_width (mm)")
    assert axes.get_title() == "60 points: 24 valid, 36 rejected"
    drawn = {c.get_gid(): c.get_offsets() for c in axes.collections}
    assert {gid: len(points) for gid, points in drawn.items()} == {
        "valid": 24, "rejected:the wheels overlap the chassis": 24,
        "rejected:the motor brackets stick out of the plate": 12}
    every = sorted((round(x, 6), round(y, 6)) for points in drawn.values() for x, y in points)
    assert every == sorted((round(1000 * r, 6), round(1000 * t, 6))
                           for r, t in itertools.product(RADII, TRACKS))
    assert figure.axes[1].get_ylabel() == "speed (m/s)"


@pytest.fixture(scope="module")
def dask_cluster():
    """A real Dask cluster on 127.0.0.1, two worker processes, shared by the module's
    sweeps that need nothing special of their workers (its start and the workers' first
    imports are paid once)."""
    distributed = pytest.importorskip("distributed", reason="the sweep extra installs Dask")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        yield cluster


def test_a_dask_local_cluster_gives_the_same_rows(grid_run, dask_cluster, tmp_path):
    """The grid's 24 points of two track widths (12 rejected, 12 simulated) on Dask: the
    rows the local workers made of them."""
    _, grid, _ = grid_run
    cluster = dask_cluster
    assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
    done = sweep(ROBOT, GRID[0], GRID[1], "--vary", "track_width=0.15,0.16",
                 "--scheduler", cluster.scheduler_address, "-o", "dask.parquet", cwd=tmp_path)
    worker_pids = {w.pid for w in cluster.workers.values() if hasattr(w, "pid")}
    assert done.returncode == 0, done.stderr
    assert f"(Dask scheduler {cluster.scheduler_address}): 12 ok, 12 rejected" in done.stderr
    remote = pd.read_parquet(tmp_path / "dask.parquet")
    local = grid[grid["track_width"].isin([0.15, 0.16])]
    assert list(remote["point"]) == list(range(24))
    pd.testing.assert_frame_equal(findings(remote).drop(columns="point"),
                                  findings(local).drop(columns="point"))
    ran_on = {int(w.rsplit(":", 1)[1]) for w in remote["worker"] if w}
    assert ran_on and (not worker_pids or ran_on <= worker_pids)
    assert os.getpid() not in ran_on


def test_csv_and_stdout_hold_what_parquet_holds(grid_run, tmp_path):
    """Four of the grid's points, as CSV to a file and to stdout: the numbers the grid's
    Parquet file holds for them."""
    _, parquet, _ = grid_run
    subset = parquet[parquet["track_width"] == 0.16].iloc[[0, 4, 7, 11]]
    radii = ",".join(repr(float(r)) for r in subset["wheel_radius"])
    words = [ROBOT, "--vary", f"wheel_radius={radii}", "--vary", "track_width=0.16",
             "--jobs", "1"]
    to_file = sweep(*words, "-o", "r.csv", cwd=tmp_path)
    to_stdout = sweep(*words, "-o", "-", cwd=tmp_path)
    assert to_file.returncode == to_stdout.returncode == 0, to_file.stderr + to_stdout.stderr
    csv = pd.read_csv(tmp_path / "r.csv", keep_default_na=False, na_values=[""])
    assert to_stdout.stdout.splitlines()[0] == (tmp_path / "r.csv").read_text().splitlines()[0]
    assert list(csv["point"]) == list(range(4))
    for column in ("wheel_radius", "speed_ratio", "yaw_ratio", "mass_kg"):
        assert list(csv[column]) == pytest.approx(list(subset[column]), rel=1e-12)
    assert list(csv["status"]) == list(subset["status"])


def test_resume_keeps_finished_rows_and_runs_only_the_missing_points(tmp_path):
    words = [ROBOT, "--vary", "wheel_radius=25mm..45mm:6", "--vary", "track_width=0.16,0.165",
             "--jobs", "2", "-o", "r.csv"]
    assert sweep(*words, cwd=tmp_path).returncode == 0
    full = (tmp_path / "r.csv").read_text().splitlines()
    header, rows = full[0], full[1:]
    # Keep 5 rows, and mark one so that a re-run of it would show.
    marked = rows[2].split(",")
    marked[header.split(",").index("total_s")] = "999.0"
    (tmp_path / "r.csv").write_text("\n".join([header, *rows[:2], ",".join(marked),
                                               *rows[3:5]]) + "\n")
    done = sweep(*words, "--resume", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "12 points in" in done.stderr and "5 from the earlier run" in done.stderr
    frame = pd.read_csv(tmp_path / "r.csv")
    assert list(frame["point"]) == list(range(12))
    assert frame.loc[2, "total_s"] == 999.0  # kept, not run again
    assert (frame["total_s"] < 999).sum() == 11


@pytest.mark.parametrize("signum, code, said", [(signal.SIGINT, 130, "mcar: interrupted"),
                                               (signal.SIGTERM, 143, "mcar: terminated")])
def test_a_signal_keeps_the_finished_rows_and_resume_finishes(tmp_path, signum, code, said):
    """... and leaves no temporary file: the worker stopped mid-point is killed, and its
    files (the point's overrides, its config probe) go with the sweep's own folder."""
    words = [ROBOT, "--vary", f"wheel_radius=25mm..45mm:{SIGNALLED}", "--vary", "track_width=0.16",
             "--jobs", "1", "-o", "r.parquet"]
    # (A short TMPDIR: multiprocessing puts its fork server's socket in it, and a socket
    # path past ~100 characters, as under pytest's tmp_path, is refused.)
    scratch = Path(tempfile.mkdtemp(prefix="mcar-t-"))
    process = subprocess.Popen([str(MCAR), "sweep", *words], cwd=tmp_path,
                               env={**os.environ, "TMPDIR": str(scratch)},
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (tmp_path / "r.parquet").exists() and time.monotonic() < deadline:
        time.sleep(0.2)  # the file is saved with the first row done
    process.send_signal(signum)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == code, stderr
    kept = pd.read_parquet(tmp_path / "r.parquet")
    assert 0 < len(kept) < SIGNALLED
    assert stderr.splitlines()[-2:] == [
        f"mcar sweep: {len(kept)} of {SIGNALLED} points kept in r.parquet; --resume runs the "
        "rest",
        said]
    assert set(kept["status"]) == {"ok"} and kept["speed_ratio"].notna().all()
    assert sorted(p.name for p in scratch.iterdir()) == []
    scratch.rmdir()
    done = sweep(*words, "--resume", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    frame = pd.read_parquet(tmp_path / "r.parquet")
    assert list(frame["point"]) == list(range(SIGNALLED)) and set(frame["status"]) == {"ok"}
    pd.testing.assert_frame_equal(frame.iloc[:len(kept)].reset_index(drop=True), kept)


def test_a_killed_worker_loses_only_its_point_which_runs_again(tmp_path, grid_run):
    _, parquet, _ = grid_run
    env = {"PYTHONPATH": str(KILL_WORKER), "SWEEP_TEST_KILL_POINT": "3",
           "SWEEP_TEST_KILL_ONCE": str(tmp_path / "killed-once")}
    words = [ROBOT, "--vary", "wheel_radius=25mm..45mm:12", "--vary", "track_width=0.16",
             "--jobs", "2", "-o", "r.parquet"]
    done = sweep(*words, cwd=tmp_path, env=env)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "killed-once").exists()  # the worker was killed
    frame = pd.read_parquet(tmp_path / "r.parquet")
    assert list(frame["point"]) == list(range(12)) and set(frame["status"]) == {"ok"}
    assert frame.loc[3, "attempts"] == 2
    subset = parquet[parquet["track_width"] == 0.16].reset_index(drop=True)
    assert list(frame["speed_ratio"]) == pytest.approx(list(subset["speed_ratio"]), rel=1e-12)


def test_a_point_that_always_kills_its_worker_is_reported(tmp_path):
    env = {"PYTHONPATH": str(KILL_WORKER), "SWEEP_TEST_KILL_POINT": "1"}
    words = [ROBOT, "--vary", "wheel_radius=25mm..45mm:4", "--vary", "track_width=0.16",
             "--jobs", "2", "-o", "r.csv"]
    done = sweep(*words, cwd=tmp_path, env=env)
    assert done.returncode == 1, done.stderr
    frame = pd.read_csv(tmp_path / "r.csv", keep_default_na=False)
    assert list(frame["status"]) == ["ok", "crashed", "ok", "ok"]
    assert frame.loc[1, "attempts"] == 2
    assert ("  point 1 crashed: its worker process died twice (killed, or crashed in native "
            "code): the point was retried once, alone") in done.stderr.splitlines()


def test_runs_from_inside_a_source_checkout(tmp_path):
    """The workers import the installed mcar, not the checkout's mobile_car/ folder that
    the working directory would put first on their path."""
    done = sweep("--vary", "wheel_radius=25mm,30mm", "-o", tmp_path / "r.csv", cwd=REPO)
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines()[0] == f"mcar: package mobile_car_description ({REPO})"
    frame = pd.read_csv(tmp_path / "r.csv")
    assert list(frame["status"]) == ["ok", "ok"]


def test_the_workers_import_nothing_from_the_working_folder(tmp_path):
    """The fork server the local workers come from imports what a point needs before any
    worker starts; a numpy.py or a mobile_car/ in the folder mcar runs in is not it."""
    marker = tmp_path / "imported"
    planted = f"open({str(marker)!r}, 'a').write(__name__ + '\\n')\n"
    (tmp_path / "numpy.py").write_text(planted)
    (tmp_path / "mujoco.py").write_text(planted)
    (tmp_path / "mobile_car").mkdir()
    (tmp_path / "mobile_car" / "__init__.py").write_text(planted)
    done = sweep(ROBOT, "--vary", "wheel_radius=25mm,45mm", "--jobs", "2", "-o", "r.csv",
                 cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert list(pd.read_csv(tmp_path / "r.csv")["status"]) == ["ok", "ok"]
    assert not marker.exists(), marker.read_text()


def test_on_dask_a_point_that_kills_its_workers_is_reported(tmp_path, monkeypatch):
    """Dask reschedules the point of a dead worker itself; when the scheduler gives up
    (allowed-failures, here 1), the point is a crashed row and the others are done."""
    distributed = pytest.importorskip("distributed", reason="the sweep extra installs Dask")
    import dask

    monkeypatch.setenv("PYTHONPATH", str(KILL_WORKER))  # the worker processes load it
    monkeypatch.setenv("SWEEP_TEST_KILL_POINT", "2")
    # Saturation 1: a worker holds only the point it runs. Dask counts a worker's death
    # against every point it holds, queued ones too (1.1, the default, queues a second
    # point on a one-thread worker), and with one allowed failure an innocent queued point
    # would be given up on as well.
    with dask.config.set({"distributed.scheduler.allowed-failures": 1,
                          "distributed.scheduler.worker-saturation": 1.0}), \
            distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                     host="127.0.0.1", dashboard_address=None) as cluster:
        done = sweep(ROBOT, "--vary", "wheel_radius=25mm..45mm:4", "--vary", "track_width=0.16",
                     "--scheduler", cluster.scheduler_address, "-o", "r.csv", cwd=tmp_path)
    assert done.returncode == 1, done.stderr
    frame = pd.read_csv(tmp_path / "r.csv", keep_default_na=False)
    assert list(frame["status"]) == ["ok", "ok", "crashed", "ok"]
    assert ("  point 2 crashed: the Dask workers running it died; the scheduler retried it "
            "and gave up (allowed-failures)") in done.stderr.splitlines()


def test_on_dask_ctrl_c_keeps_the_finished_rows_and_resume_finishes(dask_cluster, tmp_path):
    words = [ROBOT, "--vary", f"wheel_radius=25mm..45mm:{SIGNALLED}", "--vary",
             "track_width=0.16", "--scheduler", dask_cluster.scheduler_address, "-o",
             "r.parquet"]
    process = subprocess.Popen([str(MCAR), "sweep", *words], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (tmp_path / "r.parquet").exists() and time.monotonic() < deadline:
        time.sleep(0.2)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 130, stderr
    kept = pd.read_parquet(tmp_path / "r.parquet")
    assert 0 < len(kept) < SIGNALLED and set(kept["status"]) == {"ok"}
    done = sweep(*words, "--resume", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert f"{len(kept)} from the earlier run" in done.stderr
    frame = pd.read_parquet(tmp_path / "r.parquet")
    assert list(frame["point"]) == list(range(SIGNALLED)) and set(frame["status"]) == {"ok"}


def test_a_terminal_sees_a_progress_bar_and_a_log_does_not(tmp_path):
    import pty

    words = [ROBOT, "--vary", "wheel_radius=25mm..45mm:6", "--jobs", "2"]
    leader, follower = pty.openpty()
    with os.fdopen(leader, "rb", buffering=0) as terminal:
        process = subprocess.Popen([str(MCAR), "sweep", *words, "-o", "tty.csv"], cwd=tmp_path,
                                   stdout=subprocess.DEVNULL, stderr=follower)
        os.close(follower)
        seen = b""
        while True:
            try:
                chunk = terminal.read(4096)
            except OSError:  # the process closed the terminal's other end
                break
            if not chunk:
                break
            seen += chunk
        assert process.wait(timeout=120) == 0
    text = seen.decode()
    assert "mcar sweep  [" in text and "6/6" in text, text
    logged = sweep(*words, "-o", "log.csv", cwd=tmp_path)
    assert logged.returncode == 0 and "[" not in logged.stderr and "6/6" not in logged.stderr
