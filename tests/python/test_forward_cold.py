"""Forward kinematics of measured lengths that are not a trajectory (Platform.forward(cold=True),
`stewart-solve --forward --cold`): every row solved on its own from home, so independent poses
far apart are all found. The lengths come from the closed form |p + R b_k - a_k| written here."""
import json
import subprocess

import numpy as np
import pytest

import stewart
from test_platform_files import rotation

MACHINES = sorted(stewart.platform_files())
_TABLE = {p["name"]: p["defaults"] for p in stewart.parameters()}
BASE = np.reshape(_TABLE["base_joint"], (6, 3))  # the thesis platform's joints
TOP = np.reshape(_TABLE["platform_joint"], (6, 3))


def independent_poses(platform, n, seed=7):
    """n poses drawn across the axis ranges from home, each within every limit (the box shrunk
    until at least a tenth of its draws are)."""
    report = platform.check()
    ends = report.ranges.ends[0]
    rng = np.random.default_rng(seed)
    fraction = 0.8
    for _ in range(20):
        q = report.home + fraction * rng.uniform(ends[:, 0] - report.home,
                                                 ends[:, 1] - report.home, (10 * n, 6))
        inside = q[platform.limits(q).within]
        if len(inside) >= n:
            return inside[:n]
        fraction /= 2
    raise AssertionError("no poses within every limit near home")


@pytest.mark.parametrize("name", MACHINES)
def test_cold_rows_each_solve_on_their_own(name):
    path = stewart.platform_files()[name]
    platform = stewart.Platform.from_file(path)
    poses = independent_poses(platform, 100)
    data = json.loads(path.read_text())
    framed = any(k in data for k in ("tool_frame", "user_frame", "length_offset"))
    if "base_joint" in data and not framed and all(isinstance(v, (int, float)) for v in data["base_joint"]):
        base = np.reshape(data["base_joint"], (6, 3))
        top = np.reshape(data["platform_joint"], (6, 3))
        lengths = np.array([np.linalg.norm(q[:3] + top @ rotation(*q[3:]).T - base, axis=1)
                            for q in poses])
    else:  # frames or units: the library's lengths (the round trip still checks forward)
        lengths = platform.inverse(poses, fidelity="kinematic").length
    # the poses the solver takes as the working assembly mode when started at the pose itself
    # (the branch checks may refuse a pose within the limits: its own business, not cold's)
    working = platform.forward(lengths, guess=poses, cold=True).status == 0
    assert working.sum() >= 80
    poses, lengths = poses[working], lengths[working]
    cold = platform.forward(lengths, cold=True)
    assert np.all(cold.status == 0), cold.messages
    scale = max(1.0, np.abs(poses[:, :3]).max())
    assert np.abs(cold.pose - poses).max() < 1e-9 * scale
    assert np.all((cold.start == 0) | (cold.start == 3))  # from home, or walked from home


def test_cold_rows_take_their_own_guess():
    platform = stewart.Platform.from_file(stewart.platform_files()["paired_hexapod"])
    poses = independent_poses(platform, 5)
    lengths = platform.inverse(poses, fidelity="kinematic").length
    guessed = platform.forward(lengths, guess=poses + 1e-4, cold=True)
    assert np.all(guessed.status == 0) and np.all(guessed.start == 1)
    np.testing.assert_allclose(guessed.pose, poses, atol=1e-12)
    with pytest.raises(ValueError, match="cold"):
        platform.forward(lengths, t=np.arange(5.0), cold=True)


def test_the_command_line_solves_cold(tmp_path):
    from fmu_support import stewart_solve_path
    path = stewart.platform_files()["paired_hexapod"]
    platform = stewart.Platform.from_file(path)
    poses = independent_poses(platform, 30, seed=3)
    lengths = platform.inverse(poses, fidelity="kinematic").length
    infile, outfile = tmp_path / "in.csv", tmp_path / "out.csv"
    infile.write_text("t," + ",".join(f"L{k}" for k in range(1, 7)) + "\n" +
                      "".join(f"{i}," + ",".join(repr(float(v)) for v in row) + "\n"
                              for i, row in enumerate(lengths)))
    result = subprocess.run([str(stewart_solve_path()), "--forward", "--cold", "--platform",
                             str(path), str(infile), str(outfile)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    out = np.genfromtxt(outfile, delimiter=",", names=True)
    found = np.column_stack([out[c] for c in ("x", "y", "z", "roll", "pitch", "yaw")])
    np.testing.assert_allclose(found, poses, atol=1e-9)
    python = platform.forward(lengths, cold=True)
    np.testing.assert_array_equal(found, python.pose)  # the same solves, bit for bit


def test_a_cold_row_refused_from_home_is_walked_to_from_home():
    """Far from home (joint limits and strokes opened wide) Newton from home can land on another
    assembly mode; the cold solve then walks the lengths from home's, and every row found so is
    the true pose (position, and the rotation matrix: the angles may be another triple), among
    the poses the solver takes as the working mode when started at the pose itself."""
    platform = stewart.Platform(base_joint_limit=3.1, platform_joint_limit=3.1, stroke_min=0.01,
                                stroke_max=5.0)
    rng = np.random.default_rng(1)
    q = np.array([0, 0, 0.5, 0, 0, 0]) + rng.uniform(-1, 1, (20000, 6)) * [0.5, 0.5, 0.4, 1.2, 1.2, 2.0]
    q = q[platform.limits(q).within]
    lengths = np.array([np.linalg.norm(p[:3] + TOP @ rotation(*p[3:]).T - BASE, axis=1) for p in q])
    working = platform.forward(lengths, guess=q, cold=True).status == 0
    q, lengths = q[working], lengths[working]
    cold = platform.forward(lengths, cold=True)
    walked = (cold.status == 0) & (cold.start == 3)
    assert walked.sum() >= 10
    for found, true in zip(cold.pose[walked], q[walked]):
        assert np.abs(found[:3] - true[:3]).max() < 1e-9
        assert np.abs(rotation(*found[3:]) - rotation(*true[3:])).max() < 1e-9
