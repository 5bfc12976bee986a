#!/usr/bin/env python3
"""Every output of a reference build against the current build, file by file.

On every scene (scenes/*.json; scripts/scenes.py writes its poses) it runs, in both builds:
  stewart-solve at the three fidelities, stewart-solve --forward (on the reference's kinematic
  lengths, rates and accelerations), stewart-simulate at both fidelities (on the reference's
  full-level forces over the scene's first second), and through fmpy the StewartPlatform FMU (FMI
  2.0 and 3.0, fidelities 0..2, the scene's pose and derivatives as inputs) and the StewartPlant FMU
  (FMI 2.0 and 3.0, both fidelities, on the same forces).
Each pair of files is compared column by column: identical bits, or the largest difference
relative to the column's scale, max(1, max |reference|). It prints that per file and fails (exit
status 1) when one exceeds the bound (--bound, default 1e-9 relative; say 0 to ask for identical
bits).

usage: compare_outputs.py REFERENCE_BUILD CURRENT_BUILD [--bound B] [--keep DIR]
(studies/bench/compare_outputs.sh builds the reference of a commit and calls this.)
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from fmpy import simulate_fmu

ROOT = pathlib.Path(__file__).resolve().parents[2]
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
SIMULATED_SECONDS = 1.0


def read_csv(path):
    """Header and float matrix of a CSV written by the CLIs (or by write_csv below)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return header, data


def write_csv(path, header, rows):
    np.savetxt(path, rows, delimiter=",", header=",".join(header), comments="", fmt="%.17g")


def scenes():
    """Names of the Stewart platform scenes (the slider-crank scene is another mechanism)."""
    for path in sorted((ROOT / "scenes").glob("*.json")):
        if "mechanism" not in json.loads(path.read_text()):
            yield path.stem


def run_clis(build, scene, poses, reference_dir, out_dir):
    """The CLI outputs of one build on one scene; the forward and plant inputs are the
    reference's (reference_dir), so both builds see the same ones."""
    out = {}
    for fidelity in ("kinematic", "massless", "full"):
        path = out_dir / f"{scene}-solve-{fidelity}.csv"
        subprocess.run([build / "stewart-solve", "--fidelity", fidelity, poses, path], check=True)
        out[path.name] = path
    lengths = reference_dir / f"{scene}-solve-kinematic.csv"
    path = out_dir / f"{scene}-forward.csv"
    subprocess.run([build / "stewart-solve", "--forward", lengths, path], check=True)
    out[path.name] = path
    forces = reference_dir / f"{scene}-forces.csv"
    for fidelity in ("massless", "full"):
        path = out_dir / f"{scene}-simulate-{fidelity}.csv"
        # (open loop, a leg may leave its stroke: the warnings on stderr are not the point here)
        subprocess.run([build / "stewart-simulate", "--fidelity", fidelity, forces, path],
                       check=True, stderr=subprocess.DEVNULL)
        out[path.name] = path
    return out


def forces_file(reference_dir, scene):
    """t,F1..F6 of the reference's full level over the scene's first SIMULATED_SECONDS."""
    header, data = read_csv(reference_dir / f"{scene}-solve-full.csv")
    columns = [header.index("t")] + [header.index(f"F{k}") for k in range(1, 7)]
    rows = data[data[:, header.index("t")] <= SIMULATED_SECONDS + 1e-12][:, columns]
    path = reference_dir / f"{scene}-forces.csv"
    write_csv(path, ["t"] + [f"F{k}" for k in range(1, 7)], rows)
    return path


def fmu_result_csv(result, path):
    names = [n for n in result.dtype.names]
    write_csv(path, names, np.column_stack([result[n].astype(float) for n in names]))


def run_fmus(build, scene, poses, reference_dir, out_dir):
    """The FMU outputs of one build on one scene (fmpy, the same inputs for both builds)."""
    out = {}
    header, data = read_csv(poses)
    step = float(data[1, 0] - data[0, 0])
    names = ["time"] + [h for h in header[1:]]
    signals = np.array([tuple(row) for row in data], dtype=[(n, float) for n in names])
    for version in ("2.0", "3.0"):
        fmu = build / "fmus" / version / "StewartPlatform.fmu"
        for fidelity in (0, 1, 2):
            result = simulate_fmu(str(fmu), start_values={"fidelity": fidelity, "derivatives": 1},
                                  input=signals, stop_time=float(data[-1, 0]),
                                  output_interval=step, step_size=step)
            path = out_dir / f"{scene}-fmu{version}-platform-{fidelity}.csv"
            fmu_result_csv(result, path)
            out[path.name] = path
    fheader, fdata = read_csv(reference_dir / f"{scene}-forces.csv")
    fnames = ["time"] + [f"F[{k}]" for k in range(1, 7)]
    fsignals = np.array([tuple(row) for row in fdata], dtype=[(n, float) for n in fnames])
    for version in ("2.0", "3.0"):
        fmu = build / "fmus" / version / "StewartPlant.fmu"
        for fidelity in (1, 2):
            result = simulate_fmu(str(fmu), start_values={"fidelity": fidelity}, input=fsignals,
                                  stop_time=float(fdata[-1, 0]), output_interval=step,
                                  step_size=step)
            path = out_dir / f"{scene}-fmu{version}-plant-{fidelity}.csv"
            fmu_result_csv(result, path)
            out[path.name] = path
    return out


def compare(reference, current):
    """(identical, largest relative difference, its column) of two CSV files."""
    if reference.read_bytes() == current.read_bytes():
        return True, 0.0, ""
    h1, a = read_csv(reference)
    h2, b = read_csv(current)
    if h1 != h2 or a.shape != b.shape:
        return False, np.inf, "shape or header"
    with np.errstate(invalid="ignore"):
        scale = np.maximum(1.0, np.nanmax(np.abs(a), axis=0))
        diff = np.abs(a - b) / scale
    diff[np.isnan(a) & np.isnan(b)] = 0
    diff[np.isnan(diff)] = np.inf
    column = int(np.argmax(np.max(diff, axis=0)))
    return False, float(np.max(diff)), h1[column]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference", type=pathlib.Path, help="the reference build directory")
    parser.add_argument("current", type=pathlib.Path, help="the current build directory")
    parser.add_argument("--bound", type=float, default=1e-9,
                        help="largest difference allowed, relative to max(1, |column|)")
    parser.add_argument("--keep", type=pathlib.Path, help="keep the output files here")
    args = parser.parse_args()
    work = pathlib.Path(args.keep or tempfile.mkdtemp())
    work.mkdir(parents=True, exist_ok=True)
    worst, failures, identical, total = 0.0, 0, 0, 0
    try:
        for scene in scenes():
            poses = work / f"{scene}-poses.csv"
            subprocess.run([sys.executable, ROOT / "scripts" / "scenes.py", scene, poses],
                           check=True)
            dirs = {side: work / side for side in ("reference", "current")}
            for d in dirs.values():
                d.mkdir(parents=True, exist_ok=True)
            outputs = {}
            for side, build in (("reference", args.reference), ("current", args.current)):
                if side == "reference":
                    # the reference's solve first: the forward and plant inputs come from it
                    for fidelity in ("kinematic", "massless", "full"):
                        subprocess.run([build / "stewart-solve", "--fidelity", fidelity, poses,
                                        dirs[side] / f"{scene}-solve-{fidelity}.csv"], check=True)
                    forces_file(dirs[side], scene)
                outputs[side] = run_clis(build, scene, poses, dirs["reference"], dirs[side])
                outputs[side].update(run_fmus(build, scene, poses, dirs["reference"], dirs[side]))
            for name, reference in outputs["reference"].items():
                same, difference, column = compare(reference, outputs["current"][name])
                total += 1
                identical += same
                worst = max(worst, difference)
                bad = difference > args.bound
                failures += bad
                verdict = "identical" if same else f"{difference:.3g} ({column})"
                print(f"{name:45s} {verdict}{'  > bound' if bad else ''}", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    print(f"{total} files: {identical} bit for bit, largest relative difference {worst:.3g} "
          f"(bound {args.bound:g}), {failures} over the bound")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
