#!/usr/bin/env python3
"""Closed loop in fmpy: a scene's trajectory -> inverse unit (StewartPlatform.fmu) -> controller
(StewartController.fmu) -> plant (StewartPlant.fmu), FMI 2 co-simulation at fixed communication
steps. Writes OUT/closed_loop.csv (cue, achieved pose, forces) and OUT/closed_loop.png.

At each communication point t (Gauss-Seidel order; the plant has no direct feedthrough, so its
outputs at t come first and the loop has no algebraic part):
  1. the scene's pose and its exact rates and accelerations at t (for a scene with a move, the
     move planned by stewart.move on the machine) -> the inverse unit
     (derivatives = 1): reference lengths L_ref, rates L_dot_ref, feed-forward forces F_ff;
  2. the plant's measured lengths L and rates L_dot at t -> the controller, with 1.:
     F = F_ff + kp (L_ref - L) + kd (L_dot_ref - L_dot);
  3. F -> the plant, held over [t, t + h]; every unit steps to t + h.

usage: closed_loop.py [--scene combined] [--duration 12] [--step 0.001] [--kp 1e6] [--kd 1e4]
                      [--fidelity 2] [--fmus build/fmus/2.0] [--out out/closed_loop] [--no-plot]
                      [--platform FILE.json [--scale-to-ranges]] [--units mm,deg]

With --platform the units get the machine's parameters (stewart.fmu_start_values), the scene
moves about the machine's home, and the PD gains default to the thesis loop's natural frequency
and damping on the machine's moving mass per leg (machine_gains).
"""
import argparse
import pathlib
import shutil
import time

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

import scenes

ROOT = pathlib.Path(__file__).resolve().parents[1]
POSE = list(scenes.POSE)
LEGS = range(1, 7)


def legs(name):
    """['name[1]', ..., 'name[6]']"""
    return [f"{name}[{k}]" for k in LEGS]


class Unit:
    """One FMI 2 co-simulation instance, variables by name, initialised with `parameters` (and
    its real `inputs` set in initialisation mode, when given)."""

    def __init__(self, path, name, parameters, inputs=None):
        md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.directory = extract(str(path))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.directory,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()
        integers = {v.name for v in md.modelVariables if v.type == "Integer"}
        for key, value in parameters.items():
            if key in integers:
                self.fmu.setInteger([self.vr[key]], [int(value)])
            else:
                self.fmu.setReal([self.vr[key]], [float(value)])
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        if inputs:
            self.set(list(inputs), list(inputs.values()))
        self.fmu.exitInitializationMode()

    def set(self, names, values):
        self.fmu.setReal([self.vr[n] for n in names], [float(v) for v in values])

    def get(self, names):
        return np.array(self.fmu.getReal([self.vr[n] for n in names]))

    def step(self, t, h):
        self.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.directory, ignore_errors=True)


def pd_point(inverse, controller, plant, cue):
    """Steps 1 and 2 of the loop at one communication point: the cue (pose, rates and
    accelerations, 18 values) -> the inverse unit; its reference and the plant's measured L, L_dot
    (state only, no feedthrough) -> the controller. Returns the controller's forces F, the plant's
    pose and the feed-forward forces F_ff at this point."""
    inverse.set(POSE + list(scenes.DOT) + list(scenes.DDOT), cue)
    reference = inverse.get(legs("L") + legs("L_dot") + legs("F"))
    measured = plant.get(legs("L") + legs("L_dot"))
    controller.set(legs("L_ref") + legs("L_dot_ref") + legs("F_ff") + legs("L") + legs("L_dot"),
                   [*reference, *measured])
    return controller.get(legs("F")), plant.get(POSE), reference[12:]


def run(scene="combined", duration=12.0, h=1e-3, kp=1e6, kd=1e4, fidelity=2,
        fmus=ROOT / "build" / "fmus" / "2.0", machine=None, platform=None):
    """Runs the loop; returns a dict of arrays (one row per communication point) and the wall
    time [s] of the stepping loop. machine: the platform's FMU start values (None: the thesis
    platform); platform: the same machine as a stewart.Platform, on which a scene's move is
    planned at the step h (None: the thesis platform). duration None: the scene's (a move's
    own; beyond a move's end its goal is held at rest)."""
    machine = machine or {}
    scene = scenes.load(scene) if isinstance(scene, (str, pathlib.Path)) else scene
    fmus = pathlib.Path(fmus)
    t, cue, cue_dot, cue_ddot = scenes.trajectory(scene, platform, h, duration)
    n = len(t) - 1
    # the plant starts on the trajectory: the cue's pose and rates at t = 0
    start = {f"{p}0": v for p, v in zip(POSE, cue[0])}
    start.update({f"{p}_dot0": v for p, v in zip(POSE, cue_dot[0])})
    inverse = Unit(fmus / "StewartPlatform.fmu", "inverse",
                   {"fidelity": fidelity, "derivatives": 1, **machine})
    controller = Unit(fmus / "StewartController.fmu", "controller", {"kp": kp, "kd": kd})
    plant = Unit(fmus / "StewartPlant.fmu", "plant", {"fidelity": fidelity, **start, **machine})
    pose = np.zeros((n + 1, 6))
    force, feed_forward = np.zeros((n + 1, 6)), np.zeros((n + 1, 6))
    wall = time.perf_counter()
    try:
        for j in range(n + 1):
            force[j], pose[j], feed_forward[j] = pd_point(
                inverse, controller, plant, [*cue[j], *cue_dot[j], *cue_ddot[j]])
            if j == n:
                break
            # 3. controller -> plant, then every unit steps to t + h
            plant.set(legs("F"), force[j])
            for unit in (inverse, controller, plant):
                unit.step(t[j], h)
        wall = time.perf_counter() - wall
    finally:
        for unit in (inverse, controller, plant):
            unit.free()
    return {"t": t, "cue": cue, "pose": pose, "force": force, "feed_forward": feed_forward}, wall


# The thesis loop (kp 1e6 N/m, kd 1e4 N s/m on the thesis platform's moving mass per leg): its
# natural frequency and damping ratio, which machine_gains keeps on another machine.
THESIS_KP, THESIS_KD = 1e6, 1e4


def moving_mass_per_leg(platform):
    """(platform + payload mass) / 6 + both leg bodies' masses [kg]: the mass one leg's loop
    moves, roughly (the parameters the platform does not give are the thesis platform's)."""
    import stewart
    values = {p["name"]: p["defaults"][0] for p in stewart.parameters()}
    values.update({k: v for k, v in platform.params.items() if np.ndim(v) == 0})
    return ((values["platform_mass"] + values["payload_mass"]) / 6 + values["cylinder_mass"] +
            values["piston_mass"])


def machine_gains(platform):
    """(kp, kd) with the thesis loop's natural frequency and damping ratio on platform's moving
    mass per leg: kp = m w^2, kd = 2 zeta m w."""
    import stewart
    m0 = moving_mass_per_leg(stewart.Platform())
    omega, zeta = np.sqrt(THESIS_KP / m0), THESIS_KD / (2 * np.sqrt(THESIS_KP * m0))
    m = moving_mass_per_leg(platform)
    return m * omega**2, 2 * zeta * m * omega


def tracking_error(result):
    """Max |achieved - cue| over the run: (position [m], angle [rad])."""
    e = np.abs(result["pose"] - result["cue"])
    return float(e[:, :3].max()), float(e[:, 3:].max())


def write_csv(result, path):
    columns = (["t"] + [f"{p}_cue" for p in POSE] + POSE + [f"F{k}" for k in LEGS] +
               [f"F_ff{k}" for k in LEGS])
    table = np.column_stack([result["t"], result["cue"], result["pose"], result["force"],
                             result["feed_forward"]])
    np.savetxt(path, table, delimiter=",", header=",".join(columns), comments="", fmt="%.17g")


def plot(result, path, unit_text="m,rad"):
    """The run's cue and pose (in unit_text's units), error and forces; returns what each panel
    draws (plots.drawn)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import plots
    units = plots.units(unit_text)
    t = result["t"]
    fig, ax = plt.subplots(4, 1, figsize=(10, 12), sharex=True)
    for i, p in enumerate(POSE):
        a = ax[0] if i < 3 else ax[1]
        f = units.factor(p)
        line, = a.plot(t, result["cue"][:, i] * f, "--", lw=1, label=f"{p} cue")
        a.plot(t, result["pose"][:, i] * f, color=line.get_color(), lw=0.8, label=f"{p} achieved")
    ax[0].set_ylabel(f"position [{units.length}]")
    ax[1].set_ylabel(f"angle [{units.angle}]")
    error = result["pose"] - result["cue"]
    for i, p in enumerate(POSE):
        ax[2].plot(t, error[:, i] * 1e6, lw=0.8, label=p)
    ax[2].set_ylabel("achieved - cue [µm, µrad]")
    for k in range(6):
        ax[3].plot(t, result["force"][:, k], lw=0.8, label=f"F{k + 1}")
    ax[3].set_ylabel("actuator force [N]")
    ax[3].set_xlabel("t [s]")
    for a in ax:
        a.legend(ncol=6, fontsize=7)
        a.grid(alpha=0.3)
    ax[0].set_title("Closed loop: inverse unit (feed-forward) + PD on the leg lengths + plant")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return plots.drawn(ax)


def add_loop_arguments(parser, name, kp_default, kd_default):
    """The loop's --step, --kp, --kd (their defaults as kp_default, kd_default say), --fidelity,
    --fmus, --out (default out/name) and --no-plot."""
    parser.add_argument("--step", type=float, default=1e-3, help="communication step [s]")
    parser.add_argument("--kp", type=float, help=f"[N/m] (default {kp_default})")
    parser.add_argument("--kd", type=float, help=f"[N s/m] (default {kd_default})")
    parser.add_argument("--fidelity", type=int, default=2, choices=(1, 2))
    parser.add_argument("--fmus", default=str(ROOT / "build" / "fmus" / "2.0"))
    parser.add_argument("--out", default=str(ROOT / "out" / name))
    parser.add_argument("--no-plot", action="store_true")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--duration", type=float,
                        help="[s] (default: the scene's; a move's: its own)")
    add_loop_arguments(parser, "closed_loop", "1e6, or machine_gains", "1e4, or machine_gains")
    scenes.add_platform_arguments(parser)
    parser.add_argument("--view", action="store_true",
                        help="also write closed_loop.html: the run in 3D (docs/view.md)")
    import plots
    args, units = plots.parse_args_with_units(parser)
    try:
        scene, platform, machine = scenes.on_platform(scenes.load(args.scene), args)
        kp, kd = machine_gains(platform) if args.platform else (THESIS_KP, THESIS_KD)
        args.kp, args.kd = args.kp or kp, args.kd or kd
        duration = args.duration or ("move" not in scene and scene["duration"]) or None
        result, wall = run(scene, duration, args.step, args.kp, args.kd, args.fidelity,
                           args.fmus, machine, platform)
    except ValueError as e:  # SceneError, stewart.MoveError: the message names the cause
        raise SystemExit(f"closed_loop: {e}") from None
    duration = result["t"][-1]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    write_csv(result, out / "closed_loop.csv")
    if not args.no_plot:
        plot(result, out / "closed_loop.png", args.units)
    if args.view:
        import stewart
        stewart.view(platform, out / "closed_loop.csv", output=out / "closed_loop.html",
                     title=f"closed loop: {scene['name']}")
    position, angle = tracking_error(result)
    print(f"closed_loop: {scene['name']}, {duration:g} s at h = {args.step:g} s, fidelity "
          f"{args.fidelity}, kp = {args.kp:g} N/m, kd = {args.kd:g} N s/m")
    print(f"closed_loop: tracking error max {position * units.factor('x'):.3e} {units.length}, "
          f"{angle * units.factor('roll'):.3e} {units.angle}")
    print(f"closed_loop: wall time {wall:.2f} s, {wall / duration:.3f} s per simulated second")
    print(f"closed_loop: wrote {out / 'closed_loop.csv'}" +
          ("" if args.no_plot else f" and {out / 'closed_loop.png'}"))


if __name__ == "__main__":
    main()
