#!/usr/bin/env python3
"""The speed–accuracy study: every knob the unit offers, measured against one reference.

Reference: the full 14-body model with exact derivative inputs and Newton tolerance 1e-13, the
pose set exactly at each sample time (stewart-solve). Each configuration runs the FMI 2 FMU the
way a master does (set the pose at t, doStep(t, h), record the outputs at t + h) through the C
benchmark build/fmu_bench, which also times doStep; fmpy times the same loop from Python for a
subset. Knobs: fidelity level; derivative source (inputs or finite differences); communication
step 1…100 ms; Newton tolerance 1e-4…1e-12; exact or modified Newton; and a heavy-leg platform
(20 kg per leg body) to show where massless legs stop being good enough.

The plant (StewartPlant.fmu, forward dynamics): the inverse unit's forces along the same cue,
sampled every 0.125 ms, fed to the plant as a master does (forces at t with their FMI 2 input
derivative, the chord to the next sample at its own step), against a reference run of the plant
at 0.125 ms steps and tolerance 1e-13; knobs: communication step, integrator method and tolerance,
fidelity. fmpy drives and times it (median µs per doStep, the median of three runs; fmpy's ctypes
call is included).

Writes out/speed_accuracy.csv, docs/speed-accuracy-data.md and docs/speed-accuracy.png
(docs/speed-accuracy.md says what the numbers mean for a user).

usage: studies/speed_accuracy.py [--scene combined] [--duration 6] [--quick] [--plant-only]
"""
import argparse
import csv
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))  # the user scripts this study drives

import plots  # noqa: F401  (sets the Agg backend)
import matplotlib.pyplot as plt  # noqa: E402
import closed_loop  # noqa: E402
import run_scene  # noqa: E402
import scenes  # noqa: E402
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


# ---------------------------------------------------------------- the plant

PLANT_FMU = BUILD / "fmus/2.0/StewartPlant.fmu"
PLANT_DURATION = 1.0  # the plant is a saddle (docs/forward-dynamics.md): errors grow as e^(5.1 t)
PLANT_SAMPLE = 1.25e-4  # the forces' sampling step; every communication step is a multiple of it
PLANT_STEPS_MS = (0.25, 0.5, 1, 2, 5, 10)
PLANT_TOLERANCES = (1e-6, 1e-8, 1e-10, 1e-12)
METHOD = {0: "CVODE Adams", 1: "CVODE BDF", 2: "ARKODE ERK 4(3)", 3: "ARKODE ERK 5(4)"}
PLANT_DEFAULTS = {"method": 2, "relative_tolerance": 1e-10}


def inverse_forces(scene, fidelity, times):
    """The inverse unit's forces (derivatives = 1, the cue's exact rates) at `times`."""
    q, qd, qdd = scenes.pose(scene, times)
    inverse = closed_loop.Unit(FMU, "inverse", {"fidelity": fidelity, "derivatives": 1})
    try:
        forces = []
        for j in range(times.size):
            inverse.set(list(scenes.POSE) + list(scenes.DOT) + list(scenes.DDOT), [*q[j], *qd[j], *qdd[j]])
            forces.append(inverse.get(closed_loop.legs("F")))
    finally:
        inverse.free()
    return np.array(forces)


def run_plant(scene, fidelity, forces, every, method, rtol, atol=None):
    """The plant at communication step every * PLANT_SAMPLE under the sampled forces: (poses at
    the communication points, median µs per doStep, RHS evaluations per step), or None if a
    step was refused."""
    h = every * PLANT_SAMPLE
    n = (forces.shape[0] - 1) // every
    q0, qd0, _ = scenes.pose(scene, np.array([0.0]))
    parameters = {"fidelity": fidelity, "method": method, "relative_tolerance": rtol,
                  "absolute_tolerance": rtol / 100 if atol is None else atol,
                  **{f"{p}0": v for p, v in zip(scenes.POSE, q0[0])},
                  **{f"{p}_dot0": v for p, v in zip(scenes.POSE, qd0[0])}}
    plant = closed_loop.Unit(PLANT_FMU, "plant", parameters)
    force_vr = [plant.vr[name] for name in closed_loop.legs("F")]
    poses, spent = [plant.get(list(scenes.POSE))], []
    try:
        for j in range(n):
            f0, f1 = forces[j * every], forces[(j + 1) * every]
            plant.set(closed_loop.legs("F"), f0)
            plant.fmu.setRealInputDerivatives(force_vr, [1] * 6, list((f1 - f0) / h))
            t0 = time.perf_counter()
            plant.fmu.doStep(j * h, h)  # fmpy raises on Discard and Error
            spent.append(time.perf_counter() - t0)
            poses.append(plant.get(list(scenes.POSE)))
        rhs = plant.fmu.getInteger([plant.vr["total_rhs_evaluations"]])[0]
    except Exception:  # fmpy raises on Discard or Error: a refused step
        return None
    finally:
        plant.free()
    return np.array(poses), 1e6 * float(np.median(spent)), rhs / n


def plant_rows(scene):
    """The plant's table, both fidelities: for the communication step, the pose error against the
    reference run under the forces as sampled (what a larger step costs a master, input
    interpolation included); for method and tolerance at 1 ms, against the reference under the
    same 1 ms signal (the integrator's own error). Returns the rows and notes on the references."""
    times = np.arange(int(round(PLANT_DURATION / PLANT_SAMPLE)) + 1) * PLANT_SAMPLE
    cue, _, _ = scenes.pose(scene, times)
    rows, notes = [], []
    for fidelity in (1, 2):
        forces = inverse_forces(scene, fidelity, times)
        references = {}

        def reference(every):
            """ERK 5(4) at rtol 1e-13 and PLANT_SAMPLE steps under the signal a master with step
            every * PLANT_SAMPLE gives (linear between its samples), at its communication points:
            the small steps keep the reference's integration error far below any run's."""
            if every not in references:
                coarse = forces[::every]
                fine = np.array([np.interp(times, times[::every], coarse[:, k]) for k in range(6)]).T
                references[every] = run_plant(scene, fidelity, fine, 1, 3, 1e-13, 1e-15)[0][::every]
            return references[every]

        def record(knob, ms, method, rtol, against):
            every = int(round(ms * 1e-3 / PLANT_SAMPLE))
            result = run_plant(scene, fidelity, forces, every, method, rtol)
            if result is not None:  # timing: the median of three runs' medians, as for the unit
                again = [run_plant(scene, fidelity, forces, every, method, rtol) for _ in range(2)]
                result = (result[0], float(np.median([result[1], *(r[1] for r in again)])), result[2])
            row = {"knob": knob, "fidelity": LEVEL[fidelity], "step_ms": ms, "method": METHOD[method],
                   "tolerance": rtol, "position_error_m": float("nan"), "angle_error_rad": float("nan"),
                   "us_per_step_fmpy": float("nan"), "cpu_ms_per_s": float("nan"),
                   "rhs_per_step": float("nan")}
            if result is not None:
                poses, us, rhs = result
                error = np.abs(poses - (reference(1)[::every] if against == "fine" else reference(every)))
                row |= {"position_error_m": float(error[:, :3].max()),
                        "angle_error_rad": float(error[:, 3:].max()), "us_per_step_fmpy": us,
                        "cpu_ms_per_s": us / ms, "rhs_per_step": rhs}
            rows.append(row)
            print(" ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                           for k, v in row.items()), flush=True)

        notes.append(f"the {LEVEL[fidelity]} reference follows the cue to "
                     f"{np.abs(reference(1) - cue).max():.1e} (m and rad, open loop)")
        print(notes[-1])
        for ms in PLANT_STEPS_MS:
            record("step", ms, PLANT_DEFAULTS["method"], PLANT_DEFAULTS["relative_tolerance"], "fine")
        for method in METHOD:
            for rtol in PLANT_TOLERANCES:
                record("method/tolerance", 1, method, rtol, "same step")
    return rows, notes


def plant_report(rows, notes, scene):
    """The plant's section of docs/speed-accuracy-data.md (replaced in place)."""
    head = ("| knob | fidelity | step [ms] | method | rtol (atol = rtol/100) | position error [m] "
            "| angle error [rad] | RHS per step | µs/doStep (fmpy) | CPU ms per simulated s |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        lines.append(f"| {r['knob']} | {r['fidelity']} | {r['step_ms']:g} | {r['method']} | "
                     f"{r['tolerance']:.0e} | {r['position_error_m']:.2e} | {r['angle_error_rad']:.2e} | "
                     f"{r['rhs_per_step']:.1f} | {r['us_per_step_fmpy']:.2f} | {r['cpu_ms_per_s']:.2f} |")
    section = (f"{PLANT_MARK}\n\nScene `{scene['name']}`, {PLANT_DURATION:g} s: the inverse unit's "
               f"forces sampled every {PLANT_SAMPLE * 1e3:g} ms and fed with their chord as FMI 2 "
               f"input derivative. References: the plant with ARKODE ERK 5(4), rtol 1e-13, "
               f"atol 1e-15, at {PLANT_SAMPLE * 1e3:g} ms steps, under the forces as sampled for the "
               f"`step` rows, under the run's own signal (linear between its 1 ms samples) for the "
               f"`method/tolerance` rows; {'; '.join(notes)}. Failed runs: nan. "
               f"Written by `studies/speed_accuracy.py` (what the numbers mean: "
               f"speed-accuracy.md).\n\n" + "\n".join(lines) + "\n")
    path = ROOT / "docs" / "speed-accuracy-data.md"
    text = path.read_text() if path.exists() else ""
    text = text.split(PLANT_MARK)[0].rstrip("\n")
    path.write_text((text + "\n\n" if text else "") + section)


PLANT_MARK = "## The plant (StewartPlant.fmu)"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--duration", type=float, default=6.0)
    parser.add_argument("--quick", action="store_true", help="fewer steps and tolerances")
    parser.add_argument("--plant-only", action="store_true", help="only the plant's section")
    args = parser.parse_args()
    scene = scenes.load(args.scene)
    plant, plant_notes = plant_rows(scene)
    if args.plant_only:
        plant_report(plant, plant_notes, scene)
        return
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
    plant_report(plant, plant_notes, scene)


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
        f"`studies/speed_accuracy.py` (what the numbers mean: speed-accuracy.md).\n\n"
        f"![Pareto chart](speed-accuracy.png)\n\n" + "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
