"""The check a user runs first (`stewart-solve --check`, Platform.check) and the per-row status
of stewart-solve, on every shipped machine and on the entry mistakes the check must name: joints
in millimetres, swapped legs, platform joints given in the base frame, a home outside the
strokes. Lengths are checked against the closed form |(0, 0, h) + b_k - a_k| computed here."""
import csv
import json
import pathlib
import subprocess

import numpy as np
import pytest

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[2]
MACHINES = sorted(stewart.platform_files())


def solve(*args):
    from fmu_support import stewart_solve_path
    return subprocess.run([str(stewart_solve_path()), *map(str, args)], capture_output=True,
                          text=True, timeout=120)


def si_joints(path):
    """(base (6, 3), platform (6, 3), home_height) of a file that gives them as numbers in
    metres, else None."""
    data = json.loads(pathlib.Path(path).read_text())
    try:
        base = np.array(data["base_joint"], dtype=float).reshape(6, 3)
        top = np.array(data["platform_joint"], dtype=float).reshape(6, 3)
        return base, top, float(data["home_height"])
    except (KeyError, TypeError, ValueError):
        return None


def write_variant(tmp_path, name, change):
    """A copy of platforms/paired_hexapod.json with change(data) applied."""
    data = json.loads((ROOT / "platforms" / "paired_hexapod.json").read_text())
    change(data)
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps(data))
    return path


@pytest.mark.parametrize("name", MACHINES)
def test_every_shipped_machine_passes_its_check(name):
    path = stewart.platform_files()[name]
    report = stewart.Platform.from_file(path).check()
    assert report.valid, report.text
    assert report.hints == frozenset(), report.text
    assert report.limits.within[0]
    joints = si_joints(path)
    if joints is not None:
        base, top, h = joints
        expected = np.linalg.norm(top + [0, 0, h] - base, axis=1)
        np.testing.assert_allclose(report.length, expected, rtol=1e-14)
    result = solve("--check", path)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "home is within every limit" in result.stdout
    assert result.stdout == report.text


def test_the_check_report_agrees_with_the_library():
    """Lengths are the inverse's at home; margins and ranges are the limit calls' at home."""
    platform = stewart.Platform.from_file(stewart.platform_files()["paired_hexapod"])
    report = platform.check()
    np.testing.assert_array_equal(report.length, platform.inverse(report.home).length[0])
    np.testing.assert_array_equal(report.limits.margin, platform.limits(report.home).margin)
    np.testing.assert_array_equal(report.ranges.ends, platform.axis_ranges(report.home, details=True).ends)


def test_joints_in_millimetres_are_named(tmp_path):
    def to_mm(data):
        data["base_joint"] = [1000 * v for v in data["base_joint"]]
        data["platform_joint"] = [1000 * v for v in data["platform_joint"]]
    path = write_variant(tmp_path, "mm", to_mm)
    report = stewart.Platform.from_file(path).check()
    assert not report.valid and "units" in report.hints
    result = solve("--check", path)
    assert result.returncode == 1
    assert "units?" in result.stdout and "NOT a valid pose" in result.stdout


def test_swapped_legs_are_named(tmp_path):
    def swap(data):
        p = data["platform_joint"]
        data["platform_joint"] = p[3:6] + p[0:3] + p[6:]
    path = write_variant(tmp_path, "swapped", swap)
    report = stewart.Platform.from_file(path).check()
    assert "swapped_legs" in report.hints and report.crossing == (1, 2), report.text
    assert "Legs 1 and 2 cross" in solve("--check", path).stdout


def test_platform_joints_in_the_base_frame_are_named(tmp_path):
    def in_base_frame(data):
        p = np.reshape(data["platform_joint"], (6, 3))
        p[:, 2] += data["home_height"]
        data["platform_joint"] = p.ravel().tolist()
    path = write_variant(tmp_path, "base_frame", in_base_frame)
    report = stewart.Platform.from_file(path).check()
    assert "frame" in report.hints and not report.valid, report.text
    assert "frame?" in solve("--check", path).stdout


def test_a_home_outside_the_strokes_fails_the_check(tmp_path):
    path = write_variant(tmp_path, "short", lambda d: d.update(stroke_max=0.26))
    report = stewart.Platform.from_file(path).check()
    assert not report.valid and report.limits.first[0] == 1  # stroke
    assert report.hints == frozenset()  # a real mistake of stroke, not of units or frames
    result = solve("--check", path)
    assert result.returncode == 1 and "first limit it fails is stroke" in result.stdout


def test_the_axis_margin_names_its_axis_in_its_unit(tmp_path):
    """The axis class's line: the margin of the axis nearest its limit, in that axis' unit, and
    the axis' name; no limit set says so instead of printing the largest double."""
    assert "axis            none set" in solve("--check", ROOT / "platforms" / "paired_hexapod.json").stdout
    # home at z 0.25 m, yaw 0: z within 2 mm of its top, yaw 3 deg (a 0.1 m arm moves 5 mm)
    path = write_variant(tmp_path, "soft", lambda d: d.update(
        axis_max=[1, 1, 0.252, 1, 1, np.radians(3.0)], axis_min=[-1, -1, 0, -1, -1, -1]))
    line = [x for x in solve("--check", path).stdout.splitlines() if x.startswith("  axis ")][0]
    words = line.split()
    assert words[2:] == ["m", "z"] and float(words[1]) == pytest.approx(0.002, abs=1e-9), line


def test_check_with_a_bad_file_says_why(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"geometry": 1, "payload_mass": -3}')
    result = solve("--check", path)
    assert result.returncode != 0 and "payload_mass" in result.stderr


def read_out(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def test_every_row_has_a_status(tmp_path):
    """status is the first limit class of the row's pose: the library's limit check, and a pose
    past a stroke end by the closed form says stroke."""
    path = stewart.platform_files()["paired_hexapod"]
    base, top, h = si_joints(path)
    poses = np.array([[0, 0, h, 0, 0, 0], [0.01, 0, h + 0.005, 0, 0.02, 0],
                      [0, 0, h + 0.2, 0, 0, 0]])
    lengths = np.linalg.norm(top[None] + poses[:, None, :3] - base[None], axis=2)
    assert lengths[2].max() > 0.335 and lengths[:2].max() < 0.335  # row 3 past stroke_max
    infile, outfile = tmp_path / "in.csv", tmp_path / "out.csv"
    infile.write_text("t,x,y,z,roll,pitch,yaw\n" +
                      "".join(f"{i},{','.join(repr(float(v)) for v in p)}\n"
                              for i, p in enumerate(poses)))
    result = solve("--static", "--platform", path, infile, outfile)
    assert result.returncode == 0, result.stderr
    header, rows = read_out(outfile)
    status = [r[header.index("status")] for r in rows]
    assert status == ["none", "none", "stroke"]
    first = stewart.Platform.from_file(path).limits(poses).first
    assert status == [stewart.limits.class_name(c) for c in first]


def test_static_poses_get_static_forces(tmp_path):
    """--static: poses at rest. At home on the thesis platform the legs' vertical components
    carry the weight (sum F_k n_kz = m g), whatever the rows before and after."""
    poses = np.array([[0, 0, 0.5, 0, 0, 0], [0.05, 0, 0.55, 0.1, 0, 0], [0, 0, 0.5, 0, 0, 0]])
    infile, outfile = tmp_path / "in.csv", tmp_path / "out.csv"
    infile.write_text("x,y,z,roll,pitch,yaw\n" +
                      "".join(",".join(repr(float(v)) for v in p) + "\n" for p in poses))
    assert solve("--static", infile, outfile).returncode == 0  # no t column: rows at rest
    header, rows = read_out(outfile)
    F = np.array([[float(r[header.index(f"F{k}")]) for k in range(1, 7)] for r in rows])
    rates = np.array([[float(r[header.index(f"L_dot{k}")]) for k in range(1, 7)] for r in rows])
    assert np.all(rates == 0)
    table = {p["name"]: p["defaults"] for p in stewart.parameters()}
    base = np.reshape(table["base_joint"], (6, 3))
    top = np.reshape(table["platform_joint"], (6, 3)) + [0, 0, 0.5]
    n_z = (top - base)[:, 2] / np.linalg.norm(top - base, axis=1)
    weight = table["platform_mass"][0] * -table["gravity"][2]
    for j in (0, 2):
        assert abs(F[j] @ n_z - weight) < 1e-9 * weight
    # without --static the same file has no t column to differentiate: refused, naming it
    assert "t,x,y,z" in solve(infile, outfile).stderr
    # a file that gives rates is not at rest
    moving = tmp_path / "moving.csv"
    moving.write_text("t,x,y,z,roll,pitch,yaw,x_dot,y_dot,z_dot,roll_dot,pitch_dot,yaw_dot\n"
                      "0,0,0,0.5,0,0,0,0.1,0,0,0,0,0\n")
    refused = solve("--static", moving, outfile)
    assert refused.returncode == 1 and "--static" in refused.stderr
