"""Forward kinematics on numpy arrays: actuator lengths to platform poses (Platform.forward)."""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .errors import ParameterError
from .results import STATUS_COLUMN, RowStatus, new_table, place, result_of, table
from .slices import keeping_messages, run_in_slices

# The status (stewart.h) and bits (stewart_forward.h) a caller tests rows against.
STATUS_OTHER_BRANCH = -8  #: STEWART_ERR_OTHER_BRANCH: the pose found is on another assembly mode
BRANCH_BITS = {"below_base": 1, "platform_cardan": 2, "flipped": 4, "jump": 8, "singularity": 16}
START_NAMES = ("home", "guess", "predictor", "last")
#: Rows per call into the library: Python handles signals (Ctrl-C) between calls, about every
#: 10 ms of work. One solver tracks through every slice, so slices do not change the numbers.
SLICE_ROWS = 2048


@dataclass
class ForwardSolution(RowStatus):
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
    stroke_legs: np.ndarray  #: (N,) bit k set: measured length k+1 is outside its stroke
    status: np.ndarray      #: (N,) stewart_status per row: 0 solved, < 0 failed
    messages: dict[int, str] = field(default_factory=dict)  #: row -> message, first failing rows

#: ForwardSolution's arrays: the library's forward output table, then status.
FORWARD_TABLE = table(_core.forward_columns(), STATUS_COLUMN)


def empty_forward_solution(n: int) -> ForwardSolution:
    """A ForwardSolution of n rows, uninitialised (the batch writes every row)."""
    return _new_solution(n)[0]


def _new_solution(n: int) -> tuple:
    """A new ForwardSolution of n rows, the block of its arrays and where the binding finds them
    in it."""
    placement, core_placement = _placements(n)
    arrays, block = new_table(placement)
    return result_of(ForwardSolution, arrays, messages={}), block, core_placement


@functools.lru_cache(maxsize=64)
def _placements(n: int) -> tuple:
    """The placement of a result of n rows and the binding's copy of its offsets; kept for the
    sizes last used (never changed, so threads share them)."""
    placement = place(FORWARD_TABLE, n)
    return placement, _core.forward_placement(n, placement.written_bytes, list(placement.offsets))


def run_forward(model, lengths: np.ndarray, rates: Optional[np.ndarray],
                accels: Optional[np.ndarray], t: Optional[np.ndarray], guess: Optional[np.ndarray],
                options: list, max_messages: int, cold: bool = False) -> ForwardSolution:
    """The rows of lengths through the library, tracked in order by one solver in slices of
    SLICE_ROWS, so that Ctrl-C stops the batch between slices (slices.run_in_slices: a
    KeyboardInterrupt with rows_done and the partial result); with cold, every row on its own
    (guess: None, or one start per row, flattened). Bad options raise ParameterError."""
    n = lengths.shape[0]
    out, block, placement = _new_solution(n)
    try:
        run = _core.ForwardRun(
            model, lengths, rates, accels, t, guess, cold, options, block, placement)
    except ValueError as e:
        raise ParameterError(str(e)) from None
    run_in_slices("forward", n, SLICE_ROWS,
                  keeping_messages(run, out.messages, max_messages), out)
    return out
