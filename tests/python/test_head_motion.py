"""stewart.head_motion (docs/cueing.md, "Perception and scores"): the specific force and angular
velocity at the head, in the platform frame, against constructions written here: a platform at
rest reads (0, 0, +g) on every shipped machine; a tilted one reads gravity's components (closed
forms of both rotation orders); a moving one reads the second differences of the head's position
and the first differences of its rotation, the frames composed here (user, tool, z down); and the
cueing unit's own cases: a pure translation gives back the high-passed specific force (its
transfer function through scipy.signal), a pure rotation about the head gives gravity alone."""
import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
signal = pytest.importorskip("scipy.signal")

G = 9.81
F = np.diag([1.0, -1.0, -1.0])  # a z-down frame's turn by 180 deg about x


def rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def turn(angles, order):
    roll, pitch, yaw = angles
    return rz(yaw) @ ry(pitch) @ rx(roll) if order == 0 else rx(roll) @ ry(pitch) @ rz(yaw)


def transform(pose, order):
    """4x4 of a pose (x, y, z, roll, pitch, yaw) with angles in `order`."""
    T = np.eye(4)
    T[:3, :3] = turn(pose[3:], order)
    T[:3, 3] = pose[:3]
    return T


def platform_in_base(pose, params):
    """(origin, R) of the platform frame in the solvers' z-up base frame from the tool's pose in
    the user frame: T = F (T_user T_pose T_tool^-1) F, F the z-down turn (identity for z up)."""
    order = params.get("rotation_order", 0)
    T = (transform(params.get("user_frame", np.zeros(6)), order) @ transform(pose, order)
         @ np.linalg.inv(transform(params.get("tool_frame", np.zeros(6)), order)))
    if params.get("frame_convention", 0) == 1:
        Fh = np.eye(4)
        Fh[:3, :3] = F
        T = Fh @ T @ Fh
    return T[:3, 3], T[:3, :3]


@pytest.mark.parametrize("name", sorted(stewart.platform_files()))
def test_at_rest_the_head_reads_plus_g(name):
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    home = platform.check().home
    moved = home + np.array([0.01, -0.004, 0.002, 0, 0, 0])  # any pose without rotation
    felt = stewart.head_motion(platform, np.array([home, moved]), np.zeros((2, 6)),
                               np.zeros((2, 6)), head=[0.3, -0.2, 1.1])
    np.testing.assert_allclose(felt.specific_force, [[0, 0, G]] * 2, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(felt.angular_velocity, np.zeros((2, 3)))


@pytest.mark.parametrize("order", [0, 1])
def test_a_tilted_platform_at_rest_reads_gravity_components(order):
    """R^T (0, 0, g) in closed form: order 0 (Rz Ry Rx) (-sin p, sin r cos p, cos r cos p) g;
    order 1 (Rx Ry Rz, yaw 0) (-cos r sin p, sin r, cos r cos p) g. Yaw changes neither in
    order 0."""
    platform = stewart.Platform(rotation_order=order)
    rng = np.random.default_rng(3)
    poses = np.zeros((20, 6))
    poses[:, 2] = 0.5
    poses[:, 3:5] = rng.uniform(-0.3, 0.3, (20, 2))
    if order == 0:
        poses[:, 5] = rng.uniform(-0.5, 0.5, 20)
    felt = stewart.head_motion(platform, poses, np.zeros_like(poses), np.zeros_like(poses),
                               head=[0.1, 0.2, 0.4])
    r, p = poses[:, 3], poses[:, 4]
    if order == 0:
        expected = np.column_stack([-np.sin(p), np.sin(r) * np.cos(p), np.cos(r) * np.cos(p)])
    else:
        expected = np.column_stack([-np.cos(r) * np.sin(p), np.sin(r), np.cos(r) * np.cos(p)])
    np.testing.assert_allclose(felt.specific_force, G * expected, rtol=0, atol=1e-12)
    assert np.all(felt.angular_velocity == 0)


FRAMES = {
    "plain": {},
    "tool and user frames": {"tool_frame": [0.02, -0.01, 0.05, 0.1, -0.05, 0.3],
                             "user_frame": [0.01, 0.03, 0.02, 0.02, 0.04, -0.2]},
    "rotation order 1": {"rotation_order": 1, "tool_frame": [0.0, 0.02, 0.04, 0.0, 0.0, 0.5]},
    "z down": {"frame_convention": 1, "tool_frame": [0.01, 0.0, -0.03, 0.0, 0.0, 0.2],
               "base_angle": list(-np.radians([0, 30, 120, 150, 240, 270])),
               "platform_angle": list(-np.radians([330, 60, 90, 180, 210, 300]))},
}


def trajectory(t, home):
    """A smooth pose about home with its exact rates and accelerations (one sinusoid each)."""
    amplitude = np.array([0.03, -0.02, 0.015, 0.12, -0.1, 0.25])
    omega = np.array([1.3, 2.1, 0.7, 1.7, 2.9, 1.1])
    phase = np.array([0.2, 1.0, -0.4, 0.5, 2.0, -1.2])
    arg = np.outer(t, omega) + phase
    return (home + amplitude * np.sin(arg), amplitude * omega * np.cos(arg),
            -amplitude * omega**2 * np.sin(arg))


@pytest.mark.parametrize("case", sorted(FRAMES))
def test_moving_head_against_finite_differences(case):
    """The head's world position P(t) = p + R head and rotation R(t) built here from the pose and
    the frames; a_head by central second differences of P, omega from (R(t+h) - R(t-h)) R^T / 2h;
    f = R^T (a_head - g), omega in the platform frame R^T omega."""
    params = FRAMES[case]
    platform = stewart.Platform(**params)
    home = platform.check().home
    head = np.array([0.12, -0.07, 0.35])
    t = np.linspace(0.0, 3.0, 7)
    h = 1e-4
    q, qd, qdd = trajectory(t, home)
    felt = stewart.head_motion(platform, q, qd, qdd, head=head)
    for i, ti in enumerate(t):
        frames = [platform_in_base(trajectory(np.array([ti + k * h]), home)[0][0], params)
                  for k in (-1, 0, 1)]
        # head is given in the machine's platform frame: z down turns it into the solvers' z up
        arm = F @ head if params.get("frame_convention", 0) == 1 else head
        points = [p + R @ arm for p, R in frames]
        accel = (points[0] - 2 * points[1] + points[2]) / h**2
        R = frames[1][1]
        skew = (frames[2][1] - frames[0][1]) / (2 * h) @ R.T
        omega = np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
        np.testing.assert_allclose(felt.specific_force[i], R.T @ (accel - [0, 0, -G]), rtol=0,
                                   atol=2e-5, err_msg=f"{case}, t = {ti}")
        np.testing.assert_allclose(felt.angular_velocity[i], R.T @ omega, rtol=0, atol=1e-7,
                                   err_msg=f"{case}, t = {ti}")
    assert np.ptp(felt.specific_force[:, 0]) > 0.1  # the motion is felt, not only gravity


def test_cueing_pure_translation_gives_back_the_high_passed_input():
    """Surge and sway through the classical filter with no tilt (tilt_max 0) and no rotation:
    what the head feels is (0, 0, g) plus k H_t(s) (f - f_rest), the translation's high-pass
    (order 3) written here and run by scipy.signal on the held input."""
    platform = stewart.Platform()
    t = np.arange(0.0, 12.0, 0.01)
    f = np.tile([0.0, 0.0, G], (t.size, 1))
    f[:, 0] += 1.2 * np.sin(1.3 * t) * (t > 1)
    f[:, 1] += 0.8 * ((t > 2) & (t < 5))
    f[:, 2] += 0.5 * np.sin(2.2 * t)
    k, w, zeta, wb = 0.4, 3.0, 1.0, 0.6
    cue = stewart.cueing(platform, t, f, np.zeros_like(f), surge_scale=k, sway_scale=k,
                         heave_scale=k, tilt_max=0.0, translation_frequency=w,
                         translation_damping=zeta, translation_washout_frequency=wb, head_z=0.3)
    assert not cue.limited.any()
    felt = stewart.head_motion(platform, cue.pose, cue.pose_rate, cue.pose_accel,
                               head=[0.0, 0.0, 0.3])
    num = [1.0, 0.0, 0.0, 0.0]
    den = np.polymul([1.0, 2 * zeta * w, w * w], [1.0, wb])
    for axis in range(3):
        u = k * (f[:, axis] - [0.0, 0.0, G][axis])
        # scipy holds u[k] over [t_k, t_k+1), the unit over (t_k-1, t_k]
        held = np.append(u[1:], u[-1])
        q, r = np.polydiv(num, den)  # the direct term q and the strictly proper rest
        _, y, _ = signal.lsim((np.trim_zeros(r, "f"), den), held, t, interp=False)
        expected = y + q[0] * u + [0.0, 0.0, G][axis]
        np.testing.assert_allclose(felt.specific_force[:, axis], expected, rtol=0, atol=1e-9,
                                   err_msg=f"axis {axis}")
    assert np.all(felt.angular_velocity == 0)


def test_cueing_rotation_about_the_head_feels_only_gravity():
    """Angular velocity alone (no tilt coordination): the platform turns about the head, which
    stays put, so the head feels gravity turned into the cabin, R^T (0, 0, g), and the platform's
    angular velocity, the cue's angle rates through E (R = Rz Ry Rx) turned into the cabin."""
    platform = stewart.Platform()
    t = np.arange(0.0, 6.0, 0.01)
    w = np.column_stack([0.2 * np.sin(2 * t), 0.15 * np.cos(3 * t), 0.35 * (t > 1)])
    head = np.array([0.1, -0.05, 0.3])
    cue = stewart.cueing(platform, t, np.tile([0.0, 0.0, G], (t.size, 1)), w, tilt_max=0.0,
                         head_x=head[0], head_y=head[1], head_z=head[2])
    assert not cue.limited.any() and np.abs(cue.pose[:, 3:]).max() > 0.02
    felt = stewart.head_motion(platform, cue.pose, cue.pose_rate, cue.pose_accel, head=head)
    for i in range(0, t.size, 37):
        roll, pitch, yaw = cue.pose[i, 3:]
        R = turn((roll, pitch, yaw), 0)
        E = np.array([[np.cos(yaw) * np.cos(pitch), -np.sin(yaw), 0],
                      [np.sin(yaw) * np.cos(pitch), np.cos(yaw), 0],
                      [-np.sin(pitch), 0, 1]])
        np.testing.assert_allclose(felt.specific_force[i], R.T @ [0, 0, G], rtol=0, atol=1e-9)
        np.testing.assert_allclose(felt.angular_velocity[i], R.T @ E @ cue.pose_rate[i, 3:],
                                   rtol=0, atol=1e-12)


def test_bad_input_is_refused_by_name():
    platform = stewart.Platform()
    pose = np.array([[0, 0, 0.5, 0, 0, 0]] * 2, dtype=float)
    zero = np.zeros((2, 6))
    bad = pose.copy()
    bad[1, 4] = np.nan
    with pytest.raises(ValueError, match=r"pose\[1, 4\]"):
        stewart.head_motion(platform, bad, zero, zero)
    with pytest.raises(ValueError, match="pose_accel has 1 rows"):
        stewart.head_motion(platform, pose, zero, zero[:1])
    with pytest.raises(ValueError, match="head"):
        stewart.head_motion(platform, pose, zero, zero, head=[0, 1])
    with pytest.raises(TypeError, match="Platform"):
        stewart.head_motion("thesis.json", pose, zero, zero)
    with pytest.raises(ValueError, match="overflows"):
        stewart.head_motion(platform, pose, zero + 1e300, zero + 1e300, head=[1e3, 0, 0])


def test_a_z_down_machine_feels_what_its_z_up_twin_feels():
    """frame_convention 1 (the same machine stated z down, y right): its cue comes back in its own
    frames, and the same physical head, given in each machine's platform frame (z down: (x, -y,
    -z)) to the cueing unit and to head_motion, feels the same as on the z-up twin, in the
    cabin's x forward, y left, z up."""
    t = np.arange(0.0, 6.0, 0.01)
    f = np.tile([0.0, 0.0, G], (t.size, 1))
    f[:, 0] += 1.5 * np.sin(1.1 * t)
    f[:, 1] += 1.0 * (t > 2)
    w = np.column_stack([0.2 * np.sin(2 * t), 0.15 * np.cos(3 * t), 0.35 * (t > 1)])
    head = [0.1, -0.05, 0.3]
    down = stewart.Platform(frame_convention=1, **{k: FRAMES["z down"][k]
                                                    for k in ("base_angle", "platform_angle")})
    felt = []
    for platform, h in ((stewart.Platform(), head), (down, [head[0], -head[1], -head[2]])):
        cue = stewart.cueing(platform, t, f, w, head_x=h[0], head_y=h[1], head_z=h[2])
        felt.append(stewart.head_motion(platform, cue.pose, cue.pose_rate, cue.pose_accel,
                                        head=h))
    assert np.ptp(felt[0].specific_force[:, 1]) > 0.1
    for a, b in zip(*felt):
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-12)
