"""scripts/calibrate.py: a synthetic machine's measurements in, a platform file out that the
Python package and stewart-solve take and that reproduces the machine's readings (this file's
closed form); bad CSVs and platform files named by line and column, with nothing written."""
import json
import subprocess
import sys

import numpy as np
import pytest

import stewart

import calibration_truth as truth
from conftest import ROOT

SCRIPT = ROOT / "scripts" / "calibrate.py"
HEADER = "x,y,z,roll,pitch,yaw,L1,L2,L3,L4,L5,L6"


def run(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *map(str, args)], capture_output=True,
                          text=True, timeout=300)


def run_here(capsys, *args):
    """The script's main in this process (quicker than a new interpreter): (status, stderr)."""
    import calibrate  # scripts/ is on sys.path (conftest.py)
    status = calibrate.main([str(a) for a in args])
    return status, capsys.readouterr().err


@pytest.fixture(scope="module")
def machine():
    rng = np.random.default_rng(21)
    a, b = truth.thesis_joints()
    return {"base_joint": a + rng.uniform(-1e-3, 1e-3, (6, 3)),
            "platform_joint": b + rng.uniform(-1e-3, 1e-3, (6, 3)),
            "length_offset": rng.uniform(-2e-3, 2e-3, 6), "tool_frame": np.zeros(6),
            "user_frame": np.zeros(6)}


@pytest.fixture(scope="module")
def files(tmp_path_factory, machine):
    folder = tmp_path_factory.mktemp("calibrate")
    nominal = folder / "nominal.json"
    nominal.write_text(json.dumps({"payload_mass": 20.0}))
    poses = stewart.calibration_poses(stewart.Platform(payload_mass=20.0), 30)
    rng = np.random.default_rng(22)
    readings = truth.readings(machine, poses) + rng.normal(0, 1e-6, (30, 6))
    measured = folder / "measured.csv"
    rows = [HEADER] + [",".join(repr(float(v)) for v in row)
                       for row in np.hstack([truth.measured(poses, rng), readings])]
    measured.write_text("\n".join(rows) + "\n")
    return folder, nominal, measured


def test_writes_a_platform_file_of_the_machine(files, machine, build_dir):
    folder, nominal, measured = files
    out = folder / "calibrated.json"
    done = run(nominal, measured, out)
    assert done.returncode == 0, done.stderr
    params = json.loads(out.read_text())
    assert params["geometry"] == 1 and params["payload_mass"] == 20.0
    assert len(params["base_joint"]) == 18 and len(params["length_offset"]) == 6
    report = (folder / "calibrated_report.txt").read_text()
    assert "condition number" in report and "base_joint[1]" in report
    assert (folder / "calibrated_report.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The file is a Platform whose readings are the machine's (this file's closed form) to
    # the tracker's noise level, at poses it was not measured at.
    held_out = truth.random_poses(np.random.default_rng(23), 10)
    calibrated = {"base_joint": np.reshape(params["base_joint"], (6, 3)),
                  "platform_joint": np.reshape(params["platform_joint"], (6, 3)),
                  "length_offset": np.array(params["length_offset"]),
                  "tool_frame": np.array(params["tool_frame"]),
                  "user_frame": np.array(params["user_frame"])}
    error = truth.readings(calibrated, held_out) - truth.readings(machine, held_out)
    assert np.max(np.abs(error)) < 20e-6
    platform = stewart.Platform(**params)
    assert platform.inverse(held_out).status.tolist() == [0] * 10
    # stewart-solve takes the file as is: its lengths (sensor readings) are the calibrated
    # machine's by this file's closed form.
    poses_csv = folder / "poses.csv"
    poses_csv.write_text("t,x,y,z,roll,pitch,yaw\n0,0.01,0,0.5,0,0.02,0\n")
    solved = subprocess.run([str(build_dir / "stewart-solve"), "--platform", str(out),
                             str(poses_csv), str(folder / "solved.csv")],
                            capture_output=True, text=True)
    assert solved.returncode == 0, solved.stderr
    data = np.genfromtxt(folder / "solved.csv", delimiter=",", names=True)
    lengths = [float(data[f"L{k}"]) for k in range(1, 7)]
    np.testing.assert_allclose(lengths, truth.readings(calibrated, [[0.01, 0, 0.5, 0, 0.02, 0]])[0],
                               rtol=0, atol=1e-12)


BAD_CSVS = [
    (HEADER + "\n0,0,0.5,0,abc,0,0.5,0.5,0.5,0.5,0.5,0.5\n",
     "line 2 column 5 (pitch): 'abc' is not a number"),
    (HEADER + "\n0,0,0.5,0,0,0,0.5,0.5,0.5,0.5,0.5\n", "line 2: 11 values, the header has 12"),
    (HEADER + "\n0,0,0.5,0,0,0,0.5,0.5,nan,0.5,0.5,0.5\n",
     "line 2 column 9 (L3): nan is not finite"),
    ("x,y,z,roll,pitch,yaw,L1,L2,L3,L4,L5,L7\n", "line 1 column 12: unknown column 'L7'"),
    ("x,y,z,roll,pitch,yaw,L1,L2,L3,L4,L5\n", "line 1: missing column(s) L6"),
    ("x,y,z,roll,pitch,yaw,L1,L2,L3,L4,L5,L6,L1\n", "line 1 column 13: column 'L1' appears twice"),
    ("# only a comment\n", "no header"),
    (HEADER + "\n", "no measurement after the header (line 1)"),
]


@pytest.mark.parametrize("content, message", BAD_CSVS)
def test_bad_csvs_are_named_and_nothing_is_written(tmp_path, capsys, files, content, message):
    _, nominal, _ = files
    bad = tmp_path / "bad.csv"
    bad.write_text(content)
    status, stderr = run_here(capsys, nominal, bad, tmp_path / "out.json")
    assert status == 1
    assert message in stderr and str(bad) in stderr
    assert list(tmp_path.iterdir()) == [bad]


@pytest.mark.parametrize("content, message", [
    ('{"payload_mass": 20,\n "base_radius": }', "line 2 column 17"),
    ('{"payload_mas": 20}', "payload_mas"),
    ('[1, 2]', ""),
])
def test_bad_platform_files_are_named_and_nothing_is_written(tmp_path, capsys, files, content,
                                                             message):
    _, _, measured = files
    bad = tmp_path / "bad.json"
    bad.write_text(content)
    status, stderr = run_here(capsys, bad, measured, tmp_path / "out.json")
    assert status == 1
    assert str(bad) in stderr and message in stderr
    assert list(tmp_path.iterdir()) == [bad]


def write_csv(path, poses, readings, prefix=""):
    rows = [HEADER] + [",".join(repr(float(v)) for v in row)
                       for row in np.hstack([poses, readings])]
    path.write_text(prefix + "\n".join(rows) + "\n", encoding="utf-8")
    return path


def test_one_orientation_is_left_to_the_prior_and_max_std_refuses_it(tmp_path, files, machine):
    _, nominal, _ = files
    poses = truth.random_poses(np.random.default_rng(5), 20)
    poses[:, 3:] = 0.05
    measured = write_csv(tmp_path / "one_orientation.csv", poses, truth.readings(machine, poses))
    done = run(nominal, measured, tmp_path / "out.json", "--max-std", "0.1mm")
    assert done.returncode == 1
    assert "cannot identify the geometry to max_std = 0.0001" in done.stderr
    assert "base_joint[1..18]" in done.stderr
    assert list(tmp_path.iterdir()) == [measured]
    done = run(nominal, measured, tmp_path / "out.json")  # the prior keeps the split nominal
    assert done.returncode == 0, done.stderr
    assert "combination(s) set by the prior" in done.stdout
    report = (tmp_path / "out_report.txt").read_text()
    assert "set by the prior: " in report and "predicted pose error inside the workspace" in report


def test_a_byte_order_mark_is_read_past(tmp_path, capsys, files, machine):
    _, nominal, measured = files
    with_bom = tmp_path / "excel.csv"
    with_bom.write_bytes(b"\xef\xbb\xbf" + measured.read_bytes())
    status, stderr = run_here(capsys, nominal, with_bom, tmp_path / "out.json")
    assert status == 0, stderr
    assert json.loads((tmp_path / "out.json").read_text())["geometry"] == 1


@pytest.mark.parametrize("case, message", [
    ("report folder missing", "does not exist"),
    ("out is a folder", "is a folder"),
    ("angle noise 1e300", "angle_noise = 1e+300 must be 0 or from 1e-12 to 1"),
    ("readings in mm", "are they in millimetres?"),
    ("one reading +1 m", "pose row 3, leg 5"),
])
def test_refusals_name_the_cause_and_nothing_is_written(tmp_path, capsys, files, case,
                                                        message):
    _, nominal, measured = files
    out = tmp_path / "out.json"
    data = np.genfromtxt(measured, delimiter=",", skip_header=1)
    args = []
    if case == "report folder missing":
        args = ["--report", str(tmp_path / "missing" / "report")]
    elif case == "out is a folder":
        out.mkdir()
    elif case == "angle noise 1e300":
        args = ["--angle-noise", "1e300"]
    elif case == "readings in mm":
        measured = write_csv(tmp_path / "mm.csv", data[:, :6], data[:, 6:] * 1e3)
    else:
        data[3, 10] += 1.0
        measured = write_csv(tmp_path / "outlier.csv", data[:, :6], data[:, 6:])
    before = sorted(tmp_path.rglob("*"))
    status, stderr = run_here(capsys, nominal, measured, out, *args)
    assert status == 1
    assert message in stderr and "Traceback" not in stderr
    if case == "one reading +1 m":
        assert "is line 5 of" in stderr  # the header is line 1
    assert sorted(tmp_path.rglob("*")) == before


def test_a_million_rows_are_refused_with_a_message(tmp_path, files):
    _, nominal, _ = files
    big = tmp_path / "big.csv"
    with open(big, "w") as f:
        f.write(HEADER + "\n")
        f.write("0,0,0.5,0,0,0,0.5,0.5,0.5,0.5,0.5,0.5\n" * 10 ** 6)
    done = run(nominal, big, tmp_path / "out.json")
    assert done.returncode == 1
    assert "1000000 measurement rows; a calibration takes at most 20000" in done.stderr
    assert "Traceback" not in done.stderr


@pytest.mark.parametrize("path, message", [("/dev/zero", "not a regular file"),
                                           ("missing.csv", "cannot be read")])
def test_a_csv_that_is_no_file_is_refused(tmp_path, capsys, files, path, message):
    _, nominal, _ = files
    status, stderr = run_here(capsys, nominal, path, tmp_path / "out.json")
    assert status == 1 and message in stderr
    assert list(tmp_path.iterdir()) == []


def test_identify_and_tolerances_with_units(tmp_path, capsys, files):
    _, nominal, measured = files
    out = tmp_path / "offsets.json"
    status, stderr = run_here(capsys, nominal, measured, out, "--identify", "offsets",
                              "--offset-tolerance", "3mm", "--position-noise", "10um",
                              "--angle-noise", "20urad")
    assert status == 0, stderr
    report = (tmp_path / "offsets_report.txt").read_text()
    assert "identify: offsets" in report and "length_offset[6]" in report
    assert "base_joint[1] " not in report
    params = json.loads(out.read_text())
    np.testing.assert_array_equal(params["base_joint"],
                                  np.reshape(truth.thesis_joints()[0], -1))
    assert "3.0000e-3" in report  # the tolerance given in mm, reported in m
    with pytest.raises(SystemExit):
        run_here(capsys, nominal, measured, out, "--joint-tolerance", "0.5furlong")
    assert "'0.5furlong' is not a length" in capsys.readouterr().err


def test_the_default_command_line_is_the_default_calibration(tmp_path, capsys):
    """On the far-pivot precision hexapod (the machine test_calibration_machines.py judges
    against a regularised fit), the command line with no option writes the geometry
    stewart.calibrate gives with its defaults."""
    nominal_params = truth.precision_hexapod()
    nominal = tmp_path / "precision.json"
    nominal.write_text(json.dumps(nominal_params))
    platform = stewart.Platform(**nominal_params)
    poses = stewart.calibration_poses(platform, 30, candidates=500)
    rng = np.random.default_rng(31)
    a, b = np.reshape(nominal_params["base_joint"], (6, 3)), np.reshape(
        nominal_params["platform_joint"], (6, 3))
    built = {"base_joint": a + rng.uniform(-1e-3, 1e-3, (6, 3)),
             "platform_joint": b + rng.uniform(-1e-3, 1e-3, (6, 3)),
             "length_offset": rng.uniform(-1e-3, 1e-3, 6),
             "tool_frame": np.array(nominal_params["tool_frame"]), "user_frame": np.zeros(6)}
    measured_poses = truth.measured(poses, rng)
    readings = truth.readings(built, poses) + rng.normal(0, 1e-6, (30, 6))
    measured = write_csv(tmp_path / "measured.csv", measured_poses, readings)
    status, stderr = run_here(capsys, nominal, measured, tmp_path / "out.json")
    assert status == 0, stderr
    written = json.loads((tmp_path / "out.json").read_text())
    expected = stewart.calibrate(platform, measured_poses, readings).parameters
    for group in ("base_joint", "platform_joint", "length_offset"):
        np.testing.assert_allclose(written[group], expected[group], rtol=0, atol=1e-12)
