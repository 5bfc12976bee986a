"""What stewart.calibrate refuses, each with a message naming the cause and what to do: readings
in millimetres, a reading of 1e300, all readings 0, a reading of -5 m, one +1 m reading (the
outlier named by row and leg), a pose at pitch 90 deg, noises and max_evaluations out of range;
and the unknowns chosen with identify (the others stay exactly nominal); a max_std that the
poses cannot meet, with what would pass (more poses, checked with calibration_poses; or none).
"""
import numpy as np
import pytest

import stewart
from stewart.calibration_checks import MeasurementError
from stewart.calibration_model import readings_and_jacobian

import calibration_truth as truth


@pytest.fixture(scope="module")
def nominal():
    return stewart.Platform()


@pytest.fixture(scope="module")
def measured(nominal):
    """30 poses of a built thesis platform (joints 0.5 mm off, offsets 1 mm) and its
    readings, by this suite's own closed form."""
    poses = stewart.calibration_poses(nominal, 30)
    rng = np.random.default_rng(1)
    a, b = truth.thesis_joints()
    machine = {"base_joint": a + rng.choice([-5e-4, 5e-4], (6, 3)),
               "platform_joint": b + rng.choice([-5e-4, 5e-4], (6, 3)),
               "length_offset": rng.choice([-1e-3, 1e-3], 6), "tool_frame": np.zeros(6),
               "user_frame": np.zeros(6)}
    return poses, truth.readings(machine, poses)


def changed(readings, row, leg, value):
    out = readings.copy()
    out[row, leg] = value
    return out


@pytest.mark.parametrize("case, message", [
    ("millimetres", "are they in millimetres? Give them in metres"),
    ("zeros", "Every reading is 0"),
    ("1e300", "outlier: 1 reading(s)"),
    ("minus 5 m", "pose row 7, leg 2: -5 m"),
    ("plus 1 m", "pose row 11, leg 4: 1."),
])
def test_readings_no_machine_gives_are_refused(nominal, measured, case, message):
    poses, readings = measured
    bad = {"millimetres": readings * 1e3, "zeros": readings * 0.0,
           "1e300": changed(readings, 4, 2, 1e300), "minus 5 m": changed(readings, 7, 1, -5.0),
           "plus 1 m": changed(readings, 11, 3, readings[11, 3] + 1.0)}[case]
    with pytest.raises(MeasurementError, match=message.replace("?", r"\?").replace(".", r"\.")
                       .replace("(", r"\(").replace(")", r"\)")) as error:
        stewart.calibrate(nominal, poses, bad)
    if case in ("1e300", "minus 5 m", "plus 1 m"):  # named by row and leg, as an outlier
        assert len(error.value.rows) == 1 and len(error.value.legs) == 1
        assert "measure those poses again or leave their rows out" in str(error.value)


def test_angles_in_degrees_are_named(nominal, measured):
    poses, readings = measured
    in_degrees = poses.copy()
    in_degrees[:, 3:] = np.degrees(poses[:, 3:])
    with pytest.raises(MeasurementError, match="are they in degrees"):
        stewart.calibrate(nominal, in_degrees, readings)


def test_a_pose_at_pitch_90_degrees_is_refused(nominal, measured):
    poses, readings = measured
    poses = poses.copy()
    poses[5, 4] = np.pi / 2
    with pytest.raises(MeasurementError, match=r"poses\[5\]: pitch = 90 deg"):
        stewart.calibrate(nominal, poses, readings)


def test_a_fit_that_moves_a_joint_beyond_any_tolerance_is_refused(nominal, measured):
    """Readings 30 mm longer than the machine's on one leg pass the gross check with a loose
    tolerance but move that leg's joints or offset by centimetres: refused, the tolerance and
    the way out named."""
    poses, readings = measured
    shifted = readings.copy()
    shifted[:, 2] += 0.03
    with pytest.raises(MeasurementError, match="no built machine is that far from its drawing"):
        stewart.calibrate(nominal, poses, shifted, offset_tolerance=2e-3)
    # With the tolerance the user knows the machine to have, the same data calibrate.
    result = stewart.calibrate(nominal, poses, shifted, offset_tolerance=0.05)
    assert result.parameters["length_offset"][2] == pytest.approx(-0.03, abs=2e-3)


@pytest.mark.parametrize("argument, value, message", [
    ("position_noise", 1e-300, "position_noise = 1e-300 must be 0 or from 1e-12 to 1"),
    ("angle_noise", 1e300, "angle_noise = 1e[+]300 must be 0 or from 1e-12 to 1"),
    ("reading_noise", 1e-300, "reading_noise = 1e-300 must be"),
    ("reading_noise", 0.0, "reading_noise = 0"),
    ("max_evaluations", 10 ** 12, "max_evaluations = 1000000000000 must be an integer"),
    ("joint_tolerance", 1e300, "joint_tolerance = 1e[+]300 must be"),
    ("offset_tolerance", -1.0, "offset_tolerance = -1.0 must be"),
    ("max_std", float("nan"), "max_std = nan"),
    ("identify", "joints,legs", "identify: 'legs' is not one of"),
])
def test_bad_arguments_are_named(nominal, measured, argument, value, message):
    with pytest.raises(ValueError, match=message):
        stewart.calibrate(nominal, *measured, **{argument: value})


def test_no_poses_and_too_many_are_refused(nominal):
    with pytest.raises(MeasurementError, match="no measurement"):
        stewart.calibrate(nominal, np.zeros((0, 6)), np.zeros((0, 6)))
    many = np.tile([0, 0, 0.5, 0, 0, 0], (20_001, 1))
    with pytest.raises(MeasurementError, match="20001 rows; calibrate takes at most 20000"):
        stewart.calibrate(nominal, many, np.full((20_001, 6), 0.5))


@pytest.mark.parametrize("identify, free, fixed", [
    ("offsets", ["length_offset"], ["base_joint", "platform_joint"]),
    ("joints-xy,offsets", ["length_offset"], []),
    ("base,offsets", ["base_joint", "length_offset"], ["platform_joint"]),
    ("platform", ["platform_joint"], ["base_joint", "length_offset"]),
])
def test_identify_frees_only_what_it_names(nominal, measured, identify, free, fixed):
    result = stewart.calibrate(nominal, *measured, identify=identify)
    nominal_values = stewart.calibration_model.nominal_geometry(nominal)
    for group in fixed:
        np.testing.assert_array_equal(result.parameters[group], nominal_values[group])
        assert not any(n.startswith(group) for n in result.names)
    for group in free:
        assert np.any(result.parameters[group] != nominal_values[group])
    if identify.startswith("joints-xy"):  # z of every joint stays nominal, x and y move
        for group in ("base_joint", "platform_joint"):
            moved = (result.parameters[group] - nominal_values[group]).reshape(6, 3)
            assert np.all(moved[:, 2] == 0) and np.all(np.abs(moved[:, :2]).max(axis=0) > 1e-5)
        assert len(result.names) == 30
    # Fewer unknowns than the machine's errors: the residuals stay above the noise (the
    # model cannot absorb the joints it holds), except where every error is free.
    assert result.rms("after") < result.rms("before")


def test_the_prior_pulls_toward_nominal_by_the_tolerance(nominal, measured):
    """A tighter tolerance keeps the unknowns nearer nominal; a loose one leaves the data's
    answer (the unregularised least squares, which these 30 poses determine)."""
    poses, readings = measured
    loose = stewart.calibrate(nominal, poses, readings, joint_tolerance=1.0,
                              offset_tolerance=1.0)
    default = stewart.calibrate(nominal, poses, readings)
    tight = stewart.calibrate(nominal, poses[:8], readings[:8], joint_tolerance=2e-4,
                              offset_tolerance=2e-4)
    few = stewart.calibrate(nominal, poses[:8], readings[:8])
    moved = [np.linalg.norm(r.values - r.nominal) for r in (tight, few, default, loose)]
    assert moved[0] < moved[1]
    assert moved[2] == pytest.approx(moved[3], rel=0.02)
    # The tight prior is too tight for these 0.5 mm errors: the data say so (variance factor).
    assert tight.variance_factor > 2 * few.variance_factor


def test_the_report_predicts_at_the_measured_poses_when_no_random_pose_is_inside(
        nominal, measured, monkeypatch):
    """A machine with no random pose inside its limits still gets its prediction (no crash
    after a good fit), at the poses it was measured at, and the report says so."""
    import stewart.calibration as calibration
    monkeypatch.setattr(calibration, "accuracy_samples", lambda platform: np.zeros((0, 6)))
    result = stewart.calibrate(nominal, *measured)
    assert result.accuracy.samples == 30
    assert "30 measured poses (no random pose was found inside the limits)" in result.report()
    assert np.isfinite(result.accuracy.position_worst) and result.accuracy.position_worst > 0


def test_poses_for_a_z_down_machine_are_refused_with_the_conversion(tmp_path):
    """calibration_poses on SIMONA in its own z-down frames: no warning that home is beyond a
    limit (it is not) and no "pose row 0" reading error, but a refusal naming frame_convention
    and the turn to z up; that turn (the shipped z-up file) is then taken without a warning."""
    import warnings
    from test_rotation_order import simona_z_down
    down = simona_z_down(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"frame_convention 1 \(z down\)") as refused:
            stewart.calibration_poses(down, 30)
        assert "(x, -y, -z)" in str(refused.value) and "row" not in str(refused.value)
        up = stewart.Platform.from_file(stewart.platform_files()["simona_motion_base"])
        assert stewart.calibration_poses(up, 30).shape == (30, 6)
    with pytest.raises(ValueError, match="frame_convention 1") as refused:
        stewart.observability(down, np.zeros((30, 6)))


def test_poses_for_another_rotation_order_name_the_converter():
    with pytest.raises(ValueError, match=r"rotation_order 1.*convert_angles\(angles, 1, 0\)"):
        stewart.calibration_poses(stewart.Platform(rotation_order=1), 30)


def _advice(machine):
    """The max_std = 0.1 mm refusal with a 0.5 mm joint tolerance of 30 poses from
    calibration_poses on a shipped machine (as docs/calibration.md did), its poses and the
    message."""
    platform = stewart.Platform.from_file(stewart.platform_files()[machine])
    poses = stewart.calibration_poses(platform, 30)
    readings = readings_and_jacobian(platform, poses)[0]  # the nominal machine's
    with pytest.raises(stewart.UnobservableError) as error:
        stewart.calibrate(platform, poses, readings, joint_tolerance=5e-4, max_std=1e-4)
    return platform, poses, str(error.value)


def _accepted(message):
    import re
    return float(re.search(r"accept a max_std of ([0-9.e+-]+) \(--max-std\)", message).group(1))


def test_a_max_std_refusal_names_the_poses_that_would_pass():
    """SIMONA's 30 poses leave one length offset at 1.005 times 0.1 mm: the refusal names how
    many poses of the same spread would pass (checked here with poses calibration_poses chooses)
    and the smallest max_std these poses pass (before, it advised poses of varied orientation,
    which these already are, and gave the value as "up to 0.0001", the limit itself)."""
    import re
    platform, poses, message = _advice("simona_motion_base")
    assert "length_offset[3]" in message
    more = int(re.search(r"About (\d+) poses of the same spread would", message).group(1))
    assert 30 < more <= 60
    design = stewart.calibration_poses(platform, more)
    assert np.isfinite(stewart.observability(platform, design, joint_tolerance=5e-4,
                                             max_std=1e-4))
    assert np.isfinite(stewart.observability(platform, poses, joint_tolerance=5e-4,
                                             max_std=_accepted(message)))


def test_a_max_std_no_poses_can_meet_says_so_and_what_passes():
    """On the Rubin camera hexapod (+-14 mm strokes) the data barely see 18 combinations of the
    joints and offsets: four times the poses still refuse, and the refusal says no number of
    poses would, and what does pass: leaving max_std out (the regularised fit), fewer unknowns
    (offsets alone pass), or the max_std it names."""
    platform, poses, message = _advice("rubin_camera_hexapod")
    assert "No number of poses of this spread would" in message
    assert "Leave max_std out" in message and "--identify" in message
    design = stewart.calibration_poses(platform, 120)
    assert stewart.observability(platform, design, joint_tolerance=5e-4, max_std=1e-4) == np.inf
    assert np.isfinite(stewart.observability(platform, poses, identify="offsets",
                                             joint_tolerance=5e-4, max_std=1e-4))
    assert np.isfinite(stewart.observability(platform, poses, joint_tolerance=5e-4,
                                             max_std=_accepted(message)))


def test_the_advised_max_std_is_never_below_the_largest_std():
    """The max_std a refusal advises is the largest standard deviation rounded up to two
    significant digits: it reads back as at least that value (so the advice is taken), and one
    step of the second digit below it would not (so it is the nearest such number)."""
    from decimal import Decimal

    from stewart.calibration import _round_up
    rng = np.random.default_rng(7)
    values = list(10.0 ** rng.uniform(-7, 1, 2000))
    values += [0.95 + 1e-16, 0.9500000000000001, 1.0000000000000002, 9.9e-5 + 1e-20, 3e-4]
    for value in values:
        text = _round_up(value)
        advised = Decimal(text)
        assert advised >= Decimal(value), (value, text)
        assert len(advised.normalize().as_tuple().digits) <= 2, (value, text)
        step = Decimal(1).scaleb(advised.adjusted() - 1)
        assert advised - step < Decimal(value), (value, text)
