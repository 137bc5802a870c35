"""`lamplight view` in a real browser: headless Chromium (Debian's `chromium`
and `chromium-driver`) driven by Selenium. scripts/test.sh installs them; where
they cannot be installed these tests skip and say why.

One viewer of a copy of examples/luxo.toml (640x360, Whitted, adaptive
anti-aliasing) serves every test; each test opens the page afresh.
"""

import http.client
import os
import pathlib
import shutil
import subprocess
import time
import urllib.error
import urllib.parse
import urllib.request

import pytest

from conftest import EXAMPLES, ROOT

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMEDRIVER = shutil.which("chromedriver")
try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait
except ImportError:  # pragma: no cover - depends on the machine
    webdriver = None

pytestmark = pytest.mark.skipif(
    webdriver is None or CHROMIUM is None or CHROMEDRIVER is None,
    reason="needs Selenium (pip install selenium) and headless Chromium with its driver "
    "(apt-get install chromium chromium-driver); scripts/test.sh installs them where it can",
)

# A pixel of luxo at 640x360 that sees the glass sphere: its tree holds the
# camera ray, refracted and reflected rays and shadow rays.
GLASS_PIXEL = (240, 264)
# Set to a path to save the inspector's screenshot there (docs/view-inspector.png).
SCREENSHOT = os.environ.get("LAMPLIGHT_VIEW_SCREENSHOT")


@pytest.fixture(scope="module")
def viewer(cli, tmp_path_factory):
    folder = tmp_path_factory.mktemp("scene")
    scene = folder / "luxo.toml"
    shutil.copy(EXAMPLES / "luxo.toml", scene)
    (folder.parent / "secret.txt").write_text("not for the page")
    os.symlink(folder.parent / "secret.txt", folder / "link.txt")
    proc = subprocess.Popen(
        [cli, "view", str(scene), "--listen", "127.0.0.1:0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    line = proc.stdout.readline()
    if not line.startswith("lamplight view: http://"):
        proc.kill()
        pytest.fail(f"the viewer did not start: {line!r} {proc.stderr.read()}")
    url = line.split(": ", 1)[1].strip()
    yield {"url": url, "scene": scene, "folder": folder, "text": scene.read_text()}
    proc.terminate()
    proc.wait(timeout=10)


@pytest.fixture(scope="module")
def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,760"]:
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.set_script_timeout(60)
    yield driver
    driver.quit()


def hooks(driver, expression):
    return driver.execute_script(f"return window.lamplight && window.lamplight.{expression};")


def wait_for(driver, condition, timeout=30, what="a condition"):
    return WebDriverWait(driver, timeout, poll_frequency=0.02).until(lambda d: condition(d), message=f"waited {timeout} s for {what}")


def final_frame(driver, newer_than=0):
    """Waits for the last stage of a generation above `newer_than`; returns its frame message."""
    script = "const i = window.lamplight && window.lamplight.info; return i && i.last && i.generation > arguments[0] ? i : null;"
    return wait_for(driver, lambda d: d.execute_script(script, newer_than), what="the final frame")


def open_page(driver, viewer):
    driver.get(viewer["url"])
    wait_for(driver, lambda d: hooks(d, "frames") >= 1, what="a first frame")


def test_the_first_image_is_a_preview_then_refines(browser, viewer):
    # How soon the first image comes is measured in bench/view_latency.py,
    # not asserted here: a timed assertion fails on a loaded machine.
    open_page(browser, viewer)
    first = hooks(browser, "firstInfo")
    print(f"first image {hooks(browser, 'firstFrameMs'):.0f} ms after the page was opened: {first['width']}x{first['height']}")
    # The preview is one sample per pixel, at a size the server picks from the
    # time it measured per sample (crates/lamplight-view/src/renderer.rs tests
    # `preview_divisor`): smaller on a slow machine, full size on a fast one.
    assert first["spp"] == 1 and not first["last"], f"the first frame is a one-sample preview: {first}"
    assert first["width"] <= first["full_width"] and first["height"] <= first["full_height"], first
    info = final_frame(browser)
    assert (info["full_width"], info["full_height"]) == (640, 360)
    assert hooks(browser, "frames") >= 2, "the first frame was refined"
    assert info["adaptive"] and info["spp"] == 16, info
    status = browser.find_element(By.ID, "status").text
    assert "spp 16/adaptive" in status and "samples/s" in status, status


def test_dragging_moves_the_camera_and_changes_the_image(browser, viewer):
    open_page(browser, viewer)
    info = final_frame(browser)
    before = (hooks(browser, "state.camera"), hooks(browser, "checksum()"))
    canvas = browser.find_element(By.ID, "image")
    ActionChains(browser).move_to_element(canvas).click_and_hold().move_by_offset(40, 0).move_by_offset(40, 10).release().perform()
    after_info = final_frame(browser, info["generation"])
    camera, image = hooks(browser, "state.camera"), hooks(browser, "checksum()")
    assert camera["eye"] != before[0]["eye"], "the drag orbited the eye"
    assert camera["look_at"] == pytest.approx(before[0]["look_at"]), "orbiting keeps the point looked at"
    assert image != before[1], "the image changed"
    assert after_info["generation"] > info["generation"]
    browser.find_element(By.ID, "reset").click()
    final_frame(browser, after_info["generation"])
    assert hooks(browser, "state.own_camera") is True


def test_a_clicked_pixel_s_tree_adds_up_to_its_value(browser, viewer):
    open_page(browser, viewer)
    final_frame(browser)
    canvas = browser.find_element(By.ID, "image")
    x, y = GLASS_PIXEL
    # Selenium's offsets are from the element's centre.
    ActionChains(browser).move_to_element_with_offset(canvas, x - 320, y - 180).click().perform()
    m = wait_for(browser, lambda d: hooks(d, "explain"), what="the explanation")
    # The click lands within a pixel of the one aimed at (offsets round).
    assert abs(m["x"] - x) <= 1 and abs(m["y"] - y) <= 1, (m["x"], m["y"])
    x, y = m["x"], m["y"]
    tree = m["tree"]
    n = len(tree["samples"])
    mean = [sum(c[k] for s in tree["samples"] for c in s["contributions"]) / n for k in range(3)]
    shown = browser.execute_script("return window.lamplight.pixel(arguments[0], arguments[1]);", x, y)
    assert tree["value"] == pytest.approx(shown, rel=1e-6, abs=1e-9), "the tree's value is the frame's pixel"
    assert mean == pytest.approx(shown, rel=1e-5, abs=1e-9), "the contributions add up to the pixel"
    kinds = set(hooks(browser, "rays"))
    assert {"camera", "refracted", "reflected"} <= kinds and kinds & {"shadow", "blocked"}, kinds
    lines = browser.find_elements(By.CSS_SELECTOR, "#rays line")
    assert len(lines) >= 4
    # Hovering a node highlights its ray.
    summary = browser.find_element(By.CSS_SELECTOR, "#tree summary.k-refracted")
    ActionChains(browser).move_to_element(summary).perform()
    ray = browser.find_element(By.ID, summary.find_element(By.XPATH, ".").get_attribute("data-ray"))
    assert "hl" in ray.get_attribute("class")
    if SCREENSHOT:
        browser.execute_script("document.getElementById('inspector').scrollTop = 0;")
        browser.find_element(By.TAG_NAME, "main").screenshot(SCREENSHOT)


# A pixel of luxo on the floor right of the glass sphere: under the path
# tracer at 8 samples some of its paths leave the image, one of them (sample 2)
# through its bottom edge, across the controls below, had it not been clipped.
FLOOR_PIXEL = (500, 300)


def click_pixel(driver, x, y):
    canvas = driver.find_element(By.ID, "image")
    # Selenium's offsets are from the element's centre.
    ActionChains(driver).move_to_element_with_offset(canvas, x - 320, y - 180).click().perform()


def use_settings(driver, integrator, spp):
    """Sets the page's integrator and spp fields as a user would ("" for the scene's) and returns the new generation."""
    generation = hooks(driver, "state.generation")
    driver.execute_script(
        "document.getElementById('spp').value = arguments[1];"
        "const s = document.getElementById('integrator'); s.value = arguments[0]; s.dispatchEvent(new Event('change'));",
        integrator,
        spp,
    )
    wait_for(driver, lambda d: hooks(d, "state.generation") > generation, what="the new settings")
    return generation


def drawn_lines(driver):
    """The overlay's lines: (sample, x1, y1, x2, y2) each."""
    script = """return [...document.querySelectorAll('#rays line')].map((l) =>
        [l.dataset.sample, ...['x1', 'y1', 'x2', 'y2'].map((k) => +l.getAttribute(k))]);"""
    return [tuple(line) for line in driver.execute_script(script)]


def test_the_overlay_draws_one_sample_s_path_clipped_to_the_image(browser, viewer):
    open_page(browser, viewer)
    info = final_frame(browser)
    try:
        use_settings(browser, "path", "8")
        final_frame(browser, info["generation"])
        # What lies below and beside the image, as drawn before any ray is (the
        # legend's words: the inspector itself narrows when its scroll bar comes).
        names = ["#controls", ".hint"] + [f"#legend .k-{k}" for k in ["camera", "reflected", "refracted", "shadow", "blocked"]]
        around = {name: browser.find_element(By.CSS_SELECTOR, name).screenshot_as_png for name in names}
        click_pixel(browser, *FLOOR_PIXEL)
        m = wait_for(browser, lambda d: hooks(d, "explain"), what="the explanation")
        samples = m["tree"]["samples"]
        assert len(samples) == 8 and m["tree"]["integrator"] == "path", m["tree"]["integrator"]
        image = browser.find_element(By.ID, "image").rect
        for box in ["#stage", "#rays"]:
            assert browser.find_element(By.CSS_SELECTOR, box).rect == image, f"{box} is the image's box"
        assert browser.execute_script("return getComputedStyle(document.getElementById('stage')).overflow") == "hidden"
        seen = {}
        for k in range(len(samples)):
            # One sample's path at a time, k clicks on "next" from the first.
            assert hooks(browser, "sample") == k
            index = samples[k]["index"]
            label = browser.find_element(By.ID, "sample_label").text
            assert label == f"sample {index} drawn ({k + 1} of 8)", label
            lines = drawn_lines(browser)
            assert lines and {line[0] for line in lines} == {str(index)}, lines
            # The path tracer draws a path's vertices, one segment each.
            assert hooks(browser, "rays") == ["camera"] + ["reflected"] * (len(samples[k]["path"]["vertices"]) - 1)
            assert len(lines) <= len(samples[k]["path"]["vertices"])
            for _, *ends in lines:
                xs, ys = ends[0::2], ends[1::2]
                assert all(-1e-6 <= x <= 640 + 1e-6 for x in xs) and all(-1e-6 <= y <= 360 + 1e-6 for y in ys), ends
            seen[k] = sorted(lines)
            for name, png in around.items():
                assert browser.find_element(By.CSS_SELECTOR, name).screenshot_as_png == png, f"sample {index}'s rays drawn over {name}"
            browser.find_element(By.ID, "sample_next").click()
        assert hooks(browser, "sample") == 0, "next wraps around to the first sample"
        assert seen[0] != seen[1], "another sample, another path"
        browser.find_element(By.ID, "sample_prev").click()
        assert hooks(browser, "sample") == 7, "previous wraps around to the last"
        # A sample's own line in the tree selects it too.
        browser.find_element(By.CSS_SELECTOR, "#tree details.sample[data-sample='3'] > summary").click()
        assert hooks(browser, "sample") == 3 and sorted(drawn_lines(browser)) == seen[3]
    finally:
        info = hooks(browser, "info")
        use_settings(browser, "", "")
        final_frame(browser, info["generation"])


def test_moving_the_camera_marks_the_tree_stale_then_explains_the_pixel_again(browser, viewer):
    open_page(browser, viewer)
    info = final_frame(browser)
    click_pixel(browser, *GLASS_PIXEL)
    first = wait_for(browser, lambda d: hooks(d, "explain"), what="the explanation")
    assert first["camera"] == hooks(browser, "state.camera")
    assert drawn_lines(browser) and not hooks(browser, "stale")
    canvas = browser.find_element(By.ID, "image")
    try:
        # Mid-drag the camera has moved: the tree is marked stale and its rays are gone.
        drag = ActionChains(browser).move_to_element(canvas).click_and_hold().move_by_offset(30, 0).move_by_offset(30, 5)
        drag.perform()
        assert hooks(browser, "stale") is True
        note = browser.find_element(By.ID, "stale_note")
        assert note.text == (
            f"stale: the camera moved; this tree is of the view before. Pixel ({first['x']}, {first['y']}) "
            "is explained again when the new view's first frame comes."
        ), note.text
        assert "stale" in browser.find_element(By.ID, "tree").get_attribute("class")
        assert drawn_lines(browser) == []
        browser.execute_script("window.lamplight.selectSample(0);")
        assert drawn_lines(browser) == [], "choosing a sample of a stale tree draws none of its rays"
        assert hooks(browser, "explain.generation") == first["generation"], "the old tree stays, marked, until the new one comes"
        ActionChains(browser).release().perform()
        again = wait_for(
            browser, lambda d: hooks(d, "explain.generation") > first["generation"] and hooks(d, "explain"), what="the pixel explained again"
        )
        assert (again["x"], again["y"]) == (first["x"], first["y"])
        camera = hooks(browser, "state.camera")
        assert again["camera"] == camera and camera["eye"] != first["camera"]["eye"], "explained through the moved camera"
        assert not hooks(browser, "stale") and not browser.find_elements(By.ID, "stale_note")
        assert drawn_lines(browser), "the new tree's rays are drawn"
        final = final_frame(browser, first["generation"])
        assert final["generation"] == again["generation"]
        shown = browser.execute_script("return window.lamplight.pixel(arguments[0], arguments[1]);", again["x"], again["y"])
        assert again["tree"]["value"] == pytest.approx(shown, rel=1e-6, abs=1e-9), "the new tree is the new image's pixel"
        assert again["tree"]["value"] != pytest.approx(first["tree"]["value"], rel=1e-3), "the moved camera sees something else there"
    finally:
        ActionChains(browser).release().perform() if hooks(browser, "stale") else None
        generation = hooks(browser, "state.generation")
        browser.find_element(By.ID, "reset").click()
        final_frame(browser, generation)


def test_editing_the_scene_reloads_and_a_broken_file_shows_its_error(browser, viewer):
    open_page(browser, viewer)
    info = final_frame(browser)
    reloads = hooks(browser, "state.reloads")
    scene, text = viewer["scene"], viewer["text"]
    image = hooks(browser, "checksum()")
    try:
        # More ambient light: every lit pixel changes.
        assert "ambient = 1.0" in text
        edited = text.replace("ambient = 1.0", "ambient = 2.5", 1)
        scene.write_text(edited)
        info = final_frame(browser, info["generation"])
        assert hooks(browser, "state.reloads") > reloads
        good = hooks(browser, "checksum()")
        assert good != image, "the edit re-rendered the scene"
        scene.write_text(edited + "\n[camera\n")
        overlay = browser.find_element(By.ID, "overlay")
        wait_for(browser, lambda d: overlay.is_displayed(), what="the error overlay")
        assert f"{scene}:" in overlay.text, overlay.text
        line_col = overlay.text.split(f"{scene}:", 1)[1].split(":")[:2]
        assert all(part.isdigit() for part in line_col), f"file:line:col in {overlay.text!r}"
        assert hooks(browser, "checksum()") == good, "the last good image stays under the overlay"
        scene.write_text(text)
        wait_for(browser, lambda d: not overlay.is_displayed(), what="the overlay to clear")
        final_frame(browser, info["generation"])
        assert hooks(browser, "checksum()") == image, "the original scene is back"
    finally:
        scene.write_text(text)


def test_saving_writes_the_image_and_the_camera_into_the_scene_s_folder(browser, viewer):
    open_page(browser, viewer)
    final_frame(browser)
    name = browser.find_element(By.ID, "save_name")
    name.clear()
    name.send_keys("saved/out.png")
    browser.find_element(By.ID, "save").click()
    error = wait_for(browser, lambda d: hooks(d, "errors.length") and hooks(d, "errors[0]"), what="the refusal")
    assert error == f"'saved/out.png' is refused: a name, not a path; the viewer saves into {viewer['folder'].resolve()} only"
    name.clear()
    name.send_keys("out.png")
    browser.find_element(By.ID, "save").click()
    browser.find_element(By.ID, "save_camera").click()
    wait_for(browser, lambda d: hooks(d, "saved.length") == 2, what="both saves")
    png = (viewer["folder"] / "out.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert (int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")) == (640, 360)
    camera = (viewer["folder"] / "camera.toml").read_text()
    assert camera == hooks(browser, "state.camera_toml")
    assert camera.startswith("[camera]\neye = [1.3, 1.6, 3]\n") and "up = [0, 1, 0]" in camera, camera
    assert [p.name for p in viewer["folder"].iterdir() if p.name.endswith(".tmp")] == [], "no temporary file left"


def test_requests_without_the_token_foreign_hosts_and_files_are_refused(browser, viewer):
    parts = urllib.parse.urlsplit(viewer["url"])
    token = urllib.parse.parse_qs(parts.query)["token"][0]
    base = f"http://{parts.netloc}"
    for target in ["/", "/app.js", "/ws", "/files/luxo.toml"]:
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(base + target, timeout=10)
        assert refused.value.code == 403, target

    def raw(target, headers=None):
        c = http.client.HTTPConnection(parts.netloc, timeout=10)
        c.request("GET", target, headers=headers or {})
        r = c.getresponse()
        return r.status, r.read().decode()

    # The page fetches no file of the scene's folder, so none is served (issue 30).
    for name in ["luxo.toml", "../secret.txt", "link.txt"]:
        assert raw(f"/files/{name}?token={token}")[0] == 404, name
    # DNS rebinding: the right token under a foreign name is refused.
    assert raw(f"/?token={token}", {"Host": f"evil.example:{parts.port}"})[0] == 403
    # The browser without the token gets the refusal, not the page.
    browser.get(base + "/")
    assert "forbidden" in browser.find_element(By.TAG_NAME, "body").text


@pytest.fixture(scope="module")
def turntable_viewer(cli):
    proc = subprocess.Popen(
        [cli, "view", str(EXAMPLES / "turntable.toml"), "--listen", "127.0.0.1:0", "--width", "160"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stdout.readline()
    if not line.startswith("lamplight view: http://"):
        proc.kill()
        pytest.fail(f"the viewer did not start: {line!r} {proc.stderr.read()}")
    yield {"url": line.split(": ", 1)[1].strip()}
    proc.terminate()
    proc.wait(timeout=10)


def test_the_timeline_scrubs_and_plays_an_animated_scene_only(browser, viewer, turntable_viewer):
    # A static scene shows no timeline.
    open_page(browser, viewer)
    assert not browser.find_element(By.ID, "timeline").is_displayed()
    open_page(browser, turntable_viewer)
    final_frame(browser)
    slider = browser.find_element(By.ID, "frame")
    assert browser.find_element(By.ID, "timeline").is_displayed()
    assert (slider.get_attribute("min"), slider.get_attribute("max"), slider.get_attribute("value")) == ("1", "48", "1")
    # Scrubbing to 13 renders frame 13.
    browser.execute_script("const s = document.getElementById('frame'); s.value = 13; s.dispatchEvent(new Event('input'));")
    script = "const i = window.lamplight.info; return i && i.last && i.frame === 13 ? i : null;"
    info = wait_for(browser, lambda d: d.execute_script(script), what="frame 13 refined")
    assert "frame 13 of 1-48" in browser.find_element(By.ID, "frame_value").text
    assert browser.find_element(By.ID, "status").text.startswith("frame 13 ·")
    # Play shows previews and stops on the last frame, refined.
    browser.find_element(By.ID, "play").click()
    wait_for(browser, lambda d: hooks(d, "info.preview"), what="a frame of play")
    assert browser.find_element(By.ID, "play").text == "pause"
    final_frame(browser, info["generation"])
    wait_for(browser, lambda d: hooks(d, "info.frame") == 48 and hooks(d, "info.last"), what="the last frame refined")
    assert hooks(browser, "state.playing") is False
    assert browser.find_element(By.ID, "play").text == "play"
    assert slider.get_attribute("value") == "48"
