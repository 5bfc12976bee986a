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
With --player the cue of 1. comes from the scene player unit (StewartScene.fmu) instead, stepped
with the others: its sinusoids, or for a move the planned trajectory written to a file and played
through its trajectory_file, as the OSP and SSP structures run the loop.

With --drive current (a platform with drives) the controller runs its current cascade (output =
1: position -> speed -> current per leg), fed forward with the inverse unit's currents instead of
its forces, and the plant is driven by the currents (input = 1): the same three steps, currents
in place of forces (docs/drives.md, "Closing the loop on currents").

usage: closed_loop.py [--scene combined] [--duration 12] [--step 0.001] [--kp 1e6] [--kd 1e4]
                      [--fidelity 2] [--player] [--fmus build/fmus/2.0] [--out out/closed_loop]
                      [--no-plot]
                      [--platform FILE.json [--scale-to-ranges]] [--units mm,deg]
                      [--drive current [--position-gain 100] [--speed-gain G]
                       [--speed-integral-time 0.04]]

With --platform the units get the machine's parameters (stewart.fmu_start_values), the scene
moves about the machine's home, and the PD gains default to the thesis loop's natural frequency
and damping on the machine's moving mass per leg (machine_gains); the cascade's gains default to
the same loop on the motor's side (cascade_gains).
"""
import argparse
import collections
import math
import pathlib
import shutil
import tempfile
import time

import numpy as np
import fmpy.fmi2
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

import scenes

ROOT = pathlib.Path(__file__).resolve().parents[1]
POSE = list(scenes.POSE)
LEGS = range(1, 7)
DERIVED = POSE + list(scenes.DOT) + list(scenes.DDOT)


def legs(name):
    """['name[1]', ..., 'name[6]']"""
    return [f"{name}[{k}]" for k in LEGS]


class Unit:
    """One FMI 2 co-simulation instance, variables by name, initialised with `parameters` (and
    its real `inputs` set in initialisation mode, when given)."""

    def __init__(self, path, name, parameters, inputs=None):
        md = read_model_description(str(path))
        self.name = name
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.directory = extract(str(path))
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=self.directory,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        # the unit's last messages, for the error of a call it refuses (they name the cause)
        self.messages = collections.deque(maxlen=4)
        callbacks = fmi2CallbackFunctions()
        callbacks.logger = fmi2CallbackLoggerTYPE(
            lambda env, inst, status, category, message: self.messages.append(message.decode()))
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.fmi2.calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.fmi2.free)
        self._callbacks = callbacks  # alive as long as the instance
        self.fmu.instantiate(callbacks=callbacks, loggingOn=True)
        self.fmu.setDebugLogging(True, ["logStatusDiscard", "logStatusError"])  # not per step
        integers = {v.name for v in md.modelVariables if v.type == "Integer"}
        for key, value in parameters.items():
            if isinstance(value, str):
                self.fmu.setString([self.vr[key]], [value])
            elif key in integers:
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
        try:
            self.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        except FMICallException as e:
            raise ValueError(f"unit {self.name}, step from t = {t:.6g} s by {h:.6g} s: "
                             f"{str(e).rstrip('.')}: "
                             + " / ".join(self.messages)) from None

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.directory, ignore_errors=True)


DRIVES = ("force", "current")  # what the controller sends the plant: its output / input 0, 1


def pd_point(inverse, controller, plant, cue, feed_forward="F"):
    """Steps 1 and 2 of the loop at one communication point: the cue (pose, rates and
    accelerations, 18 values) -> the inverse unit; its reference and the plant's measured L, L_dot
    (state only, no feedthrough) -> the controller. Returns the controller's output F (forces,
    or currents in the cascade), the plant's pose and the feed-forward (the inverse's outputs
    named feed_forward: F, or current) at this point."""
    inverse.set(POSE + list(scenes.DOT) + list(scenes.DDOT), cue)
    reference = inverse.get(legs("L") + legs("L_dot") + legs(feed_forward))
    measured = plant.get(legs("L") + legs("L_dot"))
    controller.set(legs("L_ref") + legs("L_dot_ref") + legs("F_ff") + legs("L") + legs("L_dot"),
                   [*reference, *measured])
    return controller.get(legs("F")), plant.get(POSE), reference[12:]


def run(scene="combined", duration=12.0, h=1e-3, kp=1e6, kd=1e4, fidelity=2,
        fmus=ROOT / "build" / "fmus" / "2.0", machine=None, platform=None, drive="force",
        cascade=None, player=False):
    """Runs the loop; returns a dict of arrays (one row per communication point) and the wall
    time [s] of the stepping loop. machine: the platform's FMU start values (None: the thesis
    platform); platform: the same machine as a stewart.Platform, on which a scene's move is
    planned at the step h (None: the thesis platform). duration None: the scene's (a move's
    own; beyond a move's end its goal is held at rest). drive "current": the controller's
    cascade with the gains `cascade` (cascade_gains' dict; default: cascade_gains(platform))
    drives the plant with currents; "force" (the default): the PD with kp, kd, forces. The
    result's "force" column holds what the controller sent (currents [A] with "current").
    player: the cue comes from the scene player unit (StewartScene.fmu) stepped with the others,
    as libcosim and SSP masters run the loop (a move's trajectory through its trajectory_file);
    else from the scene sampled in Python. The two give the same cue at the communication
    points."""
    machine = machine or {}
    if drive not in DRIVES:
        raise ValueError(f"drive = {drive!r}: give one of {', '.join(DRIVES)}")
    scene = scenes.load(scene) if isinstance(scene, (str, pathlib.Path)) else scene
    fmus = pathlib.Path(fmus)
    t, cue, cue_dot, cue_ddot = scenes.trajectory(scene, platform, h, duration)
    n = len(t) - 1
    # the plant starts on the trajectory: the cue's pose and rates at t = 0
    start = {f"{p}0": v for p, v in zip(POSE, cue[0])}
    start.update({f"{p}_dot0": v for p, v in zip(POSE, cue_dot[0])})
    inverse = Unit(fmus / "StewartPlatform.fmu", "inverse",
                   {"fidelity": fidelity, "derivatives": 1, **machine})
    controls = {"kp": kp, "kd": kd}
    feed_forward_name = "F"
    if drive == "current":
        controls = controller_parameters(platform, machine, cascade)
        feed_forward_name = "current"
    controller = Unit(fmus / "StewartController.fmu", "controller", controls)
    plant = Unit(fmus / "StewartPlant.fmu", "plant",
                 {"fidelity": fidelity, **start, **machine, "input": DRIVES.index(drive)})
    units = [inverse, controller, plant]
    if player:
        folder = tempfile.TemporaryDirectory()
        units.append(Unit(fmus / "StewartScene.fmu", "scene",
                          scenes.player_values(scene, pathlib.Path(folder.name) / "scene.csv",
                                               platform, h, duration)))
        cue, cue_dot, cue_ddot = (np.zeros((n + 1, 6)) for _ in range(3))
    pose = np.zeros((n + 1, 6))
    force, feed_forward = np.zeros((n + 1, 6)), np.zeros((n + 1, 6))
    wall = time.perf_counter()
    try:
        for j in range(n + 1):
            if player:  # 1. the cue from the scene player unit
                cue[j], cue_dot[j], cue_ddot[j] = units[3].get(DERIVED).reshape(3, 6)
            force[j], pose[j], feed_forward[j] = pd_point(
                inverse, controller, plant, [*cue[j], *cue_dot[j], *cue_ddot[j]],
                feed_forward_name)
            if j == n:
                break
            # 3. controller -> plant, then every unit steps to t + h
            plant.set(legs("F"), force[j])
            for unit in units:
                unit.step(t[j], h)
        wall = time.perf_counter() - wall
    finally:
        for unit in units:
            unit.free()
        if player:
            folder.cleanup()
    return {"t": t, "cue": cue, "pose": pose, "force": force, "feed_forward": feed_forward,
            "drive": drive}, wall


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


# The cascade's gains (the controller's parameters of these names; cascade_gains gives them).
CASCADE_GAINS = ("position_gain", "speed_gain", "speed_integral_time")
# The drive parameters the controller's cascade takes, named as the platform's.
CASCADE_DRIVE = ("screw_lead", "gear_ratio", "torque_constant", "current_max", "motor_speed_max")


def motor_per_leg(platform):
    """Each leg's motor angle per leg length, c = 2 pi N / lead [rad/m] (docs/drives.md)."""
    values = leg_values(platform)
    return 2 * np.pi * values["gear_ratio"] / values["screw_lead"]


def leg_values(platform):
    """The per-leg parameters of platform (six values each: the drives' among them), defaults
    filled in and per-leg elements (gear_ratio[2]) applied."""
    import stewart
    counts = {p["name"]: p["count"] for p in stewart.parameters()}
    return {name: values for name, values in stewart.params.parameter_values(platform.params).items()
            if counts[name] == 6}


def require_drives(platform):
    """ValueError unless every leg of platform has a drive (screw_lead > 0)."""
    if platform is None or not np.all(leg_values(platform)["screw_lead"] > 0):
        raise ValueError("drive = current needs a platform with a drive on every leg "
                         "(screw_lead > 0, e.g. platforms/*_drives.json)")


def cascade_gains(platform):
    """The current cascade's gains with the thesis loop's dynamics on platform's legs, as
    machine_gains does for the PD: the PD F = kp e + kd e_dot on the moving mass m per leg is a
    speed loop of bandwidth w_v = kd / m around a position loop of gain kp / kd. On the motor's
    side the speed loop moves J_total = J + m / c^2 (the drive's own inertia J and the leg's
    share of the platform, c = 2 pi N / lead), so speed_gain = J_total w_v; the integral time
    4 / position_gain puts the integral's corner a quarter below the position loop's. With legs
    of different drives the smallest J_total sets the gain (the fastest loop stays stable)."""
    import stewart
    require_drives(platform)
    m0 = moving_mass_per_leg(stewart.Platform())
    speed_bandwidth, position_gain = THESIS_KD / m0, THESIS_KP / THESIS_KD
    c = motor_per_leg(platform)
    inertia = np.asarray(platform.reflected_mass) / c**2 + moving_mass_per_leg(platform) / c**2
    return {"position_gain": position_gain, "speed_gain": float(inertia.min() * speed_bandwidth),
            "speed_integral_time": 4.0 / position_gain}


def controller_parameters(platform, machine, cascade=None):
    """The controller's parameters for the current cascade on platform (its FMU start values
    `machine`): output = 1, the gains (default cascade_gains), each leg's drive."""
    import stewart
    require_drives(platform)
    machine = machine or stewart.fmu_start_values(platform)
    drive = {name: value for name, value in machine.items()
             if name.split("[")[0] in CASCADE_DRIVE}
    return {"output": 1, **(cascade or cascade_gains(platform)), **drive}


def tracking_error(result):
    """Max |achieved - cue| over the run: (position [m], angle [rad])."""
    e = np.abs(result["pose"] - result["cue"])
    return float(e[:, :3].max()), float(e[:, 3:].max())


def write_csv(result, path):
    name = "F" if result.get("drive", "force") == "force" else "current"
    columns = (["t"] + [f"{p}_cue" for p in POSE] + POSE + [f"{name}{k}" for k in LEGS] +
               [f"{name}_ff{k}" for k in LEGS])
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
    current = result.get("drive", "force") == "current"
    for k in range(6):
        ax[3].plot(t, result["force"][:, k], lw=0.8, label=f"{'i' if current else 'F'}{k + 1}")
    ax[3].set_ylabel("motor current [A]" if current else "actuator force [N]")
    ax[3].set_xlabel("t [s]")
    for a in ax:
        a.legend(ncol=6, fontsize=7)
        a.grid(alpha=0.3)
    loop = "current cascade per leg" if current else "PD on the leg lengths"
    ax[0].set_title(f"Closed loop: inverse unit (feed-forward) + {loop} + plant")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return plots.drawn(ax)


def cascade_arguments(parser, args, platform):
    """The cascade's gains the command line asks for (cascade_gains where not given), None for
    the force loop; refuses a gain out of range or given to the force loop, and --drive current
    without a platform with drives (ValueError)."""
    given = [f"--{name.replace('_', '-')}" for name in CASCADE_GAINS
             if getattr(args, name) is not None]
    if given and args.drive != "current":
        parser.error(f"{', '.join(given)}: the cascade's gains, for --drive current only")
    for name in given:
        value = getattr(args, name[2:].replace("-", "_"))
        if not (np.isfinite(value) and (value > 0 if name == "--speed-gain" else value >= 0)):
            parser.error(f"{name} = {value:g}: a gain is finite and >= 0 (the speed gain > 0)")
    if args.drive != "current":
        return None
    if not args.platform:
        raise ValueError("--drive current needs --platform with drives (platforms/*_drives.json)")
    cascade = cascade_gains(platform)
    for name in cascade:
        value = getattr(args, name)
        cascade[name] = cascade[name] if value is None else value
    args.cascade = cascade
    return cascade


def seconds(text):
    """A time span [s] of the command line: a finite number > 0."""
    value = float(text)
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"{text}: give a finite time > 0 [s]")
    return value


def add_loop_arguments(parser, name, kp_default, kd_default):
    """The loop's --step, --kp, --kd (their defaults as kp_default, kd_default say), --fidelity,
    --fmus, --out (default out/name) and --no-plot."""
    parser.add_argument("--step", type=seconds, default=1e-3, help="communication step [s]")
    parser.add_argument("--kp", type=float, help=f"[N/m] (default {kp_default})")
    parser.add_argument("--kd", type=float, help=f"[N s/m] (default {kd_default})")
    parser.add_argument("--fidelity", type=int, default=2, choices=(1, 2))
    parser.add_argument("--fmus", default=str(ROOT / "build" / "fmus" / "2.0"))
    parser.add_argument("--out", default=str(ROOT / "out" / name))
    parser.add_argument("--no-plot", action="store_true")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="combined")
    parser.add_argument("--duration", type=seconds,
                        help="[s] (default: the scene's; a move's: its own)")
    add_loop_arguments(parser, "closed_loop", "1e6, or machine_gains", "1e4, or machine_gains")
    parser.add_argument("--drive", default="force", choices=DRIVES,
                        help="what the controller sends the plant: forces (PD) or motor "
                             "currents (the cascade; needs --platform with drives)")
    parser.add_argument("--position-gain", type=float,
                        help="--drive current: [1/s] (default: cascade_gains)")
    parser.add_argument("--speed-gain", type=float,
                        help="--drive current: [N m s/rad] (default: cascade_gains)")
    parser.add_argument("--speed-integral-time", type=float,
                        help="--drive current: [s], 0 for none (default: cascade_gains)")
    parser.add_argument("--player", action="store_true",
                        help="the cue from the scene player unit (StewartScene.fmu, a move "
                             "through its trajectory_file) stepped with the others, as the "
                             "OSP and SSP structures run the loop")
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
        if duration is not None and duration < args.step:
            parser.error(f"--duration = {duration:g} s is shorter than one --step "
                         f"({args.step:g} s): run at least one step")
        cascade = cascade_arguments(parser, args, platform)
        result, wall = run(scene, duration, args.step, args.kp, args.kd, args.fidelity,
                           args.fmus, machine, platform, args.drive, cascade, args.player)
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
    gains = (f"kp = {args.kp:g} N/m, kd = {args.kd:g} N s/m" if args.drive == "force" else
             "current cascade: position_gain = {position_gain:g} 1/s, speed_gain = {speed_gain:g} "
             "N m s/rad, speed_integral_time = {speed_integral_time:g} s".format(**args.cascade))
    print(f"closed_loop: {scene['name']}, {duration:g} s at h = {args.step:g} s, fidelity "
          f"{args.fidelity}, {gains}")
    print(f"closed_loop: tracking error max {position * units.factor('x'):.3e} {units.length}, "
          f"{angle * units.factor('roll'):.3e} {units.angle}")
    print(f"closed_loop: wall time {wall:.2f} s" + (f", {wall / duration:.3f} s per simulated "
                                                 "second" if duration > 0 else ""))
    print(f"closed_loop: wrote {out / 'closed_loop.csv'}" +
          ("" if args.no_plot else f" and {out / 'closed_loop.png'}"))


if __name__ == "__main__":
    main()
