"""The limit check and the axis ranges (Platform.limits, Platform.axis_ranges) against
computations written here: joint positions, lengths, joint angles and the leg Jacobian from the
parameters in numpy; leg interference against a brute-force segment distance; each limit class
triggered alone by a constructed pose; axis ranges against a fine march and bisection on the
check, on random poses of random geometries."""
import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")

THESIS = dict(base_radius=0.5, platform_radius=0.5, home_height=0.5,
              base_angle=np.radians([0, 30, 120, 150, 240, 270]),
              platform_angle=np.radians([330, 60, 90, 180, 210, 300]))
# Limits that no pose below reaches, so that one class at a time can be switched on.
LOOSE = dict(stroke_min=0.05, stroke_max=3.0, base_joint_limit=np.pi, platform_joint_limit=np.pi,
             leg_diameter=0.0)
LOOSE_CONDITION = 1e300
STROKE, BASE_JOINT, PLATFORM_JOINT, INTERFERENCE, CONDITION = 1, 2, 3, 4, 5


def geometry(p):
    """Base joints a (6, 3) in the base frame and platform joints b (6, 3) in the platform frame
    from the circles' parameters."""
    def circle(r, angles):
        angles = np.asarray(angles)
        return np.column_stack([r * np.cos(angles), r * np.sin(angles), np.zeros(6)])
    return circle(p["base_radius"], p["base_angle"]), circle(p["platform_radius"], p["platform_angle"])


def rotation(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def legs(p, q):
    """Base joints, platform joints in the world, R, for pose q."""
    a, b = geometry(p)
    R = rotation(*q[3:])
    return a, q[:3] + b @ R.T, R


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def angle(u, v):
    return np.arccos(np.clip(np.sum(unit(u) * unit(v), axis=-1), -1.0, 1.0))


def home_directions(p):
    a, top, _ = legs(p, np.array([0, 0, p["home_height"], 0, 0, 0]))
    return unit(top - a)


def point_segment_distance(points, s0, s1):
    """Distance of each of points (n, 3) to the segment [s0, s1], in closed form."""
    d = s1 - s0
    t = np.clip((points - s0) @ d / (d @ d), 0.0, 1.0)
    return np.linalg.norm(points - (s0 + t[:, None] * d), axis=1)


def brute_segment_distance(p0, p1, q0, q1, samples=200001):
    """Shortest distance between two segments: one sampled densely, the other exactly."""
    s = np.linspace(0.0, 1.0, samples)[:, None]
    return point_segment_distance(p0 + s * (p1 - p0), q0, q1).min()


def jacobian_condition(p, q):
    """cond_1 of the leg Jacobian with its angular columns divided by the platform radius."""
    a, top, R = legs(p, q)
    n = unit(top - a)
    arm = top - q[:3]
    JT = np.vstack([n.T, np.cross(arm, n).T / p["platform_radius"]])
    return np.linalg.norm(JT, np.inf) * np.linalg.norm(np.linalg.inv(JT), np.inf)


def platform(**changes):
    return stewart.Platform(**(THESIS | LOOSE | changes))


def params_of(**changes):
    return THESIS | LOOSE | changes


def test_stroke_alone_with_its_margin():
    p = params_of(stroke_min=0.40, stroke_max=0.70)
    q = np.array([0.05, -0.02, 0.62, 0.0, 0.0, 0.1])
    a, top, _ = legs(p, q)
    L = np.linalg.norm(top - a, axis=1)
    expected = np.minimum(L - 0.40, 0.70 - L).min()
    assert expected < 0  # the pose was made to stretch a leg beyond stroke_max
    r = platform(stroke_min=0.40, stroke_max=0.70).limits(q, warn_condition=LOOSE_CONDITION)
    assert r.first[0] == STROKE and r.failed[0] == 1 << (STROKE - 1)
    assert r.margin[0, 0] == pytest.approx(expected, abs=1e-14)
    assert r.leg[0, 0] == 1 + np.argmin(np.minimum(L - 0.40, 0.70 - L))


def test_base_joint_alone_with_its_margin():
    p = params_of(base_joint_limit=np.radians(5))
    q = np.array([0.06, 0.03, 0.5, 0.0, 0.0, 0.0])  # a pure translation: platform joints turn as much
    a, top, _ = legs(p, q)
    angles = angle(top - a, home_directions(p))
    r = platform(base_joint_limit=np.radians(5)).limits(q, warn_condition=LOOSE_CONDITION)
    assert angles.max() > np.radians(5)
    assert r.first[0] == BASE_JOINT and r.failed[0] == 1 << (BASE_JOINT - 1)
    assert r.margin[0, 1] == pytest.approx(np.radians(5) - angles.max(), abs=1e-12)
    assert r.leg[0, 1] == 1 + np.argmax(angles)


def test_platform_joint_alone_with_its_margin_and_given_neutral_axes():
    rng = np.random.default_rng(5)
    neutral = rng.normal(size=(6, 3)) * 0.1 + np.array([0, 0, 1.0])  # any length: made unit
    p = params_of(platform_joint_limit=0.3, platform_joint_neutral=neutral.ravel())
    q = np.array([0.01, 0.02, 0.52, 0.2, -0.1, 0.15])
    a, top, R = legs(p, q)
    angles = angle(top - a, neutral @ R.T)  # the platform's neutral axes turn with it
    r = platform(platform_joint_limit=0.3, platform_joint_neutral=neutral.ravel()).limits(
        q, warn_condition=LOOSE_CONDITION)
    assert angles.max() > 0.3
    assert r.first[0] == PLATFORM_JOINT and r.failed[0] == 1 << (PLATFORM_JOINT - 1)
    assert r.margin[0, 2] == pytest.approx(0.3 - angles.max(), abs=1e-12)
    # the base joints' margin too, for the default neutral axes, although loose
    assert r.margin[0, 1] == pytest.approx(np.pi - angle(top - a, home_directions(p)).max(), abs=1e-12)


def test_interference_alone_and_against_brute_force():
    # The thesis legs stay 0.26 m apart (their joints' spacing) until a large yaw leans
    # neighbours together: 0.234 m at yaw = 1 rad, within a leg 0.24 m thick.
    q = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 1.0])
    p = params_of(leg_diameter=0.24)
    a, top, _ = legs(p, q)
    pairs = [(i, j) for i in range(6) for j in range(i + 1, 6)]
    d = [brute_segment_distance(a[i], top[i], a[j], top[j]) for i, j in pairs]
    assert min(d) < 0.24
    r = platform(leg_diameter=0.24).limits(q, warn_condition=LOOSE_CONDITION)
    assert r.first[0] == INTERFERENCE and r.failed[0] == 1 << (INTERFERENCE - 1)
    assert r.margin[0, 3] == pytest.approx(min(d) - 0.24, abs=1e-9)
    # the pair named is a closest one (the thesis' threefold symmetry ties three)
    named = pairs.index((r.leg[0, 3] - 1, r.other_leg[0, 3] - 1))
    assert d[named] == pytest.approx(min(d), abs=1e-9)


def test_interference_margin_on_random_poses_matches_brute_force():
    rng = np.random.default_rng(19)
    q = np.column_stack([rng.uniform(-0.1, 0.1, (40, 2)), rng.uniform(0.35, 0.65, 40),
                         rng.uniform(-0.4, 0.4, (40, 2)), rng.uniform(-1.5, 1.5, 40)])
    p = params_of(leg_diameter=0.02)
    r = platform(leg_diameter=0.02).limits(q)
    for row, pose in enumerate(q):
        a, top, _ = legs(p, pose)
        d = min(brute_segment_distance(a[i], top[i], a[j], top[j], 20001)
                for i in range(6) for j in range(i + 1, 6))
        assert r.margin[row, 3] + 0.02 == pytest.approx(d, abs=1e-8), row


def test_every_leg_s_own_margin_to_every_class():
    """leg_margin: each leg's margin per class against numpy (stroke, joint angles to the
    neutral axes, interference the smallest brute-force distance over the leg's pairs), the
    class margin its smallest, condition and axis the pose's at every leg."""
    rng = np.random.default_rng(23)
    q = np.column_stack([rng.uniform(-0.05, 0.05, (12, 2)), rng.uniform(0.45, 0.6, 12),
                         rng.uniform(-0.2, 0.2, (12, 2)), rng.uniform(-1.0, 1.0, 12)])
    changes = dict(stroke_min=0.40, stroke_max=0.70, base_joint_limit=0.5,
                   platform_joint_limit=0.6, leg_diameter=0.05, axis_max=[0.04] * 6)
    p = params_of(**changes)
    r = platform(**changes).limits(q)
    assert r.leg_margin.shape == (12, 10, 6)
    for row, pose in enumerate(q):
        a, top, R = legs(p, pose)
        L = np.linalg.norm(top - a, axis=1)
        np.testing.assert_allclose(r.leg_margin[row, 0], np.minimum(L - 0.40, 0.70 - L),
                                   rtol=0, atol=1e-14)
        np.testing.assert_allclose(r.leg_margin[row, 1],
                                   0.5 - angle(top - a, home_directions(p)), rtol=0, atol=1e-12)
        np.testing.assert_allclose(r.leg_margin[row, 2],
                                   0.6 - angle(top - a, home_directions(p) @ R.T), rtol=0,
                                   atol=1e-12)
        pair = np.full((6, 6), np.inf)
        for i in range(6):
            for j in range(i + 1, 6):
                pair[i, j] = pair[j, i] = brute_segment_distance(a[i], top[i], a[j], top[j],
                                                                 20001) - 0.05
        np.testing.assert_allclose(r.leg_margin[row, 3], pair.min(axis=1), rtol=0, atol=1e-8)
        for c in (4, 5):  # condition and axis: the pose's margin at every leg
            assert np.all(r.leg_margin[row, c] == r.margin[row, c])
    assert np.array_equal(r.margin, r.leg_margin.min(axis=2))
    for c in (0, 1, 2):  # the leg named is one whose own margin is the class margin
        named = np.take_along_axis(r.leg_margin[:, c], r.leg[:, c, None] - 1, axis=1)[:, 0]
        assert np.array_equal(named, r.margin[:, c])


def test_condition_alone_with_its_margin():
    q = np.array([0.02, -0.03, 0.45, 0.1, 0.05, -0.2])
    p = params_of()
    cond = jacobian_condition(p, q)
    limit = 0.9 * cond
    r = platform().limits(q, warn_condition=limit)
    assert r.first[0] == CONDITION and r.failed[0] == 1 << (CONDITION - 1)
    assert r.condition[0] == pytest.approx(cond, rel=1e-10)
    assert r.margin[0, 4] == pytest.approx(1 / cond - 1 / limit, rel=1e-9)
    assert platform().limits(q, warn_condition=1.1 * cond).failed[0] == 0


def test_first_class_is_the_first_in_check_order_and_every_failure_is_flagged():
    q = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 1.0])
    a, top, _ = legs(params_of(), q)
    too_short = 0.99 * np.linalg.norm(top - a, axis=1).max()
    r = platform(leg_diameter=0.24, stroke_max=too_short).limits(q, warn_condition=LOOSE_CONDITION)
    assert r.failed[0] == (1 << (STROKE - 1)) | (1 << (INTERFERENCE - 1))
    assert r.first[0] == STROKE


def test_home_is_within_the_default_limits_with_positive_margins():
    r = stewart.Platform().limits([0, 0, 0.5, 0, 0, 0])
    assert r.within[0] and (r.margin[0] > 0).all()
    assert r.margin[0, 1] == pytest.approx(np.pi / 2, abs=1e-12)  # the neutral axes are home's


def test_non_finite_pose_and_bad_option_are_refused_by_name():
    with pytest.raises(ValueError, match="pitch"):
        stewart.Platform().limits([0, 0, 0.5, 0, np.nan, 0])
    with pytest.raises(ValueError, match="yaw"):
        stewart.Platform().axis_ranges([[0, 0, 0.5, 0, 0, 0], [0, 0, 0.5, 0, 0, np.inf]])
    with pytest.raises(stewart.ParameterError, match="warn_condition"):
        stewart.Platform().limits([0, 0, 0.5, 0, 0, 0], warn_condition=0.5)


def test_poses_are_the_tool_frames_in_the_user_frame():
    """With a tool 0.1 m above the platform and turned, and a user frame shifted and turned about
    z, a tool pose checks as the platform pose worked out here by hand."""
    frames = dict(tool_frame=[0.0, 0.02, 0.1, 0.0, 0.0, 0.3], user_frame=[0.05, 0.0, 0.01, 0.0, 0.0, 0.2])
    q_tool = np.array([0.01, -0.02, 0.42, 0.05, 0.04, 0.1])
    Ru, Rt = rotation(0, 0, 0.2), rotation(0, 0, 0.3)
    R_tool_base = Ru @ rotation(*q_tool[3:])            # tool axes in the base frame
    R_platform = R_tool_base @ Rt.T
    position = np.array([0.05, 0.0, 0.01]) + Ru @ q_tool[:3] - R_platform @ np.array([0.0, 0.02, 0.1])
    pitch = -np.arcsin(R_platform[2, 0])
    roll, yaw = np.arctan2(R_platform[2, 1], R_platform[2, 2]), np.arctan2(R_platform[1, 0], R_platform[0, 0])
    q_platform = np.concatenate([position, [roll, pitch, yaw]])
    with_frames = stewart.Platform(**frames).limits(q_tool)
    without = stewart.Platform().limits(q_platform)
    np.testing.assert_allclose(with_frames.margin, without.margin, atol=1e-12)


def test_pose_beyond_a_limit_has_empty_ranges():
    q = np.array([0.0, 0.0, 0.8, 0.1, 0.0, 0.0])
    r = stewart.Platform().axis_ranges(q, details=True)
    np.testing.assert_array_equal(r.ends[0, :, 0], q)
    np.testing.assert_array_equal(r.ends[0, :, 1], q)
    assert (r.limit[0] == STROKE).all()


# ---------------------------------------------------------------- axis ranges against a march

def march_and_bisect(plat, q, axis, sign, extent, warn_condition, step):
    """The end of the axis range on one side by the check alone: a march of fixed steps (all
    poses in one batch), then bisection to 1e-10 between the last pose within and the first
    beyond. Returns (end, class met, 0 if none before extent)."""
    t = np.arange(step, extent + step, step)
    poses = np.repeat(q[None, :], len(t), axis=0)
    poses[:, axis] += sign * t
    r = plat.limits(poses, warn_condition=warn_condition)
    beyond = np.flatnonzero(~r.within)
    if beyond.size == 0:
        return q[axis] + sign * extent, 0
    hi = t[beyond[0]]
    lo = 0.0 if beyond[0] == 0 else t[beyond[0] - 1]
    while hi - lo > 1e-10:
        mid = 0.5 * (lo + hi)
        pose = q.copy()
        pose[axis] += sign * mid
        if plat.limits(pose, warn_condition=warn_condition).within[0]:
            lo = mid
        else:
            hi = mid
    pose = q.copy()
    pose[axis] += sign * hi
    return q[axis] + sign * lo, int(plat.limits(pose, warn_condition=warn_condition).first[0])


def tool_home(height, frames):
    """The tool's pose in the user frame at the platform's home (frames turned about z only)."""
    tool, user = np.asarray(frames["tool_frame"]), np.asarray(frames["user_frame"])
    position = rotation(0, 0, user[5]).T @ (np.array([0, 0, height]) + tool[:3] - user[:3])
    return np.concatenate([position, [0.0, 0.0, tool[5] - user[5]]])


def random_platform(rng, paired):
    """Random radii, angles, height and limits tight enough that every class shows up; paired:
    joints in close pairs as commercial hexapods have them (legs that can touch), else anywhere."""
    if paired:
        centres = rng.uniform(0, 2 * np.pi) + np.radians([0, 120, 240])
        spread = rng.uniform(np.radians(4), np.radians(15), 2)
        base = np.ravel([[c - spread[0], c + spread[0]] for c in centres])
        top = np.roll(np.ravel([[c + np.pi / 3 - spread[1], c + np.pi / 3 + spread[1]] for c in centres]), 1)
    else:
        base = np.sort(rng.uniform(0, 2 * np.pi, 6))
        top = np.sort(rng.uniform(0, 2 * np.pi, 6))
    p = dict(base_radius=rng.uniform(0.3, 0.7), platform_radius=rng.uniform(0.2, 0.5),
             home_height=rng.uniform(0.4, 0.7), base_angle=base, platform_angle=top)
    a, b = geometry(p)
    L0 = np.linalg.norm(np.array([0, 0, p["home_height"]]) + b - a, axis=1)
    top_home = np.array([0, 0, p["home_height"]]) + b
    closest = min(brute_segment_distance(a[i], top_home[i], a[j], top_home[j], 2001)
                  for i in range(6) for j in range(i + 1, 6))
    p |= dict(stroke_min=0.8 * L0.min(), stroke_max=1.25 * L0.max(),
              base_joint_limit=rng.uniform(0.25, 0.6), platform_joint_limit=rng.uniform(0.25, 0.6),
              leg_diameter=rng.uniform(0.7, 0.95) * closest)
    return p


@pytest.mark.parametrize("seed", range(10))
def test_axis_ranges_match_a_march_and_bisection_on_the_check(seed):
    rng = np.random.default_rng(seed)
    for _ in range(200):  # a geometry whose home is well within its limits
        p = random_platform(rng, paired=seed < 4)
        home = np.array([0, 0, p["home_height"], 0, 0, 0])
        frames = {}
        if seed >= 8:  # the axes are a tool frame's (0.1 m off the platform origin) in a user frame
            frames = dict(tool_frame=[0.03, 0.0, 0.1, 0.0, 0.0, 0.4],
                          user_frame=[0.0, 0.02, 0.0, 0.0, 0.0, 0.5])
            home = tool_home(home[2], frames)
        plat = stewart.Platform(**p, **frames)
        at_home = plat.limits(home)
        if at_home.within[0] and at_home.margin[0, :4].min() > 0.002:
            break
    else:
        pytest.fail("no random geometry within its limits at home")
    # a tight condition limit on every other geometry: 1.5 times home's condition
    warn = 1.5 * at_home.condition[0] if seed % 2 else None
    poses = []
    for _ in range(1000):
        q = home + np.concatenate([rng.uniform(-0.05, 0.05, 3), rng.uniform(-0.1, 0.1, 3)])
        if plat.limits(q, warn_condition=warn).within[0]:
            poses.append(q)
        if len(poses) == 3:
            break
    assert len(poses) == 3, "no pose near home within the limits"
    r = plat.axis_ranges(np.array(poses), warn_condition=warn, details=True)
    for row, q in enumerate(poses):
        for axis in range(6):
            extent = np.pi if axis >= 3 else 2 * p["stroke_max"] + 2e-5
            for side, sign in ((0, -1.0), (1, 1.0)):
                end, met = march_and_bisect(plat, q, axis, sign, extent, warn, 2e-4 if axis < 3 else 5e-4)
                got = r.ends[row, axis, side]
                where = f"seed {seed} pose {row} axis {axis} side {side}"
                if met == 0:
                    assert got == pytest.approx(end, abs=1e-9), where
                    continue
                # within 1e-6 inside the end, never beyond it
                assert sign * (end - got) >= -1e-9 and sign * (end - got) <= 1.05e-6, (where, got, end)
                assert r.limit[row, axis, side] == met, where


def test_axis_range_meets_a_condition_excursion_narrower_than_a_march_step():
    """Yaw 0.02 rad short of the thesis platform's singular 90 deg, nothing but the condition
    limited: the condition number rises above warn_condition = 1e3 only for yaw within about
    4.5e-3 rad of 90 deg and falls below it beyond, an excursion 9e-3 rad wide that a march of
    0.05 rad steps (the search before stop 26) steps over. The end against a march of 5e-4 rad
    with bisection on the check, and the condition at both sides of it against numpy."""
    plat, p, warn = platform(), params_of(), 1e3
    for yaw in (np.pi / 2 - 0.02, np.pi / 2 - 0.011):
        q = np.array([0.0, 0.0, 0.5, 0.0, 0.0, yaw])
        assert jacobian_condition(p, q) < warn
        r = plat.axis_ranges(q, warn_condition=warn, details=True)
        end, met = march_and_bisect(plat, q, 5, 1.0, np.pi, warn, 5e-4)
        assert met == CONDITION
        got = r.ends[0, 5, 1]
        assert -1e-9 <= end - got <= 1.05e-6, (yaw, got, end)
        assert r.limit[0, 5, 1] == CONDITION
        inside, outside = q.copy(), q.copy()
        inside[5], outside[5] = got, got + 2e-6
        assert jacobian_condition(p, inside) <= warn < jacobian_condition(p, outside)


@pytest.mark.parametrize("axis", range(6))
def test_axis_ranges_meet_narrow_condition_excursions_along_every_axis(axis):
    """Poses 0.01 to 0.04 rad from the yaw singularity moved along each axis, a condition limit
    1.5 to 6 times their own: every end within 0.3 against a dense march (1e-4) and bisection
    on the check (beyond 32 condition-limited steps a side's condition steps are 5e-3: none of
    these excursions is narrower)."""
    plat = platform()
    rng = np.random.default_rng(100 + axis)
    for _ in range(4):
        yaw = np.pi / 2 + rng.choice([-1, 1]) * rng.uniform(0.01, 0.04)
        q = np.array([*rng.uniform(-0.02, 0.02, 2), 0.5 + rng.uniform(-0.02, 0.02),
                      *rng.uniform(-0.02, 0.02, 2), yaw])
        warn = float(plat.limits(q, warn_condition=1e300).condition[0]) * rng.uniform(1.5, 6.0)
        r = plat.axis_ranges(q, warn_condition=warn, details=True)
        extent = np.pi if axis >= 3 else 2 * 3.0 + 2e-5
        for side, sign in ((0, -1.0), (1, 1.0)):
            end, met = march_and_bisect(plat, q, axis, sign, min(extent, 0.3), warn, 1e-4)
            got = r.ends[0, axis, side]
            if met == 0:  # nothing within the scanned 0.3: the range reaches beyond it
                assert sign * (got - q[axis]) >= 0.3 - 1e-9
                continue
            assert -1e-9 <= sign * (end - got) <= 1.05e-6, (q, axis, side, got, end, met)
            assert r.limit[0, axis, side] == met
