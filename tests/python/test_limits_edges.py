"""The limits at their edges: axis ranges that never contain a pose the check refuses (sampled
densely inside every reported range, with the check itself), short strokes and neutral axes of
any magnitude, legs that touch, actuators of a body and a rod (against a brute-force distance
written here) and the software position limits per axis."""
import json
import pathlib

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")

from test_limits import brute_segment_distance, legs, unit  # noqa: E402  (numpy references)

PLATFORMS = pathlib.Path(__file__).resolve().parents[2] / "platforms"
STROKE, BASE_JOINT, PLATFORM_JOINT, INTERFERENCE, CONDITION, AXIS = 1, 2, 3, 4, 5, 6
THESIS_HOME = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0])


def refused_inside(plat, poses, ranges, samples=4001, warn_condition=None):
    """Every pose the check refuses on a dense grid inside each reported range (ends
    included): (row, axis, value, class)."""
    found = []
    for row, q in enumerate(poses):
        for axis in range(6):
            lo, hi = ranges[row, axis]
            if hi <= lo:
                continue
            grid = np.repeat(q[None, :], samples, axis=0)
            grid[:, axis] = np.linspace(lo, hi, samples)
            r = plat.limits(grid, warn_condition=warn_condition)
            for i in np.flatnonzero(~r.within):
                found.append((row, axis, grid[i, axis], int(r.first[i])))
    return found


def ordinary_poses(plat, home, n, rng, spread=(0.05, 0.1)):
    poses = []
    while len(poses) < n:
        q = home + np.concatenate([rng.uniform(-spread[0], spread[0], 3),
                                   rng.uniform(-spread[1], spread[1], 3)])
        if plat.limits(q).within[0]:
            poses.append(q)
    return np.array(poses)


def test_the_z_range_at_home_stops_before_the_singular_plane():
    """Thesis platform, stroke_min 0.01: below z ~ 1e-3 the legs lie nearly in the base plane
    and the condition number passes warn_condition (infinite at z = 0); the z range from home
    must end there, not join home to its mirror below the base."""
    plat = stewart.Platform(stroke_min=0.01)
    r = plat.axis_ranges(THESIS_HOME, details=True)
    low = r.ends[0, 2, 0]
    assert low > 0.0, low
    assert r.limit[0, 2, 0] == CONDITION
    # the check refuses a pose just below the end (within the ranges' 1e-6 resolution)
    below = THESIS_HOME.copy()
    below[2] = low - 2e-6
    assert plat.limits(below).first[0] == CONDITION
    assert refused_inside(plat, THESIS_HOME[None, :], r.ends) == []
    # with a condition limit only a singular pose reaches (z = 0 exactly), the range ends within
    # the ranges' 1e-6 of the plane, where det J changes sign, and names the condition
    r = plat.axis_ranges(THESIS_HOME, warn_condition=1e300, details=True)
    assert 0.0 < r.ends[0, 2, 0] < 1e-6 and r.limit[0, 2, 0] == CONDITION


@pytest.mark.parametrize("name, stroke_min", [("thesis", 0.05), ("thesis", 0.01),
                                              ("paired_hexapod", None), ("genhexkins", None)])
def test_no_range_contains_a_refused_pose(name, stroke_min):
    spec = json.loads((PLATFORMS / f"{name}.json").read_text())
    spec.pop("description", None)
    if stroke_min is not None:
        spec["stroke_min"] = stroke_min
    plat = stewart.Platform(**spec)
    home = np.array([0.0, 0.0, spec.get("home_height", 0.5), 0.0, 0.0, 0.0])
    rng = np.random.default_rng(3)
    scale = home[2] / 0.5
    poses = np.vstack([home, ordinary_poses(plat, home, 31, rng, (0.05 * scale, 0.1))])
    ranges = plat.axis_ranges(poses)
    assert refused_inside(plat, poses, ranges) == []


def test_ranges_with_a_tiny_stroke_min_reach_their_limits():
    """stroke_min 1e-6 bounds nothing about how fast a leg turns: the ranges are as wide as
    the other limits allow, each end at a limit the check confirms just beyond it."""
    plat = stewart.Platform(stroke_min=1e-6)
    r = plat.axis_ranges(THESIS_HOME, details=True)
    assert (r.limit[0] != 0).all(), r.limit
    for axis in range(6):
        for side, sign in ((0, -1.0), (1, 1.0)):
            end = r.ends[0, axis, side]
            assert abs(end - THESIS_HOME[axis]) > 0.05, (axis, side, end)
            beyond = THESIS_HOME.copy()
            beyond[axis] = end + sign * 2e-6
            assert plat.limits(beyond).first[0] == r.limit[0, axis, side], (axis, side)
    assert refused_inside(plat, THESIS_HOME[None, :], r.ends) == []


def test_neutral_axes_of_any_magnitude_have_their_own_direction():
    p = dict(base_joint_limit=0.3, platform_joint_limit=0.3)
    a, top, _ = legs(dict(base_radius=0.5, platform_radius=0.5,
                          base_angle=np.radians([0, 30, 120, 150, 240, 270]),
                          platform_angle=np.radians([330, 60, 90, 180, 210, 300])), THESIS_HOME)
    home = unit(top - a)
    tilted = unit(home + np.array([0.05, -0.03, 0.0]))
    q = np.array([0.03, 0.01, 0.5, 0.02, 0.0, 0.05])
    unit_axes = stewart.Platform(**p, base_joint_neutral=tilted.ravel())
    reference = unit_axes.limits(q).margin[0, 1]
    for scale in (1e155, 1e300, 1e-200, 1e-300):
        scaled = stewart.Platform(**p, base_joint_neutral=(scale * tilted).ravel())
        assert scaled.limits(q).margin[0, 1] == pytest.approx(reference, abs=1e-14), scale
    # the zero axis is the leg at home, not the tilted one
    assert stewart.Platform(**p).limits(q).margin[0, 1] != pytest.approx(reference, abs=1e-6)
    # and ranges of a huge axis are those of the unit one, not cut to a few millimetres
    huge = stewart.Platform(**p, base_joint_neutral=(1e155 * home).ravel())
    np.testing.assert_allclose(huge.axis_ranges(THESIS_HOME),
                               stewart.Platform(**p, base_joint_neutral=home.ravel())
                               .axis_ranges(THESIS_HOME), atol=1e-9)


def test_a_neutral_axis_too_small_for_a_direction_is_refused_by_name():
    neutral = np.zeros(18)
    neutral[3:6] = [1e-310, 0.0, 2e-311]
    with pytest.raises(ValueError, match=r"base_joint_neutral\[4\.\.6\].*leg 2"):
        stewart.Platform(base_joint_neutral=neutral)


# ---------------------------------------------------------------- legs that touch

LOOSE = dict(stroke_min=0.05, stroke_max=3.0, base_joint_limit=np.pi, platform_joint_limit=np.pi)


def test_legs_that_touch_interfere_and_the_range_says_so():
    # turned far enough in yaw that legs 5 and 6 pass closer than any two joints are
    q = np.array([0.02, -0.01, 0.52, 0.03, -0.02, 0.8])
    # the library's own distance of the closest pair: a diameter of exactly that makes the
    # margin exactly 0
    distance = float(stewart.Platform(**LOOSE, leg_diameter=1e-300).limits(q).margin[0, 3])
    assert distance < 0.25  # the joints are 0.2588 m apart: the model accepts the diameter
    plat = stewart.Platform(**LOOSE, leg_diameter=distance)
    r = plat.limits(q)
    assert r.margin[0, 3] == 0.0
    assert r.first[0] == INTERFERENCE and not r.within[0]
    ranges = plat.axis_ranges(q, details=True)
    assert (ranges.limit[0] == INTERFERENCE).all()
    np.testing.assert_array_equal(ranges.ends[0, :, 0], q)
    # a hair thinner: within, with a margin of that hair
    thinner = stewart.Platform(**LOOSE, leg_diameter=np.nextafter(distance, 0.0)).limits(q)
    assert thinner.within[0] and thinner.margin[0, 3] > 0.0


@pytest.mark.parametrize("diameter_field, extra", [("leg_diameter", {}),
                                                    ("leg_body_diameter", {"leg_body_length": 0.3})])
def test_joints_closer_than_the_legs_are_thick_are_refused_at_load(diameter_field, extra):
    spec = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    spec.pop("description")
    a = np.reshape(spec["base_joint"], (6, 3))
    d = min(np.linalg.norm(a[i] - a[j]) for i in range(6) for j in range(i + 1, 6))
    if diameter_field == "leg_diameter":  # the platform joints are closer still: thinner there
        b = np.reshape(spec["platform_joint"], (6, 3))
        d = min(np.linalg.norm(b[i] - b[j]) for i in range(6) for j in range(i + 1, 6))
    with pytest.raises(ValueError, match=r"(base|platform) joints of legs \d and \d are .* m apart.*"
                                         + diameter_field):
        stewart.Platform(**spec, **{diameter_field: d}, **extra)
    stewart.Platform(**spec, **{diameter_field: 0.99 * d}, **extra)  # thinner: accepted
    # within the legs' radius the two joints of a pair are one joint of both legs (a 3-6 layout,
    # measured) and the pair is not checked: legs twice as thick as each side's pairs are apart
    sides = [np.reshape(spec[f], (6, 3)) for f in ("base_joint", "platform_joint")]
    pair = [min(np.linalg.norm(x[i] - x[j]) for i in range(6) for j in range(i + 1, 6))
            for x in sides]
    stewart.Platform(**spec, **{diameter_field: 2.01 * (max(pair) if not extra else pair[0])},
                     **extra)
    # legs that share a joint (a 3-6 platform) meet there by design and are accepted
    genhexkins = json.loads((PLATFORMS / "genhexkins.json").read_text())
    genhexkins.pop("description")
    stewart.Platform(**genhexkins, leg_diameter=0.05)


# ---------------------------------------------------------------- actuators: body and rod

def actuator_margin(a, top, body, rod, shared=()):
    """The interference margin by brute force: each leg a body (radius, length) from its base
    joint and a rod (radius, length) from its platform joint, each cut to the leg; the distance
    of every part to every part of every other leg, one part sampled densely, less the radii."""
    best = np.inf
    for i in range(6):
        for j in range(i + 1, 6):
            if (i, j) in shared:
                continue
            parts = []
            for k in (i, j):
                L = np.linalg.norm(top[k] - a[k])
                u = (top[k] - a[k]) / L
                parts.append([(a[k], a[k] + min(body[1], L) * u, body[0]),
                              (top[k] - min(rod[1], L) * u, top[k], rod[0])])
            for p0, p1, rp in parts[0]:
                for q0, q1, rq in parts[1]:
                    best = min(best, brute_segment_distance(p0, p1, q0, q1, 4001) - rp - rq)
    return best


def test_actuator_interference_against_brute_force_distances():
    spec = json.loads((PLATFORMS / "paired_hexapod.json").read_text())
    spec.pop("description")
    shapes = dict(leg_body_diameter=0.05, leg_body_length=0.2, leg_rod_diameter=0.04,
                  leg_rod_length=0.15)
    plat = stewart.Platform(**spec, **shapes)
    a = np.reshape(spec["base_joint"], (6, 3))
    b = np.reshape(spec["platform_joint"], (6, 3))
    rng = np.random.default_rng(11)
    home = np.array([0, 0, spec["home_height"], 0, 0, 0])
    poses = home + np.column_stack([rng.uniform(-0.04, 0.04, (200, 3)), rng.uniform(-0.3, 0.3, (200, 3))])
    got = plat.limits(poses).margin[:, 3]
    # the poses whose legs interfere and as many that do not
    poses = np.vstack([poses[got < 0], poses[got >= 0][:6]])
    got = plat.limits(poses).margin[:, 3]
    for q, margin in zip(poses, got):
        from test_limits import rotation
        top = q[:3] + b @ rotation(*q[3:]).T
        expected = actuator_margin(a, top, (0.025, 0.2), (0.02, 0.15))
        # the sampled part is 4001 points: the brute force is above the exact distance by at
        # most the half spacing's sagitta, far below 1e-6 m here
        assert margin == pytest.approx(expected, abs=2e-6), q
    # some of these poses interfere and some do not: both verdicts are exercised
    assert (got < 0).any() and (got > 0).any()
    # and no reported range of a shaped machine contains a pose its check refuses
    within = poses[plat.limits(poses).within][:5]
    assert len(within) >= 2
    assert refused_inside(plat, within, plat.axis_ranges(within)) == []


def test_without_body_or_rod_lengths_the_leg_is_leg_diameter_thick():
    q = np.array([0.02, -0.01, 0.52, 0.03, -0.02, 0.05])
    plain = stewart.Platform(leg_diameter=0.1).limits(q)
    ignored = stewart.Platform(leg_diameter=0.1, leg_body_diameter=0.3, leg_rod_diameter=0.3).limits(q)
    np.testing.assert_array_equal(plain.margin, ignored.margin)


# ---------------------------------------------------------------- software position limits

def test_a_pose_past_an_axis_limit_is_refused_with_its_class():
    axis_min = [-0.05, -0.05, 0.45, -0.1, -0.1, -0.2]
    axis_max = [0.05, 0.04, 0.55, 0.1, 0.1, 0.2]
    plat = stewart.Platform(axis_min=axis_min, axis_max=axis_max)
    q = np.array([0.0, 0.045, 0.5, 0.0, 0.0, 0.0])  # y past axis_max[2] = 0.04
    r = plat.limits(q)
    assert r.first[0] == AXIS and r.leg[0, 5] == 2
    assert r.margin[0, 5] == pytest.approx(0.04 - 0.045, abs=1e-15)
    on = plat.limits(np.array([0.0, 0.04, 0.5, 0.0, 0.0, 0.0]))
    assert on.within[0] and on.margin[0, 5] == 0.0  # on the limit: within
    inside = plat.limits(np.array([0.01, 0.0, 0.5, 0.0, 0.0, 0.0]))
    assert inside.within[0] and inside.margin[0, 5] == pytest.approx(0.04, abs=1e-15)
    assert inside.leg[0, 5] == 1  # x: 0.04 from axis_max[1], ahead of y's 0.04 by the order
    assert stewart.limits.class_name(AXIS) == "axis"


def test_ranges_stop_at_the_axis_limits():
    axis_min = [-0.05, -1e9, 0.45, -0.1, -np.pi, -0.2]
    axis_max = [0.05, 1e9, 0.55, 0.1, np.pi, 0.2]
    plat = stewart.Platform(axis_min=axis_min, axis_max=axis_max)
    free = stewart.Platform().axis_ranges(THESIS_HOME, details=True)
    r = plat.axis_ranges(THESIS_HOME, details=True)
    for axis in range(6):
        for side, limit in ((0, axis_min[axis]), (1, axis_max[axis])):
            inner = free.ends[0, axis, side]
            if (limit - inner) * (1 if side == 0 else -1) > 0:  # the axis limit is nearer
                assert r.ends[0, axis, side] == limit, (axis, side)
                assert r.limit[0, axis, side] == AXIS and r.leg[0, axis, side] == axis + 1
            else:
                assert r.ends[0, axis, side] == inner and r.limit[0, axis, side] == free.limit[0, axis, side]
    assert refused_inside(plat, THESIS_HOME[None, :], r.ends) == []


def test_axis_limits_are_checked_and_none_by_default():
    with pytest.raises(ValueError, match=r"axis_min\[3\] = 0\.6 must not be above axis_max\[3\]"):
        stewart.Platform(axis_min=[-1, -1, 0.6, -1, -1, -1], axis_max=[1, 1, 0.5, 1, 1, 1])
    r = stewart.Platform().limits(np.array([1e6, 0, 0.5, 0, 0, 0]))
    assert r.margin[0, 5] > 1e307 and not (r.failed & (1 << (AXIS - 1))).any()


def test_a_range_toward_a_singular_plane_stops_short_of_it_and_names_the_condition():
    """Joints (nearly) at the centres, only strokes and an exactly singular plane z = 0 (the
    legs lie in it) with warn_condition 1e300, where only the plane itself is refused: the
    proof's steps shrink toward it, and the z range ends just above it, held by the condition,
    never in the mirror assembly below."""
    plat = stewart.Platform(base_radius=1e-3, platform_radius=1e-3, stroke_min=0.3, stroke_max=0.7,
                            base_joint_limit=np.pi, platform_joint_limit=np.pi, leg_diameter=0)
    q = np.array([0.4, 0.0, 0.2, 0.0, 0.0, 0.0])
    r = plat.axis_ranges(q, warn_condition=1e300, details=True)
    # within the ranges' 1e-6 of the plane, where the determinant changes sign
    assert 0.0 < r.ends[0, 2, 0] < 1e-6 and r.limit[0, 2, 0] == CONDITION
    # the other end is the stroke: leg lengths sqrt(0.4^2 + z^2) reach 0.7 m
    assert r.limit[0, 2, 1] == STROKE
    assert r.ends[0, 2, 1] == pytest.approx(np.sqrt(0.7 ** 2 - 0.4 ** 2), abs=2e-3)
