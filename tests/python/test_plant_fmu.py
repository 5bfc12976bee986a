"""StewartPlant.fmu (forward dynamics on the FMU runtime), FMI 2 and FMI 3: its descriptions
(fmpy validate, the inverse FMU's parameter names and value references), against stewart-simulate
on the same forces, against the inverse FMU (its forces reproduce the pose), free fall in closed
form, state rollback bit for bit, instances side by side, and the edges (a NaN force, a refused
step, a leg leaving its stroke)."""
import atexit
import csv
import functools
import ctypes
import math
import shutil
import subprocess
import threading

import numpy as np
import pytest

import fmpy
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

import scenes
import stewart
from fmu_support import BUILD, VERSIONS

OK, WARNING, DISCARD, ERROR = range(4)
POSE = list(scenes.POSE)
POSE_DOT = list(scenes.DOT)
F = [f"F[{k}]" for k in range(1, 7)]
L = [f"L[{k}]" for k in range(1, 7)]
L_DOT = [f"L_dot[{k}]" for k in range(1, 7)]
WRENCH = [f"base_{w}[{i}]" for w in ("force", "torque") for i in (1, 2, 3)]
OUTPUTS = POSE + POSE_DOT + L + L_DOT + WRENCH + ["last_step_size"]
STATISTICS = ["status", "steps", "rhs_evaluations", "total_steps", "total_rhs_evaluations"]


def fmu_file(model, version):
    p = BUILD / "fmus" / version / f"{model}.fmu"
    if not p.exists():
        pytest.fail(f"{p} is missing: build the project first")
    return str(p)


@functools.lru_cache(maxsize=None)
def unzipped(path):
    """One extraction per FMU, so that instances share one loaded binary (as in a master): state
    shared between instances would show."""
    directory = fmpy.extract(path)
    atexit.register(shutil.rmtree, directory, ignore_errors=True)
    return directory


class Instance:
    """One instance of a model of this project (FMI 2 or 3) through fmpy, variables by name; raw
    calls return their status. Log messages collect in .messages."""

    def __init__(self, model, version="2.0", name="i", classes=(FMU2Slave, FMU3Slave)):
        """classes: fmpy's FMI 2 and FMI 3 classes (Model Exchange: FMU2Model, FMU3Model)."""
        path = fmu_file(model, version)
        md = fmpy.read_model_description(path)
        self.v2 = version == "2.0"
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.integers = {v.name for v in md.modelVariables if v.type in ("Integer", "Int32")}
        self.messages = []
        cls = classes[0] if self.v2 else classes[1]
        self.fmu = cls(guid=md.guid, unzipDirectory=unzipped(path),
                       modelIdentifier=model, instanceName=name)
        if self.v2:
            callbacks = fmi2CallbackFunctions()
            callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda env, inst, status, category, message: self.messages.append(message.decode()))
            callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.fmi2.calloc)
            callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.fmi2.free)
            self._callbacks = callbacks
            self.fmu.instantiate(callbacks=callbacks, loggingOn=True)
        else:
            self._log = lambda env, status, category, message: self.messages.append(
                message.decode())
            self.fmu.instantiate(loggingOn=True, logMessage=self._log)

    def init(self, start_time=0.0, **parameters):
        self.set(**parameters)
        if self.v2:
            self.fmu.setupExperiment(startTime=start_time)
            self.fmu.enterInitializationMode()
        else:
            self.fmu.enterInitializationMode(startTime=start_time)
        self.fmu.exitInitializationMode()
        return self

    def set(self, **values):
        for name, value in values.items():
            if name in self.integers:
                (self.fmu.setInteger if self.v2 else self.fmu.setInt32)([self.vr[name]],
                                                                        [int(value)])
            else:
                (self.fmu.setReal if self.v2 else self.fmu.setFloat64)([self.vr[name]],
                                                                       [float(value)])

    def set_reals(self, names, values):
        (self.fmu.setReal if self.v2 else self.fmu.setFloat64)([self.vr[n] for n in names],
                                                               [float(v) for v in values])

    def get(self, names):
        reals = [n for n in names if n not in self.integers]
        out = dict(zip(reals, (self.fmu.getReal if self.v2 else self.fmu.getFloat64)(
            [self.vr[n] for n in reals]))) if reals else {}
        for n in names:
            if n in self.integers:
                out[n] = (self.fmu.getInteger if self.v2 else self.fmu.getInt32)([self.vr[n]])[0]
        return np.array([out[n] for n in names], dtype=float)

    def step(self, t, h):
        if self.v2:
            return self.fmu.dll.fmi2DoStep(self.fmu.component, ctypes.c_double(t),
                                           ctypes.c_double(h), 1)
        flags = [ctypes.c_bool() for _ in range(3)]
        last = ctypes.c_double()
        s = self.fmu.dll.fmi3DoStep(self.fmu.component, ctypes.c_double(t), ctypes.c_double(h),
                                    True, *map(ctypes.byref, flags), ctypes.byref(last))
        self.last_successful_time = last.value
        return s

    def force_rates(self, rates):
        """FMI 2 order-1 input derivatives of F[1..6]."""
        self.fmu.setRealInputDerivatives([self.vr[n] for n in F], [1] * 6, list(rates))

    def get_state(self):
        return self.fmu.getFMUstate() if self.v2 else self.fmu.getFMUState()

    def set_state(self, s):
        (self.fmu.setFMUstate if self.v2 else self.fmu.setFMUState)(s)

    def serialize(self, s):
        return (self.fmu.serializeFMUstate if self.v2 else self.fmu.serializeFMUState)(s)

    def deserialize(self, b):
        return (self.fmu.deSerializeFMUstate if self.v2 else self.fmu.deserializeFMUState)(b)

    def free(self):
        self.fmu.freeInstance()


def plant(version="2.0", name="plant", **parameters):
    return Instance("StewartPlant", version, name).init(**parameters)


@functools.lru_cache(maxsize=None)
def _static_forces(fidelity):
    u = Instance("StewartPlatform").init(fidelity=fidelity)
    try:
        return tuple(u.get(F))
    finally:
        u.free()


def static_forces(fidelity=2):
    """The inverse FMU's forces holding the platform at rest at home."""
    return np.array(_static_forces(fidelity))


def wobble(t):
    """Forces around the static ones: a smooth, bounded push on every leg (N)."""
    k = np.arange(6)
    return 30.0 * np.sin(np.outer(t, 4.0 + k) + k)


# ---------------------------------------------------------------- descriptions

@pytest.mark.parametrize("model", ["StewartPlant", "StewartController", "StewartScene"])
@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validate_is_clean(model, version):
    assert validate_fmu(fmu_file(model, version)) == []


def test_interface_and_parameters_of_the_inverse_fmu():
    plant_md = fmpy.read_model_description(fmu_file("StewartPlant", "2.0"))
    inverse_md = fmpy.read_model_description(fmu_file("StewartPlatform", "2.0"))
    assert plant_md.guid != inverse_md.guid
    v = {x.name: x for x in plant_md.modelVariables}
    inverse = {x.name: x for x in inverse_md.modelVariables}
    for n in F:
        assert (v[n].causality, v[n].unit) == ("input", "N"), n
    for n in POSE + POSE_DOT + L + L_DOT + WRENCH:
        assert v[n].causality == "output" and v[n].type == "Real", n
    for n in ("status", "steps", "rhs_evaluations", "total_steps"):
        assert v[n].causality == "output" and v[n].type == "Integer", n
    for n in ("fidelity", "method", "max_internal_steps", "relative_tolerance",
              "absolute_tolerance") + tuple(f"{p}0" for p in POSE) + tuple(
                  f"{p}_dot0" for p in POSE):
        assert v[n].causality == "parameter", n
    assert v["fidelity"].start == "2" and v["z0"].start == "0.5" and v["x_dot0"].start == "0"
    # every geometry and mass parameter: the inverse FMU's name, value reference and default
    geometry = [n for n, x in inverse.items() if x.causality == "parameter" and
                not n.startswith(("fidelity", "derivatives", "tolerance", "max_iterations",
                                  "modified_newton", "warn_condition", "singular_condition",
                                  "limit_outputs"))]
    # every element of the library's parameter table (stewart_table.h), in both units
    assert len(geometry) == sum(p["count"] for p in stewart.parameters())
    assert set(geometry) == {n for n, x in v.items() if x.valueReference in
                             {inverse[g].valueReference for g in geometry}}
    for n in geometry:
        assert v[n].valueReference == inverse[n].valueReference, n
        assert v[n].start == inverse[n].start and v[n].unit == inverse[n].unit, n
    assert plant_md.coSimulation.canInterpolateInputs
    # the motion is state: no input reaches it within a step (loops through it are not algebraic)
    for version in VERSIONS:
        md = fmpy.read_model_description(fmu_file("StewartPlant", version))
        for unknown in md.outputs:
            name = unknown.variable.name
            if name in POSE + POSE_DOT + L + L_DOT:
                assert unknown.dependencies == [], (version, name)
            else:
                assert unknown.dependencies is None, (version, name)  # on every input
    assert plant_md.coSimulation.canGetAndSetFMUstate and plant_md.coSimulation.canSerializeFMUstate


# ---------------------------------------------------------------- against independent runs

def test_free_fall_is_the_closed_form():
    """Massless, no forces: z = z0 - g t^2 / 2, x = x0 + x_dot0 t (variable steps)."""
    u = plant(fidelity=1, x0=0.01, x_dot0=0.02)
    try:
        t = 0.0
        for h in (1e-3, 2e-3, 5e-3, 1e-3, 1e-2) * 4:
            assert u.step(t, h) == OK
            t += h
            x, z, z_dot = u.get(["x", "z", "z_dot"])
            assert x == pytest.approx(0.01 + 0.02 * t, abs=1e-13)
            assert z == pytest.approx(0.5 - 0.5 * 9.81 * t * t, abs=1e-13)
            assert z_dot == pytest.approx(-9.81 * t, abs=1e-12)
    finally:
        u.free()


@pytest.mark.parametrize("fidelity", [1, 2])
def test_same_as_stewart_simulate_on_the_same_forces(tmp_path, fidelity):
    """Forces linear between samples: the CLI's rule, and the FMU's with FMI 2 input derivatives
    (the chord's slope). Both run the library's plant: pose, rates and lengths agree to
    rounding."""
    h, n = 1e-3, 300
    t = np.arange(n + 1) * h
    forces = static_forces(fidelity) + wobble(t)
    with open(tmp_path / "in.csv", "w") as f:
        f.write("t,F1,F2,F3,F4,F5,F6\n")
        for ti, row in zip(t, forces):
            f.write(",".join(repr(float(v)) for v in (ti, *row)) + "\n")
    r = subprocess.run([str(BUILD / "stewart-simulate"), "--fidelity",
                        {1: "massless", 2: "full"}[fidelity], str(tmp_path / "in.csv"),
                        str(tmp_path / "out.csv")], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "out.csv") as f:
        rows = list(csv.reader(f))
    cli = {c: np.array([float(row[i]) for row in rows[1:]]) for i, c in enumerate(rows[0])}
    cli_columns = POSE + POSE_DOT + [f"L{k}" for k in range(1, 7)] + [
        f"L_dot{k}" for k in range(1, 7)]
    expected = np.column_stack([cli[c] for c in cli_columns])
    u = plant(fidelity=fidelity)
    try:
        got = [u.get(POSE + POSE_DOT + L + L_DOT)]
        for j in range(n):
            u.set_reals(F, forces[j])
            u.force_rates((forces[j + 1] - forces[j]) / h)
            assert u.step(t[j], h) == OK
            got.append(u.get(POSE + POSE_DOT + L + L_DOT))
            np.testing.assert_allclose(u.get(F), forces[j + 1], rtol=1e-12)  # read at t + h
        got = np.array(got)
        print(f"against stewart-simulate, fidelity {fidelity}: {np.abs(got - expected).max():.2e}")
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-11)
        assert np.abs(got[-1, :6] - got[0, :6]).max() > 1e-4  # the forces did move it
    finally:
        u.free()


@pytest.mark.parametrize("fidelity", [1, 2])
def test_forces_of_the_inverse_fmu_reproduce_the_pose(fidelity):
    """Round trip: the inverse FMU (derivatives = 1, the cue's exact rates) turns the combined cue
    into forces at 0.25 ms; the plant, started on the cue and given those forces (linear between
    samples through FMI 2 input derivatives), follows the cue open loop over 1 s."""
    h, n = 2.5e-4, 4000
    scene = scenes.load("combined")
    t = np.arange(n + 1) * h
    q, qd, qdd = scenes.pose(scene, t)
    inverse = Instance("StewartPlatform", name="inverse").init(fidelity=fidelity, derivatives=1)
    try:
        forces = []
        for j in range(n + 1):
            inverse.set_reals(POSE + POSE_DOT + list(scenes.DDOT), [*q[j], *qd[j], *qdd[j]])
            forces.append(inverse.get(F))
        forces = np.array(forces)
    finally:
        inverse.free()
    start = {f"{p}0": v for p, v in zip(POSE, q[0])}
    start.update({f"{p}_dot0": v for p, v in zip(POSE, qd[0])})
    u = plant(fidelity=fidelity, **start)
    try:
        error = 0.0
        for j in range(n):
            u.set_reals(F, forces[j])
            u.force_rates((forces[j + 1] - forces[j]) / h)
            assert u.step(t[j], h) == OK
            error = max(error, np.abs(u.get(POSE) - q[j + 1]).max())
        print(f"round trip, fidelity {fidelity}: max pose error {error:.2e}")
        assert error <= 1e-6, error
    finally:
        u.free()


# ---------------------------------------------------------------- FMU state, instances

def run_steps(u, t0, n, h=1e-3, forces=None):
    """n steps from t0 under `forces` (held), the outputs and statistics after each."""
    rows = []
    for j in range(n):
        t = t0 + j * h
        u.set_reals(F, forces if forces is not None else static_forces() + wobble([t])[0])
        assert u.step(t, h) == OK
        rows.append(np.concatenate([u.get(OUTPUTS), u.get(STATISTICS)]))
    return np.array(rows)


@pytest.mark.parametrize("version", VERSIONS)
def test_rollback_reproduces_the_outputs_bit_for_bit(version):
    u = plant(version, x_dot0=0.05, roll_dot0=0.1)
    other = plant(version, name="other", fidelity=1, payload_mass=30)  # other parameters
    try:
        run_steps(u, 0.0, 5)
        state = u.get_state()
        blob = u.serialize(state)
        first = run_steps(u, 0.005, 20)
        u.set_state(state)
        again = run_steps(u, 0.005, 20)
        assert again.tobytes() == first.tobytes()
        # serialised, onto an instance built with other parameters: the state's apply
        other.set_state(other.deserialize(blob))
        moved = run_steps(other, 0.005, 20)
        assert moved.tobytes() == first.tobytes()
    finally:
        u.free()
        other.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_instances_side_by_side(version):
    """Two instances stepped alternately give what each gives alone."""
    forces = static_forces() + 20.0
    alone = []
    for payload in (0.0, 40.0):
        u = plant(version, payload_mass=payload)
        alone.append(run_steps(u, 0.0, 30, forces=forces))
        u.free()
    a, b = plant(version, name="a"), plant(version, name="b", payload_mass=40.0)
    try:
        rows = [[], []]
        for j in range(30):
            for u, r in ((a, rows[0]), (b, rows[1])):
                r.append(run_steps(u, j * 1e-3, 1, forces=forces)[0])
        assert np.array(rows[0]).tobytes() == alone[0].tobytes()
        assert np.array(rows[1]).tobytes() == alone[1].tobytes()
        assert not np.array_equal(alone[0], alone[1])
    finally:
        a.free()
        b.free()


def test_instances_in_threads():
    """Instances stepped in two threads at once (ctypes releases the GIL in each call) give what
    each gives alone."""
    forces = static_forces() + 20.0
    units = [plant(name=f"t{i}", payload_mass=20.0 * i) for i in range(2)]
    alone = []
    for i in range(2):
        u = plant(name=f"s{i}", payload_mass=20.0 * i)
        alone.append(run_steps(u, 0.0, 300, forces=forces))
        u.free()
    results = [None, None]

    def work(i):
        results[i] = run_steps(units[i], 0.0, 300, forces=forces)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    try:
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        for i in range(2):
            assert results[i].tobytes() == alone[i].tobytes(), i
    finally:
        for u in units:
            u.free()


# ---------------------------------------------------------------- edges

@pytest.mark.parametrize("version", VERSIONS)
def test_nan_force_is_discarded_and_the_instance_stays_usable(version):
    u = plant(version)
    fresh = plant(version, name="fresh")
    try:
        forces = static_forces()
        run_steps(u, 0.0, 3, forces=forces)
        before = u.get(OUTPUTS)
        bad = forces.copy()
        bad[2] = math.nan
        u.set_reals(F, bad)
        assert u.step(0.003, 1e-3) == DISCARD
        assert any("F[3]" in m and "nan" in m for m in u.messages), u.messages
        assert u.get(["status"])[0] == 3
        after = u.get(OUTPUTS)
        assert np.all(np.isfinite(after)) and after.tobytes() == before.tobytes()
        if version == "3.0":
            assert u.last_successful_time == pytest.approx(0.003, abs=1e-15)
        # good forces again at the same t: as if the bad step had never been tried
        resumed = run_steps(u, 0.003, 5, forces=forces)
        reference = run_steps(fresh, 0.0, 8, forces=forces)[3:]
        np.testing.assert_array_equal(resumed[:, :len(OUTPUTS)], reference[:, :len(OUTPUTS)])
    finally:
        u.free()
        fresh.free()


def test_refused_step_names_the_cause_and_keeps_the_state():
    """An integrator that may take one internal step cannot cover 0.5 s: Discard with SUNDIALS'
    reason, the state at the last good point; a step it can take then succeeds."""
    u = plant(max_internal_steps=1)
    try:
        forces = static_forces() + 5.0
        run_steps(u, 0.0, 2, forces=forces)
        before = u.get(OUTPUTS)
        u.set_reals(F, forces)
        assert u.step(0.002, 0.5) == DISCARD
        text = "\n".join(u.messages)
        assert "step refused" in text and "NOT_CONVERGED" in text.upper().replace(" ", "_"), text
        assert u.get(["status"])[0] == 3
        assert u.get(OUTPUTS).tobytes() == before.tobytes()
        assert u.step(0.002, 1e-3) == OK and u.get(["status"])[0] == 0
    finally:
        u.free()


def test_leaving_the_stroke_is_a_warning_naming_the_leg():
    """Pushing every leg far beyond the platform's weight extends them past stroke_max = 0.7 m."""
    u = plant(fidelity=1)
    try:
        u.set_reals(F, [3000.0] * 6)
        t, status = 0.0, OK
        while status == OK and t < 1.0:
            status = u.step(t, 1e-3)
            t += 1e-3
        assert status == WARNING
        assert u.get(["status"])[0] == 1
        lengths = u.get(L)
        outside = [k + 1 for k in range(6) if lengths[k] > 0.7]
        assert outside
        assert any(f"L[{outside[0]}]" in m and "stroke" in m for m in u.messages), u.messages
    finally:
        u.free()


def test_statistics_add_up():
    u = plant()
    try:
        rows = run_steps(u, 0.0, 10)
        steps, rhs, total_steps, total_rhs = (rows[:, len(OUTPUTS) + i] for i in range(1, 5))
        assert np.all(steps >= 1) and np.all(rhs >= steps)
        np.testing.assert_array_equal(np.cumsum(steps), total_steps)
        np.testing.assert_array_equal(np.cumsum(rhs), total_rhs)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_step_that_skips_time_is_an_error(version):
    """The plant integrates continuously: a communication point after the end of the last step
    (which the runtime lets a stateless unit take) is an Error naming it; a restored state goes
    on."""
    u = plant(version)
    try:
        forces = static_forces()
        run_steps(u, 0.0, 2, forces=forces)
        state = u.get_state()
        before = u.get(POSE)
        assert u.step(0.5, 1e-3) == ERROR
        assert any("cannot skip time" in m and "0.5" in m for m in u.messages), u.messages
        # the unit's time stays where the plant is, and the instance is in Error: another step
        # is refused until a state is restored (or a reset)
        np.testing.assert_array_equal(u.get(POSE), before)
        if "time" in u.vr:  # FMI 3 lists the independent variable
            assert u.get(["time"])[0] == pytest.approx(0.002)
        assert u.step(0.002, 1e-3) == ERROR
        u.set_state(state)
        resumed = run_steps(u, 0.002, 3, forces=forces)
        assert np.all(resumed[:, len(OUTPUTS)] == 0)  # status ok
    finally:
        u.free()


def test_input_derivatives_set_during_initialisation_serve_the_first_step():
    """FMI 2 lets a master set input derivatives before the end of initialisation: the first
    step must use them, exactly as when they are set after it (a second way to the same step),
    and differ from a step without them."""
    def first_step(when):
        u = Instance("StewartPlant", "2.0")
        try:
            u.set(**{n: 3000.0 for n in F})
            u.fmu.setupExperiment(startTime=0.0)
            u.fmu.enterInitializationMode()
            if when == "initialisation":
                u.force_rates([1e6] * 6)
            u.fmu.exitInitializationMode()
            if when == "step":
                u.force_rates([1e6] * 6)
            assert u.step(0.0, 0.01) == OK
            return u.get(POSE)
        finally:
            u.free()
    during, after, without = first_step("initialisation"), first_step("step"), first_step("none")
    np.testing.assert_array_equal(during, after)
    assert abs(during[2] - without[2]) > 1e-3


@pytest.mark.parametrize("version", VERSIONS)
def test_scene_values_that_overflow_are_discarded(version):
    """Finite scene parameters can still overflow (omega = 1e308): Discard naming the output, the
    last finite values kept, and the unit's own state serialises and deserialises."""
    u = Instance("StewartScene", version)
    try:
        u.init(x_amplitude=1.0, x_omega=1e308)
        start = u.get(["x", "x_dot", "x_ddot"])
        assert np.all(np.isfinite(start))
        assert u.step(0.0, 2.0) == DISCARD
        assert any("x_dot" in m or "x_ddot" in m or "x " in m for m in u.messages), u.messages
        np.testing.assert_array_equal(u.get(["x", "x_dot", "x_ddot"]), start)
        state = u.get_state()
        u.deserialize(u.serialize(state))  # raises if the state were refused
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_fixed_steps_bound_the_work_and_follow_the_adaptive_plant(version):
    """fixed_steps = N: N steps of the 5-stage ERK 4(3) per communication step and one evaluation
    at its start, the same work every step (5 N + 1 right-hand sides, N steps); the pose stays
    with the error-controlled default under the wobbling forces."""
    adaptive = plant(version, name="adaptive")
    fixed = plant(version, name="fixed", fixed_steps=2)
    try:
        a = run_steps(adaptive, 0.0, 50)
        f = run_steps(fixed, 0.0, 50)
        steps, rhs = f[:, len(OUTPUTS) + 1], f[:, len(OUTPUTS) + 2]
        assert (steps == 2).all() and (rhs == 11).all(), (steps[:3], rhs[:3])
        np.testing.assert_allclose(f[:, :6], a[:, :6], rtol=0, atol=1e-9)
    finally:
        adaptive.free()
        fixed.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_fixed_steps_with_a_cvode_method_are_refused_naming_them(version):
    u = Instance("StewartPlant", version, "refused")
    try:
        with pytest.raises(Exception):
            u.init(method=0, fixed_steps=1)
        assert any("fixed_steps" in m for m in u.messages), u.messages
    finally:
        u.free()
