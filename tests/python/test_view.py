"""stewart.view's pages in a real browser: Debian's headless Chromium driven by Selenium through
Debian's chromedriver, WebGL on SwiftShader, the network off. Each page is opened from its file.

Checked against the library, never against the page itself: the page computes the leg lengths
with its own script from the pose, the joints and the frames, and they must equal
Platform.inverse's to 1e-9 m; the leg it colours as beyond its stroke must be the one
Platform.limits names. Set STEWART_VIEW_DOCS=1 to write docs/view-NAME.png from the pages."""
import io
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import stewart
from stewart.view import home_pose

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"
HAVE_CHROMIUM = bool(shutil.which("chromium")) and pathlib.Path(CHROMEDRIVER).is_file()
needs_browser = pytest.mark.skipif(
    not HAVE_CHROMIUM, reason="Debian's chromium and chromium-driver are not installed "
                              "(scripts/setup.sh installs them)")
BACKGROUND = np.array([0xf2, 0xf4, 0xf7])  # the page's scene background
RED = "#d62728"  # the page's colour of a leg at or beyond its nearest limit
POSE_NAMES = ("x", "y", "z", "roll", "pitch", "yaw")
FRAMED = dict(tool_frame=[0.02, -0.01, 0.10, 0.05, -0.04, 0.30],
              user_frame=[0.01, -0.02, 0.45, 0.02, -0.03, 0.40],
              length_offset=[0.01, -0.02, 0.003, 0.0, 0.015, -0.005])


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for flag in ("--headless", "--no-sandbox", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run",
                 "--window-size=1200,800", "--disable-dev-shm-usage",
                 f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.set_network_conditions(offline=True, latency=0, download_throughput=0,
                                  upload_throughput=0)
    yield driver
    driver.quit()


def open_page(driver, path: pathlib.Path):
    """Load the page from its file and wait for it; fail on any console error."""
    from selenium.webdriver.support.ui import WebDriverWait

    driver.get_log("browser")  # drop what earlier pages logged
    driver.get(path.resolve().as_uri())
    WebDriverWait(driver, 60).until(
        lambda d: d.execute_script("return !!(window.stewartView && window.stewartView.ready)"),
        message=f"{path} never became ready: {driver.get_log('browser')}")
    errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors, f"console errors in {path.name}: {errors}"


def canvas_pixels(driver) -> np.ndarray:
    """The 3D canvas as an (H, W, 3) uint8 array, read from its drawing buffer (the page keeps
    it): a screenshot of the element can catch the compositor's previous frame on a loaded
    machine, the buffer holds what the last render drew."""
    import base64

    from PIL import Image

    url = driver.execute_script("return document.getElementById('view3d').toDataURL('image/png')")
    png = base64.b64decode(url.split(",", 1)[1])
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))


def settled_pixels(driver, frame: int) -> np.ndarray:
    """The canvas once frame is drawn: shown until two reads in a row agree."""
    show(driver, frame)
    last = canvas_pixels(driver)
    for _ in range(4):
        show(driver, frame)
        now = canvas_pixels(driver)
        if np.array_equal(now, last):
            break
        last = now
    return now


def show(driver, frame: int) -> None:
    """setFrame(frame), then wait two animation frames: the screenshot then has it on screen."""
    driver.execute_async_script(
        f"window.stewartView.setFrame({frame}); const done = arguments[0];"
        "requestAnimationFrame(() => requestAnimationFrame(() => done()));")


def drawn_fraction(pixels: np.ndarray) -> float:
    """The share of pixels that are not the scene's background."""
    return float(np.mean(np.abs(pixels.astype(int) - BACKGROUND).max(axis=2) > 24))


def page_lengths(driver, frame: int) -> np.ndarray:
    return np.array(driver.execute_script(f"return window.stewartView.legLengths({frame})"))


def check_lengths(driver, platform, q, frames):
    library = platform.inverse(q, fidelity="kinematic")
    assert np.all(library.status == 0)
    for i in frames:
        np.testing.assert_allclose(page_lengths(driver, i), library.length[i], rtol=0, atol=1e-9)


@needs_browser
@pytest.mark.parametrize("name", sorted(stewart.platform_files()))
def test_every_shipped_platform_renders(browser, tmp_path, name):
    path = stewart.platform_files()[name]
    platform = stewart.Platform.from_file(path)
    page = stewart.view(path, output=tmp_path / f"{name}.html", title=f"{name}.json")
    open_page(browser, page)
    show(browser, 0)
    pixels = canvas_pixels(browser)
    assert drawn_fraction(pixels) > 0.03, f"{name}: the canvas is (nearly) blank"
    home = home_pose(platform)
    check_lengths(browser, platform, home[None, :], [0])
    if os.environ.get("STEWART_VIEW_DOCS") == "1":
        from PIL import Image
        Image.fromarray(pixels).save(ROOT / "docs" / f"view-{name}.png", optimize=True)


@needs_browser
def test_page_lengths_equal_the_library_along_a_result_with_frames(browser, tmp_path):
    """Tool and user frames and sensor offsets set: the page's own transform of each pose."""
    platform = stewart.Platform(**FRAMED)
    rng = np.random.default_rng(3)
    q = home_pose(platform) + rng.uniform(-1, 1, (40, 6)) * [0.03, 0.03, 0.03, 0.08, 0.08, 0.15]
    t = np.arange(40) * 0.05
    result = {"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}}
    page = stewart.view(platform, result, output=tmp_path / "framed.html")
    open_page(browser, page)
    assert browser.execute_script("return window.stewartView.frames") == 40
    check_lengths(browser, platform, q, range(40))
    assert browser.execute_script("return window.stewartView.time(39)") == t[39]


@needs_browser
def test_two_poses_give_different_pictures(browser, tmp_path):
    platform = stewart.Platform()
    poses = [[0, 0, 0.5, 0, 0, 0], [0.05, -0.04, 0.55, 0.12, -0.1, 0.3]]
    open_page(browser, stewart.view(platform, poses=poses, output=tmp_path / "two.html"))
    first = settled_pixels(browser, 0)
    second = settled_pixels(browser, 1)
    changed = np.mean(np.abs(first.astype(int) - second.astype(int)).max(axis=2) > 24)
    assert changed > 0.005, f"only {changed:.4f} of the pixels changed between the two poses"
    again = settled_pixels(browser, 0)
    assert np.array_equal(first, again), "the same frame drawn twice differs"


def pose_beyond_one_stroke(platform):
    """A pose a little past the z range's upper end of a tilted pose, where the axis ranges say
    one leg meets its stroke first; and that leg (1..6)."""
    start = np.array([0.02, 0.01, 0.5, 0.06, -0.04, 0.1])
    ranges = platform.axis_ranges(start, details=True)
    assert ranges.limit[0, 2, 1] == 1, "the z range of the start pose does not end at a stroke"
    pose = start.copy()
    pose[2] = ranges.ends[0, 2, 1] + 1e-4
    return pose, int(ranges.leg[0, 2, 1])


@needs_browser
def test_the_leg_at_its_stroke_is_the_one_the_library_names(browser, tmp_path):
    platform = stewart.Platform()
    pose, leg = pose_beyond_one_stroke(platform)
    check = platform.limits(pose)
    assert check.first[0] == 1 and check.leg[0, 0] == leg  # the library: stroke, this leg
    open_page(browser, stewart.view(platform, poses=[pose], output=tmp_path / "stroke.html"))
    states = browser.execute_script("return window.stewartView.legStates(0)")
    colours = browser.execute_script("return window.stewartView.legColours()")
    beyond = [s["leg"] for s in states if s["beyond"]]
    assert beyond == [leg], f"the page marks legs {beyond} beyond a limit, the library leg {leg}"
    assert states[leg - 1]["class"] == "stroke"
    assert states[leg - 1]["margin"] == pytest.approx(check.margin[0, 0], abs=1e-6)
    assert colours[leg - 1] == RED and colours.count(RED) == 1
    status = browser.execute_script("return document.getElementById('status').textContent")
    assert "beyond: stroke" in status
    # Hovering the leg names it, its class and that it is beyond.
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    point = browser.execute_script(f"return window.stewartView.legPoint({leg - 1})")
    ActionChains(browser).move_to_element_with_offset(
        browser.find_element(By.ID, "view3d"), int(point["x"]), int(point["y"])).perform()
    tip = browser.find_element(By.ID, "tooltip")
    assert tip.is_displayed()
    assert tip.text.startswith(f"leg {leg}:") and "nearest limit: stroke" in tip.text
    assert "at or beyond it" in tip.text


@needs_browser
def test_every_leg_is_coloured_by_its_own_joint_and_interference_margins(browser, tmp_path):
    """Vendor-like joint limits and thick legs at a pose where two base joints are beyond their
    limit and the legs' nearest classes are all four: each leg's page margin is the library's
    own margin of that leg (LimitCheck.leg_margin), not only the leg each class's smallest is at."""
    platform = stewart.Platform(base_joint_limit=0.45, platform_joint_limit=0.45, leg_diameter=0.2)
    pose = [0.05, 0.02, 0.48, 0.05, 0.1, 0.5]
    check = platform.limits(pose)
    names = list(stewart.limits.LIMIT_CLASSES)
    open_page(browser, stewart.view(platform, poses=[pose], output=tmp_path / "joints.html"))
    states = browser.execute_script("return window.stewartView.legStates(0)")
    for k, state in enumerate(states):
        own = check.leg_margin[0, names.index(state["class"]), k]
        assert state["margin"] == pytest.approx(own, abs=1e-6), (k, state)
    assert {s["class"] for s in states} == {"stroke", "base_joint", "platform_joint",
                                            "interference"}
    beyond = [s["leg"] for s in states if s["beyond"]]
    expected = [k + 1 for k in range(6) if check.leg_margin[0, :4, k].min() < 0]
    assert beyond == expected and len(beyond) == 3  # two base joints beyond, one stroke
    assert sorted(np.flatnonzero(check.leg_margin[0, 1] < 0) + 1) == [1, 5]


def write_csv(path, columns):
    names = list(columns)
    np.savetxt(path, np.column_stack([columns[n] for n in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.17g")


@needs_browser
def test_an_inverse_output_with_its_poses_through_the_script(browser, tmp_path):
    """scripts/view.py on an inverse output (t, L1..L6, F1..F6) and its input poses: the page's
    lengths equal the output's own L columns, and the force plot is drawn."""
    platform = stewart.Platform(payload_mass=50)
    t = np.linspace(0, 2, 201)
    q = np.column_stack([0.02 * np.sin(3 * t), 0 * t, 0.5 + 0.03 * np.sin(5 * t),
                         0.05 * np.sin(2 * t), 0 * t, 0.1 * np.sin(t)])
    solved = platform.inverse(q, fidelity="massless")
    write_csv(tmp_path / "in.csv", {"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}})
    write_csv(tmp_path / "out.csv", {"t": t, **{f"L{k + 1}": solved.length[:, k] for k in range(6)},
                                     **{f"F{k + 1}": solved.force[:, k] for k in range(6)}})
    platform_file = tmp_path / "payload.json"
    platform_file.write_text('{"payload_mass": 50}')
    page = tmp_path / "inverse.html"
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "view.py"), "--platform",
                          str(platform_file), str(tmp_path / "out.csv"), "--poses",
                          str(tmp_path / "in.csv"), "-o", str(page), "--force-limit", "260"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    open_page(browser, page)
    for i in (0, 57, 200):
        np.testing.assert_allclose(page_lengths(browser, i), solved.length[i], rtol=0, atol=1e-9)
    # With a force limit the force class colours the legs whose force margin is the nearest,
    # measured on the output's own forces.
    by_force = 0
    for i in range(0, 201, 20):
        for state in browser.execute_script(f"return window.stewartView.legStates({i})"):
            if state["class"] == "force":
                by_force += 1
                k = state["leg"] - 1
                assert state["margin"] == pytest.approx(260 - abs(solved.force[i, k]), abs=1e-3)
    assert by_force > 0, "no leg is nearest its force limit: the test checks nothing"
    assert browser.execute_script("return window.stewartView.setFrame(57)") == 57
    assert "F [N]" in page.read_text()  # the force panel's title is in the script, so check
    assert browser.execute_script("return window.stewartView.frame()") == 57
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    ActionChains(browser).send_keys(Keys.ARROW_RIGHT).send_keys(Keys.ARROW_RIGHT).perform()
    assert browser.execute_script("return window.stewartView.frame()") == 59
    assert "t = 0.590 s (60/201)" in browser.execute_script(
        "return document.getElementById('time').textContent")
    # Play at real time from frame 59: the frames only move forward, never ahead of the clock
    # (a frame's t <= t0 + the time since play()), and the playback stops at the end.
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select
    Select(browser.find_element(By.ID, "speed")).select_by_value("1")
    seen = browser.execute_async_script("""
        const done = arguments[0], seen = [], start = performance.now();
        window.stewartView.play();
        (function watch() {
          seen.push([(performance.now() - start) / 1000, window.stewartView.frame()]);
          if (document.getElementById('play').textContent === 'Play') done(seen);
          else requestAnimationFrame(watch);
        })();""")
    frames = [f for _, f in seen]
    assert frames[-1] == 200 and all(a <= b for a, b in zip(frames, frames[1:]))
    assert all(t[f] <= t[59] + elapsed + 1e-9 for elapsed, f in seen)
    assert seen[-1][0] >= t[200] - t[59] - 0.05  # it took (about) the 1.41 s it plays


@needs_browser
def test_a_parquet_result_opens(browser, tmp_path):
    pa = pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq

    platform = stewart.Platform()
    t = np.linspace(0, 1, 11)
    q = np.column_stack([0 * t, 0 * t, 0.5 + 0.02 * t, 0 * t, 0.05 * t, 0 * t])
    pq.write_table(pa.table({"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}}),
                   tmp_path / "r.parquet")
    open_page(browser, stewart.view(platform, tmp_path / "r.parquet", output=tmp_path / "p.html"))
    check_lengths(browser, platform, q, [0, 10])


def test_bad_results_are_refused_naming_the_cause(tmp_path):
    platform = stewart.Platform()
    write_csv(tmp_path / "lengths.csv", {"t": [0.0, 1.0], **{f"L{k}": [0.5, 0.5] for k in range(1, 7)}})
    with pytest.raises(ValueError, match="no pose columns.*--poses"):
        stewart.view(platform, tmp_path / "lengths.csv", output=tmp_path / "a.html")
    with pytest.raises(ValueError, match="row 1 has a pose that is not finite"):
        stewart.view(platform, poses=[[0, 0, 0.5, 0, 0, 0], [0, 0, np.nan, 0, 0, 0]],
                     output=tmp_path / "b.html")
    write_csv(tmp_path / "poses.csv", {"t": [0.0], **{n: [0.0] for n in POSE_NAMES}})
    with pytest.raises(ValueError, match="has 1 rows but"):
        stewart.view(platform, tmp_path / "lengths.csv", tmp_path / "poses.csv",
                     output=tmp_path / "c.html")
    write_csv(tmp_path / "back.csv", {"t": [0.0, 1.0, 0.5], **{n: [0.0, 0.0, 0.0] for n in POSE_NAMES}})
    with pytest.raises(ValueError, match="t goes back from 1.0 to 0.5 at row 2"):
        stewart.view(platform, tmp_path / "back.csv", output=tmp_path / "d.html")
    assert not (tmp_path / "a.html").exists()


def test_home_pose_is_the_platform_at_home_height():
    """The tool pose the page starts from puts the platform at (0, 0, home_height): its lengths
    equal those of the frameless platform at home (frames move where poses are taken, not the
    machine)."""
    from stewart.view import home_pose
    framed = stewart.Platform(tool_frame=FRAMED["tool_frame"], user_frame=FRAMED["user_frame"])
    plain = stewart.Platform()
    np.testing.assert_allclose(framed.inverse(home_pose(framed)).length,
                               plain.inverse([0, 0, 0.5, 0, 0, 0]).length, rtol=0, atol=1e-12)


@pytest.mark.parametrize("convention", [{}, {"rotation_order": 1}, {"frame_convention": 1}])
def test_home_pose_is_the_check_s_home_in_the_machine_s_convention(convention):
    """The page starts where every other workflow starts, Platform.check().home, bit for bit,
    in the machine's rotation order and frame convention: the pose whose inverse puts the
    platform at (0, 0, home_height) (its lengths those of the frameless thesis platform)."""
    from stewart.view import home_pose
    framed = stewart.Platform(tool_frame=FRAMED["tool_frame"], user_frame=FRAMED["user_frame"],
                              **convention)
    np.testing.assert_array_equal(home_pose(framed), framed.check().home)
    plain = stewart.Platform(**convention)
    np.testing.assert_allclose(framed.inverse(home_pose(framed)).length,
                               plain.inverse(plain.check().home).length, rtol=0, atol=1e-12)


REFERENCE = pathlib.Path(__file__).resolve().parent / "view_reference"
REFERENCE_POSES = {"home": [0, 0, 0.5, 0, 0, 0], "tilted": [0.04, -0.03, 0.55, 0.15, -0.1, 0.4],
                   "low": [-0.05, 0.05, 0.45, -0.1, 0.12, -0.3]}
REFERENCE_SIZE = (240, 190)  # the stored pictures' size: small, and blurs antialiasing away


def reference_picture(pixels: np.ndarray) -> np.ndarray:
    from PIL import Image
    return np.asarray(Image.fromarray(pixels).resize(REFERENCE_SIZE, Image.Resampling.BOX))


@needs_browser
def test_pictures_match_the_stored_ones(browser, tmp_path):
    """Three poses of the thesis platform against stored pictures of the page (made by this test
    with STEWART_VIEW_REFERENCE=1), box-filtered to 240 x 190 so software rendering's edge pixels
    average out: the mean colour difference must stay below 2 levels of 255 and no more than 0.5 %
    of the pixels may differ by more than 40 (a leg or a plate moved by a pixel does that; a
    missing leg, a wrong colour or a wrong pose does not)."""
    from PIL import Image
    page = stewart.view(stewart.Platform(payload_mass=20, payload_com=[0.05, 0, 0.08]),
                        poses=list(REFERENCE_POSES.values()), output=tmp_path / "ref.html")
    open_page(browser, page)
    pictures = {}
    for i, name in enumerate(REFERENCE_POSES):
        show(browser, i)
        pictures[name] = reference_picture(canvas_pixels(browser))
        if os.environ.get("STEWART_VIEW_REFERENCE") == "1":
            REFERENCE.mkdir(exist_ok=True)
            Image.fromarray(pictures[name]).save(REFERENCE / f"{name}.png", optimize=True)
    for name, picture in pictures.items():
        for other in REFERENCE_POSES:  # each pose matches its own picture and no other
            expected = np.asarray(Image.open(REFERENCE / f"{other}.png").convert("RGB"))
            assert picture.shape == expected.shape, f"{name}: {picture.shape} against {expected.shape}"
            difference = np.abs(picture.astype(int) - expected.astype(int)).max(axis=2)
            mean, far = difference.mean(), np.mean(difference > 40)
            if other == name:
                assert mean < 2.0 and far < 0.005, f"{name}: mean difference {mean:.2f}, {far:.4f} far"
            else:
                assert mean > 2.0 or far > 0.005, f"{name} passes as {other}: the test cannot tell"


@needs_browser
def test_run_scene_writes_the_page_beside_its_csv(browser, build_dir, tmp_path):
    """scripts/run_scene.py --view: the page's lengths equal the FMU's L[k] outputs in the CSV."""
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "run_scene.py"), "heave",
                          "--fmu", str(build_dir / "fmus" / "2.0" / "StewartPlatform.fmu"),
                          "--out", str(tmp_path), "--compare", "", "--view"],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    table = np.genfromtxt(tmp_path / "heave.csv", delimiter=",", names=True)
    open_page(browser, tmp_path / "heave.html")
    assert browser.execute_script("return window.stewartView.frames") == len(table)
    for i in (0, 37, len(table) - 1):
        fmu = [table[f"L{k}"][i] for k in range(1, 7)]  # genfromtxt drops the brackets of L[k]
        np.testing.assert_allclose(page_lengths(browser, i), fmu, rtol=0, atol=1e-9)


@needs_browser
def test_axis_range_arrows_are_the_library_ranges(browser, tmp_path):
    """The arrows along x, y, z reach the ends Platform.axis_ranges gives (float32 in the page),
    and the translation ends are where the library's inverse puts a leg on its stroke."""
    platform = stewart.Platform()
    poses = np.array([[0.01, 0.02, 0.5, 0.03, 0.02, 0.1], [0, 0, 0.55, 0, 0.1, 0]])
    open_page(browser, stewart.view(platform, poses=poses, output=tmp_path / "ranges.html"))
    ends = platform.axis_ranges(poses)
    for i in range(2):
        show(browser, i)
        arrows = browser.execute_script("return window.stewartView.rangeArrows()")
        expected = np.abs(ends[i, :3, :] - poses[i, :3, None]).reshape(-1)
        np.testing.assert_allclose(arrows, expected, rtol=1e-6, atol=1e-7)
        for axis in range(3):  # independent: a leg is on its stroke at each translation end
            for side in range(2):
                q = poses[i].copy()
                q[axis] = ends[i, axis, side]
                L = platform.inverse(q).length[0]
                assert min(np.min(np.abs(L - 0.4)), np.min(np.abs(L - 0.7))) < 2e-6
    page = stewart.view(platform, poses=poses, output=tmp_path / "none.html", axis_ranges=False)
    open_page(browser, page)
    assert browser.execute_script("return window.stewartView.axisRanges(0)") is None


@needs_browser
def test_workspace_overlay_is_the_workspace(browser, tmp_path):
    """The workspace's columns hold the volume stewart.sweeps.workspace_volume computes its own
    way (48 x 48 columns against 32 x 32: within 2 %), and the page draws their surfaces."""
    from stewart.sweeps import workspace_volume
    from stewart.view import workspace_columns

    platform = stewart.Platform()
    columns = workspace_columns(platform, [0.0, 0.0, 0.1])
    z_min, z_max = (np.array([[np.nan if v is None else v for v in row] for row in columns[k]])
                    for k in ("z_min", "z_max"))
    cell = (columns["x"][1] - columns["x"][0]) * (columns["y"][1] - columns["y"][0])
    volume = np.nansum(z_max - z_min) * cell
    assert volume == pytest.approx(workspace_volume(platform, (0.0, 0.0, 0.1)), rel=0.02)
    page = stewart.view(platform, poses=[[0, 0, 0.5, 0, 0, 0.1]], output=tmp_path / "ws.html",
                        workspace=True)
    open_page(browser, page)
    assert browser.execute_script("return window.stewartView.workspaceTriangles()") > 1000
    show(browser, 0)
    with_workspace = canvas_pixels(browser)
    browser.execute_script("const b = document.getElementById('workspace'); b.click();")
    show(browser, 0)
    without = canvas_pixels(browser)
    assert np.mean(np.abs(with_workspace.astype(int) - without.astype(int)).max(axis=2) > 8) > 0.02


@needs_browser
def test_a_machine_without_leg_diameter_renders(browser, tmp_path):
    """leg_diameter 0 turns the interference check off: the legs are still drawn and no leg is
    coloured by interference."""
    platform = stewart.Platform(leg_diameter=0)
    open_page(browser, stewart.view(platform, poses=[[0, 0, 0.5, 0, 0, 0.2]],
                                    output=tmp_path / "thin.html"))
    show(browser, 0)
    assert drawn_fraction(canvas_pixels(browser)) > 0.03
    classes = {s["class"] for s in browser.execute_script("return window.stewartView.legStates(0)")}
    assert "interference" not in classes


@needs_browser
def test_stewart_solve_output_with_its_poses(browser, solve, tmp_path):
    """The inverse output of the command line itself (with --limits: a text column among the
    numbers) and its input: the page's lengths equal the CSV's L1..L6."""
    t = np.linspace(0, 1, 21)
    q = np.column_stack([0.02 * t, 0 * t, 0.5 + 0.05 * t, 0 * t, 0.1 * t, 0.2 * t])
    write_csv(tmp_path / "in.csv", {"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}})
    platform_file = stewart.platform_files()["non_planar"]
    run = solve("--limits", "--platform", platform_file, tmp_path / "in.csv", tmp_path / "out.csv")
    assert run.returncode == 0, run.stderr
    assert "limit_class" in (tmp_path / "out.csv").read_text().splitlines()[0]
    page = stewart.view(platform_file, tmp_path / "out.csv", tmp_path / "in.csv",
                        output=tmp_path / "solve.html")
    open_page(browser, page)
    table = np.genfromtxt(tmp_path / "out.csv", delimiter=",", names=True, dtype=None,
                          encoding="utf-8")
    for i in (0, 10, 20):
        np.testing.assert_allclose(page_lengths(browser, i),
                                   [table[f"L{k}"][i] for k in range(1, 7)], rtol=0, atol=1e-9)
