"""The viewer's page in a real headless Chromium: it loads from a file, draws, the slider moves it.

Chromium and its driver come from Debian's packages (``apt-get install chromium
chromium-driver``; .ci/run installs them); nothing downloads a browser at run time. Without
them the test skips, saying so.
"""

from __future__ import annotations

import shutil
import time

import pytest

from kinetology import read, view

from kinetology_fixtures import MOCAP, needs_mocap

BVH = MOCAP / "bandai-namco-1" / "data" / "dataset-1_bow_active_001.bvh"
AMC = MOCAP / "cmu-subject02" / "02_01.amc"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")

pytestmark = [
    pytest.mark.skipif(CHROMIUM is None or DRIVER is None,
                       reason="headless browser test: chromium and chromedriver not installed "
                              "(apt-get install chromium chromium-driver)"),
    needs_mocap,
]

# the canvas's pixels, read by the page itself: where the bones are (the bone-grey pixels'
# indices: the pose, whatever colour the joints' states give them) and how many pixels have a
# state's colour
_PIXELS = """
const canvas = document.querySelectorAll("canvas")[arguments[0]];
const d = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
const bones = [];
let state = 0;
for (let i = 0; i < d.length; i += 4) {
  const r = d[i], g = d[i + 1], b = d[i + 2];
  if (Math.abs(r - 0x44) < 8 && Math.abs(g - 0x44) < 8 && Math.abs(b - 0x44) < 8) bones.push(i / 4);
  if ((r < 60 && g > 70 && b > 150) || (r < 70 && g > 130 && b < 70) ||
      (r > 190 && g < 60 && b < 60) || (r > 220 && g > 180 && b < 60)) state++;
}
return [bones, state];
"""


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    # its profile goes under pytest's own temporary folders: left to itself, Chromium made a
    # folder in /tmp at every run and kept it
    profile = tmp_path_factory.mktemp("chromium-profile")
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--window-size=1000,700", f"--user-data-dir={profile}"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(executable_path=DRIVER), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def test_page_draws_the_skeleton_and_the_slider_moves_it(browser, tmp_path):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    page = tmp_path / "view.html"
    player = view([read(BVH), read(AMC)], page)
    browser.get(page.as_uri())  # a file: no server, no network
    root = browser.find_element(By.CSS_SELECTOR, "div.kinetology-view")
    assert root.get_attribute("data-tick") == "0"
    canvases = browser.find_elements(By.CSS_SELECTOR, "canvas")
    assert len(canvases) == 2
    before = [browser.execute_script(_PIXELS, i) for i in range(2)]
    for bones, state in before:  # the bones and the coloured joints are on the canvas
        assert len(bones) > 200 and state > 50, [(len(b), s) for b, s in before]

    slider = browser.find_element(By.CSS_SELECTOR, "input.time")
    slider.send_keys(Keys.END)  # a key on the slider, as a user would: to the last step
    assert root.get_attribute("data-tick") == str(player.ticks - 1)
    frames = [int(c.get_attribute("data-frame")) for c in canvases]
    assert frames == [p.frames - 1 for p in player.panels]
    # the middle of the take (a bow bends over; a take may end in the pose it began in)
    browser.execute_script("const s = arguments[0]; s.value = String(arguments[1]); "
                           "s.dispatchEvent(new Event('input'));", slider, player.ticks // 2)
    middle = [browser.execute_script(_PIXELS, i) for i in range(2)]
    for (old, _), (new, _) in zip(before, middle):
        moved = len(set(old) ^ set(new))  # pixels where a bone is in one pose, not the other
        assert len(new) > 200 and moved > 0.3 * len(old), (moved, len(old))  # another pose
    slider.send_keys(Keys.HOME)  # and back: the first pose again, pixel for pixel
    again = [browser.execute_script(_PIXELS, i) for i in range(2)]
    assert [sorted(b) for b, _ in again] == [sorted(b) for b, _ in before]

    # arrow keys step the slider one kept frame at a time
    slider.send_keys(Keys.HOME)
    for _ in range(5):
        slider.send_keys(Keys.ARROW_RIGHT)
    assert [int(c.get_attribute("data-frame")) for c in canvases] == \
        [player.frame_of(i, 5) for i in range(2)]

    # play runs the clock; pause stops it
    browser.find_element(By.CSS_SELECTOR, "button.play").click()
    time.sleep(0.5)
    browser.find_element(By.CSS_SELECTOR, "button.play").click()
    assert root.get_attribute("data-playing") == "no"
    assert int(root.get_attribute("data-tick")) > 5


def test_two_players_of_one_motion_on_one_page_play_apart(browser, tmp_path):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    # what a notebook shows when one motion is displayed twice: one element id, twice
    fragment = read(AMC)._repr_html_()
    page = tmp_path / "twice.html"
    page.write_text(f"<!DOCTYPE html><html><body>{fragment}{fragment}</body></html>")
    browser.get(page.as_uri())
    first, second = browser.find_elements(By.CSS_SELECTOR, "div.kinetology-view")
    assert first.get_attribute("id") == second.get_attribute("id")
    second.find_element(By.CSS_SELECTOR, "input.time").send_keys(Keys.END)
    assert first.get_attribute("data-tick") == "0"
    assert int(second.get_attribute("data-tick")) > 0
