"""Limits a controller checks (stroke, joint angles, leg interference, condition, software
position limits per axis) and the axis
ranges they leave, on numpy arrays through the library (stewart/stewart_limits.h,
docs/limits.md). Platform.limits and Platform.axis_ranges call these."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core

#: The limit classes in check order; index + 1 is the library's class number (0: none).
LIMIT_CLASSES = ("stroke", "base_joint", "platform_joint", "interference", "condition", "axis")
#: The unit of each class's margin (axis: the unit of the axis it is at, m or rad).
MARGIN_UNITS = ("m", "rad", "rad", "m", "1", "m or rad")


def class_name(number: int) -> str:
    """The name of a class number: "none", "stroke", ..., "condition", "axis"."""
    return _core.limit_class_name(int(number))


@dataclass
class LimitCheck:
    """The check of N poses. first: (N,) the first failing class (0 none, 1 stroke, 2 base
    joint, 3 platform joint, 4 interference, 5 condition, 6 axis: the software position limits
    axis_min, axis_max); failed: (N,) bit c - 1 set for every failing class c; margin: (N, 6)
    each class's smallest margin (> 0 within, 0 on the limit, which is within except for
    interference: legs that touch interfere; m, rad, rad, m, 1/condition - 1/warn_condition,
    and m or rad); leg, other_leg: (N, 6) where it is (legs 1..6, for axis the axis 1..6; the
    other leg of an interfering pair, else 0); condition: (N,) the leg Jacobian's."""
    first: np.ndarray
    failed: np.ndarray
    margin: np.ndarray
    leg: np.ndarray
    other_leg: np.ndarray
    condition: np.ndarray

    @property
    def within(self) -> np.ndarray:
        """(N,) True where the pose is within every limit."""
        return self.failed == 0


def smallest_margins(platform, result: LimitCheck) -> np.ndarray:
    """Each class's smallest margin over the N poses of result (6 values): for the axis class
    that of the pose whose axis is nearest its limit, ranked as the library ranks the axes (an
    angle's margin times the longest arm from the tool origin to a platform joint), so that a
    margin in m and one in rad are never compared as numbers."""
    smallest = result.margin.min(axis=0)
    if len(result.margin):
        _, top = _core.model_joints(platform._model)
        tool = np.broadcast_to(platform.params.get("tool_frame", 0.0), (6,))[:3]
        arm = float(np.linalg.norm(np.reshape(top, (6, 3)) - tool, axis=1).max()) or 1.0
        axis = result.margin[:, 5]
        with np.errstate(over="ignore"):
            way = np.where((result.leg[:, 5] >= 4) & (axis <= 0.5 * np.finfo(float).max),
                           axis * arm, axis)
        smallest[5] = axis[int(np.argmin(way))]
    return smallest


def check(model, q: np.ndarray, warn_condition: Optional[float]) -> LimitCheck:
    """The check of every row of q (an (N, 6) C-contiguous float64 array); warn_condition None:
    the library's default."""
    n = q.shape[0]
    k = _core.LIMIT_CLASSES
    result = LimitCheck(np.zeros(n, np.int32), np.zeros(n, np.int32), np.zeros((n, k)),
                        np.zeros((n, k), np.int32), np.zeros((n, k), np.int32), np.zeros(n))
    _core.limits_check(model, q, warn_condition, result.first, result.failed,
                       result.margin, result.leg, result.other_leg, result.condition)
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
