"""Platform: one Stewart platform (the library's model) and its batch solve on numpy arrays."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Optional, Union

import numpy as np

from . import _core
from .arrays import LEG_LAYOUT, POSE_LAYOUT, rows6, times, vector
from .choices import Choice
from .errors import ParameterError
from .forward import ForwardSolution, run_forward
from .params import ParameterValue, parameter_assignments
from .results import RowStatus
from .simulate import Method, Simulation, run_simulate


class Fidelity(Choice):
    """The library's fidelity levels (stewart_fidelity); Fidelity.of takes a member, its number
    or its name ("kinematic", "massless", "full")."""
    KINEMATIC = 0  #: lengths, rates, accelerations; forces zero
    MASSLESS = 1   #: plus forces, legs as massless two-force members
    FULL = 2       #: the 14-body constraint-and-multiplier model


@dataclass
class Solution(RowStatus):
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

    @property
    def power(self) -> np.ndarray:
        """(N,) actuator power sum_k F_k dL_k/dt [W], summed over legs in order 1..6."""
        p = self.force[:, 0] * self.length_rate[:, 0]
        for k in range(1, 6):
            p = p + self.force[:, k] * self.length_rate[:, k]
        return p


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
        q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
        n = q.shape[0]
        q_dot = None if rates is None else rows6("rates", rates, n, "poses", POSE_LAYOUT)
        q_ddot = None if accels is None else rows6("accels", accels, n, "poses", POSE_LAYOUT)
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

    def forward(self, lengths, rates=None, accels=None, guess=None, *, t=None,
                tolerance: Optional[float] = None, max_iterations: Optional[int] = None,
                warn_condition: Optional[float] = None,
                singular_condition: Optional[float] = None,
                max_messages: int = 100) -> ForwardSolution:
        """Forward kinematics of N rows of actuator lengths in one call into the library.

        lengths, rates, accels: (N, 6) arrays of L_k [m] and their first and second time
        derivatives (None: not given; the pose rates and accelerations are then zero; accels
        need rates). t: (N,) increasing times [s] of the rows (None: no time, each row starts
        from the last solved pose without the rate predictor). The rows are tracked in order
        from a cold start, exactly as `stewart-solve --forward` tracks a CSV's rows: row 0 from
        guess (a pose of 6 values) or else the home pose, each later row from the last one
        solved, advanced by its rates to the row's time. A pose on another assembly mode than
        the working one is never returned: that row gets status STATUS_OTHER_BRANCH (-8) and
        its branch bits say why; a row of bad or unreachable lengths gets its status; the other
        rows are still solved. The first max_messages failing rows get a message. Bad options
        raise ParameterError; bad array shapes, a non-finite guess or a t that does not
        increase raise ValueError naming the argument and the value. Options left None keep the
        library's defaults (stewart_forward_options_default)."""
        L = rows6("lengths", lengths, None, "lengths", LEG_LAYOUT)
        n = L.shape[0]
        L_dot = None if rates is None else rows6("rates", rates, n, "lengths", LEG_LAYOUT)
        L_ddot = None if accels is None else rows6("accels", accels, n, "lengths", LEG_LAYOUT)
        if L_ddot is not None and L_dot is None:
            raise ValueError("accels were given without rates: the pose accelerations need both")
        q0 = None if guess is None else vector("guess", guess, 6)
        time = None if t is None else times("t", t, n)
        if max_messages < 0:
            raise ValueError(f"max_messages = {max_messages} must be >= 0")
        options = [(name, float(value)) for name, value in (
            ("tolerance", tolerance), ("max_iterations", max_iterations),
            ("warn_condition", warn_condition), ("singular_condition", singular_condition))
            if value is not None]
        return run_forward(self._model, L, L_dot, L_ddot, time, q0, options, max_messages)

    def simulate(self, t, forces, fidelity: Union[Fidelity, int, str] = Fidelity.FULL,
                 start=None, start_rate=None, *,
                 method: Optional[Union[Method, int, str]] = None,
                 relative_tolerance: Optional[float] = None,
                 absolute_tolerance: Optional[float] = None,
                 max_internal_steps: Optional[int] = None) -> Simulation:
        """Forward dynamics: the platform's motion under the actuator forces, in one call.

        t: (N,) increasing communication points [s]; forces: (N, 6) F_k [N] at those points
        (F_k > 0 pushes platform and base apart), linear in time between rows. The plant starts
        at t[0] from start (a pose of 6 values; None: home) with start_rate (the pose rates;
        None: at rest), and steps from row to row exactly as `stewart-simulate` does on the same
        forces CSV. fidelity: "massless" (platform and payload alone) or "full" (the 14-body
        model). A step the plant refuses (a non-finite force, a leg of zero length, a locked
        Cardan, the integrator failing) stops the run: that row gets its status, the rows after
        it STATUS_NOT_RUN, and Simulation.message says why (a plant cannot skip a step). Bad
        options raise ParameterError; bad shapes, a non-finite start or a t that does not
        increase raise ValueError naming the argument and the value. Options left None keep
        the library's defaults (stewart_plant_options_default: ERK 4(3), rtol 1e-10, atol
        1e-12)."""
        level = Fidelity.of(fidelity)
        if level == Fidelity.KINEMATIC:
            raise ParameterError("fidelity = kinematic has no dynamics: simulate needs massless or full")
        time = times("t", t, None)
        n = time.shape[0]
        F = rows6("forces", forces, n, "t", LEG_LAYOUT)
        q0 = None if start is None else vector("start", start, 6)
        q0_dot = None if start_rate is None else vector("start_rate", start_rate, 6)
        options = [("fidelity", float(level))]
        if method is not None:
            options.append(("method", float(Method.of(method))))
        for name, value in (("relative_tolerance", relative_tolerance),
                            ("absolute_tolerance", absolute_tolerance),
                            ("max_internal_steps", max_internal_steps)):
            if value is not None:
                options.append((name, float(value)))
        return run_simulate(self._model, time, F, q0, q0_dot, options)


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
