"""The leg classes of the limit check (docs/limits.md 7.1: leg_speed, leg_accel, leg_jerk,
leg_force) on every shipped platform file, against computations made here: the legs' speed,
acceleration and jerk by finite differences of the closed-form lengths |R b + p - a| (written in
test_moves.py, independent of the library) along the pose's Taylor polynomial q + q' t + q'' t^2/2
+ q''' t^3/6, and the force margins by hand from the inverse's forces. Rows exactly on a limit
(margin 0, within) and one ulp beyond it (met) for every class.

The differences are fourth-order central ones over +-2h; their truncation error is about
h^4 times the fifth (speed, jerk: sixth) derivative, far below the 1e-6 relative tolerance at
the h used, and their rounding about eps max L / h^k."""
import numpy as np
import pytest

import stewart
from stewart.scenes import POSE as POSE_NAMES
from test_moves import FILES, lengths, load

LEG_CLASSES = ("leg_speed", "leg_accel", "leg_jerk", "leg_force")
SPEED, ACCEL, JERK, FORCE = (stewart.limits.LIMIT_CLASSES.index(c) for c in LEG_CLASSES)
#: The differences' step [s]: the motions below change over seconds. The jerk's is longer: its
#: rounding, eps L / h^3, would otherwise reach 1e-6 of the small jerks of the long-legged
#: Rubin hexapods.
H = 0.01


def motions(platform, count, seed):
    """Poses near home and rates, accelerations and jerks in proportion to the machine: over
    about a second the pose moves a few percent of its axis ranges."""
    rng = np.random.default_rng(seed)
    home = platform.check().home
    ends = platform.axis_ranges(home)[0]
    span = np.minimum(home - ends[:, 0], ends[:, 1] - home)
    q = home + 0.3 * span * rng.uniform(-1, 1, (count, 6))
    rates, accels, jerks = (0.05 * span * rng.uniform(-1, 1, (count, 6)) for _ in range(3))
    return q, rates, accels, jerks


def differences(data, q, rates, accels, jerks, h):
    """Fourth-order central differences of the closed-form lengths along the Taylor polynomial
    of each row: (speed, acceleration, jerk), each (N, 6); the jerk's step 5 h."""
    def at(t):
        return lengths(data, q + rates * t + accels * t ** 2 / 2 + jerks * t ** 3 / 6)
    m2, m1, z, p1, p2 = (at(k * h) for k in (-2, -1, 0, 1, 2))
    speed = (m2 - 8 * m1 + 8 * p1 - p2) / (12 * h)
    accel = (-m2 + 16 * m1 - 30 * z + 16 * p1 - p2) / (12 * h ** 2)
    g = 5 * h
    m3, m2, m1, p1, p2, p3 = (at(k * g) for k in (-3, -2, -1, 1, 2, 3))
    jerk = (m3 - 8 * m2 + 13 * m1 - 13 * p1 + 8 * p2 - p3) / (8 * g ** 3)
    return speed, accel, jerk


def exact_value(platform_of, data_row, column, leg, first_guess):
    """The library's own |value| of leg `leg` in class `column`, exactly: with the limit a power
    of two 2^e at or above it and below twice it, the margin 2^e - |v| is exact (Sterbenz), and
    so is 2^e - margin."""
    e = float(2.0 ** np.ceil(np.log2(first_guess)))
    for _ in range(3):  # the guess is the difference's; the exponent may be one off
        margin = platform_of(e).limits(*data_row[0], **data_row[1]).leg_margin[0, column, leg]
        value = e - margin
        if e / 2 <= value <= e:
            return value
        e = float(2.0 ** np.ceil(np.log2(value)))
    raise AssertionError("no exponent brackets the value")


@pytest.mark.parametrize("name", sorted(FILES))
def test_leg_speed_accel_and_jerk_against_differences_of_the_closed_form(name):
    platform, data = load(name)
    q, rates, accels, jerks = motions(platform, 12, 7)
    speed, accel, jerk = differences(data, q, rates, accels, jerks, H)
    # Limits per leg that some rows exceed and others keep: the legs' median values.
    limits = [np.median(np.abs(v), axis=0) for v in (speed, accel, jerk)]
    extra = {"leg_diameter": 0.0} if name == "genhexkins" else {}
    limited = stewart.Platform.from_file(FILES[name], leg_speed_max=limits[0].tolist(),
                                         leg_accel_max=limits[1].tolist(),
                                         leg_jerk_max=limits[2].tolist(), **extra)
    check = limited.limits(q, rates, accels, jerks)
    for column, value, limit in ((SPEED, speed, limits[0]), (ACCEL, accel, limits[1]),
                                 (JERK, jerk, limits[2])):
        expected = limit - np.abs(value)
        scale = np.max(np.abs(value))
        assert np.max(np.abs(check.leg_margin[:, column] - expected)) < 1e-6 * scale, \
            (name, LEG_CLASSES[column - SPEED])
        assert np.array_equal(check.margin[:, column], check.leg_margin[:, column].min(axis=1))
        assert np.array_equal(check.leg[:, column], check.leg_margin[:, column].argmin(axis=1) + 1)
        # The classes are met where the differences say so (rows far from the limit).
        clear = np.abs(expected.min(axis=1)) > 1e-4 * scale
        met = (check.failed >> column) & 1
        assert np.array_equal(met[clear], (expected.min(axis=1) < 0)[clear]), name
    # Without the data (or without a limit) a leg class is never met: margin +inf, no leg.
    alone = limited.limits(q)
    assert np.all(np.isinf(alone.margin[:, SPEED:FORCE + 1])) and not alone.leg[:, SPEED:].any()
    unlimited = platform.limits(q, rates, accels, jerks)
    assert np.all(unlimited.margin[:, SPEED:] == np.inf)
    assert np.all(unlimited.first <= 6)
    # The geometric classes do not change with the leg classes' data.
    assert np.array_equal(alone.margin[:, :SPEED], check.margin[:, :SPEED])


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_row_exactly_on_each_leg_limit_is_within_and_one_ulp_beyond_is_met(name):
    platform, data = load(name)
    q, rates, accels, jerks = motions(platform, 1, 11)
    extra = {"leg_diameter": 0.0} if name == "genhexkins" else {}
    assert platform.limits(q).within[0], name
    legs = platform.inverse(q, rates, accels, fidelity="massless")
    leg = 2  # leg 3
    _, _, jerk = differences(data, q, rates, accels, jerks, H)

    def limited(parameter, value):
        return stewart.Platform.from_file(FILES[name], **{f"{parameter}[{leg + 1}]": value},
                                          **extra)

    def exact(parameter, column, guess):
        return exact_value(lambda e: limited(parameter, e), ((q, rates, accels, jerks), {}),
                           column, leg, guess)

    # The check's own values, found exactly; they agree with the inverse's (whose batch kernels
    # may round differently) and with the differences of the closed form.
    on_limit = {
        ("leg_speed_max", SPEED): exact("leg_speed_max", SPEED, abs(legs.length_rate[0, leg])),
        ("leg_accel_max", ACCEL): exact("leg_accel_max", ACCEL, abs(legs.length_accel[0, leg])),
        ("leg_jerk_max", JERK): exact("leg_jerk_max", JERK, abs(jerk[0, leg])),
        ("leg_force_max", FORCE): abs(legs.force[0, leg]),  # given: limit - |F| by hand
    }
    assert on_limit[("leg_speed_max", SPEED)] == pytest.approx(abs(legs.length_rate[0, leg]),
                                                               rel=1e-14)
    assert on_limit[("leg_accel_max", ACCEL)] == pytest.approx(abs(legs.length_accel[0, leg]),
                                                               rel=1e-14)
    for (parameter, column), value in on_limit.items():
        for limit, margin_sign in ((value, 0), (np.nextafter(value, 0), -1)):
            check = limited(parameter, limit).limits(q, rates, accels, jerks, forces=legs.force)
            margin = check.leg_margin[0, column, leg]
            assert np.sign(margin) == margin_sign and margin == limit - value, (name, parameter)
            assert check.margin[0, column] == margin and check.leg[0, column] == leg + 1
            expected_first = column + 1 if margin_sign < 0 else 0
            assert check.first[0] == expected_first, (name, parameter, check.first[0])
            assert stewart.limits.class_name(check.first[0]) == \
                ("none" if margin_sign == 0 else LEG_CLASSES[column - SPEED])
    # The jerk found exactly agrees with the differences of the closed form.
    assert abs(on_limit[("leg_jerk_max", JERK)] - abs(jerk[0, leg])) < 1e-6 * np.max(np.abs(jerk))


@pytest.mark.parametrize("name", sorted(FILES))
def test_leg_force_against_the_inverse_s_forces_by_hand(name):
    platform, data = load(name)
    q, rates, accels, _ = motions(platform, 10, 5)
    extra = {"leg_diameter": 0.0} if name == "genhexkins" else {}
    forces = platform.inverse(q, rates, accels, fidelity="massless").force
    limit = np.median(np.abs(forces), axis=0)
    limit[4] = 0.0  # no limit for leg 5
    limited = stewart.Platform.from_file(FILES[name], leg_force_max=limit.tolist(), **extra)
    given = limited.limits(q, forces=forces)
    computed = limited.limits(q, rates, accels, forces="massless")
    expected = np.where(limit > 0, limit - np.abs(forces), np.inf)
    assert np.array_equal(given.leg_margin[:, FORCE], expected), name
    assert np.array_equal(computed.leg_margin[:, FORCE], expected), name
    geometric = limited.limits(q).first
    assert np.array_equal(given.first, np.where(geometric > 0, geometric,
                                                np.where(expected.min(axis=1) < 0, FORCE + 1, 0)))
    # A full-model force differs from the massless one: the class follows the forces given.
    full = limited.limits(q, rates, accels, forces="full")
    full_forces = platform.inverse(q, rates, accels, fidelity="full").force
    assert np.array_equal(full.leg_margin[:, FORCE],
                          np.where(limit > 0, limit - np.abs(full_forces), np.inf))


def test_leg_data_refusals_name_the_cause():
    platform = stewart.Platform(leg_speed_max=0.1)
    q = platform.check().home
    with pytest.raises(ValueError, match="accels need rates"):
        platform.limits(q, None, np.zeros(6))
    with pytest.raises(ValueError, match="row 0: pose z_dot is nan"):
        platform.limits(q, [0, 0, np.nan, 0, 0, 0])
    with pytest.raises(ValueError, match="force\\[2\\] is inf"):
        platform.limits(q, forces=[0, np.inf, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="cannot be computed"):
        platform.limits([0, 0, 0, 0, 0, np.pi / 6], forces="massless")


def test_stewart_solve_report_is_the_library_check_of_each_row(solve, tmp_path):
    """stewart-solve --report: per row the first class met and the margin to every class, the
    leg classes from the rows' own rates and accelerations and the forces it solved; equal to
    Platform.limits of the same rows, bit for bit. --limits keeps the pose's classes only."""
    platform = stewart.Platform()
    home = platform.check().home
    m = stewart.move(platform, home, home + [0.02, -0.01, 0.01, 0.0, 0.0, 0.05], "line",
                     leg_speed_max=0.05, leg_accel_max=0.5, sample_time=0.01)
    src = tmp_path / "move.csv"
    header = ["t", *POSE_NAMES, *[f"{n}_dot" for n in POSE_NAMES],
              *[f"{n}_ddot" for n in POSE_NAMES]]
    np.savetxt(src, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel]), delimiter=",",
               header=",".join(header), comments="", fmt="%.17g")
    limits = {"leg_speed_max": 0.045, "leg_accel_max": 0.6, "leg_force_max": 224.0}
    params = [a for name, v in limits.items() for a in ("--param", f"{name}={v}")]
    out = tmp_path / "out.csv"
    r = solve("--report", *params, src, out)
    assert r.returncode == 0, r.stderr
    rows = np.genfromtxt(out, delimiter=",", names=True, dtype=None, encoding="utf-8")
    forces = np.column_stack([rows[f"F{k}"] for k in range(1, 7)])
    limited = stewart.Platform(**limits)
    check = limited.limits(m.pose, m.pose_rate, m.pose_accel, forces=forces)
    names = stewart.limits.LIMIT_CLASSES
    np.testing.assert_array_equal(np.column_stack([rows[f"margin_{n}"] for n in names]),
                                  check.margin)
    first = [stewart.limits.class_name(c) for c in check.first]
    assert list(rows["limit_class"]) == first and list(rows["status"]) == first
    assert {"leg_speed", "leg_force"} <= set(first)  # the limits were chosen to be met
    assert np.all(np.isinf(check.margin[:, names.index("leg_jerk")]))  # no jerk columns given
    # The forces solved are the massless inverse's: the same check with them computed.
    again = limited.limits(m.pose, m.pose_rate, m.pose_accel, forces="massless")
    np.testing.assert_allclose(again.margin, check.margin, rtol=0, atol=1e-9)
    # --limits: the pose's classes only, as before the leg classes.
    r = solve("--limits", *params, src, out)
    assert r.returncode == 0, r.stderr
    columns = open(out).readline().strip().split(",")
    assert [c for c in columns if c.startswith("margin_")] == \
        [f"margin_{n}" for n in stewart.limits.POSE_CLASSES]


@pytest.mark.parametrize("order, convention", [(1, 0), (0, 1), (1, 1)])
def test_leg_jerk_in_every_rotation_order_and_frame_convention(order, convention):
    """With tool and user frames, R = Rx Ry Rz and z-down frames: the jerk against differences
    of the library's own lengths (Platform.inverse, itself the closed form: test_frames.py,
    test_rotation_order.py) along the Taylor polynomial; speed and acceleration against the
    inverse's."""
    platform = stewart.Platform(rotation_order=order, frame_convention=convention,
                                tool_frame=[0.02, -0.01, 0.10, 0.05, -0.04, 0.30],
                                user_frame=[0.01, -0.02, 0.45, 0.02, -0.03, 0.40],
                                leg_jerk_max=1e3)
    rng = np.random.default_rng(order + 2 * convention)
    q = platform.check().home + rng.uniform(-1, 1, (8, 6)) * [0.02, 0.02, 0.02, 0.05, 0.05, 0.1]
    rates, accels, jerks = (rng.uniform(-1, 1, (8, 6)) * 0.05 for _ in range(3))

    def at(t):
        return platform.inverse(q + rates * t + accels * t ** 2 / 2 + jerks * t ** 3 / 6,
                                fidelity="kinematic").length
    g = 2 * H  # faster motions than above: the truncation (h^4) falls 16-fold per halving
    m3, m2, m1, p1, p2, p3 = (at(k * g) for k in (-3, -2, -1, 1, 2, 3))
    jerk = (m3 - 8 * m2 + 13 * m1 - 13 * p1 + 8 * p2 - p3) / (8 * g ** 3)
    check = platform.limits(q, rates, accels, jerks)
    np.testing.assert_allclose(check.leg_margin[:, JERK], 1e3 - np.abs(jerk), rtol=0,
                               atol=1e-6 * np.abs(jerk).max())


def test_stewart_solve_report_checks_the_jerks_a_file_gives(solve, tmp_path):
    """With x_dddot..yaw_dddot columns, --report checks the leg jerk class too: its margins equal
    Platform.limits given the same jerks, bit for bit."""
    platform = stewart.Platform()
    home = platform.check().home
    m = stewart.move(platform, home, home + [0.02, -0.01, 0.01, 0.0, 0.0, 0.05], "line",
                     leg_speed_max=0.05, leg_accel_max=0.5, sample_time=0.01)
    jerk = np.gradient(m.pose_accel, m.t, axis=0)
    src = tmp_path / "move.csv"
    header = ["t", *POSE_NAMES, *[f"{n}_dot" for n in POSE_NAMES],
              *[f"{n}_ddot" for n in POSE_NAMES], *[f"{n}_dddot" for n in POSE_NAMES]]
    np.savetxt(src, np.column_stack([m.t, m.pose, m.pose_rate, m.pose_accel, jerk]),
               delimiter=",", header=",".join(header), comments="", fmt="%.17g")
    out = tmp_path / "out.csv"
    r = solve("--report", "--fidelity", "kinematic", "--param", "leg_jerk_max=5", src, out)
    assert r.returncode == 0, r.stderr
    rows = np.genfromtxt(out, delimiter=",", names=True, dtype=None, encoding="utf-8")
    check = stewart.Platform(leg_jerk_max=5.0).limits(m.pose, m.pose_rate, m.pose_accel, jerk)
    margin = rows["margin_leg_jerk"]
    assert np.all(np.isfinite(margin))
    np.testing.assert_array_equal(margin, check.margin[:, stewart.limits.LIMIT_CLASSES.index("leg_jerk")])
