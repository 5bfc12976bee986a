#!/usr/bin/env python3
"""Kinematic calibration's benchmark (issue 20's goals) and accuracy study.

Synthetic machines: the thesis platform with joint errors of 0.1-1 mm and length offsets of
0.1-2 mm (random signs), measured at poses chosen by stewart.calibration_poses with a tracker's
noise (10 um per axis, 20 urad per axis, 1 um per reading); identified by stewart.calibrate;
judged on 100 held-out poses inside the strokes by forward kinematics from the true machine's
exact readings (nominal model vs calibrated model). Prints:
  * goals: held-out pose error reduction (>= 99.5 %), scaled condition number (<= 100),
    identification time (<= 1 s), median over machines;
  * accuracy against the tracker's noise and against the number of poses.

usage: .venv/bin/python studies/calibration_study.py [--machines N] [--frames tool|user|both]
       .venv/bin/python studies/calibration_study.py --timing   (30 poses on every shipped machine)
"""
import argparse
import os
import time

# One BLAS thread unless told otherwise: on this shared 2-core machine OpenBLAS's threads make
# the small factorisations of an identification ten times slower (0.3 s against 0.03 s).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import numpy as np  # noqa: E402

import stewart  # noqa: E402
from stewart.calibration import forward_poses  # noqa: E402
from stewart.calibration_poses import random_poses_inside_limits  # noqa: E402
from stewart.calibration_model import nominal_geometry, platform_with, readings_and_jacobian  # noqa: E402


def true_platform(nominal, rng, frame_error):
    g = nominal_geometry(nominal)
    sign = lambda n: rng.choice([-1.0, 1.0], n)  # noqa: E731
    g["base_joint"] = g["base_joint"] + rng.uniform(1e-4, 1e-3, 18) * sign(18)
    g["platform_joint"] = g["platform_joint"] + rng.uniform(1e-4, 1e-3, 18) * sign(18)
    g["length_offset"] = g["length_offset"] + rng.uniform(1e-4, 2e-3, 6) * sign(6)
    g["tool_frame"] = g["tool_frame"] + rng.normal(0, frame_error, 6)
    g["user_frame"] = g["user_frame"] + rng.normal(0, frame_error, 6)
    return platform_with(nominal, g)


def tracker(poses, rng, position_noise, angle_noise):
    """Measured poses: position noise per axis, a small rotation (user frame) per axis."""
    out = poses.copy()
    out[:, :3] += rng.normal(0, position_noise, (len(poses), 3))
    for row in out:
        w = rng.normal(0, angle_noise, 3)
        R = _rotation(row[3:])
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        R = (np.eye(3) + W + W @ W / 2) @ R
        row[3:] = [np.arctan2(R[2, 1], R[2, 2]), -np.arcsin(R[2, 0]), np.arctan2(R[1, 0], R[0, 0])]
    return out


def _rotation(a):
    (cr, cp, cy), (sr, sp, sy) = np.cos(a), np.sin(a)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def pose_error(model, truth, poses):
    """RMS position [m] and rotation [rad] error of the poses model computes from the readings
    truth gives at poses."""
    readings, _ = readings_and_jacobian(truth, poses)
    found = forward_poses(model, readings, poses)
    position = np.linalg.norm(found[:, :3] - poses[:, :3], axis=1)
    rotation = [np.arccos(np.clip((np.trace(_rotation(f[3:]).T @ _rotation(q[3:])) - 1) / 2, -1, 1))
                for f, q in zip(found, poses)]
    return np.sqrt(np.mean(position ** 2)), np.sqrt(np.mean(np.square(rotation)))


def run(nominal, design, held_out, rng, frames, noise_scale=1.0):
    """One machine: (position reduction, rotation reduction, condition, seconds, position
    error after [m])."""
    truth = true_platform(nominal, rng, 2e-3 if frames else 0.0)
    readings, _ = readings_and_jacobian(truth, design)
    readings = readings + rng.normal(0, 1e-6 * noise_scale, readings.shape)
    measured = tracker(design, rng, 10e-6 * noise_scale, 20e-6 * noise_scale)
    started = time.perf_counter()
    result = stewart.calibrate(nominal, measured, readings, frames=frames,
                               position_noise=10e-6 * noise_scale,
                               angle_noise=20e-6 * noise_scale, reading_noise=1e-6 * noise_scale)
    seconds = time.perf_counter() - started
    before = pose_error(nominal, truth, held_out)
    after = pose_error(result.platform, truth, held_out)
    return (1 - after[0] / before[0], 1 - after[1] / before[1], result.condition, seconds,
            after[0], after[1], before[0], before[1])


def held_out_poses(nominal, count, seed):
    """Random poses inside the strokes (the candidates calibration_poses draws from)."""
    return random_poses_inside_limits(nominal, count, np.random.default_rng(seed))


def timing(repeats: int = 5):
    """Identification time for 30 poses (calibration_poses) on every shipped machine, with
    the default command line's choices: median and worst of `repeats` synthetic machines, wall
    time and the CPU time of this process (which a loaded machine does not inflate)."""
    import scipy.optimize  # noqa: F401  (imported once per process: timed apart)
    print(f"{'machine':<24}{'median [s]':>11}{'worst [s]':>10}{'CPU [s]':>8}{'pos. worst [um]':>16}"
          f"{'rot. worst [urad]':>18}{'set by prior':>13}")
    for name, path in stewart.platform_files().items():
        nominal = stewart.Platform.from_file(path)
        design = stewart.calibration_poses(nominal, 30)
        rng = np.random.default_rng(7)
        rows = []
        for _ in range(repeats):
            truth = true_platform(nominal, rng, 0.0)
            readings = readings_and_jacobian(truth, design)[0] + rng.normal(0, 1e-6, (30, 6))
            measured = tracker(design, rng, 10e-6, 20e-6)
            started, cpu = time.perf_counter(), time.process_time()
            result = stewart.calibrate(nominal, measured, readings)
            rows.append((time.perf_counter() - started, result.accuracy.position_worst,
                         result.accuracy.orientation_worst, result.undetermined,
                         time.process_time() - cpu))
        rows = np.array(rows)
        print(f"{name:<24}{np.median(rows[:, 0]):>11.3f}{rows[:, 0].max():>10.3f}"
              f"{np.median(rows[:, 4]):>8.3f}"
              f"{np.median(rows[:, 1]) * 1e6:>16.2f}{np.median(rows[:, 2]) * 1e6:>18.2f}"
              f"{int(np.median(rows[:, 3])):>13d}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--machines", type=int, default=10)
    parser.add_argument("--frames", choices=("tool", "user", "both"), default=None)
    parser.add_argument("--timing", action="store_true",
                        help="only the identification time on every shipped machine")
    args = parser.parse_args()
    if args.timing:
        print(f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']}")
        timing()
        return
    nominal = stewart.Platform()
    print(f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']}")
    started = time.perf_counter()
    import scipy.optimize  # noqa: F401  (calibrate imports it on first use: timed apart)
    print(f"first use of scipy.optimize (import): {time.perf_counter() - started:.2f} s")
    started = time.perf_counter()
    design = stewart.calibration_poses(nominal, 30, frames=args.frames)
    print(f"calibration_poses(30): {time.perf_counter() - started:.2f} s, scaled condition "
          f"{stewart.observability(nominal, design, frames=args.frames):.1f} "
          f"(30 random poses in the same box: "
          f"{stewart.observability(nominal, held_out_poses(nominal, 30, 99), frames=args.frames):.1f})")
    held_out = held_out_poses(nominal, 100, 12345)
    rng = np.random.default_rng(2026)

    rows = np.array([run(nominal, design, held_out, rng, args.frames)
                     for _ in range(args.machines)])
    median = np.median(rows, axis=0)
    print(f"\ngoals, 30 poses, tracker noise 10 um / 20 urad, frames {args.frames}, "
          f"{args.machines} machines (median; worst):")
    print(f"  held-out position error: {median[6] * 1e6:.1f} um -> {median[4] * 1e6:.2f} um, "
          f"reduction {median[0] * 100:.3f} % (worst {rows[:, 0].min() * 100:.3f} %; goal >= 99.5 %)")
    print(f"  held-out rotation error: {median[7] * 1e6:.1f} urad -> {median[5] * 1e6:.2f} urad, "
          f"reduction {median[1] * 100:.3f} % (worst {rows[:, 1].min() * 100:.3f} %)")
    print(f"  scaled condition number: {median[2]:.1f} (worst {rows[:, 2].max():.1f}; goal <= 100)")
    print(f"  identification time: {median[3]:.3f} s (worst {rows[:, 3].max():.3f} s; goal <= 1 s)")

    print("\naccuracy against the tracker's noise (30 poses; noise x 10 um / 20 urad / 1 um):")
    print(f"  {'noise x':>8} {'position after [um]':>20} {'rotation after [urad]':>22} {'reduction %':>12}")
    for scale in (0.1, 0.3, 1.0, 3.0, 10.0):
        r = np.median([run(nominal, design, held_out, rng, args.frames, scale)
                       for _ in range(max(3, args.machines // 2))], axis=0)
        print(f"  {scale:>8g} {r[4] * 1e6:>20.3f} {r[5] * 1e6:>22.3f} {r[0] * 100:>12.3f}")

    print("\naccuracy against the number of poses (calibration_poses(n), tracker noise x 1):")
    print(f"  {'poses':>6} {'condition':>10} {'position after [um]':>20} {'rotation after [urad]':>22} "
          f"{'reduction %':>12} {'time [s]':>9}")
    for n in (8, 10, 15, 20, 30, 50, 80):
        try:
            poses = stewart.calibration_poses(nominal, n, frames=args.frames)
            r = np.median([run(nominal, poses, held_out, rng, args.frames)
                           for _ in range(max(3, args.machines // 2))], axis=0)
        except ValueError as e:  # too few poses, or stewart.UnobservableError
            print(f"  {n:>6} unobservable: {str(e)[:60]}...")
            continue
        print(f"  {n:>6} {r[2]:>10.1f} {r[4] * 1e6:>20.3f} {r[5] * 1e6:>22.3f} {r[0] * 100:>12.3f} "
              f"{r[3]:>9.3f}")


if __name__ == "__main__":
    main()
