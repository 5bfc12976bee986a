"""Cost of StewartPlantME's fmi3GetAdjointDerivative over its 18 knowns (12 states, 6 forces) and
30 unknowns (state derivatives, lengths, rates, base wrench), and of the 18 directional
derivatives of a column-by-column Jacobian: median microseconds per call through fmpy (the same
Python overhead in every row). The state moves by 1e-9 m before every call (untimed), so that no
call finds the linearisation of the one before. With --reference FMU (an older StewartPlantME.fmu,
FMI 3) the two units alternate call by call in one run, with the ratios.
usage: me_adjoint.py FMU [--reference FMU] [--calls N (200)]"""
import argparse
import ctypes
import statistics
import time

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi3 import FMU3Model


def unit(path):
    md = read_model_description(path)
    fmu = FMU3Model(guid=md.guid, unzipDirectory=extract(path),
                    modelIdentifier=md.modelExchange.modelIdentifier, instanceName="bench")
    fmu.instantiate()
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    fmu.updateDiscreteStates()
    fmu.enterContinuousTimeMode()
    vr = {v.name: v.valueReference for v in md.modelVariables}
    pose = ["x", "y", "z", "roll", "pitch", "yaw"]
    states = pose + [p + "_dot" for p in pose]
    forces = [f"F[{k}]" for k in range(1, 7)]
    unknowns = ([p + "_dot" for p in pose] + [p + "_ddot" for p in pose]
                + [f"L[{k}]" for k in range(1, 7)] + [f"L_dot[{k}]" for k in range(1, 7)]
                + [f"base_{w}[{i}]" for w in ("force", "torque") for i in (1, 2, 3)])
    x = np.array([0.01, -0.02, 0.5, 0.03, -0.02, 0.05, 0.1, 0.05, -0.1, 0.2, -0.1, 0.3])
    fmu.setContinuousStates(x.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), len(x))
    fmu.setFloat64([vr[f] for f in forces], [900.0, 950.0, 920.0, 910.0, 940.0, 930.0])
    return fmu, [vr[n] for n in unknowns], [vr[n] for n in states + forces], x


def adjoint_call(u):
    fmu, unknowns, knowns, _ = u
    seed = [1.0] * len(unknowns)
    return lambda: fmu.getAdjointDerivative(unknowns, knowns, seed, nSensitivity=len(knowns))


def columns_call(u):
    fmu, unknowns, knowns, _ = u
    seeds = np.eye(len(knowns))
    return lambda: [fmu.getDirectionalDerivative(unknowns, knowns, list(s)) for s in seeds]


def moved(u, n):
    """The state x + n 1e-9 m along x."""
    fmu, _, _, x = u
    y = x.copy()
    y[0] += 1e-9 * n
    fmu.setContinuousStates(y.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), len(y))


def timed(call):
    t0 = time.perf_counter()
    call()
    return 1e6 * (time.perf_counter() - t0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fmu")
    ap.add_argument("--reference")
    ap.add_argument("--calls", type=int, default=200)
    a = ap.parse_args()
    units = {"current": unit(a.fmu)}
    if a.reference:
        units["reference"] = unit(a.reference)
    for row, make in (("adjoint, 18 knowns x 30 unknowns", adjoint_call),
                      ("Jacobian by 18 directional derivatives", columns_call)):
        calls = {name: make(u) for name, u in units.items()}
        samples = {name: [] for name in units}
        for n in range(a.calls):
            for name, call in calls.items():
                moved(units[name], n % 2)
                samples[name].append(timed(call))
        medians = {name: statistics.median(s) for name, s in samples.items()}
        text = ", ".join(f"{name} {m:.0f} us" for name, m in medians.items())
        if a.reference:
            text += f", ratio {medians['reference'] / medians['current']:.2f}"
        print(f"{row}: median of {a.calls}: {text}")


if __name__ == "__main__":
    main()
