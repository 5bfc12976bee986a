#!/usr/bin/env python3
"""Runs a scene (scenes/*.json) through the FMI 2.0 FMU with fmpy; writes a CSV of every output
and PNG plots (and a GIF for scenes with "animate": true) into the output folder. The slider-crank
scene runs build/slider-crank-solve instead.

At each communication point the master sets the pose (and, with derivatives = 1, its exact first
and second derivatives), reads the outputs (a direct function of the inputs set), then steps. A
scene with a move section plays the move planned by stewart.move on the platform (docs/moves.md).

usage: run_scene.py SCENE [--fmu PATH] [--out DIR] [--fidelity 0|1|2] [--derivatives 0|1]
                          [--compare 1,2] [--platform FILE.json [--scale-to-ranges]]
"""
import argparse
import pathlib
import shutil
import subprocess
import sys

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

import plots
import scenes

ROOT = pathlib.Path(__file__).resolve().parents[1]
LEG_OUTPUTS = ("L", "L_dot", "L_ddot", "F")
REAL_OUTPUTS = ([f"{g}[{k}]" for g in LEG_OUTPUTS for k in range(1, 7)] + ["condition", "residual"]
                + [f"base_force[{i}]" for i in range(1, 4)] + [f"base_torque[{i}]" for i in range(1, 4)])
INTEGER_OUTPUTS = ("newton_iterations", "status")


class Unit:
    """One FMI 2 co-simulation instance of the Stewart platform FMU."""

    def __init__(self, fmu_path, parameters=None, name="stewart"):
        self.md = read_model_description(fmu_path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.unzipped = extract(fmu_path)
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.unzipped,
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName=name)
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        for key, value in (parameters or {}).items():
            self.set(key, value)
        self.fmu.exitInitializationMode()

    def set(self, name, value):
        if self.types[name] == "Integer":
            self.fmu.setInteger([self.vr[name]], [int(value)])
        else:
            self.fmu.setReal([self.vr[name]], [float(value)])

    def set_pose(self, q, qd=None, qdd=None):
        names = list(scenes.POSE)
        values = list(q)
        if qd is not None:
            names += list(scenes.DOT) + list(scenes.DDOT)
            values += list(qd) + list(qdd)
        self.fmu.setReal([self.vr[n] for n in names], values)

    def outputs(self):
        reals = self.fmu.getReal([self.vr[n] for n in REAL_OUTPUTS])
        ints = self.fmu.getInteger([self.vr[n] for n in INTEGER_OUTPUTS])
        return dict(zip(REAL_OUTPUTS, reals)) | dict(zip(INTEGER_OUTPUTS, ints))

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.unzipped, ignore_errors=True)


def run(fmu_path, scene, fidelity=2, derivatives=1, dt=None, parameters=None, platform=None):
    """Every output at every communication point: {name: array}, plus 't' and the pose. A
    move is planned on `platform` (the machine `parameters` describe; default the thesis
    platform with the scene's parameters)."""
    t, q, qd, qdd = scenes.trajectory(scene, platform, dt)
    unit = Unit(fmu_path, {"fidelity": fidelity, "derivatives": derivatives,
                           **scene.get("parameters", {}), **(parameters or {})})
    rows = []
    try:
        for i, ti in enumerate(t):
            unit.set_pose(q[i], *((qd[i], qdd[i]) if derivatives else ()))
            rows.append(unit.outputs())
            if i + 1 < len(t):
                # fmpy raises on Discard or Error; a Warning is in the `status` output
                unit.fmu.doStep(ti, t[i + 1] - ti)
    finally:
        unit.close()
    result = {"t": t, **{name: q[:, i] for i, name in enumerate(scenes.POSE)}}
    for name in rows[0]:
        result[name] = np.array([r[name] for r in rows])
    return result


def legs(result, group):
    return np.column_stack([result[f"{group}[{k}]"] for k in range(1, 7)])


def write_csv(result, path):
    names = list(result)
    np.savetxt(path, np.column_stack([result[n] for n in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.17g")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--fmu", default=str(ROOT / "build/fmus/2.0/StewartPlatform.fmu"))
    parser.add_argument("--out", default=str(ROOT / "out"))
    parser.add_argument("--fidelity", type=int, default=2)
    parser.add_argument("--derivatives", type=int, default=1)
    parser.add_argument("--compare", default="1,2",
                        help="fidelity levels whose forces share one chart ('' for none)")
    scenes.add_platform_arguments(parser)
    parser.add_argument("--view", action="store_true",
                        help="also write NAME.html, the run in 3D in a browser (docs/view.md)")
    args, _ = plots.parse_args_with_units(parser)
    try:
        scene = scenes.load(args.scene)
    except ValueError as e:
        raise SystemExit(f"run_scene: {e}") from None
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    name, title = scene["name"], scene.get("title", scene["name"])
    if scene.get("mechanism") == "slider-crank":
        return run_slider_crank(scene, out, name, title)

    try:
        scene, platform, machine = scenes.on_platform(scene, args)
        result = run(args.fmu, scene, args.fidelity, args.derivatives, parameters=machine,
                     platform=platform)
    except ValueError as e:  # SceneError, stewart.MoveError: the message names the cause
        raise SystemExit(f"run_scene: {e}") from None
    write_csv(result, out / f"{name}.csv")
    level = plots.FIDELITY_NAMES[args.fidelity]
    plots.plot_legs(result["t"], {g: legs(result, g) for g in ("L", "L_dot", "F")},
                    out / f"{name}.png", f"{title} — {level}", args.units)
    written = [f"{name}.csv", f"{name}.png"]
    if args.view:
        import stewart
        stewart.view(platform, result,
                     output=out / f"{name}.html", title=title)
        written.append(f"{name}.html")
    if args.compare:
        levels = [int(v) for v in args.compare.split(",")]
        forces = {lv: legs(run(args.fmu, scene, lv, args.derivatives, parameters=machine,
                               platform=platform), "F") for lv in levels}
        plots.plot_forces_per_fidelity(result["t"], forces, out / f"{name}_fidelity.png", title)
        written.append(f"{name}_fidelity.png")
    framed = any(np.any(platform.params.get(f, 0.0)) for f in ("tool_frame", "user_frame"))
    if scene.get("animate") and framed:
        print("run_scene: no GIF: it draws the platform frame's poses, and this platform's poses "
              "are a tool frame's in a user frame (scripts/view.py draws those)")
    elif scene.get("animate"):
        base, top = platform_points(platform)
        q = np.column_stack([result[n] for n in scenes.POSE])
        plots.animate_platform(result["t"], q, out / f"{name}.gif", base, top, title=name)
        written.append(f"{name}.gif")
    print(f"run_scene: wrote {', '.join(str(out / w) for w in written)}")


def run_slider_crank(scene, out, name, title):
    csv_path = out / f"{name}.csv"
    subprocess.run([str(ROOT / "build/slider-crank-solve"), "--rpm", str(scene["rpm"]),
                    "--turns", str(scene["turns"]), "--dt", str(scene["step"]), str(csv_path)],
                   check=True)
    data = np.genfromtxt(csv_path, delimiter=",", names=True)
    plots.plot_slider_crank(data, out / f"{name}.png", title)
    print(f"run_scene: wrote {csv_path}, {out / f'{name}.png'}")


def platform_points(platform):
    """The joint centres for the drawing, as the library has them: base (6, 3) in the base
    frame, platform (6, 3) in the platform frame."""
    from stewart import _core
    base, top = _core.model_joints(platform._model)
    return np.reshape(base, (6, 3)), np.reshape(top, (6, 3))


if __name__ == "__main__":
    sys.exit(main())
