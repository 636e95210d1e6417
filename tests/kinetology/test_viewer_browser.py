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

# the canvas's pixels, read by the page itself: how many are bone grey, how many a state's
# colour, and a digest of the whole picture (to see that it changed)
_PIXELS = """
const canvas = document.querySelectorAll("canvas")[arguments[0]];
const d = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
let bone = 0, state = 0, digest = 0;
for (let i = 0; i < d.length; i += 4) {
  const r = d[i], g = d[i + 1], b = d[i + 2];
  if (Math.abs(r - 0x44) < 8 && Math.abs(g - 0x44) < 8 && Math.abs(b - 0x44) < 8) bone++;
  if ((r < 60 && g > 70 && b > 150) || (r < 70 && g > 130 && b < 70) ||
      (r > 190 && g < 60 && b < 60) || (r > 220 && g > 180 && b < 60)) state++;
  digest = (digest * 31 + r + 7 * g + 13 * b) % 1000000007;
}
return [bone, state, digest];
"""


@pytest.fixture(scope="module")
def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--window-size=1000,700"):
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
    for bone, state, _ in before:  # the bones and the coloured joints are on the canvas
        assert bone > 200 and state > 50, before

    slider = browser.find_element(By.CSS_SELECTOR, "input.time")
    slider.send_keys(Keys.END)  # a key on the slider, as a user would: to the last step
    assert root.get_attribute("data-tick") == str(player.ticks - 1)
    frames = [int(c.get_attribute("data-frame")) for c in canvases]
    assert frames == [p.frames - 1 for p in player.panels]
    after = [browser.execute_script(_PIXELS, i) for i in range(2)]
    for (_, _, old), (bone, _, new) in zip(before, after):
        assert new != old and bone > 200  # another pose, still a body

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
