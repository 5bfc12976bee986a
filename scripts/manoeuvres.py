#!/usr/bin/env python3
"""The thesis' test manoeuvres (model.md §2) as pose CSVs with exact derivatives.

Each is a sinusoid at 5 rad/s over 12 s sampled every 0.1 s (121 rows): heave z = 0.5 + 0.04 sin 5t;
roll, pitch or yaw = (pi/18) sin 5t with z held at 0.5 m. The CSV has the header
t,x,y,z,roll,pitch,yaw,x_dot,...,yaw_dot,x_ddot,...,yaw_ddot that stewart-solve reads.

usage: manoeuvres.py {heave,roll,pitch,yaw} OUT.csv [--dt 0.1] [--duration 12] [--no-derivatives]
"""
import argparse
import math

POSE = ("x", "y", "z", "roll", "pitch", "yaw")
COMPONENT = {"heave": (2, 0.04), "roll": (3, math.pi / 18), "pitch": (4, math.pi / 18),
             "yaw": (5, math.pi / 18)}
OMEGA = 5.0
HOME_Z = 0.5


def header(derivatives=True):
    cols = ["t", *POSE]
    if derivatives:
        cols += [f"{p}_dot" for p in POSE] + [f"{p}_ddot" for p in POSE]
    return cols


def pose_row(name, t):
    """Pose, first and second derivative (three lists of six) of a manoeuvre at time t."""
    index, amplitude = COMPONENT[name]
    q, qd, qdd = [0.0] * 6, [0.0] * 6, [0.0] * 6
    q[2] = HOME_Z
    q[index] += amplitude * math.sin(OMEGA * t)
    qd[index] = amplitude * OMEGA * math.cos(OMEGA * t)
    qdd[index] = -amplitude * OMEGA ** 2 * math.sin(OMEGA * t)
    return q, qd, qdd


def times(dt=0.1, duration=12.0):
    n = int(round(duration / dt))
    return [i * dt for i in range(n + 1)]


def write_csv(name, path, dt=0.1, duration=12.0, derivatives=True):
    with open(path, "w") as f:
        f.write(",".join(header(derivatives)) + "\n")
        for t in times(dt, duration):
            q, qd, qdd = pose_row(name, t)
            values = [t, *q] + ([*qd, *qdd] if derivatives else [])
            f.write(",".join(repr(v) for v in values) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("manoeuvre", choices=sorted(COMPONENT))
    parser.add_argument("out")
    parser.add_argument("--dt", type=float, default=0.1)
    parser.add_argument("--duration", type=float, default=12.0)
    parser.add_argument("--no-derivatives", action="store_true",
                        help="pose columns only (stewart-solve then uses finite differences)")
    args = parser.parse_args()
    write_csv(args.manoeuvre, args.out, args.dt, args.duration, not args.no_derivatives)


if __name__ == "__main__":
    main()
