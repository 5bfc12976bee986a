"""stewart-solve from the command line: format, derivative columns, and errors."""
import csv
import math

import numpy as np
import pytest

import reference
import scenes

LEGS = range(1, 7)
EXPECTED_HEADER = (["t"] + [f"L{k}" for k in LEGS] + [f"L_dot{k}" for k in LEGS]
                   + [f"L_ddot{k}" for k in LEGS] + [f"F{k}" for k in LEGS]
                   + ["condition", "iterations", "status"])


def read(path):
    """header and values; the status column (a limit class name) as 0 for "none", else -1."""
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        text = header.index("status") if "status" in header else -1
        return header, np.array([[(0.0 if v == "none" else -1.0) if i == text else float(v)
                                  for i, v in enumerate(row)] for row in reader])


def column(header, data, name):
    return data[:, header.index(name)]


def run_manoeuvre(solve, tmp_path, name, *, dt=0.1, derivatives=True, fidelity="massless"):
    pose_csv, out_csv = tmp_path / f"{name}_in.csv", tmp_path / f"{name}_{fidelity}_out.csv"
    scenes.write_pose_csv(name, pose_csv, dt=dt, derivatives=derivatives)
    result = solve("--fidelity", fidelity, pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    return read(out_csv)


def test_header_and_rows(solve, tmp_path):
    header, data = run_manoeuvre(solve, tmp_path, "yaw")
    assert header == EXPECTED_HEADER
    assert data.shape == (121, len(EXPECTED_HEADER))
    assert np.all(np.isfinite(data))
    np.testing.assert_allclose(data[:, 0], np.arange(121) * 0.1, atol=1e-12)


def test_lengths_match_closed_form_heave(solve, tmp_path):
    header, data = run_manoeuvre(solve, tmp_path, "heave")
    t = data[:, 0]
    z = 0.5 + 0.04 * np.sin(5 * t)
    chord2 = math.sin(math.radians(15)) ** 2  # (2 r sin 15deg)^2 with r = 0.5
    for k in LEGS:
        np.testing.assert_allclose(column(header, data, f"L{k}"), np.sqrt(chord2 + z ** 2),
                                   rtol=0, atol=1e-14)


def test_exact_rates_agree_with_differences_of_lengths(solve, tmp_path):
    header, data = run_manoeuvre(solve, tmp_path, "roll", dt=0.001)
    t = data[:, 0]
    for k in LEGS:
        L = column(header, data, f"L{k}")
        L_dot = column(header, data, f"L_dot{k}")
        fd = np.gradient(L, t)
        np.testing.assert_allclose(L_dot[1:-1], fd[1:-1], atol=2e-6)
        fd2 = np.gradient(L_dot, t)
        np.testing.assert_allclose(column(header, data, f"L_ddot{k}")[1:-1], fd2[1:-1], atol=5e-5)


@pytest.mark.parametrize("name", ["heave", "pitch"])
def test_missing_derivative_columns_come_from_differences(solve, tmp_path, name):
    """Without derivative columns, central differences of the poses stand in: second-order
    accurate, so at dt = 1 ms they agree with the exact derivatives closely."""
    h_exact, exact = run_manoeuvre(solve, tmp_path, name, dt=0.001)
    (tmp_path / "fd").mkdir()
    h_fd, fd = run_manoeuvre(solve, tmp_path / "fd", name, dt=0.001, derivatives=False)
    assert h_exact == h_fd
    interior = slice(1, -1)
    for k in LEGS:
        # central differences err by about h^2/6 f''' (rates) and h^2/12 f'''' (accelerations)
        for name_, atol in ((f"L{k}", 0), (f"L_dot{k}", 5e-6), (f"L_ddot{k}", 5e-5)):
            np.testing.assert_allclose(column(h_fd, fd, name_)[interior],
                                       column(h_exact, exact, name_)[interior], atol=atol + 1e-15)
        # one-sided differences at the ends are less accurate, but still close
        np.testing.assert_allclose(column(h_fd, fd, f"L_dot{k}")[[0, -1]],
                                   column(h_exact, exact, f"L_dot{k}")[[0, -1]], atol=1e-5)


def test_massless_heave_forces_in_closed_form(solve, tmp_path):
    header, data = run_manoeuvre(solve, tmp_path, "heave")
    t = data[:, 0]
    z = 0.5 + 0.04 * np.sin(5 * t)
    z_ddot = -0.04 * 25 * np.sin(5 * t)
    mass = reference.M_PLATFORM
    for k in LEGS:
        L = column(header, data, f"L{k}")
        np.testing.assert_allclose(column(header, data, f"F{k}"), mass * (9.81 + z_ddot) * L / (6 * z),
                                   rtol=1e-10)


def test_kinematic_level_has_no_forces(solve, tmp_path):
    header, data = run_manoeuvre(solve, tmp_path, "yaw", fidelity="kinematic")
    for k in LEGS:
        assert np.all(column(header, data, f"F{k}") == 0)


def test_full_level_close_to_massless(solve, tmp_path):
    """The thesis' legs weigh 0.143 kg per body against a 106.03 kg platform: the lengths are
    the same, and the full model's forces exceed the massless ones by more than nothing and by
    less than the legs' whole weight can add: 12 x 0.143 / 106.03 = 1.62 % (the manoeuvre is
    slow, so inertia adds little; measured: 0.72 % to 0.88 %)."""
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "full.csv"
    scenes.write_pose_csv("pitch", pose_csv, dt=0.1)
    result = solve("--fidelity", "full", pose_csv, out_csv)
    if result.returncode != 0 and "not available" in result.stderr:
        pytest.skip("this build has no full 14-body level")
    assert result.returncode == 0, result.stderr
    header, full = read(out_csv)
    _, massless = run_manoeuvre(solve, tmp_path, "pitch")
    for k in LEGS:
        np.testing.assert_allclose(column(header, full, f"L{k}"), column(header, massless, f"L{k}"),
                                   atol=1e-11)
        ratio = column(header, full, f"F{k}") / column(header, massless, f"F{k}")
        assert np.all(ratio > 1.003) and np.all(ratio < 1 + 12 * 0.143 / 106.03), ratio


def test_single_row_is_a_platform_at_rest(solve, tmp_path):
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n")
    result = solve(pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    assert np.all(data[:, [header.index(f"L_dot{k}") for k in LEGS]] == 0)


BAD_INPUTS = {
    "missing_column": ("t,x,y,z,roll,pitch\n0,0,0,0.5,0,0\n", "t,x,y,z,roll,pitch,yaw"),
    "not_a_number": ("t,x,y,z,roll,pitch,yaw\n0,0,0,abc,0,0,0\n", "column z = 'abc'"),
    "nan_value": ("t,x,y,z,roll,pitch,yaw\n0,0,0,nan,0,0,0\n", "column z = 'nan'"),
    "short_row": ("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0\n", "line 2"),
    "time_not_increasing": ("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n0,0,0,0.5,0,0,0\n",
                            "does not increase"),
    "partial_derivatives": ("t,x,y,z,roll,pitch,yaw,x_dot\n0,0,0,0.5,0,0,0,0\n", "_dot columns"),
    "no_rows": ("t,x,y,z,roll,pitch,yaw\n", "no data rows"),
    "unreachable": ("t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0.5235987755982988\n", "leg 1"),
}


@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_bad_input_is_reported(solve, tmp_path, case):
    text, mention = BAD_INPUTS[case]
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose_csv.write_text(text)
    result = solve(pose_csv, out_csv)
    assert result.returncode == 1
    assert mention in result.stderr
    assert not out_csv.exists()


def test_bad_command_lines(solve, tmp_path):
    assert solve("--fidelity", "exact", "a", "b").returncode == 2
    assert solve("only-one-path").returncode == 2
    assert solve("--bogus", "a", "b").returncode == 2
    result = solve(tmp_path / "missing.csv", tmp_path / "out.csv")
    assert result.returncode == 1 and "cannot open" in result.stderr
    assert "usage" in solve("--help").stdout
    for option, words in (("--fidelity", "--fidelity needs a value (kinematic|massless|full)"),
                          ("--tolerance", "--tolerance needs a value")):
        result = solve(option)
        assert result.returncode == 2 and words in result.stderr, result.stderr
    result = solve("--tolerance", "1e-16", tmp_path / "in.csv", tmp_path / "out.csv")
    assert result.returncode != 0 and "tolerance" in result.stderr, result.stderr


def test_parameters_from_the_command_line(solve, tmp_path):
    """--param NAME=VALUE (the FMU's names): another geometry gives the closed-form lengths
    |p + R b - a| computed here, and a payload at rest is carried by the six legs:
    sum_k F_k n_kz = (platform + payload mass) g, all six equal by symmetry."""
    from reference import lengths as closed_form_lengths
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose = [0.01, -0.02, 0.55, 0.05, -0.03, 0.1]
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n0," + ",".join(map(str, pose)) + "\n")
    beta = (5, 25, 125, 145, 245, 265)
    args = ["--param", "base_radius=0.6", "--param", "platform_radius=0.4"]
    for k, b in enumerate(beta):
        args += ["--param", f"base_angle[{k + 1}]={math.radians(b)!r}"]
    result = solve(*args, pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    got = np.array([column(header, data, f"L{k}")[0] for k in LEGS])
    np.testing.assert_allclose(got, closed_form_lengths(pose, 0.6, 0.4, np.radians(beta)), rtol=1e-13)

    home = [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n")
    result = solve("--param", "payload_mass=50", pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    forces = np.array([column(header, data, f"F{k}")[0] for k in LEGS])
    n_z = 0.5 / closed_form_lengths(home)          # vertical component of each leg's axis
    platform_mass = reference.M_PLATFORM  # the thesis disc, model.md §2
    np.testing.assert_allclose(forces, (platform_mass + 50) * 9.81 / (6 * n_z), rtol=1e-12)


@pytest.mark.parametrize("assignment,words,code", [
    ("payload_mas=1", "the nearest is payload_mass", 2),
    ("base_angle[7]=1", "no parameter is named 'base_angle[7]'", 2),
    ("payload_mass", "is not NAME=VALUE", 2),
    ("payload_mass=heavy", "'heavy' is not a number", 2),
    ("payload_mass=-1", "payload_mass = -1 kg must be >= 0", 1),
    ("gravity[3]=nan", "parameter gravity[3] is nan", 1),
])
def test_bad_parameters_on_the_command_line(solve, tmp_path, assignment, words, code):
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n")
    result = solve("--param", assignment, pose_csv, out_csv)
    assert result.returncode == code and words in result.stderr, result.stderr
    assert not out_csv.exists()


def test_condition_is_the_one_norm_condition_of_the_leg_jacobian(solve, tmp_path):
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    rng = np.random.default_rng(7)
    poses = np.column_stack([rng.uniform(-0.05, 0.05, 20), rng.uniform(-0.05, 0.05, 20),
                             rng.uniform(0.45, 0.55, 20), *(rng.uniform(-0.3, 0.3, (3, 20)))])
    with open(pose_csv, "w") as f:
        f.write("t,x,y,z,roll,pitch,yaw\n")
        for i, q in enumerate(poses):
            f.write(",".join(repr(float(v)) for v in [i, *q]) + "\n")
    result = solve(pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    # J with rows (n_k, (R b_k) x n_k / radius), from the pose alone (tests/python/reference.py)
    expected = [np.linalg.cond(reference.leg_jacobian(q), 1) for q in poses]
    np.testing.assert_allclose(column(header, data, "condition"), expected, rtol=1e-9)


def test_still_pose_at_vanishing_spacing_stays_at_rest(solve, tmp_path):
    """Finite differences in divided-difference form: a pose that does not move has zero rates
    even when the samples are 1e-200 s apart (weights of 1/h^2 would overflow to inf * 0)."""
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(
        f"{i * 1e-200!r},0.01,0,0.5,0,0,0.1\n" for i in range(4)))
    result = solve(pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    for k in LEGS:
        assert np.all(column(header, data, f"L_dot{k}") == 0)
        assert np.all(column(header, data, f"L_ddot{k}") == 0)


def test_every_inverse_option_by_name(solve, tmp_path):
    """--param takes every option of the library's inverse table: each at its table default
    changes no byte; a value below its range is refused naming it; fidelity and tolerance are
    the --fidelity and --tolerance flags' options; warn_condition and singular_condition reach
    the limit check and the solver; the usage lists each option."""
    from stewart import _core
    pose_csv = tmp_path / "in.csv"
    scenes.write_pose_csv("combined", pose_csv, dt=0.05)

    def run(*args):
        out = tmp_path / "out.csv"
        out.unlink(missing_ok=True)
        result = solve(*args, pose_csv, out)
        return result, (out.read_bytes() if out.exists() else None)

    plain = run()[1]
    usage = solve("--help").stdout
    for option in _core.option_table("inverse"):
        name = option["name"]
        assert f"{name} [" in usage, name
        result, got = run("--param", f"{name}={option['default']!r}")
        assert result.returncode == 0 and got == plain, (name, result.stderr)
        result, got = run("--param", f"{name}={option['min'] - 1!r}")
        assert result.returncode == 2 and f"{name} = " in result.stderr, (name, result.stderr)
        assert got is None
    kinematic = run("--fidelity", "kinematic")[1]
    assert kinematic != plain and run("--param", "fidelity=0")[1] == kinematic
    assert run("--param", "fidelity=2", "--param", "tolerance=1e-9")[1] == \
        run("--fidelity", "full", "--tolerance", "1e-9")[1]
    # every pose of the manoeuvre has a condition number above 1: all flagged, then all refused
    result, got = run("--param", "warn_condition=1")
    assert result.returncode == 0, result.stderr
    with open(tmp_path / "out.csv") as f:
        assert {row["status"] for row in csv.DictReader(f)} == {"condition"}
    result, got = run("--param", "warn_condition=1", "--param", "singular_condition=1")
    assert result.returncode == 1 and "singular" in result.stderr and got is None, result.stderr


def test_forward_options_by_name(solve, tmp_path):
    """With --forward, --param takes forward kinematics' table (each default changes no byte,
    tolerance is --tolerance's) and refuses an inverse option it would ignore."""
    from stewart import _core
    pose_csv, legs_csv = tmp_path / "pose.csv", tmp_path / "legs.csv"
    scenes.write_pose_csv("combined", pose_csv, dt=0.05)
    assert solve(pose_csv, legs_csv).returncode == 0

    def run(*args):
        out = tmp_path / "out.csv"
        out.unlink(missing_ok=True)
        result = solve("--forward", *args, legs_csv, out)
        return result, (out.read_bytes() if out.exists() else None)

    plain = run()[1]
    usage = solve("--help").stdout
    for option in _core.option_table("forward"):
        assert f"{option['name']} [" in usage, option["name"]
        result, got = run("--param", f"{option['name']}={option['default']!r}")
        assert result.returncode == 0 and got == plain, (option["name"], result.stderr)
    assert run("--param", "tolerance=1e-6")[1] == run("--tolerance", "1e-6")[1] != plain
    result, got = run("--param", "fidelity=2")
    assert result.returncode == 2 and got is None
    assert "fidelity: not an option of forward kinematics" in result.stderr, result.stderr


def test_option_names_are_no_parameter_names():
    """--param finds an option before a parameter: no option of any table may hide one."""
    import stewart
    from stewart import _core
    parameters = {p["name"] for p in stewart.parameters()}
    for direction in ("inverse", "forward", "plant"):
        names = {o["name"] for o in _core.option_table(direction)}
        assert not names & parameters, (direction, names & parameters)


class _Table(dict):
    columns = property(lambda self: list(self))


def _table(path):
    """{column: float array, or a list of text for a text column}, in the file's order."""
    with open(path, newline="") as f:
        header, *rows = list(csv.reader(f))
    table = _Table()
    for i, name in enumerate(header):
        cells = [r[i] for r in rows]
        try:
            table[name] = np.array([float(c) for c in cells])
        except ValueError:
            table[name] = cells
    return table


@pytest.mark.parametrize("units, length, angle", [("mm,deg", 1e3, 180 / math.pi),
                                                  ("deg,um", 1e6, 180 / math.pi),
                                                  ("mrad", 1.0, 1e3)])
def test_units_of_the_output_are_the_si_output_converted(solve, tmp_path, units, length, angle):
    """--units: every length (legs, their rates and accelerations, stroke and interference
    margins, position ranges) times the length unit's factor, every angle (joint margins, angle
    ranges) times the angle's; forces, conditions, status and margin_axis as in SI."""
    path = tmp_path / "in.csv"
    rows = [[0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0], [0.1, 0.01, -0.02, 0.51, 0.02, 0.01, 0.0],
            [0.2, 0.02, 0.0, 0.52, 0.04, 0.0, 0.01]]
    path.write_text("t,x,y,z,roll,pitch,yaw\n" + "".join(",".join(map(repr, r)) + "\n" for r in rows))
    for extra in ([], ["--units", units]):
        r = solve("--limits", "--ranges", *extra, path, tmp_path / f"out{len(extra)}.csv")
        assert r.returncode == 0, r.stderr
    si, converted = _table(tmp_path / "out0.csv"), _table(tmp_path / "out2.csv")
    assert list(si.columns) == list(converted.columns)
    lengths = [c for c in si.columns if c.startswith("L") or c in (
        "margin_stroke", "margin_interference") or c[:2] in ("x_", "y_", "z_")]
    angles = ["margin_base_joint", "margin_platform_joint",
              *[f"{a}_{e}" for a in ("roll", "pitch", "yaw") for e in ("min", "max")]]
    assert len(lengths) == 18 + 2 + 6 and len(angles) == 8
    for c in si.columns:
        factor = length if c in lengths else angle if c in angles else 1.0
        if isinstance(si[c], list):
            assert si[c] == converted[c], c
        else:
            np.testing.assert_allclose(converted[c], si[c] * factor, rtol=1e-15, atol=0,
                                       err_msg=c)


def test_forward_units_are_the_si_output_converted(solve, tmp_path):
    lengths = tmp_path / "lengths.csv"
    poses = tmp_path / "poses.csv"
    poses.write_text("t,x,y,z,roll,pitch,yaw\n0,0.01,-0.02,0.51,0.02,0.01,0.03\n"
                     "0.1,0.02,-0.01,0.52,0.01,0.02,0.02\n")
    assert solve(poses, lengths).returncode == 0
    for extra in ([], ["--units", "um,deg"]):
        r = solve("--forward", *extra, lengths, tmp_path / f"f{len(extra)}.csv")
        assert r.returncode == 0, r.stderr
    si, converted = _table(tmp_path / "f0.csv"), _table(tmp_path / "f2.csv")
    for c, factor in (("x", 1e6), ("z", 1e6), ("yaw", 180 / math.pi), ("residual", 1e6),
                      ("condition", 1.0), ("t", 1.0)):
        np.testing.assert_allclose(converted[c], si[c] * factor, rtol=1e-15, atol=0, err_msg=c)


def test_units_refused_by_name(solve, tmp_path):
    r = solve("--units", "mm,inch", "in.csv", "out.csv")
    assert r.returncode == 2 and "'inch' is neither a length unit" in r.stderr
    platform = tmp_path / "p.json"
    platform.write_text("{}")
    r = solve("--check", platform, "--units", "mm")  # the check's text in them (test_check.py)
    assert r.returncode == 0 and "length [mm]" in r.stdout, r.stderr
