"""Forward dynamics on numpy arrays: actuator forces to platform motion (Platform.simulate)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from . import _core
from .choices import Choice
from .errors import ParameterError
from .results import (STATUS_COLUMN, STATUS_NOT_RUN, STATUS_OK, Column, RowStatus, table,
                      table_arrays, table_outputs)
from .slices import run_in_slices

#: Communication points per call into the library: Python handles signals (Ctrl-C) between
#: calls. One plant runs every slice, so slices do not change the numbers.
SLICE_ROWS = 256


class Method(Choice):
    """The plant's integrators (stewart_plant_method); Method.of takes a member, its number or
    its name ("adams", "bdf", "erk", "erk5")."""
    ADAMS = 0  #: CVODE Adams-Moulton, fixed-point iteration
    BDF = 1    #: CVODE BDF, Newton with a dense difference-quotient Jacobian
    ERK = 2    #: ARKODE explicit Runge-Kutta 4(3) (the default)
    ERK5 = 3   #: ARKODE explicit Runge-Kutta 5(4), Dormand-Prince


class PlantInput(Choice):
    """What drives the plant's legs (stewart_plant_input_kind); PlantInput.of takes a member,
    its number or its name ("force", "current", "voltage")."""
    FORCE = 0    #: the leg's axial force [N]
    CURRENT = 1  #: the motor's current [A]
    VOLTAGE = 2  #: the motor's terminal voltage [V]

    @classmethod
    def _argument(cls) -> str:
        return "input"  # Platform.simulate's keyword, named in errors


def plant_input_kind(value) -> int:
    """The option value of a PlantInput given as a member, number or name."""
    return int(PlantInput.of(value))


@dataclass
class Simulation(RowStatus):
    """The result of Platform.simulate over N communication points: arrays of N rows.

    Row 0 is the start state. A step the plant refuses stops the run: that row gets its status,
    the rows after it STATUS_NOT_RUN, and all of them hold zeros; message says why."""
    t: np.ndarray            #: (N,) the communication points [s]
    pose: np.ndarray         #: (N, 6) (x, y, z [m], roll, pitch, yaw [rad])
    pose_rate: np.ndarray    #: (N, 6) d/dt of the six pose components
    length: np.ndarray       #: (N, 6) L_k [m]
    length_rate: np.ndarray  #: (N, 6) dL_k/dt [m/s]
    base_force: np.ndarray   #: (N, 3) force the moving bodies put on the base, world frame [N]
    base_torque: np.ndarray  #: (N, 3) its torque about the world origin [N m]
    warnings: np.ndarray     #: (N,) bits: 1 a leg outside the stroke, 8 a joint beyond its
    #: angle limit, 16 two legs closer than leg_diameter (docs/limits.md)
    stroke_legs: np.ndarray  #: (N,) bit k set: leg k+1 is outside its stroke
    force: np.ndarray        #: (N, 6) axial force F_k on the mechanism [N] (the input, or the drive's)
    current: np.ndarray      #: (N, 6) motor current [A] (0 with force input)
    voltage: np.ndarray      #: (N, 6) motor voltage [V]: the input, or R i + k_t omega (current input)
    motor_speed: np.ndarray  #: (N, 6) 2 pi N L_dot / lead [rad/s]
    motor_torque: np.ndarray  #: (N, 6) k_t i [N m]
    electrical_power: np.ndarray  #: (N, 6) voltage times current [W], < 0 regenerates
    current_max_legs: np.ndarray  #: (N,) bit k set: leg k+1 above its current_max
    voltage_max_legs: np.ndarray  #: (N,) bit k set: leg k+1 above its voltage_max
    motor_speed_max_legs: np.ndarray    #: (N,) bit k set: leg k+1 above its motor_speed_max
    steps: np.ndarray        #: (N,) internal integrator steps of the step into the row
    rhs_evaluations: np.ndarray       #: (N,) of the step into the row
    nonlinear_iterations: np.ndarray  #: (N,) of the step into the row
    error_test_failures: np.ndarray   #: (N,) of the step into the row
    status: np.ndarray       #: (N,) 0 ran, < 0 the stewart_status that stopped the run, 1 not run
    message: str = ""        #: why the run stopped ("" if every row ran)
    statistics: dict[str, float] = field(default_factory=dict)  #: the integrator's totals

    @property
    def completed(self) -> bool:
        """True if every row ran."""
        return bool(np.all(self.status == STATUS_OK))


#: Simulation's arrays: the library's plant output and step tables, then status and t.
PLANT_TABLE = table(_core.plant_columns(), STATUS_COLUMN, Column("t", 1, np.dtype(np.float64)))


def empty_simulation(t: np.ndarray) -> Simulation:
    """A Simulation over the communication points t (copied), uninitialised otherwise (the run
    writes every row)."""
    arrays = table_arrays(PLANT_TABLE, t.shape[0])
    arrays["t"][:] = t
    return Simulation(**arrays)


def run_simulate(model, t: np.ndarray, forces: np.ndarray, start: Optional[np.ndarray],
                 start_rate: Optional[np.ndarray], options: list) -> Simulation:
    """One plant run through the library in slices of SLICE_ROWS communication points, the plant
    going on from slice to slice, so that Ctrl-C stops the run between slices
    (slices.run_in_slices: a KeyboardInterrupt with rows_done and the partial result). Bad
    options raise ParameterError."""
    n = t.shape[0]
    out = empty_simulation(t)
    try:
        run = _core.PlantRun(
            model, t, forces, start, start_rate, options,
            table_outputs(PLANT_TABLE, out), out.status)
    except ValueError as e:
        raise ParameterError(str(e)) from None

    def run_rows(first: int, stop: int) -> bool:
        status, _, message = run.rows(first, stop)
        out.message = message
        out.statistics = dict(run.statistics())
        return status == STATUS_OK
    run_in_slices("simulate", n, SLICE_ROWS, run_rows, out)
    return out
