"""Moves: rest-to-rest trajectories from one pose to another, time-optimal under the legs' speed
and acceleration limits along the whole path, checked against every geometric limit class at
every sample (docs/moves.md).

A move is a path q(s), s in [0, 1], and a time law s(t). The path is either a straight line in
the 6-D pose space ("point": every axis arrives together) or a straight line of the tool point
with a slerp of the orientation ("line": one path parameter for both), or straight lines in pose
space through waypoints with blended corners (passed without stopping). The time law comes from a
phase-plane computation on a fine grid of s (time-optimal path parametrisation, TOPP): with
x = ds/dt squared and u = d2s/dt2 constant on each grid segment, the leg speed L'(s) ds/dt and
acceleration L'(s) u + L''(s) x are kept within their limits at both ends of every segment, a
backward pass finds the largest speed from which the goal can still be reached at rest, and a
forward pass accelerates as hard as that allows. With a leg jerk limit that law (whose path
acceleration switches at once) is replaced by a jerk-limited S-curve of s (moves_jerk). Rates,
accelerations and jerks of the samples are exact: q' ds/dt, q' d2s/dt2 + q'' (ds/dt)^2 and
q' d3s/dt3 + 3 q'' ds/dt d2s/dt2 + q''' (ds/dt)^3 with the path's own derivatives.

>>> import stewart
>>> m = stewart.move(stewart.Platform(), [0, 0, 0.5, 0, 0, 0], [0.01, 0, 0.5, 0, 0, 0],
...                  leg_speed_max=0.05, leg_accel_max=0.5)
>>> m.pose[-1].tolist() == [0.01, 0, 0.5, 0, 0, 0]
True
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .angles import _angles_of, _rate_matrix, _rate_matrix_dot, rotation_matrix
from .arrays import vector
from .limits import (LIMIT_CLASSES, MARGIN_UNITS, POSE_CLASSES, LimitCheck, class_name,
                     leg_limits_of, with_leg_limits)
from .moves_jerk import LegPeaks, jerk_limited_law, sample_law
from .params import parameter_values

KINDS = ("point", "line")
FRAMES = ("user", "tool")
#: Grid segments of s for the phase-plane computation (the first try; refined on a retry).
GRID_SEGMENTS = 1000
#: The limits are planned this much inside (relative); the samples are then checked at the full
#: limits. Between grid nodes the constraints vary by O(segment^2): this margin covers it.
PLAN_MARGIN = 1e-4
#: Relative slack of the check of the sampled leg speeds and accelerations against the limits.
CHECK_SLACK = 1e-9
#: Speeds squared are capped here where nothing limits them (no Cartesian or leg speed limit).
_X_CAP = 1e30


class MoveError(ValueError):
    """A move that cannot be made: limit_class names the limit ("stroke", "base_joint",
    "platform_joint", "interference", "condition", "axis", "unreachable", "leg_speed",
    "leg_accel", "leg_jerk", "leg_force", "current"), and time [s] and s (the path parameter
    in [0, 1]) say where, when known."""

    def __init__(self, message: str, limit_class: str, time: Optional[float] = None,
                 s: Optional[float] = None) -> None:
        super().__init__(message)
        self.limit_class, self.time, self.s = limit_class, time, s


@dataclass
class Move:
    """A planned move at the sample time: t (N,) [s] from 0 to duration, pose, pose_rate,
    pose_accel (N, 6) (x, y, z [m], roll, pitch, yaw [rad] in the platform's rotation order, and
    their exact first and second time derivatives), s, s_rate, s_accel (N,) the path parameter
    and its derivatives. Row 0 is the start at rest; the last row is the goal at rest, with the
    braking acceleration just before arrival."""
    t: np.ndarray
    pose: np.ndarray
    pose_rate: np.ndarray
    pose_accel: np.ndarray
    s: np.ndarray
    s_rate: np.ndarray
    s_accel: np.ndarray
    duration: float
    kind: str
    pose_jerk: Optional[np.ndarray] = None  #: (N, 6) exact third derivatives (jerk-limited moves)


class _PointPath:
    """q(s) = q0 + s (q1 - q0): a straight line in pose space."""

    def __init__(self, q0: np.ndarray, q1: np.ndarray, order: int) -> None:
        self.q0, self.q1, self.dq, self.order = q0, q1, q1 - q0, order

    breaks = np.zeros(0)  #: s where the path's second derivative jumps (none)

    def derivatives(self, s: np.ndarray, side: str = "right"):
        """q, dq/ds, d2q/ds2 (n, 6) and the angular velocity per unit s (n, 3), base axes."""
        q = self.q0 + s[:, None] * self.dq
        q[s == 1.0] = self.q1
        dq = np.broadcast_to(self.dq, q.shape).copy()
        omega = np.einsum("nij,j->ni", _rate_matrix(q[:, 3:], self.order), self.dq[3:])
        return q, dq, np.zeros_like(q), omega

    def third(self, q, dq, ddq):
        """d3q/ds3 (n, 6): zero on a straight line."""
        return np.zeros_like(q)


class _LinePath:
    """The tool point on a straight line, the orientation R(s) = exp(s [w]) R0 (a slerp from R0
    to R1; w the rotation vector of R1 R0^T): its angular velocity per unit s is w, constant."""

    def __init__(self, q0: np.ndarray, q1: np.ndarray, order: int) -> None:
        self.q0, self.q1, self.order = q0, q1, order
        self.R0 = rotation_matrix(q0[3:], order)
        self.w = _rotation_vector(rotation_matrix(q1[3:], order) @ self.R0.T)
        end = self._angles(np.array([1.0]))[0]
        if np.max(np.abs(end - q1[3:])) > 1e-9:
            raise ValueError(f"the slerp from the start reaches the goal's rotation at angles "
                             f"{end.tolist()}, not the goal's {q1[3:].tolist()} (a whole turn "
                             "apart): give the goal's roll and yaw on that branch")

    def _angles(self, s: np.ndarray) -> np.ndarray:
        R = _exp(s[:, None] * self.w) @ self.R0
        a = _angles_of(R, self.order, np.broadcast_to(self.q0[3:], (s.size, 3)))
        a[:, [0, 2]] = np.unwrap(np.vstack([self.q0[[3, 5]], a[:, [0, 2]]]), axis=0)[1:]
        return a

    breaks = np.zeros(0)

    def derivatives(self, s: np.ndarray, side: str = "right"):
        n = s.size
        q = np.empty((n, 6))
        q[:, :3] = self.q0[:3] + s[:, None] * (self.q1[:3] - self.q0[:3])
        q[:, 3:] = self._angles(s)
        q[s == 0.0] = self.q0
        q[s == 1.0] = self.q1
        if np.any(np.abs(np.cos(q[:, 4])) < 1e-9):
            raise ValueError("the line passes pitch +-90 degrees, where the angles' rates are "
                             "not defined: use kind='point' or another start or goal")
        E = _rate_matrix(q[:, 3:], self.order)
        dq = np.empty((n, 6))
        dq[:, :3] = self.q1[:3] - self.q0[:3]
        dq[:, 3:] = _solve3(E, np.broadcast_to(self.w, (n, 3)))
        # d/ds (E a') = dw/ds = 0, so E a'' = -(dE/ds) a'.
        bias = np.einsum("nij,nj->ni", _rate_matrix_dot(q[:, 3:], dq[:, 3:], self.order),
                         dq[:, 3:])
        ddq = np.zeros((n, 6))
        ddq[:, 3:] = -_solve3(E, bias)
        return q, dq, ddq, np.broadcast_to(self.w, (n, 3)).copy()

    def third(self, q, dq, ddq):
        """d3q/ds3 (n, 6) from q, dq, ddq of derivatives(): differentiating E a' = w twice,
        E a''' = -(d2E/ds2) a' - 2 (dE/ds) a'', where d2E/ds2 is dE/ds differentiated along a'
        at fixed rates (by a complex step: exact to rounding) plus dE/ds at the rates a''."""
        a, a1, a2 = q[:, 3:], dq[:, 3:], ddq[:, 3:]
        h = 1e-30
        E2 = (np.imag(_rate_matrix_dot(a + 1j * h * a1, a1, self.order)) / h
              + _rate_matrix_dot(a, a2, self.order))
        E1 = _rate_matrix_dot(a, a1, self.order)
        rhs = np.einsum("nij,nj->ni", E2, a1) + 2 * np.einsum("nij,nj->ni", E1, a2)
        out = np.zeros_like(q)
        out[:, 3:] = -_solve3(_rate_matrix(a, self.order), rhs)
        return out


class _BlendedPath:
    """Straight lines in pose space through waypoints, each corner replaced by a quadratic
    Bezier blend from r before the corner to r after it (r = blend times the shorter adjacent
    line, lengths in pose space with metres and radians alike): the path's direction is
    continuous, so the move passes the corners without stopping. Every piece is a quadratic
    c0 + c1 l + c2 l^2 in its own length l; the parameter s is the length over the total."""

    def __init__(self, points: np.ndarray, blend: float, order: int) -> None:
        steps = np.diff(points, axis=0)
        lengths = np.linalg.norm(steps, axis=1)
        if np.any(lengths == 0):
            j = int(np.flatnonzero(lengths == 0)[0])
            raise ValueError(f"waypoints {j} and {j + 1} (counting the start as 0) are the "
                             "same pose: leave one out")
        units = steps / lengths[:, None]
        r = np.zeros(len(points))
        r[1:-1] = blend * np.minimum(lengths[:-1], lengths[1:])
        pieces = []  # (length, c0, c1, c2)
        for j in range(len(steps)):
            if j > 0:
                pieces.append((2 * r[j], points[j] - r[j] * units[j - 1], units[j - 1],
                               (units[j] - units[j - 1]) / (4 * r[j])))
            straight = lengths[j] - r[j] - r[j + 1]
            if straight > 0:
                pieces.append((straight, points[j] + r[j] * units[j], units[j], 0 * units[j]))
        size = np.array([p[0] for p in pieces])
        self.total = float(np.sum(size))
        self.starts = np.concatenate([[0.0], np.cumsum(size)[:-1]]) / self.total
        self.c = np.array([[p[1], p[2], p[3]] for p in pieces])  # (pieces, 3, 6)
        self.breaks = self.starts[1:]
        self.q0, self.q1, self.order = points[0], points[-1], order

    def derivatives(self, s: np.ndarray, side: str = "right"):
        k = np.searchsorted(self.starts, s, side="right" if side == "right" else "left") - 1
        k = np.clip(k, 0, len(self.starts) - 1)
        length = (s - self.starts[k])[:, None] * self.total
        c0, c1, c2 = self.c[k, 0], self.c[k, 1], self.c[k, 2]
        q = c0 + c1 * length + c2 * length ** 2
        q[s == 0.0], q[s == 1.0] = self.q0, self.q1
        dq = (c1 + 2 * c2 * length) * self.total
        ddq = 2 * c2 * self.total ** 2
        omega = np.einsum("nij,nj->ni", _rate_matrix(q[:, 3:], self.order), dq[:, 3:])
        return q, dq, ddq, omega


def _exp(w: np.ndarray) -> np.ndarray:
    """Rodrigues: exp([w]) = cos(t) I + sin(t)/t [w] + (1 - cos(t))/t^2 w w^T for (n, 3)
    rotation vectors w of angle t, entry by entry."""
    theta = np.linalg.norm(w, axis=-1)
    small = theta < 1e-8
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - theta ** 2 / 6, np.sin(safe) / safe)
    b = np.where(small, 0.5 - theta ** 2 / 24, (1 - np.cos(safe)) / safe ** 2)
    c = np.where(small, 1.0 - theta ** 2 / 2, np.cos(safe))
    R = (b[:, None] * w)[:, :, None] * w[:, None, :]
    R[:, [0, 1, 2], [0, 1, 2]] += c[:, None]
    aw = a[:, None] * w
    R[:, 0, 1] -= aw[:, 2]
    R[:, 1, 0] += aw[:, 2]
    R[:, 0, 2] += aw[:, 1]
    R[:, 2, 0] -= aw[:, 1]
    R[:, 1, 2] -= aw[:, 0]
    R[:, 2, 1] += aw[:, 0]
    return R


def _solve3(E: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with E x = rhs for (n, 3, 3) E and (n, 3) rhs, by the adjugate, entry by entry (the
    rate matrices here are well conditioned away from pitch +-90 degrees, which is refused)."""
    (a, b, c), (d, e, f), (g, h, k) = ([E[:, r, col] for col in range(3)] for r in range(3))
    x, y, z = rhs[:, 0], rhs[:, 1], rhs[:, 2]
    A, B, C = e * k - f * h, f * g - d * k, d * h - e * g   # cofactors of the first row
    det = a * A + b * B + c * C
    out = np.empty_like(rhs)
    out[:, 0] = A * x + (c * h - b * k) * y + (b * f - c * e) * z
    out[:, 1] = B * x + (a * k - c * g) * y + (c * d - a * f) * z
    out[:, 2] = C * x + (b * g - a * h) * y + (a * e - b * d) * z
    return out / det[:, None]


def _rotation_vector(R: np.ndarray) -> np.ndarray:
    """log of a rotation matrix as a rotation vector of angle in [0, pi)."""
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    theta = math.atan2(np.linalg.norm(v) / 2, (np.trace(R) - 1) / 2)
    if theta > math.pi - 1e-6:
        raise ValueError("start and goal orientations are 180 degrees apart: the slerp's "
                         "direction is not defined; go through an intermediate pose")
    return v / 2 * (1 + theta ** 2 / 6 if theta < 1e-8 else theta / math.sin(theta))


def _limit_vector(name: str, value) -> Optional[np.ndarray]:
    """A leg limit as 6 values (scalar or per leg; 0 = none), or None if there is none."""
    if value is None:
        return None
    a = np.broadcast_to(np.asarray(value, dtype=float), (6,)) if np.ndim(value) == 0 \
        else vector(name, value, 6)
    if not np.all(np.isfinite(a)) or np.any(a < 0):
        raise ValueError(f"{name} = {np.asarray(value).tolist()} must be finite and >= 0 "
                         "(0: no limit)")
    return None if not np.any(a > 0) else np.where(a > 0, a, np.inf)


def _speed_bound(name, value) -> Optional[float]:
    if value is None or value == 0:
        return None
    if not (isinstance(value, numbers.Real) and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value!r} must be a finite number > 0 (or None)")
    return float(value)


def _segment_constraints(start, end, ds, accel_max, x_speed):
    """The bounds on u (d2s/dt2, constant on a grid segment) of every segment i as linear
    functions of x_i ((ds/dt)^2 at its start): uppers u <= (c - b x_i) / d and lowers
    u >= (c - b x_i) / d, d >= 0, each a triple of (N, K) arrays. They keep the leg
    accelerations L' u + L'' x within accel_max at both ends of the segment (at its end
    x = x_i + 2 u ds), (ds/dt)^2 at its end within x_speed and >= 0. start, end: (L', L'') at
    the segments' starts and ends, (N, 6) each (one-sided where the path's L'' jumps); ds (N,)."""
    n = ds.size
    ds = ds[:, None]
    on = np.isfinite(accel_max)
    A = np.broadcast_to(np.where(on, accel_max, _X_CAP), (n, 6))
    ends = []
    for a, b in ((start[0], start[1]), (end[0] + 2 * ds * end[1], end[1])):
        sign = np.where(a >= 0, 1.0, -1.0)
        ends.append((np.where(on, sign * b, 0.0), np.where(on, np.abs(a), 0.0)))
    b_legs = np.hstack([e[0] for e in ends])
    d_legs = np.hstack([e[1] for e in ends])
    A2 = np.hstack([A, A])
    col = np.ones((n, 1))
    upper = (np.hstack([A2, x_speed[1:, None]]), np.hstack([b_legs, col]),
             np.hstack([d_legs, 2 * ds * col]))
    lower = (np.hstack([-A2, 0 * col]), np.hstack([b_legs, col]), np.hstack([d_legs, 2 * ds * col]))
    return upper, lower


def _controllable(upper, lower, x_speed, ds):
    """The largest x_i ((ds/dt)^2) of every grid node from which the goal is reached at rest
    within the bounds (backward pass). u is eliminated pairwise (Fourier-Motzkin): a lower
    bound (c_l - b_l x) / d_l <= an upper (c_u - b_u x) / d_u is
    x (d_l b_u - d_u b_l) <= d_l c_u - d_u c_l, written without dividing by a d that may be 0."""
    (cu, bu, du), (cl, bl, dl) = upper, lower
    n = cu.shape[0]
    static = np.minimum(_static_bound(upper, lower), np.minimum(x_speed[:-1], _X_CAP))
    # The pairs of each lower bound with the next node's set, x + 2 u ds <= hi[i + 1]:
    # x (d_l - 2 ds b_l) <= d_l hi - 2 ds c_l.
    ds = ds[:, None]
    next_coef = dl - 2 * ds * bl
    use = next_coef > 0
    next_coef = np.where(use, next_coef, 1.0)
    next_d = np.where(use, dl, 0.0)
    next_c = np.where(use, 2 * ds * cl, -np.inf)
    # The sequential pass runs on Python floats (numpy's per-call cost dominates a few values)
    # over the bounds that are the smallest for some x in [0, the next node's static bound].
    top_next = np.append(np.minimum(static[1:], _X_CAP), 0.0)
    keep = _envelope(next_d / next_coef, -next_c / next_coef, top_next)
    next_d, next_c, next_coef = _compact(keep, (next_d, 0.0), (next_c, -np.inf), (next_coef, 1.0))
    rows = zip(next_d.tolist(), next_c.tolist(), next_coef.tolist(), static.tolist())
    hi = [0.0] * (n + 1)
    for i, (d, c, k, top) in zip(range(n - 1, -1, -1), reversed(list(rows))):
        h = hi[i + 1]
        limit = min([(dj * h - cj) / kj for dj, cj, kj in zip(d, c, k)])
        hi[i] = max(0.0, min(top, limit))
    return np.array(hi)


def _static_bound(upper, lower):
    """Per segment the smallest x bound of every pair (lower, upper) of _segment_constraints'
    bounds (the pairs of _controllable's docstring). The legs' bounds (all columns but the
    last) come in pairs of one line, u within +-A: the pair (lower j, upper k) gives
    x (d_j b_k - d_k b_j) <= d_j A_k + d_k A_j and (lower k, upper j) the same with the
    coefficient negated, so each unordered pair is computed once, with |coefficient|."""
    (cu, bu, du), (cl, bl, dl) = upper, lower
    A, b, d = cu[:, :-1], bu[:, :-1], du[:, :-1]
    j, k = np.triu_indices(A.shape[1], 1)
    coef = [np.abs(d[:, j] * b[:, k] - d[:, k] * b[:, j]),
            dl[:, :-1] * bu[:, -1:] - du[:, -1:] * bl[:, :-1],   # leg lowers, last upper
            dl[:, -1:] * bu[:, :-1] - du[:, :-1] * bl[:, -1:]]   # last lower, leg uppers
    rhs = [d[:, j] * A[:, k] + d[:, k] * A[:, j],
           dl[:, :-1] * cu[:, -1:] - du[:, -1:] * cl[:, :-1],
           dl[:, -1:] * cu[:, :-1] - du[:, :-1] * cl[:, -1:]]
    smallest = np.full(cu.shape[0], np.inf)
    for c, r in zip(coef, rhs):
        bound = np.divide(r, c, out=np.full_like(r, np.inf), where=c > 0)
        smallest = np.minimum(smallest, bound.min(axis=1))
    return smallest


def _envelope(slope, offset, top):
    """Which of the lines slope h + offset ((n, m) each; offset +inf: no line) are the smallest
    of row i's lines somewhere in h in [0, top[i]]: the lower envelope, walked from h = 0 (the
    smallest line there, ties to the smaller slope) to each next line that crosses below the
    current one (the first crossing, ties to the smaller slope) until a crossing lies beyond
    top. The slope falls at every step, so at most m steps, each one numpy pass over all rows.
    Exact but for rounding at a crossing, where the lines differ by rounding."""
    n, m = slope.shape
    rows = np.arange(n)
    finite = np.isfinite(offset)
    keep = np.zeros((n, m), dtype=bool)
    start = np.where(finite, offset, np.inf)
    tied = finite & (start == start.min(axis=1)[:, None])
    line = np.argmin(np.where(tied, slope, np.inf), axis=1)
    live = finite.any(axis=1)
    h = np.zeros(n)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for _ in range(m):
            keep[rows[live], line[live]] = True
            s_now, o_now = slope[rows, line][:, None], offset[rows, line][:, None]
            below = finite & (slope < s_now)
            cross = np.where(below, np.maximum((offset - o_now) / (s_now - slope), h[:, None]),
                             np.inf)
            h_next = cross.min(axis=1)
            live &= h_next <= top
            if not live.any():
                break
            tied = below & (cross == h_next[:, None])
            line = np.where(live, np.argmin(np.where(tied, slope, np.inf), axis=1), line)
            h = np.where(live, h_next, h)
    return keep


def _compact(keep, *columns):
    """Each (array, inert value) of columns with row i's kept entries first, cut to the widest
    row's count, the rest filled with the inert value (a bound that never binds)."""
    width = max(1, int(keep.sum(axis=1).max()))
    order = np.argsort(~keep, axis=1, kind="stable")[:, :width]
    kept = np.take_along_axis(keep, order, axis=1)
    return tuple(np.where(kept, np.take_along_axis(a, order, axis=1), inert)
                 for a, inert in columns)


def _forward(upper, hi, ds):
    """The fastest x of every node from rest (forward pass) and u of every segment: the largest
    u each segment allows that keeps the next node within hi."""
    cu, bu, du = upper
    n = cu.shape[0]
    positive = du > 0
    inv_d = np.where(positive, 1.0 / np.where(positive, du, 1.0), 0.0)
    # A bound with d = 0 is no bound on u (its x part is in hi): c - b x times 0 drops it.
    cu = np.where(positive, cu, _X_CAP)
    bu = np.where(positive, bu, 0.0)
    # Only the bounds that are the smallest for some x in [0, hi] of their node enter the
    # sequential pass.
    keep = _envelope(-bu * inv_d, np.where(positive, cu * inv_d, np.inf), hi[:-1])
    cu, bu, inv_d = _compact(keep, (cu, _X_CAP), (bu, 0.0), (inv_d, 0.0))
    x = [0.0] * (n + 1)
    u = [0.0] * n
    his, steps = hi.tolist(), ds.tolist()
    for i, (c, b, r) in enumerate(zip(cu.tolist(), bu.tolist(), inv_d.tolist())):
        xi, step = x[i], steps[i]
        room = min([(cj - bj * xi) * rj if rj else _X_CAP for cj, bj, rj in zip(c, b, r)])
        u[i] = min(room, (his[i + 1] - xi) / (2 * step))
        x[i + 1] = max(0.0, xi + 2 * step * u[i])
    x[n] = 0.0
    u[n - 1] = -x[n - 1] / (2 * steps[n - 1])
    return np.array(x), np.array(u)


def _leg_derivatives(platform, path, s, side):
    """The path's poses, leg L' and L'' (the inverse's length rate and acceleration for the pose
    moving along the path at ds/dt = 1, d2s/dt2 = 0) and x bounds' inputs at s, from `side`."""
    q, dq, ddq, omega = path.derivatives(s, side)
    legs = platform.inverse(q, dq, ddq, fidelity="kinematic")
    bad = np.flatnonzero(legs.status != 0)
    if bad.size:
        i = bad[0]
        raise MoveError(f"the path has a pose the legs cannot reach at s = {s[i]:.6g} "
                        f"(pose {q[i].tolist()}): {legs.messages.get(i, legs.status_name(i))}",
                        "unreachable", None, float(s[i]))
    return q, legs.length_rate, legs.length_accel, dq, omega


def _speed_bound_x(Lp, dq, omega, limits, shrink):
    """The largest (ds/dt)^2 the speed limits allow at each node."""
    speed, _, tool_speed, angular_speed = limits
    with np.errstate(divide="ignore"):
        xs = np.full(Lp.shape[0], _X_CAP)
        if speed is not None:
            xs = np.minimum(xs, np.min((shrink * speed / np.abs(Lp)) ** 2, axis=1))
        for bound, rate in ((tool_speed, np.linalg.norm(dq[:, :3], axis=1)),
                            (angular_speed, np.linalg.norm(omega, axis=1))):
            if bound is not None:
                xs = np.minimum(xs, (shrink * bound / rate) ** 2)
    return xs


def _time_law(path, platform, segments, margin, limits):
    """s nodes, ds/dt at them, u per segment and node times of the time-optimal law on a grid
    of `segments` (plus the path's breaks), with the limits planned `margin` inside; and the
    grid's poses."""
    s = np.union1d(np.linspace(0.0, 1.0, segments + 1), path.breaks)
    ds = np.diff(s)
    shrink = 1.0 - margin
    q, Lp, Lpp, dq, omega = _leg_derivatives(platform, path, s, "right")
    xs = _speed_bound_x(Lp, dq, omega, limits, shrink)
    end = (Lp[1:], Lpp[1:])
    if path.breaks.size:  # at a break, the segment before it ends on the other side's L''
        at = np.flatnonzero(np.isin(s, path.breaks))  # elsewhere both sides are the same
        _, Lp_at, Lpp_at, dq_at, omega_at = _leg_derivatives(platform, path, s[at], "left")
        xs[at] = np.minimum(xs[at], _speed_bound_x(Lp_at, dq_at, omega_at, limits, shrink))
        Lp_left, Lpp_left = Lp.copy(), Lpp.copy()
        Lp_left[at], Lpp_left[at] = Lp_at, Lpp_at
        end = (Lp_left[1:], Lpp_left[1:])
    upper, lower = _segment_constraints((Lp[:-1], Lpp[:-1]), end, ds, shrink * limits[1], xs)
    hi = _controllable(upper, lower, xs, ds)
    x, u = _forward(upper, hi, ds)
    v = np.sqrt(x)
    if np.any(v[:-1] + v[1:] <= 0):
        raise MoveError("the time law stalls on the path (a zero speed bound): a speed limit "
                        "(leg_speed_max, motor_speed_max, speed_max, angular_speed_max) is too "
                        "small to time this path; give a larger one", "leg_speed")
    t = np.concatenate([[0.0], np.cumsum(2 * ds / (v[:-1] + v[1:]))])
    return s, v, u, t, q


def _sample(s_nodes, v, u, t_nodes, sample_time):
    """Sample times (the duration rounded up to whole samples by slowing the law down
    uniformly, which keeps every limit) and s, ds/dt, d2s/dt2 at them."""
    duration = t_nodes[-1]
    count = max(1, math.ceil(duration / sample_time - 1e-9))
    if count > 100_000_000:
        raise ValueError(f"the move takes {duration:.6g} s: {count:.6g} samples of {sample_time} s "
                         "are too many; give a larger sample_time")
    scale = count * sample_time / duration
    t = np.arange(count + 1) * sample_time
    tau = t / scale
    i = np.clip(np.searchsorted(t_nodes, tau, side="right") - 1, 0, u.size - 1)
    d = tau - t_nodes[i]
    s = np.clip(s_nodes[i] + v[i] * d + 0.5 * u[i] * d * d, 0.0, 1.0)
    rate = np.maximum(v[i] + u[i] * d, 0.0) / scale
    accel = u[i] / scale ** 2
    s[0], rate[0], s[-1], rate[-1] = 0.0, 0.0, 1.0, 0.0
    return t, s, rate, accel, scale


def _first_limit(check, poses, s, times):
    """MoveError at the smallest s whose pose is beyond a geometric limit in check (a
    Platform.limits result of poses; the geometric classes are checked first, so a row's first
    class is geometric if one is met), if any."""
    bad = np.flatnonzero((check.first != 0) & (check.first <= len(POSE_CLASSES)))
    if bad.size:
        j = bad[np.argmin(s[bad])]
        name = class_name(check.first[j])
        raise MoveError(f"the path crosses the {name} limit at t = {times[j]:.6g} s "
                        f"(s = {s[j]:.6g}, pose {poses[j].tolist()}, margin "
                        f"{check.margin[j, check.first[j] - 1]:.3g}): the start and goal may be "
                        "valid but the path is not; go through an intermediate pose or use "
                        "the other kind", name, float(times[j]), float(s[j]))


def _leg_excess(limited, check, t, s):
    """MoveError naming the first sample whose leg speed, acceleration (or the massless
    inverse's force) exceeds the limited platform's leg limit by more than CHECK_SLACK
    (relative), from the library's leg classes in check (limited.limits of the samples with
    their rates and accelerations); or None."""
    bounds = leg_limits_of(limited)
    for name in ("leg_speed", "leg_accel", "leg_jerk", "leg_force"):
        column = LIMIT_CLASSES.index(name)
        over = check.leg_margin[:, column] < -CHECK_SLACK * bounds[f"{name}_max"]
        rows = np.flatnonzero(over.any(axis=1))
        if rows.size:
            j = rows[0]
            k = int(np.argmax(over[j]))
            return MoveError(f"the planned move exceeds {name} at t = {t[j]:.6g} s "
                             f"(s = {s[j]:.6g}): leg {k + 1} by "
                             f"{-check.leg_margin[j, column, k]:.6g} {MARGIN_UNITS[column]}",
                             name, float(t[j]), float(s[j]))
    return None


def _joined(a, b):
    """The first classes and margins of two limit checks, rows of a then b (what
    _first_limit reads)."""
    return LimitCheck(np.concatenate([a.first, b.first]), None,
                      np.vstack([a.margin, b.margin]), None, None, None, None)


def _rotation_order(platform) -> int:
    return int(np.asarray(platform.params.get("rotation_order", 0)).reshape(-1)[0])


def _goal_pose(start, goal, frame, order) -> np.ndarray:
    """The absolute goal: goal itself (frame None) or goal as a displacement (dx, dy, dz, and
    angles of a rotation) of the tool in the user frame's axes or in the tool's own axes, about
    the tool point."""
    if frame is None:
        return goal
    if frame not in FRAMES:
        raise ValueError(f"frame = {frame!r} must be None (absolute goal), 'user' or 'tool'")
    R0 = rotation_matrix(start[3:], order)
    Rd = rotation_matrix(goal[3:], order)
    if frame == "user":
        p, R = start[:3] + goal[:3], Rd @ R0
    else:
        p, R = start[:3] + R0 @ goal[:3], R0 @ Rd
    angles = _angles_of(R, order, start[3:] + goal[3:])
    return np.concatenate([p, angles])


def _path(kind, q0, q1, via, blend, frame, order):
    """The path of a move: a line in pose space, a line with a slerp, or blended lines through
    the waypoints `via` ((K, 6) poses)."""
    if via is None:
        return (_PointPath if kind == "point" else _LinePath)(q0, q1, order)
    if kind != "point" or frame is not None:
        raise ValueError("waypoints (via) are blended in pose space: they need kind='point' "
                         "and an absolute goal (frame=None)")
    points = np.asarray(via, dtype=float)
    if points.ndim != 2 or points.shape[1] != 6 or not np.all(np.isfinite(points)):
        raise ValueError(f"via has shape {points.shape}: it must be (K, 6) finite poses")
    if not (isinstance(blend, numbers.Real) and 0 < blend <= 0.5):
        raise ValueError(f"blend = {blend!r} must be in (0, 0.5]: the share of the shorter "
                         "line next to a waypoint that its blend takes")
    return _BlendedPath(np.vstack([q0, points, q1]), float(blend), order)


def _topp_law(path, platform, attempt, limits, sample_time):
    """The speed and acceleration law's samples (s and its first three time derivatives; the
    third None) and its grid nodes' s, times and poses."""
    nodes, v, u, t_nodes, grid = _time_law(path, platform, GRID_SEGMENTS * 4 ** attempt,
                                           PLAN_MARGIN * 10 ** attempt, limits)
    t, s, s_rate, s_accel, scale = _sample(nodes, v, u, t_nodes, sample_time)
    return (t, s, s_rate, s_accel, None), (nodes, t_nodes * scale, grid)


def _jerk_law(path, platform, attempt, limits, jerk, sample_time):
    """The jerk-limited law's samples and its grid (moves_jerk): the legs' L', L'' from the
    library on the grid, L''' by second-order differences of L'' (the samples are then checked
    with the exact jerks)."""
    nodes = np.linspace(0.0, 1.0, GRID_SEGMENTS * 4 ** attempt + 1)
    shrink = 1.0 - PLAN_MARGIN * 10 ** attempt
    grid, Lp, Lpp, dq, omega = _leg_derivatives(platform, path, nodes, "right")
    Lppp = np.gradient(Lpp, nodes, axis=0, edge_order=2)
    speed, accel, tool_speed, angular_speed = limits
    cartesian = np.column_stack([np.linalg.norm(dq[:, :3], axis=1),
                                 np.linalg.norm(omega, axis=1)])
    bounds = np.concatenate([np.full(6, np.inf) if speed is None else speed,
                             [tool_speed or np.inf, angular_speed or np.inf]])
    peaks = LegPeaks(nodes, Lp, Lpp, Lppp, cartesian, shrink * bounds, shrink * accel,
                     shrink * jerk)
    curve, stretch = jerk_limited_law(peaks)
    t, s, s_rate, s_accel, s_jerk = sample_law(curve, stretch, sample_time)
    return (t, s, s_rate, s_accel, s_jerk), (nodes, np.interp(nodes, s, t), grid)


def _plan(platform, limited, path, q1, limits, jerk, sample_time, warn_condition, kind):
    """The move along path: the time law (jerk-limited when jerk is not None), its samples, and
    the checks of every sample against the geometric and the leg limits (the limited platform's
    leg classes; the plan made again on a finer grid with a wider margin if a leg speed,
    acceleration or jerk is exceeded; a leg force or motor current the planner does not plan
    for is refused at once)."""
    with_forces = bool(np.any(leg_limits_of(limited)["leg_force_max"] > 0))
    current_max = _per_leg(platform, "current_max") * (_per_leg(platform, "screw_lead") > 0)
    for attempt in range(3):
        if jerk is None:
            law, (nodes, t_nodes, grid) = _topp_law(path, platform, attempt, limits, sample_time)
        else:
            law, (nodes, t_nodes, grid) = _jerk_law(path, platform, attempt, limits, jerk,
                                                    sample_time)
        t, s, s_rate, s_accel, s_jerk = law
        q, dq, ddq, _ = path.derivatives(s)
        q[-1] = q1
        rate = dq * s_rate[:, None]
        acc = dq * s_accel[:, None] + ddq * (s_rate ** 2)[:, None]
        pose_jerk = None if s_jerk is None else (
            dq * s_jerk[:, None] + 3 * ddq * (s_rate * s_accel)[:, None]
            + path.third(q, dq, ddq) * (s_rate ** 3)[:, None])
        # One check of the samples gives their geometric and leg classes; the grid's poses
        # (between the samples) are checked for the geometric ones.
        check = limited.limits(q, rate, acc, pose_jerk, warn_condition=warn_condition)
        on_grid = platform.limits(grid, warn_condition=warn_condition)
        _first_limit(_joined(check, on_grid), np.vstack([q, grid]),
                     np.concatenate([s, nodes]), np.concatenate([t, t_nodes]))
        if with_forces:  # the forces need poses within the geometric limits
            check = limited.limits(q, rate, acc, pose_jerk, forces="massless",
                                   warn_condition=warn_condition)
        excess = _leg_excess(limited, check, t, s)
        if excess is None and np.any(current_max > 0):
            excess = _current_excess(platform, q, rate, acc, current_max, t, s)
        if excess is None:
            return Move(t, q, rate, acc, s, s_rate, s_accel, float(t[-1]), kind, pose_jerk)
        if excess.limit_class in ("leg_force", "current"):
            raise MoveError(f"{excess}: the move is planned on the legs' speed, acceleration "
                            "and jerk only; lower leg_accel_max (or leg_speed_max) until it "
                            "fits", excess.limit_class, excess.time, excess.s)
    raise excess


def _current_excess(platform, q, rate, acc, current_max, t, s):
    """MoveError naming the first sample whose motor current (the massless inverse's: the
    drive's inertia, the leg force through the screw, friction) exceeds current_max by more
    than CHECK_SLACK (relative); or None."""
    current = np.abs(platform.inverse(q, rate, acc, fidelity="massless").current)
    limit = np.where(current_max > 0, current_max, np.inf)
    over = current > limit * (1 + CHECK_SLACK)
    rows = np.flatnonzero(over.any(axis=1))
    if not rows.size:
        return None
    j = rows[0]
    k = int(np.argmax(over[j]))
    return MoveError(f"the planned move exceeds current_max at t = {t[j]:.6g} s "
                     f"(s = {s[j]:.6g}): leg {k + 1}'s motor takes {current[j, k]:.6g} A of "
                     f"{limit[k]:.6g} A", "current", float(t[j]), float(s[j]))


def _per_leg(platform, name) -> np.ndarray:
    """A per-leg parameter's 6 values on platform (its defaults where not given)."""
    return parameter_values(platform.params)[name]


def drive_leg_speed_max(platform) -> np.ndarray:
    """(6,) the leg speed [m/s] at which each leg's motor turns at motor_speed_max:
    motor_speed_max screw_lead / (2 pi gear_ratio); 0 (no limit) on a leg without a drive
    (screw_lead 0) or without motor_speed_max."""
    lead, speed = _per_leg(platform, "screw_lead"), _per_leg(platform, "motor_speed_max")
    gear = _per_leg(platform, "gear_ratio")
    return np.where((lead > 0) & (speed > 0), speed * lead / (2 * math.pi * gear), 0.0)


def move(platform, start, goal, kind: str = "point", *, leg_speed_max=None, leg_accel_max=None,
         leg_jerk_max=None, speed_max: Optional[float] = None,
         angular_speed_max: Optional[float] = None, sample_time: float = 0.001,
         frame: Optional[str] = None, via=None, blend: float = 0.25,
         warn_condition: Optional[float] = None) -> Move:
    """A rest-to-rest move of `platform` (a stewart.Platform) from pose `start` to `goal` (6
    values each: x, y, z [m], roll, pitch, yaw [rad] of the tool in the user frame), time-optimal
    under the limits along the whole path (docs/moves.md).

    kind: "point" (a straight line in pose space: every axis arrives together) or "line" (the
    tool point on a straight line, the orientation a slerp, one path parameter). frame: None
    (goal is a pose), "user" or "tool" (goal is a displacement: the position in that frame's
    axes, the angles a rotation about the tool point in that frame's axes). via: (K, 6)
    waypoints between start and goal (kind "point"), passed without stopping on quadratic
    blends that begin `blend` (0 to 0.5) of the shorter adjacent line before each waypoint.
    leg_speed_max [m/s], leg_accel_max [m/s^2] and leg_jerk_max [m/s^3]: the platform's
    parameters of those names unless given here (scalars or 6 values per leg; 0: no limit of
    that leg); an acceleration limit is required. With a jerk limit the time law is a
    jerk-limited S-curve of the path parameter (moves_jerk; waypoints are then refused, since
    their blends' curvature jumps). On a platform with drives the legs' speed is held within
    motor_speed_max too (drive_leg_speed_max; the tighter of the two per leg). speed_max
    [m/s]: the tool point's speed; angular_speed_max [rad/s]: the platform's angular speed.
    Every sample and the planning grid are checked with Platform.limits (warn_condition as
    there): MoveError names the class, time and s of the first limit the path crosses; and
    every sample's leg speed, acceleration and jerk (and, when the platform has leg_force_max,
    the massless inverse's forces; with drives and current_max, its motor currents) are
    checked with the library's leg classes."""
    if kind not in KINDS:
        raise ValueError(f"kind = {kind!r} must be 'point' or 'line'")
    if not (isinstance(sample_time, numbers.Real) and 0 < sample_time < math.inf):
        raise ValueError(f"sample_time = {sample_time!r} must be a finite number > 0 [s]")
    sample_time = float(sample_time)
    own = leg_limits_of(platform)
    leg_speed_max = own["leg_speed_max"] if leg_speed_max is None else leg_speed_max
    leg_accel_max = own["leg_accel_max"] if leg_accel_max is None else leg_accel_max
    leg_jerk_max = own["leg_jerk_max"] if leg_jerk_max is None else leg_jerk_max
    speed = _tighter(_limit_vector("leg_speed_max", leg_speed_max),
                     _limit_vector("motor_speed_max", drive_leg_speed_max(platform)))
    accel = _limit_vector("leg_accel_max", leg_accel_max)
    jerk = _limit_vector("leg_jerk_max", leg_jerk_max)
    if accel is None or not np.all(np.isfinite(accel)):
        raise ValueError("leg_accel_max is needed for every leg (the platform's parameter or "
                         "the keyword): without it a move from rest would reach its speed in no "
                         "time")
    if jerk is not None and via is not None:
        raise ValueError("waypoints (via) with leg_jerk_max: the blends' curvature jumps where "
                         "they meet the lines, so the legs' acceleration jumps there while "
                         "moving; plan the legs between waypoints as separate moves, or pass "
                         "leg_jerk_max=0 to plan without a jerk limit")
    limited = with_leg_limits(platform, leg_speed_max=_as_parameter(speed),
                              leg_accel_max=leg_accel_max, leg_jerk_max=_as_parameter(jerk))
    limits = (speed, accel, _speed_bound("speed_max", speed_max),
              _speed_bound("angular_speed_max", angular_speed_max))
    order = _rotation_order(platform)
    q0 = vector("start", start, 6)
    q1 = _goal_pose(q0, vector("goal", goal, 6), frame, order)
    ends = platform.limits(np.vstack([q0, q1]), warn_condition=warn_condition)
    for row, name in ((0, "start"), (1, "goal")):
        if ends.first[row] != 0:
            limit = class_name(ends.first[row])
            raise MoveError(f"the {name} pose {[q0, q1][row].tolist()} is beyond the {limit} "
                            "limit", limit, None, float(row))
    path = _path(kind, q0, q1, via, blend, frame, order)
    if via is None and np.array_equal(q0, q1):
        zero = np.zeros((1, 6))
        return Move(np.zeros(1), q0[None].copy(), zero, zero.copy(), np.zeros(1), np.zeros(1),
                    np.zeros(1), 0.0, kind)
    return _plan(platform, limited, path, q1, limits, jerk, sample_time, warn_condition, kind)


def _tighter(a: Optional[np.ndarray], b: Optional[np.ndarray]) -> Optional[np.ndarray]:
    """The smaller of two limits per leg (None: no limit)."""
    return b if a is None else a if b is None else np.minimum(a, b)


def _as_parameter(limit: Optional[np.ndarray]):
    """A limit vector (inf: none) as a leg-limit parameter (0: none)."""
    return 0.0 if limit is None else np.where(np.isfinite(limit), limit, 0.0)
