"""The shipped manoeuvres (manoeuvres/*.csv): each file regenerates byte for byte from
scripts/make_manoeuvres.py, the package ships the same files and stewart.manoeuvre reads them; and
the physics, checked from the files alone with formulas written here: rest reads (0, 0, g); the
coordinated turn has no lateral specific force at the centre of gravity and banks at
atan(v omega / g); braking decelerates at the model's rate and stops at the closed-form time; the
take-off reaches V_R and 15 deg of pitch; the cars, re-integrated from f and w, pass between the
cones of ISO 3888-1 and of the slalom."""
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import make_manoeuvres as model  # scripts/ (conftest.py): the models' stated constants
import stewart

ROOT = pathlib.Path(__file__).resolve().parents[2]
G = 9.81
NAMES = ["aircraft_takeoff", "aircraft_turn", "car_braking", "car_lane_change", "car_slalom"]


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory):
    out = tmp_path_factory.mktemp("manoeuvres")
    script = ROOT / "scripts" / "make_manoeuvres.py"
    subprocess.run([sys.executable, str(script), "--out", str(out)], check=True,
                   capture_output=True, timeout=300)
    return out


@pytest.mark.parametrize("name", NAMES)
def test_each_file_regenerates_byte_for_byte(name, regenerated):
    shipped = ROOT / "manoeuvres" / f"{name}.csv"
    assert (regenerated / f"{name}.csv").read_bytes() == shipped.read_bytes()


def test_the_package_ships_the_files_and_reads_them():
    files = stewart.manoeuvre_files()
    assert sorted(files) == NAMES == sorted(p.stem for p in (ROOT / "manoeuvres").glob("*.csv"))
    for name, path in files.items():
        assert path.read_bytes() == (ROOT / "manoeuvres" / f"{name}.csv").read_bytes()
        t, f, w = stewart.manoeuvre(name)
        raw = np.loadtxt(ROOT / "manoeuvres" / f"{name}.csv", delimiter=",", skiprows=1)
        assert np.array_equal(np.column_stack([t, f, w]), raw)
        assert np.allclose(np.diff(t), 0.01, rtol=0, atol=1e-12) and t[0] == 0


def test_the_loader_refuses_what_is_not_a_manoeuvre(tmp_path):
    with pytest.raises(ValueError, match="no manoeuvre 'car_crash'"):
        stewart.manoeuvre("car_crash")
    bad = tmp_path / "bad.csv"
    bad.write_text("t,x\n0,1\n")
    with pytest.raises(ValueError, match="not the columns"):
        stewart.manoeuvre(bad)
    bad.write_text("t,f_x,f_y,f_z,w_x,w_y,w_z\n0,0,0,9.81,0,0,0\n0.01,0,nan,9.81,0,0,0\n")
    with pytest.raises(ValueError, match="row 2 .* not finite"):
        stewart.manoeuvre(bad)
    with pytest.raises(ValueError, match="missing.csv"):
        stewart.manoeuvre(tmp_path / "missing.csv")


@pytest.mark.parametrize("name", NAMES)
def test_every_manoeuvre_starts_in_steady_straight_motion(name):
    """At rest or at constant speed in a straight line: f = (0, 0, g), w = 0."""
    _, f, w = stewart.manoeuvre(name)
    assert f[0].tolist() == [0.0, 0.0, G] and w[0].tolist() == [0.0, 0.0, 0.0]


def centre_of_gravity(t, f, w, head):
    """f moved from the head back to the centre of gravity: less alpha x r + w x (w x r), alpha by
    central differences of w."""
    alpha = np.gradient(w, t[1] - t[0], axis=0)
    r = np.broadcast_to(head, w.shape)
    return f - np.cross(alpha, r) - np.cross(w, np.cross(w, r))


def test_braking_decelerates_at_the_model_rate_and_stops():
    t, f, w = stewart.manoeuvre("car_braking")
    a, v0 = model.BRAKING_DECELERATION, model.BRAKING_SPEED
    t_stop = 2.0 + model.BRAKING_BUILD_UP / 2 + v0 / a  # the ramp's mean is half the rate
    plateau = (t >= 2.0 + model.BRAKING_BUILD_UP) & (t < t_stop)
    assert np.all(f[plateau, 0] == -a)
    braking = np.flatnonzero(f[:, 0] < 0)
    assert t[braking[-1]] < t_stop <= t[braking[-1]] + 0.01
    assert np.all(f[t >= t_stop] == [0.0, 0.0, G]) and np.all(w == 0)
    # the speed lost, sum of f_x dt, is the initial speed (to one sample of deceleration)
    assert abs(np.sum(f[:, 0]) * 0.01 + v0) < a * 0.01


def test_coordinated_turn_has_no_lateral_specific_force():
    t, f, w = stewart.manoeuvre("aircraft_turn")
    cg = centre_of_gravity(t, f, w, model.HEAD_AIRCRAFT)
    assert np.max(np.abs(cg[:, 1])) < 5e-3
    assert np.max(np.abs(f[:, 1])) > 0.1  # at the head the roll acceleration is felt sideways
    # the steady turn: |w| = omega, bank = atan(v omega / g) from the roll angle integrated from
    # w_x, the specific force g / cos(bank) along the body's z
    steady = (t > 12) & (t < 38)
    bank = np.cumsum(w[:, 0]) * 0.01
    omega = np.linalg.norm(w[steady], axis=1)
    assert omega == pytest.approx(3 * math.pi / 180, rel=1e-6)
    expected = math.atan(model.TURN_SPEED * omega[0] / G)
    assert np.abs(bank[steady]) == pytest.approx(expected, abs=2e-3)
    assert np.arctan2(-w[steady, 1], w[steady, 2]) == pytest.approx(expected, abs=1e-9)
    assert cg[steady, 2] == pytest.approx(G / math.cos(expected), rel=1e-4)
    assert np.abs(cg[steady, 0]) == pytest.approx(0, abs=1e-4)


def test_takeoff_reaches_rotation_speed_and_pitch_attitude():
    t, f, w = stewart.manoeuvre("aircraft_takeoff")
    rotating = np.flatnonzero(w[:, 1] != 0)
    before = slice(0, rotating[0])
    assert np.all(w[before] == 0) and np.all(f[before, 1:] == [0.0, G])
    # sum of f_x dt on the level runway: the speed at rotation
    assert np.sum(f[before, 0]) * 0.01 == pytest.approx(model.ROTATION_SPEED, abs=0.05)
    assert np.all(f[t < 2.0] == [0.0, 0.0, G])
    nose_up = -np.cumsum(w[:, 1]) * 0.01
    assert nose_up[-1] == pytest.approx(15 * math.pi / 180, abs=1e-4)
    # 1 s ramp up, 4 s at 3 deg/s, 1 s ramp down: 15 deg in 6 s
    assert t[rotating[-1]] - t[rotating[0]] == pytest.approx(6.0, abs=0.02)


def integrate_car(t, f, w, speed, x0, y0):
    """The car's track (X, Y) re-integrated from the file: the centre of gravity's specific force,
    heading from w_z, body lateral velocity from dv_y/dt = f_y - r u at constant forward speed u."""
    dt = t[1] - t[0]

    def integral(x):
        return np.concatenate([[0.0], np.cumsum((x[1:] + x[:-1]) / 2 * dt)])

    cg = centre_of_gravity(t, f, w, model.HEAD_CAR)
    heading = integral(w[:, 2])
    vy = integral(cg[:, 1] - w[:, 2] * speed)
    x = x0 + integral(speed * np.cos(heading) - vy * np.sin(heading))
    y = y0 + integral(speed * np.sin(heading) + vy * np.cos(heading))
    return x, y


def test_double_lane_change_stays_between_the_iso_3888_1_cones():
    """ISO 3888-1 for a car of width b: lanes of 1.1 b + 0.25 (15 m), 1.2 b + 0.25 (25 m, right
    cone line 3.5 m left of the first's, after 30 m) and 1.3 b + 0.25 (30 m, after 25 m more,
    right line in line with the first's); the car's sides stay inside."""
    t, f, w = stewart.manoeuvre("car_lane_change")
    x, y = integrate_car(t, f, w, model.LANE_CHANGE_SPEED, -40.0, 0.0)
    b = model.CAR_WIDTH
    right = -(1.1 * b + 0.25) / 2
    lanes = [(0, 15, right, 1.1 * b + 0.25), (45, 70, right + 3.5, 1.2 * b + 0.25),
             (95, 125, right, 1.3 * b + 0.25)]
    for x0, x1, y_right, width in lanes:
        inside = (x >= x0) & (x <= x1)
        assert inside.sum() > 50
        assert np.min(y[inside] - b / 2 - y_right) > 0.05
        assert np.max(y[inside] + b / 2 - (y_right + width)) < -0.05
    assert x[-1] > 160


def test_slalom_passes_the_cones_on_alternate_sides():
    t, f, w = stewart.manoeuvre("car_slalom")
    x, y = integrate_car(t, f, w, model.SLALOM_SPEED, -60.0, 0.0)
    for k in range(8):
        at_cone = y[np.argmin(np.abs(x - 18.0 * k))]
        side = 1 if k % 2 == 0 else -1  # the first cone on the car's right: the car on its left
        assert side * at_cone > model.CAR_WIDTH / 2 + 0.15
    assert np.max(np.abs(f[:, 1])) < 0.5 * G  # within a linear tyre model's range


def test_random_vehicle_peaks_repeats_and_refusals():
    """stewart.random_vehicle: each axis peaks at 0.2 to 1 times its peak (about (0, 0, g) for
    the specific force), the same seed gives the same signal and another seed another; bad times
    and peaks are refused by name."""
    t = np.arange(0, 20, 0.01)
    peaks = []
    for seed in range(20):
        f, w = stewart.random_vehicle(np.random.default_rng(seed), t, force_peak=5.0, rate_peak=2.0)
        assert f.shape == w.shape == (len(t), 3)
        peaks.append(np.r_[np.abs(f - [0, 0, G]).max(axis=0) / 5.0, np.abs(w).max(axis=0) / 2.0])
    peaks = np.array(peaks)
    assert peaks.min() >= 0.2 - 1e-12 and peaks.max() <= 1 + 1e-12 and peaks.max() > 0.9
    one = stewart.random_vehicle(np.random.default_rng(7), t)
    again = stewart.random_vehicle(np.random.default_rng(7), t)
    other = stewart.random_vehicle(np.random.default_rng(8), t)
    assert all(np.array_equal(a, b) for a, b in zip(one, again))
    assert not np.array_equal(one[0], other[0])
    with pytest.raises(ValueError, match=r"t\[2\]"):
        stewart.random_vehicle(np.random.default_rng(7), [0.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="force_peak"):
        stewart.random_vehicle(np.random.default_rng(7), t, force_peak=math.nan)
    with pytest.raises(ValueError, match="rate_peak"):
        stewart.random_vehicle(np.random.default_rng(7), t, rate_peak=-1.0)


def test_random_vehicle_on_any_times_and_numpy_peaks():
    """No times give empty signals; times before 0 give a signal of the same peaks (0.2 to 1
    times each peak) as any; a numpy scalar peak is the same number as a float."""
    f, w = stewart.random_vehicle(np.random.default_rng(3), [])
    assert f.shape == w.shape == (0, 3)
    t = np.arange(-30, -10, 0.01)
    f, w = stewart.random_vehicle(np.random.default_rng(3), t, force_peak=5.0, rate_peak=2.0)
    peaks = np.r_[np.abs(f - [0, 0, G]).max(axis=0) / 5.0, np.abs(w).max(axis=0) / 2.0]
    assert peaks.min() >= 0.2 - 1e-12 and peaks.max() <= 1 + 1e-12
    t = np.arange(0, 20, 0.01)
    plain = stewart.random_vehicle(np.random.default_rng(4), t, force_peak=5.0, rate_peak=2.0)
    numpy = stewart.random_vehicle(np.random.default_rng(4), t, force_peak=np.float32(5.0),
                                   rate_peak=np.int64(2))
    assert all(np.array_equal(a, b) for a, b in zip(plain, numpy))


def test_a_manoeuvre_file_as_a_spreadsheet_writes_it(tmp_path):
    """A shipped manoeuvre rewritten with a UTF-8 byte order mark and CRLF line ends (a
    spreadsheet's "CSV UTF-8"): the same columns, bit for bit."""
    path = stewart.manoeuvre_files()["car_braking"]
    sheet = tmp_path / "sheet.csv"
    sheet.write_bytes(b"\xef\xbb\xbf" + path.read_bytes().replace(b"\n", b"\r\n"))
    for a, b in zip(stewart.manoeuvre("car_braking"), stewart.manoeuvre(sheet)):
        assert np.array_equal(a, b)
