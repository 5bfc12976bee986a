"""Platform: one Stewart platform (the library's model), the façade of the three directions on
numpy arrays: inverse (inverse.py), forward (forward.py), simulate (simulate.py)."""
from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Optional, Union

import numpy as np

from . import _core
from .arrays import LEG_LAYOUT, POSE_LAYOUT, all_finite, rows6, times, vector
from .check import HomeCheck, check_home, text_units
from .choices import Fidelity
from .errors import ParameterError
from .forward import ForwardSolution, run_forward
from .inverse import InverseSolution, run_inverse
from .linearize import InverseJacobian, Linearization, run_linearize, run_linearize_inverse
from .limits import AxisRanges, LimitCheck
from .limits import check as check_limits
from .limits import ranges as limit_ranges
from .params import ParameterValue, option_values, parameter_assignments, read_platform_file
from .simulate import Method, Simulation, plant_input_kind, run_simulate


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
        self._file_units = ("", "")  # (length, angle) of the file read, for printing in them
        try:
            self._model = _core.Model(parameter_assignments(self._params))
        except ParameterError:
            raise
        except ValueError as e:
            raise ParameterError(str(e)) from None

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"], **params: ParameterValue) -> "Platform":
        """The platform of a platform file (docs/geometry.md: a JSON object of parameter names to
        numbers or lists, e.g. one of ``stewart.platform_files()``), with ``params`` changed on
        top of it. The library reads the file and checks every field against the parameter
        table: ParameterError names the file, the line and the field, and nothing is built from
        a file with any bad field. A parameter in ``params`` replaces the file's (whole, or the
        element it names: ``stroke_max=0.8``, ``stroke_max[2]=0.8``)."""
        merged: dict[str, ParameterValue] = dict(read_platform_file(path))
        for name, value in params.items():
            merged.pop(name, None)  # given again: placed after the file's, so it wins
            merged[name] = value
        platform = cls(**merged)
        platform._file_units = tuple(_core.platform_file_units(os.fsdecode(os.fspath(path))))
        return platform

    @property
    def params(self) -> Mapping[str, ParameterValue]:
        """The parameters given to the constructor (the rest are the thesis platform's)."""
        return dict(self._params)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self._params.items())
        return f"Platform({inner})"

    def __reduce__(self):
        return (_rebuild, (self._params, self._file_units))

    def inverse(self, poses, rates=None, accels=None,
                fidelity: Union[Fidelity, int, str] = Fidelity.MASSLESS, *,
                tolerance: Optional[float] = None, max_iterations: Optional[int] = None,
                modified_newton: Optional[bool] = None, warn_condition: Optional[float] = None,
                singular_condition: Optional[float] = None, max_messages: int = 100,
                out: Optional[InverseSolution] = None, t=None, jerks=None) -> InverseSolution:
        """Inverse kinematics and dynamics of N poses in one batch through the library.

        poses, rates, accels: (N, 6) arrays of (x, y, z [m], roll, pitch, yaw [rad]) and their
        first and second time derivatives (None: zero, i.e. the platform at rest). The rows are
        solved in order from a fresh start, as `stewart-solve` solves a CSV's rows (at the full
        level each pose starts from the previous solution), so the same call gives the same
        numbers bit for bit. A row that fails (non-finite value, unreachable or singular pose,
        no convergence) gets its status and, for the first max_messages failing rows, a message;
        the other rows are still solved. Bad options raise ParameterError. Options left None keep
        the library's defaults (stewart_options_default). out: an InverseSolution of as many rows
        to write into (its arrays are reused, which saves allocating and first-touching fresh
        memory in a loop of equal batches); it is returned. Its arrays must be the ones a new
        result has (dtype, shape, C order): any other raises ValueError naming it, since the
        library would write into a converted copy. Ctrl-C stops the batch within about a slice
        of rows (inverse.SLICE_ROWS, FULL_SLICE_ROWS at the full level): KeyboardInterrupt,
        with the rows solved so far valid in out (its rows_done says how many).

        With drives (screw_lead > 0, docs/drives.md) each row also gives the motors' angle,
        speed, torque, current, voltage and power. t: (N,) increasing times [s] of the rows
        when they are a trajectory: the currents' rates (current_rate) are then differences of
        the currents over t (central, second order; one-sided at the ends and beside a failed
        row), and the voltages include the winding's L dI/dt; None (the default): the rows are
        unrelated poses, current_rate 0. jerks: (N, 6) the poses' third time derivatives
        instead of t: current_rate is then the drive's law differentiated along each pose's own
        motion (the legs' jerks and the forces' rates from Platform.linearize_inverse's
        Jacobian; exact, about 20-40x a massless row's work), for poses that are not samples of
        one trajectory or whose jerk is known."""
        level = Fidelity.of(fidelity)
        q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
        n = q.shape[0]
        row_times = None if t is None else times("t", t, n)
        if t is not None and jerks is not None:
            raise ValueError("give t (differences along the rows) or jerks, not both")
        q_dddot = None if jerks is None else rows6("jerks", jerks, n, "poses", POSE_LAYOUT)
        q_dot = None if rates is None else rows6("rates", rates, n, "poses", POSE_LAYOUT)
        q_ddot = None if accels is None else rows6("accels", accels, n, "poses", POSE_LAYOUT)
        options = [("fidelity", float(level))]
        if (tolerance is not None or max_iterations is not None or modified_newton is not None
                or warn_condition is not None or singular_condition is not None):
            options += option_values(
                tolerance=tolerance, max_iterations=max_iterations,
                modified_newton=modified_newton, warn_condition=warn_condition,
                singular_condition=singular_condition)
        if max_messages < 0:
            raise ValueError(f"max_messages = {max_messages} must be >= 0")
        return run_inverse(self._model, q, q_dot, q_ddot, level, options, max_messages, out,
                           row_times, q_dddot)

    @property
    def reflected_mass(self) -> np.ndarray:
        """(6,) each leg's drive inertia seen on the leg's axis [kg]: (rotor_inertia +
        screw_inertia / N^2) (2 pi N / screw_lead)^2, N the gear ratio; 0 without a drive."""
        return np.array(_core.model_reflected_mass(self._model))

    def forward(self, lengths, rates=None, accels=None, guess=None, *, t=None, cold: bool = False,
                tolerance: Optional[float] = None, max_iterations: Optional[int] = None,
                warn_condition: Optional[float] = None,
                singular_condition: Optional[float] = None,
                max_messages: int = 100) -> ForwardSolution:
        """Forward kinematics of N rows of actuator lengths in one batch through the library.

        lengths, rates, accels: (N, 6) arrays of L_k [m] and their first and second time
        derivatives (None: not given; the pose rates and accelerations are then zero; accels
        need rates). t: (N,) increasing times [s] of the rows (None: no time, each row starts
        from the last solved pose without the rate predictor). The rows are tracked in order
        from a cold start, exactly as `stewart-solve --forward` tracks a CSV's rows: row 0 from
        guess (a pose of 6 values) or else the home pose, each later row from the last one
        solved, advanced by its rates to the row's time. A pose on another assembly mode than
        the working one is never returned: that row gets status STATUS_OTHER_BRANCH (-8) and
        its branch bits say why; a row of bad or unreachable lengths gets its status; the other
        rows are still solved. cold=True: the rows are not a trajectory (measured lengths of
        unrelated poses): each row is solved on its own from home, or from guess (one pose for
        every row, or (N, 6): a start per row), with the assembly-mode checks against home; t is then not taken. The first max_messages failing rows get a message. Bad options
        raise ParameterError; bad array shapes, a non-finite guess or a t that does not
        increase raise ValueError naming the argument and the value. Options left None keep the
        library's defaults (stewart_forward_options_default). Ctrl-C stops the batch within
        about a slice of rows (forward.SLICE_ROWS; the solver tracks on across slices):
        KeyboardInterrupt, whose result holds its first rows_done rows solved."""
        L = rows6("lengths", lengths, None, "lengths", LEG_LAYOUT)
        n = L.shape[0]
        L_dot = None if rates is None else rows6("rates", rates, n, "lengths", LEG_LAYOUT)
        L_ddot = None if accels is None else rows6("accels", accels, n, "lengths", LEG_LAYOUT)
        if L_ddot is not None and L_dot is None:
            raise ValueError("accels were given without rates: the pose accelerations need both")
        if cold:
            if t is not None:
                raise ValueError("t was given with cold=True: rows solved cold have no time")
            q0 = None if guess is None else np.ascontiguousarray(np.broadcast_to(
                rows6("guess", guess, None, "poses", POSE_LAYOUT), (n, 6))).ravel()
            if q0 is not None and not all_finite(q0):
                raise ValueError("guess has a value that is not finite")
        else:
            q0 = None if guess is None else vector("guess", guess, 6)
        time = None if t is None else times("t", t, n)
        if max_messages < 0:
            raise ValueError(f"max_messages = {max_messages} must be >= 0")
        options = []
        if (tolerance is not None or max_iterations is not None or warn_condition is not None
                or singular_condition is not None):
            options = option_values(tolerance=tolerance, max_iterations=max_iterations,
                                    warn_condition=warn_condition,
                                    singular_condition=singular_condition)
        return run_forward(self._model, L, L_dot, L_ddot, time, q0, options, max_messages, cold)

    def limits(self, poses, rates=None, accels=None, jerks=None, *, forces=None,
               warn_condition: Optional[float] = None) -> LimitCheck:
        """The limits a controller checks, for N poses ((N, 6) or one row of 6): per pose the
        first failing class (stroke, base joint angle, platform joint angle, leg interference,
        condition number above warn_condition; None: the inverse option's default, 1e3; software
        position limits axis_min, axis_max; then the legs' speed, acceleration, jerk and force
        against leg_speed_max, leg_accel_max, leg_jerk_max, leg_force_max) and the margin to
        every class [m, rad, rad, m, 1, m or rad, m/s, m/s^2, m/s^3, N] with the leg (axis)
        where it is, and each leg's own margins (docs/limits.md). The leg classes need data:
        rates, accels, jerks are the poses' first to third time derivatives ((N, 6) each;
        accels need rates, jerks accels); forces the legs' forces (N, 6) [N], or a fidelity
        ("massless", "full") to compute them with Platform.inverse from the poses, rates and
        accels (zero where not given). A class without its data or its limit has margin +inf.
        A non-finite value raises ValueError naming its row and component."""
        q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
        n = q.shape[0]
        derivatives = [None if v is None else rows6(name, v, n, "poses", POSE_LAYOUT)
                       for name, v in (("rates", rates), ("accels", accels), ("jerks", jerks))]
        if isinstance(forces, (str, Fidelity, int)) and not isinstance(forces, bool):
            legs = self.inverse(q, derivatives[0], derivatives[1], forces,
                                warn_condition=warn_condition)
            bad = np.flatnonzero(~legs.ok)
            if bad.size:
                raise ValueError(f"poses row {bad[0]}: the forces cannot be computed: "
                                 f"{legs.messages.get(bad[0], legs.status_name(bad[0]))}")
            forces = legs.force
        elif forces is not None:
            forces = rows6("forces", forces, n, "poses", LEG_LAYOUT)
        return check_limits(self._model, q, _warn_condition(warn_condition), *derivatives,
                            forces)

    def check(self, *, warn_condition: Optional[float] = None,
              units: Optional[str] = None) -> HomeCheck:
        """The check to run first on a new platform file: the home pose's leg lengths against
        the strokes, the margin to every limit class, the condition number, the axis ranges
        from home, whether home is a valid pose, and hints that name a likely entry mistake
        ("units", "swapped_legs", "frame"); print() it for the report of `stewart-solve
        --check` (docs/geometry.md). The report's numbers are SI; its text is in the units of
        the file read by from_file (its "units", else the unit its values are written in; m
        and deg where it states none), or in units ("mm,deg", either alone; as `--units`).
        ValueError names a word of units that is not a unit."""
        shown = text_units(self._file_units, units)
        return check_home(self._model, _warn_condition(warn_condition), shown)

    def axis_ranges(self, poses, *, warn_condition: Optional[float] = None,
                    details: bool = False) -> Union[np.ndarray, AxisRanges]:
        """For N poses ((N, 6) or one row of 6), the interval each axis (x, y, z [m], roll,
        pitch, yaw [rad]) can move over with the other five held, within every limit of
        Platform.limits, to 1e-6 inside the first limit met: an (N, 6, 2) array of [min, max]
        in the pose's own units. A pose beyond a limit gets [q_i, q_i]. details=True returns an
        AxisRanges with the class, leg and other leg met at each end as well. Errors as
        Platform.limits."""
        q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
        result = limit_ranges(self._model, q, _warn_condition(warn_condition))
        return result if details else result.ends

    def simulate(self, t, forces, fidelity: Union[Fidelity, int, str] = Fidelity.FULL,
                 start=None, start_rate=None, *,
                 method: Optional[Union[Method, int, str]] = None,
                 relative_tolerance: Optional[float] = None,
                 absolute_tolerance: Optional[float] = None,
                 max_internal_steps: Optional[int] = None,
                 fixed_steps: Optional[int] = None,
                 input: Optional[Union[int, str]] = None,
                 smoothing_speed: Optional[float] = None) -> Simulation:
        """Forward dynamics: the platform's motion under the actuator forces, in one batch.

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
        1e-12). fixed_steps = N (1..1000, explicit methods only) takes N equal steps per
        communication step without error control, a fixed amount of work per step (the
        latency-bound choice; docs/speed-accuracy.md says its accuracy). input: what the
        (N, 6) array `forces` carries per leg, "force" [N] (default), "current" [A] or "voltage"
        [V] (0, 1, 2): with a current or voltage every leg needs a drive (screw_lead,
        torque_constant; docs/forward-dynamics.md "Drives"), and the result's force, current,
        voltage, motor_speed, motor_torque and electrical_power say what the drives did.
        smoothing_speed [m/s]: the leg speed below which the drives' friction and screw losses
        fade out (default 1e-4). Ctrl-C stops the run within about a slice of communication points
        (simulate.SLICE_ROWS; the plant goes on across slices): KeyboardInterrupt, whose result
        holds its first rows_done rows run."""
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
        options += option_values(relative_tolerance=relative_tolerance,
                                 absolute_tolerance=absolute_tolerance,
                                 max_internal_steps=max_internal_steps,
                                 fixed_steps=fixed_steps,
                                 smoothing_speed=smoothing_speed)
        if input is not None:
            options.append(("input", float(plant_input_kind(input))))
        return run_simulate(self._model, time, F, q0, q0_dot, options)

    def linearize(self, pose, pose_rate=None, forces=None,
                  fidelity: Union[Fidelity, int, str] = Fidelity.FULL, input="force",
                  winding_current=None,
                  smoothing_speed: Optional[float] = None) -> Linearization:
        """The plant linearised at one operating point: A, B, C, D in the minimal coordinates
        x = (pose, pose rates), u = forces, y = (pose, pose rates, lengths, length rates), exact
        (automatic differentiation through the library's equations of motion, not finite
        differences). pose, pose_rate (None: at rest), forces (None: those that hold the pose at
        these rates without acceleration): 6 values each. With tool_frame and user_frame the
        pose, its rates and x are the tool's in the user frame, as every pose of the package.
        fidelity "massless" or "full". A pose
        the plant cannot take (a zero-length leg, a locked Cardan, pitch at +-90 degrees) raises
        ValueError with the library's message.

        input "current" or "voltage" (as Platform.simulate's; a drive on every leg): the plant
        driven by its motors, forces then holding the six currents [A] or voltages [V] (needed),
        u those and B by them; the drives' reflected inertia, screw efficiency, friction and end
        stops are in A and B (docs/drives.md). With voltage input and a winding_inductance the
        windings' currents are states 13-18 (winding_current: their values, 6, default 0;
        refused where they are no states); smoothing_speed as Platform.simulate's (refused with
        force input). Linearization.not_smooth_legs names the legs at a
        kink of the law (at rest with a lossy screw: the one-sided derivatives' mean)."""
        return run_linearize(self._model, pose, pose_rate, forces, fidelity, input,
                             winding_current, smoothing_speed)

    def linearize_inverse(self, pose, pose_rate=None, pose_accel=None,
                          fidelity: Union[Fidelity, int, str] = Fidelity.FULL) -> InverseJacobian:
        """The inverse side's Jacobian at one pose: lengths, their rates and accelerations, the
        forces of the fidelity and the base wrench, with their derivatives with respect to
        (q, q_dot, q_ddot) (InverseJacobian.jacobian, 30 x 18)."""
        return run_linearize_inverse(self._model, pose, pose_rate, pose_accel, fidelity)


def _warn_condition(value: Optional[float]) -> Optional[float]:
    """The condition limit of the limit check (None: the library's default), or
    ParameterError if it is not a number."""
    if value is None:
        return None
    pairs = option_values(warn_condition=value)
    if not 1.0 <= pairs[0][1] < float("inf"):
        raise ParameterError(f"warn_condition = {value!r} must be finite and >= 1")
    return pairs[0][1]


def _rebuild(params: dict, file_units: tuple = ("", "")) -> Platform:
    platform = Platform(**params)
    platform._file_units = file_units
    return platform
