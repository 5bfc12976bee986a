"""The library's readings at measured poses and their closed-form derivatives with respect to the
geometry (stewart_geometry_jacobian) against the tests' own closed form (calibration_truth.py) and
its central differences, on random general geometries with tool and user frames and offsets."""
import numpy as np
import pytest

import stewart
from stewart.calibration_model import ReadingError, readings_and_jacobian

import calibration_truth as truth


def random_machine(rng):
    """A general machine: joints off the thesis circles by up to 5 cm (out of plane too), random
    offsets, a tool frame 0.1 m above the platform and a user frame off the base, both tilted."""
    a, b = truth.thesis_joints()
    return {"base_joint": a + rng.uniform(-0.05, 0.05, (6, 3)),
            "platform_joint": b + rng.uniform(-0.05, 0.05, (6, 3)),
            "length_offset": rng.uniform(-0.01, 0.01, 6),
            "tool_frame": np.r_[rng.uniform(-0.05, 0.05, 2), 0.1, rng.uniform(-0.2, 0.2, 3)],
            "user_frame": np.r_[rng.uniform(-0.1, 0.1, 3), rng.uniform(-0.2, 0.2, 3)]}


def platform_of(machine):
    return stewart.Platform(geometry=1, **{k: np.ravel(v).tolist() for k, v in machine.items()})


def user_poses(machine, rng, n):
    """Poses of the tool frame in the user frame for platform poses near home."""
    platform = truth.random_poses(rng, n)
    out = np.empty_like(platform)
    t, u = machine["tool_frame"], machine["user_frame"]
    Ru, Rt = truth.rotation(*u[3:]), truth.rotation(*t[3:])
    for i, q in enumerate(platform):
        R = truth.rotation(*q[3:])
        out[i, :3] = Ru.T @ (q[:3] + R @ t[:3] - u[:3])
        out[i, 3:] = truth.angles(Ru.T @ R @ Rt)
    return out


def central_difference(machine, poses, group, index, h=1e-6):
    plus = {k: np.array(v, dtype=float) for k, v in machine.items()}
    minus = {k: np.array(v, dtype=float) for k, v in machine.items()}
    plus[group].flat[index] += h
    minus[group].flat[index] -= h
    return (truth.readings(plus, poses) - truth.readings(minus, poses)) / (2 * h)


@pytest.mark.parametrize("seed", range(5))
def test_readings_and_derivatives_match_the_closed_form(seed):
    rng = np.random.default_rng(seed)
    machine = random_machine(rng)
    poses = user_poses(machine, rng, 8)
    reading, derivatives = readings_and_jacobian(platform_of(machine), poses)
    np.testing.assert_allclose(reading, truth.readings(machine, poses), rtol=0, atol=1e-13)
    for group in ("base_joint", "platform_joint"):
        for k in range(6):
            for i in range(3):
                fd = central_difference(machine, poses, group, 3 * k + i)
                expected = np.zeros_like(fd)
                expected[:, k] = fd[:, k]
                got = np.zeros_like(fd)
                got[:, k] = derivatives[group][:, k, i]
                assert np.all(np.delete(fd, k, axis=1) == 0)  # other legs do not move
                np.testing.assert_allclose(got, expected, rtol=0, atol=1e-8,
                                           err_msg=f"{group} {k} {i}")
    for group in ("tool_frame", "user_frame"):
        for j in range(6):
            np.testing.assert_allclose(derivatives[group][:, :, j],
                                       central_difference(machine, poses, group, j),
                                       rtol=0, atol=1e-8, err_msg=f"{group} {j}")
    for j in range(6):
        plus, minus = poses.copy(), poses.copy()
        plus[:, j] += 1e-6
        minus[:, j] -= 1e-6
        fd = (truth.readings(machine, plus) - truth.readings(machine, minus)) / 2e-6
        np.testing.assert_allclose(derivatives["pose"][:, :, j], fd, rtol=0, atol=1e-8)


def test_offsets_shift_readings_one_for_one():
    rng = np.random.default_rng(9)
    machine = random_machine(rng)
    poses = user_poses(machine, rng, 3)
    shifted = dict(machine, length_offset=machine["length_offset"] + np.arange(1, 7) * 1e-3)
    before, _ = readings_and_jacobian(platform_of(machine), poses)
    after, _ = readings_and_jacobian(platform_of(shifted), poses)
    np.testing.assert_allclose(before - after, np.tile(np.arange(1, 7) * 1e-3, (3, 1)),
                               rtol=0, atol=1e-14)


def test_a_pose_with_a_leg_of_zero_length_is_named():
    machine = random_machine(np.random.default_rng(3))
    machine["tool_frame"] = np.zeros(6)
    machine["user_frame"] = np.zeros(6)
    a, b = machine["base_joint"][2], machine["platform_joint"][2]
    bad = np.array([[0, 0, 0.5, 0, 0, 0], [*(a - b), 0, 0, 0]])  # leg 3's joints coincide
    with pytest.raises(ReadingError, match=r"pose row 1: leg 3 has length 0"):
        readings_and_jacobian(platform_of(machine), bad)


def test_readings_are_what_the_inverse_and_forward_directions_take():
    """The calibration model and the product agree: the inverse direction's lengths (tool frame
    in the user frame in, sensor readings out) are the readings, and forward kinematics of the
    readings gives the pose back: a calibrated platform file means the same to both."""
    rng = np.random.default_rng(12)
    machine = random_machine(rng)
    platform = platform_of(machine)
    poses = user_poses(machine, rng, 6)
    reading, _ = readings_and_jacobian(platform, poses)
    np.testing.assert_allclose(platform.inverse(poses, fidelity="kinematic").length, reading,
                               rtol=0, atol=1e-13)
    for pose, row in zip(poses, reading):
        found = platform.forward(row[None, :], guess=pose)
        assert found.status[0] == 0, found.messages
        np.testing.assert_allclose(found.pose[0], pose, rtol=0, atol=1e-11)
