"""stewart-solve --view: the page the C++ command line writes carries the same data as
stewart.view's page of the same platform and run (both parsed here, every number to 1e-12), and
renders in headless Chromium with the library's lengths. And the page's own work per slider move,
measured in the page (printed, not asserted: docs/view.md, "Size and speed")."""
import base64
import json
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import stewart
from stewart.view import home_pose, read_columns
from stewart.view_template import template_parts
from test_view import (FRAMED, POSE_NAMES, browser, canvas_pixels, drawn_fraction,  # noqa: F401
                       needs_browser, open_page, page_lengths, pose_beyond_one_stroke, show,
                       write_csv)

ROOT = pathlib.Path(__file__).resolve().parents[2]
#: The page's binary arrays and their element types (view_page.js unpacks them the same way).
PACKED = {"t": "<f8", "pose": "<f8", "force": "<f4", "leg_class": "u1", "leg_margin": "<f4",
          "first": "u1", "first_margin": "<f4", "condition": "<f4", "ranges": "<f4"}


def page_data(path: pathlib.Path) -> dict:
    """The JSON a page carries, its packed arrays decoded."""
    text = path.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="stewart-data">(.*?)</script>', text,
                      re.S)
    assert found, f"{path} carries no data element"
    data = json.loads(found.group(1))
    for key, dtype in PACKED.items():
        if data[key] is not None:
            data[key] = np.frombuffer(base64.b64decode(data[key]), dtype=dtype).astype(float)
    return data


def assert_same_data(a, b, where="data"):
    """Equal structure and strings, numbers to 1e-12 (relative, or absolute near 0), NaN = NaN."""
    if isinstance(a, dict):
        assert sorted(a) == sorted(b), f"{where}: keys {sorted(a)} != {sorted(b)}"
        for key in a:
            assert_same_data(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, (str, type(None), bool)):
        assert a == b, f"{where}: {a!r} != {b!r}"
    elif isinstance(a, list) and any(isinstance(x, (str, list, dict)) for x in a):
        assert isinstance(b, list) and len(a) == len(b), f"{where}: {a!r} != {b!r}"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same_data(x, y, f"{where}[{i}]")
    else:
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        assert a.shape == b.shape, f"{where}: shapes {a.shape} != {b.shape}"
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12, equal_nan=True, err_msg=where)


def framed_platform(tmp_path) -> pathlib.Path:
    """non_planar.json with tool and user frames, sensor offsets, a payload and a thick leg."""
    fields = json.loads(pathlib.Path(stewart.platform_files()["non_planar"]).read_text())
    fields.update(FRAMED, payload_mass=40, payload_com=[0.01, 0.0, 0.08], leg_diameter=0.05)
    path = tmp_path / "framed.json"
    path.write_text(json.dumps(fields))
    return path


def run_with_view(solve, tmp_path, platform_file, q, *options):
    t = np.linspace(0, 2, len(q))
    write_csv(tmp_path / "in.csv", {"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}})
    run = solve("--platform", platform_file, *options, "--view", tmp_path / "in.csv",
                tmp_path / "out.csv")
    assert run.returncode == 0, run.stderr
    return tmp_path / "out.html"


def moving_poses(rows=41, home=(0, 0, 0.5, 0, 0, 0)):
    """A run about home (the tool's home pose in the user frame) turning and moving on all axes."""
    s = np.linspace(0, 1, rows)
    return np.asarray(home) + np.column_stack([0.03 * np.sin(4 * s), 0.02 * s,
                                               0.05 * np.sin(3 * s), 0.05 * s,
                                               -0.08 * np.sin(2 * s), 0.2 * s])


def framed_home(platform_file):
    return home_pose(stewart.Platform.from_file(platform_file))


@pytest.mark.parametrize("case", ["framed", "thesis_full", "beyond_stroke"])
def test_the_command_line_page_carries_the_python_page_data(solve, tmp_path, case):
    """OUT.html of stewart-solve --view against stewart.view(platform, OUT.csv, IN.csv): every
    key, list and packed array equal (the title aside), along a run with frames and offsets, with
    the full model's forces, and through a pose beyond one stroke (a leg red, the pose refused)."""
    if case == "framed":
        platform_file = framed_platform(tmp_path)
        q, options = moving_poses(home=framed_home(platform_file)), ()
    elif case == "thesis_full":
        platform_file, q, options = "thesis", moving_poses(), ("--fidelity", "full")
    else:
        platform_file = stewart.platform_files()["thesis"]
        beyond, _ = pose_beyond_one_stroke(stewart.Platform.from_file(platform_file))
        q, options = np.vstack([moving_poses(5), beyond]), ()
    platform_file = stewart.platform_files().get(platform_file, platform_file)
    page = run_with_view(solve, tmp_path, platform_file, q, *options)
    python_page = stewart.view(platform_file, tmp_path / "out.csv", tmp_path / "in.csv",
                               output=tmp_path / "python.html")
    cli, python = page_data(page), page_data(python_page)
    assert cli.pop("title") == f"stewart-solve {tmp_path / 'out.csv'}"
    python.pop("title")
    assert_same_data(cli, python)
    assert cli["frames"] == len(q) and cli["ranges"] is not None
    if case == "beyond_stroke":  # the run reaches a refused pose: the data shows it
        assert cli["first"][-1] == 1 and np.any(cli["leg_margin"][-6:] < 0)
    # Both writers fill one template: the pages differ only in their title and their data.
    strip = re.compile(r'(<title>|<h1>|id="stewart-data">).*?(</title>|</h1>|</script>)', re.S)
    assert strip.sub("", page.read_text()) == strip.sub("", python_page.read_text())


def test_the_platform_force_limits_colour_the_legs(solve, tmp_path):
    """A platform file with leg_force_max (leg 3 without one): stewart-solve --view and
    stewart.view (no force_limit=) both take the force class from the file, margins equal to
    leg_force_max - |F_k| of OUT.csv's own forces, and never on the leg without a limit."""
    fields = json.loads(pathlib.Path(stewart.platform_files()["thesis"]).read_text())
    fields["payload_mass"] = 60
    platform_file = tmp_path / "forces.json"
    platform_file.write_text(json.dumps(fields))
    q = moving_poses()
    peak = np.abs(stewart.Platform.from_file(platform_file).inverse(q, fidelity="full").force).max()
    limit = [1.02 * peak] * 6
    limit[2] = 0  # leg 3: no force limit
    fields["leg_force_max"] = limit
    platform_file.write_text(json.dumps(fields))
    page = run_with_view(solve, tmp_path, platform_file, q, "--fidelity", "full")
    python_page = stewart.view(platform_file, tmp_path / "out.csv", tmp_path / "in.csv",
                               output=tmp_path / "python.html")
    cli, python = page_data(page), page_data(python_page)
    cli.pop("title"), python.pop("title")
    assert_same_data(cli, python)
    out = read_columns(tmp_path / "out.csv")
    force = np.column_stack([out[f"F{k + 1}"] for k in range(6)])
    leg_class = np.asarray(cli["leg_class"]).reshape(-1, 6)
    margin = np.asarray(cli["leg_margin"]).reshape(-1, 6)
    by_force = leg_class == cli["classes"].index("force")
    assert by_force.any(), "no leg is nearest its force limit: the test checks nothing"
    assert not by_force[:, 2].any(), "leg 3 has no force limit but is coloured by force"
    expected = 1.02 * peak - np.abs(force)
    np.testing.assert_allclose(margin[by_force], expected[by_force], rtol=1e-6, atol=1e-3)


def test_the_simulate_page_carries_the_python_page_data(build_dir, tmp_path):
    """stewart-simulate --view: the plant's poses with IN.csv's forces, the same data as
    stewart.view of OUT.csv's poses and IN.csv's forces."""
    platform_file = stewart.platform_files()["thesis"]
    platform = stewart.Platform.from_file(platform_file)
    hold = platform.inverse(home_pose(platform)[None, :], fidelity="full").force[0]
    t = np.linspace(0, 0.5, 26)
    force = hold[None, :] * (1 + 0.02 * np.sin(8 * t)[:, None] * np.arange(1, 7)[None, :] / 6)
    write_csv(tmp_path / "in.csv", {"t": t, **{f"F{k + 1}": force[:, k] for k in range(6)}})
    run = subprocess.run([str(build_dir / "stewart-simulate"), "--platform", platform_file,
                          "--view", tmp_path / "in.csv", tmp_path / "sim.csv"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    out = read_columns(tmp_path / "sim.csv")
    python_page = stewart.view(platform, {"t": out["t"], **{n: out[n] for n in POSE_NAMES},
                                          **{f"F{k + 1}": force[:, k] for k in range(6)}},
                               output=tmp_path / "python.html")
    cli, python = page_data(tmp_path / "sim.html"), page_data(python_page)
    assert cli.pop("title") == f"stewart-simulate {tmp_path / 'sim.csv'}"
    python.pop("title")
    assert_same_data(cli, python)
    assert cli["frames"] == len(t) and np.ptp(cli["pose"].reshape(-1, 6)[:, 2]) > 0  # it moved


def test_view_refusals_name_the_cause(solve, tmp_path):
    """--view with --forward, or with an empty path, is refused before anything is written."""
    write_csv(tmp_path / "in.csv", {"t": [0.0], "L1": [0.6], "L2": [0.6], "L3": [0.6],
                                    "L4": [0.6], "L5": [0.6], "L6": [0.6]})
    run = solve("--forward", "--view", tmp_path / "in.csv", tmp_path / "out.csv")
    assert run.returncode == 2 and "--view" in run.stderr and "scripts/view.py" in run.stderr
    run = solve("--view=", tmp_path / "in.csv", tmp_path / "out.csv")
    assert run.returncode == 2 and "needs a path" in run.stderr
    assert not (tmp_path / "out.csv").exists() and not (tmp_path / "out.html").exists()


def test_a_build_without_three_js_says_to_run_setup(tmp_path):
    """The build's template source made without three.js holds no page and the reason, which
    names scripts/setup.sh (what --view then prints instead of writing a page)."""
    out = tmp_path / "view_template.cpp"
    subprocess.run([sys.executable, ROOT / "python/stewart/view_template.py", "--three",
                    tmp_path / "nothing", "--cpp", out], check=True)
    text = out.read_text()
    assert "kViewTemplateParts = 0;" in text and "scripts/setup.sh" in text
    subprocess.run([sys.executable, ROOT / "python/stewart/view_template.py", "--three",
                    ROOT / ".cache/three", "--cpp", out], check=True)
    parts = int(re.search(r"kViewTemplateParts = (\d+);", out.read_text()).group(1))
    assert parts == len(template_parts()) == 7  # four texts around title, data, title


@needs_browser
def test_the_command_line_page_renders_with_the_library_lengths(browser, solve, tmp_path):
    """The page of stewart-solve --view=PAGE opens from its file with the network off, draws the
    machine, and its lengths are the run's own L1..L6 (its output CSV) to 1e-9 m."""
    platform_file = framed_platform(tmp_path)
    q = moving_poses(home=framed_home(platform_file))
    t = np.linspace(0, 2, len(q))
    write_csv(tmp_path / "in.csv", {"t": t, **{n: q[:, i] for i, n in enumerate(POSE_NAMES)}})
    page = tmp_path / "elsewhere.html"
    run = solve("--platform", platform_file, f"--view={page}", tmp_path / "in.csv",
                tmp_path / "out.csv")
    assert run.returncode == 0, run.stderr
    open_page(browser, page)
    show(browser, 20)
    assert drawn_fraction(canvas_pixels(browser)) > 0.03
    table = np.genfromtxt(tmp_path / "out.csv", delimiter=",", names=True, dtype=None,
                          encoding="utf-8")
    for i in (0, 20, 40):
        np.testing.assert_allclose(page_lengths(browser, i),
                                   [table[f"L{k}"][i] for k in range(1, 7)], rtol=0, atol=1e-9)


@needs_browser
def test_scrub_work_per_slider_move(browser, solve, tmp_path):
    """A 10^5-row run: 300 slider moves spread over it, each an input event as a user's drag
    makes; the page's own work per move (its performance.now around the update) is printed."""
    rows = 100000
    s = np.linspace(0, 1, rows)
    q = np.column_stack([0.03 * np.sin(40 * s), 0 * s, 0.5 + 0.04 * np.sin(70 * s), 0 * s,
                         0.1 * np.sin(30 * s), 0 * s])
    page = run_with_view(solve, tmp_path, stewart.platform_files()["thesis"], q, "--fidelity",
                         "full")
    open_page(browser, page)
    # 300 animation frames: a software renderer on a loaded machine takes 0.1-0.3 s a frame
    browser.set_script_timeout(600)
    times = browser.execute_async_script("""
        const done = arguments[0], slider = document.getElementById('slider');
        const frames = window.stewartView.frames, moves = 300;
        let m = 0;
        function step() {
          if (m === moves) {
            done([window.stewartView.frameWork(), window.stewartView.drawWork()]);
            return;
          }
          slider.value = String(Math.floor(m++ * (frames - 1) / (moves - 1)));
          slider.dispatchEvent(new Event('input'));
          requestAnimationFrame(step);
        }
        requestAnimationFrame(step);""")
    moves, draws = np.array(times[0][-300:]), np.array(times[1][-300:])
    assert len(moves) == 300 and np.all(moves >= 0) and len(draws) >= 290
    print(f"\nscrub, {rows} rows, page {page.stat().st_size / 1e6:.1f} MB, "
          f"{browser.execute_script('return window.stewartView.renderer()')}")
    for name, work in (("a slider move's (setFrame)", moves), ("a draw's (render)", draws)):
        print(f"the page's work, {name} [ms]: median {np.median(work):.2f}, "
              f"p90 {np.percentile(work, 90):.2f}, p99 {np.percentile(work, 99):.2f}, "
              f"max {work.max():.2f}")
