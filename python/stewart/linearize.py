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

#: The order of the state x, input u and output y of Linearization.
STATES = ("x", "y", "z", "roll", "pitch", "yaw",
          "x_dot", "y_dot", "z_dot", "roll_dot", "pitch_dot", "yaw_dot")
INPUTS = tuple(f"F[{k}]" for k in range(1, 7))
OUTPUTS = STATES + tuple(f"L[{k}]" for k in range(1, 7)) + tuple(f"L_dot[{k}]" for k in range(1, 7))


@dataclass
class Linearization:
    """The plant at an operating point in minimal coordinates x = (pose, pose rates) (12),
    u = the leg forces (6), y = (pose, pose rates, lengths, length rates) (24):
    dx/dt ~= state_rate + A dx + B du, y ~= output + C dx + D du (D = 0)."""
    A: np.ndarray           #: (12, 12) df/dx
    B: np.ndarray           #: (12, 6) df/du
    C: np.ndarray           #: (24, 12) dg/dx
    D: np.ndarray           #: (24, 6) dg/du (zero)
    state_rate: np.ndarray  #: (12,) f(x, u) = (pose rates, pose accelerations)
    output: np.ndarray      #: (24,) g(x)
    warnings: int           #: bits: 1 a leg outside the stroke
    fidelity: Fidelity

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


def run_linearize(model, pose, pose_rate, forces, fidelity) -> Linearization:
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
