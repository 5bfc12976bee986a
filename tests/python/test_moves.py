"""stewart.move (docs/moves.md) checked independently of the planner: the leg lengths of every
sample from a closed form written here (T_base_platform = T(user_frame) T(q) T(tool_frame)^-1,
L_k = |p + R b_k - a_k|), their finite differences against the leg limits, the geometric limits
at every sample, the end pose and rest, the pose rates against differences of the poses, the
line's geometry against scipy's slerp, and the duration against a time-optimal parametrisation
computed here by the classical forward/backward passes on a fine phase-plane grid.

Slack of the difference checks: a central difference is a mean of the continuous derivative over
[t - dt, t + dt] (weighted, for the second difference), so it never exceeds the derivative's
bound; only rounding adds to it. The closed form's lengths are good to DELTA_L = 16 eps max L,
so a speed difference can be off by DELTA_L / dt and an acceleration difference by
4 DELTA_L / dt^2, on top of the relative 1e-6 slack."""
import json
import math
import re
import subprocess
import sys

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import stewart
from conftest import ROOT
from stewart.limits import class_name

FILES = stewart.platform_files()
EPS = np.finfo(float).eps
DT = 0.001


def rotation(angles):
    """R = Rz(yaw) Ry(pitch) Rx(roll) for (n, 3) angles (every shipped file has order 0)."""
    return Rotation.from_euler("ZYX", np.asarray(angles)[:, ::-1]).as_matrix()


def frames(data):
    tool = np.array(data.get("tool_frame", [0.0] * 6))
    user = np.array(data.get("user_frame", [0.0] * 6))
    return tool, user


def lengths_of(data, p, R):
    """Closed-form leg lengths (n, 6) of tool positions p (n, 3) and rotations R (n, 3, 3)."""
    assert data.get("rotation_order", 0) == 0 and data.get("frame_convention", 0) == 0
    assert "length_offset" not in data, "extend the closed form"
    base = np.array(data["base_joint"]).reshape(6, 3)
    plate = np.array(data["platform_joint"]).reshape(6, 3)
    tool, user = frames(data)
    Rt, Ru = rotation(tool[None, 3:])[0], rotation(user[None, 3:])[0]
    R_plat = Ru @ R @ Rt.T
    p_plat = user[:3] + (p - (R @ Rt.T) @ tool[:3]) @ Ru.T
    legs = p_plat[:, None, :] + np.einsum("nij,kj->nki", R_plat, plate) - base
    return np.linalg.norm(legs, axis=2)


def lengths(data, poses):
    return lengths_of(data, poses[:, :3], rotation(poses[:, 3:]))


def load(name):
    """The shipped platform; genhexkins' legs meet in pairs at shared joints, so its home is an
    interference at any leg_diameter: its check is off (leg_diameter 0)."""
    extra = {"leg_diameter": 0.0} if name == "genhexkins" else {}
    return (stewart.Platform.from_file(FILES[name], **extra),
            json.loads(FILES[name].read_text()))


def leg_limits(data):
    """Leg limits in proportion to the machine: half the shortest stroke per second, twice it
    per second squared."""
    span = float(np.min(np.array(data["stroke_max"]) - np.array(data["stroke_min"])))
    return 0.5 * span, 2.0 * span


def goal_of(platform, home, kind):
    """A move from home over 15 % of every axis range at once (the sides alternate)."""
    ends = platform.axis_ranges(home)[0]
    side = np.array([1, 0, 1, 0, 1, 1]) if kind == "point" else np.array([0, 1, 0, 1, 0, 1])
    return home + 0.15 * (ends[np.arange(6), side] - home)


def test_closed_form_is_the_library_s():
    for name in FILES:
        platform, data = load(name)
        home = platform.check().home
        poses = home + np.array([[0, 0, 0, 0, 0, 0], [1e-3, -2e-3, 1e-3, 0.01, -0.02, 0.03]])
        expected = platform.inverse(poses, fidelity="kinematic").length
        assert np.max(np.abs(lengths(data, poses) - expected)) < 1e-12, name


@pytest.mark.parametrize("kind", ["point", "line"])
@pytest.mark.parametrize("name", sorted(FILES))
def test_every_move_keeps_every_limit(name, kind):
    platform, data = load(name)
    home = platform.check().home
    goal = goal_of(platform, home, kind)
    speed, accel = leg_limits(data)
    m = stewart.move(platform, home, goal, kind, leg_speed_max=speed, leg_accel_max=accel)
    assert np.max(np.abs(m.pose[-1] - goal)) <= 1e-12 and np.array_equal(m.pose[0], home)
    assert not m.pose_rate[0].any() and not m.pose_rate[-1].any()
    assert np.allclose(np.diff(m.t), DT, rtol=0, atol=1e-12) and m.duration == m.t[-1]
    L = lengths(data, m.pose)
    delta_L = 16 * EPS * np.max(L)
    v = (L[2:] - L[:-2]) / (2 * DT)
    a = (L[2:] - 2 * L[1:-1] + L[:-2]) / DT ** 2
    assert np.max(np.abs(v)) <= speed * (1 + 1e-6) + delta_L / DT
    assert np.max(np.abs(a)) <= accel * (1 + 1e-6) + 4 * delta_L / DT ** 2
    # Time-optimal: a limit is met somewhere (else the move could be faster).
    assert np.max(np.abs(v)) > 0.99 * speed or np.max(np.abs(a)) > 0.99 * accel
    assert np.all(platform.limits(m.pose).within)
    # The rates are the poses' derivatives: a central difference is off by at most
    # dt / 2 max |pose_accel| (a mean of the rate over two samples), plus rounding.
    diff = (m.pose[2:] - m.pose[:-2]) / (2 * DT) - m.pose_rate[1:-1]
    bound = 0.5 * DT * np.max(np.abs(m.pose_accel), axis=0) * 1.01 + 4 * EPS * 4 / DT
    assert np.all(np.abs(diff) <= bound)
    # Away from the few samples where the path acceleration switches, far closer: dt^2/6 times
    # the rate's second derivative.
    tight = np.abs(diff) > 1e-5 * np.max(np.abs(m.pose_rate), axis=0) + 4 * EPS * 4 / DT
    assert np.count_nonzero(tight.any(axis=1)) <= 0.02 * len(m.t)


def test_the_accelerations_are_the_rates_derivatives():
    """Between samples the rate changes by the trapezoid of the accelerations, but where the
    path acceleration switches (a few samples): there by at most dt times the jump."""
    platform, data = load("thesis")
    home = platform.check().home
    m = stewart.move(platform, home, goal_of(platform, home, "line"), "line",
                     leg_speed_max=0.1, leg_accel_max=0.4)
    step = np.diff(m.pose_rate, axis=0)
    trapezoid = 0.5 * DT * (m.pose_accel[1:] + m.pose_accel[:-1])
    scale = DT * np.max(np.abs(m.pose_accel), axis=0)
    off = np.abs(step - trapezoid) > 1e-3 * scale
    assert np.count_nonzero(off.any(axis=1)) <= 8
    assert np.all(np.abs(step - trapezoid) <= 1.01 * scale)


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_line_is_a_line_with_a_slerp(name):
    platform, data = load(name)
    home = platform.check().home
    goal = goal_of(platform, home, "line")
    speed, accel = leg_limits(data)
    m = stewart.move(platform, home, goal, "line", leg_speed_max=speed, leg_accel_max=accel)
    along = (m.pose[:, :3] - home[:3]) @ (goal[:3] - home[:3]) / np.sum((goal[:3] - home[:3]) ** 2)
    assert np.max(np.abs(m.pose[:, :3] - home[:3] - np.outer(along, goal[:3] - home[:3]))) < 1e-15
    assert np.allclose(along, m.s, rtol=0, atol=1e-13)
    slerp = Slerp([0, 1], Rotation.from_matrix(rotation(np.vstack([home[3:], goal[3:]]))))
    assert np.max(np.abs(rotation(m.pose[:, 3:]) - slerp(m.s).as_matrix())) < 1e-12


def topp_duration(data, p0, p1, R_of_s, speed, accel, nodes=10001):
    """The time-optimal rest-to-rest duration along the path, by the classical phase-plane
    method: L'(s) and L''(s) by central differences of the closed-form lengths, the maximum
    velocity curve by bisection, a forward pass at the largest path acceleration and a backward
    pass at the largest deceleration, x = (ds/dt)^2 the smaller of the two."""
    s = np.linspace(0, 1, nodes)
    h = 1e-4

    def L(s):
        return lengths_of(data, p0 + np.outer(s, p1 - p0), R_of_s(s))
    d1 = (L(s + h) - L(s - h)) / (2 * h)
    d2 = (L(s + h) - 2 * L(s) + L(s - h)) / h ** 2

    def u_range(j, x):
        lo = np.where(d1[j] > 0, (-accel - d2[j] * x) / d1[j], (accel - d2[j] * x) / d1[j])
        hi = np.where(d1[j] > 0, (accel - d2[j] * x) / d1[j], (-accel - d2[j] * x) / d1[j])
        return np.max(lo, axis=-1), np.min(hi, axis=-1)

    top = np.min((speed / np.abs(d1)) ** 2, axis=1)
    low = np.zeros(nodes)
    for _ in range(200):  # the largest x at which the accelerations leave a u
        mid = 0.5 * (low + top)
        lo, hi = u_range(np.arange(nodes), mid[:, None])
        ok = lo <= hi
        low, top = np.where(ok, mid, low), np.where(ok, top, mid)
    mvc = low
    ds = s[1] - s[0]
    x = np.zeros(nodes)
    for j in range(nodes - 1):
        x[j + 1] = min(mvc[j + 1], x[j] + 2 * ds * u_range(j, x[j])[1])
    x[-1] = 0.0
    for j in range(nodes - 2, -1, -1):
        x[j] = min(x[j], x[j + 1] - 2 * ds * u_range(j + 1, x[j + 1])[0])
    v = np.sqrt(np.maximum(x, 0))
    return float(np.sum(2 * ds / (v[1:] + v[:-1])))


@pytest.mark.parametrize("name, kind", [("thesis", "line"), ("rubin_m2_hexapod", "line"),
                                        ("simona_motion_base", "line"), ("thesis", "point"),
                                        ("paired_hexapod", "point")])
def test_a_move_is_time_optimal(name, kind):
    platform, data = load(name)
    home = platform.check().home
    goal = goal_of(platform, home, kind)
    speed, accel = leg_limits(data)
    m = stewart.move(platform, home, goal, kind, leg_speed_max=speed, leg_accel_max=accel)
    if kind == "line":
        R0, R1 = Rotation.from_matrix(rotation(np.vstack([home[3:], goal[3:]])))
        w = (R1 * R0.inv()).as_rotvec()  # the slerp, R0 turned by s w (s a little beyond [0, 1])

        def R_of_s(s):
            return (Rotation.from_rotvec(np.outer(s, w)) * R0).as_matrix()
    else:
        def R_of_s(s):  # the angles on a straight line
            return rotation(home[3:] + np.outer(s, goal[3:] - home[3:]))
    optimum = topp_duration(data, home[:3], goal[:3], R_of_s, speed, accel)
    assert abs(m.duration - optimum) <= 0.01 * optimum, (m.duration, optimum)


def crossing_pair(platform, home):
    """A start and a goal within every limit whose straight line in pose space is not, found by
    a seeded search over poses drawn in the box of the axis ranges; and the class of the first
    pose beyond a limit on a fine scan of the line, with its s."""
    ends = platform.axis_ranges(home)[0]
    rng = np.random.default_rng(36)
    drawn = ends[:, 0] + rng.uniform(0, 1, (4000, 6)) * (ends[:, 1] - ends[:, 0])
    valid = drawn[platform.limits(drawn).within]
    s = np.linspace(0, 1, 2001)
    for a, b in zip(valid[0::2], valid[1::2]):
        scan = platform.limits(a + np.outer(s, b - a))
        if not scan.within.all():
            j = np.flatnonzero(~scan.within)[0]
            return a, b, class_name(scan.first[j]), s[j]
    raise AssertionError("no crossing pair found")


def test_a_move_across_a_limit_is_refused_naming_class_and_time():
    platform = stewart.Platform()
    a, b, limit, s_first = crossing_pair(platform, platform.check().home)
    with pytest.raises(stewart.MoveError) as info:
        stewart.move(platform, a, b, leg_speed_max=0.1, leg_accel_max=0.5)
    e = info.value
    assert e.limit_class == limit and limit in str(e)
    assert abs(e.s - s_first) <= 1e-3 and 0 < e.time < math.inf
    assert f"t = {e.time:.6g} s" in str(e)
    # The strokes do not enter the time law, only the check: with them wide the same move is
    # made, and it reaches the refused s at the refused time.
    assert limit == "stroke"
    wide = stewart.move(stewart.Platform(stroke_min=0.05, stroke_max=3.0), a, b,
                        leg_speed_max=0.1, leg_accel_max=0.5)
    assert abs(np.interp(e.s, wide.s, wide.t) - e.time) <= DT


def test_relative_moves_in_the_user_and_the_tool_frame():
    platform = stewart.Platform()
    start = np.array([0.01, -0.02, 0.52, 0.05, -0.03, 0.2])
    step = np.array([0.01, 0.0, 0.0, 0.0, 0.0, 0.02])
    R0 = rotation(start[None, 3:])[0]
    user = stewart.move(platform, start, step, frame="user", leg_speed_max=0.1,
                        leg_accel_max=0.5)
    tool = stewart.move(platform, start, step, "line", frame="tool", leg_speed_max=0.1,
                        leg_accel_max=0.5)
    Rz = Rotation.from_euler("z", 0.02).as_matrix()
    assert np.allclose(user.pose[-1, :3], start[:3] + step[:3], rtol=0, atol=1e-15)
    assert np.allclose(rotation(user.pose[-1:, 3:])[0], Rz @ R0, rtol=0, atol=1e-14)
    assert np.allclose(tool.pose[-1, :3], start[:3] + R0 @ step[:3], rtol=0, atol=1e-15)
    assert np.allclose(rotation(tool.pose[-1:, 3:])[0], R0 @ Rz, rtol=0, atol=1e-14)


@pytest.mark.parametrize("kwargs, words", [
    (dict(leg_accel_max=0.5, leg_jerk_max=5.0, via=[[0.005, 0.0, 0.5, 0.0, 0.0, 0.0]]),
     "waypoints .via. with leg_jerk_max"),
    (dict(leg_accel_max=0.5, leg_jerk_max=-5.0), "leg_jerk_max .* must be finite and >= 0"),
    (dict(leg_speed_max=0.1), "leg_accel_max is needed"),
    (dict(leg_accel_max=-1.0), "must be finite and >= 0"),
    (dict(leg_accel_max=0.5, sample_time=0.0), "sample_time"),
    (dict(leg_accel_max=0.5, frame="world"), "frame"),
])
def test_bad_arguments_are_refused(kwargs, words):
    with pytest.raises(ValueError, match=words):
        stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0.01, 0, 0.5, 0, 0, 0], **kwargs)


def test_a_goal_beyond_a_limit_is_refused():
    with pytest.raises(stewart.MoveError, match="goal pose .* beyond the stroke limit"):
        stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0, 0, 2.0, 0, 0, 0],
                     leg_accel_max=0.5)


def test_speed_and_cartesian_limits():
    """A Cartesian speed limit caps the tool point's speed (independent: differences of the
    sampled positions)."""
    platform = stewart.Platform()
    m = stewart.move(platform, [0, 0, 0.5, 0, 0, 0], [0.05, 0.03, 0.5, 0, 0, 0], "line",
                     leg_speed_max=1.0, leg_accel_max=2.0, speed_max=0.02)
    speed = np.linalg.norm(np.diff(m.pose[:, :3], axis=0), axis=1) / DT
    assert np.max(speed) <= 0.02 * (1 + 1e-6) and np.max(speed) > 0.019


def test_the_command_line_writes_the_move(tmp_path):
    out = tmp_path / "move.csv"
    args = [sys.executable, str(ROOT / "scripts" / "move.py"), "--platform", str(FILES["thesis"]),
            "--start", "0,0,0.5,0,0,0", "--goal", "0.01,0,0.51,0,0,0.02", "--line",
            "--leg-speed-max", "0.05", "--leg-accel-max", "0.5", "-o", str(out)]
    run = subprocess.run(args, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    header = out.read_text().splitlines()[0].split(",")
    assert header[:7] == ["t", "x", "y", "z", "roll", "pitch", "yaw"] and len(header) == 19
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    m = stewart.move(stewart.Platform.from_file(FILES["thesis"]), [0, 0, 0.5, 0, 0, 0],
                     [0.01, 0, 0.51, 0, 0, 0.02], "line", leg_speed_max=0.05, leg_accel_max=0.5)
    assert np.array_equal(table, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel]))
    # The platform file's leg limits when the command gives none: the same move.
    machine = tmp_path / "machine.json"
    machine.write_text(json.dumps({**json.loads(FILES["thesis"].read_text()),
                                   "leg_speed_max": 0.05, "leg_accel_max": 0.5}))
    own = subprocess.run(args[:3] + [str(machine)] + args[4:9] + ["-o", str(tmp_path / "own.csv")],
                         capture_output=True, text=True, timeout=120)
    assert own.returncode == 0, own.stderr
    assert np.array_equal(np.loadtxt(tmp_path / "own.csv", delimiter=",", skiprows=1), table)
    none = subprocess.run(args[:9] + ["-o", str(tmp_path / "none.csv")], capture_output=True,
                          text=True, timeout=120)
    assert none.returncode == 1 and "leg_accel_max is needed" in none.stderr
    bad = subprocess.run(args[:-6] + ["--goal", "0,0,2,0,0,0", "--leg-accel-max", "0.5", "-o",
                                      str(out)], capture_output=True, text=True, timeout=120)
    assert bad.returncode == 1 and "stroke" in bad.stderr


def test_the_feasibility_report_of_a_move():
    """The leg margins against the reference's closed-form length rates and accelerations
    (tests/python/reference.py, the thesis geometry); the first class and the worst times."""
    import reference
    platform = stewart.Platform()
    start, goal = np.array([0, 0, 0.5, 0, 0, 0.0]), np.array([0.02, -0.01, 0.51, 0.02, 0, 0.05])
    m = stewart.move(platform, start, goal, "line", leg_speed_max=0.05, leg_accel_max=0.5)
    rates = np.array([reference.length_rates_and_accelerations(q, qd, qdd)
                      for q, qd, qdd in zip(m.pose, m.pose_rate, m.pose_accel)])
    speed, accel = np.abs(rates[:, 0]), np.abs(rates[:, 1])
    report = stewart.feasibility(platform, m.t, m.pose, m.pose_rate, m.pose_accel,
                                 leg_speed_max=0.04, leg_accel_max=0.5)
    classes = stewart.Feasibility.names[1:]  # the margin columns
    SPEED, ACCEL = classes.index("leg_speed"), classes.index("leg_accel")
    assert np.allclose(report.margin[:, SPEED], 0.04 - speed.max(axis=1), rtol=0, atol=1e-12)
    assert np.allclose(report.margin[:, ACCEL], 0.5 - accel.max(axis=1), rtol=0, atol=1e-12)
    assert np.array_equal(report.leg[:, SPEED], speed.argmax(axis=1) + 1)
    over = np.flatnonzero(speed.max(axis=1) > 0.04)
    assert over.size and np.array_equal(np.flatnonzero(~report.within), over)
    assert np.all(np.array(report.names)[report.first[over]] == "leg_speed")
    j = np.argmax(speed.max(axis=1))
    assert report.worst["leg_speed"] == (pytest.approx(0.04 - speed.max()), m.t[j])
    assert 0 < report.worst["leg_accel"][0] < 1e-3 * 0.5  # the move's own limit, just met
    assert "leg_speed" in str(report) and "met" in str(report)


def test_the_feasibility_report_names_a_geometric_limit_first():
    platform = stewart.Platform()
    poses = np.array([[0, 0, 0.5, 0, 0, 0], [0, 0, 0.95, 0, 0, 0], [0, 0, 0.5, 0, 0, 0.01]])
    report = stewart.feasibility(platform, [0, 1, 2], poses, np.ones((3, 6)), np.zeros((3, 6)),
                                 leg_speed_max=1e-3, leg_accel_max=10.0)
    assert report.names[report.first[1]] == "stroke"
    assert report.names[report.first[0]] == "leg_speed"
    assert report.worst["stroke"][1] == 1.0 and report.worst["stroke"][0] < 0
    with pytest.raises(ValueError, match="leg_speed_max needs the trajectory.s data: give rates="):
        stewart.feasibility(platform, [0, 1, 2], poses, leg_speed_max=0.1)


def test_a_line_in_rotation_order_1():
    """R = Rx Ry Rz (PI's U-V-W): the slerp, the limits and the rates in that order."""
    data = json.loads(FILES["thesis"].read_text())
    platform = stewart.Platform.from_file(FILES["thesis"], rotation_order=1)
    start = np.array([0.01, 0.0, 0.5, 0.03, 0.02, -0.05])
    goal = np.array([-0.01, 0.02, 0.51, -0.02, 0.04, 0.08])
    m = stewart.move(platform, start, goal, "line", leg_speed_max=0.05, leg_accel_max=0.5)

    def uvw(angles):
        return Rotation.from_euler("XYZ", angles).as_matrix()
    slerp = Slerp([0, 1], Rotation.from_matrix(uvw(np.vstack([start[3:], goal[3:]]))))
    assert np.max(np.abs(uvw(m.pose[:, 3:]) - slerp(m.s).as_matrix())) < 1e-12
    L = lengths_of(data, m.pose[:, :3], uvw(m.pose[:, 3:]))
    v = (L[2:] - L[:-2]) / (2 * DT)
    a = (L[2:] - 2 * L[1:-1] + L[:-2]) / DT ** 2
    delta_L = 16 * EPS * np.max(L)
    assert np.max(np.abs(v)) <= 0.05 * (1 + 1e-6) + delta_L / DT
    assert np.max(np.abs(a)) <= 0.5 * (1 + 1e-6) + 4 * delta_L / DT ** 2
    diff = (m.pose[2:] - m.pose[:-2]) / (2 * DT) - m.pose_rate[1:-1]
    tight = np.abs(diff) > 1e-5 * np.max(np.abs(m.pose_rate), axis=0) + 16 * EPS / DT
    assert np.count_nonzero(tight.any(axis=1)) <= 0.02 * len(m.t)


def test_stewart_solve_takes_the_move(tmp_path, solve):
    """The CSV of scripts/move.py through stewart-solve: its exact rates give the leg speeds,
    within the limit and equal to Platform.inverse's."""
    moved, out = tmp_path / "move.csv", tmp_path / "legs.csv"
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "move.py"), "--start",
                          "0,0,0.5,0,0,0", "--goal", "0.02,0.01,0.49,0.01,0,0.03",
                          "--leg-speed-max", "0.03", "--leg-accel-max", "0.3", "-o", str(moved)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    r = solve("--fidelity", "kinematic", moved, out)
    assert r.returncode == 0, r.stderr
    with open(out) as f:
        header = f.readline().strip().split(",")
    columns = [header.index(f"L_dot{k}") for k in range(1, 7)]
    rate = np.loadtxt(out, delimiter=",", skiprows=1, usecols=columns)
    table = np.loadtxt(moved, delimiter=",", skiprows=1)
    expected = stewart.Platform().inverse(table[:, 1:7], table[:, 7:13], table[:, 13:19],
                                          fidelity="kinematic").length_rate
    assert np.max(np.abs(rate - expected)) < 1e-12
    assert np.max(np.abs(rate)) <= 0.03 * (1 + 1e-9) and np.max(np.abs(rate)) > 0.0299


def test_waypoints_are_passed_without_stopping_on_blends():
    """Blended lines through two waypoints: the blend's closest approach to each waypoint is the
    quadratic Bezier's midpoint, r |d_out - d_in| / 4 away (r the blend's reach, d the unit
    directions in pose space), the rest of the path is on the lines, the legs keep their limits
    (closed form, differences), the move never stops between its ends, and it is faster than
    stopping at each waypoint."""
    platform, data = load("thesis")
    home = platform.check().home
    points = home + np.array([[0, 0, 0, 0, 0, 0], [0.03, 0, 0, 0, 0, 0.05],
                              [0.03, 0.03, 0.01, 0, 0.02, 0], [0, 0.03, 0, 0, 0, 0]])
    limits = dict(leg_speed_max=0.05, leg_accel_max=0.5)
    m = stewart.move(platform, points[0], points[-1], via=points[1:-1], blend=0.3, **limits)
    assert np.max(np.abs(m.pose[-1] - points[-1])) <= 1e-12 and np.all(m.s_rate[1:-1] > 0)
    step = np.max(np.linalg.norm(np.diff(m.pose, axis=0), axis=1))
    lines = np.diff(points, axis=0)
    length = np.linalg.norm(lines, axis=1)
    units = lines / length[:, None]
    offsets = []
    for j in (1, 2):
        r = 0.3 * min(length[j - 1], length[j])
        offsets.append(r * np.linalg.norm(units[j] - units[j - 1]) / 4)
        closest = np.min(np.linalg.norm(m.pose - points[j], axis=1))
        assert abs(closest - offsets[-1]) <= step, (closest, offsets[-1])

    def to_polyline(q):
        along = np.clip(np.einsum("kj,kj->k", q - points[:-1], units), 0, length)
        return np.min(np.linalg.norm(q - points[:-1] - along[:, None] * units, axis=1))
    assert max(to_polyline(q) for q in m.pose) <= max(offsets) * (1 + 1e-9)
    L = lengths(data, m.pose)
    delta_L = 16 * EPS * np.max(L)
    assert np.max(np.abs(L[2:] - L[:-2])) / (2 * DT) <= 0.05 * (1 + 1e-6) + delta_L / DT
    assert (np.max(np.abs(L[2:] - 2 * L[1:-1] + L[:-2])) / DT ** 2
            <= 0.5 * (1 + 1e-6) + 4 * delta_L / DT ** 2)
    assert np.all(platform.limits(m.pose).within)
    # The rates against differences of the poses where the path acceleration hardly changes
    # over the difference's two samples (on the blends it changes fast where the legs'
    # acceleration limits the speed): there the difference's error dt^2/6 times the rate's
    # second derivative is small; the others within the mean-value bound.
    diff = (m.pose[2:] - m.pose[:-2]) / (2 * DT) - m.pose_rate[1:-1]
    assert np.all(np.abs(diff) <= 0.5 * DT * np.max(np.abs(m.pose_accel), axis=0) * 1.01
                  + 16 * EPS / DT)
    smooth = (np.abs(m.s_accel[2:] - m.s_accel[:-2]) <= 1e-3 * np.max(np.abs(m.s_accel)))
    assert np.mean(smooth) > 0.75
    tight = np.abs(diff) > 1e-5 * np.max(np.abs(m.pose_rate), axis=0) + 16 * EPS / DT
    assert not np.any(tight[smooth])
    stops = sum(stewart.move(platform, a, b, **limits).duration
                for a, b in zip(points[:-1], points[1:]))
    assert m.duration < stops


def test_bad_waypoints_are_refused():
    home = [0, 0, 0.5, 0, 0, 0]
    with pytest.raises(ValueError, match="same pose"):
        stewart.move(stewart.Platform(), home, [0.01, 0, 0.5, 0, 0, 0], via=[home],
                     leg_accel_max=0.5)
    with pytest.raises(ValueError, match="kind='point'"):
        stewart.move(stewart.Platform(), home, [0.01, 0, 0.5, 0, 0, 0], "line",
                     via=[[0.005, 0.01, 0.5, 0, 0, 0]], leg_accel_max=0.5)
    with pytest.raises(ValueError, match="blend"):
        stewart.move(stewart.Platform(), home, [0.01, 0, 0.5, 0, 0, 0],
                     via=[[0.005, 0.01, 0.5, 0, 0, 0]], blend=0.7, leg_accel_max=0.5)


def test_the_command_line_takes_waypoints(tmp_path):
    out = tmp_path / "tour.csv"
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "move.py"), "--start",
                          "0,0,0.5,0,0,0", "--goal", "0,0.02,0.5,0,0,0", "--via",
                          "0.02,0,0.5,0,0,0.03", "--via", "0.02,0.02,0.505,0,0,0", "--blend",
                          "0.3", "--leg-speed-max", "0.05", "--leg-accel-max", "0.5", "-o",
                          str(out)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    m = stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0, 0.02, 0.5, 0, 0, 0],
                     via=[[0.02, 0, 0.5, 0, 0, 0.03], [0.02, 0.02, 0.505, 0, 0, 0]], blend=0.3,
                     leg_speed_max=0.05, leg_accel_max=0.5)
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.array_equal(table, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel]))


def test_a_move_takes_the_platform_s_leg_limits():
    """leg_speed_max and leg_accel_max of the platform are the move's unless given: the same
    move as with the keywords, bit for bit; a keyword overrides; every sample within the
    platform's limits by differences of the closed-form lengths."""
    limited = stewart.Platform(leg_speed_max=0.05, leg_accel_max=0.5)
    home = limited.check().home
    goal = home + [0.02, -0.01, 0.01, 0.0, 0.0, 0.05]
    own = stewart.move(limited, home, goal, "line")
    given = stewart.move(stewart.Platform(), home, goal, "line", leg_speed_max=0.05,
                         leg_accel_max=0.5)
    assert np.array_equal(own.pose, given.pose) and np.array_equal(own.pose_accel,
                                                                   given.pose_accel)
    slower = stewart.move(limited, home, goal, "line", leg_speed_max=0.03)
    assert np.array_equal(slower.pose, stewart.move(stewart.Platform(), home, goal, "line",
                                                    leg_speed_max=0.03, leg_accel_max=0.5).pose)
    assert slower.duration > own.duration
    import reference  # the thesis geometry's closed-form length rates and accelerations
    rates = np.array([reference.length_rates_and_accelerations(q, qd, qdd)
                      for q, qd, qdd in zip(own.pose, own.pose_rate, own.pose_accel)])
    assert np.abs(rates[:, 0]).max() <= 0.05 * (1 + 1e-6)
    assert np.abs(rates[:, 1]).max() <= 0.5 * (1 + 1e-6)
    with pytest.raises(ValueError, match="leg_accel_max is needed"):
        stewart.move(stewart.Platform(leg_speed_max=0.05), home, goal)
    # The platform's jerk limit is planned for unless the keyword says none (0).
    jerky = stewart.Platform(leg_accel_max=0.5, leg_jerk_max=5.0)
    free = stewart.move(jerky, home, goal, leg_jerk_max=0)
    limited = stewart.move(jerky, home, goal)
    assert limited.duration > free.duration and free.pose_jerk is None
    assert np.array_equal(limited.pose, stewart.move(stewart.Platform(), home, goal,
                                                     leg_accel_max=0.5, leg_jerk_max=5.0).pose)


def test_a_move_beyond_the_leg_force_limit_is_refused_naming_it():
    """A platform whose leg_force_max the planned move's massless forces exceed: MoveError
    leg_force at the first sample whose force exceeds it, found here from the inverse."""
    home = np.array([0, 0, 0.5, 0, 0, 0.0])
    goal = home + [0.02, -0.01, 0.01, 0.0, 0.0, 0.05]
    free = stewart.move(stewart.Platform(), home, goal, "line", leg_accel_max=0.5,
                        leg_speed_max=0.05)
    forces = np.abs(stewart.Platform().inverse(free.pose, free.pose_rate, free.pose_accel).force)
    limit = 0.5 * (forces.max() + np.abs(stewart.Platform().inverse(home).force).max())
    with pytest.raises(stewart.MoveError) as e:
        stewart.move(stewart.Platform(leg_force_max=limit), home, goal, "line",
                     leg_accel_max=0.5, leg_speed_max=0.05)
    first = np.flatnonzero((forces > limit * (1 + 1e-9)).any(axis=1))[0]
    assert e.value.limit_class == "leg_force" and e.value.time == free.t[first]
    assert "leg_force" in str(e.value) and "lower leg_accel_max" in str(e.value)


def test_the_feasibility_report_has_the_jerk_and_force_classes():
    """forces computed by the massless inverse against leg_force_max by hand; the jerk class
    from jerks given; a platform limit without its data reported as not checked."""
    platform = stewart.Platform(leg_jerk_max=2.0)
    home = platform.check().home
    m = stewart.move(platform, home, home + [0.01, 0, 0.005, 0, 0, 0.02], leg_accel_max=0.5,
                     leg_jerk_max=0)
    forces = platform.inverse(m.pose, m.pose_rate, m.pose_accel).force
    report = stewart.feasibility(platform, m.t, m.pose, m.pose_rate, m.pose_accel,
                                 forces="massless", leg_force_max=230.0)
    FORCE = report.names.index("leg_force") - 1
    assert np.array_equal(report.margin[:, FORCE], (230.0 - np.abs(forces)).min(axis=1))
    assert np.array_equal(report.leg[:, FORCE], np.abs(forces).argmax(axis=1) + 1)
    assert report.unchecked == ("leg_jerk",) and "leg_jerk        not checked" in str(report)
    met = (np.abs(forces) > 230.0).any(axis=1)
    assert met.any() and np.array_equal(~report.within, met)
    jerks = np.zeros_like(m.pose)
    jerks[:, 2] = 3.0  # a constant heave jerk: about 3 m/s^3 per leg at home, above 2
    with_jerk = stewart.feasibility(platform, m.t, m.pose, m.pose_rate, m.pose_accel, jerks)
    JERK = report.names.index("leg_jerk") - 1
    assert with_jerk.unchecked == () and with_jerk.worst["leg_jerk"][0] < 0
    assert np.array_equal(with_jerk.margin[:, JERK], platform.limits(
        m.pose, m.pose_rate, m.pose_accel, jerks).margin[:, JERK])
    with pytest.raises(ValueError, match="leg_jerk_max needs the trajectory's data"):
        stewart.feasibility(platform, m.t, m.pose, m.pose_rate, leg_jerk_max=1.0)


def test_numpy_scalars_are_numbers_as_floats_are():
    """speed_max, angular_speed_max, blend and sample_time as numpy scalars (a float32, an
    array's max): the same move, bit for bit, as the equal Python floats."""
    platform = stewart.Platform()
    home = platform.check().home
    goal = home + [0.03, -0.01, 0.01, 0.0, 0.0, 0.02]
    via = [home + [0.02, 0.01, 0.0, 0.0, 0.0, 0.0]]
    kw = dict(via=via, leg_speed_max=0.1, leg_accel_max=0.5)
    plain = stewart.move(platform, home, goal, speed_max=0.25, angular_speed_max=0.5,
                         blend=0.25, sample_time=2.0 ** -10, **kw)
    numpy = stewart.move(platform, home, goal, speed_max=np.float32(0.25),
                         angular_speed_max=np.max(np.array([0.5], np.float32)),
                         blend=np.float32(0.25), sample_time=np.float32(2.0 ** -10), **kw)
    for name in ("t", "pose", "pose_rate", "pose_accel"):
        assert np.array_equal(getattr(plain, name), getattr(numpy, name)), name


def test_limits_too_small_for_the_path_are_refused_naming_them():
    """A speed bound whose square underflows stalls the time law: the refusal names the speed
    limits to raise. A move too long for its samples gives the count as a number a person
    reads (6 digits: the duration over the sample time), not hundreds of digits."""
    platform = stewart.Platform()
    home = platform.check().home
    goal = home + [0.03, 0, 0, 0, 0, 0]
    with pytest.raises(stewart.MoveError, match="speed_max.*give a larger one"):
        stewart.move(platform, home, goal, speed_max=1e-300, leg_speed_max=0.1,
                     leg_accel_max=0.5)
    with pytest.raises(ValueError, match=r"the move takes (\S+) s: (\S+) samples") as info:
        stewart.move(platform, home, goal, leg_speed_max=0.1, leg_accel_max=1e-300)
    duration, count = (float(x) for x in re.search(r"takes (\S+) s: (\S+) samples",
                                                    str(info.value)).groups())
    assert len(str(info.value)) < 200 and count == pytest.approx(duration / 0.001, rel=1e-5)
