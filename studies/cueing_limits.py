#!/usr/bin/env python3
"""Random vehicle signals through stewart.cueing on every shipped machine: the count of samples
beyond a stroke (the leg lengths |R b + p - a| in the tests' closed form,
tests/python/reference.py, against stroke_min and stroke_max) and beyond any limit (Platform.limits), with how often the limiter acted. With
--leg-limits, every machine also gets leg_speed_max = one stroke per second and leg_accel_max = ten
strokes per s^2, and the samples whose legs' rates or accelerations (closed form here, from the
poses with their rates and accelerations) pass them are counted (those the pose limits force are
reported in leg_limits; an unreported one fails the study), with the largest finite differences
of the lengths over the limits.

Each signal is 20 s at 100 Hz from stewart.random_vehicle: per axis a sum of 1 to 3 steps, ramps
and sines scaled to a random peak up to 2 g of specific force (about the rest value (0, 0, g))
and 200 deg/s of angular velocity, all scales 1 (the cue asks for far more than any machine has).
tests/python/test_cueing.py runs 20 signals per machine; this runs the rest.

usage: cueing_limits.py [--signals 1000] [--platform NAME ...] [--seed 37] [--leg-limits]
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
from reference import machine_lengths, rotation, shipped_machine  # noqa: E402  the tests' closed form


def angle_rate_matrices(q, qd):
    """E (omega = E angles') and its time derivative, (N, 3, 3), for R = Rz Ry Rx."""
    p, y, pd, yd = q[:, 4], q[:, 5], qd[:, 4], qd[:, 5]
    cp, sp, cy, sy = np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    zero, one = np.zeros_like(p), np.ones_like(p)
    E = np.stack([np.stack([cy * cp, -sy, zero], -1), np.stack([sy * cp, cy, zero], -1),
                  np.stack([-sp, zero, one], -1)], -2)
    E_dot = np.stack([np.stack([-sy * yd * cp - cy * sp * pd, -cy * yd, zero], -1),
                      np.stack([cy * yd * cp - sy * sp * pd, -sy * yd, zero], -1),
                      np.stack([-cp * pd, zero, zero], -1)], -2)
    return E, E_dot


def leg_motion(m, q, qd, qdd):
    """Lengths, rates and accelerations (N, 6): d = p + R b - a, p = user + q - R tool,
    L' = d.d' / L, L'' = (|d'|^2 - L'^2) / L + d.d'' / L."""
    a, b, _, _, tool, user = m
    R = np.stack([rotation(*angles) for angles in q[:, 3:]])
    E, E_dot = angle_rate_matrices(q, qd)
    omega = np.einsum("nij,nj->ni", E, qd[:, 3:])
    alpha = np.einsum("nij,nj->ni", E, qdd[:, 3:]) + np.einsum("nij,nj->ni", E_dot, qd[:, 3:])
    arm = np.einsum("nij,kj->nki", R, b) - np.einsum("nij,j->ni", R, tool)[:, None, :]
    d = user + q[:, None, :3] + arm - a
    w = omega[:, None, :].repeat(6, 1)
    v = qd[:, None, :3] + np.cross(w, arm)
    acc = (qdd[:, None, :3] + np.cross(alpha[:, None, :].repeat(6, 1), arm) +
           np.cross(w, np.cross(w, arm)))
    L = np.linalg.norm(d, axis=2)
    Ld = np.sum(d * v, axis=2) / L
    Ldd = (np.sum(v * v, axis=2) - Ld**2) / L + np.sum(d * acc, axis=2) / L
    return L, Ld, Ldd


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--signals", type=int, default=1000)
    ap.add_argument("--platform", nargs="*", help="platform file stems (default: every one)")
    ap.add_argument("--seed", type=int, default=37)
    ap.add_argument("--leg-limits", action="store_true",
                    help="set leg_speed_max and leg_accel_max on every machine and count the "
                         "samples beyond them")
    args = ap.parse_args()
    files = sorted((ROOT / "platforms").glob("*.json"))
    if args.platform:
        files = [f for f in files if f.stem in args.platform]
    t = np.arange(0, 20, 0.01)
    total_beyond = 0
    for path in files:
        m = shipped_machine(path)
        span = float(np.min(m[3] - m[2]))
        v_max, a_max = span, 10 * span
        legs = dict(leg_speed_max=v_max, leg_accel_max=a_max) if args.leg_limits else {}
        plat = stewart.Platform.from_file(path, **legs)
        rng = np.random.default_rng(args.seed)
        samples = beyond_stroke = beyond_any = limited = cut = beyond_legs = unreported = 0
        fd_speed = fd_accel = 0.0
        start = time.perf_counter()
        for _ in range(args.signals):
            f, w = stewart.random_vehicle(rng, t)
            r = stewart.cueing(plat, t, f, w, surge_scale=1, sway_scale=1, heave_scale=1,
                               roll_scale=1, pitch_scale=1, yaw_scale=1)
            if args.leg_limits:
                L, Ld, Ldd = leg_motion(m, r.pose, r.pose_rate, r.pose_accel)
                beyond = np.any((np.abs(Ld) > v_max) | (np.abs(Ldd) > a_max), axis=1)
                beyond_legs += int(np.sum(beyond))
                unreported += int(np.sum(beyond & ((r.leg_limits & 3) == 0)))
                fd_speed = max(fd_speed, np.max(np.abs(np.diff(L, axis=0))) / 0.01 / v_max)
                fd_accel = max(fd_accel, np.max(np.abs(np.diff(L, 2, axis=0))) / 1e-4 / a_max)
            else:
                L = machine_lengths(m, r.pose)
            beyond_stroke += int(np.sum(np.any((L < m[2]) | (L > m[3]), axis=1)))
            beyond_any += int(np.sum(~plat.limits(r.pose).within))
            limited += int(np.sum(r.limited))
            cut += int(np.sum(r.cut))
            samples += len(t)
        total_beyond += beyond_stroke + beyond_any + unreported
        legs_report = (f"; {beyond_legs} beyond a leg speed or acceleration limit ({unreported} "
                       f"of them not reported in leg_limits), finite "
                       f"differences of the lengths at most {fd_speed:.4f} of the speed limit and "
                       f"{fd_accel:.4f} of the acceleration limit" if args.leg_limits else "")
        print(f"{path.stem}: {args.signals} signals, {samples} samples: {beyond_stroke} beyond a "
              f"stroke, {beyond_any} beyond any limit{legs_report}; limiter acting on "
              f"{limited / samples:.1%}, cut at {cut} samples "
              f"({time.perf_counter() - start:.0f} s)", flush=True)
    print(f"total samples beyond a limit (and not reported): {total_beyond}")
    return 1 if total_beyond else 0


if __name__ == "__main__":
    raise SystemExit(main())
