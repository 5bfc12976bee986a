#!/usr/bin/env python3
"""The Python API against the C batches it wraps, in one run (issue 22: the Python batch at
>= 90 % of the C batch's speed at every level).

Runs build/bench-batch (ns per row of stewart_inverse_batch at the three levels,
stewart_forward_batch tracking the kinematic lengths, stewart_plant_batch at both fidelities on the
full level's forces; the combined cue at 1 ms, the median of whole batches), then the same rows
through Platform.inverse, Platform.forward and Platform.simulate, timed alike, and prints ns per
row for both and the ratio C / Python (1.0: Python adds nothing; the goal is >= 0.9). bench-batch
writes into the same arrays every repeat; a Python call makes new ones (their first touch costs
page faults), so the inverse is also timed with out= (Platform.inverse's arrays reused), the like
of the C side. C and Python take turns, ROUNDS times, and each number is the median over the
rounds, so that a change of the shared machine's load between the two does not land on one side.
Writes the table, with the machine's load, to studies/bench/batches-results.md.

usage: studies/bench/batches.py [BUILD_DIR (build)] [ROWS (6000)] [ROUNDS (3)]
"""
import pathlib
import statistics
import subprocess
import sys
import time

import numpy as np

import stewart
from stewart import scenes
from stewart.inverse import empty_inverse_solution

ROOT = pathlib.Path(__file__).resolve().parents[2]
STEP = 1e-3  # [s] between rows, as bench-batch
# name in bench-batch's output -> repeats (as bench-batch's)
REPEATS = {"inverse kinematic": 51, "inverse massless": 51, "inverse full": 5,
           "forward tracking": 21, "plant massless": 11, "plant full": 3}


def median_ns_per_row(repeats, rows, call):
    times = []
    for _ in range(repeats):
        start = time.perf_counter_ns()
        call()
        times.append((time.perf_counter_ns() - start) / rows)
    return statistics.median(times)


def c_batches(build, rows):
    out = subprocess.run([build / "bench-batch", str(rows)], check=True, capture_output=True,
                         text=True).stdout
    result = {}
    for line in out.splitlines():
        if line.startswith("#") or not line.strip():
            continue
        name, value = line.rsplit(None, 1)
        result[name.strip()] = float(value)
    return result


def python_batches(rows):
    """The same rows through the Python API (the combined cue from scenes/combined.json, which
    bench-batch's combined_cue.hpp writes out)."""
    platform = stewart.Platform()
    t = np.arange(rows) * STEP
    q, qd, qdd = scenes.pose(scenes.load("combined", ROOT / "scenes"), t)
    result, reused = {}, {}
    out = empty_inverse_solution(rows)
    for level in ("kinematic", "massless", "full"):
        name = f"inverse {level}"
        result[name] = median_ns_per_row(
            REPEATS[name], rows, lambda: platform.inverse(q, qd, qdd, fidelity=level))
        reused[name] = median_ns_per_row(
            REPEATS[name], rows, lambda: platform.inverse(q, qd, qdd, fidelity=level, out=out))
    lengths = platform.inverse(q, fidelity="kinematic").length
    forces = platform.inverse(q, qd, qdd, fidelity="full").force
    result["forward tracking"] = median_ns_per_row(
        REPEATS["forward tracking"], rows, lambda: platform.forward(lengths, t=t))
    for fidelity in ("massless", "full"):
        name = f"plant {fidelity}"
        result[name] = median_ns_per_row(
            REPEATS[name], rows,
            lambda: platform.simulate(t, forces, fidelity=fidelity, start=q[0], start_rate=qd[0]))
    return result, reused


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build").resolve()
    rows = int(sys.argv[2]) if len(sys.argv) > 2 else 6000
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    if not (build / "bench-batch").exists():
        sys.exit(f"batches.py: {build}/bench-batch is missing: build first")
    load_before = pathlib.Path("/proc/loadavg").read_text().split()[:3]
    turns = [(c_batches(build, rows), *python_batches(rows)) for _ in range(rounds)]
    c, py, reused = ({name: statistics.median(turn[side][name] for turn in turns)
                      for name in turns[0][side]} for side in range(3))
    load_after = pathlib.Path("/proc/loadavg").read_text().split()[:3]
    lines = [
        "# The Python API against the C batches (studies/bench/batches.py)",
        "",
        f"{rows} rows of the combined cue at 1 ms; ns per row, the median of whole batches "
        f"(C and Python in turn, the median over {rounds} rounds); "
        f"load average before {' '.join(load_before)}, after {' '.join(load_after)}.",
        "",
        "| batch | C [ns/row] | Python [ns/row] | C / Python | Python, out= [ns/row] | C / Python, out= |",
        "|---|---|---|---|---|---|",
    ]
    for name in REPEATS:
        with_out = (f"{reused[name]:.1f} | {c[name] / reused[name]:.3f}" if name in reused
                    else "– | –")
        lines.append(f"| {name} | {c[name]:.1f} | {py[name]:.1f} | {c[name] / py[name]:.3f} | "
                     f"{with_out} |")
    text = "\n".join(lines) + "\n"
    (ROOT / "studies" / "bench" / "batches-results.md").write_text(text)
    print(text, end="")


if __name__ == "__main__":
    main()
