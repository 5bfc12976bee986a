"""The tests' reference (reference.py) checked against finite differences of its own lengths, and the
library's rates and accelerations (stewart-solve, kinematic level) checked against the reference."""
import csv

import numpy as np

import reference

# A combined motion: pose, rate and acceleration as functions of t (every component moving).
AMP = np.array([0.03, -0.02, 0.04, 0.15, -0.12, 0.2])
W = np.array([3.0, 4.0, 5.0, 2.0, 3.5, 4.5])
PHASE = np.array([0.1, 0.7, 0.0, 0.5, 1.0, 1.5])
MEAN = np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0])


def motion(t):
    return (MEAN + AMP * np.sin(W * t + PHASE), AMP * W * np.cos(W * t + PHASE),
            -AMP * W * W * np.sin(W * t + PHASE))


def test_rates_and_accelerations_are_the_derivatives_of_the_lengths():
    h = 1e-4
    for t in np.linspace(0.0, 2.0, 9):
        q, qd, qdd = motion(t)
        L_dot, L_ddot = reference.length_rates_and_accelerations(q, qd, qdd)
        before, now, after = (reference.lengths(motion(t + s)[0]) for s in (-h, 0.0, h))
        np.testing.assert_allclose(L_dot, (after - before) / (2 * h), atol=1e-8)
        np.testing.assert_allclose(L_ddot, (after - 2 * now + before) / h ** 2, atol=2e-5)


def test_jacobian_maps_the_twist_to_the_leg_rates():
    for t in np.linspace(0.0, 2.0, 5):
        q, qd, qdd = motion(t)
        omega, _ = reference.angular_motion(q, qd, qdd)
        J = reference.leg_jacobian(q, scale=1.0)
        L_dot, _ = reference.length_rates_and_accelerations(q, qd, qdd)
        np.testing.assert_allclose(J @ np.concatenate([qd[:3], omega]), L_dot, atol=1e-15)
        # the radius-scaled Jacobian takes the twist with omega scaled by the radius
        Js = reference.leg_jacobian(q)
        np.testing.assert_allclose(Js @ np.concatenate([qd[:3], 0.5 * omega]), L_dot, atol=1e-15)


def test_angular_velocity_is_the_rotation_rate():
    """skew(omega) = R_dot R^T, with R_dot by central differences."""
    h = 1e-6
    for t in np.linspace(0.0, 2.0, 5):
        q, qd, qdd = motion(t)
        omega, _ = reference.angular_motion(q, qd, qdd)
        R_dot = (reference.rotation(*motion(t + h)[0][3:]) -
                 reference.rotation(*motion(t - h)[0][3:])) / (2 * h)
        S = R_dot @ reference.rotation(*q[3:]).T
        np.testing.assert_allclose([S[2, 1], S[0, 2], S[1, 0]], omega, atol=1e-9)


def test_library_rates_and_accelerations_equal_the_reference(solve, tmp_path):
    times = np.linspace(0.0, 2.0, 21)
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    names = ["x", "y", "z", "roll", "pitch", "yaw"]
    with open(pose_csv, "w") as f:
        f.write(",".join(["t", *names, *(n + "_dot" for n in names),
                          *(n + "_ddot" for n in names)]) + "\n")
        for t in times:
            f.write(",".join(repr(float(v)) for v in [t, *np.concatenate(motion(t))]) + "\n")
    result = solve("--fidelity", "kinematic", pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    with open(out_csv) as f:
        rows = list(csv.DictReader(f))
    for t, row in zip(times, rows):
        L_dot, L_ddot = reference.length_rates_and_accelerations(*motion(t))
        got = lambda prefix: np.array([float(row[f"{prefix}{k}"]) for k in range(1, 7)])
        np.testing.assert_allclose(got("L"), reference.lengths(motion(t)[0]), rtol=1e-13)
        np.testing.assert_allclose(got("L_dot"), L_dot, atol=1e-13)
        np.testing.assert_allclose(got("L_ddot"), L_ddot, atol=1e-12)
