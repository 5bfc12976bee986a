"""Linearisation on numpy arrays (Platform.linearize, Platform.linearize_inverse): the plant's
A, B, C, D at an operating point and the inverse side's Jacobian, exact (automatic
differentiation through the library's equations of motion, stewart_linearize.h)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _core
from .choices import Fidelity
from .errors import ParameterError
from .simulate import PlantInput

#: The order of the state x, input u and output y of Linearization.
STATES = ("x", "y", "z", "roll", "pitch", "yaw",
          "x_dot", "y_dot", "z_dot", "roll_dot", "pitch_dot", "yaw_dot")
INPUTS = tuple(f"F[{k}]" for k in range(1, 7))
OUTPUTS = STATES + tuple(f"L[{k}]" for k in range(1, 7)) + tuple(f"L_dot[{k}]" for k in range(1, 7))
#: The inputs with current or voltage input, and the windings' current states (voltage input
#: with a winding_inductance > 0).
CURRENT_INPUTS = tuple(f"current[{k}]" for k in range(1, 7))
VOLTAGE_INPUTS = tuple(f"voltage[{k}]" for k in range(1, 7))
WINDING_STATES = tuple(f"winding_current[{k}]" for k in range(1, 7))


@dataclass
class Linearization:
    """The plant at an operating point in minimal coordinates x = (pose, pose rates) (12),
    u = the leg forces (6), y = (pose, pose rates, lengths, length rates) (24):
    dx/dt ~= state_rate + A dx + B du, y ~= output + C dx + D du (D = 0). Driven by the motors
    (input current or voltage) u is the currents or voltages, and with voltage input and a
    winding inductance x gains the windings' currents (18): `states` and `inputs` name them."""
    A: np.ndarray           #: (12, 12) df/dx
    B: np.ndarray           #: (12, 6) df/du
    C: np.ndarray           #: (24, 12) dg/dx
    D: np.ndarray           #: (24, 6) dg/du (zero)
    state_rate: np.ndarray  #: (12,) f(x, u) = (pose rates, pose accelerations)
    output: np.ndarray      #: (24,) g(x)
    warnings: int           #: bits: 1 a leg outside the stroke, 32 a kink (not_smooth_legs)
    fidelity: Fidelity
    input: PlantInput = PlantInput.FORCE  #: what u carries: forces, currents or voltages
    leg_force: np.ndarray = None  #: (6,) the drives' forces on the mechanism (driven input) [N]
    not_smooth_legs: int = 0  #: bit k: leg k+1's terms are the mean of one-sided derivatives

    states = STATES
    inputs = INPUTS
    outputs = OUTPUTS


@dataclass
class InverseJacobian:
    """The inverse side at a pose (q, q_dot, q_ddot): lengths, their rates and accelerations,
    the forces of the fidelity, the base wrench, and d(L, L_dot, L_ddot, F, base_force,
    base_torque)/d(q, q_dot, q_ddot) (30 x 18)."""
    length: np.ndarray        #: (6,) [m]
    length_rate: np.ndarray   #: (6,) [m/s]
    length_accel: np.ndarray  #: (6,) [m/s2]
    force: np.ndarray         #: (6,) [N]
    base_force: np.ndarray    #: (3,) force the moving bodies put on the base, world [N]
    base_torque: np.ndarray   #: (3,) its torque about the world origin [N m]
    jacobian: np.ndarray      #: (30, 18) rows L, L_dot, L_ddot, F, base_force, base_torque;
    #: columns q, q_dot, q_ddot
    warnings: int
    fidelity: Fidelity


def _six(name: str, value) -> list[float]:
    if value is None:
        return [0.0] * 6
    a = np.asarray(value, dtype=float).reshape(-1)
    if a.shape != (6,):
        raise ValueError(f"{name} must hold 6 values, not {np.asarray(value).shape}")
    values = a.tolist()
    if not all(map(math.isfinite, values)):
        i = int(np.flatnonzero(~np.isfinite(a))[0])
        raise ValueError(f"{name}[{i}] = {a[i]} must be finite")
    return values


def _level(fidelity) -> Fidelity:
    level = Fidelity.of(fidelity)
    if level == Fidelity.KINEMATIC:
        raise ParameterError("fidelity = kinematic has no dynamics: linearize needs massless or full")
    return level


def run_linearize_inverse(model, pose, pose_rate, pose_accel, fidelity) -> InverseJacobian:
    level = _level(fidelity)
    q, q_dot, q_ddot = _six("pose", pose), _six("pose_rate", pose_rate), _six("pose_accel", pose_accel)
    # L, L_dot, L_ddot, F, base force, base torque, jacobian: the library writes them in place
    arrays = [np.empty(n) for n in (6, 6, 6, 6, 3, 3, (30, 18))]
    status, message, warnings = _core.linearize_inverse(model, int(level), q, q_dot, q_ddot, *arrays)
    if status != 0:
        raise ValueError(message)
    return InverseJacobian(*arrays, warnings, level)


def run_linearize_driven(model, pose, pose_rate, inputs, fidelity, kind, winding_current,
                         smoothing_speed) -> Linearization:
    level = _level(fidelity)
    if inputs is None:
        raise ValueError(f"linearize with input = {kind.name.lower()} needs the inputs (6 values)")
    q, q_dot = _six("pose", pose), _six("pose_rate", pose_rate)
    arrays = [np.empty(shape) for shape in ((18, 18), (18, 6), (24, 18), (24, 6), 18, 24)]
    A, B, C, D, rate, output = arrays
    leg_force = np.empty(6)
    speed = None if smoothing_speed is None else float(smoothing_speed)
    status, message, warnings, states, not_smooth = _core.linearize_driven(
        model, int(level), int(kind), speed, q, q_dot, _six("inputs", inputs),
        _six("winding_current", winding_current), rate, output, A, B, C, D, leg_force)
    if status != 0:
        raise ParameterError(message) if status == -2 else ValueError(message)
    n = states
    lin = Linearization(A[:n, :n].copy(), B[:n].copy(), C[:, :n].copy(), D, rate[:n].copy(),
                        output, warnings, level, kind, leg_force, not_smooth)
    lin.states = STATES + (WINDING_STATES if n == 18 else ())
    lin.inputs = CURRENT_INPUTS if kind == PlantInput.CURRENT else VOLTAGE_INPUTS
    return lin


def run_linearize(model, pose, pose_rate, forces, fidelity, input="force", winding_current=None,
                  smoothing_speed=None) -> Linearization:
    kind = PlantInput.of(input)
    if kind != PlantInput.FORCE:
        return run_linearize_driven(model, pose, pose_rate, forces, fidelity, kind,
                                    winding_current, smoothing_speed)
    level = _level(fidelity)
    q, q_dot = _six("pose", pose), _six("pose_rate", pose_rate)
    if forces is None:  # the forces that hold the pose (at these rates, without acceleration)
        forces = run_linearize_inverse(model, q, q_dot, None, level).force
    # A, B, C, D, state rate, output: the library writes them in place
    arrays = [np.empty(shape) for shape in ((12, 12), (12, 6), (24, 12), (24, 6), 12, 24)]
    A, B, C, D, rate, output = arrays
    status, message, warnings = _core.linearize_plant(
        model, int(level), q, q_dot, _six("forces", forces), rate, output, A, B, C, D)
    if status != 0:
        raise ValueError(message)
    return Linearization(*arrays, warnings, level)
