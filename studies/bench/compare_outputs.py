#!/usr/bin/env python3
"""Every output of a reference build against the current build, file by file: the one check that
a refactoring changes no number (--bound 0) and that a speed change stays within rounding.

On every scene (scenes/*.json; scripts/scenes.py writes its poses) it runs, in both builds:
  stewart-solve at the three fidelities, on the scene's poses with their exact derivatives and
  without them (the CLI then differentiates the samples); stewart-solve --forward on the
  reference's kinematic lengths, with their rates and accelerations and on the lengths alone;
  stewart-simulate at both fidelities on the reference's full-level forces over the scene's first
  second; and through fmpy the StewartPlatform FMU (FMI 2.0 and 3.0, fidelities 0..2, the scene's
  pose and derivatives as inputs) and the StewartPlant FMU (FMI 2.0 and 3.0, both fidelities, on
  the same forces).
Each pair of files is compared column by column: identical bits, or the largest difference
relative to the column's scale, max(1, max |reference|). It prints that per file and fails (exit
status 1) when one exceeds the bound (--bound, default 1e-9 relative). --bound 0 asks for
identical bits, and then also for identical messages from every CLI run (its exit status, stdout
and stderr): a run both builds refuse alike is the same output. Under a bound above 0 the
integrator's work counters (COUNTERS: steps, right-hand sides, error test failures, ...) are not
results: a change of rounding may let the error test reject another step now and then, so they
are reported beside the file ("counters differ") and not held to the bound.

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
# The plant's statistics columns (stewart_outputs.h STEWART_PLANT_STEP_TABLE; the plant FMUs'
# outputs of the same names, their totals, the last internal step's size and order): how much
# work the integrator did, not what it computed.
STEP_COUNTERS = ("steps", "rhs_evaluations", "nonlinear_iterations", "error_test_failures",
                 "jacobian_evaluations")
COUNTERS = {*STEP_COUNTERS, *(f"total_{c}" for c in STEP_COUNTERS), "last_step_size",
            "last_order"}


# The text cells of stewart-solve's status and limit_class columns (stewart_limit_class_name), read
# as their class numbers: a changed class is a difference like any other.
LIMIT_CLASSES = ("none", "stroke", "base_joint", "platform_joint", "interference", "condition",
                 "axis")


def read_csv(path):
    """Header and float matrix of a CSV written by the CLIs (or by write_csv below)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    def number(cell):  # a limit class by name (the CLIs) or a number (the FMUs' status)
        return float(LIMIT_CLASSES.index(cell)) if cell in LIMIT_CLASSES else float(cell)
    text = {i: number for i, name in enumerate(header) if name in ("status", "limit_class")}
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2, converters=text or None)
    return header, data


def write_csv(path, header, rows):
    np.savetxt(path, rows, delimiter=",", header=",".join(header), comments="", fmt="%.17g")


def scenes():
    """Names of the Stewart platform scenes (the slider-crank scene is another mechanism)."""
    for path in sorted((ROOT / "scenes").glob("*.json")):
        if "mechanism" not in json.loads(path.read_text()):
            yield path.stem


def run_cli(command, path, out):
    """One CLI run writing path; its exit status and messages go to path + '.log' (a refused
    run writes no file: the log is its output)."""
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    log = path.with_name(path.name + ".log")
    log.write_text(f"exit {done.returncode}\n{done.stdout}{done.stderr}")
    out[path.name] = path
    out[log.name] = log


def run_clis(build, scene, poses, reference_dir, out_dir):
    """The CLI outputs of one build on one scene; the forward and plant inputs are the
    reference's (reference_dir), so both builds see the same ones."""
    out = {}
    for variant, pose_file in (("", poses), ("-fd", poses.with_name(poses.stem + "-fd.csv"))):
        for fidelity in ("kinematic", "massless", "full"):
            path = out_dir / f"{scene}-solve{variant}-{fidelity}.csv"
            run_cli([build / "stewart-solve", "--fidelity", fidelity, pose_file, path], path, out)
    for variant in ("", "-lengths"):
        lengths = reference_dir / f"{scene}-solve-kinematic{variant}.csv"
        path = out_dir / f"{scene}-forward{variant}.csv"
        run_cli([build / "stewart-solve", "--forward", lengths, path], path, out)
    forces = reference_dir / f"{scene}-forces.csv"
    for fidelity in ("massless", "full"):
        path = out_dir / f"{scene}-simulate-{fidelity}.csv"
        # (open loop, a leg may leave its stroke: its warnings are part of the log)
        run_cli([build / "stewart-simulate", "--fidelity", fidelity, forces, path], path, out)
    return out


def lengths_only(reference_dir, scene):
    """t,L1..L6 of the reference's kinematic level: forward kinematics without rates."""
    header, data = read_csv(reference_dir / f"{scene}-solve-kinematic.csv")
    columns = [header.index("t")] + [header.index(f"L{k}") for k in range(1, 7)]
    write_csv(reference_dir / f"{scene}-solve-kinematic-lengths.csv",
              ["t"] + [f"L{k}" for k in range(1, 7)], data[:, columns])


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


def compare(reference, current, messages):
    """(identical, largest relative difference, its column, whether counters differ) of two
    output files: CSV files column by column, a run's log only when messages count (else it
    passes); COUNTERS columns are left out of the difference unless messages count (bound 0)."""
    if not reference.exists() or not current.exists():
        same = reference.exists() == current.exists()  # both refused: their logs say the rest
        return same, 0.0 if same else np.inf, "" if same else "one build wrote no file", False
    if reference.read_bytes() == current.read_bytes():
        return True, 0.0, "", False
    if reference.suffix == ".log":
        return False, np.inf if messages else 0.0, "exit status or messages", False
    h1, a = read_csv(reference)
    h2, b = read_csv(current)
    if h1 != h2 and set(h1) <= set(h2) and a.shape[0] == b.shape[0]:
        # columns added (the drive columns of a model with drives): the reference's compared
        b = b[:, [h2.index(name) for name in h1]]
        h2 = h1
    if h1 != h2 or a.shape != b.shape:
        return False, np.inf, "shape or header", False
    with np.errstate(invalid="ignore"):
        scale = np.maximum(1.0, np.nanmax(np.abs(a), axis=0))
        diff = np.abs(a - b) / scale
    diff[np.isnan(a) & np.isnan(b)] = 0
    diff[np.isnan(diff)] = np.inf
    counters = [j for j, name in enumerate(h1) if name in COUNTERS]
    counters_differ = bool(np.any(diff[:, counters] > 0))
    if not messages:
        diff[:, counters] = 0
    column = int(np.argmax(np.max(diff, axis=0)))
    return False, float(np.max(diff)), h1[column], counters_differ


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
    worst, failures, identical, total, counters_differ_files = 0.0, 0, 0, 0, 0
    try:
        for scene in scenes():
            poses = work / f"{scene}-poses.csv"
            subprocess.run([sys.executable, ROOT / "scripts" / "scenes.py", scene, poses],
                           check=True)
            subprocess.run([sys.executable, ROOT / "scripts" / "scenes.py", scene,
                            work / f"{scene}-poses-fd.csv", "--no-derivatives"], check=True)
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
                    lengths_only(dirs[side], scene)
                outputs[side] = run_clis(build, scene, poses, dirs["reference"], dirs[side])
                outputs[side].update(run_fmus(build, scene, poses, dirs["reference"], dirs[side]))
            for name, reference in outputs["reference"].items():
                same, difference, column, counters_differ = compare(
                    reference, outputs["current"][name], args.bound == 0)
                total += 1
                identical += same
                worst = max(worst, difference)
                bad = difference > args.bound
                failures += bad
                verdict = "identical" if same else f"{difference:.3g} ({column})"
                counted = counters_differ and args.bound > 0
                counters_differ_files += counted
                print(f"{name:45s} {verdict}{'  > bound' if bad else ''}"
                      f"{'  (counters differ)' if counted else ''}", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    print(f"{total} files: {identical} bit for bit, largest relative difference {worst:.3g} "
          f"(bound {args.bound:g}), {failures} over the bound"
          + (f"; integrator counters differ in {counters_differ_files}" if args.bound > 0 else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
