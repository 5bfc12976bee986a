"""What stewart.calibrate refuses, and why (docs/calibration.md §3): arguments out of range,
measurements it cannot weight, readings no machine within its tolerances gives, and fits that
move the geometry further than any tolerance. Each error names the cause and what to do."""
from __future__ import annotations

import numpy as np

MAX_POSES = 20_000        # a calibration uses tens to hundreds; 20,000 need ~60 MB of Jacobian
MAX_EVALUATIONS = 100_000
GROSS_ERROR = 30.0        # a reading this many predicted standard deviations off is no reading
FAR_MOVE = 10.0           # a parameter moved this many tolerances is no machine's tolerance
FAR_FRACTION = 0.25       # ... nor a joint or offset moved this fraction of the machine's size
GIMBAL_COS = 1e-3         # |cos(pitch)| below: within 0.06 deg of pitch = +-90 deg


class MeasurementError(ValueError):
    """Measurements calibrate cannot use; `rows` (0-based pose rows) and `legs` (1-based) name
    the readings at fault, when it is some of them."""

    def __init__(self, message: str, rows=(), legs=()) -> None:
        super().__init__(message)
        self.rows = [int(r) for r in rows]
        self.legs = [int(k) for k in legs]


def check_options(loss: str, losses, outlier_threshold, max_std, max_evaluations) -> None:
    if loss not in losses:
        raise ValueError(f"loss = {loss!r} must be one of {', '.join(losses)}")
    if not (_number(outlier_threshold) and np.isfinite(outlier_threshold)
            and outlier_threshold > 0):
        raise ValueError(f"outlier_threshold = {outlier_threshold!r} must be finite and > 0")
    if max_std is not None and not (_number(max_std) and np.isfinite(max_std) and max_std > 0):
        raise ValueError(f"max_std = {max_std!r} must be None or finite and > 0")
    if (not isinstance(max_evaluations, (int, np.integer)) or isinstance(max_evaluations, bool)
            or not 1 <= max_evaluations <= MAX_EVALUATIONS):
        raise ValueError(f"max_evaluations = {max_evaluations!r} must be an integer from 1 to "
                         f"{MAX_EVALUATIONS}")


def _number(value) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)


def check_measurements(poses: np.ndarray, readings: np.ndarray) -> None:
    """ValueError for no poses or too many, a value that is not finite, or a pose at the
    roll-pitch-yaw angles' singular orientation (pitch +-90 deg)."""
    if poses.shape[0] == 0:
        raise MeasurementError("poses: no measurement (0 rows): give the measured poses and the "
                               "readings at them (stewart.calibration_poses says where)")
    if poses.shape[0] > MAX_POSES:
        raise MeasurementError(f"poses: {poses.shape[0]} rows; calibrate takes at most "
                               f"{MAX_POSES} (tens of well-spread poses identify a machine: "
                               f"stewart.calibration_poses chooses them); give a subset")
    for name, a in (("poses", poses), ("readings", readings)):
        bad = np.argwhere(~np.isfinite(a))
        if bad.size:
            row, col = bad[0]
            raise MeasurementError(f"{name}[{row}, {col}] = {float(a[row, col])!r} is not "
                                   f"finite", rows=[row])
    locked = np.flatnonzero(np.abs(np.cos(poses[:, 4])) < GIMBAL_COS)
    if locked.size:
        row = locked[0]
        raise MeasurementError(
            f"poses[{row}]: pitch = {np.degrees(poses[row, 4]):.6g} deg, where roll and yaw are "
            f"not defined (R = Rz(yaw) Ry(pitch) Rx(roll) at pitch +-90 deg): its orientation "
            f"cannot be weighted. Are the angles in radians? Leave out pose rows "
            f"{locked.tolist()} or measure away from that orientation", rows=locked)


def refuse_gross_errors(readings: np.ndarray, predicted: np.ndarray, spread: np.ndarray,
                        poses: np.ndarray) -> None:
    """MeasurementError when readings differ from the nominal machine's by more than GROSS_ERROR
    times what its tolerances and the noise allow (spread: that standard deviation per reading):
    one or a few named as outliers by row and leg, many as a units or set-up mistake."""
    with np.errstate(invalid="ignore", over="ignore"):
        z = np.abs(readings - predicted) / spread
    bad = ~(z <= GROSS_ERROR)
    if not bad.any():
        return
    rows, legs = np.nonzero(bad)
    if bad.sum() <= max(1, bad.size // 20) and np.unique(rows).size < readings.shape[0] / 4:
        listed = "; ".join(f"pose row {r}, leg {k + 1}: {readings[r, k]:.6g} m where the "
                           f"nominal machine reads {predicted[r, k]:.6g} m"
                           for r, k in list(zip(rows, legs))[:5])
        raise MeasurementError(
            f"outlier: {bad.sum()} reading(s) differ from the nominal machine's by more than "
            f"{GROSS_ERROR:g} times what its tolerances and the noise allow ({listed}): measure "
            f"those poses again or leave their rows out", rows=rows, legs=legs + 1)
    raise MeasurementError(
        f"{bad.sum()} of {bad.size} readings differ from the nominal machine's by more than "
        f"{GROSS_ERROR:g} times what its tolerances and the noise allow (pose row {rows[0]}, "
        f"leg {legs[0] + 1}: {readings[rows[0], legs[0]]:.6g} m where the nominal machine reads "
        f"{predicted[rows[0], legs[0]]:.6g} m). {_set_up_hint(readings, predicted, poses)}",
        rows=np.unique(rows), legs=np.unique(legs) + 1)


def _set_up_hint(readings: np.ndarray, predicted: np.ndarray, poses: np.ndarray) -> str:
    angle = float(np.max(np.abs(poses[:, 3:])))
    if angle > 1.0:  # no hexapod tilts 57 degrees
        return (f"The poses' angles reach {angle:.4g}: are they in degrees? Give them in "
                f"radians.")
    if np.all(readings == 0):
        return "Every reading is 0: the readings columns are empty or not the sensors'."
    ratio = np.median(np.abs(readings)) / max(np.median(np.abs(predicted)), 1e-300)
    for factor, unit in ((1e3, "millimetres"), (1e6, "micrometres"), (1e-3, "kilometres")):
        if factor / 3 < ratio < factor * 3:
            return (f"The readings are about {ratio:.4g} times the nominal: are they in {unit}? "
                    f"Give them in metres.")
    return ("Check the units (m, rad), the column order, the nominal platform file (a reading "
            "is the joint-to-joint length minus length_offset) and the tool and user frames of "
            "the poses; if the machine is this far from its drawing, give larger tolerances.")


def refuse_far_moves(names: list[str], change: np.ndarray, tolerance: np.ndarray,
                     limit: np.ndarray, worst_rows: list[int]) -> None:
    """MeasurementError when the fit moves an unknown further than limit (FAR_MOVE tolerances,
    or a fraction of the machine's size) from nominal, or gives a value that is not finite."""
    if not np.all(np.isfinite(change)):
        raise MeasurementError("the fit gives parameters that are not finite: the measurements "
                               "do not describe this machine (check the units and outliers)",
                               rows=worst_rows)
    ratio = np.abs(change) / limit
    i = int(np.argmax(ratio))
    if ratio[i] <= 1:
        return
    unit = "rad" if "frame[" in names[i] and int(names[i].split("[")[1][:-1]) > 3 else "m"
    raise MeasurementError(
        f"the fit moves {names[i]} by {change[i]:.4g} {unit} from nominal, more than "
        f"{limit[i]:.3g} {unit} ({FAR_MOVE:g} times its tolerance {tolerance[i]:.3g} {unit}, "
        f"at most {FAR_FRACTION:g} of the machine's size): no built machine is that far from "
        f"its drawing. Check the units (m, rad) and the pose rows with the largest residuals "
        f"({', '.join(map(str, worst_rows))}); if the machine really is that far off, give a "
        f"larger tolerance (joint_tolerance, offset_tolerance, frame_tolerance)",
        rows=worst_rows)
