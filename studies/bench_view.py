"""The 3D page of a long result (stewart.view, docs/view.md): its size, how long it takes to write
and to open, and how long a frame takes when scrubbing, in Debian's headless Chromium (WebGL on
SwiftShader, the CPU renderer: a real GPU draws faster). Prints numbers; asserts nothing.

usage: python studies/bench_view.py [ROWS] [MOVES]   (default 100000 rows, 300 slider moves)"""
import os
import pathlib
import shutil
import sys
import tempfile
import time

import numpy as np

import stewart

# perMove slider moves (input events, as a drag makes) per animation frame; the page draws once a
# frame (its draw runs before the next step, which then waits for the GPU: gl.finish).
SCRUB = """
const [frames, perFrame, done] = [arguments[0], arguments[1], arguments[arguments.length - 1]];
const view = window.stewartView, n = view.frames, gl = document.getElementById('view3d').getContext('webgl2');
const slider = document.getElementById('slider'), finish = [], intervals = [];
let k = 0, last = performance.now();
function step(now) {
  if (k > 0) {
    intervals.push(now - last);
    const t0 = performance.now();
    gl.finish();
    finish.push(performance.now() - t0);
  }
  last = performance.now();
  if (k >= frames) {
    done({moves: view.frameWork().slice(-frames), draws: view.drawWork().slice(-intervals.length),
          finish, intervals});
    return;
  }
  for (let m = 0; m < perFrame && k < frames; m++, k++) {
    slider.value = String(Math.floor((k * 7919) % frames * (n - 1) / (frames - 1)));  // jumps
    slider.dispatchEvent(new Event('input'));
  }
  requestAnimationFrame(step);
}
requestAnimationFrame(step);
"""
# The same loop drawing nothing: what the headless browser's frame clock gives by itself.
IDLE = """
const [frames, done] = [arguments[0], arguments[arguments.length - 1]];
const intervals = [];
let k = 0, last = performance.now();
function step(now) {
  if (k > 0) intervals.push(now - last);
  last = now;
  if (k++ === frames) { done(intervals); return; }
  requestAnimationFrame(step);
}
requestAnimationFrame(step);
"""


def result(rows: int):
    """A combined heave, sway and turn over rows steps of 1 ms, with massless forces."""
    platform = stewart.Platform(payload_mass=50)
    t = np.arange(rows) * 1e-3
    q = np.column_stack([0.03 * np.sin(0.7 * t), 0.02 * np.sin(1.1 * t), 0.5 + 0.04 * np.sin(5 * t),
                         0.05 * np.sin(0.9 * t), 0.04 * np.sin(1.3 * t), 0.1 * np.sin(0.5 * t)])
    forces = platform.inverse(q, fidelity="massless").force
    columns = {"t": t, **{n: q[:, i] for i, n in enumerate(("x", "y", "z", "roll", "pitch", "yaw"))}}
    columns.update({f"F{k + 1}": forces[:, k] for k in range(6)})
    return platform, columns


def browser(profile: str):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for flag in ("--headless", "--no-sandbox", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--disable-background-networking",
                 "--no-first-run", "--window-size=1200,800", f"--user-data-dir={profile}"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)
    driver.set_script_timeout(600)
    return driver


def percentiles(name: str, values) -> None:
    v = np.asarray(values)
    p = np.percentile(v, [50, 90, 99, 100])
    print(f"{name}: median {p[0]:.2f} ms, p90 {p[1]:.2f}, p99 {p[2]:.2f}, max {p[3]:.2f} "
          f"({np.mean(v <= 1000 / 60 + 0.05):.0%} within a 60 Hz frame, {len(v)} values)")


def main(rows: int = 100_000, frames: int = 300) -> None:
    from selenium.webdriver.support.ui import WebDriverWait

    folder = pathlib.Path(tempfile.mkdtemp())
    platform, columns = result(rows)
    start = time.perf_counter()
    page = stewart.view(platform, columns, output=folder / "long.html")
    print(f"{rows} rows: page {page.stat().st_size / 1e6:.1f} MB, written in "
          f"{time.perf_counter() - start:.2f} s")
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    driver = browser(str(folder / "profile"))
    try:
        for attempt in (1, 2):  # the second open finds the shaders compiled in the profile's cache
            start = time.perf_counter()
            driver.get(page.as_uri())
            WebDriverWait(driver, 120).until(lambda d: d.execute_script(
                "return !!(window.stewartView && window.stewartView.ready)"))
            wall = time.perf_counter() - start
            t = driver.execute_script("return window.stewartView.timings")
            print(f"open {attempt}: ready {t['ready'] / 1e3:.2f} s after navigation (scripts parsed "
                  f"{t['scriptStart'] / 1e3:.2f} s, scene {t['sceneBuilt'] / 1e3:.2f} s, plots "
                  f"{t['plotsDrawn'] / 1e3:.2f} s); {wall:.2f} s through the driver")
        print("renderer:", driver.execute_script("return window.stewartView.renderer()"))
        for per_frame in (1, 4):
            timing = driver.execute_async_script(SCRUB, frames, per_frame)
            print(f"{frames} slider moves, {per_frame} per animation frame:")
            percentiles("  a move's work (setFrame)", timing["moves"])
            percentiles("  a draw's work (three.js render)", timing["draws"])
            percentiles("  then waiting for the GPU (gl.finish)", timing["finish"])
            percentiles("  frame interval (requestAnimationFrame)", timing["intervals"])
        percentiles("frame interval drawing nothing", driver.execute_async_script(IDLE, frames))
    finally:
        driver.quit()
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
