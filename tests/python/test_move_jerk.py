"""Jerk-limited moves and the drives' limits in planning (docs/moves.md "Jerk", "Drives"),
checked independently of the planner: leg lengths from the closed form of test_moves.py, their
first, second and third differences against the leg limits, the time scale of each move by a
bisection on those differences, its duration against a lower bound computed here (each leg's
own fastest rest-to-rest jerk-limited motion over its length change, by bisection on its peak
speed), and the motors' speeds and currents from the inverse's drive outputs.

Slack of the difference checks: a k-th difference over k steps is a weighted mean of the k-th
derivative over those steps, so it never exceeds the derivative's bound; only rounding adds to
it: DELTA_L / dt^k times 1, 4 and 8 for the speed, acceleration and jerk."""
import json
import math

import numpy as np
import pytest

import stewart
from stewart import moves, moves_jerk
from test_moves import DT, EPS, FILES, goal_of, leg_limits, lengths, load, rotation


def limits_of(data):
    """The speed and acceleration limits of test_moves.py and a jerk of 8 strokes per s^3,
    which binds on every shipped machine (the moves take 1.3 to 1.6 times as long as without
    it)."""
    speed, accel = leg_limits(data)
    return speed, accel, 4.0 * accel


def one_leg_time(distance, speed, accel, jerk):
    """The shortest rest-to-rest motion over `distance` with |v| <= speed, |a| <= accel,
    |j| <= jerk: accelerate to a peak speed w and brake, cruising at w = speed if the distance
    allows; the time to reach w is w / accel + accel / jerk if the acceleration limit is reached
    on the way (w >= accel^2 / jerk), else 2 sqrt(w / jerk); w by bisection when there is no
    cruise."""
    def rise(w):
        return w / accel + accel / jerk if w >= accel ** 2 / jerk else 2 * math.sqrt(w / jerk)
    if speed * rise(speed) <= distance:
        return rise(speed) + distance / speed
    lo, hi = 0.0, speed
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid * rise(mid) <= distance else (lo, mid)
    return 2 * rise(lo)


def differences(L, step):
    """The largest |first, second, third difference| of the rows of L over the time step."""
    return (np.max(np.abs(np.diff(L, 1, axis=0))) / step,
            np.max(np.abs(np.diff(L, 2, axis=0))) / step ** 2,
            np.max(np.abs(np.diff(L, 3, axis=0))) / step ** 3)


def smallest_time_scale(L, speed, accel, jerk):
    """The smallest k (bisection) for which the samples L, k dt apart, keep the limits by their
    differences: below 1 by as much as the move could be sped up uniformly."""
    lo, hi = 0.5, 2.0
    for _ in range(60):
        k = 0.5 * (lo + hi)
        v, a, j = differences(L, k * DT)
        lo, hi = (lo, k) if v <= speed and a <= accel and j <= jerk else (k, hi)
    return hi


@pytest.mark.parametrize("kind", ["point", "line"])
@pytest.mark.parametrize("name", sorted(FILES))
def test_every_jerk_limited_move_keeps_every_limit(name, kind):
    platform, data = load(name)
    home = platform.check().home
    goal = goal_of(platform, home, kind)
    speed, accel, jerk = limits_of(data)
    m = stewart.move(platform, home, goal, kind, leg_speed_max=speed, leg_accel_max=accel,
                     leg_jerk_max=jerk)
    assert np.max(np.abs(m.pose[-1] - goal)) <= 1e-12 and np.array_equal(m.pose[0], home)
    for row in (0, -1):  # at rest, and without acceleration: the jerk is bounded from rest
        assert not m.pose_rate[row].any() and not m.pose_accel[row].any()
    assert np.allclose(np.diff(m.t), DT, rtol=0, atol=1e-12) and m.duration == m.t[-1]
    L = lengths(data, m.pose)
    delta_L = 16 * EPS * np.max(L)
    v, a, j = differences(L, DT)
    assert v <= speed * (1 + 1e-6) + delta_L / DT
    assert a <= accel * (1 + 1e-6) + 4 * delta_L / DT ** 2
    assert j <= jerk * (1 + 1e-6) + 8 * delta_L / DT ** 3
    assert np.all(platform.limits(m.pose).within)
    # Tight: sped up uniformly by 0.5 % the samples would break a limit.
    assert smallest_time_scale(L, speed, accel, jerk) > 0.995
    # Near time-optimal: no shorter than any leg's own fastest motion over its length change
    # (a lower bound of the optimum), and at most 4 % longer (measured: 0.01 % to 3.3 %, all
    # but the thesis line within 0.5 %).
    bound = max(one_leg_time(abs(d), speed, accel, jerk) for d in L[-1] - L[0])
    assert bound <= m.duration <= 1.04 * bound, (m.duration, bound)


def test_the_jerks_are_the_accelerations_derivatives():
    """pose_jerk (the path's exact third derivative through the time law) integrates to the
    change of pose_accel between samples, but at the few samples where the path jerk jumps;
    on a slerp in both rotation orders."""
    for order in (0, 1):
        platform = stewart.Platform(rotation_order=order)
        start = np.array([0.01, 0.0, 0.5, 0.03, 0.02, -0.05])
        goal = np.array([-0.01, 0.02, 0.51, -0.02, 0.04, 0.08])
        m = stewart.move(platform, start, goal, "line", leg_speed_max=0.05, leg_accel_max=0.5,
                         leg_jerk_max=4.0)
        step = np.diff(m.pose_accel, axis=0)
        trapezoid = 0.5 * DT * (m.pose_jerk[1:] + m.pose_jerk[:-1])
        scale = DT * np.max(np.abs(m.pose_jerk), axis=0)
        off = np.abs(step - trapezoid) > 1e-3 * scale
        assert np.count_nonzero(off.any(axis=1)) <= 8
        assert np.all(np.abs(step - trapezoid) <= 1.01 * scale)


@pytest.mark.parametrize("order", [0, 1])
def test_the_slerp_s_third_derivative_is_the_difference_of_its_second(order):
    q0 = np.array([0.01, 0.0, 0.5, 0.3, 0.2, -0.5])
    q1 = np.array([-0.01, 0.02, 0.51, -0.2, 0.4, 0.8])
    path = moves._LinePath(q0, q1, order)
    s, h = np.linspace(0.05, 0.95, 19), 1e-4
    third = path.third(*path.derivatives(s)[:3])
    central = (path.derivatives(s + h)[2] - path.derivatives(s - h)[2]) / (2 * h)
    assert np.max(np.abs(third - central)) <= 1e-6 * np.max(np.abs(third))
    assert np.max(np.abs(third[:, 3:])) > 0.1  # a slerp's angles are not affine in s


@pytest.mark.parametrize("v, a, j", [(0.8, 3.0, 40.0), (5.0, 3.0, 40.0), (0.8, 3.0, 5.0),
                                     (50.0, 300.0, 2.0), (1e30, 1e20, 1e10),
                                     (1e30, 1e2, 1e8)])
def test_the_s_curve_is_the_fastest_one_dimensional_motion(v, a, j):
    """Every case of the S-curve (cruise or none, acceleration limit reached or not, a speed
    bound far above the peak, as in a tiny move): it ends at rest at 1, keeps its bounds
    (sampled), and takes the time of one_leg_time."""
    curve = moves_jerk.SCurve(v, a, j)
    s, sd, sdd, sddd = curve.at(np.linspace(0, curve.duration, 20001))
    assert abs(s[-1] - 1) < 1e-12 and abs(sd[-1]) < 1e-12 and abs(sdd[-1]) < 1e-9
    assert sd.max() <= v * (1 + 1e-12) and np.abs(sdd).max() <= a * (1 + 1e-12)
    assert np.abs(sddd).max() <= j
    assert abs(curve.duration - one_leg_time(1.0, v, a, j)) <= 1e-9 * curve.duration


def test_a_platform_s_jerk_limit_and_the_cartesian_limits_together():
    platform = stewart.Platform(leg_speed_max=0.2, leg_accel_max=1.0, leg_jerk_max=6.0)
    home = platform.check().home
    m = stewart.move(platform, home, home + [0.04, 0.02, 0.0, 0.0, 0.0, 0.05], "line",
                     speed_max=0.05, angular_speed_max=0.08)
    tool = np.linalg.norm(np.diff(m.pose[:, :3], axis=0), axis=1) / DT
    assert np.max(tool) <= 0.05 * (1 + 1e-6) and np.max(tool) > 0.0495
    R = rotation(m.pose[:, 3:])
    turn = np.array([np.arccos(np.clip((np.trace(R[i + 1] @ R[i].T) - 1) / 2, -1, 1))
                     for i in range(len(R) - 1)]) / DT
    assert np.max(turn) <= 0.08 * (1 + 1e-6)


def drives_platform(name, share):
    """The shipped drive machine with motor_speed_max lowered until the motors' speed limit is
    `share` of test_moves.py's leg speed limit (so it binds); its data and that leg speed."""
    data = json.loads(FILES[name].read_text())
    speed, accel = leg_limits(data)
    motor = share * speed * 2 * math.pi * data["gear_ratio"] / data["screw_lead"]
    return stewart.Platform.from_file(FILES[name], motor_speed_max=motor), data, speed, accel


@pytest.mark.parametrize("jerk", [False, True])
@pytest.mark.parametrize("name", ["rubin_m2_hexapod_drives", "simona_motion_base_drives"])
def test_the_motors_speed_limit_bounds_the_legs_speed(name, jerk):
    platform, data, speed, accel = drives_platform(name, 0.5)
    home = platform.check().home
    goal = goal_of(platform, home, "point")
    m = stewart.move(platform, home, goal, leg_speed_max=speed, leg_accel_max=accel,
                     leg_jerk_max=4 * accel if jerk else 0)
    motor = np.abs(platform.inverse(m.pose, m.pose_rate, m.pose_accel).motor_speed)
    limit = platform.params["motor_speed_max"]
    assert motor.max() <= limit * (1 + 1e-9) and motor.max() > 0.99 * limit
    # The motor speed is the leg speed through the screw and gear: 2 pi N / lead L'.
    L = lengths(data, m.pose)
    v = np.max(np.abs(np.diff(L, axis=0))) / DT
    assert v <= limit * data["screw_lead"] / (2 * math.pi * data["gear_ratio"]) * (1 + 1e-6)


def test_the_shipped_drives_give_the_leg_speed_of_their_motors():
    for name in ("rubin_m2_hexapod_drives", "simona_motion_base_drives"):
        data = json.loads(FILES[name].read_text())
        expected = data["motor_speed_max"] * data["screw_lead"] / (2 * math.pi *
                                                                  data["gear_ratio"])
        bound = moves.drive_leg_speed_max(stewart.Platform.from_file(FILES[name]))
        assert np.allclose(bound, expected, rtol=1e-15, atol=0)
    assert not moves.drive_leg_speed_max(stewart.Platform()).any()  # no drive: no bound


def test_a_move_beyond_the_motors_current_is_refused_naming_it():
    """current_max between the motors' current at rest and the planned move's peak: MoveError
    current at the first sample whose current exceeds it, found here from the inverse."""
    name = "simona_motion_base_drives"
    free = stewart.Platform.from_file(FILES[name], current_max=0.0)
    data = json.loads(FILES[name].read_text())
    speed, accel = leg_limits(data)
    home = free.check().home
    goal = goal_of(free, home, "point")
    m = stewart.move(free, home, goal, leg_speed_max=speed, leg_accel_max=accel)
    current = np.abs(free.inverse(m.pose, m.pose_rate, m.pose_accel).current)
    limit = 0.5 * (current.max() + np.abs(free.inverse(home[None]).current).max())
    capped = stewart.Platform.from_file(FILES[name], current_max=limit)
    with pytest.raises(stewart.MoveError) as e:
        stewart.move(capped, home, goal, leg_speed_max=speed, leg_accel_max=accel)
    first = np.flatnonzero((current > limit * (1 + 1e-9)).any(axis=1))[0]
    assert e.value.limit_class == "current" and e.value.time == m.t[first]
    assert "current_max" in str(e.value) and "lower leg_accel_max" in str(e.value)
    # With the shipped 105 A the move is made: its currents within it.
    shipped = stewart.Platform.from_file(FILES[name])
    assert np.array_equal(stewart.move(shipped, home, goal, leg_speed_max=speed,
                                       leg_accel_max=accel).pose, m.pose)
    assert current.max() <= data["current_max"]


def test_a_scene_s_move_takes_a_jerk_limit():
    """The move section's leg_jerk_max reaches the planner: the scene's trajectory is the
    jerk-limited move, its third differences of the closed-form lengths within the limit."""
    platform, data = load("thesis")
    scene = stewart.scenes.load("move_line", "scenes")
    scene["move"]["leg_jerk_max"] = 2.0
    t, pose, rate, accel = stewart.scenes.trajectory(scene, platform)
    section = scene["move"]
    m = stewart.move(platform, platform.check().home, section["goal"], section["kind"],
                     leg_speed_max=section["leg_speed_max"],
                     leg_accel_max=section["leg_accel_max"], leg_jerk_max=2.0)
    assert np.array_equal(pose[:len(m.t)], m.pose) and np.array_equal(accel[:len(m.t)],
                                                                      m.pose_accel)
    L = lengths(data, pose)
    assert differences(L, DT)[2] <= 2.0 * (1 + 1e-6) + 8 * 16 * EPS * np.max(L) / DT ** 3


def test_the_command_line_takes_a_jerk_limit(tmp_path):
    import subprocess
    import sys
    from conftest import ROOT
    out = tmp_path / "move.csv"
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "move.py"), "--start",
                          "0,0,0.5,0,0,0", "--goal", "0.01,0,0.51,0,0,0.02", "--line",
                          "--leg-speed-max", "0.05", "--leg-accel-max", "0.5", "--leg-jerk-max",
                          "3", "-o", str(out)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    m = stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0.01, 0, 0.51, 0, 0, 0.02],
                     "line", leg_speed_max=0.05, leg_accel_max=0.5, leg_jerk_max=3.0)
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    assert np.array_equal(table, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel]))


def test_an_asymmetric_s_curve_ends_at_rest_within_its_bounds():
    """Speeding up and braking with their own bounds, with and without a cruise."""
    for v in (0.5, 50.0):
        curve = moves_jerk.SCurve(v, 3.0, 40.0, 1.5, 10.0)
        tau = np.linspace(0, curve.duration, 40001)
        s, sd, sdd, sddd = curve.at(tau)
        assert abs(s[-1] - 1) < 1e-12 and abs(sd[-1]) < 1e-12 and abs(sdd[-1]) < 1e-9
        assert sd.max() <= v * (1 + 1e-12) and np.all(np.diff(s) >= 0)
        assert sdd.max() <= 3.0 * (1 + 1e-12) and sdd.min() >= -1.5 * (1 + 1e-12)
        braking = tau > curve.times[3]  # after the speeding up (and the cruise, if any)
        assert np.all(sdd[braking] <= 1e-12) and np.all(sdd[~braking] >= -1e-12)
        assert np.abs(sddd[~braking]).max() == 40.0 and np.abs(sddd[braking]).max() == 10.0


def test_the_shape_search_finds_the_family_s_best():
    """The planner's law against a grid over the S-curve's four ratios around its start (9
    values each, log-spaced over a factor e^1.5 either way), unwarped: no grid point gives a
    shorter stretched duration (the planner's warp can only shorten it further)."""
    captured = {}

    def spy(peaks):
        captured["peaks"] = peaks
        return law(peaks)
    law = moves_jerk.jerk_limited_law
    moves.jerk_limited_law = spy
    try:
        platform, data = load("thesis")
        home = platform.check().home
        speed, accel, jerk = limits_of(data)
        stewart.move(platform, home, goal_of(platform, home, "line"), "line",
                     leg_speed_max=speed, leg_accel_max=accel, leg_jerk_max=jerk)
    finally:
        moves.jerk_limited_law = law
    peaks = captured["peaks"]
    curve, stretch = law(peaks)
    found = stretch * curve.duration
    top = np.max(np.abs(peaks.columns[:, :6]), axis=0)
    v0, a0, j0 = (float(np.min(limit / top)) for limit in (peaks.speed[:6], peaks.accel,
                                                             peaks.jerk))
    steps = np.exp(np.linspace(-1.5, 1.5, 9))
    best = np.inf
    for fv in steps:
        for fa in steps:
            for fa2 in steps:
                for fj2 in steps:
                    c = moves_jerk.SCurve(v0 * fv, a0 * fa, j0, a0 * fa2, j0 * fj2)
                    best = min(best, peaks.stretch(c, 16) * c.duration)
    assert found <= best * (1 + 1e-4), (found, best)


def test_a_jerk_limited_move_across_a_limit_is_refused_naming_class_and_time():
    """The pair of test_moves.py whose straight line crosses the stroke limit: refused with
    the class, and at the path parameter where a fine scan of the line first meets it."""
    from test_moves import crossing_pair
    platform = stewart.Platform()
    a, b, limit, s_first = crossing_pair(platform, platform.check().home)
    with pytest.raises(stewart.MoveError) as info:
        stewart.move(platform, a, b, leg_speed_max=0.1, leg_accel_max=0.5, leg_jerk_max=5.0)
    e = info.value
    assert e.limit_class == limit and limit in str(e) and f"t = {e.time:.6g} s" in str(e)
    assert abs(e.s - s_first) <= 1e-3 and 0 < e.time < math.inf


def test_the_warped_law_s_derivatives_are_its_differences():
    """s(t) = w(sigma(t)) through the cubic warp: its rate, acceleration and jerk against
    central differences of s, s' and s'' (away from the S-curve's segment ends, where the jerk
    jumps); it goes from 0 to 1 at rest."""
    curve = moves_jerk.SCurve(0.8, 3.0, 40.0, 2.0, 25.0)
    law = moves_jerk.WarpedLaw(curve, 0.3, -0.2)
    tau = np.linspace(0, law.duration, 4001)
    h = 1e-6
    s, v, a, j = law.at(tau)
    ahead, behind = law.at(tau + h), law.at(tau - h)
    inside = np.all(np.abs(tau[:, None] - curve.times[None, :]) > 2 * h, axis=1)
    for value, k in ((v, 0), (a, 1), (j, 2)):
        central = (ahead[k] - behind[k]) / (2 * h)
        assert np.max(np.abs(central - value)[inside]) <= 1e-6 * np.max(np.abs(value))
    assert s[0] == 0 and abs(s[-1] - 1) < 1e-12 and v[0] == 0 and abs(v[-1]) < 1e-12
    assert np.all(np.diff(s) > 0)
    with pytest.raises(ValueError, match="would not increase"):
        moves_jerk.WarpedLaw(curve, 0.6, 0.4)


@pytest.mark.parametrize("name", ["simona_motion_base", "rubin_m2_hexapod"])
def test_a_jerk_limit_on_a_leg_that_does_not_move(name):
    """A turn about a pivot at leg 1's platform joint leaves that leg's length constant (its
    joint's velocity w x 0 is exactly zero), so its jerk limit, the only one, binds nothing:
    the move keeps the speed and acceleration limits by the closed-form lengths' differences,
    and takes no less than any leg's own fastest motion without a jerk limit and at most 2 %
    longer (the S-curve's ramps; measured 0.4 % and 0.9 %)."""
    platform, data = load(name)
    data = dict(data, tool_frame=[*data["platform_joint"][:3], 0, 0, 0])
    platform = stewart.Platform.from_file(FILES[name], tool_frame=data["tool_frame"])
    home = platform.check().home
    goal = home + [0, 0, 0, np.radians(0.1), np.radians(-0.05), np.radians(0.1)]
    speed, accel = leg_limits(data)
    m = stewart.move(platform, home, goal, leg_speed_max=speed, leg_accel_max=accel,
                     leg_jerk_max=[8 * accel, 0, 0, 0, 0, 0])
    assert np.all(np.isfinite(m.pose)) and np.max(np.abs(m.pose[-1] - goal)) <= 1e-12
    L = lengths(data, m.pose)
    assert np.ptp(L[:, 0]) <= 1e-12
    delta_L = 16 * EPS * np.max(L)
    v, a, _ = differences(L, DT)
    assert v <= speed * (1 + 1e-6) + delta_L / DT
    assert a <= accel * (1 + 1e-6) + 4 * delta_L / DT ** 2
    bound = max(one_leg_time(abs(d), speed, accel, math.inf) for d in L[-1] - L[0])
    assert bound <= m.duration <= 1.02 * bound, (m.duration, bound)


def test_a_move_below_the_legs_rounding_with_a_jerk_limit():
    """A goal 5e-324 m from the start changes no leg length (closed form: equal in every
    bit), so every limit holds at any speed: one sample step to the goal, at rest at both
    ends, as without a jerk limit."""
    platform, data = load("simona_motion_base")
    home = platform.check().home
    goal = home + [5e-324, 0, 0, 0, 0, 0]
    assert np.array_equal(lengths(data, home[None]), lengths(data, goal[None]))
    speed, accel, jerk = limits_of(data)
    plain = stewart.move(platform, home, goal, leg_speed_max=speed, leg_accel_max=accel)
    m = stewart.move(platform, home, goal, leg_speed_max=speed, leg_accel_max=accel,
                     leg_jerk_max=jerk)
    assert m.duration == plain.duration == DT and np.array_equal(m.pose[-1], goal)
    assert not m.pose_rate.any() and not m.pose_accel.any()


def test_stewart_solve_reads_a_move_as_a_spreadsheet_saves_it(tmp_path, solve):
    """scripts/move.py's table saved with a UTF-8 byte order mark and CRLF line ends: the same
    solution, byte for byte, as from the table itself."""
    plain = tmp_path / "move.csv"
    m = stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0.01, 0, 0.51, 0, 0, 0.02],
                     leg_speed_max=0.05, leg_accel_max=0.5, leg_jerk_max=3.0)
    header = "t," + ",".join(n + s for s in ("", "_dot", "_ddot")
                             for n in ("x", "y", "z", "roll", "pitch", "yaw"))
    np.savetxt(plain, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel]), delimiter=",",
               header=header, comments="", fmt="%.17g")
    sheet = tmp_path / "sheet.csv"
    sheet.write_bytes(b"\xef\xbb\xbf" + plain.read_bytes().replace(b"\n", b"\r\n"))
    for path in (plain, sheet):
        run = solve(path, path.with_suffix(".out.csv"))
        assert run.returncode == 0, run.stderr
    assert (plain.with_suffix(".out.csv").read_bytes() ==
            sheet.with_suffix(".out.csv").read_bytes())
