"""stewart.calibrate on synthetic machines: a true geometry = the thesis platform + random joint
errors (0.1-1 mm) and length offsets (0.1-2 mm), measured in this file with its own closed form
(calibration_truth.py) and a tracker's noise (10 um, 20 urad; 1 um on the readings). Checked: the
identified parameters against the truth within their reported standard deviations (coverage over
many seeds), the pose error on held-out poses, an unobservable set, an outlier, the frames."""
import numpy as np
import pytest

import stewart
from stewart.calibration import forward_poses

import calibration_truth as truth

JOINT_ERROR = (1e-4, 1e-3)
OFFSET_ERROR = (1e-4, 2e-3)


def signed(rng, low_high, size):
    return rng.uniform(*low_high, size) * rng.choice([-1.0, 1.0], size)


def nominal_machine():
    a, b = truth.thesis_joints()
    return {"base_joint": a, "platform_joint": b, "length_offset": np.zeros(6),
            "tool_frame": np.zeros(6), "user_frame": np.zeros(6)}


def true_machine(rng, frame_error=0.0):
    m = nominal_machine()
    m["base_joint"] = m["base_joint"] + signed(rng, JOINT_ERROR, (6, 3))
    m["platform_joint"] = m["platform_joint"] + signed(rng, JOINT_ERROR, (6, 3))
    m["length_offset"] = signed(rng, OFFSET_ERROR, 6)
    m["tool_frame"] = rng.normal(0, frame_error, 6)
    m["user_frame"] = rng.normal(0, frame_error, 6)
    return m


def measure(machine, poses, rng):
    """What the tracker and the sensors report at the true poses."""
    readings = truth.readings(machine, poses) + rng.normal(0, 1e-6, (len(poses), 6))
    return truth.measured(poses, rng), readings


def pose_errors(machine, true_machine_, poses):
    """Position [m] and rotation [rad] errors of the poses machine computes from the readings
    the true machine gives at poses (forward kinematics of this file)."""
    found = truth.forward(machine, truth.readings(true_machine_, poses), poses)
    position = np.linalg.norm(found[:, :3] - poses[:, :3], axis=1)
    rotation = np.array([np.arccos(np.clip((np.trace(truth.rotation(*f[3:]).T
                                                     @ truth.rotation(*q[3:])) - 1) / 2, -1, 1))
                         for f, q in zip(found, poses)])
    return position, rotation


@pytest.fixture(scope="module")
def nominal():
    return stewart.Platform()


@pytest.fixture(scope="module")
def design(nominal):
    return stewart.calibration_poses(nominal, 30)


def test_calibration_poses_are_inside_the_strokes_and_identify_everything(nominal, design):
    assert design.shape == (30, 6)
    lengths = truth.readings(nominal_machine(), design)
    assert np.all((lengths > 0.4) & (lengths < 0.7))
    assert stewart.observability(nominal, design) < 200  # the study measures it: about 86
    random = truth.random_poses(np.random.default_rng(0), 30)
    assert stewart.observability(nominal, design) < stewart.observability(nominal, random)


def test_identified_parameters_match_the_truth_within_their_standard_deviations(nominal, design):
    z = []
    for seed in range(12):
        rng = np.random.default_rng(100 + seed)
        machine = true_machine(rng)
        result = stewart.calibrate(nominal, *measure(machine, design, rng))
        expected = np.concatenate([machine["base_joint"].ravel(),
                                   machine["platform_joint"].ravel(), machine["length_offset"]])
        assert result.names[0] == "base_joint[1]" and result.names[-1] == "length_offset[6]"
        assert np.all(result.std > 0) and np.all(result.std < 1e-4)
        z.append((result.values - expected) / result.std)
    z = np.abs(np.concatenate(z))  # 504 normalised errors: about N(0, 1) if the std are right
    assert 0.58 < np.mean(z < 1) < 0.78, np.mean(z < 1)
    assert 0.91 < np.mean(z < 2) < 0.99, np.mean(z < 2)
    assert np.mean(z < 3) > 0.985


def test_held_out_pose_error_falls_by_99_percent(nominal, design):
    rng = np.random.default_rng(7)
    machine = true_machine(rng)
    result = stewart.calibrate(nominal, *measure(machine, design, rng))
    assert result.rms("after") < 0.05 * result.rms("before")
    assert result.condition < 200 and 0.5 < result.variance_factor < 2
    held_out = truth.random_poses(rng, 15)
    before = pose_errors(nominal_machine(), machine, held_out)
    after = pose_errors(truth.identified_machine(result), machine, held_out)
    for b, a in zip(before, after):
        assert np.sqrt(np.mean(a ** 2)) < 0.01 * np.sqrt(np.mean(b ** 2))
    # The package's forward kinematics on the calibrated Platform agrees with this file's.
    found = forward_poses(result.platform, truth.readings(machine, held_out), held_out)
    expected = truth.forward(truth.identified_machine(result), truth.readings(machine, held_out),
                             held_out)
    np.testing.assert_allclose(found, expected, rtol=0, atol=1e-11)


def test_one_orientation_leaves_the_joints_to_the_prior_and_max_std_refuses_it(nominal):
    rng = np.random.default_rng(3)
    machine = true_machine(rng)
    poses = truth.random_poses(rng, 30)
    poses[:, 3:] = [0.1, -0.05, 0.2]  # every pose at one orientation
    measured = measure(machine, poses, rng)
    # Leg k's base and platform joints move together unseen (only a_k - R b_k is measured):
    # 18 free combinations carried by all 36 joint coordinates. The prior keeps them near
    # nominal, and the result says so.
    joints = {f"{g}[{i}]" for g in ("base_joint", "platform_joint") for i in range(1, 19)}
    result = stewart.calibrate(nominal, *measured)
    assert 18 <= result.undetermined <= 24
    assert joints <= set(result.undetermined_names)
    assert "set by the prior: " in result.report() and "base_joint[1..18]" in result.report()
    # The split is unknown to about the tolerance: the predicted pose error at other
    # orientations is far above a well-measured machine's.
    assert result.accuracy.position_worst > 100e-6
    with pytest.raises(stewart.UnobservableError) as error:
        stewart.calibrate(nominal, *measured, max_std=1e-4)
    names = set(error.value.unobservable)
    assert joints <= names
    assert names - joints <= {f"length_offset[{i}]" for i in range(1, 7)}
    assert "base_joint[1..18]" in str(error.value) and "platform_joint[1..18]" in str(error.value)
    # observability says what calibrate does with the same choices.
    assert stewart.observability(nominal, poses, max_std=1e-4) == float("inf")


def test_observability_measures_what_calibrate_uses(nominal, design):
    """The condition number observability gives is the one calibrate reports at the nominal
    geometry (same scaled, gauge-fixed, prior-augmented Jacobian); few poses look worse than
    thirty good ones; no poses are unobservable (not an IndexError)."""
    rng = np.random.default_rng(4)
    readings = truth.readings(nominal_machine(), design)
    result = stewart.calibrate(nominal, design, readings)
    assert stewart.observability(nominal, design) == pytest.approx(result.condition, rel=1e-6)
    good = stewart.observability(nominal, design)
    assert stewart.observability(nominal, design[:1]) > 3 * good
    assert stewart.observability(nominal, design[:6]) > 3 * good
    assert stewart.observability(nominal, np.zeros((0, 6))) == float("inf")
    with pytest.raises(stewart.UnobservableError):
        stewart.calibrate(nominal, *measure(true_machine(rng), design[:6], rng), max_std=1e-4)


def test_an_outlier_is_named_and_a_robust_loss_resists_it(nominal, design):
    rng = np.random.default_rng(11)
    machine = true_machine(rng)
    poses, readings = measure(machine, design, rng)
    readings[17, 2] += 0.5e-3  # one bad reading
    linear = stewart.calibrate(nominal, poses, readings)
    assert linear.outliers == [17] and linear.outlier_leg(17) == 3
    assert "17 (leg 3)" in linear.report()
    robust = stewart.calibrate(nominal, poses, readings, loss="soft_l1")
    assert 17 in robust.outliers
    held_out = truth.random_poses(rng, 10)
    position, _ = pose_errors(truth.identified_machine(robust), machine, held_out)
    assert np.max(position) < 50e-6


def test_frames_are_identified_in_the_stated_gauge(nominal, design):
    rng = np.random.default_rng(5)
    machine = true_machine(rng, frame_error=2e-3)
    poses = stewart.calibration_poses(nominal, 30, frames="both")
    result = stewart.calibrate(nominal, *measure(machine, poses, rng), frames="both")
    assert result.names[-12:] == [f"{f}[{i}]" for f in ("tool_frame", "user_frame")
                                  for i in range(1, 7)]
    # The gauge: the joints' net translation and rotation from nominal are zero.
    for group, nominal_points in zip(("base_joint", "platform_joint"), truth.thesis_joints()):
        shift = result.parameters[group].reshape(6, 3) - nominal_points
        np.testing.assert_allclose(shift.sum(axis=0), 0, atol=1e-12)
        np.testing.assert_allclose(np.cross(nominal_points, shift).sum(axis=0), 0, atol=1e-12)
    held_out = truth.random_poses(rng, 10)
    before = pose_errors(nominal_machine(), machine, held_out)
    after = pose_errors(truth.identified_machine(result), machine, held_out)
    for b, a in zip(before, after):
        assert np.sqrt(np.mean(a ** 2)) < 0.01 * np.sqrt(np.mean(b ** 2))


@pytest.mark.parametrize("argument, value, message", [
    ("loss", "square", "loss = 'square' must be one of"),
    ("frames", "platform", "frames = 'platform' must be"),
    ("position_noise", -1.0, "position_noise = -1.0 must be"),
    ("max_std", 0.0, "max_std = 0.0 must be"),
])
def test_bad_arguments_are_named(nominal, design, argument, value, message):
    readings = truth.readings(nominal_machine(), design)
    with pytest.raises(ValueError, match=message):
        stewart.calibrate(nominal, design, readings, **{argument: value})


def test_non_finite_measurements_are_named(nominal, design):
    readings = truth.readings(nominal_machine(), design)
    readings[4, 3] = np.nan
    with pytest.raises(ValueError, match=r"readings\[4, 3\] = nan is not finite"):
        stewart.calibrate(nominal, design, readings)


def test_a_nominal_given_element_by_element_is_read_whole():
    """A platform whose offsets and strokes are given by element names: the nominal geometry
    has them, and the calibrated platform replaces the whole array (no element left over)."""
    from stewart.calibration_model import nominal_geometry, platform_with
    nominal = stewart.Platform(**{"length_offset[3]": 1e-3, "stroke_max[2]": 0.71})
    geometry = nominal_geometry(nominal)
    np.testing.assert_array_equal(geometry["length_offset"], [0, 0, 1e-3, 0, 0, 0])
    geometry["length_offset"] = geometry["length_offset"] + 1e-4
    calibrated = platform_with(nominal, geometry)
    assert "length_offset[3]" not in calibrated.params
    np.testing.assert_allclose(calibrated.params["length_offset"],
                               [1e-4] * 2 + [1.1e-3] + [1e-4] * 3)
    assert calibrated.params["stroke_max[2]"] == 0.71
