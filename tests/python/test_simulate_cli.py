"""stewart-simulate from the command line: format, closed-form motions, a round trip through
stewart-solve, and errors naming the line and column."""

import numpy as np
import pytest

import scenes
from test_cli import read

POSE = ["x", "y", "z", "roll", "pitch", "yaw"]
LEGS = range(1, 7)
EXPECTED_HEADER = (["t"] + POSE + [f"{p}_dot" for p in POSE] + [f"L{k}" for k in LEGS]
                   + [f"L_dot{k}" for k in LEGS]
                   + ["warnings", "steps", "rhs_evaluations", "nonlinear_iterations",
                      "error_test_failures"])


def write_forces(path, t, forces):
    with open(path, "w") as f:
        f.write("t,F1,F2,F3,F4,F5,F6\n")
        for ti, row in zip(t, forces):
            f.write(",".join(repr(float(v)) for v in [ti, *row]) + "\n")


def test_free_fall_massless_is_the_closed_form(simulate, tmp_path):
    t = np.arange(0, 0.2001, 0.01)
    write_forces(tmp_path / "in.csv", t, np.zeros((t.size, 6)))
    r = simulate("--fidelity", "massless", tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 0, r.stderr
    header, data = read(tmp_path / "out.csv")
    assert header == EXPECTED_HEADER
    assert data.shape == (t.size, len(EXPECTED_HEADER))
    col = {name: data[:, i] for i, name in enumerate(header)}
    np.testing.assert_allclose(col["t"], t, atol=0)
    np.testing.assert_allclose(col["z"], 0.5 - 0.5 * 9.81 * t ** 2, atol=1e-12)
    np.testing.assert_allclose(col["z_dot"], -9.81 * t, atol=1e-12)
    for name in ["x", "y", "roll", "pitch", "yaw"]:
        np.testing.assert_allclose(col[name], 0, atol=1e-12)
    assert np.all(col["steps"][1:] >= 1) and np.all(col["rhs_evaluations"][1:] >= 1)
    assert col["steps"][0] == 0


def test_start_state_from_params_drifts_in_a_straight_line(simulate, tmp_path):
    t = np.arange(0, 0.5001, 0.05)
    write_forces(tmp_path / "in.csv", t, np.zeros((t.size, 6)))
    r = simulate("--fidelity", "massless", "--param", "gravity[3]=0", "--param", "x0=0.01",
                 "--param", "z0=0.52", "--param", "x_dot0=0.02", "--param", "y_dot0=-0.01",
                 tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 0, r.stderr
    header, data = read(tmp_path / "out.csv")
    col = {name: data[:, i] for i, name in enumerate(header)}
    np.testing.assert_allclose(col["x"], 0.01 + 0.02 * t, atol=1e-12)
    np.testing.assert_allclose(col["y"], -0.01 * t, atol=1e-12)
    np.testing.assert_allclose(col["z"], 0.52, atol=1e-12)


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_round_trip_through_stewart_solve(simulate, solve, tmp_path, fidelity):
    """Forces of the combined cue from stewart-solve, simulated: the cue's pose comes back."""
    dt, duration = 2.5e-4, 1.0
    scene = scenes.load("combined")
    scene["duration"] = duration
    scenes.write_pose_csv(scene, tmp_path / "pose.csv", dt=dt)
    r = solve("--fidelity", fidelity, tmp_path / "pose.csv", tmp_path / "forces_all.csv")
    assert r.returncode == 0, r.stderr
    header, data = read(tmp_path / "forces_all.csv")
    forces = np.column_stack([data[:, header.index(f"F{k}")] for k in LEGS])
    write_forces(tmp_path / "forces.csv", data[:, 0], forces)
    t = data[:, 0]
    q, qd, _ = scenes.pose(scene, t)
    params = []
    for i, name in enumerate(POSE):
        params += ["--param", f"{name}0={float(q[0, i])!r}", "--param",
                   f"{name}_dot0={float(qd[0, i])!r}"]
    r = simulate("--fidelity", fidelity, *params, "--param", "relative_tolerance=1e-12",
                 "--param", "absolute_tolerance=1e-14", tmp_path / "forces.csv",
                 tmp_path / "out.csv")
    assert r.returncode == 0, r.stderr
    header, out = read(tmp_path / "out.csv")
    pose = np.column_stack([out[:, header.index(p)] for p in POSE])
    # Forces linear between samples (error ~ dt^2 F'' / 12, 2e-6 m at 1 ms): below 1e-6 m and
    # rad over 1 s at 0.25 ms.
    error = np.max(np.abs(pose - q))
    print(f"{fidelity}: max pose error {error:.3g}")
    assert error < 1e-6


@pytest.mark.parametrize("content, fragment", [
    ("t,F1,F2,F3,F4,F5,F6\n0,0,0,0,0,0,0\n0.01,0,x,0,0,0,0\n", "line 3, column 3 (F2): 'x'"),
    ("t,F1,F2,F3,F4,F5,F6\n0,0,0,0,0,0,0\n0.01,0,0,0,0,nan,0\n", "line 3, column 6 (F5)"),
    ("t,F1,F2,F3,F4,F5,F6\n0,0,0,0,0,0,0\n0,0,0,0,0,0,0\n", "line 3, column 1 (t)"),
    ("t,F1,F2,F3,F4,F5,F6\n0,0,0,0,0,0,0\n0.01,0,0,0\n", "line 3: 4 values"),
    ("t,F1,F2,F3,F4,F6\n0,0,0,0,0,0\n", "line 1: column 'F5' is missing"),
    ("", "is empty"),
])
def test_bad_input_names_line_and_column(simulate, tmp_path, content, fragment):
    (tmp_path / "in.csv").write_text(content)
    r = simulate(tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 1
    assert fragment in r.stderr, r.stderr
    assert not (tmp_path / "out.csv").exists()


def test_refused_step_exits_1_naming_the_row(simulate, tmp_path):
    t = [0.0, 0.001, 0.002]
    write_forces(tmp_path / "in.csv", t, [[0] * 6, [1e308, -1e308] * 3, [0] * 6])
    r = simulate(tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 1
    assert "row 2" in r.stderr and "out of range" in r.stderr, r.stderr
    header, data = read(tmp_path / "out.csv")  # the row before it, marked partial on stderr
    assert header == EXPECTED_HEADER and data.shape[0] == 1
    assert "partial" in r.stderr and "before row 2" in r.stderr, r.stderr


def test_late_failure_keeps_the_rows_before_it(simulate, tmp_path):
    """A run that fails at row 1,341 writes the 1,340 rows before it, the same bit for bit as a
    run of those rows alone, and exits 1 naming the row and the output as partial."""
    t = np.arange(1341) * 1e-3
    forces = np.zeros((t.size, 6))
    forces[-1] = [1e308, -1e308] * 3
    write_forces(tmp_path / "in.csv", t, forces)
    write_forces(tmp_path / "good.csv", t[:-1], forces[:-1])
    r = simulate("--fidelity", "massless", tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 1
    assert "row 1341" in r.stderr and "partial" in r.stderr, r.stderr
    good = simulate("--fidelity", "massless", tmp_path / "good.csv", tmp_path / "good_out.csv")
    assert good.returncode == 0, good.stderr
    assert (tmp_path / "out.csv").read_text() == (tmp_path / "good_out.csv").read_text()
    _, data = read(tmp_path / "out.csv")
    assert data.shape[0] == 1340


def test_failure_at_the_first_row_writes_nothing(simulate, tmp_path):
    write_forces(tmp_path / "in.csv", [0.0, 0.001], [[0] * 6] * 2)
    r = simulate("--param", "pitch0=1.5707963267948966", tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 1, r.stderr
    assert "start state" in r.stderr and "pitch0" in r.stderr, r.stderr
    assert not (tmp_path / "out.csv").exists()


def test_bad_options(simulate, tmp_path):
    write_forces(tmp_path / "in.csv", [0.0], [[0] * 6])
    for args, fragment in [(["--param", "no_such=1"], "no_such"),
                           (["--param", "relative_tolerance=0"], "relative_tolerance"),
                           (["--fidelity", "kinematic"], "unknown fidelity")]:
        r = simulate(*args, tmp_path / "in.csv", tmp_path / "out.csv")
        assert r.returncode == 2, (args, r.stderr)
        assert fragment in r.stderr, r.stderr


def test_every_plant_option_by_name(simulate, tmp_path):
    """--param takes every option of the library's plant table: each at its table default changes
    no byte, fixed_steps = 3 takes 3 internal steps per row (the table reaches the integrator),
    and a bad value is refused naming the option and the value."""
    from stewart import _core
    t = np.arange(0, 0.0201, 0.001)
    write_forces(tmp_path / "in.csv", t, np.full((t.size, 6), 700.0))
    r = simulate(tmp_path / "in.csv", tmp_path / "plain.csv")
    assert r.returncode == 0, r.stderr
    plain = (tmp_path / "plain.csv").read_bytes()
    for option in _core.option_table("plant"):
        r = simulate("--param", f"{option['name']}={option['default']!r}", tmp_path / "in.csv",
                     tmp_path / "out.csv")
        assert r.returncode == 0, (option, r.stderr)
        assert (tmp_path / "out.csv").read_bytes() == plain, option["name"]
    r = simulate("--param", "fixed_steps=3", tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 0, r.stderr
    header, data = read(tmp_path / "out.csv")
    assert np.all(data[1:, header.index("steps")] == 3)
    assert np.all(data[1:, header.index("error_test_failures")] == 0)
    r = simulate("--param", "fixed_steps=2.5", tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 2 and "fixed_steps = 2.5" in r.stderr, r.stderr


def test_stroke_warning_on_stderr(simulate, tmp_path):
    t = np.arange(0, 0.4001, 0.01)
    write_forces(tmp_path / "in.csv", t, np.zeros((t.size, 6)))
    r = simulate(tmp_path / "in.csv", tmp_path / "out.csv")
    assert r.returncode == 0, r.stderr
    assert "warning" in r.stderr and "stroke" in r.stderr and "leg " in r.stderr
    header, data = read(tmp_path / "out.csv")
    # the stroke bit; the collapsed platform's legs also pass their joints' 90 degrees (8)
    assert int(data[-1, header.index("warnings")]) & 1 == 1


def test_usage_shows_each_default_in_its_shortest_exact_form(simulate):
    """The usage names each plant option's default as the shortest text that reads back as the
    table's double (Python's repr is that text), not 17 digits of binary noise."""
    import re
    from stewart import _core
    usage = simulate("--help")
    text = usage.stdout + usage.stderr
    for o in _core.option_table("plant"):
        shown = re.search(rf"^\s+{o['name']} \[([^\]]+)\]:", text, re.M)
        assert shown, o["name"]
        assert float(shown[1]) == o["default"]
        assert len(shown[1]) <= len(repr(float(o["default"]))), shown[1]
