"""Limits a controller checks (stroke, joint angles, leg interference, condition, software
position limits per axis; the legs' speed, acceleration, jerk and force) and the axis
ranges they leave, on numpy arrays through the library (stewart/stewart_limits.h,
docs/limits.md). Platform.limits and Platform.axis_ranges call these."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from .params import parameter_assignments

#: The limit classes in check order; index + 1 is the library's class number (0: none).
LIMIT_CLASSES = ("stroke", "base_joint", "platform_joint", "interference", "condition", "axis",
                 "leg_speed", "leg_accel", "leg_jerk", "leg_force")
#: The unit of each class's margin (axis: the unit of the axis it is at, m or rad).
MARGIN_UNITS = ("m", "rad", "rad", "m", "1", "m or rad", "m/s", "m/s^2", "m/s^3", "N")
#: The classes of the pose alone (the leg classes need its derivatives or the legs' forces).
POSE_CLASSES = LIMIT_CLASSES[:6]


def class_name(number: int) -> str:
    """The name of a class number: "none", "stroke", ..., "condition", "axis"."""
    return _core.limit_class_name(int(number))


@dataclass
class LimitCheck:
    """The check of N poses. first: (N,) the first failing class (0 none, 1 stroke, 2 base
    joint, 3 platform joint, 4 interference, 5 condition, 6 axis: the software position limits
    axis_min, axis_max; 7 leg_speed, 8 leg_accel, 9 leg_jerk, 10 leg_force: leg_speed_max,
    leg_accel_max, leg_jerk_max, leg_force_max); failed: (N,) bit c - 1 set for every failing
    class c; margin: (N, 10) each class's smallest margin (> 0 within, 0 on the limit, which is
    within except for interference: legs that touch interfere; m, rad, rad, m, 1/condition -
    1/warn_condition, m or rad, m/s, m/s^2, m/s^3, N; +inf for a leg class without its data or
    its limit); leg, other_leg: (N, 10) where it is (legs 1..6, for axis the axis 1..6; the
    other leg of an interfering pair, else 0); condition: (N,) the leg Jacobian's; leg_margin:
    (N, 10, 6) each leg's own margin to each class (margin is their smallest; interference: the
    smallest over the leg's pairs; condition and axis, properties of the pose: the class margin
    at every leg)."""
    first: np.ndarray
    failed: np.ndarray
    margin: np.ndarray
    leg: np.ndarray
    other_leg: np.ndarray
    condition: np.ndarray
    leg_margin: np.ndarray

    @property
    def within(self) -> np.ndarray:
        """(N,) True where the pose is within every limit."""
        return self.failed == 0


def smallest_margins(platform, result: LimitCheck) -> np.ndarray:
    """Each class's smallest margin over the N poses of result (one per class): for the axis class
    that of the pose whose axis is nearest its limit, ranked as the library ranks the axes (an
    angle's margin times the longest arm from the tool origin to a platform joint), so that a
    margin in m and one in rad are never compared as numbers."""
    smallest = result.margin.min(axis=0)
    if len(result.margin):
        # the model's own joints and tool frame (both in the frames the parameters are given
        # in), not the parameters as given: an element set alone counts too
        _, top = _core.model_joints(platform._model)
        tool = np.array(_core.model_tool_frame(platform._model))[:3]
        arm = float(np.linalg.norm(np.reshape(top, (6, 3)) - tool, axis=1).max()) or 1.0
        axis = result.margin[:, 5]
        with np.errstate(over="ignore"):
            way = np.where((result.leg[:, 5] >= 4) & (axis <= 0.5 * np.finfo(float).max),
                           axis * arm, axis)
        smallest[5] = axis[int(np.argmin(way))]
    return smallest


def check(model, q: np.ndarray, warn_condition: Optional[float], rates=None, accels=None,
          jerks=None, forces=None) -> LimitCheck:
    """The check of every row of q (an (N, 6) C-contiguous float64 array), with the pose's
    rates, accelerations, jerks and the legs' forces (each None or (N, 6) like q; accels need
    rates, jerks accels) for the leg classes; warn_condition None: the library's default."""
    n = q.shape[0]
    k = _core.LIMIT_CLASSES
    leg_margin = np.zeros((n, k * 6))
    result = LimitCheck(np.zeros(n, np.int32), np.zeros(n, np.int32), np.zeros((n, k)),
                        np.zeros((n, k), np.int32), np.zeros((n, k), np.int32), np.zeros(n),
                        leg_margin.reshape(n, k, 6))
    _core.limits_check(model, q, rates, accels, jerks, forces, warn_condition, result.first,
                       result.failed, result.margin, result.leg, result.other_leg,
                       result.condition, leg_margin)
    return result


@dataclass
class AxisRanges:
    """The axis ranges of N poses: ends (N, 6, 2) [min, max] of each axis (x, y, z [m], roll,
    pitch, yaw [rad]) with the other five held; limit, leg, other_leg (N, 6, 2): the class met
    at each end (0: the search's end, pi away for an angle; where the search's proof ran out of
    steps, the class that held them), its leg (axis: the axis) and the interfering pair's other
    leg."""
    ends: np.ndarray
    limit: np.ndarray
    leg: np.ndarray
    other_leg: np.ndarray


def ranges(model, q: np.ndarray, warn_condition: Optional[float]) -> AxisRanges:
    """The axis ranges of every row of q (an (N, 6) C-contiguous float64 array)."""
    n = q.shape[0]
    ends = np.zeros((n, 12))
    limit, leg, other = (np.zeros((n, 12), np.int32) for _ in range(3))
    _core.limits_ranges(model, q, warn_condition, ends, limit, leg, other)

    def pairs(a: np.ndarray) -> np.ndarray:  # (N, 12) min.., max.. -> (N, 6, 2)
        return np.ascontiguousarray(np.stack([a[:, :6], a[:, 6:]], axis=2))

    return AxisRanges(pairs(ends), pairs(limit), pairs(leg), pairs(other))


#: The leg classes' limit parameters, in class order (per leg; 0: no limit).
LEG_LIMITS = ("leg_speed_max", "leg_accel_max", "leg_jerk_max", "leg_force_max")


def leg_limits_of(platform) -> dict:
    """The platform's leg limits: LEG_LIMITS name -> 6 values (0: no limit of that leg)."""
    values = {name: np.zeros(6) for name in LEG_LIMITS}
    for name, value in parameter_assignments(platform.params):
        base, _, index = name.partition("[")
        if base in values:
            if index:
                values[base][int(index.rstrip("]")) - 1] = value
            else:
                values[base][:] = value
    return values


def with_leg_limits(platform, **limits):
    """platform itself when every value of limits (LEG_LIMITS names) is None, else a platform of
    the same parameters with those leg limits replaced (a scalar or 6 values; 0: none)."""
    given = {name: value for name, value in limits.items() if value is not None}
    unknown = set(given) - set(LEG_LIMITS)
    if unknown:
        raise TypeError(f"not a leg limit: {sorted(unknown)}; the leg limits are {LEG_LIMITS}")
    if not given:
        return platform
    params = {name: value for name, value in platform.params.items()
              if name.partition("[")[0] not in given}
    for name, value in given.items():
        a = np.asarray(value, dtype=float)
        if a.shape not in ((), (6,)) or not np.all(np.isfinite(a)) or np.any(a < 0):
            raise ValueError(f"{name} = {a.tolist()} must be one value or 6, finite and >= 0 "
                             "(0: no limit)")
        params[name] = float(a) if a.ndim == 0 else a.tolist()
    return type(platform)(**params)
