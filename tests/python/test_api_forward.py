"""Platform.forward: the inverse closed form's lengths read back to the poses (scenes.py computes
the poses, Platform.inverse the lengths), the same numbers as `stewart-solve --forward`, and the
documented per-row statuses (another assembly mode, lengths no pose has, bad arguments)."""
import math

import numpy as np
import pytest

import scenes
import stewart
from test_cli import read

MANOEUVRES = ["heave", "roll", "pitch", "yaw", "combined"]
OTHER_BRANCH, UNREACHABLE, ARGUMENT = -8, -4, -1
# Every leg at home: sqrt(z^2 + chord^2), chord = 2 r sin 15 deg between base and platform point.
HOME_LENGTH = math.sqrt(0.5 ** 2 + (2 * 0.5 * math.sin(math.radians(15))) ** 2)


@pytest.fixture(scope="module")
def platform():
    return stewart.Platform()


def manoeuvre(name, duration=2.0, dt=0.01):
    scene = scenes.load(name)
    scene["duration"] = duration
    t = scenes.times(scene, dt)
    return (t, *scenes.pose(scene, t))


@pytest.mark.parametrize("name", MANOEUVRES)
def test_forward_of_inverse_gives_back_the_manoeuvre(platform, name):
    t, q, qd, qdd = manoeuvre(name)
    legs = platform.inverse(q, qd, qdd, fidelity="kinematic")
    assert legs.ok.all()
    fw = platform.forward(legs.length, legs.length_rate, legs.length_accel, t=t)
    assert fw.ok.all(), fw.messages
    np.testing.assert_allclose(fw.pose, q, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fw.pose_rate, qd, rtol=0, atol=1e-10)
    np.testing.assert_allclose(fw.pose_accel, qdd, rtol=0, atol=1e-8)
    assert fw.start[0] == 0 and (fw.start[1:] >= 2).all()  # home, then tracking
    assert (fw.branch == 0).all() and (fw.residual <= 1e-12).all()


def test_forward_of_inverse_gives_back_random_workspace_poses(platform):
    rng = np.random.default_rng(7)
    n = 200
    q = np.column_stack([rng.uniform(-0.08, 0.08, n), rng.uniform(-0.08, 0.08, n),
                         rng.uniform(0.42, 0.58, n), rng.uniform(-0.12, 0.12, (n, 3))])
    legs = platform.inverse(q, fidelity="kinematic")
    # each pose on its own (a cold start from home) ...
    for j in range(0, n, 10):
        fw = platform.forward(legs.length[j])
        assert fw.ok.all(), fw.messages
        np.testing.assert_allclose(fw.pose[0], q[j], rtol=0, atol=1e-12)
    # ... and all of them tracked in one batch: a row too far from the last one is refused, not
    # answered with another pose, and started from home it solves.
    fw = platform.forward(legs.length)
    solved = fw.ok
    np.testing.assert_allclose(fw.pose[solved], q[solved], rtol=0, atol=1e-12)
    for j in np.flatnonzero(~solved):
        assert fw.status[j] == OTHER_BRANCH and fw.branch[j] != 0, fw.messages.get(j)
        np.testing.assert_allclose(platform.forward(legs.length[j]).pose[0], q[j], atol=1e-12)


def test_same_numbers_as_stewart_solve_forward(platform, solve, tmp_path):
    t, q, qd, qdd = manoeuvre("combined", duration=1.0)
    legs = platform.inverse(q, qd, fidelity="kinematic")
    in_csv, out_csv = tmp_path / "lengths.csv", tmp_path / "poses.csv"
    header = ["t"] + [f"L{k}" for k in range(1, 7)] + [f"L_dot{k}" for k in range(1, 7)]
    rows = np.column_stack([t, legs.length, legs.length_rate])
    in_csv.write_text(",".join(header) + "\n" + "".join(
        ",".join(repr(float(v)) for v in row) + "\n" for row in rows))
    guess = [0.01, 0.0, 0.49, 0.0, 0.0, 0.0]
    result = solve("--forward", "--guess", ",".join(map(str, guess)), in_csv, out_csv)
    assert result.returncode == 0, result.stderr
    cli_header, cli = read(out_csv)
    fw = platform.forward(legs.length, legs.length_rate, guess=guess, t=t)
    assert fw.ok.all()
    col = {name: cli[:, i] for i, name in enumerate(cli_header)}
    pose = np.column_stack([col[p] for p in scenes.POSE])
    rate = np.column_stack([col[p] for p in scenes.DOT])
    np.testing.assert_array_equal(fw.pose, pose)
    np.testing.assert_array_equal(fw.pose_rate, rate)
    np.testing.assert_array_equal(fw.iterations, col["iterations"])
    np.testing.assert_array_equal(fw.residual, col["residual"])
    np.testing.assert_array_equal(fw.condition, col["condition"])
    assert fw.start[0] == 1  # from the guess


def test_another_assembly_mode_is_a_row_status_not_an_answer(platform):
    lengths = np.full((3, 6), HOME_LENGTH)
    fw = platform.forward(lengths, guess=[0, 0, -0.45, 0, 0, 0])
    assert fw.status[0] == OTHER_BRANCH and fw.status_name(0) != "ok"
    assert fw.branch[0] & stewart.forward.BRANCH_BITS["below_base"]
    assert fw.warnings[0] & 4
    assert "below the base" in fw.messages[0]
    assert (fw.pose[0] == 0).all()
    # the next rows start from home (no history was kept) and solve
    assert fw.ok[1:].all()
    np.testing.assert_allclose(fw.pose[1:], [[0, 0, 0.5, 0, 0, 0]] * 2, rtol=0, atol=1e-12)


def test_lengths_no_pose_has_and_bad_values_are_row_statuses(platform):
    _, q, _, _ = manoeuvre("combined", duration=0.5)
    L = platform.inverse(q, fidelity="kinematic").length.copy()
    L[10, 4] = 3.0       # leg 5 three metres long: no pose has it
    L[20, 2] = np.nan    # not a number
    fw = platform.forward(L)
    assert fw.status[10] == UNREACHABLE and "leg 5" in fw.messages[10]
    assert fw.status[20] == ARGUMENT and "3" in fw.messages[20]
    others = np.ones(len(L), bool)
    others[[10, 20]] = False
    assert fw.ok[others].all()
    np.testing.assert_allclose(fw.pose[others], q[others], rtol=0, atol=1e-12)
    assert (fw.pose[[10, 20]] == 0).all()


@pytest.mark.parametrize("call, words", [
    (lambda p: p.forward(np.ones((3, 5))), ["lengths", "(3, 5)"]),
    (lambda p: p.forward(np.ones((3, 6)), rates=np.ones((2, 6))), ["rates", "2 rows"]),
    (lambda p: p.forward(np.ones((3, 6)), accels=np.ones((3, 6))), ["accels", "rates"]),
    (lambda p: p.forward(np.ones((3, 6)), guess=[0, 0, 0.5]), ["guess", "3 values"]),
    (lambda p: p.forward(np.ones((3, 6)), guess=[0, 0, np.inf, 0, 0, 0]), ["guess", "inf"]),
    (lambda p: p.forward(np.ones((3, 6)), t=[0, 1, 1]), ["t[2]", "does not increase"]),
    (lambda p: p.forward(np.ones((3, 6)), t=[0, 1]), ["t", "(2,)"]),
    (lambda p: p.forward(np.ones((3, 6)), max_messages=-1), ["max_messages", "-1"]),
])
def test_bad_arguments_raise_naming_them(platform, call, words):
    with pytest.raises(ValueError) as e:
        call(platform)
    for w in words:
        assert w in str(e.value)


@pytest.mark.parametrize("option, value", [("tolerance", 1e-20), ("max_iterations", 0),
                                           ("max_iterations", 2.5)])
def test_bad_options_raise_parameter_error(platform, option, value):
    with pytest.raises(stewart.ParameterError) as e:
        platform.forward(np.full((1, 6), HOME_LENGTH), **{option: value})
    assert option in str(e.value)
