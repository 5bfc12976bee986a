"""stewart.cueing, the classical washout and its limiter (docs/cueing.md): each filter against
its continuous transfer function written here and discretised by scipy.signal (zero-order hold on
both sides) to 1e-9, the tilt coordination against arcsin of the low-passed specific force, and
random vehicle signals of up to 2 g and 200 deg/s through every shipped machine with every leg
length, from a closed form written here, within its stroke (studies/cueing_limits.py runs 10^3
signals per machine)."""
import json
import pathlib

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
signal = pytest.importorskip("scipy.signal")

from reference import machine_lengths, rotation, shipped_machine  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLATFORMS = sorted((ROOT / "platforms").glob("*.json"))
G = 9.81  # the default platform's |gravity|: the vehicle at rest reads (0, 0, +G)


def reference(num, den, t, u):
    """The response at the samples to the input u, each sample held over the interval that ends
    at it (the unit's convention), of num/den and of its first two time derivatives, as left
    limits (the input held): num s^j / den = P_j(s) + R_j(s) / den; a held input makes the
    polynomial part P_j(0) u and the strictly proper part is scipy's zero-order-hold response."""
    held = np.append(u[1:], u[-1])  # scipy holds u[k] over [t_k, t_k+1)
    out = []
    for j in range(3):
        q, r = np.polydiv(np.polymul(num, [1.0] + [0.0] * j), den)
        r = np.trim_zeros(r, "f") if np.any(r) else np.array([0.0])
        _, y, _ = signal.lsim((r, den), held, t, interp=False)
        out.append(np.asarray(y) + np.polyval(q, 0.0) * u)
    return out


def quadratic(w, zeta):
    return np.array([1.0, 2 * zeta * w, w * w])


def inputs(n, axis=None, force=None, omega=None):
    f = np.tile([0.0, 0.0, G], (n, 1))
    w = np.zeros((n, 3))
    if force is not None:
        f[:, axis] += force
    if omega is not None:
        w[:, axis] = omega
    return f, w


T = np.arange(0, 20.0, 0.01)
SIGNALS = {"step": np.where(T > 0.5, 1.0, 0.0), "sine": np.sin(2 * np.pi * 0.4 * T)}


@pytest.mark.parametrize("order", [2, 3])
@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("shape", sorted(SIGNALS))
def test_translation_against_its_transfer_function(order, axis, shape):
    plat = stewart.Platform()
    k, w, zeta, wb = 0.3, 2.0, 0.8, 0.4
    amplitude = 0.3
    f, om = inputs(len(T), axis, force=amplitude * SIGNALS[shape])
    r = stewart.cueing(plat, T, f, om, translation_order=order, translation_frequency=w,
                       translation_damping=zeta, translation_washout_frequency=wb,
                       surge_scale=k, sway_scale=k, heave_scale=k, tilt_max=0.0)
    assert not r.limited.any()
    den = quadratic(w, zeta) if order == 2 else np.polymul(quadratic(w, zeta), [1.0, wb])
    num = [k] if order == 2 else [k, 0.0]
    home = np.array([0, 0, 0.5, 0, 0, 0])
    want = reference(num, den, T, amplitude * SIGNALS[shape])
    for got, ref in zip((r.pose[:, axis] - home[axis], r.pose_rate[:, axis], r.pose_accel[:, axis]), want):
        assert np.max(np.abs(got - ref)) < 1e-9 * max(1.0, np.max(np.abs(ref)))
    assert np.max(np.abs(want[0])) > 1e-3  # the cue is not trivially small
    others = [i for i in range(6) if i != axis]
    assert np.all(r.pose[:, others] == home[others]) and not r.pose_rate[:, others].any()


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("shape", sorted(SIGNALS))
def test_rotation_against_its_transfer_function(order, axis, shape):
    plat = stewart.Platform()
    k, w, zeta = 0.7, 1.5, 0.9
    amplitude = np.radians(8)
    f, om = inputs(len(T), axis, omega=amplitude * SIGNALS[shape])
    r = stewart.cueing(plat, T, f, om, rotation_filter_order=order, rotation_frequency=w,
                       rotation_damping=zeta, roll_scale=k, pitch_scale=k, yaw_scale=k)
    assert not r.limited.any()
    den = quadratic(w, zeta) if order == 2 else np.array([1.0, w])
    num = [k, 0.0] if order == 2 else [k]
    want = reference(num, den, T, amplitude * SIGNALS[shape])
    i = 3 + axis
    for got, ref in zip((r.pose[:, i], r.pose_rate[:, i], r.pose_accel[:, i]), want):
        assert np.max(np.abs(got - ref)) < 1e-9 * max(1.0, np.max(np.abs(ref)))
    assert np.max(np.abs(want[0])) > 1e-3


@pytest.mark.parametrize("shape", sorted(SIGNALS))
def test_tilt_coordination_against_arcsin_of_the_low_pass(shape):
    """pitch = -asin(k LP f_x / g), roll = asin(k LP f_y / (g cos pitch)) with LP = w^2 / (s^2 +
    2 zeta w s + w^2), slow enough for the rate limit to stay open; their rates by the chain
    rule on scipy's responses."""
    plat = stewart.Platform()
    k, w, zeta = 0.5, 1.2, 0.7
    ax, ay = 0.4 * SIGNALS[shape], -0.3 * SIGNALS[shape]
    f, om = inputs(len(T))
    f[:, 0] += ax
    f[:, 1] += ay
    r = stewart.cueing(plat, T, f, om, surge_scale=k, sway_scale=k, tilt_frequency=w,
                       tilt_damping=zeta, translation_frequency=3.0)
    assert not r.limited.any() and not r.tilt_limited.any()
    lx = reference([k * w * w], quadratic(w, zeta), T, ax)
    ly = reference([k * w * w], quadratic(w, zeta), T, ay)
    pitch = -np.arcsin(lx[0] / G)
    roll = np.arcsin(ly[0] / (G * np.cos(pitch)))
    assert np.max(np.abs(r.pose[:, 4] - pitch)) < 1e-9
    assert np.max(np.abs(r.pose[:, 3] - roll)) < 1e-9
    pitch_rate = -lx[1] / G / np.sqrt(1 - (lx[0] / G) ** 2)
    assert np.max(np.abs(r.pose_rate[:, 4] - pitch_rate)) < 1e-9
    assert np.max(np.abs(pitch)) > 1e-3


def test_tilt_rate_limit_and_tilt_max():
    plat = stewart.Platform()
    t = np.arange(0, 30, 0.005)
    f, om = inputs(len(t), 0, force=np.where(t > 1, 0.9 * G, 0.0))
    rate_max = np.radians(3)
    r = stewart.cueing(plat, t, f, om, surge_scale=1.0, tilt_rate_max=rate_max, tilt_max=np.radians(10),
                       translation_frequency=30.0, limiter_lookahead=0.0)
    assert r.tilt_limited.any() and not r.limited.any()
    assert np.max(np.abs(np.diff(r.pose[:, 4])) / 0.005) <= rate_max * (1 + 1e-9)
    assert np.max(np.abs(r.pose_rate[:, 4])) <= rate_max * (1 + 1e-9)
    assert abs(r.pose[-1, 4] + np.radians(10)) < 1e-6  # held at tilt_max, nose up


# --- limits on every shipped machine --------------------------------------------------------

def run_signals(path, count, seed, dt=0.01):
    """count random signals of 20 s through the machine of path: the samples beyond a stroke
    (closed form), beyond any limit (the library's check), and the samples the limiter scaled."""
    plat = stewart.Platform.from_file(path)
    machine = shipped_machine(path)
    smin, smax = machine[2:4]
    t = np.arange(0, 20, dt)
    rng = np.random.default_rng(seed)
    beyond_stroke = beyond_check = limited = 0
    for _ in range(count):
        f, w = stewart.random_vehicle(rng, t)
        r = stewart.cueing(plat, t, f, w, surge_scale=1, sway_scale=1, heave_scale=1,
                           roll_scale=1, pitch_scale=1, yaw_scale=1)
        L = machine_lengths(machine, r.pose)
        beyond_stroke += int(np.sum(np.any((L < smin) | (L > smax), axis=1)))
        beyond_check += int(np.sum(~plat.limits(r.pose).within))
        limited += int(np.sum(r.limited))
        assert np.all(np.isfinite(r.pose_rate)) and np.all(np.isfinite(r.pose_accel))
    return beyond_stroke, beyond_check, limited


@pytest.mark.parametrize("path", PLATFORMS, ids=[p.stem for p in PLATFORMS])
def test_random_vehicles_never_leave_the_limits(path):
    beyond_stroke, beyond_check, limited = run_signals(path, 20, seed=37)
    assert beyond_stroke == 0 and beyond_check == 0
    assert limited > 0  # the limiter had work to do


def test_limiter_scale_is_smooth_when_the_lookahead_suffices():
    """A slow sine of surge that asks for twice the machine's travel: the scale moves no faster
    than limiter_rate, and the rates and accelerations are those of the poses: the backward
    difference of x over a step within dt max|acceleration| of the rate at its end (the scale
    is linear over a step), and of the rate within dt max|jerk| of the acceleration."""
    plat = stewart.Platform()
    t = np.arange(0, 20, 0.002)
    f, w = inputs(len(t), 0, force=8.0 * np.sin(2 * np.pi * 0.3 * t))
    r = stewart.cueing(plat, t, f, w, surge_scale=1.0, tilt_max=0.0, limiter_rate=2.0,
                       limiter_accel=20.0, limiter_lookahead=0.5)
    assert r.limited.any() and np.all(plat.limits(r.pose).within)
    smooth = ~(r.cut[1:] | r.cut[:-1])[1:]  # second differences over two steps without a cut
    assert np.sum(r.cut) <= 0.01 * len(t)
    assert np.max(np.abs(np.diff(r.scale)[~r.cut[1:]])) <= 2.0 * 0.002 * (1 + 1e-9)
    assert np.max(np.abs(np.diff(r.scale, 2)[smooth])) <= 20.0 * 0.002 ** 2 * (1 + 1e-9)
    x, v, a = r.pose[:, 0], r.pose_rate[:, 0], r.pose_accel[:, 0]
    dt = 0.002
    assert np.max(np.abs(np.diff(x) / dt - v[1:])) <= dt * np.max(np.abs(a)) * 1.01
    jerk = np.max(np.abs(np.diff(a))) / dt
    assert np.max(np.abs(np.diff(v) / dt - a[1:])) <= dt * jerk * 1.01 + 1e-9
    assert np.max(np.abs(v)) > 0.1  # against a cue of no speed


def test_bad_input_is_refused_by_name():
    plat = stewart.Platform()
    t = np.arange(0, 1, 0.01)
    f, w = inputs(len(t))
    with pytest.raises(ValueError, match="translation_order = 5"):
        stewart.cueing(plat, t, f, w, translation_order=5)
    with pytest.raises(ValueError, match="unknown cueing option 'tilt'"):
        stewart.cueing(plat, t, f, w, tilt=1)
    # a platform's parameter given as an option: where it goes
    with pytest.raises(ValueError, match=r"leg_speed_max is a parameter of the platform.*"
                       r"Platform.from_file\(path, leg_speed_max=...\)"):
        stewart.cueing(plat, t, f, w, leg_speed_max=0.1)
    with pytest.raises(ValueError, match="algorithm = 'mpc'"):
        stewart.cueing(plat, t, f, w, algorithm="mpc")
    f[3, 1] = np.nan
    with pytest.raises(ValueError, match=r"specific_force\[3, 1\]"):
        stewart.cueing(plat, t, f, w)
    with pytest.raises(ValueError, match="shape"):
        stewart.cueing(plat, t, f[:5], w)
    with pytest.raises(TypeError, match="stewart.Platform"):
        stewart.cueing("thesis.json", t, f, w)


def test_algorithms_and_options_are_listed():
    assert stewart.CUEING_ALGORITHMS == ("classical",)
    names = stewart.cueing.__module__ and [o["name"] for o in stewart._core.option_table("cueing")]
    assert names[0] == "algorithm" and "tilt_rate_max" in names and "head_z" in names


def test_platform_turns_about_the_head():
    """With the vehicle's rotation alone the head point (head_x, head_y, head_z in the platform
    frame) stays where it is at home: p + R head = home + head at every sample, and its velocity
    p' + omega x (R head) is zero (omega from the angle rates, R = Rz Ry Rx)."""
    plat = stewart.Platform()
    t = np.arange(0, 6, 0.01)
    f, w = inputs(len(t))
    w[:, 0] = np.radians(10) * np.sin(2 * t)
    w[:, 1] = np.radians(8) * np.cos(3 * t)
    w[:, 2] = np.radians(20) * (t > 1)
    head = np.array([0.1, -0.05, 0.3])
    r = stewart.cueing(plat, t, f, w, head_x=head[0], head_y=head[1], head_z=head[2])
    assert not r.limited.any() and np.max(np.abs(r.pose[:, 3:])) > np.radians(2)
    home_head = np.array([0, 0, 0.5]) + head
    for q, qd in zip(r.pose, r.pose_rate):
        R = rotation(*q[3:])
        assert np.max(np.abs(q[:3] + R @ head - home_head)) < 1e-12
        roll, pitch, yaw = q[3:]
        E = np.array([[np.cos(yaw) * np.cos(pitch), -np.sin(yaw), 0],
                      [np.sin(yaw) * np.cos(pitch), np.cos(yaw), 0],
                      [-np.sin(pitch), 0, 1]])
        omega = E @ qd[3:]
        assert np.max(np.abs(qd[:3] + np.cross(omega, R @ head))) < 1e-12


def test_a_z_down_machine_gets_the_same_cue_in_its_own_frame():
    """frame_convention 1 (z down, y right): the same machine's cue, turned by 180 deg about x:
    (x, y, z, roll, pitch, yaw) -> (x, -y, -z, roll, -pitch, -yaw), rates and accelerations
    alike (the joints' azimuths measured toward y right: the same physical machine)."""
    t = np.arange(0, 8, 0.01)
    f, w = inputs(len(t))
    f[:, 0] += 1.5 * np.sin(1.1 * t)
    f[:, 1] += 1.0 * (t > 2)
    w[:, 0] = 0.2 * np.sin(2 * t)
    w[:, 2] = 0.3 * (t > 1)
    up = stewart.cueing(stewart.Platform(), t, f, w)
    down_platform = stewart.Platform(frame_convention=1, base_angle=-np.radians([0, 30, 120, 150, 240, 270]),
                                     platform_angle=-np.radians([330, 60, 90, 180, 210, 300]))
    down = stewart.cueing(down_platform, t, f, w)
    sign = np.array([1, -1, -1, 1, -1, -1])
    for a, b in ((up.pose, down.pose), (up.pose_rate, down.pose_rate), (up.pose_accel, down.pose_accel)):
        assert np.max(np.abs(a * sign - b)) < 1e-12
    assert np.array_equal(up.limited, down.limited)


def angle_rate_matrix(pitch, yaw):
    """E with omega = E (roll, pitch, yaw)' for R = Rz Ry Rx."""
    return np.array([[np.cos(yaw) * np.cos(pitch), -np.sin(yaw), 0],
                     [np.sin(yaw) * np.cos(pitch), np.cos(yaw), 0],
                     [-np.sin(pitch), 0, 1]])


def leg_motion(path, pose, rate, accel):
    """Each leg's length, rate and acceleration (N, 6) in closed form from the tool's poses in the
    user frame: d = p + R b - a with p = user + q - R tool, L = |d|, L' = d.d' / L and
    L'' = (|d'|^2 - L'^2) / L + d.d'' / L; omega = E angles', alpha = E angles'' + E' angles'
    (E' by a central difference of E along the angles: E is smooth)."""
    a, b, _, _, tool, user = shipped_machine(path)
    n = len(pose)
    L, Ld, Ldd = (np.empty((n, 6)) for _ in range(3))
    for i, (q, qd, qdd) in enumerate(zip(pose, rate, accel)):
        R = rotation(*q[3:])
        E = angle_rate_matrix(q[4], q[5])
        h = 1e-6
        E_dot = (angle_rate_matrix(q[4] + h * qd[4], q[5] + h * qd[5]) -
                 angle_rate_matrix(q[4] - h * qd[4], q[5] - h * qd[5])) / (2 * h)
        omega = E @ qd[3:]
        alpha = E @ qdd[3:] + E_dot @ qd[3:]
        arm = b @ R.T - R @ tool  # platform joints from the tool origin
        d = user + q[:3] + arm - a
        v = qd[:3] + np.cross(omega, arm)
        acc = qdd[:3] + np.cross(alpha, arm) + np.cross(omega, np.cross(omega, arm))
        L[i] = np.linalg.norm(d, axis=1)
        Ld[i] = np.sum(d * v, axis=1) / L[i]
        Ldd[i] = (np.sum(v * v, axis=1) - Ld[i] ** 2) / L[i] + np.sum(d * acc, axis=1) / L[i]
    return L, Ld, Ldd


def leg_motion_limits(path):
    """A leg speed limit of one stroke per second and an acceleration limit of ten strokes per
    s^2: far below what the random signals ask for on every machine."""
    _, _, smin, smax, _, _ = shipped_machine(path)
    span = float(np.min(smax - smin))
    return span, 10 * span


def run_signals_with_leg_limits(path, count, seed, dt=0.01):
    """count random signals through the machine with leg_speed_max and leg_accel_max set: the
    samples beyond a stroke or a pose limit, whose closed-form leg rate or acceleration is beyond
    its limit (and of those, the ones leg_limits does not report), the largest finite differences
    of the closed-form lengths over the limits away from reported samples, and the largest gap
    between the first differences and the mean of the rates at both ends (over dt a_max: the
    rates are those of the lengths)."""
    v_max, a_max = leg_motion_limits(path)
    plat = stewart.Platform.from_file(path, leg_speed_max=v_max, leg_accel_max=a_max)
    _, _, smin, smax, _, _ = shipped_machine(path)
    t = np.arange(0, 20, dt)
    rng = np.random.default_rng(seed)
    out = dict(samples=0, beyond_pose=0, beyond_legs=0, unreported=0, limited=0,
               fd_speed=0.0, fd_accel=0.0, rate_gap=0.0)
    for _ in range(count):
        f, w = stewart.random_vehicle(rng, t)
        r = stewart.cueing(plat, t, f, w, surge_scale=1, sway_scale=1, heave_scale=1,
                           roll_scale=1, pitch_scale=1, yaw_scale=1)
        L, Ld, Ldd = leg_motion(path, r.pose, r.pose_rate, r.pose_accel)
        out["beyond_pose"] += int(np.sum(np.any((L < smin) | (L > smax), axis=1) |
                                         ~plat.limits(r.pose).within))
        beyond = np.any((np.abs(Ld) > v_max) | (np.abs(Ldd) > a_max), axis=1)
        reported = (r.leg_limits & 3) != 0  # LEG_SPEED, LEG_ACCEL
        out["samples"] += len(t)
        out["beyond_legs"] += int(np.sum(beyond))
        out["unreported"] += int(np.sum(beyond & ~reported))
        out["limited"] += int(np.sum(r.limited))
        clear = ~(reported | np.roll(reported, 1) | np.roll(reported, -1))  # not next to one
        step = np.abs(np.diff(L, axis=0))[clear[1:] & clear[:-1]]
        out["fd_speed"] = max(out["fd_speed"], np.max(step) / dt / v_max)
        second = np.abs(np.diff(L, 2, axis=0))[clear[2:] & clear[1:-1] & clear[:-2]]
        out["fd_accel"] = max(out["fd_accel"], np.max(second) / dt**2 / a_max)
        gap = np.abs(np.diff(L, axis=0) / dt - 0.5 * (Ld[1:] + Ld[:-1]))[clear[1:] & clear[:-1]]
        out["rate_gap"] = max(out["rate_gap"], np.max(gap) / (dt * a_max))
    return out


@pytest.mark.parametrize("path", PLATFORMS, ids=[p.stem for p in PLATFORMS])
def test_random_vehicles_keep_the_legs_speed_and_acceleration_limits(path):
    """Every output sample's leg rates and accelerations (closed form) within leg_speed_max and
    leg_accel_max, with the pose limits still kept, but where the pose limits left no motion
    within the legs' limits: rare (at most 1e-4 of the samples) and every one reported in
    leg_limits; the lengths' finite differences agree (the first within dt a_max of the rates'
    mean, a check that the rates are the lengths'; the speeds between samples within 0.1 %; the
    second differences, which average the acceleration between samples the limiter does not
    see, within 5 %)."""
    r = run_signals_with_leg_limits(path, 10, seed=37)
    assert r["beyond_pose"] == 0
    assert r["unreported"] == 0 and r["beyond_legs"] <= 1e-4 * r["samples"]
    assert r["limited"] > 0
    assert r["rate_gap"] <= 1.0
    assert r["fd_speed"] <= 1.001 and r["fd_accel"] <= 1.05


def test_generous_leg_limits_leave_the_cue_bit_for_bit():
    """Leg limits the cue never reaches: the output is the cue without them, bit for bit."""
    path = ROOT / "platforms" / "thesis.json"
    t = np.arange(0, 10, 0.01)
    f, w = inputs(len(t))
    f[:, 0] += 1.5 * np.sin(1.5 * t)
    w[:, 2] = 0.3 * np.sin(0.9 * t)
    free = stewart.cueing(stewart.Platform.from_file(path), t, f, w)
    loose = stewart.cueing(stewart.Platform.from_file(path, leg_speed_max=10.0,
                                                      leg_accel_max=1e3), t, f, w)
    assert not loose.limited.any()
    for name in ("pose", "pose_rate", "pose_accel"):
        assert np.array_equal(getattr(free, name), getattr(loose, name))


def test_a_rate_step_is_smoothed_within_the_leg_limits():
    """A step of yaw rate makes the rotation channel's angle rate jump: with the legs' limits the
    output's yaw rate rises over several samples instead, every leg within both limits, and then
    rejoins the cue (the same yaw as without limits once the cue is slow again)."""
    path = ROOT / "platforms" / "thesis.json"
    t = np.arange(0, 12, 0.001)
    f, w = inputs(len(t), 2, omega=np.radians(20) * (t > 1))
    v_max, a_max = 0.05, 0.5
    free = stewart.cueing(stewart.Platform.from_file(path), t, f, w)
    plat = stewart.Platform.from_file(path, leg_speed_max=v_max, leg_accel_max=a_max)
    r = stewart.cueing(plat, t, f, w)
    _, Ld, Ldd = leg_motion(path, r.pose[::10], r.pose_rate[::10], r.pose_accel[::10])
    assert np.max(np.abs(Ld)) <= v_max and np.max(np.abs(Ldd)) <= a_max
    assert np.max(np.abs(Ld)) > 0.5 * v_max  # the limits were met
    jump = np.max(np.abs(np.diff(free.pose_rate[:, 5])))
    assert jump > 0.05 and np.max(np.abs(np.diff(r.pose_rate[:, 5]))) < 0.1 * jump
    assert r.limited[1000:1100].any() and not r.limited[-1000:].any()
    assert np.max(np.abs(r.pose[-1000:] - free.pose[-1000:])) < 1e-9


def test_leg_force_limit_is_reported():
    """leg_force_max is checked (massless legs through the inverse solver), not enforced: a limit
    below the platform's weight share is reported (bit 4) at every sample, and only that bit."""
    path = ROOT / "platforms" / "thesis.json"
    plat = stewart.Platform.from_file(path, leg_force_max=1.0)
    t = np.arange(0, 2, 0.01)
    f, w = inputs(len(t))
    f[:, 0] += np.sin(3 * t)
    r = stewart.cueing(plat, t, f, w)
    assert np.all(r.leg_limits == 4)


def simona_in_its_own_frame():
    """SIMONA as its motion software states it: x forward, y right, z down (frame_convention 1),
    the joints and the payload's centre of the file's z-up machine turned by 180 deg about x."""
    d = json.loads((ROOT / "platforms" / "simona_motion_base.json").read_text())
    turn = np.array([1.0, -1.0, -1.0])
    params = {k: v for k, v in d.items() if k != "description"}
    for key in ("base_joint", "platform_joint"):
        params[key] = (np.reshape(d[key], (6, 3)) * turn).ravel().tolist()
    params["payload_com"] = (np.asarray(d["payload_com"], float) * turn).tolist()
    params["frame_convention"] = 1
    return stewart.Platform(**params)


def test_the_head_is_given_in_the_machines_frame():
    """SIMONA's design eye point (1.2075 m above the upper gimbal plane, a little forward and to
    the side here) given in each statement's own platform frame gives the same cue, turned: (x,
    y, z, roll, pitch, yaw) -> (x, -y, -z, roll, -pitch, -yaw). The same numbers given to both
    do not (the head matters to the cue)."""
    t = np.arange(0, 8, 0.01)
    f, w = inputs(len(t))
    f[:, 0] += 1.5 * np.sin(1.1 * t)
    w[:, 0] = 0.2 * np.sin(2 * t)
    w[:, 1] = 0.15 * np.cos(1.3 * t)
    w[:, 2] = 0.3 * (t > 1)
    head_up = np.array([0.3, 0.2, 1.2075])
    head_down = head_up * [1, -1, -1]
    up_platform = stewart.Platform.from_file(ROOT / "platforms" / "simona_motion_base.json")
    down_platform = simona_in_its_own_frame()
    def cue(platform, head):
        return stewart.cueing(platform, t, f, w, head_x=head[0], head_y=head[1], head_z=head[2])
    up, down, misread = cue(up_platform, head_up), cue(down_platform, head_down), cue(down_platform, head_up)
    assert not up.limited.any()
    sign = np.array([1, -1, -1, 1, -1, -1])
    for name in ("pose", "pose_rate", "pose_accel"):
        assert np.max(np.abs(getattr(up, name) * sign - getattr(down, name))) < 1e-9
    assert np.max(np.abs(up.pose * sign - misread.pose)) > 0.01
