#!/usr/bin/env python3
"""Plans a rest-to-rest move with stewart.move and writes it as a stewart-solve input CSV:
t,x,y,z,roll,pitch,yaw, their rates x_dot..yaw_dot and accelerations x_ddot..yaw_ddot (SI: m,
rad, s). A move that cannot be made exits with status 1 and the message naming the limit, the
time and the path parameter (docs/moves.md).

usage: move.py [--platform FILE.json] --start x,y,z,roll,pitch,yaw --goal x,y,z,roll,pitch,yaw
               [--line | --via x,y,z,roll,pitch,yaw ... [--blend F]] [--frame user|tool]
               [--leg-accel-max A] [--leg-speed-max V] [--leg-jerk-max J]
               [--speed-max V] [--angular-speed-max W] [--sample-time DT] -o MOVE.csv
"""
import argparse
import sys

import numpy as np

import stewart

AXES = ("x", "y", "z", "roll", "pitch", "yaw")


def pose(text: str):
    """Six comma-separated numbers (the C locale's decimal point, whatever the user's locale)."""
    parts = text.split(",")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not six comma-separated numbers") from None
    if len(values) != 6:
        raise argparse.ArgumentTypeError(f"{text!r} has {len(values)} values: it needs 6 "
                                         "(x,y,z [m],roll,pitch,yaw [rad])")
    return values


def limit(text: str):
    """One number, or six comma-separated numbers (one per leg)."""
    try:
        values = [float(p) for p in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number or 6 numbers") from None
    if len(values) not in (1, 6):
        raise argparse.ArgumentTypeError(f"{text!r} has {len(values)} values: give 1 or 6")
    return values[0] if len(values) == 1 else values


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--platform", help="platform file (JSON); default the thesis platform")
    ap.add_argument("--start", type=pose, required=True)
    ap.add_argument("--goal", type=pose, required=True,
                    help="the goal pose, or with --frame the displacement")
    ap.add_argument("--line", action="store_true",
                    help="straight line of the tool point with a slerp (default: point to point)")
    ap.add_argument("--via", type=pose, action="append",
                    help="a waypoint passed on a blend (repeat for more; point-to-point only)")
    ap.add_argument("--blend", type=float, default=0.25,
                    help="share of the shorter line next to a waypoint its blend takes (0, 0.5]")
    ap.add_argument("--frame", choices=("user", "tool"),
                    help="the goal is a displacement in the user or the tool frame")
    ap.add_argument("--leg-speed-max", type=limit,
                    help="[m/s], 1 or 6 values; default the platform's leg_speed_max")
    ap.add_argument("--leg-accel-max", type=limit,
                    help="[m/s^2], 1 or 6 values; default the platform's leg_accel_max (needed "
                         "from the one or the other)")
    ap.add_argument("--leg-jerk-max", type=limit,
                    help="[m/s^3], 1 or 6 values; default the platform's leg_jerk_max (0: none)")
    ap.add_argument("--speed-max", type=float, help="tool point speed [m/s]")
    ap.add_argument("--angular-speed-max", type=float, help="angular speed [rad/s]")
    ap.add_argument("--sample-time", type=float, default=0.001, help="[s], default 0.001")
    ap.add_argument("-o", "--output", required=True, help="the CSV to write")
    args = ap.parse_args(argv)
    try:
        platform = (stewart.Platform.from_file(args.platform) if args.platform
                    else stewart.Platform())
        planned = stewart.move(platform, args.start, args.goal, "line" if args.line else "point",
                               leg_speed_max=args.leg_speed_max, leg_accel_max=args.leg_accel_max,
                               leg_jerk_max=args.leg_jerk_max,
                               speed_max=args.speed_max, angular_speed_max=args.angular_speed_max,
                               sample_time=args.sample_time, frame=args.frame, via=args.via,
                               blend=args.blend)
    except (ValueError, OSError) as e:
        print(f"move.py: {e}", file=sys.stderr)
        return 1
    header = (["t"] + list(AXES) + [f"{a}_dot" for a in AXES] + [f"{a}_ddot" for a in AXES])
    table = np.column_stack([planned.t, planned.pose, planned.pose_rate, planned.pose_accel])
    np.savetxt(args.output, table, delimiter=",", header=",".join(header), comments="",
               fmt="%.17g")
    print(f"move.py: {planned.kind} move of {planned.duration:.6g} s, {len(planned.t)} rows "
          f"-> {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
