"""The drives' sizing outputs (docs/drives.md) against closed forms written here, each term alone:
the drive's inertia, the screw's efficiency forward and backward, friction with its Stribeck
peak, back-EMF, R I and L dI/dt; the published numbers of looms-polimi/Parallel_manipulators'
electric cylinder; no drive: every other output as before and the drive columns zero; the
sizing report against numpy on the same arrays; scripts/size.py and stewart-solve's columns."""
import csv
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[2]
LEAD, GEAR, KT = 0.005, 3.0, 0.5
RATIO = 2 * np.pi * GEAR / LEAD  # motor radians per metre of leg
DRIVE_COLUMNS = ("motor_angle", "motor_speed", "motor_accel", "motor_torque", "current",
                 "current_rate", "voltage", "electrical_power", "motor_power")
LEG_COLUMNS = ("length", "length_rate", "length_accel", "force", "condition", "residual",
               "base_force", "base_torque", "iterations", "warnings", "stroke_legs")


def manoeuvre(n=401, duration=2.0):
    """t and an exact pose trajectory around home: heave, roll and yaw at once."""
    t = np.linspace(0.0, duration, n)
    q, qd, qdd = (np.zeros((n, 6)) for _ in range(3))
    for axis, amplitude, w, home in ((2, 0.03, 3.0, 0.5), (3, 0.05, 2.0, 0.0),
                                     (5, 0.04, 2.5, 0.0)):
        q[:, axis] = home + amplitude * np.sin(w * t)
        qd[:, axis] = amplitude * w * np.cos(w * t)
        qdd[:, axis] = -amplitude * w * w * np.sin(w * t)
    return t, q, qd, qdd


def driven(**params):
    """The thesis platform with a drive on every leg: 5 mm lead, gear 3, 0.5 N.m/A."""
    return stewart.Platform(screw_lead=LEAD, gear_ratio=GEAR, torque_constant=KT, **params)


def close(a, b, rel=1e-12):
    scale = max(1.0, float(np.max(np.abs(b))))
    np.testing.assert_allclose(a, b, rtol=0, atol=rel * scale)


def test_looms_polimi_published_numbers():
    """Its defaults: rotor 1.37e-4 kg.m2, lead 5 mm, gear ratio 3 reflect as 1,947.08 kg and
    take 2.582 N.m at 5 m/s^2 on the rotor alone (the issue's figures, from the library's
    parameters by hand)."""
    platform = driven(rotor_inertia=1.37e-4)
    assert platform.reflected_mass == pytest.approx(np.full(6, 1947.08), abs=0.005)
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, "kinematic")  # F = 0: the rotor alone
    moving = np.abs(sol.length_accel) > 1e-3
    per_accel = sol.motor_torque[moving] / sol.length_accel[moving]
    assert 5.0 * per_accel == pytest.approx(2.582, abs=5e-4)


def test_inertia_alone():
    J_rotor, J_screw = 2e-4, 3e-4
    platform = driven(rotor_inertia=J_rotor, screw_inertia=J_screw)
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, "kinematic")
    J = J_rotor + J_screw / GEAR**2
    close(sol.motor_torque, J * RATIO * sol.length_accel)
    close(sol.motor_angle, RATIO * sol.length)
    close(sol.motor_speed, RATIO * sol.length_rate)
    close(sol.motor_accel, RATIO * sol.length_accel)
    close(sol.current, sol.motor_torque / KT)


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_efficiency_by_power_flow(fidelity):
    eta, eta_back = 0.9, 0.7
    platform = driven(screw_efficiency=eta, screw_back_efficiency=eta_back)
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, fidelity)
    F, v = sol.force, sol.length_rate
    motoring = F * v >= 0  # at rest the forward efficiency (docs/drives.md)
    assert motoring.any() and (~motoring).any()
    expected = np.where(motoring, F / (RATIO * eta), F * eta_back / RATIO)
    close(sol.motor_torque, expected)
    # the power the motor gives: the load's over eta, or a share eta_back of what it takes back
    P_load = F * v
    close(sol.motor_power, np.where(motoring, P_load / eta, P_load * eta_back))


def test_self_locking_screw_holds_the_load():
    platform = driven(screw_back_efficiency=0.0)
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, "massless")
    back = sol.force * sol.length_rate < 0
    assert back.any()
    assert np.all(sol.motor_torque[back] == 0.0)


def test_friction_with_its_stribeck_peak():
    Fc, Fs, vs, b, eta = 20.0, 35.0, 0.01, 150.0, 0.8
    platform = driven(coulomb_friction=Fc, stribeck_friction=Fs, stribeck_speed=vs,
                      viscous_friction=b, screw_efficiency=eta, screw_back_efficiency=0.5)
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, "kinematic")  # F = 0: friction alone
    v = sol.length_rate
    assert np.any(np.abs(v) < vs) and np.any(np.abs(v) > 5 * vs)
    friction = (Fc + (Fs - Fc) * np.exp(-(v / vs) ** 2)) * np.sign(v) + b * v
    close(sol.motor_torque, friction / (RATIO * eta))  # friction always takes power: forward


def test_back_emf_alone():
    platform = driven()
    t, q, qd, qdd = manoeuvre()
    sol = platform.inverse(q, qd, qdd, "kinematic")  # no load, no inertia: no current
    assert np.all(sol.current == 0)
    close(sol.voltage, KT * RATIO * sol.length_rate)


def test_resistance_and_inductance():
    R, L = 1.3, 4e-3
    platform = driven(winding_resistance=R, winding_inductance=L, rotor_inertia=1e-4)
    t, q, qd, qdd = manoeuvre()
    static = platform.inverse(q, qd, qdd, "full")  # poses alone: dI/dt 0
    assert np.all(static.current_rate == 0)
    close(static.voltage, R * static.current + KT * static.motor_speed)
    sol = platform.inverse(q, qd, qdd, "full", t=t)
    close(sol.current, static.current, rel=0)
    rate = np.gradient(sol.current, t, axis=0)
    close(sol.current_rate, rate, rel=1e-10)
    close(sol.voltage, R * sol.current + KT * sol.motor_speed + L * rate, rel=1e-12)
    close(sol.electrical_power, sol.voltage * sol.current)
    close(sol.motor_power, sol.motor_torque * sol.motor_speed)
    # uneven steps: numpy's second-order differences too
    uneven = np.sort(np.concatenate([t[::3], t[1::7] + 1e-3]))
    _, q2, qd2, qdd2 = manoeuvre()
    q2 = np.interp(uneven, t, q[:, 2])
    poses = np.zeros((uneven.size, 6))
    poses[:, 2] = q2
    sol2 = platform.inverse(poses, None, None, "massless", t=uneven)
    close(sol2.current_rate, np.gradient(sol2.current, uneven, axis=0), rel=1e-10)


def test_no_drive_leaves_every_output_and_gives_zeros():
    t, q, qd, qdd = manoeuvre()
    for fidelity in ("kinematic", "massless", "full"):
        plain = stewart.Platform().inverse(q, qd, qdd, fidelity, t=t)
        with_drive = driven(rotor_inertia=1e-4, winding_inductance=1e-3).inverse(
            q, qd, qdd, fidelity, t=t)
        for name in LEG_COLUMNS:
            assert np.array_equal(getattr(plain, name), getattr(with_drive, name)), name
        for name in DRIVE_COLUMNS + ("current_max_legs", "voltage_max_legs",
                                     "motor_speed_max_legs"):
            assert not np.any(getattr(plain, name)), name
        assert np.any(with_drive.motor_torque)


def test_limit_flags():
    t, q, qd, qdd = manoeuvre()
    free = driven(rotor_inertia=1e-4).inverse(q, qd, qdd, "massless")
    current_max = 0.5 * np.max(np.abs(free.current))
    speed_max = 0.5 * np.max(np.abs(free.motor_speed))
    sol = driven(rotor_inertia=1e-4, current_max=current_max, motor_speed_max=speed_max,
                 voltage_max=1e9).inverse(q, qd, qdd, "massless")
    bits = 1 << np.arange(6)
    expected_current = ((np.abs(free.current) > current_max) * bits).sum(axis=1)
    expected_speed = ((np.abs(free.motor_speed) > speed_max) * bits).sum(axis=1)
    assert np.array_equal(sol.current_max_legs, expected_current)
    assert np.array_equal(sol.motor_speed_max_legs, expected_speed)
    assert not np.any(sol.voltage_max_legs)
    assert np.any(expected_current) and not np.all(expected_current == 63)


def trapezoid(t, f):
    return np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)[:, None], axis=0)


def test_sizing_report_against_numpy(tmp_path):
    platform = driven(rotor_inertia=1e-4, winding_resistance=1.0, winding_inductance=2e-3,
                      current_max=10, voltage_max=300, motor_speed_max=400)
    t1, q1, qd1, qdd1 = manoeuvre()
    t2, q2, _, _ = manoeuvre(n=201, duration=1.0)
    report = stewart.sizing(platform, [(t1, q1, qd1, qdd1), (t2, q2)])
    assert report.names == ["trajectory 1", "trajectory 2"]
    for i, (t, sol) in enumerate(report.solutions):
        T = t[-1] - t[0]
        P = sol.voltage * sol.current
        assert np.array_equal(report.peak_torque[i], np.abs(sol.motor_torque).max(axis=0))
        assert np.array_equal(report.peak_current[i], np.abs(sol.current).max(axis=0))
        assert np.array_equal(report.peak_speed[i], np.abs(sol.motor_speed).max(axis=0))
        assert np.array_equal(report.peak_power[i], np.abs(P).max(axis=0))
        np.testing.assert_allclose(report.rms_torque[i],
                                   np.sqrt(np.trapezoid(sol.motor_torque**2, t, axis=0) / T),
                                   rtol=1e-12)
        np.testing.assert_allclose(report.rms_current[i],
                                   np.sqrt(np.trapezoid(sol.current**2, t, axis=0) / T),
                                   rtol=1e-12)
        np.testing.assert_allclose(report.energy[i], np.trapezoid(P, t, axis=0), rtol=1e-10,
                                   atol=1e-12)
        np.testing.assert_allclose(report.regenerated_energy[i],
                                   np.trapezoid(np.maximum(-P, 0), t, axis=0), rtol=1e-12)
        inertia_torque = 1e-4 * RATIO * sol.length_accel  # J (2 pi N / lead) L''
        np.testing.assert_allclose(
            report.inertia_share[i],
            np.sqrt(np.trapezoid(inertia_torque**2, t, axis=0) / T) / report.rms_torque[i],
            rtol=1e-10)
    # the second trajectory's rates: numpy's differences of its samples, as the report says
    t, sol = report.solutions[1]
    qd = np.gradient(q2, t2, axis=0)
    ref = platform.inverse(q2, qd, np.gradient(qd, t2, axis=0), "full", t=t2)
    assert np.array_equal(ref.motor_torque, sol.motor_torque)
    assert "peak_torque [N.m]" in report.summary()
    report.plot(tmp_path / "torque_speed.png")
    assert (tmp_path / "torque_speed.png").read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(ValueError, match="no drive"):
        stewart.sizing(stewart.Platform(), [(t1, q1)])
    # keep=False: the same numbers, one result's arrays reused, nothing to plot
    lean = stewart.sizing(platform, [(t1, q1, qd1, qdd1), (t2, q2), (t1, q1, qd1, qdd1)],
                          keep=False)
    from stewart.sizing import REPORT_FIELDS
    for name in REPORT_FIELDS:
        assert np.array_equal(getattr(lean, name)[:2], getattr(report, name)), name
        assert np.array_equal(getattr(lean, name)[2], getattr(report, name)[0]), name
    with pytest.raises(ValueError, match="keep=True"):
        lean.plot(tmp_path / "none.png")


def test_sizing_plot_draws_each_legs_own_limits(tmp_path, monkeypatch):
    # leg 2 with its own motor (k_t, current_max): its torque limit is not leg 1's
    pytest.importorskip("matplotlib")
    from matplotlib.axes import Axes
    drawn = []
    axhline = Axes.axhline
    monkeypatch.setattr(Axes, "axhline", lambda ax, y=0, *a, **kw: (drawn.append(y),
                                                                       axhline(ax, y, *a, **kw))[1])
    platform = driven(current_max=10, **{"torque_constant[2]": 2 * KT, "current_max[2]": 4})
    t, q, qd, qdd = manoeuvre(n=21, duration=0.2)
    stewart.sizing(platform, [(t, q, qd, qdd)]).plot(tmp_path / "legs.png")
    assert sorted(drawn) == pytest.approx(sorted([10 * KT, -10 * KT, 4 * 2 * KT, -4 * 2 * KT]))


def test_a_drive_whose_reflected_inertia_overflows_is_refused_by_its_parameters():
    # 2 pi N / lead = 1.9e301 rad/m: J r^2 is inf, every torque of the leg inf or NaN (the
    # inverse then refused each pose as if the pose were out of range)
    with pytest.raises(stewart.ParameterError, match=r"screw_lead\[3\] = 1e-300 m, "
                       r"gear_ratio\[3\] = 3: .* give the lead in metres"):
        driven(rotor_inertia=1e-4, **{"screw_lead[3]": 1e-300})
    with pytest.raises(stewart.ParameterError, match=r"screw_lead\[1\] = 1e-310 m"):
        driven(**{"screw_lead[1]": 1e-310})  # the ratio itself overflows
    assert np.isfinite(driven(rotor_inertia=1e-4, **{"screw_lead[3]": 1e-9}).reflected_mass).all()


def test_current_rates_that_overflow_are_refused():
    # increasing finite times 5e-324 s apart, or a jerk of 1e308: dI/dt and L dI/dt are inf
    # (they came back with status 0)
    platform = driven(winding_inductance=0.01, winding_resistance=1.0)
    t, q, qd, qdd = manoeuvre(n=3)
    rows = [0, 2]
    with pytest.raises(ValueError, match=r"row 0 \(t = 0 s\): the currents' rates over t overflow"):
        platform.inverse(q[rows], qd[rows], qdd[rows], t=np.array([0.0, 5e-324]))
    jerks = np.zeros((2, 6))
    jerks[:, 2] = 1e308
    with pytest.raises(ValueError, match="row 0: its jerk makes a current's rate or the voltage"):
        platform.inverse(q[rows], qd[rows], qdd[rows], jerks=jerks)
    ok = platform.inverse(q[rows], qd[rows], qdd[rows], t=np.array([0.0, 1e-3]))
    assert np.isfinite(ok.voltage).all() and np.any(ok.current_rate != 0)


def test_sizing_names_the_cell_that_is_not_a_number(tmp_path):
    # a CSV cell that does not read ("abc" in row 2's z): the differences spread its NaN to
    # rows 0..3, and the refusal named row 0's z_ddot
    t, q, _, _ = manoeuvre(n=6)
    write_poses(tmp_path / "cycle.csv", t, q)
    lines = (tmp_path / "cycle.csv").read_text().splitlines()
    cells = lines[3].split(",")
    cells[3] = "abc"
    lines[3] = ",".join(cells)
    (tmp_path / "cycle.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"cycle.csv: poses row 2 \(t = 0.8\): z = nan is not"):
        stewart.sizing(driven(), [tmp_path / "cycle.csv"])
    with pytest.raises(ValueError, match=r"trajectory 1: rates row 1 \(t = 0.4\): roll = inf"):
        qd = np.zeros((6, 6))
        qd[1, 3] = np.inf
        stewart.sizing(driven(), [(t, q, qd)])


def test_sizing_of_one_trajectory_not_in_a_list_says_so(tmp_path):
    # the path's characters were read as files ("/": a directory), (t, q) as two trajectories
    t, q, _, _ = manoeuvre(n=11)
    write_poses(tmp_path / "cycle.csv", t, q)
    for one in (str(tmp_path / "cycle.csv"), tmp_path / "cycle.csv", (t, q)):
        with pytest.raises(ValueError, match=r"one trajectory: give a list of them"):
            stewart.sizing(driven(), one)
    assert stewart.sizing(driven(), [(t, q)]).names == ["trajectory 1"]


def test_sizing_refuses_poses_of_another_length_than_t():
    t, q, _, _ = manoeuvre()
    with pytest.raises(ValueError, match=r"trajectory 1: poses has shape \(%d, 6\): it must be "
                       r"\(%d, 6\)" % (t.size - 1, t.size)):
        stewart.sizing(driven(), [(t, q[:-1])])


def write_poses(path, t, q):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "x", "y", "z", "roll", "pitch", "yaw"])
        for tj, row in zip(t, q):
            w.writerow([repr(float(tj))] + [repr(float(x)) for x in row])


def test_size_script_and_cli_columns(tmp_path, build_dir):
    platform_file = tmp_path / "drives.json"
    platform_file.write_text('{"screw_lead": 0.005, "gear_ratio": 3, "torque_constant": 0.5, '
                             '"rotor_inertia": 1e-4, "winding_resistance": 1.0, '
                             '"winding_inductance": 0.002, "current_max": 10}')
    t, q, _, _ = manoeuvre(n=101, duration=1.0)
    poses = tmp_path / "poses.csv"
    write_poses(poses, t, q)
    run = subprocess.run([sys.executable, ROOT / "scripts" / "size.py", "--platform",
                          platform_file, "--plot", tmp_path / "ts.png", "--csv",
                          tmp_path / "size.csv", poses], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    assert "rms_torque" in run.stdout and (tmp_path / "ts.png").exists()
    platform = stewart.Platform.from_file(platform_file)
    report = stewart.sizing(platform, [poses])
    rows = list(csv.DictReader(open(tmp_path / "size.csv")))
    assert float(rows[2]["peak_torque"]) == report.peak_torque[0, 2]
    for option in ("--csv", "--plot"):  # an output it cannot write: its name, no traceback
        run = subprocess.run([sys.executable, ROOT / "scripts" / "size.py", "--platform",
                              platform_file, option, tmp_path / "no" / "out", poses],
                             capture_output=True, text=True, timeout=300)
        assert run.returncode == 1 and "size.py: cannot write" in run.stderr, run.stderr
        assert "Traceback" not in run.stderr
    # stewart-solve: the drive columns of the same table, the currents' rates over its t
    out = tmp_path / "out.csv"
    params = ["--param", "screw_lead=0.005", "--param", "gear_ratio=3", "--param",
              "torque_constant=0.5", "--param", "rotor_inertia=1e-4", "--param",
              "winding_resistance=1.0", "--param", "winding_inductance=0.002"]
    run = subprocess.run([build_dir / "stewart-solve", *params, "--fidelity", "full", poses, out],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    data = list(csv.DictReader(open(out)))
    _, sol = report.solutions[0]
    voltage = np.array([[float(r[f"voltage{k}"]) for k in range(1, 7)] for r in data])
    torque = np.array([[float(r[f"motor_torque{k}"]) for k in range(1, 7)] for r in data])
    assert "current_max_legs" in data[0]
    # the CLI differentiates the samples itself (three-point differences, its own at the two
    # ends): close to numpy's between the ends, not equal
    inner = slice(3, -3)
    np.testing.assert_allclose(torque[inner], sol.motor_torque[inner], rtol=1e-3, atol=1e-3)
    np.testing.assert_allclose(voltage[inner], sol.voltage[inner], rtol=1e-3, atol=1e-2)
    bad = subprocess.run([sys.executable, ROOT / "scripts" / "size.py", "--platform",
                          ROOT / "platforms" / "genhexkins.json", poses], capture_output=True,
                         text=True, timeout=300)
    assert bad.returncode == 1 and "no drive" in bad.stderr


def test_a_reused_out_holds_zeros_after_a_model_without_drives():
    t, q, qd, qdd = manoeuvre(n=50)
    sol = driven(rotor_inertia=1e-4).inverse(q, qd, qdd, "massless")
    assert np.any(sol.motor_torque)
    again = stewart.Platform().inverse(q, qd, qdd, "massless", out=sol)
    assert again is sol
    for name in DRIVE_COLUMNS:
        assert not np.any(getattr(sol, name)), name


@pytest.mark.parametrize("machine", ["simona_motion_base", "rubin_m2_hexapod"])
def test_drive_files_are_their_machine_with_drives(machine):
    """platforms/<machine>_drives.json: every field of <machine>.json unchanged, the drive's
    fields added (the datasheet's numbers, platforms/README.md), a model that builds."""
    import json
    base = json.loads((ROOT / "platforms" / f"{machine}.json").read_text())
    drives = json.loads((ROOT / "platforms" / f"{machine}_drives.json").read_text())
    for key, value in base.items():
        if key != "description":
            assert drives[key] == value, key
    added = set(drives) - set(base)
    assert {"screw_lead", "torque_constant", "rotor_inertia", "current_max"} <= added
    platform = stewart.Platform.from_file(stewart.platform_files()[f"{machine}_drives"])
    lead, J = drives["screw_lead"], drives["rotor_inertia"]
    assert platform.reflected_mass == pytest.approx(J * (2 * np.pi / lead) ** 2, rel=1e-14)


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_the_inverse_fmu_gives_the_drive_outputs(version):
    """StewartPlatform with drives (parameters by element): its drive outputs at a pose with
    rates and accelerations given are the library's (Platform.inverse, one pose: dI/dt 0)."""
    from fmu_support import Unit, every_leg
    params = dict(screw_lead=LEAD, gear_ratio=GEAR, torque_constant=KT, rotor_inertia=1e-4,
                  winding_resistance=1.1, screw_efficiency=0.9, current_max=0.5)
    pose = [0.01, -0.02, 0.52, 0.03, -0.02, 0.05]
    rate = [0.1, 0.05, -0.08, 0.2, -0.1, 0.15]
    accel = [1.0, -0.5, 0.8, -1.5, 2.0, 0.7]
    u = Unit(version)
    try:
        assert u.init(fidelity=2, derivatives=1, **every_leg(**params)) == 0
        names = ["x", "y", "z", "roll", "pitch", "yaw"]
        u.set_values({**dict(zip(names, pose)), **{n + "_dot": v for n, v in zip(names, rate)},
                      **{n + "_ddot": v for n, v in zip(names, accel)}})
        assert u.do_step(0.0, 0.01) in (0, 1)
        got = {c: np.array(u.get([f"{c}[{k}]" for k in range(1, 7)]))
               for c in ("motor_torque", "current", "voltage", "motor_speed", "motor_power")}
        flags = u.get(["current_max_legs"])[0]
    finally:
        u.free()
    # the unit holds the step's end: the pose advanced by its rates and accelerations over h
    h, q, qd, qdd = 0.01, np.array(pose), np.array(rate), np.array(accel)
    sol = stewart.Platform(**params).inverse([q + h * qd + h * h / 2 * qdd], [qd + h * qdd],
                                             [qdd], "full")
    for name, values in got.items():
        np.testing.assert_allclose(values, getattr(sol, name)[0], rtol=1e-9, atol=1e-9)
    assert flags == sol.current_max_legs[0] and flags != 0


def test_current_rates_stop_at_a_failed_row():
    """A row that does not solve splits the trajectory: the rates of each run of solved rows are
    its own differences (one-sided beside the gap), the failed row keeps its zeros."""
    t, q, qd, qdd = manoeuvre(n=60)
    q[25, 2] = np.nan  # refused: not finite
    platform = driven(rotor_inertia=1e-4, winding_inductance=2e-3)
    sol = platform.inverse(q, qd, qdd, "massless", t=t)
    assert list(np.flatnonzero(sol.status)) == [25]
    for run in (slice(0, 25), slice(26, 60)):
        close(sol.current_rate[run], np.gradient(sol.current[run], t[run], axis=0), rel=1e-10)
    assert not np.any(sol.current_rate[25]) and not np.any(sol.voltage[25])


def manoeuvre_with_jerk(t):
    """The manoeuvre's poses at t and their rate, acceleration and jerk, exactly."""
    q, qd, qdd, qddd = (np.zeros((t.size, 6)) for _ in range(4))
    for axis, amplitude, w, home in ((2, 0.03, 3.0, 0.5), (3, 0.05, 2.0, 0.0),
                                     (5, 0.04, 2.5, 0.0)):
        q[:, axis] = home + amplitude * np.sin(w * t)
        qd[:, axis] = amplitude * w * np.cos(w * t)
        qdd[:, axis] = -amplitude * w**2 * np.sin(w * t)
        qddd[:, axis] = -amplitude * w**3 * np.cos(w * t)
    return q, qd, qdd, qddd


@pytest.mark.parametrize("fidelity", ["kinematic", "massless", "full"])
def test_current_rates_from_jerks_are_the_currents_time_derivative(fidelity):
    """jerks=: dI/dt from the drive's law along each pose's motion, against central differences
    in time of the currents of the exact poses at t -/+ h (away from the instants where the
    power flow or the leg's direction turns, where the current steps)."""
    params = dict(rotor_inertia=1e-4, screw_efficiency=0.9, screw_back_efficiency=0.7,
                  coulomb_friction=20, stribeck_friction=35, stribeck_speed=0.01,
                  viscous_friction=150, winding_resistance=1.1, winding_inductance=2e-3)
    platform = driven(**params)
    t = np.linspace(0.05, 2.0, 80)
    q, qd, qdd, qddd = manoeuvre_with_jerk(t)
    sol = platform.inverse(q, qd, qdd, fidelity, jerks=qddd)
    h = 1e-4 if fidelity == "full" else 1e-5
    before = platform.inverse(*manoeuvre_with_jerk(t - h)[:3], fidelity)
    after = platform.inverse(*manoeuvre_with_jerk(t + h)[:3], fidelity)
    differences = (after.current - before.current) / (2 * h)

    def flow(s):  # the screw's power flow and the leg's direction at each row and leg
        v = s.length_rate
        friction = ((20 + 15 * np.exp(-(v / 0.01) ** 2)) * np.sign(v) + 150 * v)
        return np.sign((s.force + friction) * v), np.sign(v)
    steady = np.ones_like(sol.current, bool)
    for a, b in list(zip(flow(sol), flow(before))) + list(zip(flow(sol), flow(after))):
        steady &= a == b
    assert steady.mean() > 0.8
    scale = np.max(np.abs(differences[steady]))
    np.testing.assert_allclose(sol.current_rate[steady], differences[steady], rtol=0,
                               atol=(1e-4 if fidelity == "full" else 1e-6) * scale)
    close(sol.voltage, 1.1 * sol.current + KT * sol.motor_speed + 2e-3 * sol.current_rate)
    with pytest.raises(ValueError, match="not both"):
        platform.inverse(q, qd, qdd, fidelity, t=t, jerks=qddd)


def test_the_envelope_sweep_gives_the_sizing_numbers(tmp_path):
    """A load-envelope sweep on a platform with drives: per case the drive columns are
    stewart.sizing's on the case's trajectory; without drives they are null."""
    pytest.importorskip("distributed")
    import json
    import pyarrow.parquet as pq
    from stewart.sweeps import run
    drive = {"screw_lead": LEAD, "gear_ratio": GEAR, "torque_constant": KT,
             "rotor_inertia": 1e-4, "winding_resistance": 1.0, "winding_inductance": 2e-3}
    spec = {"kind": "envelope", "fidelity": ["massless"], "platform": drive,
            "payload_mass": [20.0], "payload_com": [[0.0, 0.0, 0.1]],
            "manoeuvres": [{"scene": "heave", "amplitude": [1.0]}], "duration": 1.0}
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(spec))
    run(path, tmp_path / "out", ROOT / "scenes", progress=False, log=lambda m: None, workers=1)
    row = pq.read_table(tmp_path / "out" / "envelope.parquet").to_pylist()[0]
    from stewart.sweeps.spec import manoeuvre_samples, resolve
    resolved = resolve(json.loads(path.read_text()), ROOT / "scenes")
    t, q, qd, qdd = manoeuvre_samples(resolved, resolved["manoeuvres"][0], 1.0, 1.0)
    platform = stewart.Platform(**drive, payload_mass=20.0, payload_com=[0.0, 0.0, 0.1])
    report = stewart.sizing(platform, [(t, q, qd, qdd)], "massless")
    for k in range(6):
        assert row[f"peak_motor_torque_{k + 1}"] == report.peak_torque[0, k]
        assert row[f"rms_motor_torque_{k + 1}"] == report.rms_torque[0, k]
        assert row[f"peak_current_{k + 1}"] == report.peak_current[0, k]
        assert row[f"peak_motor_speed_{k + 1}"] == report.peak_speed[0, k]
        assert row[f"peak_electrical_power_{k + 1}"] == report.peak_power[0, k]
    spec["platform"] = {}
    path.write_text(json.dumps(spec))
    run(path, tmp_path / "plain", ROOT / "scenes", progress=False, log=lambda m: None, workers=1)
    plain = pq.read_table(tmp_path / "plain" / "envelope.parquet").to_pylist()[0]
    assert plain["peak_motor_torque_1"] is None and plain["peak_force_1"] > 0


def test_stewart_solve_takes_the_poses_jerks(tmp_path, build_dir):
    """x_dddot..yaw_dddot columns: stewart-solve's currents' rates from the jerks, as
    Platform.inverse(jerks=) gives them, bit for bit."""
    t = np.linspace(0.0, 1.0, 41)
    q, qd, qdd, qddd = manoeuvre_with_jerk(t)
    names = ["x", "y", "z", "roll", "pitch", "yaw"]
    header = ["t"] + [n + s for s in ("", "_dot", "_ddot", "_dddot") for n in names]
    rows = np.column_stack([t, q, qd, qdd, qddd])
    poses = tmp_path / "poses.csv"
    poses.write_text(",".join(header) + "\n" +
                     "".join(",".join(repr(float(v)) for v in r) + "\n" for r in rows))
    params = dict(rotor_inertia=1e-4, winding_resistance=1.1, winding_inductance=2e-3,
                  coulomb_friction=20, viscous_friction=100)
    args = [a for k, v in {"screw_lead": LEAD, "gear_ratio": GEAR, "torque_constant": KT,
                            **params}.items() for a in ("--param", f"{k}={v!r}")]
    out = tmp_path / "out.csv"
    run = subprocess.run([build_dir / "stewart-solve", *args, "--fidelity", "massless", poses,
                          out], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    data = list(csv.DictReader(open(out)))
    rate = np.array([[float(r[f"current_rate{k}"]) for k in range(1, 7)] for r in data])
    voltage = np.array([[float(r[f"voltage{k}"]) for k in range(1, 7)] for r in data])
    sol = driven(**params).inverse(q, qd, qdd, "massless", jerks=qddd)
    assert np.array_equal(rate, sol.current_rate) and np.any(rate)
    assert np.array_equal(voltage, sol.voltage)
