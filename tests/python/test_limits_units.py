"""The limits where the units report them: the inverse FMU's limit outputs (limit_outputs = 1,
2) against Platform.limits and Platform.axis_ranges (themselves checked against numpy in
test_limits.py), zero and silent when off; stewart-solve --limits --ranges the same numbers;
the plant's joint-limit and interference warning bits against the check of its output pose."""
import csv

import numpy as np
import pytest

from fmu_support import OK, WARNING, VERSIONS, Unit, opened_unit

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")

MARGINS = tuple(f"limit_margin[{c}]" for c in range(1, 7))
RANGE_MIN = tuple(f"range_min[{a}]" for a in range(1, 7))
RANGE_MAX = tuple(f"range_max[{a}]" for a in range(1, 7))
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
# A pose within the default limits, and one whose base joints lean beyond 0.2 rad.
WITHIN = np.array([0.02, -0.01, 0.52, 0.03, -0.02, 0.05])
LEANING = np.array([0.12, 0.0, 0.45, 0.0, 0.0, 0.0])


def solve_once(version, pose, **params):
    with opened_unit(version) as u:
        assert u.init(**params) == OK
        u.set(**dict(zip(POSE, pose)))
        status = u.do_step(0.0, 0.1)
        reals = u.get_reals(MARGINS + RANGE_MIN + RANGE_MAX)
        (limit_class,) = u.get(("limit_class",))
        return status, limit_class, reals, u.messages_text()


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_limit_outputs_are_the_library_check_and_ranges(version):
    status, limit_class, reals, _ = solve_once(version, WITHIN, limit_outputs=2, fidelity=1)
    assert status == OK and limit_class == 0
    check = stewart.Platform().limits(WITHIN)
    ranges = stewart.Platform().axis_ranges(WITHIN)[0]
    np.testing.assert_array_equal(reals[:6], check.margin[0, :6])
    np.testing.assert_array_equal(reals[6:12], ranges[:, 0])
    np.testing.assert_array_equal(reals[12:], ranges[:, 1])


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_limit_outputs_off_by_default_and_ranges_only_at_level_2(version):
    status, limit_class, reals, log = solve_once(version, LEANING, base_joint_limit=0.2, fidelity=1)
    assert status == OK and limit_class == 0 and not reals.any() and "joint" not in log
    status, limit_class, reals, log = solve_once(version, LEANING, base_joint_limit=0.2,
                                                 limit_outputs=1, fidelity=1)
    assert status == WARNING and limit_class == 2  # the base joint
    assert reals[1] == pytest.approx(stewart.Platform(base_joint_limit=0.2).limits(LEANING).margin[0, 1])
    assert not reals[6:].any()
    assert "base joint of leg" in log


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_software_position_limit(version):
    """A pose past axis_max[3] (z): class 6 with its margin, a Warning naming the axis, and the
    z range ending on the limit; as the library's."""
    limits = {"axis_max[3]": 0.51, "axis_min[3]": 0.45}
    status, limit_class, reals, log = solve_once(version, WITHIN, limit_outputs=2, fidelity=1,
                                                 **limits)
    assert status == WARNING and limit_class == 6
    assert reals[5] == pytest.approx(0.51 - WITHIN[2], abs=1e-15)
    assert "z is" in log and "software position limit" in log
    below = WITHIN.copy()
    below[2] = 0.5
    status, limit_class, reals, _ = solve_once(version, below, limit_outputs=2, fidelity=1, **limits)
    plat = stewart.Platform(axis_max=[1e300, 1e300, 0.51, 1e300, 1e300, 1e300],
                            axis_min=[-1e300, -1e300, 0.45, -1e300, -1e300, -1e300])
    assert status == OK and limit_class == 0
    np.testing.assert_array_equal(reals[:6], plat.limits(below).margin[0, :6])
    assert reals[6 + 2] == 0.45 and reals[12 + 2] == 0.51


def test_cli_limits_and_ranges_columns(solve, tmp_path):
    poses = np.array([WITHIN, LEANING])
    src = tmp_path / "in.csv"
    src.write_text("t,x,y,z,roll,pitch,yaw\n" +
                   "".join(f"{i * 0.1},{','.join(repr(float(v)) for v in p)}\n" for i, p in enumerate(poses)))
    out = tmp_path / "out.csv"
    r = solve("--limits", "--ranges", "--param", "base_joint_limit=0.2", src, out)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(out.open()))
    plat = stewart.Platform(base_joint_limit=0.2)
    check, ranges = plat.limits(poses), plat.axis_ranges(poses)
    names = ("stroke", "base_joint", "platform_joint", "interference", "condition", "axis")
    for j, row in enumerate(rows):
        assert row["limit_class"] == stewart.limits.class_name(check.first[j])
        np.testing.assert_array_equal([float(row[f"margin_{n}"]) for n in names], check.margin[j, :6])
        np.testing.assert_array_equal([float(row[f"{a}_min"]) for a in POSE], ranges[j, :, 0])
        np.testing.assert_array_equal([float(row[f"{a}_max"]) for a in POSE], ranges[j, :, 1])
    assert [row["limit_class"] for row in rows] == ["none", "base_joint"]


def test_plant_warns_of_joint_limits_and_interference_as_of_strokes():
    """The platform falls freely from home turned by 0.8 rad of yaw (no forces): its legs lean
    further and neighbours come together; the warning bits follow the check of each output
    pose, and both switch on during the fall."""
    params = dict(base_joint_limit=0.8, platform_joint_limit=0.8, leg_diameter=0.245,
                  stroke_min=0.05, stroke_max=3.0)
    plat = stewart.Platform(**params)
    t = np.linspace(0.0, 0.35, 36)
    sim = plat.simulate(t, np.zeros((len(t), 6)), fidelity="massless",
                        start=[0.0, 0.0, 0.5, 0.0, 0.0, 0.8])
    assert sim.completed, sim.message
    check = plat.limits(sim.pose)
    joint_bits = (check.failed & 0b0110) != 0
    interference = (check.failed & 0b1000) != 0
    np.testing.assert_array_equal((sim.warnings & 8) != 0, joint_bits)
    np.testing.assert_array_equal((sim.warnings & 16) != 0, interference)
    for bits in (joint_bits, interference):
        assert not bits[0] and bits[-1]


def longest_arm(platform):
    """The largest distance from the tool origin to a platform joint (platform frame) [m]."""
    from stewart import _core
    _, top = _core.model_joints(platform._model)
    tool = np.broadcast_to(platform.params.get("tool_frame", 0.0), (6,))[:3]
    return float(np.linalg.norm(np.reshape(top, (6, 3)) - tool, axis=1).max())


@pytest.mark.parametrize("name", sorted(stewart.platform_files()))
def test_axis_margin_is_one_axis_in_its_own_unit(name):
    """Software position limits 10 mm from home in x and a roll limit whose arc at the farthest
    platform joint is 9 mm (then 11 mm): the axis class names roll with its margin in rad (then x
    with its margin in m), whichever number is smaller in m or rad."""
    path = stewart.platform_files()[name]
    home = stewart.Platform.from_file(path).check().home
    arm = longest_arm(stewart.Platform.from_file(path))
    for factor, axis, margin in ((0.9, 4, 0.009 / arm), (1.1, 1, 0.01)):
        angle = factor * 0.01 / arm
        low, high = np.full(6, -1e300), np.full(6, 1e300)
        low[0], high[0] = home[0] - 0.01, home[0] + 0.01
        low[3], high[3] = home[3] - angle, home[3] + angle
        platform = stewart.Platform.from_file(path, axis_min=low.tolist(),
                                              axis_max=high.tolist())
        check = platform.limits(home)
        assert check.leg[0, 5] == axis, (factor, check.margin[0, 5], arm)
        assert check.margin[0, 5] == pytest.approx(margin, rel=1e-9)
        assert check.within[0]


def test_smallest_axis_margin_over_poses_is_ranked_as_the_library_ranks_axes():
    """Over two poses of the Rubin camera hexapod (arm 2.7 m): x 5 mm from its limit at one,
    roll 8 mm of arc (2.9 mrad) from its at the other. The smallest axis margin of the two (a
    sweep's margin_axis) is the 5 mm, not the number 0.0029 of the other unit."""
    from stewart.limits import smallest_margins
    path = stewart.platform_files()["rubin_camera_hexapod"]
    home = stewart.Platform.from_file(path).check().home
    arm = longest_arm(stewart.Platform.from_file(path))
    low, high = np.full(6, -1e300), np.full(6, 1e300)
    low[0], high[0] = home[0] - 0.01, home[0] + 0.01
    low[3], high[3] = home[3] - 0.01 / arm, home[3] + 0.01 / arm
    platform = stewart.Platform.from_file(path, axis_min=low.tolist(), axis_max=high.tolist())
    a, b = home.copy(), home.copy()
    a[0] += 0.005
    b[3] += 0.002 / arm
    check = platform.limits(np.array([a, b]))
    assert check.within.all() and list(check.leg[:, 5]) == [1, 4]
    assert check.margin[1, 5] < 0.005  # the other unit's number is the smaller one
    assert smallest_margins(platform, check)[5] == pytest.approx(0.005, rel=1e-9)
    np.testing.assert_array_equal(smallest_margins(platform, check)[:5], check.margin.min(axis=0)[:5])


def _turned_z_down(data):
    """A z-up platform file's fields (no Cardan axes or frame angles) in z-down frames
    (frame_convention 1): every joint, centre of mass and frame origin (x, y, z) -> (x, -y, -z)."""
    turn = np.array([1.0, -1.0, -1.0])
    out = dict(data, frame_convention=1)
    for name in ("base_joint", "platform_joint"):
        out[name] = (np.reshape(data[name], (6, 3)) * turn).ravel().tolist()
    for name in ("payload_com", "platform_com"):
        if name in data:
            out[name] = (np.asarray(data[name]) * turn).tolist()
    for name in ("tool_frame", "user_frame"):
        assert not np.any(data[name][3:])
        out[name] = (np.asarray(data[name][:3]) * turn).tolist() + [0.0, 0.0, 0.0]
    return out


def _rubin_camera_as(how):
    """The Rubin camera hexapod (its pivot 2.6 m below the top joints) with its tool frame given
    as `how` says: "file" (the shipped file), "elements" (each tool_frame[k] by its own name, as
    a sweep spec or Platform(**params) gives them), "z_down" (the same machine in z-down
    frames); a function of the axis limits to a Platform."""
    data = stewart.params.read_platform_file(stewart.platform_files()["rubin_camera_hexapod"])
    if how == "elements":
        tool = data.pop("tool_frame")
        data.update({f"tool_frame[{k}]": v for k, v in enumerate(tool, start=1)})
    elif how == "z_down":
        data = _turned_z_down(data)
    return lambda **limits: stewart.Platform(**data, **limits)


@pytest.mark.parametrize("how", ["file", "elements", "z_down"])
def test_smallest_axis_margin_ranks_as_the_library_whatever_way_the_tool_frame_is_given(how):
    """Poses a (x 1.5 mm from its limit) and b (yaw 1 mrad from its): which is nearer its limit
    is the library's own answer at the pose c with both (its check ranks an angle through the
    arm from the tool origin, 2.7 m here, 0.7 m without the pivot: 1 mrad is then 2.7 mm, farther
    than 1.5 mm). smallest_margins over a and b gives the margin the library gives at c."""
    from stewart.limits import smallest_margins
    make = _rubin_camera_as(how)
    home = make().check().home
    d, theta = 0.0015, 0.001
    low, high = home - 1.0, home + 1.0  # far, but for x and yaw (2 d and 2 theta above home)
    high[0], high[5] = home[0] + 2 * d, home[5] + 2 * theta
    platform = make(axis_min=low.tolist(), axis_max=high.tolist())
    a, b, c = home.copy(), home.copy(), home.copy()
    a[0] += d
    b[5] += theta
    c[0] += d
    c[5] += theta
    library = platform.limits(c[None, :])
    assert library.within[0] and library.leg[0, 5] == 1, library.margin[0]  # x: the pivot counts
    check = platform.limits(np.array([a, b]))
    assert check.within.all() and list(check.leg[:, 5]) == [1, 6]
    assert smallest_margins(platform, check)[5] == pytest.approx(library.margin[0, 5], rel=1e-9)
