"""The calibration model: which geometry parameters are unknown, their values as one vector, the
sensor readings they predict at measured poses with the library's closed-form derivatives
(stewart_geometry_jacobian), the measurement noise as a weight, and the gauge (docs/calibration.md).

Parameters are the table's (stewart_table.h): base_joint[1..18] and platform_joint[1..18] (x, y, z
of legs 1..6 [m], geometry 1), length_offset[1..6] [m] (joint-to-joint length = reading +
offset), and, when asked, tool_frame[1..6] and user_frame[1..6] (x, y, z [m], roll, pitch, yaw
[rad]).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from .params import parameters
from .platform import Platform

JOINT_GROUPS = ("base_joint", "platform_joint", "length_offset")
FRAME_GROUPS = ("tool_frame", "user_frame")
ALL_GROUPS = JOINT_GROUPS + FRAME_GROUPS
GROUP_SIZE = {"base_joint": 18, "platform_joint": 18, "length_offset": 6, "tool_frame": 6,
              "user_frame": 6}
FRAME_CHOICES = {None: (), "none": (), "tool": ("tool_frame",), "user": ("user_frame",),
                 "both": FRAME_GROUPS}
_XY = np.tile([True, True, False], 6)
_ALL18 = np.ones(18, bool)
# What each `identify` word frees: group -> mask over its elements.
IDENTIFY_CHOICES = {
    "offsets": {"length_offset": np.ones(6, bool)},
    "joints": {"base_joint": _ALL18, "platform_joint": _ALL18},
    "joints-xy": {"base_joint": _XY, "platform_joint": _XY},
    "base": {"base_joint": _ALL18},
    "platform": {"platform_joint": _ALL18},
    "tool": {"tool_frame": np.ones(6, bool)},
    "user": {"user_frame": np.ones(6, bool)},
}
DEFAULT_IDENTIFY = ("joints", "offsets")

def parameter_value(platform: Platform, name: str) -> np.ndarray:
    """A parameter of platform as an array of its table count: the value given, else the
    table's default (a scalar given for a per-leg parameter fills its six legs)."""
    entry = next((p for p in parameters() if p["name"] == name), None)
    if entry is None:
        raise KeyError(f"the library has no parameter '{name}'")
    value = platform.params.get(name, entry["defaults"])
    out = np.broadcast_to(np.asarray(value, dtype=float), (entry["count"],)).copy()
    for key, element in platform.params.items():  # elements given by their own names
        if key.startswith(name + "[") and key.endswith("]"):
            out[int(key[len(name) + 1:-1]) - 1] = float(element)
    return out


def frame_groups(frames) -> tuple[str, ...]:
    """The frame parameters identified for a `frames` choice (None, "tool", "user", "both")."""
    try:
        return FRAME_CHOICES[frames]
    except (KeyError, TypeError):
        raise ValueError(f"frames = {frames!r} must be None, 'tool', 'user' or 'both'") from None


def identify_words(identify, frames=None) -> tuple[str, ...]:
    """The `identify` choice as its words ("joints,offsets", ["joints", "offsets"]), with the
    frames of `frames` added; ValueError naming a word that is not a choice."""
    if identify is None:
        words = list(DEFAULT_IDENTIFY)
    elif isinstance(identify, str):
        words = [w.strip() for w in identify.split(",") if w.strip()]
    else:
        try:
            words = [str(w).strip() for w in identify]
        except TypeError:
            raise ValueError(f"identify = {identify!r} must be a string or a list of "
                             f"{', '.join(IDENTIFY_CHOICES)}") from None
    words += [g.split("_")[0] for g in frame_groups(frames)]
    for word in words:
        if word not in IDENTIFY_CHOICES:
            raise ValueError(f"identify: {word!r} is not one of {', '.join(IDENTIFY_CHOICES)}")
    if not words:
        raise ValueError("identify is empty: name at least one of "
                         + ", ".join(IDENTIFY_CHOICES))
    return tuple(dict.fromkeys(words))


@dataclass(frozen=True)
class Layout:
    """Every calibration parameter (the five groups, 54 values, each by its table name,
    "base_joint[4]") and which of them are unknown (`free`); the others stay nominal."""
    free: np.ndarray
    words: tuple[str, ...] = DEFAULT_IDENTIFY
    groups: tuple[str, ...] = ALL_GROUPS

    @classmethod
    def of(cls, identify=None, frames=None) -> "Layout":
        free = {g: np.zeros(GROUP_SIZE[g], bool) for g in ALL_GROUPS}
        words = identify_words(identify, frames)
        for word in words:
            for group, mask in IDENTIFY_CHOICES[word].items():
                free[group] = free[group] | mask
        return cls(np.concatenate([free[g] for g in ALL_GROUPS]), words)

    @property
    def all_names(self) -> list[str]:
        return [f"{g}[{i}]" for g in self.groups for i in range(1, GROUP_SIZE[g] + 1)]

    @property
    def names(self) -> list[str]:
        """The unknowns' names."""
        return [n for n, f in zip(self.all_names, self.free) if f]

    @property
    def size(self) -> int:
        return sum(GROUP_SIZE[g] for g in self.groups)

    def identified_frames(self) -> tuple[str, ...]:
        return tuple(g for g in FRAME_GROUPS if np.any(self.split(self.free)[g]))

    def slices(self) -> dict[str, slice]:
        out, start = {}, 0
        for g in self.groups:
            out[g] = slice(start, start + GROUP_SIZE[g])
            start += GROUP_SIZE[g]
        return out

    def split(self, values: np.ndarray) -> dict[str, np.ndarray]:
        return {g: values[s] for g, s in self.slices().items()}


def nominal_geometry(platform: Platform) -> dict[str, np.ndarray]:
    """Every calibration parameter of platform: the joints the model uses (from the circles of
    geometry 0 or the coordinates of geometry 1), offsets and frames."""
    base, top = _core.model_joints(platform._model)
    geometry = {"base_joint": np.array(base), "platform_joint": np.array(top)}
    for name in ("length_offset",) + FRAME_GROUPS:
        geometry[name] = parameter_value(platform, name)
    return geometry


def platform_with(nominal: Platform, geometry: dict[str, np.ndarray]) -> Platform:
    """nominal with the joints given as coordinates (geometry 1) and the other calibration
    parameters replaced: a Platform, and as its params a platform file's content."""
    params = dict(nominal.params)
    params["geometry"] = 1
    for name, value in geometry.items():
        # The whole array replaces the nominal's, however it was spelled (element by element).
        for key in [k for k in params if k.startswith(name + "[")]:
            del params[key]
        params[name] = [float(v) for v in value]
    return Platform(**params)


def check_conventions(platform: Platform, what: str) -> None:
    """ValueError naming the parameter and the conversion to make when platform's poses or frames
    are not in the conventions calibration takes (rotation_order 0 and frame_convention 0: the
    closed-form derivatives of the readings are written in them). `what`: the function refusing,
    for the message."""
    order = int(parameter_value(platform, "rotation_order")[0])
    z_down = int(parameter_value(platform, "frame_convention")[0])
    if not (order or z_down):
        return
    steps = []
    if z_down:
        steps.append("frame_convention 1 (z down): give the machine in z-up frames, turned by 180 "
                     "deg about x: every joint, axis (neutral, Cardan), centre of mass and "
                     "position (x, y, z) of a pose or frame as (x, -y, -z), its angles (roll, "
                     "pitch, yaw) as (roll, -pitch, -yaw)")
    if order:
        steps.append("rotation_order 1 (R = Rx Ry Rz): give the poses' and the tool and user "
                     "frames' angles as Rz Ry Rx, stewart.convert_angles(angles, 1, 0)")
    raise ValueError(f"{what} takes rotation_order 0 and frame_convention 0 (the platform file's "
                     f"defaults); this platform has {'; and '.join(steps)}. Calibrate that "
                     "machine, then turn its calibrated joints back")


class ReadingError(ValueError):
    """A pose at which the model has no reading (a leg of zero length): names the pose row."""


def readings_and_jacobian(platform: Platform, poses: np.ndarray):
    """The readings (N, 6) the platform predicts at poses (tool frame in the user frame), and the
    derivatives by group: base_joint, platform_joint (N, 6, 3: leg k's own joint), tool_frame,
    user_frame, pose (N, 6, 6)."""
    n = poses.shape[0]
    out = {"length": np.empty((n, 6)), "reading": np.empty((n, 6)),
           "base_joint": np.empty((n, 18)), "platform_joint": np.empty((n, 18)),
           "tool_frame": np.empty((n, 36)), "user_frame": np.empty((n, 36)),
           "pose": np.empty((n, 36))}
    row, message = _core.geometry_jacobian(platform._model, np.ascontiguousarray(poses), **out)
    if row >= 0:
        raise ReadingError(f"pose row {row}: {message}")
    derivatives = {g: out[g].reshape(n, 6, 3) for g in ("base_joint", "platform_joint")}
    derivatives.update({g: out[g].reshape(n, 6, 6) for g in ("tool_frame", "user_frame", "pose")})
    return out["reading"], derivatives


def stacked_jacobian(layout: Layout, derivatives: dict[str, np.ndarray]) -> np.ndarray:
    """d reading / d unknowns as an (N, 6, p) array (readings of one pose, leg by leg)."""
    n = derivatives["pose"].shape[0]
    J = np.zeros((n, 6, layout.size))
    legs = np.arange(6)
    for group, s in layout.slices().items():
        block = J[:, :, s]
        if group in ("base_joint", "platform_joint"):
            for i in range(3):
                block[:, legs, 3 * legs + i] = derivatives[group][:, :, i]
        elif group == "length_offset":
            block[:, legs, legs] = -1.0
        else:
            block[:, :, :] = derivatives[group]
    return J


def angle_rate_matrices(poses: np.ndarray) -> np.ndarray:
    """E per pose (N, 3, 3): omega = E (roll, pitch, yaw)_dot for R = Rz Ry Rx (motion.hpp)."""
    cp, sp = np.cos(poses[:, 4]), np.sin(poses[:, 4])
    cy, sy = np.cos(poses[:, 5]), np.sin(poses[:, 5])
    E = np.zeros((poses.shape[0], 3, 3))
    E[:, 0, 0], E[:, 0, 1] = cy * cp, -sy
    E[:, 1, 0], E[:, 1, 1] = sy * cp, cy
    E[:, 2, 0], E[:, 2, 2] = -sp, 1.0
    return E


@dataclass(frozen=True)
class Noise:
    """Measurement noise, standard deviations: the tracker's position [m] and orientation (a small
    rotation, any axis) [rad] of each measured pose, and each sensor reading [m]."""
    position: float = 10e-6
    angle: float = 20e-6
    reading: float = 1e-6

    def check(self) -> None:
        """ValueError naming a noise that is not 0 or from 1e-12 to 1 (m or rad): below, its
        square underflows the weights; above, it is no measurement."""
        for name in ("position", "angle", "reading"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float, np.floating, np.integer)) and np.isfinite(v)
                    and (v == 0 or 1e-12 <= v <= 1.0)):
                raise ValueError(f"{name}_noise = {v!r} must be 0 or from 1e-12 to 1 "
                                 f"({'rad' if name == 'angle' else 'm'}): a standard deviation "
                                 f"of the measurement")
        if self.reading == 0:
            raise ValueError("reading_noise = 0: every sensor has some noise, and a pose's six "
                             "residuals need it to be weighted (give its standard deviation, "
                             "e.g. 1e-6 m)")


def whitening(pose_jacobian: np.ndarray, poses: np.ndarray, noise: Noise) -> np.ndarray:
    """W (N, 6, 6) with W r of unit covariance for the residual r = measured - predicted readings
    of a pose: cov r = J_p Σ_p J_pᵀ + J_w Σ_w J_wᵀ + σ_r² I, the pose noise seen through the
    readings' pose derivatives (J_w per small rotation = J_angles E⁻¹)."""
    Jp = pose_jacobian[:, :, :3]
    Jw = np.linalg.solve(np.swapaxes(angle_rate_matrices(poses), 1, 2),
                         np.swapaxes(pose_jacobian[:, :, 3:], 1, 2))
    Jw = np.swapaxes(Jw, 1, 2)
    cov = (noise.position ** 2 * Jp @ np.swapaxes(Jp, 1, 2)
           + noise.angle ** 2 * Jw @ np.swapaxes(Jw, 1, 2)
           + noise.reading ** 2 * np.eye(6))
    return np.linalg.inv(np.linalg.cholesky(cov))


def gauge_constraints(layout: Layout, nominal: dict[str, np.ndarray]) -> Optional[np.ndarray]:
    """The linear conditions that fix the gauge when a frame is identified with every coordinate
    of the joints it carries (rows of C, C δ = 0): a frame and its joints can move together
    without changing a reading, so the joints' net rigid motion from nominal is held at zero
    (6 rows per such frame: the sum of the joint shifts, and the sum of nominal joint x shift).
    None when there is no such pair (the nominal frames, or the prior, fix the split)."""
    pairs = {"user_frame": "base_joint", "tool_frame": "platform_joint"}
    slices, free = layout.slices(), layout.split(layout.free)
    rows = []
    for frame, joints in pairs.items():
        if not (np.all(free[frame]) and np.all(free[joints])):
            continue
        points = nominal[joints].reshape(6, 3)
        for axis in range(3):  # translation: sum_k d_k = 0
            row = np.zeros(layout.size)
            row[slices[joints]][axis::3] = 1.0
            rows.append(row)
        for axis in range(3):  # rotation: sum_k p_k x d_k = 0
            e = np.zeros(3)
            e[axis] = 1.0
            row = np.zeros(layout.size)
            # (p x d) . e = d . (e x p)
            row[slices[joints]] = np.cross(e, points).reshape(-1)
            rows.append(row)
    return np.array(rows) if rows else None


def weighted_rows(platform: Platform, poses: np.ndarray, layout: Layout, noise: Noise):
    """The readings platform predicts at poses (N, 6), the whitening W (N, 6, 6) of their
    residuals, and the weighted identification Jacobian W d reading / d parameters (N, 6, 54)."""
    predicted, derivatives = readings_and_jacobian(platform, poses)
    W = whitening(derivatives["pose"], poses, noise)
    return predicted, W, W @ stacked_jacobian(layout, derivatives)


def scaled_basis(layout: Layout, geometry: dict[str, np.ndarray], rows: np.ndarray,
                 tolerance: np.ndarray) -> np.ndarray:
    """T (54, r) with parameters = nominal + T z: the unknowns only (the others' rows are zero),
    each scaled to a unit column of the weighted Jacobian rows (m, 54) stacked on its prior row
    (1 / tolerance), the scale of the reported condition number; restricted to the gauge
    (C T = 0, gauge_constraints)."""
    norms = np.sqrt(np.sum(rows ** 2, axis=0) + 1.0 / tolerance ** 2)
    scale = np.where(layout.free, 1.0 / norms, 0.0)
    T = np.diag(scale)[:, layout.free]
    constraints = gauge_constraints(layout, geometry)
    if constraints is None:
        return T
    _, sv, Vt = np.linalg.svd(constraints @ T)
    rank = int(np.sum(sv > sv[0] * 1e-12))
    return T @ Vt[rank:].T


@dataclass(frozen=True)
class Prior:
    """The nominal geometry's tolerances: standard deviations of the built machine's parameters
    about their nominal values (joints and offsets [m], frames' origins [m] and angles [rad])."""
    joint: float = 1e-3
    offset: float = 1e-3
    frame_position: float = 5e-3
    frame_angle: float = 5e-3

    def check(self) -> None:
        names = {"joint": "joint_tolerance", "offset": "offset_tolerance",
                 "frame_position": "frame_tolerance", "frame_angle": "frame_angle_tolerance"}
        for field, name in names.items():
            v = getattr(self, field)
            if not (isinstance(v, (int, float, np.floating, np.integer)) and np.isfinite(v)
                    and 1e-9 <= v <= 1e3):
                raise ValueError(f"{name} = {v!r} must be a number from 1e-9 to 1e3 "
                                 f"({'rad' if field == 'frame_angle' else 'm'})")

    def vector(self, layout: Layout) -> np.ndarray:
        """The tolerance of each of the 54 parameters."""
        frame = np.r_[[self.frame_position] * 3, [self.frame_angle] * 3]
        joint = np.full(18, self.joint)
        by_group = {"base_joint": joint, "platform_joint": joint,
                    "length_offset": np.full(6, self.offset), "tool_frame": frame,
                    "user_frame": frame}
        return np.concatenate([by_group[g] for g in layout.groups]).astype(float)

