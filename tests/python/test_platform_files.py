"""Platform files and the general geometry from Python, the command lines, sweep specs and the FMU
(docs/geometry.md): the shipped files against their joints, the thesis file against the defaults,
bad files refused naming the field, a file as an FMU parameter set, the old scalar strokes."""
import csv
import json
import math
import pathlib
import subprocess

import numpy as np
import pytest

import stewart
from stewart.sweeps import SpecError, resolve

from fmu_support import assert_unit_solves_as_the_library, stewart_solve_path
from reference import rotation

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATFORMS = ROOT / "platforms"
NAMES = ("thesis", "paired_hexapod", "genhexkins", "non_planar")


def joints(name):
    data = json.loads((PLATFORMS / f"{name}.json").read_text())
    return (np.array(data["base_joint"]).reshape(6, 3), np.array(data["platform_joint"]).reshape(6, 3),
            data["home_height"])


def closed_form(base, plate, pose):
    R = rotation(*pose[3:])
    return np.linalg.norm(np.asarray(pose[:3]) + plate @ R.T - base, axis=1)


def test_the_package_ships_the_platform_files():
    files = stewart.platform_files()
    shipped = {p.stem for p in PLATFORMS.glob("*.json")}
    assert set(NAMES) <= shipped and set(files) == shipped
    for name in shipped:
        assert files[name].read_text() == (PLATFORMS / f"{name}.json").read_text()


@pytest.mark.parametrize("name", NAMES)
def test_shipped_platform_lengths_and_round_trip(name):
    platform = stewart.Platform.from_file(PLATFORMS / f"{name}.json")
    base, plate, h = joints(name)
    rng = np.random.default_rng(19)
    poses = np.column_stack([rng.uniform(-0.01, 0.01, (50, 2)), h + rng.uniform(-0.01, 0.01, 50),
                             rng.uniform(-0.03, 0.03, (50, 3))])
    sol = platform.inverse(poses, fidelity="full")
    assert np.all(sol.status == 0)
    expected = np.array([closed_form(base, plate, q) for q in poses])
    assert np.max(np.abs(sol.length - expected)) < 1e-14
    back = platform.forward(sol.length)
    assert np.max(np.abs(back.pose - poses)) < 1e-11


def test_thesis_file_gives_the_default_platform():
    pose = np.array([[0.02, -0.01, 0.51, 0.05, -0.03, 0.1], [0, 0, 0.5, 0, 0, 0]])
    default, thesis = stewart.Platform(), stewart.Platform.from_file(PLATFORMS / "thesis.json")
    for level in ("kinematic", "massless"):
        a, b = default.inverse(pose, fidelity=level), thesis.inverse(pose, fidelity=level)
        assert np.array_equal(a.length, b.length) and np.array_equal(a.force, b.force)
    a, b = default.inverse(pose, fidelity="full"), thesis.inverse(pose, fidelity="full")
    assert np.array_equal(a.length, b.length)
    assert np.max(np.abs(a.force - b.force) / np.abs(a.force)) < 1e-12  # Cardan arms: rounding


def test_scalar_strokes_fill_every_leg():
    """stroke_min=0.55 is stroke_min=[0.55] * 6; one leg's own limit flags that leg alone."""
    home = np.array([[0, 0, 0.5, 0, 0, 0]])  # every leg 0.563 m
    for lo, hi, flagged in ((0.55, 0.6, 0), (0.57, 0.6, 1), (0.5, 0.56, 1)):
        scalar = stewart.Platform(stroke_min=lo, stroke_max=hi).inverse(home)
        per_leg = stewart.Platform(stroke_min=[lo] * 6, stroke_max=[hi] * 6).inverse(home)
        assert scalar.warnings[0] & 1 == per_leg.warnings[0] & 1 == flagged
    for k in range(6):
        one = [0.7] * 6
        one[k] = 0.56
        assert stewart.Platform(stroke_max=one).inverse(home).warnings[0] & 1 == 1


BAD_FILES = [
    ('{"payload_mas": 1}', ["payload_mas", "nearest is payload_mass", "line 1 column 2"]),
    ('{"payload_mass": -1}', ["payload_mass = -1"]),
    ('{"gravity": [0, 9.81]}', ["gravity has 2 values"]),
    ('{"base_cardan_axis": 0}', ["base_cardan_axis = 0 must be a list"]),
    ('{"stroke_min": [0.4, 0.4, 0.4]}', ["stroke_min has 3 values"]),
    ('{"home_height": 0.5, "home_height": 0.6}', ["home_height", "twice"]),
    ('{"geometry": 1}', ["geometry = 1 but not base_joint"]),
    ('{"payload_mass": 1', ["after the value of \"payload_mass\""]),
    ('{"payload_mass": Infinity}', ["payload_mass: expected a number"]),
]


def refusal_naming(path, text, words):
    """Platform.from_file's refusal of a file holding `text`, which names each of `words`."""
    path.write_text(text)
    with pytest.raises(stewart.ParameterError) as e:
        stewart.Platform.from_file(path)
    for w in words:
        assert w in str(e.value)
    return str(e.value)


@pytest.mark.parametrize("text,words", BAD_FILES)
def test_bad_files_are_refused_naming_the_field(tmp_path, solve, text, words):
    path = tmp_path / "bad.json"
    assert str(path) in refusal_naming(path, text, words)
    # the command line: refused before anything is solved, nothing written
    poses, out = tmp_path / "in.csv", tmp_path / "out.csv"
    poses.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n")
    r = solve("--platform", path, poses, out)
    assert r.returncode == 2 and not out.exists()
    for w in words:
        assert w in r.stderr


def test_cross_field_checks_name_the_field(tmp_path):
    base, plate, h = joints("genhexkins")
    data = json.loads((PLATFORMS / "genhexkins.json").read_text())
    data["platform_cardan_axis"] = [0.0] * 15 + [0.6, 0.0, 0.0]  # not a unit vector
    path = tmp_path / "arm.json"
    path.write_text(json.dumps(data))
    with pytest.raises(stewart.ParameterError, match=r"platform_cardan_axis\[16\.\.18\]"):
        stewart.Platform.from_file(path)


def read_csv(path):
    """header and values of the numeric columns (stewart-solve's status is a class name)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    numeric = [i for i, h in enumerate(rows[0]) if h != "status"]
    return ([rows[0][i] for i in numeric],
            np.array([[float(r[i]) for i in numeric] for r in rows[1:]]))


def test_command_lines_read_the_file(tmp_path, solve, build_dir):
    """stewart-solve (inverse and forward) and stewart-simulate on a platform file give what
    Python gives on the same file."""
    file = PLATFORMS / "non_planar.json"
    platform = stewart.Platform.from_file(file)
    poses = np.array([[0.01, 0.0, 0.5, 0.02, 0.0, 0.01], [0.0, 0.01, 0.49, 0.0, 0.03, -0.02]])
    pose_csv, out_csv = tmp_path / "poses.csv", tmp_path / "out.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(
        f"{i},{','.join(repr(float(v)) for v in q)}\n" for i, q in enumerate(poses)))
    r = solve("--fidelity", "massless", "--platform", file, pose_csv, out_csv)
    assert r.returncode == 0, r.stderr
    header, data = read_csv(out_csv)
    lengths = data[:, [header.index(f"L{k}") for k in range(1, 7)]]
    assert np.array_equal(lengths, platform.inverse(poses, fidelity="massless").length)
    # forward on those lengths
    back_csv = tmp_path / "back.csv"
    r = solve("--forward", "--platform", file, out_csv, back_csv)
    assert r.returncode == 0, r.stderr
    header, back = read_csv(back_csv)
    assert np.max(np.abs(back[:, 1:7] - poses)) < 1e-12
    # the plant at rest under the static forces stays there
    static = platform.inverse(np.array([[0, 0, 0.5, 0, 0, 0]]), fidelity="massless").force[0]
    force_csv, sim_csv = tmp_path / "forces.csv", tmp_path / "sim.csv"
    force_csv.write_text("t," + ",".join(f"F{k}" for k in range(1, 7)) + "\n" +
                         "".join(f"{t},{','.join(repr(float(v)) for v in static)}\n" for t in (0, 0.1)))
    r = subprocess.run([str(build_dir / "stewart-simulate"), "--fidelity", "massless", "--platform",
                        str(file), str(force_csv), str(sim_csv)], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    header, sim = read_csv(sim_csv)
    assert np.max(np.abs(sim[:, header.index("z")] - 0.5)) < 1e-9


def test_sweep_spec_takes_a_platform_file(tmp_path):
    spec = {"kind": "workspace", "platform_file": "genhexkins.json", "platform": {"payload_mass": 5},
            "slices": [{"name": "z", "axes": {"z": {"start": 0.45, "stop": 0.55, "num": 3}}}]}
    (tmp_path / "genhexkins.json").write_text((PLATFORMS / "genhexkins.json").read_text())
    resolved = resolve(spec, ROOT / "scenes", tmp_path)
    base, _, h = joints("genhexkins")
    assert resolved["platform"]["payload_mass"] == 5
    assert np.array_equal(np.reshape(resolved["platform"]["base_joint"], (6, 3)), base)
    (tmp_path / "bad.json").write_text('{"geometry": 1, "payload_mass": -3}')
    with pytest.raises(SpecError, match=r"platform_file: .*payload_mass = -3"):
        resolve({**spec, "platform_file": "bad.json"}, ROOT / "scenes", tmp_path)


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_a_platform_file_is_an_fmu_parameter_set(version):
    """The file's names, element by element, are the FMU's parameters: the unit gives the
    library's lengths and forces for the same file."""
    data = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    values = {}
    for name, value in data.items():
        if name == "description":
            continue
        if isinstance(value, list):
            values.update({f"{name}[{k}]": v for k, v in enumerate(value, start=1)})
        elif name.startswith("stroke_"):
            values.update({f"{name}[{k}]": value for k in range(1, 7)})
        else:
            values[name] = value
    start_values = stewart.fmu_start_values(PLATFORMS / "paired_hexapod.json", version)
    assert {name: start_values[name] for name in values} == values
    pose = [0.002, -0.001, data["home_height"] + 0.003, 0.01, -0.02, 0.015]
    platform = stewart.Platform.from_file(PLATFORMS / "paired_hexapod.json")
    assert_unit_solves_as_the_library(start_values, platform, pose, version)


# ------------------------------------------------ overrides, units, strokes, locales, files

def test_from_file_changes_on_top_of_the_file(tmp_path):
    """from_file(path, stroke_max=...) replaces the file's field (whole, or the element named):
    the legs at home (0.5631 m) warn against the file's stroke_max of 0.55 and not against 0.8."""
    path = tmp_path / "machine.json"
    path.write_text('{"stroke_min": 0.4, "stroke_max": 0.55, "payload_mass": 2}')
    home = np.array([[0, 0, 0.5, 0, 0, 0]])
    assert stewart.Platform.from_file(path).inverse(home).warnings[0] & 1
    changed = stewart.Platform.from_file(path, stroke_max=0.8)
    assert changed.params["stroke_max"] == 0.8 and changed.params["payload_mass"] == 2
    assert not changed.inverse(home).warnings[0] & 1
    one_leg = stewart.Platform.from_file(path, **{"stroke_max": 0.8, "stroke_max[3]": 0.55})
    margins = one_leg.limits(home).margin[0]
    assert one_leg.inverse(home).warnings[0] & 1 and margins[0] < 0  # leg 3 alone is over
    assert np.array_equal(stewart.Platform.from_file(path, payload_mass=5).inverse(home, fidelity="massless").force,
                          stewart.Platform(stroke_min=0.4, stroke_max=0.55, payload_mass=5).inverse(
                              home, fidelity="massless").force)


def shifted_decimal(text, places):
    """The decimal number text times 10**places, written exactly (no binary rounding)."""
    from decimal import Decimal
    return format(Decimal(text).scaleb(places), "f")


def as_json_numbers(data):
    """data (numbers as decimal strings) as JSON text with those numbers written as numbers."""
    def value(v):
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f'"{k}": "{x}"' for k, x in v.items()) + "}"
        if isinstance(v, str) and not v[:1].isalpha():
            return v
        return json.dumps(v)
    return "{" + ", ".join(f'"{k}": {value(v)}' for k, v in data.items()) + "}"


@pytest.mark.parametrize("name", ["paired_hexapod", "genhexkins", "rubin_camera_hexapod",
                                  "rubin_m2_hexapod_drives", "simona_motion_base_drives"])
def test_a_file_in_mm_and_deg_gives_the_outputs_of_the_file_in_m(tmp_path, solve, name):
    """The same machine in mm and deg (file-wide units) and in m and rad: the same parameters bit
    for bit (a decimal prefix moves the exponent, so 198.054 mm reads as 0.198054 does), so the
    same lengths and forces from Python and the command line. Every length of the parameter
    table's (m; the x, y, z of the frames), the real machines' frames, leg diameters and screw
    leads too."""
    units = {p["name"]: p["unit"] for p in stewart.parameters()}
    data = json.loads((PLATFORMS / f"{name}.json").read_text(), parse_float=str, parse_int=str)
    mm = {"units": {"length": "mm", "angle": "deg"}}
    for key, value in data.items():
        if units.get(key) == "m":
            value = [shifted_decimal(v, 3) for v in value] if isinstance(value, list) else shifted_decimal(value, 3)
        elif units.get(key) == "m, rad":  # x, y, z, roll, pitch, yaw: zero angles in the files
            assert all(float(v) == 0 for v in value[3:]), key
            value = [shifted_decimal(v, 3) for v in value[:3]] + value[3:]
        mm[key] = value
    mm["base_joint_limit"] = "40"
    si = dict(data, base_joint_limit=repr(40 * (math.pi / 180)))
    (tmp_path / "mm.json").write_text(as_json_numbers(mm))
    (tmp_path / "m.json").write_text(as_json_numbers(si))
    assert "198.054" in (tmp_path / "mm.json").read_text() or name != "paired_hexapod"
    a = stewart.params.read_platform_file(tmp_path / "m.json")
    b = stewart.params.read_platform_file(tmp_path / "mm.json")
    assert a == b
    home = stewart.Platform.from_file(tmp_path / "m.json").check().home
    poses = home + np.array([[0.001, -0.002, 0.003, 0.01, -0.02, 0.015], [0, 0, 0, 0, 0, 0]])
    pa = stewart.Platform.from_file(tmp_path / "m.json").inverse(poses, fidelity="full")
    pb = stewart.Platform.from_file(tmp_path / "mm.json").inverse(poses, fidelity="full")
    assert np.array_equal(pa.length, pb.length) and np.array_equal(pa.force, pb.force)
    pose_csv = tmp_path / "poses.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(
        f"{i},{','.join(repr(float(v)) for v in q)}\n" for i, q in enumerate(poses)))
    for f in ("m", "mm"):
        r = solve("--fidelity", "full", "--platform", tmp_path / f"{f}.json", pose_csv, tmp_path / f"{f}.csv")
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "m.csv").read_text() == (tmp_path / "mm.csv").read_text()


def test_strokes_as_neutral_and_travel(tmp_path):
    path = tmp_path / "travel.json"
    path.write_text('{"stroke_neutral": "563 mm", "stroke_travel": [0.1, 0.1, 0.1, 0.1, 0.1, 0.05]}')
    fields = stewart.params.read_platform_file(path)
    assert np.allclose(fields["stroke_min"], [0.463] * 5 + [0.513], rtol=0, atol=1e-15)
    assert np.allclose(fields["stroke_max"], [0.663] * 5 + [0.613], rtol=0, atol=1e-15)
    path.write_text('{"stroke_max": 0.7, "stroke_neutral": 0.55, "stroke_travel": 0.1}')
    with pytest.raises(stewart.ParameterError, match="the strokes are given twice"):
        stewart.Platform.from_file(path)


MORE_BAD_FILES = [
    ('{"geometry": 1, "base_joint[1]": 0.6, "platform_joint[1]": 0.45}',
     ["only some of base_joint", "base_joint[2] and 16 more are missing"]),
    ('{"gravity": [0, 0, -9.81], "gravity[3]": -9.8}', ["gravity[3] is given twice", '"gravity"', '"gravity[3]"']),
    ('{"stroke_min": 0.4, "stroke_min[2]": 0.41}', ["stroke_min[2] is given twice"]),
    ('{"home_height": "0.5 kg"}', ["kg is not a unit of home_height"]),
    ('{"units": {"length": "yard"}}', ['units.length = "yard" is not a unit of length']),
]


@pytest.mark.parametrize("text,words", MORE_BAD_FILES)
def test_more_bad_files_are_refused_naming_the_field(tmp_path, text, words):
    refusal_naming(tmp_path / "bad.json", text, words)


def test_only_regular_files_are_read_at_once(tmp_path, solve):
    """A FIFO without a writer, /dev/zero, a directory and a file over the cap are refused at once
    by Python and stewart-solve (the subprocess's timeout guards against a blocking open)."""
    import os
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    big = tmp_path / "big.json"
    big.write_text('{"payload_mass": 1}' + " " * stewart.params.PLATFORM_FILE_MAX_BYTES)
    cases = [(fifo, "is a FIFO"), ("/dev/zero", "is a device"), (tmp_path, "is a directory"),
             (big, "larger than 1048576 bytes")]
    poses = tmp_path / "in.csv"
    poses.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n")
    for path, words in cases:
        with pytest.raises(stewart.ParameterError, match=words):
            stewart.Platform.from_file(path)
        r = solve("--platform", path, poses, tmp_path / "out.csv")
        assert r.returncode == 2 and words in r.stderr


def decimal_comma_locale(tmp_path):
    """LC_NUMERIC = de_DE.UTF-8 (decimal comma), built here by localedef if the system has none."""
    import locale
    import os
    try:
        return locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")
    except locale.Error:
        pass
    subprocess.run(["localedef", "-c", "-i", "de_DE", "-f", "UTF-8", str(tmp_path / "de_DE.UTF-8")],
                   capture_output=True, timeout=120)
    os.environ["LOCPATH"] = str(tmp_path)
    return locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")


def test_platform_files_read_the_same_under_a_decimal_comma(tmp_path, monkeypatch):
    """A Python program that sets a German numeric locale (as desktop programs do) reads every
    shipped file, and a file of decimals, as under "C": 12.5 stays 12.5, not 12."""
    import locale
    monkeypatch.delenv("LOCPATH", raising=False)
    in_c = {name: stewart.params.read_platform_file(PLATFORMS / f"{name}.json") for name in NAMES}
    path = tmp_path / "decimals.json"
    path.write_text('{"payload_mass": 12.5, "gravity[3]": -9.81, "home_height": "512.5 mm"}')
    try:
        decimal_comma_locale(tmp_path)
        assert locale.localeconv()["decimal_point"] == ","
        under_de = {name: stewart.params.read_platform_file(PLATFORMS / f"{name}.json") for name in NAMES}
        decimals = stewart.params.read_platform_file(path)
        legs = stewart.Platform.from_file(PLATFORMS / "thesis.json").inverse(np.array([[0, 0, 0.5, 0, 0, 0]]))
    finally:
        locale.setlocale(locale.LC_NUMERIC, "C")
    assert under_de == in_c
    assert decimals == {"payload_mass": 12.5, "gravity": [0.0, 0.0, -9.81], "home_height": 0.5125}
    assert legs.status[0] == 0


def shifted_origin(name, c):
    """The shipped file's machine with the base frame's origin moved up by c (base joints and
    home_height lowered by c): the same machine."""
    data = json.loads((PLATFORMS / f"{name}.json").read_text())
    base = np.array(data["base_joint"]).reshape(6, 3)
    base[:, 2] -= c
    return dict(data, base_joint=base.ravel().tolist(), home_height=data["home_height"] - c)


@pytest.mark.parametrize("c", [-0.3, 0.2])
def test_a_shifted_base_origin_gives_the_same_lengths(tmp_path, c):
    """The base origin below the base (c < 0) or between the plates: lengths at the same
    physical poses equal to rounding, forward kinematics round-trips."""
    path = tmp_path / "shifted.json"
    path.write_text(json.dumps(shifted_origin("paired_hexapod", c)))
    data = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    poses = np.array([[0.001, -0.002, data["home_height"] + 0.003, 0.01, -0.02, 0.015]])
    moved = poses - np.array([0, 0, c, 0, 0, 0])
    a = stewart.Platform.from_file(PLATFORMS / "paired_hexapod.json").inverse(poses, fidelity="full")
    b = stewart.Platform.from_file(path).inverse(moved, fidelity="full")
    assert np.max(np.abs(a.length - b.length)) < 1e-15
    assert np.max(np.abs(a.force - b.force)) < 1e-9 * np.max(np.abs(a.force))
    back = stewart.Platform.from_file(path).forward(b.length)
    assert np.max(np.abs(back.pose - moved)) < 1e-12


def test_frames_anywhere_give_the_same_machine(tmp_path):
    """The base origin 0.1 m above the platform's joints and the platform frame's origin 0.3 m
    above them (home_height stays > 0): the same machine, so the same lengths and full-model
    forces at the same physical poses (p' = p + R (0, 0, s) - (0, 0, c)), and forward kinematics
    round-trips. Every use of home_height (the home pose, the model's length unit, the branch
    sides, the limits' neutral axes) sees only where the joints are."""
    data = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    c, s = data["home_height"] + 0.1, 0.3
    moved = shifted_origin("paired_hexapod", c)
    plate = np.array(data["platform_joint"]).reshape(6, 3)
    plate[:, 2] -= s
    moved.update(platform_joint=plate.ravel().tolist(), home_height=moved["home_height"] + s,
                 platform_com=[0.0, 0.0, -s])
    assert 0 < moved["home_height"] < s
    path = tmp_path / "frames.json"
    path.write_text(json.dumps(moved))
    rng = np.random.default_rng(33)
    poses = np.column_stack([rng.uniform(-0.005, 0.005, (8, 2)), data["home_height"] + rng.uniform(-0.005, 0.005, 8),
                             rng.uniform(-0.02, 0.02, (8, 3))])
    there = np.array([np.r_[q[:3] + rotation(*q[3:]) @ [0, 0, s] - [0, 0, c], q[3:]] for q in poses])
    a = stewart.Platform.from_file(PLATFORMS / "paired_hexapod.json").inverse(poses, fidelity="full")
    b = stewart.Platform.from_file(path).inverse(there, fidelity="full")
    assert np.all(b.status == 0)
    assert np.max(np.abs(a.length - b.length)) < 1e-15
    assert np.max(np.abs(a.force - b.force)) < 1e-9 * np.max(np.abs(a.force))
    back = stewart.Platform.from_file(path).forward(b.length)
    assert np.max(np.abs(back.pose - there)) < 1e-12


def test_a_base_origin_above_the_top_plane_gives_the_same_lengths(tmp_path):
    data = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    c = data["home_height"] + 0.1  # the origin 0.1 m above the platform's joints: home_height < 0
    path = tmp_path / "above.json"
    path.write_text(json.dumps(shifted_origin("paired_hexapod", c)))
    poses = np.array([[0.001, -0.002, data["home_height"] + 0.003, 0.01, -0.02, 0.015]])
    a = stewart.Platform.from_file(PLATFORMS / "paired_hexapod.json").inverse(poses, fidelity="full")
    b = stewart.Platform.from_file(path).inverse(poses - np.array([0, 0, c, 0, 0, 0]), fidelity="full")
    assert np.max(np.abs(a.length - b.length)) < 1e-15


def test_the_documented_file_in_mm_is_the_documented_file_in_m(tmp_path):
    """docs/geometry.md shows one machine in m and again in mm and deg with its strokes as 285 mm
    +- 50 mm: the library reads the same parameters (and the joint limit as 40 degrees), the
    strokes to rounding (285 mm - 50 mm is 0.285 - 0.05 in doubles, not the double of 0.235)."""
    import re
    page = (ROOT / "docs" / "geometry.md").read_text()
    section = page[page.index("## 3. Platform files"):page.index("### Shipped platforms")]
    si_text, mm_text = re.findall(r"```json\n(.*?)```", section, re.S)
    (tmp_path / "si.json").write_text(si_text)
    (tmp_path / "mm.json").write_text(mm_text)
    si = stewart.params.read_platform_file(tmp_path / "si.json")
    mm = stewart.params.read_platform_file(tmp_path / "mm.json")
    assert mm.pop("base_joint_limit") == 40 * (math.pi / 180)
    for stroke in ("stroke_min", "stroke_max"):
        assert np.max(np.abs(np.subtract(mm.pop(stroke), si.pop(stroke)))) <= 1e-16
    assert mm == si
