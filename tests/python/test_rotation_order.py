"""rotation_order and frame_convention (docs/geometry.md, "Rotation order and frames"): poses in
R = Rx Ry Rz against the lengths of closed forms with the rotation matrices written here; the same
physical pose in either order gives the same lengths; stewart.convert_angles round trips and its
rates and accelerations against differences in time; a machine given in a z-down frame (the SIMONA
motion base's joints turned back into its own frame) against the shipped z-up file, gravity
physical; forward kinematics, the plant, axis ranges, the linearisation, the CLI and the inverse
FMU in the convention."""
import json
import math
import pathlib

import numpy as np
import pytest

import stewart
from fmu_support import L, OK, POSE, VERSIONS, Unit, opened_unit
from reference import geometry
from test_cli import column, read

REPO = pathlib.Path(__file__).resolve().parents[2]
SIMONA = REPO / "platforms" / "simona_motion_base.json"
TURN_X = np.diag([1.0, -1.0, -1.0])  # 180 deg about x: z up <-> z down


def rx(a):
    return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])


def ry(a):
    return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])


def rz(a):
    return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])


def r_zyx(roll, pitch, yaw):
    return rz(yaw) @ ry(pitch) @ rx(roll)


def r_xyz(roll, pitch, yaw):
    return rx(roll) @ ry(pitch) @ rz(yaw)


def zyx_angles(R):
    """Angles of R = Rz Ry Rx (principal)."""
    return np.array([math.atan2(R[2, 1], R[2, 2]), math.asin(-R[2, 0]),
                     math.atan2(R[1, 0], R[0, 0])])


def random_xyz_poses(n, seed=3):
    rng = np.random.default_rng(seed)
    q = np.empty((n, 6))
    q[:, :3] = rng.uniform(-0.05, 0.05, (n, 3)) + [0, 0, 0.5]
    q[:, 3:] = rng.uniform(-0.3, 0.3, (n, 3))
    return q


def thesis_lengths(position, R):
    """|p + R b_k - a_k| of the thesis platform (reference.geometry: joints from docs/model.md)."""
    a, b = geometry()
    return np.linalg.norm(np.asarray(position) + b @ R.T - a, axis=1)


def test_lengths_in_either_order_are_the_same_physical_lengths():
    poses = random_xyz_poses(40)
    xyz = stewart.Platform(rotation_order=1).inverse(poses, fidelity="kinematic")
    assert xyz.ok.all()
    by_hand = np.array([thesis_lengths(q[:3], r_xyz(*q[3:])) for q in poses])
    np.testing.assert_allclose(xyz.length, by_hand, rtol=0, atol=1e-15)
    # the same rotations as Rz Ry Rx angles, through the default order
    zyx_poses = np.array([np.concatenate([q[:3], zyx_angles(r_xyz(*q[3:]))]) for q in poses])
    zyx = stewart.Platform().inverse(zyx_poses, fidelity="kinematic")
    np.testing.assert_allclose(xyz.length, zyx.length, rtol=0, atol=1e-15)
    # the orders differ by more than rounding at these angles: the test can tell them apart
    assert np.abs(stewart.Platform().inverse(poses, fidelity="kinematic").length
                  - xyz.length).max() > 1e-3


def test_frames_angles_are_in_the_order_too():
    """tool_frame and user_frame are poses the caller gives: their angles are Rx Ry Rz too."""
    tool = np.array([0.02, -0.01, 0.10, 0.05, -0.04, 0.30])
    user = np.array([0.01, -0.02, 0.05, 0.02, -0.03, 0.40])
    poses = random_xyz_poses(10)
    poses[:, 2] -= 0.05 + 0.10  # the tool 0.1 m above the platform, the user frame 0.05 m up
    out = stewart.Platform(rotation_order=1, tool_frame=tool, user_frame=user).inverse(
        poses, fidelity="kinematic")
    assert out.ok.all(), out.messages
    Ru, Rt = r_xyz(*user[3:]), r_xyz(*tool[3:])
    expected = []
    for q in poses:
        Rp = Ru @ r_xyz(*q[3:]) @ Rt.T
        expected.append(thesis_lengths(user[:3] + Ru @ q[:3] - Rp @ tool[:3], Rp))
    np.testing.assert_allclose(out.length, expected, rtol=0, atol=1e-14)


def test_convert_angles_round_trips_and_keeps_the_rotation():
    rng = np.random.default_rng(7)
    a = rng.uniform(-1.4, 1.4, (200, 3)) * [2, 1, 2]
    rates, accels = rng.uniform(-2, 2, (200, 3)), rng.uniform(-5, 5, (200, 3))
    b, b_rate, b_accel = stewart.convert_angles(a, 0, 1, rates, accels)
    for one, other in zip(a, b):
        np.testing.assert_allclose(r_xyz(*other), r_zyx(*one), atol=2e-15)
    back, back_rate, back_accel = stewart.convert_angles(b, "xyz", "zyx", b_rate, b_accel)
    np.testing.assert_allclose(back, a, rtol=0, atol=1e-13)
    np.testing.assert_allclose(back_rate, rates, rtol=0, atol=1e-12)
    np.testing.assert_allclose(back_accel, accels, rtol=0, atol=1e-11)
    np.testing.assert_array_equal(stewart.convert_angles(a, 1, "uvw"), a)
    with pytest.raises(ValueError, match="rotation order"):
        stewart.convert_angles(a, 0, 2)


def test_converted_rates_and_accelerations_are_time_derivatives():
    """The angles of a motion converted at t - h, t, t + h: their differences against the rates
    and accelerations convert_angles gives."""
    def path(t):
        return np.array([0.4 * math.sin(1.3 * t), 0.3 * math.cos(0.7 * t), 2.5 + 0.9 * t])

    def rate(t):
        return np.array([0.52 * math.cos(1.3 * t), -0.21 * math.sin(0.7 * t), 0.9])

    def accel(t):
        return np.array([-0.676 * math.sin(1.3 * t), -0.147 * math.cos(0.7 * t), 0.0])

    h = 1e-4
    for t in np.linspace(0, 3, 7):
        b, b_rate, b_accel = stewart.convert_angles(path(t), 0, 1, rate(t), accel(t))
        ahead = stewart.convert_angles(path(t + h), 0, 1)
        behind = stewart.convert_angles(path(t - h), 0, 1)
        np.testing.assert_allclose(b_rate, (ahead - behind) / (2 * h), atol=1e-7)
        np.testing.assert_allclose(b_accel, (ahead - 2 * b + behind) / h ** 2, atol=1e-5)


def test_forward_returns_the_order_s_angles():
    t = np.linspace(0, 1, 21)[:, None]
    poses = np.hstack([0.03 * np.sin(2 * t), 0.02 * np.cos(3 * t), 0.5 + 0.02 * np.sin(t),
                       0.25 * np.sin(3 * t), 0.2 * np.sin(2 * t + 1), 0.3 * np.cos(t)])
    lengths = np.array([thesis_lengths(q[:3], r_xyz(*q[3:])) for q in poses])
    out = stewart.Platform(rotation_order=1).forward(lengths)
    assert out.ok.all(), out.messages
    np.testing.assert_allclose(out.pose, poses, atol=1e-11)


def test_simulate_starts_and_ends_in_the_order():
    """The same physical start in either order, the same forces: the same motion (rotations
    compared as matrices), each pose in its platform's order."""
    start = np.array([0.01, -0.02, 0.52, 0.1, -0.08, 0.2])  # Rx Ry Rz
    zyx_start = np.concatenate([start[:3], zyx_angles(r_xyz(*start[3:]))])
    plain = stewart.Platform()
    t = np.linspace(0, 0.05, 11)
    forces = np.tile(plain.inverse(zyx_start[None, :]).force, (t.size, 1)) * 1.01
    a = plain.simulate(t, forces, fidelity="massless", start=zyx_start)
    b = stewart.Platform(rotation_order=1).simulate(t, forces, fidelity="massless", start=start)
    assert a.completed and b.completed, b.message
    np.testing.assert_allclose(b.pose[0], start, atol=1e-15)
    for p, q in zip(a.pose, b.pose):
        np.testing.assert_allclose(r_xyz(*q[3:]), r_zyx(*p[3:]), atol=1e-12)
        np.testing.assert_allclose(q[:3], p[:3], atol=1e-12)
    np.testing.assert_allclose(b.length, a.length, atol=1e-12)


def test_axis_ranges_move_the_order_s_angle():
    """At a turned pose, each angle's range ends where the pose with that angle at the end (the
    other five held, angles Rx Ry Rz) meets a limit."""
    pose = np.array([0.0, 0.0, 0.5, 0.08, -0.06, 0.15])
    platform = stewart.Platform(rotation_order=1)
    ends = platform.axis_ranges(pose)[0]
    for axis in (3, 4, 5):
        for side in (0, 1):
            at_end = pose.copy()
            at_end[axis] = ends[axis, side]
            inside = at_end.copy()
            inside[axis] += 1e-4 if side == 0 else -1e-4
            beyond = at_end.copy()
            beyond[axis] -= 1e-4 if side == 0 else -1e-4
            check = platform.limits(np.array([inside, beyond]))
            assert check.within[0] and not check.within[1], (axis, side, check.margin)


def test_linearisation_states_are_the_order_s_angles():
    """At rest, the angle accelerations' response to the forces in Rx Ry Rz is E1^-1 E0 times the
    Rz Ry Rx one (omega_dot = E angles_ddot at zero rates, E of each order written here); the
    lengths' rows are the lengths' slopes in the order's angles (central differences)."""
    start = np.array([0.01, -0.02, 0.52, 0.1, -0.08, 0.2])
    zyx_start = np.concatenate([start[:3], zyx_angles(r_xyz(*start[3:]))])
    a = stewart.Platform().linearize(zyx_start, fidelity="massless")
    b = stewart.Platform(rotation_order=1).linearize(start, fidelity="massless")
    r, p, y = zyx_start[3:]
    E0 = np.column_stack([rz(y) @ ry(p) @ [1, 0, 0], rz(y) @ [0, 1, 0], [0, 0, 1]])
    r1, p1, _ = start[3:]
    E1 = np.column_stack([[1, 0, 0], rx(r1) @ [0, 1, 0], rx(r1) @ ry(p1) @ [0, 0, 1]])
    np.testing.assert_allclose(b.B[9:12], np.linalg.solve(E1, E0 @ a.B[9:12]), rtol=1e-9,
                               atol=1e-12 * np.abs(a.B[9:12]).max())
    np.testing.assert_allclose(b.B[6:9], a.B[6:9], rtol=1e-9, atol=1e-12 * np.abs(a.B).max())
    h = 1e-6
    for i in (3, 4, 5):
        ahead, behind = start.copy(), start.copy()
        ahead[i] += h
        behind[i] -= h
        slope = (thesis_lengths(ahead[:3], r_xyz(*ahead[3:]))
                 - thesis_lengths(behind[:3], r_xyz(*behind[3:]))) / (2 * h)
        np.testing.assert_allclose(b.C[12:18, i], slope, atol=1e-8)


def test_command_line_takes_the_order(solve, tmp_path):
    pose = random_xyz_poses(1, seed=5)[0]
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    row = ",".join(repr(float(v)) for v in pose)
    pose_csv.write_text(f"t,x,y,z,roll,pitch,yaw\n0,{row}\n")
    result = solve("--param", "rotation_order=1", pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    got = np.array([column(header, data, f"L{k}")[0] for k in range(1, 7)])
    np.testing.assert_allclose(got, thesis_lengths(pose[:3], r_xyz(*pose[3:])), atol=1e-14)


@pytest.mark.parametrize("version", VERSIONS)
def test_inverse_fmu_takes_the_order(version):
    pose = random_xyz_poses(1, seed=9)[0]
    with opened_unit(version) as u:
        assert u.init(fidelity=0, rotation_order=1, **dict(zip(POSE, pose))) == OK
        got = np.array(u.get(L))
    np.testing.assert_allclose(got, thesis_lengths(pose[:3], r_xyz(*pose[3:])), atol=1e-14)


def test_bad_conventions_are_refused_by_name():
    for name, value in (("rotation_order", 0.5), ("rotation_order", 2), ("frame_convention", -1)):
        with pytest.raises(stewart.ParameterError, match=name):
            stewart.Platform(**{name: value})


# ---- z down: the SIMONA motion base in its own frame (x forward, y right, z down) ----

def simona_z_down(tmp_path, **more):
    """platforms/simona_motion_base.json turned back into SIMONA's z-down frames (its description:
    the shipped file is SIMONA's turned by 180 deg about x), as a platform file with `more`."""
    data = json.loads(SIMONA.read_text())
    for name in ("base_joint", "platform_joint"):
        data[name] = (np.array(data[name]).reshape(6, 3) @ TURN_X).ravel().tolist()
    data["payload_com"] = (TURN_X @ data["payload_com"]).tolist()
    data["frame_convention"] = 1
    data["description"] = "SIMONA in its own z-down frames"
    path = tmp_path / "simona_z_down.json"
    path.write_text(json.dumps(dict(data, **more)))
    return stewart.Platform.from_file(path)


def z_down_pose(q):
    """A z-up pose (Rz Ry Rx) as the same physical pose of the z-down frames."""
    R = TURN_X @ r_zyx(*q[3:]) @ TURN_X
    return np.concatenate([TURN_X @ q[:3], zyx_angles(R)])


def simona_poses():
    rng = np.random.default_rng(17)
    q = np.zeros((30, 6))
    q[:, :3] = rng.uniform(-0.2, 0.2, (30, 3)) + [0, 0, 2.39]
    q[:, 3:] = rng.uniform(-0.15, 0.15, (30, 3))
    return q


def test_z_down_machine_has_the_z_up_machine_s_lengths_and_forces(tmp_path):
    up = stewart.Platform.from_file(SIMONA)
    down = simona_z_down(tmp_path)
    q = simona_poses()
    rates = np.tile([0.1, -0.2, 0.05, 0.1, 0.2, -0.1], (q.shape[0], 1))
    sign = np.array([1, -1, -1, 1, -1, -1])  # z-down angles are (r, -p, -y) of the z-up ones
    accels = np.tile([-0.5, 0.3, 1.0, 0.4, -0.2, 0.3], (q.shape[0], 1))
    a = up.inverse(q, rates, accels, fidelity="full")
    b = down.inverse(np.array([z_down_pose(p) for p in q]), rates * sign, accels * sign,
                     fidelity="full")
    assert a.ok.all() and b.ok.all(), b.messages
    np.testing.assert_allclose(b.length, a.length, rtol=0, atol=1e-14)
    np.testing.assert_allclose(b.length_rate, a.length_rate, rtol=0, atol=1e-13)
    np.testing.assert_allclose(b.length_accel, a.length_accel, rtol=0, atol=1e-12)
    # gravity is physical: the same weight on the legs
    np.testing.assert_allclose(b.force, a.force, rtol=1e-10, atol=1e-8)
    # the base wrench in the z-down base frame: the z-up one turned by 180 deg about x
    np.testing.assert_allclose(b.base_force, a.base_force @ TURN_X, rtol=1e-10, atol=1e-8)
    np.testing.assert_allclose(b.base_torque, a.base_torque @ TURN_X, rtol=1e-10, atol=1e-8)
    # forward kinematics answers in the z-down frames
    back = down.forward(a.length[:5])
    assert back.ok.all(), back.messages
    np.testing.assert_allclose(back.pose, [z_down_pose(p) for p in q[:5]], atol=1e-10)


def test_z_down_plant_holds_its_home_under_its_weight(tmp_path):
    """The forces that hold home (from the inverse side) keep the z-down plant at rest there, at
    z = -home_height: gravity pulls toward +z of the z-down frames."""
    down = simona_z_down(tmp_path)
    home = np.array([0, 0, -2.39, 0, 0, 0])
    hold = down.inverse(home[None, :], fidelity="massless").force
    t = np.linspace(0, 0.2, 11)
    out = down.simulate(t, np.tile(hold, (t.size, 1)), fidelity="massless", start=home)
    assert out.completed, out.message
    np.testing.assert_allclose(out.pose, np.tile(home, (t.size, 1)), atol=1e-9)
    assert out.pose[0, 2] < 0
    # at rest the legs push the base down with the weight of platform and payload (massless
    # legs): +z in the z-down frame
    weight = (1500.0 + 1000.0) * 9.81
    np.testing.assert_allclose(out.base_force[-1], [0, 0, weight], rtol=1e-9, atol=1e-6)


@pytest.mark.parametrize("version", VERSIONS)
def test_plant_fmu_falls_toward_plus_z_in_z_down_frames(version):
    """The thesis' parameters given z down (frame_convention 1), massless, no forces, started at
    its home z0 = -home_height with a sideways speed: x = x0 + x_dot0 t, y = 0,
    z = z0 + g t^2 / 2 (z down: gravity stays physical), the angles at 0."""
    from test_plant_fmu import plant
    u = plant(version, fidelity=1, frame_convention=1, x0=0.01, z0=-0.5, x_dot0=0.02)
    try:
        t = 0.0
        for h in (1e-3, 2e-3, 5e-3, 1e-2):
            assert u.step(t, h) == OK
            t += h
            x, y, z, z_dot, roll, pitch, yaw = u.get(["x", "y", "z", "z_dot", "roll", "pitch",
                                                      "yaw"])
            assert x == pytest.approx(0.01 + 0.02 * t, abs=1e-13)
            assert z == pytest.approx(-0.5 + 0.5 * 9.81 * t * t, abs=1e-13)
            assert z_dot == pytest.approx(9.81 * t, abs=1e-12)
            assert max(abs(y), abs(roll), abs(pitch), abs(yaw)) < 1e-13
    finally:
        u.free()


def xyz_path(t):
    """A smooth manoeuvre (N, 6), angles Rx Ry Rz, and its first and second derivatives."""
    t = np.asarray(t, dtype=float)[:, None]
    amplitude = np.array([0.03, 0.02, 0.02, 0.2, 0.15, 0.25])
    omega = np.array([2.0, 3.0, 1.5, 2.5, 3.5, 1.2])
    phase = np.arange(6)
    q = amplitude * np.sin(omega * t + phase) + [0, 0, 0.5, 0, 0, 0]
    return q, amplitude * omega * np.cos(omega * t + phase), \
        -amplitude * omega ** 2 * np.sin(omega * t + phase)


def test_rates_and_accelerations_are_the_order_s_angle_derivatives():
    """Inverse: the length rates and accelerations of Rx Ry Rz pose rates against differences in
    time of the lengths computed here; forward: the pose rates and accelerations it returns
    against the path's derivatives written here."""
    t, h = np.linspace(0.1, 1.9, 10), 1e-4
    q, q_dot, q_ddot = xyz_path(t)
    platform = stewart.Platform(rotation_order=1)
    out = platform.inverse(q, q_dot, q_ddot, fidelity="kinematic")
    assert out.ok.all(), out.messages

    def lengths(time):
        return np.array([thesis_lengths(p[:3], r_xyz(*p[3:])) for p in xyz_path(time)[0]])

    ahead, here, behind = lengths(t + h), lengths(t), lengths(t - h)
    np.testing.assert_allclose(out.length_rate, (ahead - behind) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(out.length_accel, (ahead - 2 * here + behind) / h ** 2, atol=2e-5)
    back = platform.forward(out.length, rates=out.length_rate, accels=out.length_accel, t=t)
    assert back.ok.all(), back.messages
    np.testing.assert_allclose(back.pose, q, atol=1e-11)
    np.testing.assert_allclose(back.pose_rate, q_dot, atol=1e-9)
    np.testing.assert_allclose(back.pose_accel, q_ddot, atol=1e-8)


def test_z_down_tool_frame_is_given_in_the_z_down_platform_frame(tmp_path):
    """SIMONA's design eye point, 1.2075 m above the upper gimbal plane, as the tool frame: given
    z down (0, 0, -1.2075) with z-down poses, the lengths of the z-up file with the tool frame
    (0, 0, 1.2075) at the same physical poses."""
    up = stewart.Platform.from_file(SIMONA, tool_frame=[0, 0, 1.2075, 0, 0, 0])
    down = simona_z_down(tmp_path, tool_frame=[0, 0, -1.2075, 0, 0, 0])
    q = simona_poses()
    q[:, 2] += 1.2075  # the eye point's height
    a = up.inverse(q, fidelity="kinematic")
    b = down.inverse(np.array([z_down_pose(p) for p in q]), fidelity="kinematic")
    assert a.ok.all() and b.ok.all(), b.messages
    np.testing.assert_allclose(b.length, a.length, rtol=0, atol=1e-14)


def test_model_joints_come_back_in_the_frames_given(tmp_path):
    from stewart import _core
    down = simona_z_down(tmp_path)
    base, top = _core.model_joints(down._model)
    data = json.loads(SIMONA.read_text())
    for got, name in ((base, "base_joint"), (top, "platform_joint")):
        given = np.reshape(data[name], (6, 3)) @ TURN_X
        np.testing.assert_array_equal(np.ravel(got), given.ravel())


def test_calibration_refuses_the_conventions_it_does_not_take():
    with pytest.raises(Exception, match="rotation_order 0 and frame_convention 0"):
        stewart.observability(stewart.Platform(rotation_order=1), random_xyz_poses(30))


def test_a_vendor_s_xyz_poses_of_a_precision_hexapod_are_the_same_physical_poses():
    """The Rubin camera hexapod (Rubin states rotations as Rx Ry Rz) about its pivot 2.6 m below
    the joints, at angles up to its 0.36 deg: its own xyz poses (rotation_order 1) and the same
    rotations converted to Rz Ry Rx give the same lengths to 1e-15 m; taken as Rz Ry Rx
    unconverted they are tens of micrometres off (what a silent convention mix-up costs)."""
    path = stewart.platform_files()["rubin_camera_hexapod"]
    rng = np.random.default_rng(3)
    poses = np.column_stack([rng.uniform(-0.005, 0.005, (40, 3)),
                             rng.uniform(-0.0063, 0.0063, (40, 3))])
    xyz = stewart.Platform.from_file(path, rotation_order=1).inverse(poses, fidelity="kinematic")
    converted = poses.copy()
    converted[:, 3:] = stewart.convert_angles(poses[:, 3:], "xyz", "zyx")
    zyx_platform = stewart.Platform.from_file(path)
    zyx = zyx_platform.inverse(converted, fidelity="kinematic")
    assert xyz.ok.all() and zyx.ok.all()
    np.testing.assert_allclose(xyz.length, zyx.length, rtol=0, atol=1e-15)
    mixed_up = zyx_platform.inverse(poses, fidelity="kinematic").length
    assert np.abs(mixed_up - xyz.length).max() > 2e-5
