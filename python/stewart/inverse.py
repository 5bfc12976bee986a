"""Inverse kinematics and dynamics on numpy arrays: poses to actuator lengths and forces
(Platform.inverse)."""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .choices import Fidelity
from .errors import ParameterError
from .results import STATUS_COLUMN, RowStatus, new_table, place, result_of, table
from .slices import keeping_messages, run_in_slices

#: Rows per call into the library when rows are independent (kinematic and massless levels) and
#: at the full level (slower rows): Python handles signals (Ctrl-C) between calls, about every
#: 10 ms of work. One solver object runs every slice of a call, so slices do not change the numbers.
SLICE_ROWS = 8192
FULL_SLICE_ROWS = 512


@dataclass
class InverseSolution(RowStatus):
    """The result of Platform.inverse for N poses: arrays of N rows (legs in the library's order).

    A row whose status is not 0 failed (see status_name and messages) and holds zeros; the other
    rows are solved as if it were not there."""
    length: np.ndarray        #: (N, 6) actuator lengths L_k [m]
    length_rate: np.ndarray   #: (N, 6) dL_k/dt [m/s]
    length_accel: np.ndarray  #: (N, 6) d2L_k/dt2 [m/s^2]
    force: np.ndarray         #: (N, 6) actuator forces F_k [N], > 0 pushes the platform away
    condition: np.ndarray     #: (N,) leg Jacobian condition number (0 at the kinematic level)
    residual: np.ndarray      #: (N,) constraint residual after the solve [m]
    base_force: np.ndarray    #: (N, 3) force the legs put on the base, world frame [N]
    base_torque: np.ndarray   #: (N, 3) its torque about the world origin [N m]
    iterations: np.ndarray    #: (N,) Newton iterations (full level)
    warnings: np.ndarray      #: (N,) STEWART_WARN_* bits: 1 stroke limit, 2 near singular
    stroke_legs: np.ndarray   #: (N,) bit k set: leg k+1 is outside its stroke
    # Each leg's drive (docs/drives.md): 0 on a leg without one (screw_lead 0).
    motor_angle: np.ndarray   #: (N, 6) motor angle 2 pi N L_k / lead [rad]
    motor_speed: np.ndarray   #: (N, 6) motor speed [rad/s]
    motor_accel: np.ndarray   #: (N, 6) motor acceleration [rad/s^2]
    motor_torque: np.ndarray  #: (N, 6) motor torque: drive inertia, leg force, friction [N m]
    current: np.ndarray       #: (N, 6) motor current [A]
    current_rate: np.ndarray  #: (N, 6) dI/dt [A/s]: differences over t when t is given, else 0
    voltage: np.ndarray       #: (N, 6) R I + L dI/dt + k_t motor_speed [V]
    electrical_power: np.ndarray  #: (N, 6) voltage x current [W], < 0 regenerating
    motor_power: np.ndarray   #: (N, 6) motor_torque x motor_speed [W]
    current_max_legs: np.ndarray  #: (N,) bit k set: leg k+1's |current| > current_max
    voltage_max_legs: np.ndarray  #: (N,) bit k set: leg k+1's |voltage| > voltage_max
    motor_speed_max_legs: np.ndarray  #: (N,) bit k set: leg k+1's |motor_speed| > motor_speed_max
    status: np.ndarray        #: (N,) stewart_status per row: 0 solved, < 0 failed
    messages: dict[int, str] = field(default_factory=dict)  #: row -> message, first failing rows

    @property
    def power(self) -> np.ndarray:
        """(N,) actuator power sum_k F_k dL_k/dt [W], summed over legs in order 1..6."""
        p = self.force[:, 0] * self.length_rate[:, 0]
        for k in range(1, 6):
            p = p + self.force[:, k] * self.length_rate[:, k]
        return p


#: InverseSolution's arrays: the library's inverse output table, then status.
INVERSE_TABLE = table(_core.inverse_columns(), STATUS_COLUMN)
#: The drive columns: the table's last, after stroke_legs (stewart_outputs.h).
DRIVE_COLUMNS = tuple(c.name for c in INVERSE_TABLE.columns[
    [c.name for c in INVERSE_TABLE.columns].index("stroke_legs") + 1:] if c.name != "status")


def empty_inverse_solution(n: int, drives: bool = True) -> InverseSolution:
    """An InverseSolution of n rows, uninitialised (the batch writes every row); without drives
    the drive columns are zeros the batch is not asked to write (calloc'd pages: no work)."""
    return _new_solution(n, drives)[0]


def _new_solution(n: int, drives: bool) -> tuple:
    """A new InverseSolution of n rows, the block of the arrays the batch writes and where the
    binding finds them in it."""
    placement, core_placement = _placements(n, drives)
    arrays, block = new_table(placement)
    sol = result_of(InverseSolution, arrays, messages={})
    sol._drive_zeros = not drives
    return sol, block, core_placement


@functools.lru_cache(maxsize=64)
def _placements(n: int, drives: bool) -> tuple:
    """The placement of a result of n rows (without drives the drive columns zeroed), and the
    binding's copy of its offsets; kept for the sizes last used (a loop of equal calls places
    them once; they are never changed, so threads share them)."""
    placement = place(INVERSE_TABLE, n, frozenset() if drives else frozenset(DRIVE_COLUMNS))
    return placement, _core.inverse_placement(n, placement.written_bytes,
                                              list(placement.offsets))


def check_out(out: InverseSolution, n: int) -> None:
    """ValueError naming the array unless every array of out is one the library writes in place:
    n rows of the right width and dtype, C-contiguous, aligned, writeable. Anything else would be
    converted into a temporary copy and the results lost."""
    if not isinstance(out, InverseSolution):
        raise ValueError(f"out is a {type(out).__name__}: it must be an InverseSolution")
    rows = np.shape(out.status)[0] if np.ndim(out.status) else 0
    if rows != n:
        raise ValueError(f"out has {rows} rows but poses has {n}")
    for name, count, dtype in INVERSE_TABLE.columns:
        a = getattr(out, name)
        shape = (n, count) if count > 1 else (n,)
        if not isinstance(a, np.ndarray):
            raise ValueError(f"out.{name} is a {type(a).__name__}: it must be a numpy array {shape}")
        if a.dtype != dtype:
            raise ValueError(f"out.{name} has dtype {a.dtype}: it must be {dtype} "
                             "(results are written in place, never converted)")
        if a.shape != shape:
            raise ValueError(f"out.{name} has shape {a.shape}: it must be {shape}")
        flags = a.flags
        if not (flags.c_contiguous and flags.aligned):
            raise ValueError(f"out.{name} is not C-contiguous (Fortran order, strides or a "
                             "view): results are written in place, give a C-ordered array")
        if not flags.writeable:
            raise ValueError(f"out.{name} is read-only")


def run_inverse(model, q: np.ndarray, q_dot: Optional[np.ndarray], q_ddot: Optional[np.ndarray],
                level: Fidelity, options: list, max_messages: int,
                out: Optional[InverseSolution], t: Optional[np.ndarray] = None,
                q_dddot: Optional[np.ndarray] = None) -> InverseSolution:
    """The rows of q through the library into out (a new InverseSolution if None), in slices of
    SLICE_ROWS (FULL_SLICE_ROWS at the full level) on one solver, so that Ctrl-C stops the batch
    between slices: KeyboardInterrupt, whose rows_done says how many rows of out are solved
    (slices.run_in_slices). Bad options raise ParameterError. t: (N,) increasing times of the
    rows, or None (the rows are not a trajectory: current_rate 0); q_dddot: (N, 6) the poses'
    jerks instead (current_rate from the drive's law along the motion)."""
    n = q.shape[0]
    drives = _core.model_has_drives(model)
    if out is None:  # a new result: the binding finds its arrays in their block
        out, block, placement = _new_solution(n, drives)
        arrays = None
    else:
        check_out(out, n)
        if not drives and not getattr(out, "_drive_zeros", False):  # once per out reused
            for name in DRIVE_COLUMNS:
                getattr(out, name).fill(0)
        out._drive_zeros = not drives
        out.messages = {}
        # its arrays by name, of which the binding takes its table's columns (the drive columns
        # only for a model with drives)
        arrays = vars(out) if drives else {k: v for k, v in vars(out).items()
                                           if k not in DRIVE_COLUMNS}
    try:
        if arrays is None:
            run = _core.InverseRun(model, q, q_dot, q_ddot, options, block, placement)
        else:
            run = _core.InverseRun(model, q, q_dot, q_ddot, options, arrays, out.status)
    except ValueError as e:
        raise ParameterError(str(e)) from None
    run_in_slices("inverse", n, FULL_SLICE_ROWS if level == Fidelity.FULL else SLICE_ROWS,
                  keeping_messages(run, out.messages, max_messages), out)
    if t is not None:  # the rows are a trajectory: the currents' rates by differences over t
        run.current_rates(t)
    elif q_dddot is not None:  # the poses' jerks: the currents' rates from the drive's law
        try:
            run.current_rates_from_jerks(int(level), q_dddot)
        except ValueError as e:
            raise ParameterError(str(e)) from None
    return out
