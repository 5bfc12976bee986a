"""Forward kinematics on numpy arrays: actuator lengths to platform poses (Platform.forward)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .errors import ParameterError

# stewart_status values (stewart.h) and bits (stewart_forward.h) a caller tests rows against.
STATUS_OK = 0
STATUS_OTHER_BRANCH = -8  #: STEWART_ERR_OTHER_BRANCH: the pose found is on another assembly mode
BRANCH_BITS = {"below_base": 1, "platform_cardan": 2, "flipped": 4, "jump": 8, "singularity": 16}
START_NAMES = ("home", "guess", "predictor", "last")


@dataclass
class ForwardSolution:
    """The result of Platform.forward for N rows of lengths: arrays of N rows.

    A row whose status is not 0 failed (see status_name and messages) and holds zeros, but for
    its warnings and branch bits; the rows after it are tracked from the last row that solved."""
    pose: np.ndarray        #: (N, 6) (x, y, z [m], roll, pitch, yaw [rad])
    pose_rate: np.ndarray   #: (N, 6) d/dt of the pose (zero unless rates were given)
    pose_accel: np.ndarray  #: (N, 6) d2/dt2 of the pose (zero unless accels were given)
    residual: np.ndarray    #: (N,) max |L_k(q) - L_k| at the last Newton iterate [m]
    condition: np.ndarray   #: (N,) leg Jacobian condition number
    jump: np.ndarray        #: (N,) largest platform-point move from the last pose [m]
    iterations: np.ndarray  #: (N,) Newton iterations
    warnings: np.ndarray    #: (N,) STEWART_WARN_* bits: 1 stroke, 2 near singular, 4 other branch
    branch: np.ndarray      #: (N,) STEWART_BRANCH_* bits (BRANCH_BITS): why not the working mode
    start: np.ndarray       #: (N,) where Newton started: 0 home, 1 guess, 2 predictor, 3 last
    status: np.ndarray      #: (N,) stewart_status per row: 0 solved, < 0 failed
    messages: dict[int, str] = field(default_factory=dict)  #: row -> message, first failing rows

    def __len__(self) -> int:
        return len(self.status)

    @property
    def ok(self) -> np.ndarray:
        """(N,) True where the row solved."""
        return self.status == STATUS_OK

    def status_name(self, row: int) -> str:
        """The library's name of row's status ("ok", "other assembly mode", ...)."""
        return _core.status_name(int(self.status[row]))


def empty_forward_solution(n: int) -> ForwardSolution:
    """A ForwardSolution of n rows, uninitialised (the batch writes every row)."""
    def ints():
        return np.empty(n, dtype=np.int32)
    return ForwardSolution(
        pose=np.empty((n, 6)), pose_rate=np.empty((n, 6)), pose_accel=np.empty((n, 6)),
        residual=np.empty(n), condition=np.empty(n), jump=np.empty(n), iterations=ints(),
        warnings=ints(), branch=ints(), start=ints(), status=ints())


def vector(name: str, value, size: int) -> np.ndarray:
    """value as a C-contiguous float64 array of size values, or ValueError naming it."""
    a = np.ascontiguousarray(value, dtype=np.float64).reshape(-1)
    if a.shape[0] != size:
        raise ValueError(f"{name} has {a.shape[0]} values: it must have {size}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} = {a.tolist()} has a value that is not finite")
    return a


def times(name: str, value, n: int, strictly_increasing: bool) -> np.ndarray:
    """value as (n,) float64 times, finite (and increasing if asked), or ValueError naming the
    first bad entry and its value."""
    t = np.ascontiguousarray(value, dtype=np.float64)
    if t.ndim != 1 or t.shape[0] != n:
        raise ValueError(f"{name} has shape {t.shape}: it must be ({n},), one time per row")
    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise ValueError(f"{name}[{bad[0]}] = {float(t[bad[0]])!r} is not finite")
    if strictly_increasing and n > 1:
        bad = np.flatnonzero(np.diff(t) <= 0)
        if bad.size:
            j = bad[0] + 1
            raise ValueError(f"{name}[{j}] = {float(t[j])!r} does not increase "
                             f"(t[{j - 1}] = {float(t[j - 1])!r})")
    return t


def run_forward(model, lengths: np.ndarray, rates: Optional[np.ndarray],
                accels: Optional[np.ndarray], t: Optional[np.ndarray], guess: Optional[np.ndarray],
                options: list, max_messages: int) -> ForwardSolution:
    """One forward batch into the library; bad options raise ParameterError."""
    n = lengths.shape[0]
    out = empty_forward_solution(n)
    try:
        _, _, _, kept = model.forward(
            lengths, rates, accels, t, guess, options, out.pose, out.pose_rate, out.pose_accel,
            out.residual, out.condition, out.jump, out.iterations, out.warnings, out.branch,
            out.start, out.status, min(max_messages, n))
    except ValueError as e:
        raise ParameterError(str(e)) from None
    out.messages = dict(kept)
    return out
