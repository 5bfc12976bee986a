"""What the platform makes its occupant's head feel (docs/cueing.md, "Perception and scores"):
the specific force and angular velocity at a point fixed on the platform, in the platform's frame,
from the platform's poses with their rates and accelerations, the inputs a vehicle's motion gives
stewart.perception, so that the two can be compared.

With the platform frame's origin p, rotation R (platform axes to base axes), angular velocity w
and angular acceleration alpha in the base frame (w and alpha from the angle rates through the
rotation order's exact matrices), and r = R head the head's arm:

    a_head = p'' + alpha x r + w x (w x r),    f = R^T (a_head - g),    w_platform = R^T w

with g the platform's gravity (0, 0, -9.81 by default), so that a platform at rest reads
f = (0, 0, +|g|), as a vehicle at rest does.

>>> import numpy as np, stewart
>>> plat = stewart.Platform()
>>> felt = stewart.head_motion(plat, [0, 0, 0.5, 0, 0, 0], np.zeros(6), np.zeros(6))
>>> felt.specific_force.round(6).tolist(), felt.angular_velocity.tolist()
([[0.0, 0.0, 9.81]], [[0.0, 0.0, 0.0]])
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _core
from .arrays import POSE_LAYOUT, rows6, vector


class HeadMotion(NamedTuple):
    """The motion felt at the head, (N, 3) each, in the platform frame (x forward, y left, z up:
    the cueing unit's vehicle axes): specific_force [m/s2], (0, 0, +g) at rest, and
    angular_velocity [rad/s]. stewart.perception(t, *motion) takes it as it is."""
    specific_force: np.ndarray
    angular_velocity: np.ndarray


def _finite(name: str, a: np.ndarray) -> np.ndarray:
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        r, c = bad[0]
        raise ValueError(f"{name}[{r}, {c}] = {float(a[r, c])!r} is not finite")
    return a


def _z_down(platform) -> bool:
    from .calibration_model import parameter_value
    return bool(parameter_value(platform, "frame_convention")[0])


def head_motion(platform, pose, pose_rate, pose_accel, head=(0.0, 0.0, 0.0)) -> HeadMotion:
    """The specific force and angular velocity at the head, in the platform frame, for the
    platform's poses. pose, pose_rate, pose_accel: (N, 6) or (6,), as Platform.inverse takes them
    and stewart.cueing returns them (the tool in the user frame, angles in the platform's
    rotation_order, z down with frame_convention 1; rates and accelerations the time derivatives
    of those components). head: (3,) [m], the head's position in the platform frame from the
    platform frame's origin, as the cueing unit's options head_x, head_y, head_z take it (the
    machine's platform frame: z down with frame_convention 1). The output's axes are the z-up
    platform frame's: x forward, y left, z up, the vehicle's axes in stewart.cueing (for a z-down
    machine, its platform frame turned by 180 deg about x). Returns HeadMotion; ValueError names
    a bad argument."""
    from .platform import Platform
    if not isinstance(platform, Platform):
        raise TypeError(f"platform must be a stewart.Platform (Platform.from_file(path) for a "
                        f"platform file), not {type(platform).__name__}")
    q = _finite("pose", rows6("pose", pose, None, "", POSE_LAYOUT))
    n = q.shape[0]
    rates = _finite("pose_rate", rows6("pose_rate", pose_rate, n, "pose", POSE_LAYOUT))
    accels = _finite("pose_accel", rows6("pose_accel", pose_accel, n, "pose", POSE_LAYOUT))
    arm = vector("head", head, 3)
    if _z_down(platform):  # the solvers' z-up platform frame: turned by 180 deg about x
        arm = arm * np.array([1.0, -1.0, -1.0])
    position, velocity, acceleration, omega, alpha = (np.empty((n, 3)) for _ in range(5))
    rotation = np.empty((n, 9))
    _core.platform_motion(platform._model, q, rates, accels, position, velocity, acceleration,
                          rotation, omega, alpha)
    R = rotation.reshape(n, 3, 3)
    r = R @ arm
    gravity = np.array(_core.model_gravity(platform._model))
    to_platform = np.transpose(R, (0, 2, 1))
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below, by row
        a_head = acceleration + np.cross(alpha, r) + np.cross(omega, np.cross(omega, r))
        force = np.einsum("nij,nj->ni", to_platform, a_head - gravity)
        angular = np.einsum("nij,nj->ni", to_platform, omega)
    if not (np.all(np.isfinite(force)) and np.all(np.isfinite(angular))):
        row = int(np.argwhere(~(np.isfinite(force).all(1) & np.isfinite(angular).all(1)))[0, 0])
        raise ValueError(f"row {row}: the head's motion overflows; the pose's rates or "
                         "accelerations are too large")
    return HeadMotion(force, angular)
