#!/usr/bin/env python3
"""Planning cost of stewart.move (docs/moves.md): a straight-line move of about 10 s sampled at
1 kHz on the thesis platform, timed over ROUNDS plans; prints the median and the fastest wall time
per plan (and the CPU time, less sensitive to a shared machine's load), the move's duration and
its samples. The goal is <= 10 ms per plan.

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
    times, cpu = [], []
    for _ in range(rounds):
        t0, c0 = time.perf_counter(), time.process_time()
        planned = stewart.move(platform, start, goal, "line", **limits)
        times.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    print(f"stewart {stewart.__version__}, {os.cpu_count()} cores; load average "
          f"{os.getloadavg()[0]:.2f}")
    print(f"line move of {planned.duration:.3f} s, {len(planned.t)} samples at 1 kHz, "
          f"{stewart.moves.GRID_SEGMENTS} grid segments: median {1e3 * statistics.median(times):.1f} ms, "
          f"fastest {1e3 * min(times):.1f} ms per plan over {rounds} plans (CPU time: median "
          f"{1e3 * statistics.median(cpu):.1f} ms)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
