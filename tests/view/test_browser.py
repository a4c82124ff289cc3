"""The page in a real browser: Debian's chromium, driven by playwright, draws the robot with
software WebGL (SwiftShader), and a slider moved on the page reaches the server.

playwright's own browser download cannot work here; the test uses /usr/bin/chromium
(`make test` installs the Debian package) and skips where it is absent.
"""

from __future__ import annotations

import io
import os
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("viser", reason='viser is not installed (pip install "mcar[view]"; '
                                    "`make test` installs it)")
sync_api = pytest.importorskip("playwright.sync_api",
                               reason="playwright is not installed (the test extra has it)")

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
        "--disable-background-networking", "--disable-component-update"]
VIEWPORT = {"width": 900, "height": 600}
# Where a person looks at the pictures: view.png, the one docs/view.md shows
# (MCAR_SCREENSHOT_DIR=docs), view-wheel.png (a turned wheel, its markers turned) and
# view-error.png (a whole error message in the panel).
SCREENSHOT_DIR = os.environ.get("MCAR_SCREENSHOT_DIR")
# Every wait below is bounded by this, playwright's own included: its default (30 s for a
# screenshot, a click, a fill) is a fixed wait that a loaded machine overran, taking a
# software-GL screenshot while other tests ran.
SECONDS = 60


@pytest.fixture(scope="module")
def browser():
    """One chromium for the module's tests (its start is ~8 s of CPU with software GL)."""
    if not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} is not installed (Debian package chromium; `make test` "
                    "installs it)")
    with sync_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=ARGS,
                                             timeout=SECONDS * 1000)
        try:
            yield browser
        finally:
            browser.close()


@pytest.fixture
def page(browser):
    """A page of its own (a new browser context: no cookies, storage or cache shared)."""
    context = browser.new_context(viewport=VIEWPORT)
    context.set_default_timeout(SECONDS * 1000)
    try:
        yield context.new_page()
    finally:
        context.close()


def _picture(page, seconds: float = SECONDS) -> np.ndarray:
    from PIL import Image

    shot = page.screenshot(timeout=max(seconds, 1) * 1000)
    with Image.open(io.BytesIO(shot)) as image:
        return np.asarray(image.convert("RGB")).astype(int)


def _red(picture: np.ndarray) -> int:
    """Pixels of the arm's red (the base is grey, the ground white and grey; the red x of
    the axis triad in the corner has about a hundred)."""
    r, g, b = picture[..., 0], picture[..., 1], picture[..., 2]
    return int(((r > 150) & (g < 110) & (b < 110)).sum())


def _until(condition, what: str) -> None:
    """Poll ``condition`` (given the seconds left) until it holds, for SECONDS at most."""
    deadline = time.monotonic() + SECONDS
    while (left := deadline - time.monotonic()) > 0:
        if condition(left):
            return
        time.sleep(0.25)
    pytest.fail(f"within {SECONDS} s: {what}")


def _picture_when(page, condition, what: str) -> np.ndarray:
    """The first screenshot for which ``condition`` holds, within SECONDS: each screenshot
    may take what is left of them, not playwright's own fixed 30 s."""
    pictures = []

    def taken(left):
        pictures.append(_picture(page, left))
        return condition(pictures[-1])

    _until(taken, what)
    return pictures[-1]


def test_the_page_draws_the_robot_and_a_slider_moves_it(served, page):
    page.goto(served.url, timeout=SECONDS * 1000)
    # The panel says the robot's name once the page has the server's state ...
    page.get_by_text("arm", exact=True).wait_for(timeout=SECONDS * 1000)
    # ... and the canvas shows the red arm once WebGL has drawn the meshes.
    robot = _picture_when(page, lambda p: _red(p) > 1500, "the red arm appears on the page")
    if SCREENSHOT_DIR:
        page.screenshot(path=str(Path(SCREENSHOT_DIR) / "view.png"), timeout=SECONDS * 1000)
    # Without the visual geometry the same view is an empty scene: the robot made the
    # difference.
    served.show_visual.value = False
    empty = _picture_when(page, lambda p: _red(p) < 300,
                          "the arm disappears when the visual geometry is switched off")
    differing = (np.abs(robot - empty).max(axis=2) > 16).mean()
    assert differing > 0.01, f"only {differing:.2%} of the pixels show the robot"
    served.show_visual.value = True

    # Type a value into the shoulder slider's box, as a person would.
    box = page.locator(".mantine-NumberInput-input").first
    box.fill("0.75")
    box.press("Enter")
    _until(lambda _: abs(served.joint_values()["shoulder"] - 0.75) < 1e-9,
           "the server sees shoulder = 0.75 from the page")
    assert served.joint_values()["wrist"] == 0.0
    # The link moved on the server, which is what every page then draws (the slider's
    # value is set before its callback poses the links: wait for the pose, not the value).
    from viser.transforms import SO3

    def turned(_) -> bool:
        matrix = SO3(np.asarray(served.frames["upper_arm"].wxyz)).as_matrix()
        return bool(np.isclose(matrix[0, 0], np.cos(0.75))
                    and np.isclose(matrix[0, 2], np.sin(0.75)))

    _until(turned, "the server turns upper_arm by shoulder = 0.75")


def test_a_dimension_typed_on_the_page_rebuilds_the_robot_and_its_yaml_shows(car, page):
    page.goto(car.url, timeout=SECONDS * 1000)
    page.get_by_text("Dimensions", exact=True).click(timeout=SECONDS * 1000)  # (folded)
    page.get_by_text("wheel_radius (m)", exact=True).wait_for(timeout=SECONDS * 1000)
    # The number boxes: the two wheel joints', then the dimensions' from wheel_radius on.
    box = page.locator(".mantine-NumberInput-input").nth(len(car.sliders))
    assert box.input_value() == "0.0325"
    box.fill("0.04")
    box.press("Enter")
    # (The overrides are taken once the car is built, and the car is shown just after: a
    # loaded machine can be read between the two.)
    _until(lambda _: car.dimensions.values == {"wheel_radius": 0.04}
           and car.model.urdf.joint_map["base_joint"].origin[2, 3] == 0.04,
           "the server rebuilds and shows the car with wheel_radius = 0.04 from the page")
    page.get_by_text("Copy overrides as --config YAML").click()
    area = page.locator("textarea").first
    _until(lambda _: area.is_visible() and area.input_value() == "wheel_radius: 0.04\n",
           "the page shows the overrides as YAML")


# Each element from the error box up to the panel: (scrollWidth, clientWidth).
_WIDTHS = """e => { const out = [];
  for (let n = e; n && !(n.className || "").toString().includes("mantine-Paper-root");
       n = n.parentElement) out.push([n.scrollWidth, n.clientWidth]);
  return out; }"""


# Columns of the scene left of the control panel and of the near wheel it half hides (the
# facets of a turning cylinder's rim shade differently there, markers or not): the far
# wheel's marker shows over the chassis.
CANVAS = 500


def _magenta(picture: np.ndarray) -> int:
    """Pixels of the joint markers' spokes (nothing else on the car is magenta)."""
    r, g, b = picture[..., 0], picture[..., 1], picture[..., 2]
    return int(((r > 170) & (g < 90) & (b > 120)).sum())


def _changed(one: np.ndarray, other: np.ndarray) -> int:
    """Scene pixels that differ clearly (not by a shade) between two pictures."""
    return int((np.abs(one[:, :CANVAS] - other[:, :CANVAS]).max(axis=2) > 48).sum())


@pytest.mark.slow
def test_a_turned_wheel_is_seen_turning(car, page):
    page.goto(car.url, timeout=SECONDS * 1000)
    page.get_by_text("wheel_left_joint", exact=True).wait_for(timeout=SECONDS * 1000)
    rest = _picture_when(page, lambda p: _magenta(p[:, :CANVAS]) > 40,
                         "the wheels' joint markers appear")
    for slider in car.sliders.values():
        slider.value = 1.2
    turned = _picture_when(page, lambda p: _changed(rest, p) > 150,
                           "the wheels' markers turn with them")
    if SCREENSHOT_DIR:
        page.screenshot(path=str(Path(SCREENSHOT_DIR) / "view-wheel.png"),
                        timeout=SECONDS * 1000)
    # The control: without the markers, the plain cylinders turning back change nothing.
    car.show_markers.value = False
    hidden = _picture_when(page, lambda p: _magenta(p[:, :CANVAS]) < 5,
                           "the markers are switched off")
    for slider in car.sliders.values():
        slider.value = 0.0
    box = page.locator(".mantine-NumberInput-input").first
    _until(lambda _: box.input_value() == "0", "the page has the wheels at 0")
    _picture(page)  # (a frame drawn after the update)
    back = _picture(page)
    # (a plain cylinder's facets shade a few dozen rim pixels differently as it turns: 44
    # on a loaded machine; the markers move hundreds)
    unmarked, marked = _changed(hidden, back), _changed(rest, turned)
    assert unmarked < 80 and 3 * unmarked < marked, (unmarked, marked)


@pytest.mark.slow
def test_the_pages_share_one_robot_as_docs_view_says(served, page, browser):
    """The state is the viewer's, not the page's (docs/view.md): a page opened later opens
    with the joint values set, and a joint moved in one page moves in every page."""
    page.goto(served.url, timeout=SECONDS * 1000)
    first = page.locator(".mantine-NumberInput-input").first  # the shoulder's box
    first.fill("0.75")
    first.press("Enter")
    _until(lambda _: served.joint_values()["shoulder"] == 0.75, "the server has 0.75")
    context = browser.new_context(viewport=VIEWPORT)
    context.set_default_timeout(SECONDS * 1000)
    try:
        later = context.new_page()
        later.goto(served.url, timeout=SECONDS * 1000)
        second = later.locator(".mantine-NumberInput-input").first
        _until(lambda _: second.input_value() == "0.75", "a later page opens at 0.75")
        second.fill("-0.5")
        second.press("Enter")
        _until(lambda _: first.input_value() == "-0.5", "the first page follows the second")
    finally:
        context.close()
    assert served.joint_values()["shoulder"] == -0.5
    page_text = (Path(__file__).resolve().parents[2] / "docs" / "view.md").read_text()
    assert "one robot for every page" in " ".join(page_text.split())


@pytest.mark.slow
def test_a_dragged_dimension_slider_lands_on_a_plausible_value_and_an_error_shows_whole(
        car, page):
    page.goto(car.url, timeout=SECONDS * 1000)
    page.get_by_text("Dimensions", exact=True).click(timeout=SECONDS * 1000)  # (folded)
    page.get_by_text("wheel_radius (m)", exact=True).wait_for(timeout=SECONDS * 1000)
    # A value that does not fit: the whole message, wrapped at the panel's edge.
    error = car.set_dimension("track_width", 0.3)  # the brackets stick out of the plate
    assert error is not None and len(car.errors[0]) > 200  # far wider than the panel
    box = page.locator(".mcar-errors")
    box.wait_for(timeout=SECONDS * 1000)
    assert box.inner_text() == car.errors[0]  # every word of it, as text
    # Nothing between it and the panel is wider than it shows: no hidden scroll.
    widths = box.evaluate(_WIDTHS)
    assert widths and all(scroll <= client for scroll, client in widths), widths
    assert box.bounding_box()["height"] > 4 * 12  # on several rows
    if SCREENSHOT_DIR:
        page.screenshot(path=str(Path(SCREENSHOT_DIR) / "view-error.png"),
                        timeout=SECONDS * 1000)
    # The control: the same message in a markdown code block, as the page showed it
    # before, is one row wider than the panel, its end behind a scroll bar.
    car.status.content = "```\n" + car.errors[0] + "\n```"
    block = page.locator("pre").first
    block.wait_for(timeout=SECONDS * 1000)
    scroll, client = block.evaluate("e => [e.scrollWidth, e.clientWidth]")
    assert scroll > 2 * client

    # Then a drag: it lands on a plausible value (and, built, clears the message).
    slider = car.dimension_sliders["wheel_radius"]
    span = (slider.min, slider.max)
    # The sliders: the two wheel joints', then the dimensions' from wheel_radius on.
    track = page.locator(".mantine-Slider-root").nth(len(car.sliders)).bounding_box()
    thumb = page.locator(".mantine-Slider-thumb").nth(len(car.sliders)).bounding_box()
    x, y = thumb["x"] + thumb["width"] / 2, thumb["y"] + thumb["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + track["width"] / 4, y, steps=4)  # a quarter of the track right
    page.mouse.up()

    def landed(_):  # (past the values the drag sent on its way)
        value = car.dimensions.values.get("wheel_radius", 0.0)
        return value > 0.0325 + (span[1] - span[0]) / 10 and value == slider.value \
            and _base_height(car) == value and not car.errors

    _until(landed, "the dragged wheel_radius rebuilds the car")
    value = car.dimensions.values["wheel_radius"]
    # A quarter of 16.2..65 mm is some 12 mm: a wheel a little bigger, on the 0.2 mm grid.
    assert 0.0325 < value <= 0.0325 + (span[1] - span[0]) / 4 + 0.002, value
    assert round(value / 0.0002) * 0.0002 == pytest.approx(value, abs=1e-12)
    # (A quarter of the slider it replaced, 5 mm..0.5 m, was a wheel 124 mm bigger.)
    assert (value - 0.0325) * 8 < (0.5 - 0.005) / 4


def _base_height(view) -> float:
    return float(view.model.urdf.joint_map["base_joint"].origin[2, 3])
