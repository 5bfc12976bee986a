"""stewart-solve --forward: the inverse output read back to the scene's poses (scenes.py computes
them independently, with exact derivatives), the columns, and the errors."""
import csv
import math

import numpy as np
import pytest

import scenes

POSE = list(scenes.POSE)


def read(path):
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        numeric = [i for i, h in enumerate(header) if h != "status"]  # status: a class name
        return ([header[i] for i in numeric],
                np.array([[float(row[i]) for i in numeric] for row in reader]))


def lengths_csv(solve, tmp_path, scene, dt):
    pose_csv, legs_csv = tmp_path / f"{scene}_pose.csv", tmp_path / f"{scene}_legs.csv"
    scenes.write_pose_csv(scene, pose_csv, dt=dt)
    result = solve("--fidelity", "kinematic", pose_csv, legs_csv)
    assert result.returncode == 0, result.stderr
    return legs_csv


@pytest.mark.parametrize("scene", ["combined", "heave", "roll", "pitch", "yaw"])
def test_round_trip_through_the_inverse_output(solve, tmp_path, scene):
    legs_csv = lengths_csv(solve, tmp_path, scene, dt=0.001)
    out_csv = tmp_path / "forward.csv"
    result = solve("--forward", legs_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    assert header == (["t"] + POSE + list(scenes.DOT) + list(scenes.DDOT)
                      + ["iterations", "residual", "condition"])
    q, qd, qdd = scenes.pose(scenes.load(scene), data[:, 0])
    np.testing.assert_allclose(data[:, 1:7], q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(data[:, 7:13], qd, rtol=0, atol=1e-9 * np.abs(qd).max())
    np.testing.assert_allclose(data[:, 13:19], qdd, rtol=0, atol=1e-9 * np.abs(qdd).max())
    assert np.all(data[:, header.index("residual")] <= 1e-12)


def test_lengths_only_give_the_pose_only(solve, tmp_path):
    legs_csv = lengths_csv(solve, tmp_path, "yaw", dt=0.01)
    header, data = read(legs_csv)
    only = tmp_path / "only.csv"
    np.savetxt(only, data[:, :7], delimiter=",", header="t,L1,L2,L3,L4,L5,L6", comments="",
               fmt="%.17g")
    out_csv = tmp_path / "forward.csv"
    result = solve("--forward", only, out_csv)
    assert result.returncode == 0, result.stderr
    header, out = read(out_csv)
    assert header == ["t"] + POSE + ["iterations", "residual", "condition"]
    q, _, _ = scenes.pose(scenes.load("yaw"), out[:, 0])
    np.testing.assert_allclose(out[:, 1:7], q, rtol=0, atol=1e-12)


def write_rows(path, rows):
    path.write_text("t,L1,L2,L3,L4,L5,L6\n" + "".join(",".join(r) + "\n" for r in rows))


# Every leg at home: sqrt(z^2 + chord^2), chord = 2 r sin 15 deg between base and platform point.
HOME = [repr(math.sqrt(0.5 ** 2 + (2 * 0.5 * math.sin(math.radians(15))) ** 2))] * 6


@pytest.mark.parametrize("rows, line, leg", [
    # a value that is not a number
    ([["0"] + HOME, ["0.1"] + HOME, ["0.2"] + HOME[:2] + ["nan"] + HOME[3:]], 4, 3),
    # lengths no pose has: leg 5 three metres long, the others at home
    ([["0"] + HOME, ["0.1"] + HOME[:4] + ["3.0"] + HOME[5:]], 3, 5),
])
def test_bad_rows_name_line_and_leg_and_write_nothing(solve, tmp_path, rows, line, leg):
    in_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    write_rows(in_csv, rows)
    result = solve("--forward", in_csv, out_csv)
    assert result.returncode == 1
    assert f"line {line}" in result.stderr and f"leg {leg}" in result.stderr, result.stderr
    assert not out_csv.exists()


def test_guess_near_the_mirror_is_reported_not_returned(solve, tmp_path):
    in_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    write_rows(in_csv, [["0"] + HOME])
    result = solve("--forward", "--guess", "0,0,-0.45,0,0,0", in_csv, out_csv)
    assert result.returncode == 1
    assert "line 2" in result.stderr and "below the base" in result.stderr, result.stderr
    assert not out_csv.exists()
    result = solve("--forward", "--guess", "0.01,0,0.45,0,0,0.02", in_csv, out_csv)
    assert result.returncode == 0, result.stderr
    _, out = read(out_csv)
    np.testing.assert_allclose(out[0, 1:7], [0, 0, 0.5, 0, 0, 0], rtol=0, atol=1e-12)
