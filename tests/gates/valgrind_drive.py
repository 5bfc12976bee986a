"""The simulations tests/gates/valgrind_fmu.sh runs under valgrind: fmpy's simulate_fmu over a
combined manoeuvre, then the edge paths through fmpy's slave classes.

The plant (StewartPlant.fmu) runs a short forced motion at both fidelities with its edge paths
(a NaN force, a refused step, FMU state get/set/serialise). The Model Exchange plant
(StewartPlantME.fmu) runs under fmpy's CVODE with forces, then its refused derivatives (pitch at
90 degrees, a NaN force) and an FMU state round trip. The cueing unit (StewartCueing.fmu) runs a
vehicle signal that makes its limiter act, a NaN input and an FMU state round trip. The scene
player (StewartScene.fmu) plays a trajectory file and refuses a bad one.

usage: valgrind_drive.py BUILD_DIR (the FMUs are BUILD_DIR/fmus/<version>/StewartPlatform.fmu and
StewartPlant.fmu)"""
import math
import sys
import tempfile
from ctypes import POINTER, c_double

import numpy as np
import fmpy
from fmpy import simulate_fmu
from fmpy.fmi2 import FMU2Model, FMU2Slave
from fmpy.fmi3 import FMU3Model, FMU3Slave

build = sys.argv[1]


def manoeuvre():
    t = np.linspace(0.0, 0.5, 51)
    return np.array([(ti, 0.5 + 0.04 * math.sin(5 * ti), 0.17 * math.sin(5 * ti),
                      0.1 * math.sin(3 * ti), 0.17 * math.cos(5 * ti)) for ti in t],
                    dtype=[("time", float), ("z", float), ("roll", float), ("pitch", float),
                           ("yaw", float)])


def edges(path, version):
    md = fmpy.read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    d = tempfile.mkdtemp()
    fmpy.extract(path, d)
    cls = FMU2Slave if version == "2.0" else FMU3Slave
    fmu = cls(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
              instanceName="vg")
    fmu.instantiate(loggingOn=True)
    set_real = fmu.setReal if version == "2.0" else fmu.setFloat64
    get_real = fmu.getReal if version == "2.0" else fmu.getFloat64
    set_int = fmu.setInteger if version == "2.0" else fmu.setInt32
    set_int([vr["fidelity"]], [1])
    if version == "2.0":
        fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    dll, c = fmu.dll, fmu.component
    do_step = (lambda t, h: dll.fmi2DoStep(c, t, h, 1)) if version == "2.0" else None
    if do_step is None:
        from ctypes import byref
        from fmpy.fmi3 import fmi3Boolean, fmi3Float64
        flags = [fmi3Boolean() for _ in range(3)]
        last = fmi3Float64()
        do_step = lambda t, h: dll.fmi3DoStep(c, t, h, fmi3Boolean(True), byref(flags[0]),
                                              byref(flags[1]), byref(flags[2]), byref(last))
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"
               and v.type in ("Real", "Float64")]
    t = 0.0
    for j, (name, value) in enumerate([("yaw", 0.2), ("x", math.nan), ("x", 0.0),
                                       ("yaw", math.pi / 2), ("yaw", 0.1), ("z", 0.9),
                                       ("z", 0.5)]):
        set_real([vr[name]], [value])
        s = do_step(t, 0.01)
        values = get_real(outputs)
        assert all(math.isfinite(v) for v in values), (name, value)
        if s in (0, 1):
            t += 0.01
    assert do_step(t, 0.0) == 3 and do_step(t, -1.0) == 3
    state = fmu.getFMUstate() if version == "2.0" else fmu.getFMUState()
    blob = (fmu.serializeFMUstate if version == "2.0" else fmu.serializeFMUState)(state)
    other = (fmu.deSerializeFMUstate if version == "2.0" else fmu.deserializeFMUState)(blob)
    (fmu.setFMUstate if version == "2.0" else fmu.setFMUState)(other)
    (fmu.freeFMUstate if version == "2.0" else fmu.freeFMUState)(other)
    (fmu.freeFMUstate if version == "2.0" else fmu.freeFMUState)(state)
    fmu.terminate()
    fmu.reset()
    fmu.freeInstance()
    return t


def fidelity_available(path, version, fidelity):
    """Exit initialisation at that fidelity succeeds (the instance is freed either way: fmpy's
    simulate_fmu does not free an instance whose initialisation failed)."""
    md = fmpy.read_model_description(path)
    d = tempfile.mkdtemp()
    fmpy.extract(path, d)
    cls = FMU2Slave if version == "2.0" else FMU3Slave
    fmu = cls(guid=md.guid, unzipDirectory=d, modelIdentifier=md.coSimulation.modelIdentifier,
              instanceName="probe")
    fmu.instantiate()
    try:
        vr = {v.name: v.valueReference for v in md.modelVariables}
        (fmu.setInteger if version == "2.0" else fmu.setInt32)([vr["fidelity"]], [fidelity])
        if version == "2.0":
            fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        return True
    except Exception:
        return False
    finally:
        fmu.freeInstance()


def plant(path, version, fidelity):
    """50 forced steps of 1 ms, a NaN force (Discard), an over-long step with one internal step
    allowed (Discard), a state round trip; returns the final z."""
    md = fmpy.read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    cls = FMU2Slave if version == "2.0" else FMU3Slave
    fmu = cls(guid=md.guid, unzipDirectory=fmpy.extract(path, tempfile.mkdtemp()),
              modelIdentifier="StewartPlant", instanceName="vg_plant")
    fmu.instantiate(loggingOn=True)
    set_real = fmu.setReal if version == "2.0" else fmu.setFloat64
    get_real = fmu.getReal if version == "2.0" else fmu.getFloat64
    (fmu.setInteger if version == "2.0" else fmu.setInt32)([vr["fidelity"], vr["max_internal_steps"]],
                                                           [fidelity, 50])
    if version == "2.0":
        fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    forces = [vr[f"F[{k}]"] for k in range(1, 7)]
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"
               and v.type in ("Real", "Float64")]
    state = fmu.getFMUstate() if version == "2.0" else fmu.getFMUState()
    for j in range(50):
        set_real(forces, [200.0 + 20.0 * math.sin(3 * j * 1e-3 + k) for k in range(6)])
        if version == "2.0":
            fmu.setRealInputDerivatives(forces, [1] * 6, [60.0] * 6)
        fmu.doStep(j * 1e-3, 1e-3)
        assert all(math.isfinite(v) for v in get_real(outputs))
    t = 0.05
    for bad_force, h in ((math.nan, 1e-3), (200.0, 10.0)):
        set_real(forces, [bad_force] * 6)
        if version == "2.0":
            status = fmu.dll.fmi2DoStep(fmu.component, t, h, 1)
        else:
            from ctypes import byref
            from fmpy.fmi3 import fmi3Boolean, fmi3Float64
            flags, last = [fmi3Boolean() for _ in range(3)], fmi3Float64()
            status = fmu.dll.fmi3DoStep(fmu.component, t, h, fmi3Boolean(True), byref(flags[0]),
                                        byref(flags[1]), byref(flags[2]), byref(last))
        assert status == 2, status
        assert all(math.isfinite(v) for v in get_real(outputs))
    blob = (fmu.serializeFMUstate if version == "2.0" else fmu.serializeFMUState)(state)
    other = (fmu.deSerializeFMUstate if version == "2.0" else fmu.deserializeFMUState)(blob)
    (fmu.setFMUstate if version == "2.0" else fmu.setFMUState)(other)
    for s in (other, state):
        (fmu.freeFMUstate if version == "2.0" else fmu.freeFMUState)(s)
    z = get_real([vr["z"]])[0]
    fmu.terminate()
    fmu.reset()
    fmu.freeInstance()
    return z


def initialised(path, version, classes, instance_name, identifier):
    """(fmu, value references by name, FMI 2?): an instance of classes[0] (FMI 2) or classes[1]
    (FMI 3) of the unit at path, through its initialisation with its start values."""
    md = fmpy.read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    v2 = version == "2.0"
    fmu = classes[0 if v2 else 1](guid=md.guid, instanceName=instance_name,
                                  unzipDirectory=fmpy.extract(path, tempfile.mkdtemp()),
                                  modelIdentifier=identifier)
    fmu.instantiate(loggingOn=True)
    if v2:
        fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    return fmu, vr, v2


def round_trip_and_free(fmu, v2, state):
    """The FMU state serialised, deserialised and set; both states freed, the instance too."""
    blob = (fmu.serializeFMUstate if v2 else fmu.serializeFMUState)(state)
    other = (fmu.deSerializeFMUstate if v2 else fmu.deserializeFMUState)(blob)
    (fmu.setFMUstate if v2 else fmu.setFMUState)(other)
    for s in (other, state):
        (fmu.freeFMUstate if v2 else fmu.freeFMUState)(s)
    fmu.terminate()
    fmu.freeInstance()


def plant_me(path, version, fidelity):
    """0.05 s of CVODE under uneven forces, then the derivative call's refusals and a state round
    trip; returns the final z."""
    forces = np.array([(0.0,) + (220.0, 180.0, 210.0, 190.0, 200.0, 170.0)] * 2,
                      dtype=[("time", float)] + [(f"F[{k}]", float) for k in range(1, 7)])
    forces["time"][1] = 1.0
    r = simulate_fmu(path, fmi_type="ModelExchange", solver="CVode", stop_time=0.05,
                     output_interval=0.01, input=forces, start_values={"fidelity": fidelity},
                     output=["z", "L[1]"])
    fmu, vr, v2 = initialised(path, version, (FMU2Model, FMU3Model), "vg_me", "StewartPlantME")
    fmu.newDiscreteStates() if v2 else fmu.updateDiscreteStates()
    fmu.enterContinuousTimeMode()
    state = fmu.getFMUstate() if v2 else fmu.getFMUState()
    for pitch, force in ((math.pi / 2, 0.0), (0.0, math.nan)):
        x = np.array([0, 0, 0.5, 0, pitch, 0] + [0] * 6, dtype=float)
        fmu.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), len(x))
        (fmu.setReal if v2 else fmu.setFloat64)([vr["F[1]"]], [force])
        try:
            dx = (c_double * 12)()
            (fmu.getDerivatives if v2 else fmu.getContinuousStateDerivatives)(dx, 12)
            raise AssertionError("derivatives at a refused state")
        except fmpy.fmi1.FMICallException as e:
            assert e.status == 2, e.status
    round_trip_and_free(fmu, v2, state)
    return r["z"][-1]


def cueing(path, version):
    """0.5 s of a vehicle signal beyond the machine (the limiter acts), then a NaN input (refused)
    and an FMU state round trip; returns the final x."""
    t = np.linspace(0.0, 0.5, 51)
    vehicle = np.array([(ti, 8 * math.sin(4 * ti), 9.81, 2.0 * (ti > 0.2)) for ti in t],
                       dtype=[("time", float), ("specific_force[1]", float),
                              ("specific_force[3]", float), ("angular_velocity[3]", float)])
    r = simulate_fmu(path, fmi_type="CoSimulation", stop_time=0.5, output_interval=0.01,
                     step_size=0.01, input=vehicle, output=["x", "scale", "limited"])
    fmu, vr, v2 = initialised(path, version, (FMU2Slave, FMU3Slave), "vg_cue", "StewartCueing")
    set_real = fmu.setReal if v2 else fmu.setFloat64
    step = (lambda t, h: fmu.dll.fmi2DoStep(fmu.component, t, h, 1)) if v2 else fmu.doStep
    set_real([vr["specific_force[1]"]], [5.0])
    step(0.0, 0.01)
    state = fmu.getFMUstate() if v2 else fmu.getFMUState()
    set_real([vr["specific_force[2]"]], [math.nan])
    try:
        step(0.01, 0.01)
    except fmpy.fmi1.FMICallException:
        pass
    round_trip_and_free(fmu, v2, state)
    assert r["limited"].any()
    return r["x"][-1]


def scene_player(path):
    """The scene player on a trajectory file (read at initialisation, played between its rows,
    held after them), then a file it refuses at a bad line; returns the final x."""
    folder = tempfile.mkdtemp()
    names = ["x", "y", "z", "roll", "pitch", "yaw"]
    header = ",".join(["t", *names, *(n + "_dot" for n in names), *(n + "_ddot" for n in names)])
    rows = [[0.0] + [0.0] * 18, [0.1, 0.01] + [0.0] * 17, [0.2, 0.02] + [0.0] * 17]
    good, bad = f"{folder}/move.csv", f"{folder}/bad.csv"
    with open(good, "w") as f:
        f.write(header + "\n" + "".join(",".join(map(repr, r)) + "\n" for r in rows))
    with open(bad, "w") as f:
        f.write(header + "\n" + ",".join(map(repr, rows[0])) + "\n0,nan\n")
    r = simulate_fmu(path, fmi_type="CoSimulation", stop_time=0.3, output_interval=0.01,
                     step_size=0.01, start_values={"trajectory_file": good}, output=["x"])
    try:
        simulate_fmu(path, fmi_type="CoSimulation", stop_time=0.1, output_interval=0.01,
                     start_values={"trajectory_file": bad})
        raise AssertionError("the bad trajectory file was not refused")
    except fmpy.fmi1.FMICallException:
        pass
    return r["x"][-1]


for version in ("2.0", "3.0"):
    x = scene_player(f"{build}/fmus/{version}/StewartScene.fmu")
    print(f"valgrind_fmu: scene player FMI {version}: x = {x:.6f} m")
    x = cueing(f"{build}/fmus/{version}/StewartCueing.fmu", version)
    print(f"valgrind_fmu: cueing FMI {version}: x = {x:.6f} m")
    for fidelity in (1, 2):
        z = plant_me(f"{build}/fmus/{version}/StewartPlantME.fmu", version, fidelity)
        print(f"valgrind_fmu: Model Exchange plant FMI {version} fidelity {fidelity}: z = {z:.6f} m")
        z = plant(f"{build}/fmus/{version}/StewartPlant.fmu", version, fidelity)
        print(f"valgrind_fmu: plant FMI {version} fidelity {fidelity}: z = {z:.6f} m")
    path = f"{build}/fmus/{version}/StewartPlatform.fmu"
    for fidelity in (0, 1, 2):
        if not fidelity_available(path, version, fidelity):
            assert fidelity == 2, f"fidelity {fidelity} must be available"
            print(f"valgrind_fmu: FMI {version} fidelity 2 not available in this build: skipped")
            continue
        r = simulate_fmu(path, fmi_type="CoSimulation", stop_time=0.5, output_interval=0.01,
                         step_size=0.01, input=manoeuvre(), start_values={"fidelity": fidelity},
                         output=["L[1]", "F[1]", "status"])
        print(f"valgrind_fmu: FMI {version} fidelity {fidelity}: {len(r)} points, "
              f"L[1] = {r['L[1]'][-1]:.6f} m, F[1] = {r['F[1]'][-1]:.3f} N")
    print(f"valgrind_fmu: FMI {version} edge paths up to t = {edges(path, version):.2f} s")
print("valgrind_fmu: DRIVER DONE")
