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

from fmu_support import OK, Unit, F, L, stewart_solve_path

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATFORMS = ROOT / "platforms"
NAMES = ("thesis", "paired_hexapod", "genhexkins", "non_planar")


def joints(name):
    data = json.loads((PLATFORMS / f"{name}.json").read_text())
    return (np.array(data["base_joint"]).reshape(6, 3), np.array(data["platform_joint"]).reshape(6, 3),
            data["home_height"])


def rotation(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


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


@pytest.mark.parametrize("text,words", BAD_FILES)
def test_bad_files_are_refused_naming_the_field(tmp_path, solve, text, words):
    path = tmp_path / "bad.json"
    path.write_text(text)
    with pytest.raises(stewart.ParameterError) as e:
        stewart.Platform.from_file(path)
    for w in words:
        assert w in str(e.value)
    assert str(path) in str(e.value)
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
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]])


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
    pose = [0.002, -0.001, data["home_height"] + 0.003, 0.01, -0.02, 0.015]
    expected = stewart.Platform.from_file(PLATFORMS / "paired_hexapod.json").inverse(
        np.array([pose]), fidelity="full")
    u = Unit(version)
    try:
        at_pose = dict(zip(("x", "y", "z", "roll", "pitch", "yaw"), pose))
        assert u.init(**values, **at_pose, derivatives=1) == OK, u.messages
        assert u.do_step(0.0, 0.01) == OK, u.messages
        assert np.array_equal(u.get_reals(L), expected.length[0])
        assert np.max(np.abs(u.get_reals(F) - expected.force[0])) < 1e-9 * np.max(np.abs(expected.force))
    finally:
        u.free()
