"""Time from a camera change to the first new frame in `lamplight view`, as the
page sees it (headless Chromium, Selenium).

    python bench/view_latency.py target/release/lamplight [SCENE] [--moves N]

Starts the viewer at 640x360 (Whitted, the scene's settings), opens the page,
waits for the final frame, then sends N camera changes along an orbit, each
as soon as the previous one's first full-size frame arrived (so each change
lands while the previous one is still refining, as when dragging). For each
it records, from the moment the page sends the camera: the first new frame
(the quarter-size preview), and the first full-size (640x360, 1 sample)
frame; and the server's own time from receiving the change to finishing the
preview. Prints the medians and quartiles in milliseconds.
"""

import argparse
import math
import statistics
import subprocess
import sys

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.support.ui import WebDriverWait


def quartiles(xs):
    q = statistics.quantiles(xs, n=4)
    return f"median {statistics.median(xs):.1f} ms (quartiles {q[0]:.1f}-{q[2]:.1f}, n = {len(xs)})"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("lamplight")
    ap.add_argument("scene", nargs="?", default="luxo")
    ap.add_argument("--moves", type=int, default=100)
    args = ap.parse_args()
    proc = subprocess.Popen([args.lamplight, "view", args.scene, "--listen", "127.0.0.1:0"], stdout=subprocess.PIPE, text=True)
    url = proc.stdout.readline().split(": ", 1)[1].strip()
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,760"]:
        options.add_argument(a)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        driver.set_script_timeout(60)
        driver.get(url)
        WebDriverWait(driver, 60).until(lambda d: d.execute_script("return window.lamplight.info && window.lamplight.info.last"))
        start = driver.execute_script("return window.lamplight.state.camera;")
        eye, at = start["eye"], start["look_at"]
        offset = [eye[i] - at[i] for i in range(3)]
        first, full, server, sizes = [], [], [], {}
        for i in range(1, args.moves + 1):
            a = 0.01 * i
            rotated = [offset[0] * math.cos(a) + offset[2] * math.sin(a), offset[1], -offset[0] * math.sin(a) + offset[2] * math.cos(a)]
            camera = dict(start, eye=[at[k] + rotated[k] for k in range(3)])
            t = driver.execute_async_script(
                "const done = arguments[arguments.length - 1];"
                "const g = window.lamplight.state.generation;"
                "window.lamplight.timeCamera(arguments[0]).then((r) => done(r));",
                camera,
            )
            first.append(t["first_ms"])
            full.append(t["full_ms"])
        # The preview's size (chosen by the server for its time budget), from a few more changes.
        for i in range(10):
            info = driver.execute_async_script(
                "const done = arguments[arguments.length - 1];"
                "const h = window.lamplight, g = h.state.generation;"
                "h.camera = arguments[0];"
                "const wait = () => h.nextFrame().then(() => (h.info.generation > g ? done(h.info) : wait()));"
                "wait(); h.timeCamera(arguments[0]);",
                dict(start, vfov=start["vfov"] - 0.1 * (i + 1)),
            )
            size = f"{info['width']}x{info['height']}"
            sizes[size] = sizes.get(size, 0) + 1
        # The server's own figure for the preview, from a last change made while idle.
        for _ in range(20):
            WebDriverWait(driver, 60).until(lambda d: d.execute_script("return window.lamplight.info.last"))
            driver.execute_async_script(
                "const done = arguments[arguments.length - 1];"
                "window.lamplight.timeCamera(arguments[0]).then(done);",
                dict(start, vfov=start["vfov"] + 0.1 * (len(server) + 1)),
            )
            server.append(driver.execute_script("return window.lamplight.info.latency_ms;"))
        print(f"{args.scene} at 640x360, whitted; {args.moves} camera changes while refining")
        print(f"  change -> first new frame (the preview): {quartiles(first)}; preview sizes seen: {sizes}")
        print(f"  change -> first 640x360 frame (1 sample):   {quartiles(full)}")
        print(f"  server, change -> 640x360 frame rendered (idle before): {quartiles(server)}")
    finally:
        driver.quit()
        proc.terminate()
    return 0


if __name__ == "__main__":
    sys.exit(main())
