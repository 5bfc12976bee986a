"""Helpers for the FMU tests (test_fmu_*.py): paths, a uniform FMI 2 / FMI 3 driver over fmpy,
the thesis manoeuvres, stewart-solve as the reference, and independent closed forms.

The build directory comes from STEWART_BUILD_DIR (default `build` relative to the repository root).
"""
import atexit
import contextlib
import csv
import math
import os
import pathlib
import shutil
import subprocess
import tempfile
import zipfile
from ctypes import byref, c_size_t

import numpy as np
import pytest

import fmpy
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE)
from fmpy.fmi3 import FMU3Slave, fmi3Boolean, fmi3Float64

REPO = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("STEWART_BUILD_DIR", "build"))
if not BUILD.is_absolute():
    BUILD = REPO / BUILD

VERSIONS = ("2.0", "3.0")
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
POSE_DOT = tuple(p + "_dot" for p in POSE)
POSE_DDOT = tuple(p + "_ddot" for p in POSE)
L = tuple(f"L[{k}]" for k in range(1, 7))
L_DOT = tuple(f"L_dot[{k}]" for k in range(1, 7))
L_DDOT = tuple(f"L_ddot[{k}]" for k in range(1, 7))
F = tuple(f"F[{k}]" for k in range(1, 7))
BASE_WRENCH = tuple(f"base_force[{k}]" for k in range(1, 4)) + tuple(
    f"base_torque[{k}]" for k in range(1, 4))
REAL_OUTPUTS = L + L_DOT + L_DDOT + F + ("condition", "residual") + BASE_WRENCH
INT_OUTPUTS = ("newton_iterations", "status")

OK, WARNING, DISCARD, ERROR, FATAL = range(5)


def every_leg(**values):
    """FMU variables setting a per-leg parameter to one value on all six legs: every_leg(
    stroke_min=0.4) gives stroke_min[1]..stroke_min[6] (the FMU has no scalar of that name)."""
    return {f"{name}[{k}]": value for name, value in values.items() for k in range(1, 7)}


def fmu_path(version):
    p = BUILD / "fmus" / version / "StewartPlatform.fmu"
    if not p.exists():
        pytest.fail(f"{p} is missing: build the project first (cmake --build {BUILD})")
    return p


def stewart_solve_path():
    p = BUILD / "stewart-solve"
    if not p.exists():
        pytest.fail(f"{p} is missing: build the project first")
    return p


_unzipped = {}
_descriptions = {}


def model_description(version):
    if version not in _descriptions:
        _descriptions[version] = fmpy.read_model_description(str(fmu_path(version)))
    return _descriptions[version]


def unzipped(version):
    if version not in _unzipped:
        d = tempfile.mkdtemp(prefix=f"stewart_fmu{version[0]}_")
        atexit.register(shutil.rmtree, d, ignore_errors=True)
        with zipfile.ZipFile(fmu_path(version)) as z:
            z.extractall(d)
        _unzipped[version] = d
    return _unzipped[version]


class Unit:
    """One FMU instance driven through fmpy. Calls whose status matters return it (raw), the
    rest raise like fmpy does. Log messages are collected in .messages as (status, category,
    message)."""

    def __init__(self, version, name="stewart", logging=True):
        self.version = version
        md = model_description(version)
        self.md = md
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.type = {v.name: v.type for v in md.modelVariables}
        self.messages = []
        d = unzipped(version)
        if version == "2.0":
            self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="StewartPlatform",
                                 instanceName=name)

            def logger(env, instance, status, category, message):
                self.messages.append((status, category.decode(), message.decode()))

            cb = fmi2CallbackFunctions()
            cb.logger = fmi2CallbackLoggerTYPE(logger)
            cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.fmi2.calloc)
            cb.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.fmi2.free)
            self._callbacks = cb
            self.fmu.instantiate(callbacks=cb, loggingOn=logging)
        else:
            self.fmu = FMU3Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="StewartPlatform",
                                 instanceName=name)

            def log_message(env, status, category, message):
                self.messages.append((status, category.decode(), message.decode()))

            self._log = log_message
            self.fmu.instantiate(loggingOn=logging, logMessage=log_message)
        self.dll = self.fmu.dll
        self.c = self.fmu.component
        self.time = 0.0

    # ---- values by name
    def set(self, **values):
        self.set_values(values)

    def set_values(self, values):
        reals = [(self.vr[n], float(v)) for n, v in values.items() if self.type[n] in ("Real", "Float64")]
        ints = [(self.vr[n], int(v)) for n, v in values.items() if self.type[n] in ("Integer", "Int32")]
        assert len(reals) + len(ints) == len(values)
        if self.version == "2.0":
            if reals:
                self.fmu.setReal([r for r, _ in reals], [v for _, v in reals])
            if ints:
                self.fmu.setInteger([r for r, _ in ints], [v for _, v in ints])
        else:
            if reals:
                self.fmu.setFloat64([r for r, _ in reals], [v for _, v in reals])
            if ints:
                self.fmu.setInt32([r for r, _ in ints], [v for _, v in ints])

    def get(self, names):
        out = []
        for n in names:
            if self.type[n] in ("Real", "Float64"):
                out.append((self.fmu.getReal if self.version == "2.0" else self.fmu.getFloat64)([self.vr[n]])[0])
            else:
                out.append((self.fmu.getInteger if self.version == "2.0" else self.fmu.getInt32)([self.vr[n]])[0])
        return out

    def get_reals(self, names):
        vrs = [self.vr[n] for n in names]
        f = self.fmu.getReal if self.version == "2.0" else self.fmu.getFloat64
        return np.array(f(vrs))

    def outputs(self):
        """All Real outputs (REAL_OUTPUTS order) and the integer outputs as a dict."""
        r = self.get_reals(REAL_OUTPUTS)
        i = self.get(INT_OUTPUTS)
        return r, dict(zip(INT_OUTPUTS, i))

    # ---- raw calls that return the status
    def enter_init(self, start_time=0.0):
        self.time = start_time
        if self.version == "2.0":
            self.fmu.setupExperiment(startTime=start_time)
            return self.dll.fmi2EnterInitializationMode(self.c)
        return self.dll.fmi3EnterInitializationMode(self.c, fmi3Boolean(False), fmi3Float64(0.0),
                                                    fmi3Float64(start_time), fmi3Boolean(False),
                                                    fmi3Float64(0.0))

    def exit_init(self):
        name = "fmi2ExitInitializationMode" if self.version == "2.0" else "fmi3ExitInitializationMode"
        return getattr(self.dll, name)(self.c)

    def init(self, start_time=0.0, **params):
        self.set_values(params)
        s = self.enter_init(start_time)
        assert s == OK
        return self.exit_init()

    def do_step(self, t, h):
        if self.version == "2.0":
            return self.dll.fmi2DoStep(self.c, t, h, 1)
        a, b, c = fmi3Boolean(), fmi3Boolean(), fmi3Boolean()
        last = fmi3Float64()
        return self.dll.fmi3DoStep(self.c, t, h, fmi3Boolean(True), byref(a), byref(b), byref(c),
                                   byref(last))

    def reset(self):
        return getattr(self.dll, "fmi2Reset" if self.version == "2.0" else "fmi3Reset")(self.c)

    def set_debug_logging(self, on, categories):
        self.fmu.setDebugLogging(on, categories)

    # ---- FMU state
    def get_state(self):
        return self.fmu.getFMUstate() if self.version == "2.0" else self.fmu.getFMUState()

    def set_state(self, s):
        (self.fmu.setFMUstate if self.version == "2.0" else self.fmu.setFMUState)(s)

    def free_state(self, s):
        (self.fmu.freeFMUstate if self.version == "2.0" else self.fmu.freeFMUState)(s)

    def serialize(self, s):
        return (self.fmu.serializeFMUstate if self.version == "2.0" else self.fmu.serializeFMUState)(s)

    def deserialize(self, b):
        if self.version == "2.0":
            return self.fmu.deSerializeFMUstate(b)
        return self.fmu.deserializeFMUState(b)

    def free(self):
        try:
            getattr(self.dll, "fmi2FreeInstance" if self.version == "2.0" else "fmi3FreeInstance")(self.c)
        finally:
            self.fmu.freeLibrary() if hasattr(self.fmu, "freeLibrary") else None

    def messages_text(self):
        return "\n".join(m for _, _, m in self.messages)


@contextlib.contextmanager
def opened_unit(version, *args, **kwargs):
    """A Unit (Unit(version, ...)), freed when the block ends, however it ends."""
    u = Unit(version, *args, **kwargs)
    try:
        yield u
    finally:
        u.free()


def fidelity_available(version, fidelity):
    """True if this build solves `fidelity` (detected at run time: exit initialisation fails with
    an 'unsupported' message otherwise)."""
    with opened_unit(version) as u:
        s = u.init(fidelity=fidelity)
        if s in (OK, WARNING):
            return True
        text = u.messages_text().lower()
        assert "not available" in text or "unsupported" in text, text
        return False


def require_fidelity(version, fidelity):
    if fidelity == 2 and not fidelity_available(version, 2):
        pytest.skip("fidelity 2 (full 14-body model) is not available in this build")


def assert_unit_solves_as_the_library(values, platform, pose, version):
    """The StewartPlatform unit with start values `values` (stewart.fmu_start_values), started at
    `pose` and stepped once, gives the library's full-fidelity lengths of `platform` at that pose
    bit for bit and its forces to 1e-9 of their scale."""
    expected = platform.inverse(np.array([pose]), fidelity="full")
    with opened_unit(version) as u:
        assert u.init(**values, **dict(zip(POSE, pose)), derivatives=1) == OK, u.messages
        assert u.do_step(0.0, 0.01) == OK, u.messages
        assert np.array_equal(u.get_reals(L), expected.length[0])
        scale = np.max(np.abs(expected.force))
        assert np.max(np.abs(u.get_reals(F) - expected.force[0])) < 1e-9 * scale


# ---------------------------------------------------------------- manoeuvres and references

def thesis_manoeuvre(kind, t):
    """Pose, first and second derivatives (each (n, 6)) of a thesis motion at times t."""
    t = np.asarray(t, dtype=float)
    n = len(t)
    w, a_z, a_ang = 5.0, 0.04, math.pi / 18
    q = np.zeros((n, 6)); qd = np.zeros((n, 6)); qdd = np.zeros((n, 6))
    q[:, 2] = 0.5
    col, amp = {"heave": (2, a_z), "roll": (3, a_ang), "pitch": (4, a_ang), "yaw": (5, a_ang)}[kind]
    q[:, col] += amp * np.sin(w * t)
    qd[:, col] = amp * w * np.cos(w * t)
    qdd[:, col] = -amp * w * w * np.sin(w * t)
    return q, qd, qdd


MANOEUVRES = ("heave", "roll", "pitch", "yaw")
THESIS_T = np.round(np.arange(121) * 0.1, 12)


def stewart_solve(t, q, qd=None, qdd=None, fidelity="massless"):
    """Runs build/stewart-solve on the poses; returns dict column -> array."""
    with tempfile.TemporaryDirectory() as d:
        inp, out = pathlib.Path(d, "in.csv"), pathlib.Path(d, "out.csv")
        cols = ["t"] + list(POSE)
        data = [np.asarray(t)[:, None], q]
        if qd is not None:
            cols += list(POSE_DOT) + list(POSE_DDOT)
            data += [qd, qdd]
        m = np.hstack(data)
        with open(inp, "w") as f:
            f.write(",".join(cols) + "\n")
            for row in m:
                f.write(",".join(repr(float(v)) for v in row) + "\n")
        r = subprocess.run([str(stewart_solve_path()), "--fidelity", fidelity, str(inp), str(out)],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        with open(out) as f:
            rows = list(csv.reader(f))
    numeric = [i for i, h in enumerate(rows[0]) if h != "status"]  # status: a limit class name
    header = [rows[0][i] for i in numeric]
    body = np.array([[float(r[i]) for i in numeric] for r in rows[1:]])
    return {h: body[:, i] for i, h in enumerate(header)}


def reference_matrix(ref):
    """stewart-solve columns in the order L, L_dot, L_ddot, F -> (n, 24)."""
    return np.column_stack([ref[f"{g}{k}"] for g in ("L", "L_dot", "L_ddot", "F") for k in range(1, 7)])


def backward_fd(ts, qs):
    """The FMU's documented finite differences, written independently: derivatives at the newest
    point of the quadratic through the last three poses; with two poses, the chord's slope and
    zero acceleration; with one pose, at rest."""
    n = len(ts)
    qd = np.zeros_like(qs); qdd = np.zeros_like(qs)
    for j in range(n):
        if j == 0:
            continue
        if j == 1:
            qd[1] = (qs[1] - qs[0]) / (ts[1] - ts[0])
            continue
        t0, t1, t2 = ts[j - 2], ts[j - 1], ts[j]
        # Lagrange quadratic through the three points, differentiated at t2
        q0, q1, q2 = qs[j - 2], qs[j - 1], qs[j]
        d0 = (t2 - t1) / ((t0 - t1) * (t0 - t2))
        d1 = (t2 - t0) / ((t1 - t0) * (t1 - t2))
        d2 = ((t2 - t0) + (t2 - t1)) / ((t2 - t0) * (t2 - t1))
        qd[j] = d0 * q0 + d1 * q1 + d2 * q2
        qdd[j] = 2 * (q0 / ((t0 - t1) * (t0 - t2)) + q1 / ((t1 - t0) * (t1 - t2)) +
                      q2 / ((t2 - t0) * (t2 - t1)))
    return qd, qdd


def libcosim_outputs(osp, steps, units=("plant",), names=POSE):
    """libcosim on an OSP system structure (a path): the Real outputs `names` of each of `units`
    after each of `steps` steps, {unit: (steps, len(names))}."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_osp_config_file(str(osp))
    observer = CosimObserver.create_last_value()
    ex.add_observer(observer)
    index = {s.name.decode(): s.index for s in ex.slave_infos()}
    references = {unit: {v.name.decode(): v.reference for v in ex.slave_variables(index[unit])}
                  for unit in units}
    out = {unit: [] for unit in units}
    for _ in range(steps):
        assert ex.step()
        for unit in units:
            out[unit].append(observer.last_real_values(index[unit],
                                                       [references[unit][n] for n in names]))
    return {unit: np.array(rows) for unit, rows in out.items()}
