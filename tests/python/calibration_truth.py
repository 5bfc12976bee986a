"""The calibration tests' own model of a machine, written here from docs/model.md and the issue
(independent of the library): closed-form sensor readings at a pose of the tool frame in the user
frame, a tracker's noisy measurement of that pose, and forward kinematics by Newton's method with
finite-difference derivatives."""
import numpy as np

THESIS_BASE_ANGLES = np.radians([0, 30, 120, 150, 240, 270])
THESIS_PLATFORM_ANGLES = np.radians([330, 60, 90, 180, 210, 300])


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = (np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch),
                              np.cos(yaw), np.sin(yaw))
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def angles(R):
    """(roll, pitch, yaw) of R = Rz Ry Rx (|pitch| < 90 deg)."""
    return np.array([np.arctan2(R[2, 1], R[2, 2]), -np.arcsin(R[2, 0]),
                     np.arctan2(R[1, 0], R[0, 0])])


def thesis_joints():
    """The thesis platform's joints (radius 0.5 m, z 0), (6, 3) each."""
    def circle(a):
        return np.stack([0.5 * np.cos(a), 0.5 * np.sin(a), np.zeros(6)], axis=1)
    return circle(THESIS_BASE_ANGLES), circle(THESIS_PLATFORM_ANGLES)


def readings(machine, poses):
    """Sensor readings (N, 6) of machine (dict: base_joint, platform_joint (6, 3), length_offset
    (6,), tool_frame, user_frame (6,)) at poses (N, 6) of the tool frame in the user frame."""
    a, b = machine["base_joint"], machine["platform_joint"]
    t, u = machine["tool_frame"], machine["user_frame"]
    Rt, Ru = rotation(*t[3:]), rotation(*u[3:])
    out = np.empty((len(poses), 6))
    for i, q in enumerate(poses):
        Rq = rotation(*q[3:])
        R = Ru @ Rq @ Rt.T                                   # platform in base
        p = u[:3] + Ru @ (q[:3] - Rq @ Rt.T @ t[:3])         # platform origin in base
        out[i] = np.linalg.norm(p + b @ R.T - a, axis=1) - machine["length_offset"]
    return out


def measured(poses, rng, position_noise=10e-6, angle_noise=20e-6):
    """A tracker's measurement of poses: each position off by N(0, position_noise) per axis, each
    orientation by a small rotation of N(0, angle_noise) per axis (user frame)."""
    out = np.array(poses, dtype=float)
    for row in out:
        row[:3] += rng.normal(0, position_noise, 3)
        w = rng.normal(0, angle_noise, 3)
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        small = np.eye(3) + W + W @ W / 2  # exp(W) to second order: 1e-15 at 20 urad
        row[3:] = angles(small @ rotation(*row[3:]))
    return out


def forward(machine, reading_rows, guess, iterations=20):
    """Poses at which machine reads reading_rows, Newton from guess, derivatives by central
    differences of readings()."""
    q = np.array(guess, dtype=float)
    for i in range(len(q)):
        for _ in range(iterations):
            f = readings(machine, q[i:i + 1])[0] - reading_rows[i]
            if np.max(np.abs(f)) < 1e-14:
                break
            J = np.empty((6, 6))
            for j in range(6):
                h = np.zeros(6)
                h[j] = 1e-7
                J[:, j] = (readings(machine, [q[i] + h])[0]
                           - readings(machine, [q[i] - h])[0]) / 2e-7
            q[i] -= np.linalg.solve(J, f)
    return q


def random_poses(rng, n, home_height=0.5, position=0.08, angle=np.radians(15)):
    """n poses around home: x, y, z within +-position of (0, 0, home_height), angles within
    +-angle (inside the thesis platform's strokes for the defaults)."""
    q = np.empty((n, 6))
    q[:, :3] = rng.uniform(-position, position, (n, 3))
    q[:, 2] += home_height
    q[:, 3:] = rng.uniform(-angle, angle, (n, 3))
    return q


def precision_hexapod():
    """Platform parameters of a precision small-stroke hexapod with a far pivot, written here in
    the style of heavy-payload positioning hexapods (no vendor's data): joints in pairs on
    radii 0.6 m (base) and 0.45 m (platform), the top plate 0.5 m above the base, strokes +-14 mm
    about the home length, and the tool frame (the pivot the moves are commanded about) 2.6 m
    below the top plate."""
    base_angles = np.radians([350, 10, 110, 130, 230, 250])
    platform_angles = np.radians([320, 40, 80, 160, 200, 280])

    def circle(radius, a):
        return np.stack([radius * np.cos(a), radius * np.sin(a), np.zeros(6)], axis=1)
    a, b = circle(0.6, base_angles), circle(0.45, platform_angles)
    home = float(np.linalg.norm(b[0] + [0, 0, 0.5] - a[0]))
    return {"geometry": 1, "base_joint": a.ravel().tolist(), "platform_joint": b.ravel().tolist(),
            "home_height": 0.5, "stroke_min": home - 0.014, "stroke_max": home + 0.014,
            "tool_frame": [0.0, 0.0, -2.6, 0.0, 0.0, 0.0]}


def pose_derivatives(machine, q, h=1e-7):
    """d readings / d (position, small rotation in the user frame) of a measured pose q, by
    central differences of readings()."""
    J = np.empty((6, 6))
    for j in range(3):
        e = np.zeros(6)
        e[j] = h
        J[:, j] = (readings(machine, [q + e])[0] - readings(machine, [q - e])[0]) / (2 * h)
    for j in range(3):
        ends = []
        for sign in (1, -1):
            w = np.zeros(3)
            w[j] = sign * h
            W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
            turned = np.array(q, dtype=float)
            turned[3:] = angles((np.eye(3) + W + W @ W / 2) @ rotation(*q[3:]))
            ends.append(readings(machine, [turned])[0])
        J[:, 3 + j] = (ends[0] - ends[1]) / (2 * h)
    return J


JOINT_KEYS = (("base_joint", 18), ("platform_joint", 18), ("length_offset", 6))


def shifted(machine, theta):
    """machine with its joints and offsets moved by theta (42: base, platform, offsets)."""
    out = {k: np.array(v, dtype=float) for k, v in machine.items()}
    start = 0
    for key, size in JOINT_KEYS:
        out[key] = out[key] + np.reshape(theta[start:start + size], out[key].shape)
        start += size
    return out


def regularised_fit(nominal, poses, reading_rows, joint_tolerance, offset_tolerance,
                    position_noise=10e-6, angle_noise=20e-6, reading_noise=1e-6, iterations=6):
    """The maximum a posteriori joints and offsets of a machine (a dict as readings() takes)
    measured at poses: Gauss-Newton on the readings' residuals whitened by the noise seen
    through their pose derivatives, stacked on the prior rows theta / tolerance, with
    derivatives by central differences and numpy's least squares."""
    tolerance = np.r_[[joint_tolerance] * 36, [offset_tolerance] * 6]
    whiten = []
    for q in poses:
        J = pose_derivatives(nominal, q)
        C = (position_noise ** 2 * J[:, :3] @ J[:, :3].T + angle_noise ** 2 * J[:, 3:] @ J[:, 3:].T
             + reading_noise ** 2 * np.eye(6))
        whiten.append(np.linalg.inv(np.linalg.cholesky(C)))
    whiten = np.array(whiten)
    theta = np.zeros(42)
    for _ in range(iterations):
        f = readings(shifted(nominal, theta), poses)
        J = np.empty((len(poses), 6, 42))
        for j in range(42):
            e = np.zeros(42)
            e[j] = 1e-7
            J[:, :, j] = (readings(shifted(nominal, theta + e), poses)
                          - readings(shifted(nominal, theta - e), poses)) / 2e-7
        r = np.einsum("nij,nj->ni", whiten, reading_rows - f).ravel()
        A = np.vstack([(whiten @ J).reshape(-1, 42), np.diag(1 / tolerance)])
        theta = theta + np.linalg.lstsq(A, np.r_[r, -theta / tolerance], rcond=None)[0]
    return shifted(nominal, theta)


def pose_errors(machine, true_machine, poses):
    """Position [m] and rotation [rad] errors of the poses machine computes (forward()) from the
    readings true_machine gives at poses."""
    found = forward(machine, readings(true_machine, poses), poses)
    position = np.linalg.norm(found[:, :3] - poses[:, :3], axis=1)
    turn = np.array([np.arccos(np.clip((np.trace(rotation(*f[3:]).T @ rotation(*q[3:])) - 1) / 2,
                                       -1, 1)) for f, q in zip(found, poses)])
    return position, turn


def identified_machine(result):
    """The machine (the dict readings takes) a stewart.calibrate result identified."""
    p = result.parameters
    return {"base_joint": p["base_joint"].reshape(6, 3),
            "platform_joint": p["platform_joint"].reshape(6, 3),
            "length_offset": p["length_offset"], "tool_frame": p["tool_frame"],
            "user_frame": p["user_frame"]}
