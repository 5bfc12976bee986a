"""Motion cueing (docs/cueing.md): a vehicle's specific force and angular velocity in, the
platform's poses with their exact rates and accelerations out, within every limit of the machine,
through the library's cueing unit (stewart/stewart_cueing.h)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _core
from .arrays import rows3, times
from .params import parameters

#: The cueing algorithms, by name; the index is the library's `algorithm` option.
#: "classical": the classical washout with tilt coordination (Reid & Nahon 1985).
ALGORITHMS = ("classical",)
assert len(ALGORITHMS) == _core.CUEING_ALGORITHMS


@dataclass
class Cueing:
    """The platform's motion for N vehicle samples. t: (N,) [s]; pose, pose_rate, pose_accel:
    (N, 6) the pose as Platform.inverse takes it (x, y, z [m], roll, pitch, yaw [rad]: the tool
    in the user frame, home when the vehicle is at rest) and its exact time derivatives; scale:
    (N,) the limiter's scale of the excursion from home (1: the filter's cue unchanged); limited:
    (N,) True where the limiter scaled the cue down to keep the machine within its limits, or
    the output left the scaled cue to keep the legs' speed and acceleration limits; cut:
    (N,) True where the scale's smooth motion (limiter_rate, limiter_accel, limiter_lookahead)
    did not suffice and it was cut at once (a jolt: tune the cue down or look further ahead);
    tilt_limited: (N,) True where a tilt angle met tilt_max or tilt_rate_max; leg_limits: (N,)
    the legs' motion limits of the platform the pose breaks, checked when given: bit 1 a leg's
    speed beyond leg_speed_max, 2 its acceleration beyond leg_accel_max (both enforced: set only
    where the pose limits left no motion within them), 4 its force (massless legs) beyond
    leg_force_max (reported, not enforced) (LEG_SPEED, LEG_ACCEL, LEG_FORCE)."""
    t: np.ndarray
    pose: np.ndarray
    pose_rate: np.ndarray
    pose_accel: np.ndarray
    scale: np.ndarray
    limited: np.ndarray
    cut: np.ndarray
    tilt_limited: np.ndarray
    leg_limits: np.ndarray


#: Bits of Cueing.leg_limits.
LEG_SPEED, LEG_ACCEL, LEG_FORCE = 1, 2, 4


def option_names() -> tuple:
    """The names of the cueing options (keywords of stewart.cueing), in the library's order."""
    return tuple(o["name"] for o in _core.option_table("cueing"))


def cueing(platform, t, specific_force, angular_velocity, algorithm: str = "classical",
           **options) -> Cueing:
    """The platform motion that cues a vehicle's motion. t: (N,) increasing times [s];
    specific_force: (N, 3) [m/s2] and angular_velocity: (N, 3) [rad/s] in the vehicle frame at
    the pilot's head, x forward, y left, z up (at rest (0, 0, +g), g the platform's gravity);
    each sample is held over the interval that ends at it (zero-order hold; the first sample
    finds the filters at rest), and the outputs are at the samples. algorithm: one of ALGORITHMS.
    options: the cueing unit's options by name (option_names(); docs/cueing.md has each one's
    meaning, unit and default), e.g. surge_scale=0.4, translation_frequency=2.0,
    tilt_rate_max=np.radians(3), head_z=1.0 (the head in the machine's platform frame). Every
    output pose is within every limit of the platform (strokes, joint angles, interference,
    condition, axis_min/axis_max), and every leg's speed and acceleration within leg_speed_max
    and leg_accel_max when given (at the samples); the legs' force limit is reported only
    (leg_limits). Bad input raises ValueError naming it."""
    from .platform import Platform
    if not isinstance(platform, Platform):
        raise TypeError(f"platform must be a stewart.Platform (Platform.from_file(path) for a "
                        f"platform file), not {type(platform).__name__}")
    if algorithm not in ALGORITHMS:
        raise ValueError(f"algorithm = {algorithm!r} is not one of {ALGORITHMS}")
    if "algorithm" in options:
        raise ValueError("give the algorithm by name: algorithm='classical'")
    time = times("t", t, None)
    n = time.shape[0]
    force = rows3("specific_force", specific_force, n)
    omega = rows3("angular_velocity", angular_velocity, n)
    values = [("algorithm", float(ALGORITHMS.index(algorithm)))]
    platform_names = {p["name"] for p in parameters()} - set(option_names())
    for name, value in options.items():
        if name in platform_names:  # leg_speed_max, payload_mass ...: the machine's, not the cue's
            raise ValueError(f"{name} is a parameter of the platform, not a cueing option: "
                             f"give it to the platform (Platform.from_file(path, {name}=...))")
        try:
            values.append((name, float(value)))
        except (TypeError, ValueError):
            raise ValueError(f"option {name} = {value!r} is not a number") from None
    result = Cueing(time, np.zeros((n, 6)), np.zeros((n, 6)), np.zeros((n, 6)), np.zeros(n),
                    np.zeros(n, np.int32), np.zeros(n, np.int32), np.zeros(n, np.int32),
                    np.zeros(n, np.int32))
    _core.cueing_run(platform._model, time, force, omega, values, result.pose, result.pose_rate,
                     result.pose_accel, result.scale, result.limited, result.cut,
                     result.tilt_limited, result.leg_limits)
    result.limited = result.limited.astype(bool)
    result.cut = result.cut.astype(bool)
    result.tilt_limited = result.tilt_limited.astype(bool)
    return result
