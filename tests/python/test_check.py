"""The check a user runs first (`stewart-solve --check`, Platform.check) and the per-row status
of stewart-solve, on every shipped machine and on the entry mistakes the check must name: joints
in millimetres, swapped legs, platform joints given in the base frame, a home outside the
strokes. Lengths are checked against the closed form |(0, 0, h) + b_k - a_k| computed here."""
import csv
import json
import pathlib
import subprocess
from decimal import Decimal

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


def write_variant(tmp_path, name, change, machine="paired_hexapod"):
    """A copy of platforms/MACHINE.json with change(data) applied."""
    data = json.loads((ROOT / "platforms" / f"{machine}.json").read_text())
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


# The entry mistakes on a machine of each kind: a positioning hexapod, the precision hexapod with
# its far pivot, the motion simulator.
MISTAKE_MACHINES = ["paired_hexapod", "rubin_camera_hexapod", "simona_motion_base"]


@pytest.mark.parametrize("machine", MISTAKE_MACHINES)
def test_joints_in_millimetres_are_named(tmp_path, machine):
    def to_mm(data):
        data["base_joint"] = [1000 * v for v in data["base_joint"]]
        data["platform_joint"] = [1000 * v for v in data["platform_joint"]]
    path = write_variant(tmp_path, "mm", to_mm, machine)
    report = stewart.Platform.from_file(path).check()
    assert not report.valid and "units" in report.hints
    result = solve("--check", path)
    assert result.returncode == 1
    assert "units?" in result.stdout and "NOT a valid pose" in result.stdout


@pytest.mark.parametrize("machine", MISTAKE_MACHINES)
def test_swapped_legs_are_named(tmp_path, machine):
    def swap(data):
        p = data["platform_joint"]
        data["platform_joint"] = p[3:6] + p[0:3] + p[6:]
    path = write_variant(tmp_path, "swapped", swap, machine)
    report = stewart.Platform.from_file(path).check()
    assert "swapped_legs" in report.hints and report.crossing == (1, 2), report.text
    assert "Legs 1 and 2 cross" in solve("--check", path).stdout


@pytest.mark.parametrize("machine", MACHINES)
def test_platform_joints_in_the_base_frame_are_named(tmp_path, machine):
    """On every shipped machine, including one whose platform joints lie at several heights
    (rubin_m2_hexapod: legs 1-3 vertical, 4-6 horizontal), where neither "below the base" nor "z
    equal to home_height" holds."""
    def in_base_frame(data):
        p = np.reshape(data["platform_joint"], (6, 3))
        p[:, 2] += data["home_height"]
        data["platform_joint"] = p.ravel().tolist()
    path = write_variant(tmp_path, "base_frame", in_base_frame, machine)
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


@pytest.mark.parametrize("machine", ["rubin_m2_hexapod", "simona_motion_base"])
def test_a_home_refused_by_another_limit_is_no_frame_mistake(machine):
    """The frame hint wants a leg beyond its stroke at home: a home refused by the condition
    number (a warn_condition no machine meets), its strokes met, names that limit and no entry
    mistake."""
    report = stewart.Platform.from_file(stewart.platform_files()[machine]).check(warn_condition=1.5)
    assert not report.valid and report.limits.first[0] == 5, report.text  # condition
    assert (report.length > report.stroke_min).all() and (report.length < report.stroke_max).all()
    assert report.hints == frozenset(), report.text


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


def test_static_poses_of_a_precision_hexapod_carry_its_weight(tmp_path):
    """The Rubin camera hexapod (3.4 t on its legs) at home, moved, and at home again, rows with
    times but no derivatives: with --static the home rows' forces hold the weight, sum F_k n_kz
    = (platform_mass + payload_mass) g with n_k from the joints; without it the rows are a
    trajectory, differentiated, and row 0's forces are dynamic ones."""
    path = stewart.platform_files()["rubin_camera_hexapod"]
    base, top, h = si_joints(path)
    data = json.loads(pathlib.Path(path).read_text())
    top = top + [0, 0, h]
    n_z = (top - base)[:, 2] / np.linalg.norm(top - base, axis=1)
    weight = (data["platform_mass"] + data["payload_mass"]) * 9.81
    home = stewart.Platform.from_file(path).check().home
    poses = np.array([home, home + [0.005, 0, 0.004, 0, 0.002, 0], home])
    infile = tmp_path / "in.csv"
    infile.write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(
        f"{0.1 * i},{','.join(repr(float(v)) for v in p)}\n" for i, p in enumerate(poses)))
    forces = {}
    for extra in ([], ["--static"]):
        out = tmp_path / f"out{len(extra)}.csv"
        result = solve(*extra, "--platform", path, infile, out)
        assert result.returncode == 0, result.stderr
        header, rows = read_out(out)
        forces[len(extra)] = np.array([[float(r[header.index(f"F{k}")]) for k in range(1, 7)]
                                       for r in rows])
    for j in (0, 2):
        assert abs(forces[1][j] @ n_z - weight) < 1e-9 * weight
    assert abs(forces[0][0] @ n_z - weight) > 0.01 * weight  # differentiated: not at rest


# ---- the check in the file's units -------------------------------------------------------------

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _in_units(data, length, angle, as_strings=False):
    """data (SI, as a platform file gives it) with every length times `length` (a power of ten),
    every angle times `angle`, by the parameter table's units; as_strings writes "12.5 mm" and
    "0.4 deg" values instead of plain numbers."""
    units = {p["name"]: p["unit"] for p in stewart.parameters()}
    out = {}
    for name, value in data.items():
        unit = units.get(name)
        kinds = {"m": ["m"], "rad": ["rad"], "m, rad": ["m"] * 3 + ["rad"] * 3}.get(unit)
        if kinds is None:
            out[name] = value
            continue
        values = list(np.atleast_1d(value))
        kinds = kinds * (len(values) // len(kinds)) if len(kinds) < len(values) else kinds
        # lengths by moving the decimal point (the reader's prefixes do too: the same doubles)
        converted = [(Decimal(repr(float(v))) * Decimal(length), "mm") if k == "m"
                     else (float(v) * angle, "deg") for v, k in zip(values, kinds)]
        written = [f"{v} {u}" if as_strings else float(v) for v, u in converted]
        out[name] = written if np.ndim(value) else written[0]
    return out


def _shown(si_text, text, length, angle, si_names=("m", "deg"), names=("mm", "deg")):
    """Every number of text against the same number of si_text times its unit's factor: a
    number followed by a length unit (after '..' and the range's other end) times length, by an
    angle unit times angle, the rows of the leg table times length, leg numbers and the
    condition number unchanged."""
    import re
    token = re.compile(rf"{NUMBER}|[A-Za-z_]+|\.\.")
    si_lines, lines = si_text.splitlines(), text.splitlines()
    assert len(si_lines) == len(lines)
    compared = 0
    for si_line, line in zip(si_lines, lines):
        si_tokens, tokens = token.findall(si_line), token.findall(line)
        assert len(si_tokens) == len(tokens), (si_line, line)
        leg_row = re.match(r"\d    ", si_line) is not None
        for i, (a, b) in enumerate(zip(si_tokens, tokens)):
            if not re.fullmatch(NUMBER, a):
                if a in si_names:  # the SI name where the text has its own
                    assert b == names[si_names.index(a)], (si_line, line)
                else:
                    assert a == b, (si_line, line)
                continue
            after = [t for t in si_tokens[i + 1:i + 4] if t != ".." and not re.fullmatch(NUMBER, t)]
            unit = after[0] if after else None
            factor = 1.0
            if leg_row and i > 0:
                factor = length
            elif i > 0 and si_tokens[i - 1] in ("leg", "legs", "and"):
                factor = 1.0
            elif unit == si_names[0]:
                factor = length
            elif unit == si_names[1]:
                factor = angle
            # both printed to 6 significant digits (each within 5e-6)
            assert float(b) == pytest.approx(float(a) * factor, rel=1e-5, abs=1e-9 * abs(factor)), \
                (si_line, line)
            compared += factor != 1.0
    return compared


@pytest.mark.parametrize("as_strings", [False, True], ids=["file_units", "values_with_units"])
def test_the_check_prints_in_the_file_units(tmp_path, as_strings):
    """A real machine written in mm and deg (the file's "units", or each value with its unit):
    every length and angle the check prints (legs, strokes, margins, clearances, the axis limit,
    the ranges, home) is the SI file's check times the unit's factor, and the text names mm; the
    numbers of the report stay SI. --units (and units=) override the file's."""
    data = json.loads((ROOT / "platforms" / "rubin_camera_hexapod.json").read_text())
    # software limits of 20 mm and 0.4 deg, so that the axis class prints a margin too
    data.update(axis_min=[-0.02, -0.02, -0.02, -0.007, -0.007, -0.007],
                axis_max=[0.02, 0.02, 0.02, 0.007, 0.007, 0.007])
    si_path, mm_path = tmp_path / "si.json", tmp_path / "mm.json"
    si_path.write_text(json.dumps(data))
    deg = 180 / np.pi
    mm = _in_units(data, 1000, deg, as_strings)
    if not as_strings:
        mm["units"] = {"length": "mm", "angle": "deg"}
    mm_path.write_text(json.dumps(mm))
    si_run, mm_run = solve("--check", si_path), solve("--check", mm_path)
    assert si_run.returncode == 0 and mm_run.returncode == 0, si_run.stderr + mm_run.stderr
    assert "length [mm]" in mm_run.stdout and " mm  (stroke" in mm_run.stdout
    assert "length [m]" in si_run.stdout
    # home x y z, 6 legs x 4, the stroke and interference margins, the x y z ranges
    assert _shown(si_run.stdout, mm_run.stdout, 1e3, 1.0) >= 3 + 6 * 4 + 2 + 6
    report = stewart.Platform.from_file(mm_path).check()
    assert report.text == mm_run.stdout and report.units == ("mm", "deg")
    np.testing.assert_allclose(report.length, stewart.Platform.from_file(si_path).check().length,
                               rtol=1e-15)
    # --units over the file's: um and urad
    um_run = solve("--check", mm_path, "--units", "um,urad")
    assert um_run.returncode == 0, um_run.stderr
    _shown(si_run.stdout, um_run.stdout, 1e6, 1e6 / deg, names=("um", "urad"))
    assert stewart.Platform.from_file(mm_path).check(units="urad,um").text == um_run.stdout
    bad = solve("--check", mm_path, "--units", "mm,inch")
    assert bad.returncode == 2 and "'inch' is neither a length unit" in bad.stderr
    with pytest.raises(ValueError, match="'inch' is neither"):
        stewart.Platform.from_file(mm_path).check(units="inch")


@pytest.mark.parametrize("fields, units", [
    ({"units": {"length": "um"}, "stroke_max": "0.7 m"}, ("um", "deg")),  # stated wins
    ({"stroke_min": "400 mm", "stroke_max": "0.6 m"}, ("m", "deg")),  # two units: neither
    ({"stroke_min": "400 mm", "axis_max[6]": "3 deg", "axis_max[5]": "50 mrad"}, ("mm", "deg")),
    ({"stroke_min": "400 mm", "stroke_max": "700 mm", "axis_max[6]": "50 mrad"}, ("mm", "mrad")),
])
def test_the_file_units_are_the_stated_else_the_one_written(tmp_path, fields, units):
    path = tmp_path / "p.json"
    path.write_text(json.dumps(fields))
    report = stewart.Platform.from_file(path).check()
    assert report.units == units
    assert f"length [{units[0]}]" in report.text and f"roll 0 {units[1]}" in report.text
    assert solve("--check", path).stdout == report.text
