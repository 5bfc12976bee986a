"""Platform: one Stewart platform (the library's model) and its batch solve on numpy arrays."""
from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Optional, Union

import numpy as np

from . import _core
from .errors import ParameterError
from .params import ParameterValue, parameter_assignments


class Fidelity(enum.IntEnum):
    """The library's fidelity levels (stewart_fidelity)."""
    KINEMATIC = 0  #: lengths, rates, accelerations; forces zero
    MASSLESS = 1   #: plus forces, legs as massless two-force members
    FULL = 2       #: the 14-body constraint-and-multiplier model

    @classmethod
    def of(cls, value: Union["Fidelity", int, str]) -> "Fidelity":
        """A Fidelity from itself, its number or its name ("kinematic", "massless", "full")."""
        if isinstance(value, str):
            try:
                return cls[value.upper()]
            except KeyError:
                raise ParameterError(f"fidelity = {value!r} must be kinematic, massless or full") from None
        try:
            return cls(int(value))
        except ValueError:
            raise ParameterError(f"fidelity = {value!r} must be 0 (kinematic), 1 (massless) or 2 (full)") from None


# stewart_status values (stewart.h).
STATUS_OK = 0


@dataclass
class Solution:
    """The result of Platform.solve for N poses: arrays of N rows (legs in the library's order).

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
    status: np.ndarray        #: (N,) stewart_status per row: 0 solved, < 0 failed
    messages: dict[int, str] = field(default_factory=dict)  #: row -> message, first failing rows

    def __len__(self) -> int:
        return len(self.status)

    @property
    def ok(self) -> np.ndarray:
        """(N,) True where the row solved."""
        return self.status == STATUS_OK

    @property
    def power(self) -> np.ndarray:
        """(N,) actuator power sum_k F_k dL_k/dt [W], summed over legs in order 1..6."""
        p = self.force[:, 0] * self.length_rate[:, 0]
        for k in range(1, 6):
            p = p + self.force[:, k] * self.length_rate[:, k]
        return p

    def status_name(self, row: int) -> str:
        """The library's name of row's status ("ok", "unreachable pose", ...)."""
        return _core.status_name(int(self.status[row]))


def _rows(name: str, value, n: Optional[int]) -> np.ndarray:
    """value as a C-contiguous float64 (n, 6) array; a single pose of 6 values is one row."""
    a = np.ascontiguousarray(value, dtype=np.float64)
    if a.ndim == 1 and a.shape[0] == 6:
        a = a.reshape(1, 6)
    if a.ndim != 2 or a.shape[1] != 6:
        raise ValueError(f"{name} has shape {a.shape}: it must be (N, 6), (x, y, z, roll, pitch, yaw) per row")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name} has {a.shape[0]} rows but poses has {n}")
    return a


class Platform:
    """A Stewart platform: the thesis platform with the given parameters changed.

    Parameters are the FMU's names in SI units, scalars by name and arrays as sequences counted
    in leg order, e.g. ``Platform(payload_mass=50, payload_com=[0, 0, 0.1])``. A bad name or value
    raises ParameterError with the library's message (it names the parameter and the value; a
    typo gets the nearest name). A Platform is immutable; it can be pickled (Dask) and used from
    several threads (solves on one Platform take turns; use one Platform per thread for
    parallelism)."""

    def __init__(self, **params: ParameterValue) -> None:
        self._params: dict[str, ParameterValue] = dict(params)
        try:
            self._model = _core.Model(parameter_assignments(self._params))
        except ParameterError:
            raise
        except ValueError as e:
            raise ParameterError(str(e)) from None

    @property
    def params(self) -> Mapping[str, ParameterValue]:
        """The parameters given to the constructor (the rest are the thesis platform's)."""
        return dict(self._params)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self._params.items())
        return f"Platform({inner})"

    def __reduce__(self):
        return (_rebuild, (self._params,))

    def solve(self, poses, rates=None, accels=None,
              fidelity: Union[Fidelity, int, str] = Fidelity.MASSLESS, *,
              tolerance: Optional[float] = None, max_iterations: Optional[int] = None,
              modified_newton: Optional[bool] = None, warn_condition: Optional[float] = None,
              singular_condition: Optional[float] = None, max_messages: int = 100,
              out: Optional[Solution] = None) -> Solution:
        """Inverse kinematics and dynamics of N poses in one call into the library.

        poses, rates, accels: (N, 6) arrays of (x, y, z [m], roll, pitch, yaw [rad]) and their
        first and second time derivatives (None: zero, i.e. the platform at rest). The rows are
        solved in order from a fresh start, as `stewart-solve` solves a CSV's rows (at the full
        level each pose starts from the previous solution), so the same call gives the same
        numbers bit for bit. A row that fails (non-finite value, unreachable or singular pose,
        no convergence) gets its status and, for the first max_messages failing rows, a message;
        the other rows are still solved. Bad options raise ParameterError. Options left None keep
        the library's defaults (stewart_options_default). out: a Solution of as many rows to
        write into (its arrays are reused, which saves allocating and first-touching fresh
        memory in a loop of equal batches); it is returned."""
        level = Fidelity.of(fidelity)
        q = _rows("poses", poses, None)
        n = q.shape[0]
        q_dot = None if rates is None else _rows("rates", rates, n)
        q_ddot = None if accels is None else _rows("accels", accels, n)
        options = [("fidelity", float(level))]
        for name, value in (("tolerance", tolerance), ("max_iterations", max_iterations),
                            ("modified_newton", modified_newton),
                            ("warn_condition", warn_condition),
                            ("singular_condition", singular_condition)):
            if value is not None:
                options.append((name, float(value)))
        if max_messages < 0:
            raise ValueError(f"max_messages = {max_messages} must be >= 0")
        if out is not None and len(out) != n:
            raise ValueError(f"out has {len(out)} rows but poses has {n}")
        out = out if out is not None else _empty_solution(n)
        try:
            _, _, _, kept = self._model.solve(
                q, q_dot, q_ddot, options, out.length, out.length_rate, out.length_accel,
                out.force, out.condition, out.residual, out.base_force, out.base_torque,
                out.iterations, out.warnings, out.status, min(max_messages, n))
        except ValueError as e:
            raise ParameterError(str(e)) from None
        out.messages = dict(kept)
        return out


def _empty_solution(n: int) -> Solution:
    """A Solution of n rows, uninitialised (the batch writes every row)."""
    return Solution(
        length=np.empty((n, 6)), length_rate=np.empty((n, 6)), length_accel=np.empty((n, 6)),
        force=np.empty((n, 6)), condition=np.empty(n), residual=np.empty(n),
        base_force=np.empty((n, 3)), base_torque=np.empty((n, 3)),
        iterations=np.empty(n, dtype=np.int32), warnings=np.empty(n, dtype=np.int32),
        status=np.empty(n, dtype=np.int32))


def _rebuild(params: dict) -> Platform:
    return Platform(**params)
