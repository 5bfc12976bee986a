#!/usr/bin/env python3
"""Benchmark (not a test) of the Python package and the Dask sweeps; prints and writes FILE.

usage: bench_python.py [FILE] [--build BUILD_DIR] [--skip-sweeps] [--sweeps KIND ...] [--pairs N]
       bench_python.py --calls [--rounds N] [--against DIR] [--build BUILD_DIR]

--calls: the cost of a one-row call (Platform.inverse at each fidelity, forward, limits,
linearize, linearize_inverse) along the combined cue (scenes/combined.json's formula, as
build/bench-calls and bench-linearize run it), CPU time per call (the median of blocks of calls,
each in a fresh process per round), against the library's own cost of the same call from those
C benchmarks (the full level's inverse and forward on a reset solver, bench-calls
inverse-full-fresh and forward-fresh, as the binding's kept solvers are reset when taken; forward
from the previous pose as its guess): the difference is what the binding and the package add. --against DIR: an
installed package `stewart` in DIR (e.g. a copy of an earlier build's site-packages/stewart)
measured in rounds alternating with this one (the machine may be shared: alternating spreads
its load over both), medians of the rounds printed side by side.

1. Batch throughput of stewart.Platform.inverse per fidelity on a batch of 12001 poses (the yaw
   manoeuvre that build/bench-closed-form and build/bench-full time), median of repeated calls,
   against those C benchmarks run in the same invocation.
2. Sweeps through scripts/sweep.py's engine on a LocalCluster of 1 and 2 workers, in 10 chunks
   of about 1 s of work each (docs/sweeps.md: chunks of >= 1 s keep Dask's overhead at a few
   percent; 10 share out evenly on 1 or 2 workers): an envelope of 840 cases (about 1e6 poses)
   at the full level and a 3200 x 3200 workspace slice (1.02e7 poses) at the massless level; wall time
   from the first submission to the last result (cluster start-up apart), the workers' own time
   (solving, building the table, writing its Parquet file), Dask's overhead
   (1 - workers' time / (wall x workers)), the speed-up, and the workers' CPU time over the wall
   time (how many cores they really had: on a shared machine, fewer than the workers), the median
   chunk's CPU time (it grows when the workers contend for something) and the load average at
   the start of each sweep, and the CPU time of each worker's first chunk (the slowest of them:
   it faults in the worker's arrays). Each sweep starts after os.sync(), so that no earlier
   sweep's files are written back during it, and its OUT_DIR is deleted once measured (sweep()).
   --pairs N: N pairs of sweeps (1 worker, then 2) of each kind, one after the other, each
   pair's speed-up and their median (the machine may be shared: one pair says little);
   --sweeps workspace: only the workspace map (with --skip-batches: no C benchmarks, no batches).
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import stewart
from stewart import scenes
from stewart.sweeps import run

ROOT = pathlib.Path(__file__).resolve().parents[1]


def yaw_batch(n):
    """The yaw scene (scenes/yaw.json) at n times over 12 s: pose, rates, accelerations."""
    return scenes.pose(scenes.load("yaw", ROOT / "scenes"), np.linspace(0.0, 12.0, n))


def python_ns_per_pose(level, n, repeats):
    """Median ns per pose of inverse() with fresh result arrays, and writing into one reused
    InverseSolution (out=), calls of both kinds interleaved."""
    platform = stewart.Platform()
    q, qd, qdd = yaw_batch(n)
    reused = platform.inverse(q, qd, qdd, fidelity=level)
    fresh_times, reused_times = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        sol = platform.inverse(q, qd, qdd, fidelity=level)
        fresh_times.append(time.perf_counter() - start)
        start = time.perf_counter()
        platform.inverse(q, qd, qdd, fidelity=level, out=reused)
        reused_times.append(time.perf_counter() - start)
        assert sol.ok.all() and reused.ok.all()
    return [statistics.median(t) / n * 1e9 for t in (fresh_times, reused_times)]


def c_ns_per_pose(build):
    out = subprocess.run([str(build / "bench-closed-form")], capture_output=True, text=True,
                         check=True).stdout
    full = subprocess.run([str(build / "bench-full")], capture_output=True, text=True, check=True).stdout
    kin = float(re.search(r"kinematic:\s+([\d.]+) ns", out).group(1))
    mass = float(re.search(r"massless:\s+([\d.]+) ns", out).group(1))
    # stewart_solve's full level starts from the closed-form guess: the first block of bench-full.
    full_us = float(re.search(r"closed-form initial guess.*?block LU \(ours\):\s+([\d.]+) us", full, re.S).group(1))
    return {"kinematic": kin, "massless": mass, "full": full_us * 1e3}


CUE_MEAN = np.array([0, 0, 0.5, 0, 0, 0])
CUE_AMPLITUDE = np.array([0.05, 0.04, 0.03, 0.10, 0.08, 0.15])
CUE_FREQUENCY = np.array([3.0, 2.0, 4.0, 2.5, 3.5, 1.5])
CUE_PHASE = np.array([0.1, 0.7, 0.3, 1.1, 0.4, 0.9])


def combined_cue(t):
    """csrc/bench/combined_cue.hpp's cue at times t: (q, q_dot, q_ddot), rows of 6."""
    arg = CUE_FREQUENCY * np.asarray(t)[:, None] + CUE_PHASE
    return (CUE_MEAN + CUE_AMPLITUDE * np.sin(arg), CUE_AMPLITUDE * CUE_FREQUENCY * np.cos(arg),
            -CUE_AMPLITUDE * CUE_FREQUENCY ** 2 * np.sin(arg))


def one_row_calls(poses=1000):
    """(name, call(i)) of each one-row call, at pose i of the cue at 1 kHz: the C benchmarks'."""
    platform = stewart.Platform()
    q, qd, qdd = combined_cue(np.arange(poses + 1) * 1e-3)
    legs = platform.inverse(q, qd, qdd, fidelity="kinematic")
    force = platform.inverse(q, qd, qdd, fidelity="full").force
    L, Ld, Ldd = legs.length, legs.length_rate, legs.length_accel
    calls = [(f"inverse {level}",
              lambda i, level=level: platform.inverse(q[i], qd[i], qdd[i], fidelity=level))
             for level in ("kinematic", "massless", "full")]
    # forward from the last pose, as a tracking solver starts a row from the row before
    calls.append(("forward", lambda i: platform.forward(L[i + 1], Ld[i + 1], Ldd[i + 1], guess=q[i])))
    calls.append(("limits", lambda i: platform.limits(q[i])))
    calls.append(("linearize full", lambda i: platform.linearize(q[i], qd[i], force[i], fidelity="full")))
    calls.append(("linearize_inverse full",
                  lambda i: platform.linearize_inverse(q[i], qd[i], qdd[i], fidelity="full")))
    return calls


def calls_worker(poses=1000, blocks=15):
    """Prints {name: median ns per call} as JSON: per call kind, blocks of `poses` calls (one per
    cue pose), CPU time of the thread per block."""
    result = {}
    for name, call in one_row_calls(poses):
        for i in range(min(poses, 200)):  # warm: kept solvers made, caches filled
            call(i)
        per_call = []
        for _ in range(blocks):
            start = time.thread_time_ns()
            for i in range(poses):
                call(i)
            per_call.append((time.thread_time_ns() - start) / poses)
        result[name] = statistics.median(per_call)
    print(json.dumps(result))


def c_call_ns(build):
    """The library's own cost (median ns) of each one-row call, from the C benchmarks."""
    def run(*args):
        return subprocess.run([str(build / args[0]), *args[1:]], capture_output=True, text=True,
                              check=True).stdout
    ns = {}
    # A one-row call's solver is reset first (the binding's kept solvers are): the "-fresh" rows
    # time that, forward from the previous pose as its guess, as one_row_calls calls it.
    for level, row in (("kinematic", "inverse-kinematic"), ("massless", "inverse-massless"),
                       ("full", "inverse-full-fresh")):
        out = run("bench-calls", row, "20000")
        ns[f"inverse {level}"] = float(re.search(r"median ([\d.]+) ns", out).group(1))
    out = run("bench-calls", "forward-fresh", "20000")
    ns["forward"] = float(re.search(r"median ([\d.]+) ns", out).group(1))
    out = run("bench-limits", "2000")
    ns["limits"] = 1e3 * float(re.search(r"check\s+median\s+([\d.]+) us", out).group(1))
    out = run("bench-linearize")
    ns["linearize full"] = float(re.search(r"plant-full\s+median ([\d.]+) ns", out).group(1))
    ns["linearize_inverse full"] = float(re.search(r"inverse-full\s+median ([\d.]+) ns", out).group(1))
    return ns


def calls_report(args):
    """--calls: rounds of one worker process per package (alternating which goes first), the
    medians printed against the C costs."""
    sides = [("this", None)] + ([("against", args.against)] if args.against else [])
    rounds = {name: [] for name, _ in sides}
    for r in range(args.rounds):
        for name, path in (sides if r % 2 == 0 else sides[::-1]):
            env = dict(os.environ)
            if path:
                env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(path), env.get("PYTHONPATH")]))
            out = subprocess.run([sys.executable, __file__, "--calls-worker"], env=env,
                                 capture_output=True, text=True, check=True).stdout
            rounds[name].append(json.loads(out))
    c = c_call_ns(pathlib.Path(args.build))
    lines = [f"one-row calls, CPU us per call, median of {args.rounds} rounds (load average "
             f"{os.getloadavg()[0]:.2f}); C: the library's call alone (bench-calls, bench-limits, "
             "bench-linearize)"]
    head = f"  {'call':24s} {'C':>8s} {'python':>8s} {'over C':>8s}"
    if args.against:
        head += f" {'against':>8s} {'over C':>8s}"
    lines.append(head)
    for name in c:
        us = {side: statistics.median(r[name] for r in rounds[side]) / 1e3 for side in rounds}
        line = f"  {name:24s} {c[name] / 1e3:8.2f} {us['this']:8.2f} {us['this'] - c[name] / 1e3:8.2f}"
        if args.against:
            line += f" {us['against']:8.2f} {us['against'] - c[name] / 1e3:8.2f}"
        lines.append(line)
    return lines


def sweep(spec, workers, tmp):
    """One sweep, timed, then merged, its size taken and its OUT_DIR deleted. Deleting it
    matters on the 2-core VM of the 2026-12-02 runs (docs/sweeps.md): while an earlier sweep's
    files (a workspace map's 3 GB of chunks and merged results) stayed in the page cache, every
    chunk's Parquet write took 4 times the system time (0.5 s instead of 0.12 s a chunk): the
    page cache grew into memory the host had taken back. The sweep run second, always the one on
    2 workers, paid for it."""
    path = pathlib.Path(tmp) / f"spec-{spec['kind']}-{workers}.json"
    path.write_text(json.dumps(spec))
    out = pathlib.Path(tmp) / f"out-{spec['kind']}-{workers}"
    # The previous sweep's files are written back to disk now, not by the kernel's flusher
    # threads during this sweep.
    os.sync()
    load = os.getloadavg()[0]
    start = time.perf_counter()
    summary = run(path, out, ROOT / "scenes", workers=workers, progress=False, log=lambda m: None)
    total = time.perf_counter() - start
    compute = sum(c["seconds"] + c.get("write_seconds", 0.0) for c in summary["computed"])
    cpu = sum(c["cpu_seconds"] for c in summary["computed"])
    poses = sum(c["poses"] for c in summary["computed"])
    cases = sum(c["cases"] for c in summary["computed"])
    wall = summary["wall_seconds"]
    size = sum(f.stat().st_size for f in out.glob("*.parquet"))
    shutil.rmtree(out)
    # A one-thread worker computes its chunks one after the other: its first result is its first chunk.
    first = {}
    for c in summary["computed"]:
        first.setdefault(c["worker"], c["cpu_seconds"])
    return {"workers": workers, "wall": wall, "first_cpu": max(first.values()), "total": total, "compute": compute, "poses": poses,
            "cases": cases, "overhead": 1 - compute / (wall * workers), "bytes": size, "cpu": cpu,
            "load": load,
            "chunk_cpu": statistics.median(c["cpu_seconds"] for c in summary["computed"])}


ENVELOPE = {"kind": "envelope", "fidelity": ["full"], "payload_mass": {"start": 0, "stop": 100, "num": 21},
            "payload_com": [[0, 0, 0.1], [0.05, 0.05, 0.15]],
            "manoeuvres": [{"scene": s, "amplitude": [0.5, 1.0], "frequency": [1.0, 2.0]}
                           for s in ("heave", "roll", "pitch", "yaw", "combined")],
            "cases_per_chunk": 84}
WORKSPACE = {"kind": "workspace", "fidelity": "massless", "platform": {"payload_mass": 50},
             "slices": [{"name": "xy", "fixed": {"z": 0.55},
                         "axes": {"x": {"start": -0.4, "stop": 0.4, "num": 3200},
                                  "y": {"start": -0.4, "stop": 0.4, "num": 3200}}}],
             "poses_per_chunk": 1024000}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("file", nargs="?")
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--skip-sweeps", action="store_true")
    parser.add_argument("--skip-batches", action="store_true")
    parser.add_argument("--sweeps", nargs="+", choices=["envelope", "workspace"],
                        default=["envelope", "workspace"])
    parser.add_argument("--pairs", type=int, default=1)
    parser.add_argument("--calls", action="store_true", help="one-row calls only (see above)")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--against", help="an installed package stewart in this folder, alternated")
    parser.add_argument("--calls-worker", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.calls_worker:
        return calls_worker()
    if args.calls:
        lines = calls_report(args)
        print("\n".join(lines), flush=True)
        if args.file:
            pathlib.Path(args.file).write_text("\n".join(lines) + "\n")
        return 0
    lines = [f"stewart {stewart.__version__}, {os.cpu_count()} cores; load average at start "
             f"{os.getloadavg()[0]:.2f} (the machine may be shared: see docs/sweeps.md)"]
    if not args.skip_batches:
        c = c_ns_per_pose(pathlib.Path(args.build))
        lines.append("batch throughput, yaw manoeuvre, 12001 poses per call, median of calls:")
        lines.append(f"  {'level':10s} {'C ns/pose':>10s} {'python ns/pose':>15s} {'python/C poses/s':>17s}"
                     f" {'out= ns/pose':>13s} {'out= python/C':>14s}")
        for level, repeats in (("kinematic", 41), ("massless", 41), ("full", 5)):
            fresh, reused = python_ns_per_pose(level, 12001, repeats)
            lines.append(f"  {level:10s} {c[level]:10.1f} {fresh:15.1f} {c[level] / fresh:17.1%}"
                         f" {reused:13.1f} {c[level] / reused:14.1%}")
    print("\n".join(lines), flush=True)
    specs = {"envelope": ENVELOPE, "workspace": WORKSPACE}
    if not args.skip_sweeps:
        with tempfile.TemporaryDirectory() as tmp:
            for spec in (specs[k] for k in args.sweeps):
                speedups = []
                for _ in range(args.pairs):
                    rows = [sweep(spec, w, tmp) for w in (1, 2)]
                    speedups.append(report(spec, rows, lines))
                if args.pairs > 1:
                    lines.append(f"{spec['kind']}: {args.pairs} pairs, speed-ups "
                                 f"{', '.join(f'{x:.2f}x' for x in speedups)}, median "
                                 f"{statistics.median(speedups):.2f}x")
                    print(lines[-1], flush=True)
    if args.file:
        pathlib.Path(args.file).write_text("\n".join(lines) + "\n")


def report(spec, rows, lines):
    """Appends (and prints) one pair of sweeps' lines; returns the speed-up."""
    level = spec["fidelity"][0] if spec["kind"] == "envelope" else spec["fidelity"]
    lines.append(f"sweep {spec['kind']} ({level}), {rows[0]['poses']} poses, "
                 f"{rows[0]['cases'] or '-'} cases:")
    for r in rows:
        per_core = r["poses"] / (r["wall"] * r["workers"])
        lines.append(
            f"  {r['workers']} worker(s): wall {r['wall']:.2f} s (with start-up, merge, plots "
            f"{r['total']:.2f} s), workers' own time {r['compute']:.2f} s, Dask overhead "
            f"{r['overhead']:.1%}, {r['poses'] / r['wall']:.3g} poses/s "
            f"({per_core:.3g} per core); workers' CPU {r['cpu']:.2f} s = "
            f"{r['cpu'] / r['wall']:.2f} cores busy on average, median chunk CPU "
            f"{r['chunk_cpu']:.2f} s (a worker's first: {r['first_cpu']:.2f} s), load average {r['load']:.2f} at its start" +
            (f", {r['cases'] / r['wall']:.3g} cases/s" if r["cases"] else ""))
    lines.append(f"  speed-up 2 vs 1 worker: {rows[0]['wall'] / rows[1]['wall']:.2f}x; "
                 f"merged Parquet {rows[0]['bytes'] / 1e6:.1f} MB "
                 f"({rows[0]['bytes'] / (rows[0]['cases'] or rows[0]['poses']):.0f} B per "
                 f"{'case' if rows[0]['cases'] else 'pose'})")
    print("\n".join(lines[-4:]), flush=True)
    return rows[0]['wall'] / rows[1]['wall']


if __name__ == "__main__":
    sys.exit(main())
