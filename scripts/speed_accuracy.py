#!/usr/bin/env python3
"""The speed–accuracy study: every knob the unit offers, measured against one reference.

Reference: the full 14-body model with exact derivative inputs and Newton tolerance 1e-13, the
pose set exactly at each sample time (stewart-solve). Each configuration runs the FMI 2 FMU the
way a master does (set the pose at t, doStep(t, h), record the outputs at t + h) through the C
benchmark build/fmu_bench, which also times doStep; fmpy times the same loop from Python for a
subset. Knobs: fidelity level; derivative source (inputs or finite differences); communication
step 1…100 ms; Newton tolerance 1e-4…1e-12; exact or modified Newton; and a heavy-leg platform
(20 kg per leg body) to show where massless legs stop being good enough.

Writes out/speed_accuracy.csv, docs/speed-accuracy-data.md and docs/speed-accuracy.png
(docs/speed-accuracy.md says what the numbers mean for a user).

usage: speed_accuracy.py [--scene combined] [--duration 6] [--quick]
"""
import argparse
import csv
import pathlib
import subprocess
import tempfile
import time

import numpy as np

import plots  # noqa: F401  (sets the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402
import run_scene  # noqa: E402
import scenes  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = ROOT / "build"
FMU_SO = BUILD / "fmu/StewartPlatform/stage2/binaries/linux64/StewartPlatform.so"
FMU = BUILD / "fmus/2.0/StewartPlatform.fmu"
STEPS_MS = (1, 2, 5, 10, 20, 50, 100)
TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
LEVEL = {0: "kinematic", 1: "massless", 2: "full"}
STARTUP_STEPS = 3
# 20 kg per leg body: a 0.3 m rod of that mass, principal moments m (3 r^2 + l^2) / 12, m r^2 / 2
HEAVY = {"cylinder_mass": 20.0, "piston_mass": 20.0}
for body in ("cylinder", "piston"):
    r, length = 0.0075, 0.3
    HEAVY |= {f"{body}_inertia[1]": 20 * (3 * r * r + length * length) / 12,
              f"{body}_inertia[2]": 20 * (3 * r * r + length * length) / 12,
              f"{body}_inertia[3]": 20 * r * r / 2}


def pose_argument(scene):
    values = []
    for name in scenes.POSE:
        s = scene["pose"].get(name, {})
        values += [s.get("mean", 0.0), s.get("amplitude", 0.0), s.get("omega", 0.0), s.get("phase", 0.0)]
    return ",".join(repr(float(v)) for v in values)


def run_bench(scene, duration, fidelity, derivatives, step, tolerance=1e-12, modified=0,
              parameters=None):
    """(outputs as {column: array}, median µs per doStep, mean Newton iterations)."""
    with tempfile.NamedTemporaryFile(suffix=".csv") as out:
        cmd = [str(BUILD / "fmu_bench"), str(FMU_SO), "--fidelity", str(fidelity),
               "--derivatives", str(derivatives), "--step", repr(step), "--duration", repr(duration),
               "--tolerance", repr(tolerance), "--modified-newton", str(modified),
               "--pose", pose_argument(scene), "--out", out.name]
        for key, value in (parameters or {}).items():
            cmd += ["--set", f"{key}={value!r}"]
        result = subprocess.run(cmd, capture_output=True, text=True, check=True)
        stats = dict(kv.split("=") for kv in result.stdout.split())
        data = np.genfromtxt(out.name, delimiter=",", names=True)
        # Timing: the median of three runs' medians, so that one disturbed run does not count.
        medians = [float(stats["doStep_us_median"])]
        for _ in range(2):
            again = subprocess.run(cmd[:-2], capture_output=True, text=True, check=True)
            medians.append(float(dict(kv.split("=") for kv in again.stdout.split())["doStep_us_median"]))
    return data, float(np.median(medians)), float(stats["iterations_mean"])


def reference(scene, times, parameters=None):
    """Full model, exact derivatives, tolerance 1e-13, the pose set exactly at each time: the
    thesis platform through stewart-solve (independent of the FMU layer); another platform
    through the FMU read before stepping (outputs are a direct function of the inputs set)."""
    if parameters:
        h = times[1] - times[0]
        result = run_scene.run(str(FMU), scene | {"duration": times[-1]}, fidelity=2, derivatives=1,
                               dt=h, parameters={"tolerance": 1e-13, **parameters})
        return {f"{g}{k}": result[f"{g}[{k}]"][1:] for g in ("L", "F") for k in range(1, 7)}
    with tempfile.TemporaryDirectory() as tmp:
        q, qd, qdd = scenes.pose(scene, times)
        pose_csv = pathlib.Path(tmp) / "in.csv"
        cols = ["t", *scenes.POSE, *scenes.DOT, *scenes.DDOT]
        np.savetxt(pose_csv, np.column_stack([times, q, qd, qdd]), delimiter=",",
                   header=",".join(cols), comments="", fmt="%.17g")
        out_csv = pathlib.Path(tmp) / "out.csv"
        subprocess.run([str(BUILD / "stewart-solve"), "--fidelity", "full", "--tolerance", "1e-13",
                        str(pose_csv), str(out_csv)], check=True, capture_output=True)
        data = np.genfromtxt(out_csv, delimiter=",", names=True)
    return {k: data[k] for k in data.dtype.names}


def errors(data, ref, skip=STARTUP_STEPS):
    """Worst errors after the first `skip` steps: with finite differences the unit starts from
    rest and needs two earlier poses, so its first steps carry a start-up transient, reported
    apart."""
    L = np.column_stack([data[f"L{k}"] for k in range(1, 7)])
    F = np.column_stack([data[f"F{k}"] for k in range(1, 7)])
    L_ref = np.column_stack([ref[f"L{k}"] for k in range(1, 7)])
    F_ref = np.column_stack([ref[f"F{k}"] for k in range(1, 7)])
    force = np.max(np.abs(F - F_ref), axis=1)
    peak = float(np.max(np.abs(F_ref)))
    return {"length_error_m": float(np.max(np.abs(L - L_ref)[skip:])),
            "force_error_N": float(np.max(force[skip:])),
            "force_error_pct": 100 * float(np.max(force[skip:])) / peak,
            "startup_force_error_N": float(np.max(force[:skip]))}


def fmpy_us_per_step(scene, fidelity, derivatives, step, steps=2000):
    """Median µs per doStep when fmpy drives the same FMU from Python."""
    unit = run_scene.Unit(str(FMU), {"fidelity": fidelity, "derivatives": derivatives})
    t = np.arange(steps) * step
    q, qd, qdd = scenes.pose(scene, t)
    spent = []
    try:
        for i in range(steps):
            unit.set_pose(q[i], *((qd[i], qdd[i]) if derivatives else ()))
            t0 = time.perf_counter()
            unit.fmu.doStep(t[i], step)
            spent.append(time.perf_counter() - t0)
    finally:
        unit.close()
    return 1e6 * float(np.median(spent))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--duration", type=float, default=6.0)
    parser.add_argument("--quick", action="store_true", help="fewer steps and tolerances")
    args = parser.parse_args()
    scene = scenes.load(args.scene)
    steps_ms = (1, 10, 100) if args.quick else STEPS_MS
    tolerances = (1e-4, 1e-8, 1e-12) if args.quick else TOLERANCES

    rows = []

    def record(knob, fidelity, derivatives, step, tolerance=1e-12, modified=0, parameters=None,
               platform="thesis"):
        data, us, iterations = run_bench(scene, args.duration, fidelity, derivatives, step,
                                         tolerance, modified, parameters)
        ref = reference(scene, data["t"], parameters)
        row = {"knob": knob, "platform": platform, "fidelity": LEVEL[fidelity],
               "derivatives": "inputs" if derivatives else "finite differences",
               "step_ms": step * 1e3, "tolerance": tolerance,
               "newton": "modified" if modified else "exact", "us_per_step_c": us,
               "iterations": iterations, **errors(data, ref)}
        rows.append(row)
        print(" ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items()),
              flush=True)

    for fidelity in (0, 1, 2):
        for derivatives in (1, 0):
            for ms in steps_ms:
                record("fidelity/derivatives/step", fidelity, derivatives, ms / 1e3)
    for modified in (0, 1):
        for tol in tolerances:
            record("tolerance/newton", 2, 1, 1e-3, tol, modified)
    for fidelity in (1, 2):
        record("heavy legs", fidelity, 1, 1e-3, parameters=HEAVY, platform="heavy legs (20 kg)")

    # fmpy timing for the step sizes a user would pick, at each fidelity
    for row in rows:
        row["us_per_step_fmpy"] = ""
    for fidelity in (0, 1, 2):
        us = fmpy_us_per_step(scene, fidelity, 1, 1e-3)
        for row in rows:
            if row["knob"] == "fidelity/derivatives/step" and row["fidelity"] == LEVEL[fidelity] \
                    and row["step_ms"] == 1 and row["derivatives"] == "inputs":
                row["us_per_step_fmpy"] = us

    out = ROOT / "out"
    out.mkdir(exist_ok=True)
    with open(out / "speed_accuracy.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    write_report(rows, scene, args)


def pareto_chart(rows, path):
    """Error against CPU time per simulated second: a larger step costs fewer steps but errs
    more, a higher fidelity costs more per step."""
    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    markers = {"massless": "o", "full": "s"}
    colors = {"inputs": "tab:blue", "finite differences": "tab:orange"}
    for level, marker in markers.items():
        for source, color in colors.items():
            pts = sorted((r["us_per_step_c"] / r["step_ms"], max(r["force_error_pct"], 1e-12), r["step_ms"])
                         for r in rows if r["knob"] == "fidelity/derivatives/step"
                         and r["fidelity"] == level and r["derivatives"] == source)
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=color,
                    linestyle="-" if source == "inputs" else "--", alpha=0.8,
                    label=f"{level}, {'derivative inputs' if source == 'inputs' else 'finite differences'}")
            for x, y, ms in pts:
                if level == "full" and source == "inputs":
                    ax.annotate(f"{ms:g} ms", (x, y), textcoords="offset points", xytext=(4, -10),
                                fontsize="x-small")
    heavy = [r for r in rows if r["platform"] != "thesis"]
    for r in heavy:
        ax.scatter(r["us_per_step_c"] / r["step_ms"], r["force_error_pct"], marker="x", color="tab:red",
                   label=f"heavy legs (20 kg), {r['fidelity']}")
    ax.set_xscale("log"), ax.set_yscale("log")
    ax.set_xlabel("CPU time per simulated second [ms]  (µs per doStep ÷ step in ms)")
    ax.set_ylabel("worst force error [% of peak force]")
    ax.set_title("Speed against accuracy, combined cue (lower left is better)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_report(rows, scene, args):
    docs = ROOT / "docs"
    docs.mkdir(exist_ok=True)
    pareto_chart(rows, docs / "speed-accuracy.png")
    head = ("| knob | platform | fidelity | derivatives | step [ms] | tolerance | Newton | µs/step (C) "
            "| µs/step (fmpy) | iterations | worst length error [m] | worst force error [N] | [%] "
            "| start-up force error [N] |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        fmpy_us = f"{r['us_per_step_fmpy']:.2f}" if r["us_per_step_fmpy"] != "" else ""
        forces = (f"{r['force_error_N']:.3g} | {r['force_error_pct']:.3g} | {r['startup_force_error_N']:.3g}"
                  if r["fidelity"] != "kinematic" else "— | — | —")  # the kinematic level has no forces
        lines.append(f"| {r['knob']} | {r['platform']} | {r['fidelity']} | {r['derivatives']} | "
                     f"{r['step_ms']:g} | {r['tolerance']:.0e} | {r['newton']} | {r['us_per_step_c']:.2f} | "
                     f"{fmpy_us} | {r['iterations']:.2f} | {r['length_error_m']:.2e} | {forces} |")
    (docs / "speed-accuracy-data.md").write_text(
        f"# Speed–accuracy measurements\n\nScene `{scene['name']}`, {args.duration:g} s, written by "
        f"`scripts/speed_accuracy.py` (what the numbers mean: speed-accuracy.md).\n\n"
        f"![Pareto chart](speed-accuracy.png)\n\n" + "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
