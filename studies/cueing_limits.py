#!/usr/bin/env python3
"""Random vehicle signals through stewart.cueing on every shipped machine: the count of samples
beyond a stroke (the leg lengths |R b + p - a| in the tests' closed form,
tests/python/reference.py, against stroke_min and stroke_max) and beyond any limit
(Platform.limits), with how often the limiter acted.

Each signal is 20 s at 100 Hz from stewart.random_vehicle: per axis a sum of 1 to 3 steps, ramps
and sines scaled to a random peak up to 2 g of specific force (about the rest value (0, 0, g))
and 200 deg/s of angular velocity, all scales 1 (the cue asks for far more than any machine has).
tests/python/test_cueing.py runs 20 signals per machine; this runs the rest.

usage: cueing_limits.py [--signals 1000] [--platform NAME ...] [--seed 37]
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
from reference import machine_lengths, shipped_machine  # noqa: E402  the tests' closed form


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--signals", type=int, default=1000)
    ap.add_argument("--platform", nargs="*", help="platform file stems (default: every one)")
    ap.add_argument("--seed", type=int, default=37)
    args = ap.parse_args()
    files = sorted((ROOT / "platforms").glob("*.json"))
    if args.platform:
        files = [f for f in files if f.stem in args.platform]
    t = np.arange(0, 20, 0.01)
    total_beyond = 0
    for path in files:
        plat = stewart.Platform.from_file(path)
        m = shipped_machine(path)
        rng = np.random.default_rng(args.seed)
        samples = beyond_stroke = beyond_any = limited = cut = 0
        start = time.perf_counter()
        for _ in range(args.signals):
            f, w = stewart.random_vehicle(rng, t)
            r = stewart.cueing(plat, t, f, w, surge_scale=1, sway_scale=1, heave_scale=1,
                               roll_scale=1, pitch_scale=1, yaw_scale=1)
            L = machine_lengths(m, r.pose)
            beyond_stroke += int(np.sum(np.any((L < m[2]) | (L > m[3]), axis=1)))
            beyond_any += int(np.sum(~plat.limits(r.pose).within))
            limited += int(np.sum(r.limited))
            cut += int(np.sum(r.cut))
            samples += len(t)
        total_beyond += beyond_stroke + beyond_any
        print(f"{path.stem}: {args.signals} signals, {samples} samples: {beyond_stroke} beyond a "
              f"stroke, {beyond_any} beyond any limit; limiter acting on {limited / samples:.1%}, "
              f"cut at {cut} samples ({time.perf_counter() - start:.0f} s)", flush=True)
    print(f"total samples beyond a limit: {total_beyond}")
    return 1 if total_beyond else 0


if __name__ == "__main__":
    raise SystemExit(main())
