"""mcar specs on the command line: the same figures as text, JSON and Markdown; notes on
stderr; exit 0, 1 for a robot that fails its check or a figure its proof contradicts, 2
for bad usage, each said in one line."""

from __future__ import annotations

import json

import pytest
from specs import robots

from mobile_car.specs.figures import Figure, Proof, Section

BODY_KEYS = {"body.mass", "body.com", "body.com_height", "body.footprint",
             "body.radius.circumscribed", "body.radius.inscribed", "body.clearance",
             "wheels.radius", "wheels.track", "wheels.wheelbase"}
LOADS = {"loads.wheel_left_link", "loads.wheel_right_link", "loads.castor_link"}


@pytest.fixture(scope="module")
def car_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("specs_cli") / "car.urdf"
    path.write_text(robots.box_on_wheels())
    return path


def _specs(cli, *args):
    return cli("specs", *args, terminal_width=200)


def test_json_gives_every_body_figure_by_key(cli, car_file):
    result = _specs(cli, car_file, "--format", "json")
    assert result.exit_code == 0, result.stderr
    document = json.loads(result.stdout)
    (entry,) = document["files"]
    assert document["exit_code"] == entry["exit_code"] == 0
    assert entry["robot"] == "box_on_wheels"
    figures = entry["figures"]
    assert BODY_KEYS | LOADS <= set(figures)
    mass = figures["body.mass"]
    assert (mass["value"], mass["unit"], mass["section"], mass["proof"]) == (5.2, "kg", "body",
                                                                            None)
    assert figures["body.footprint"]["value"][0] == [-0.1, -0.1]
    assert figures["wheels.wheelbase"]["value"] is None
    assert figures["wheels.wheelbase"]["source"].startswith("one axle")
    assert all(f["source"] for f in figures.values())
    assert entry["sections"][0] == {"name": "body", "notes": [], "diagnostics": []}


def test_text_is_a_table_per_section_with_sources(cli, car_file):
    result = _specs(cli, car_file, "--no-proof")
    assert result.exit_code == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].endswith("car.urdf (box_on_wheels)")
    assert lines[1] == "  body"
    mass = next(line for line in lines if line.lstrip().startswith("mass "))
    assert mass.split()[:3] == ["mass", "5.2", "kg"] and "<inertial><mass> of 4 links" in mass
    assert any(line.split()[:4] == ["track", "0.26", "m", "between"] for line in lines)
    assert any("wheelbase" in line and "—  one axle" in line for line in lines)
    assert "8 points (-0.1..0.2 × -0.15..0.15) m" in result.stdout
    assert result.stderr == ""


def test_markdown_is_a_table_a_pull_request_shows(cli, car_file):
    result = _specs(cli, car_file, "--format", "markdown")
    assert result.exit_code == 0, result.stderr
    text = result.stdout
    assert text.startswith("## mcar specs: box\\_on\\_wheels (")
    assert "### body\n\n| figure | key | value | source | assumes |\n|---|---|---|---|---|\n" \
        in text
    # the description's tags are escaped, else a Markdown page would swallow them as HTML
    assert "| mass | body.mass | 5.2 kg | \\<inertial\\>\\<mass\\> of 4 links |  |" in text
    assert "| load on castor\\_link | loads.castor\\_link | " in text


def test_a_figure_its_proof_contradicts_fails_the_run(cli, car_file, monkeypatch):
    """Exit 1, one line on stderr naming the figure and both values; the table shows the
    proof beside the figure (the proofs are the statics and sensors sections')."""
    from mobile_car.specs import compute

    real = compute.computed

    def with_proofs(checked, options):
        context = real(checked, {**options, "proof": False})
        proved = Section("statics", figures=[
            Figure("statics.tip.left", "tip angle, left", 23.4, "deg", "support polygon",
                   proof=Proof(23.5, True, "1°")),
            Figure("statics.tip.forward", "tip angle, forward", 30.0, "deg",
                   "support polygon", proof=Proof(19.0, False, "1°", "tipped on a slope"))])
        context.sections = [context.sections[0], proved]
        return context

    monkeypatch.setattr(compute, "computed", with_proofs)
    result = _specs(cli, car_file)
    assert result.exit_code == 1
    assert result.stderr.splitlines() == [
        f"{car_file}: error: statics.tip.forward (tip angle, forward): 30° computed, MuJoCo "
        "measured 19° (tolerance 1°): tipped on a slope"]
    (left,) = [line for line in result.stdout.splitlines() if "tip angle, left" in line]
    assert left.split()[3:] == ["23.4°", "MuJoCo", "23.5°", "✓", "support", "polygon"]
    assert "30°  MuJoCo 19° ✗ disagrees  support polygon" in result.stdout
    document = json.loads(_specs(cli, car_file, "--format", "json").stdout)
    assert document["exit_code"] == 1
    assert document["files"][0]["figures"]["statics.tip.forward"]["proof"] == {
        "measured": 19.0, "agrees": False, "tolerance": "1°", "detail": "tipped on a slope"}


def test_a_robot_that_fails_its_check_is_reported_as_check_does(cli, tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text(robots.box_on_wheels().replace('<sphere radius="0.02"/>',
                                                  '<sphere radius="0"/>'))
    result = _specs(cli, bad)
    check = cli("check", bad)
    assert result.exit_code == check.exit_code == 1
    assert result.stdout == ""
    # check's own lines, its summary left out
    assert result.stderr.splitlines() == check.stderr.splitlines()[:-1]
    line = next(n for n, text in enumerate(bad.read_text().splitlines(), 1)
                if '<sphere radius="0"/>' in text)
    assert f'{bad}:{line}: error: link \'castor_link\' <collision>: <sphere radius="0"> must ' \
           'be > 0 [E113]' in result.stderr.splitlines()


@pytest.mark.parametrize(("args", "message"), [
    (["nowhere.urdf"], "nowhere.urdf: error: no such file"),
    (["--left", "wheel_left_joint"], "mcar: error: --left and --right go together: name both "
                                     "drive joints"),
])
def test_bad_usage_is_one_line_exit_2(run_mcar, car_file, args, message):
    words = args if args[0] == "nowhere.urdf" else [car_file, *args]
    result = run_mcar("specs", *words)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [message]
    assert result.stdout == ""


def test_a_robot_on_stdin(run_mcar, car_file):
    result = run_mcar("specs", "-", "--format", "json", input=car_file.read_text())
    assert result.returncode == 0, result.stderr
    figures = json.loads(result.stdout)["files"][0]["figures"]
    assert figures["wheels.track"]["value"] == pytest.approx(0.26)


def test_help_explains_frames_sections_and_sources(cli):
    text = cli("specs", "--help", terminal_width=100).output
    for words in ("root frame", "floor frame", "base_footprint", "body ", "statics ",
                  "joints ", "sensors ", "stack ", "inertia ", "Sources, in the order",
                  "--no-proof", "--friction MU", "--fix-inertia", "docs/specs.md"):
        assert words in text, words
    assert "--picture FILE.png" in text


def test_a_proof_that_saw_something_else_first_says_what():
    """A tip angle MuJoCo could not reach (the robot slid first) shows what happened, not a
    bare tick beside "not measured"."""
    from mobile_car.specs.report import SpecsReport, text_table

    section = Section("statics", figures=[
        Figure("statics.tip.left", "tip-over angle left", 67.9, "deg", "support polygon",
               proof=Proof(None, True, "±1°", "slides at 43.78° before it could tip",
                           instead="slid first at 43.8°")),
        Figure("statics.tip.right", "tip-over angle right", 67.9, "deg", "support polygon",
               proof=Proof(None, False, "±1°", "neither slid nor tipped"))])
    rows = text_table(SpecsReport("robot.urdf", "robot", [section]))
    assert rows[2].split()[3:] == ["67.9°", "MuJoCo", "slid", "first", "at", "43.8°", "✓",
                                   "support", "polygon"]
    assert "67.9°  MuJoCo not measured ✗ disagrees" in rows[3]
