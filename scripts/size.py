#!/usr/bin/env python3
"""Sizes a machine's motors over duty cycles (docs/drives.md): the inverse with the platform's
drives along each trajectory (a stewart-solve input CSV: t,x,y,z,roll,pitch,yaw, optionally the
rates x_dot..yaw_dot and accelerations x_ddot..yaw_ddot; absent ones are differences of the
samples), then per leg the peak and RMS torque, current and power, the peak motor speed, the
energy per cycle, the regenerated energy and the drive inertia's share of the torque. It prints
the largest of each over the trajectories and, with --plot, writes the torque-speed scatter with
the motor's limits over it. A platform without drives, a row that does not solve or an output
it cannot write: exit status 1 and the message.

usage: size.py --platform FILE.json [--fidelity kinematic|massless|full] [--plot OUT.png]
               [--csv OUT.csv] TRAJ.csv [TRAJ.csv ...]
"""
import argparse
import sys

import numpy as np

import stewart
from stewart.sizing import REPORT_FIELDS


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--platform", required=True, help="platform file with drives (JSON)")
    parser.add_argument("--fidelity", default="full", help="kinematic, massless or full")
    parser.add_argument("--plot", help="torque-speed scatter, PNG")
    parser.add_argument("--csv", help="every number per trajectory and leg, CSV")
    parser.add_argument("trajectories", nargs="+", help="pose trajectory CSV files")
    args = parser.parse_args(argv)
    try:
        platform = stewart.Platform.from_file(args.platform)
        report = stewart.sizing(platform, args.trajectories, args.fidelity, keep=bool(args.plot))
    except (ValueError, OSError) as e:
        print(f"size.py: {e}", file=sys.stderr)
        return 1
    print(report.summary())
    try:
        if args.csv:
            with open(args.csv, "w", encoding="utf-8") as f:
                f.write("trajectory,leg," + ",".join(REPORT_FIELDS) + "\n")
                for i, name in enumerate(report.names):
                    for k in range(6):
                        values = [float(getattr(report, n)[i, k]) for n in REPORT_FIELDS]
                        f.write(f"{name},{k + 1}," + ",".join(repr(v) for v in values) + "\n")
        if args.plot:
            report.plot(args.plot)
    except OSError as e:  # an output path that cannot be written: its name and why
        print(f"size.py: cannot write {e.filename}: {e.strerror}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
