#!/usr/bin/env python3
"""Closed loop of a vehicle's motion in fmpy: cueing unit (StewartCueing.fmu) -> inverse unit
(StewartPlatform.fmu) -> controller (StewartController.fmu) -> plant (StewartPlant.fmu), FMI 2
co-simulation at fixed communication steps on one machine (docs/cueing.md, docs/closed-loop.md).
Writes OUT/cueing_loop.csv (cue, achieved pose, forces) and OUT/cueing_loop.png.

The vehicle's samples (a manoeuvre file, 100 Hz) are interpolated linearly to the loop's steps.
At each communication point t_j (the Gauss-Seidel order of scripts/closed_loop.py; neither the
cueing unit nor the plant has direct feedthrough, so the loop has no algebraic part):
  1. the cueing unit's pose with its exact rates and accelerations at t_j -> the inverse unit
     (derivatives = 1): L_ref, L_dot_ref, F_ff;
  2. the plant's L and L_dot at t_j -> the controller, with 1.: F;
  3. F -> the plant; the vehicle's sample at t_j+1 -> the cueing unit (its input is held over the
     step that ends at the sample, as stewart.cueing takes it); every unit steps to t_j+1.
Each step is t_j+1 - t_j (exact, t_j = t_0 + j h), the dt stewart.cueing takes from the same
samples: the cue is then the library's, bit for bit.

usage: cueing_loop.py (VEHICLE.csv | --manoeuvre NAME) --platform FILE [--option NAME=VALUE ...]
                      [--duration S] [--step 0.001] [--kp KP] [--kd KD] [--fidelity 2]
                      [--fmus build/fmus/2.0] [--out out/cueing_loop] [--no-plot] [--osp DIR]

The same loop runs in libcosim from osp_structure, the vehicle's recorded samples given as the
events of a libcosim scenario (libcosim_scenario; --osp writes both files), and in ecos from
write_ssp with the vehicle held.

The PD gains default to closed_loop.machine_gains (the thesis loop's natural frequency and
damping on the machine's moving mass per leg).
"""
import argparse
import pathlib
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

import closed_loop
import cueing as cueing_script
import stewart
from closed_loop import POSE, Unit, legs

ROOT = pathlib.Path(__file__).resolve().parents[1]
DOT = [f"{p}_dot" for p in POSE]
DDOT = [f"{p}_ddot" for p in POSE]
INPUTS = [f"specific_force[{i}]" for i in (1, 2, 3)] + [f"angular_velocity[{i}]" for i in (1, 2, 3)]


def vehicle_at(t, t_vehicle, specific_force, angular_velocity):
    """The vehicle's specific force and angular velocity at the times t, linearly interpolated
    (held at the ends), as (N, 6)."""
    columns = np.hstack([specific_force, angular_velocity])
    return np.column_stack([np.interp(t, t_vehicle, columns[:, i]) for i in range(6)])


def run(platform, t_vehicle, specific_force, angular_velocity, options=None, duration=None,
        h=1e-3, kp=None, kd=None, fidelity=2, fmus=ROOT / "build" / "fmus" / "2.0"):
    """Runs the loop; returns a dict of arrays (one row per communication point: t, vehicle (the
    inputs), cue, cue_rate, cue_accel, pose, force, feed_forward) and the wall time [s]."""
    options = dict(options or {})
    t, vehicle = vehicle_samples(t_vehicle, specific_force, angular_velocity, h, duration)
    n = len(t) - 1
    gains = closed_loop.machine_gains(platform)
    kp, kd = gains[0] if kp is None else kp, gains[1] if kd is None else kd
    fmus = pathlib.Path(fmus)
    machine = stewart.fmu_start_values(platform)
    units = []
    try:
        cueing = Unit(fmus / "StewartCueing.fmu", "cueing", {**machine, **options},
                      dict(zip(INPUTS, vehicle[0])))
        units.append(cueing)
        cue0 = cueing.get(POSE + DOT)
        start = {**stewart.fmu_start_values(platform, model="StewartPlant"),
                 **{f"{p}0": v for p, v in zip(POSE, cue0[:6])},
                 **{f"{p}_dot0": v for p, v in zip(POSE, cue0[6:])}}
        inverse = Unit(fmus / "StewartPlatform.fmu", "inverse",
                       {"fidelity": fidelity, "derivatives": 1, **machine})
        units.append(inverse)
        controller = Unit(fmus / "StewartController.fmu", "controller", {"kp": kp, "kd": kd})
        units.append(controller)
        plant = Unit(fmus / "StewartPlant.fmu", "plant", {"fidelity": fidelity, **start})
        units.append(plant)
        cue = np.zeros((n + 1, 18))
        pose, force, feed_forward = (np.zeros((n + 1, 6)) for _ in range(3))
        wall = time.perf_counter()
        for j in range(n + 1):
            # 1. and 2. cue -> inverse unit; plant and reference -> controller
            cue[j] = cueing.get(POSE + DOT + DDOT)
            force[j], pose[j], feed_forward[j] = closed_loop.pd_point(inverse, controller, plant,
                                                                      cue[j])
            if j == n:
                break
            # 3. controller -> plant, the next vehicle sample -> cueing unit, every unit steps
            plant.set(legs("F"), force[j])
            cueing.set(INPUTS, vehicle[j + 1])
            for unit in units:  # t[j + 1] - t[j]: the library's dt for the same samples
                unit.step(t[j], t[j + 1] - t[j])
        wall = time.perf_counter() - wall
    finally:
        for unit in units:
            unit.free()
    return {"t": t, "vehicle": vehicle, "cue": cue[:, :6], "cue_rate": cue[:, 6:12],
            "cue_accel": cue[:, 12:], "pose": pose, "force": force,
            "feed_forward": feed_forward}, wall


def vehicle_samples(t_vehicle, specific_force, angular_velocity, h=1e-3, duration=None):
    """The vehicle at the loop's communication points t_j = t_0 + j h (linearly interpolated, as
    run takes it): (t, (N + 1, 6) inputs)."""
    duration = t_vehicle[-1] - t_vehicle[0] if duration is None else duration
    t = t_vehicle[0] + np.arange(int(round(duration / h)) + 1) * h
    return t, vehicle_at(t, t_vehicle, specific_force, angular_velocity)


def vehicle_events(t, vehicle):
    """A recorded vehicle signal as the structures' events, (time from the start [s], cueing
    unit's input, value) per input and step: at t_j the sample of t_j+1, which the cueing unit
    then holds over the step that ends at it (the loop of run, and stewart.cueing of the same
    samples); the first sample is the structure's start value (osp_structure's inputs)."""
    return [(float(t[j] - t[0]), name, float(vehicle[j + 1, i]))
            for j in range(len(t) - 1) for i, name in enumerate(INPUTS)]


def libcosim_scenario(t, vehicle):
    """vehicle_events as a libcosim scenario (JSON text: CosimExecution.load_scenario with a
    scenario manager), each an override of the cueing unit's input."""
    import json
    events = [{"time": time, "model": "cueing", "variable": name, "action": "override",
               "value": value} for time, name, value in vehicle_events(t, vehicle)]
    return json.dumps({"description": "a recorded vehicle signal at the cueing unit's inputs",
                       "events": events, "end": float(t[-1] - t[0])})


def osp_structure(platform, options, inputs, fmus=ROOT / "build" / "fmus" / "2.0"):
    """The loop as an OSP system structure for libcosim (CosimExecution.from_osp_config_file), as
    an ElementTree root: scenes/closed_loop's structure with the scene player replaced by the
    cueing unit (its outputs have the scene player's names), the machine's parameters, the cueing
    options, the vehicle's specific force and angular velocity `inputs` (6 values) from t = 0
    (held, or the first sample of a recorded signal whose others come as the events of
    libcosim_scenario), the PD gains of closed_loop.machine_gains and the plant
    started at home; the FMI 2 units of the folder fmus. libcosim steps every unit from the values
    of the last step (docs/closed-loop.md)."""
    import machine_ssp
    import osp_to_ssd
    kp, kd = closed_loop.machine_gains(platform)
    machine = stewart.fmu_start_values(platform)
    values = {"cueing": {**machine, **options, **dict(zip(INPUTS, map(float, inputs)))},
              "inverse": {"fidelity": 2, "derivatives": 1, **machine},
              "controller": {"kp": kp, "kd": kd},
              "plant": {"fidelity": 2, **stewart.fmu_start_values(platform, model="StewartPlant")}}
    integers = {"algorithm", "translation_order", "rotation_filter_order"}
    values["cueing"].update({k: int(v) for k, v in values["cueing"].items() if k in integers})
    ns = {"o": osp_to_ssd.OSP}
    template = machine_ssp.osp_structure({**values, "scene": {}}, pathlib.Path(fmus))
    for simulator in template.findall("o:Simulators/o:Simulator", ns):
        if simulator.get("name") == "scene":
            simulator.set("name", "cueing")
            simulator.set("source", str(pathlib.Path(fmus) / "StewartCueing.fmu"))
            initial = simulator.find("o:InitialValues", ns)
            for variable, value in values["cueing"].items():
                entry = ET.SubElement(initial, f"{{{osp_to_ssd.OSP}}}InitialValue",
                                      {"variable": variable})
                kind, text = machine_ssp.typed(value)
                ET.SubElement(entry, f"{{{osp_to_ssd.OSP}}}{kind}", {"value": text})
    for variable in template.findall("o:Connections/o:VariableConnection/o:Variable", ns):
        if variable.get("simulator") == "scene":
            variable.set("simulator", "cueing")
    return template


def write_ssp(platform, options, inputs, out, fmus=ROOT / "build" / "fmus" / "2.0",
              stop_time=10.0):
    """The loop of osp_structure as an SSP archive at out (SystemStructure.ssd written by
    scripts/osp_to_ssd.py: the parameter set "initialValues", every input connector's start
    value, a default experiment to stop_time [s]; the FMI 2 units of fmus as resources), for SSP
    masters (ecos: init(parameter_set="initialValues"))."""
    import tempfile
    import zipfile

    import osp_to_ssd
    fmus = pathlib.Path(fmus)
    with tempfile.TemporaryDirectory() as folder:
        osp_path = pathlib.Path(folder) / "cueing_loop" / "OspSystemStructure.xml"
        osp_path.parent.mkdir()
        ET.ElementTree(osp_structure(platform, options, inputs, fmus)).write(
            osp_path, encoding="utf-8", xml_declaration=True)
        ssd = osp_to_ssd.convert(osp_path, stop_time)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("SystemStructure.ssd", ssd)
        for unit in ("StewartCueing", "StewartPlatform", "StewartController", "StewartPlant"):
            archive.write(fmus / f"{unit}.fmu", f"resources/{unit}.fmu")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    cueing_script.add_vehicle_arguments(parser)
    parser.add_argument("--duration", type=closed_loop.seconds,
                        help="[s] (default: the vehicle's)")
    closed_loop.add_loop_arguments(parser, "cueing_loop", "closed_loop.machine_gains",
                                   "closed_loop.machine_gains")
    parser.add_argument("--osp", metavar="DIR",
                        help="also write the loop's OSP structure (OspSystemStructure.xml) with "
                             "the vehicle as a libcosim scenario (vehicle_scenario.json) to DIR")
    args = parser.parse_args(argv)
    t, f, w, platform, options = cueing_script.vehicle_of(args, parser, "cueing_loop.py")
    try:
        result, wall = run(platform, t, f, w, options, args.duration, args.step, args.kp,
                           args.kd, args.fidelity, args.fmus)
    except ValueError as e:  # a unit's refusal: its message names the cause
        raise SystemExit(f"cueing_loop: {e}") from None
    if args.osp:
        osp = pathlib.Path(args.osp)
        osp.mkdir(parents=True, exist_ok=True)
        steps, vehicle = vehicle_samples(t, f, w, args.step, args.duration)
        structure = osp_structure(platform, options, vehicle[0], pathlib.Path(args.fmus).resolve())
        ET.ElementTree(structure).write(osp / "OspSystemStructure.xml", encoding="utf-8",
                                        xml_declaration=True)
        (osp / "vehicle_scenario.json").write_text(libcosim_scenario(steps, vehicle))
        print(f"cueing_loop: wrote {osp / 'OspSystemStructure.xml'} and "
              f"{osp / 'vehicle_scenario.json'}")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    closed_loop.write_csv(result, out / "cueing_loop.csv")
    if not args.no_plot:
        closed_loop.plot(result, out / "cueing_loop.png")
    position, angle = closed_loop.tracking_error(result)
    duration = result["t"][-1] - result["t"][0]
    print(f"cueing_loop: {args.manoeuvre or args.vehicle} on {args.platform}, {duration:g} s at "
          f"h = {args.step:g} s")
    print(f"cueing_loop: tracking error max {position:.3e} m, {angle:.3e} rad")
    print(f"cueing_loop: wall time {wall:.2f} s" + (f", {wall / duration:.3f} s per simulated "
                                                 "second" if duration > 0 else ""))
    print(f"cueing_loop: wrote {out / 'cueing_loop.csv'}" +
          ("" if args.no_plot else f" and {out / 'cueing_loop.png'}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
