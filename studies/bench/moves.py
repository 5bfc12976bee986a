#!/usr/bin/env python3
"""Planning cost of stewart.move (docs/moves.md): a straight-line move of about 10 s sampled at
1 kHz on the thesis platform, timed over ROUNDS plans; prints the median and the fastest wall time
per plan (and the CPU time, less sensitive to a shared machine's load), the move's duration and
its samples, without and with a leg jerk limit. The goal is <= 10 ms per plan.

usage: studies/bench/moves.py [ROUNDS (7)]
"""
import os
import statistics
import sys
import time

import stewart


def main() -> int:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    platform = stewart.Platform()
    start, goal = [0.0, 0.0, 0.5, 0.0, 0.0, 0.0], [0.08, -0.05, 0.53, 0.03, -0.02, 0.1]
    limits = dict(leg_speed_max=0.0083, leg_accel_max=0.02, sample_time=0.001)
    print(f"stewart {stewart.__version__}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f}")
    # The jerk limit: the speed and acceleration limits' law switches the acceleration within
    # 0.02 * 4 / 0.01 = 8 s of the jerk limit 0.01 m/s^3, so it binds.
    for label, extra in (("speed, acceleration", {}), ("and jerk", {"leg_jerk_max": 0.01})):
        times, cpu = [], []
        for _ in range(rounds):
            t0, c0 = time.perf_counter(), time.process_time()
            planned = stewart.move(platform, start, goal, "line", **limits, **extra)
            times.append(time.perf_counter() - t0)
            cpu.append(time.process_time() - c0)
        print(f"{label}: line move of {planned.duration:.3f} s, {len(planned.t)} samples at "
              f"1 kHz, {stewart.moves.GRID_SEGMENTS} grid segments: median "
              f"{1e3 * statistics.median(times):.1f} ms, fastest {1e3 * min(times):.1f} ms per "
              f"plan over {rounds} plans (CPU time: median {1e3 * statistics.median(cpu):.1f} ms)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
