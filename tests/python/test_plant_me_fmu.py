"""StewartPlantME.fmu (the plant as FMI 2 / FMI 3 Model Exchange): its descriptions (fmpy validate,
the co-simulation plant's names and value references), fmpy's CVODE integrating it against the
co-simulation plant StewartPlant (free motion and a forced case, both fidelities), a second master
(tests/importer/me_rk4.c: fixed-step RK4 over the C API) against the same, the derivatives against
the co-simulation plant's motion, and the edges (pitch at +-90 degrees, a zero-length leg found from
the unit's own lengths, a NaN force or state, call order, FMU state round trip)."""
import ctypes
import subprocess

import numpy as np
import pytest

import fmpy
from fmpy.fmi2 import FMU2Model
from fmpy.fmi3 import FMU3Model
from fmpy.validation import validate_fmu

from fmu_support import BUILD, VERSIONS
from test_plant_fmu import F, L, L_DOT, POSE, POSE_DOT, WRENCH, Instance, fmu_file, unzipped

OK, WARNING, DISCARD, ERROR = range(4)
POSE_DDOT = [p + "_ddot" for p in POSE]
STATES = POSE + POSE_DOT
COMPARED = POSE + POSE_DOT + L + L_DOT
START = {"x_dot0": 0.05, "y_dot0": -0.03, "roll_dot0": 0.2, "pitch_dot0": -0.1, "yaw_dot0": 0.3}


class MEInstance(Instance):
    """One Model Exchange instance through fmpy (FMI 2 or 3), variables by name (Instance's get
    and set); raw calls return their status. Log messages collect in .messages."""

    def __init__(self, version="2.0", name="me"):
        super().__init__("StewartPlantME", version, name, classes=(FMU2Model, FMU3Model))
        self.dll, self.c = self.fmu.dll, self.fmu.component
        self.prefix = "fmi2" if self.v2 else "fmi3"

    def init(self, **parameters):
        """Parameters set, in initialisation mode (Instance.init also leaves it)."""
        self.set(**parameters)
        if self.v2:
            self.fmu.setupExperiment(startTime=0.0)
            self.fmu.enterInitializationMode()
        else:
            self.fmu.enterInitializationMode(startTime=0.0)
        return self

    def continuous(self):
        """Exit initialisation, pass event mode, enter continuous-time mode."""
        self.fmu.exitInitializationMode()
        if self.v2:
            self.fmu.newDiscreteStates()
        else:
            self.fmu.updateDiscreteStates()
        self.fmu.enterContinuousTimeMode()
        return self

    def raw(self, function, *args):
        return getattr(self.dll, self.prefix + function)(self.c, *args)

    def set_states(self, x):
        x = np.asarray(x, dtype=float)
        return self.raw("SetContinuousStates", x.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                        ctypes.c_size_t(len(x)))

    def derivatives(self):
        """(status, the 12 derivatives)."""
        dx = np.zeros(12)
        s = self.raw("GetDerivatives" if self.v2 else "GetContinuousStateDerivatives",
                     dx.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), ctypes.c_size_t(12))
        return s, dx



# ---------------------------------------------------------------- descriptions

@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validate_is_clean(version):
    assert validate_fmu(fmu_file("StewartPlantME", version)) == []


@pytest.mark.parametrize("version", VERSIONS)
def test_states_derivatives_and_the_co_simulation_plants_names(version):
    me = fmpy.read_model_description(fmu_file("StewartPlantME", version))
    cs = fmpy.read_model_description(fmu_file("StewartPlant", version))
    assert me.modelExchange and not me.coSimulation and me.guid != cs.guid
    assert me.modelExchange.modelIdentifier == "StewartPlantME"
    v = {x.name: x for x in me.modelVariables}
    # the states, in order, with their derivatives: x' = x_dot, x_dot' = x_ddot
    assert [d.variable.name for d in me.derivatives] == POSE_DOT + POSE_DDOT
    assert [d.variable.derivative.name for d in me.derivatives] == STATES
    # every input, output and parameter of the co-simulation plant but its integrator's
    integrator = {"method", "relative_tolerance", "absolute_tolerance", "max_internal_steps",
                  "fixed_steps",
                  "steps", "rhs_evaluations", "nonlinear_iterations", "error_test_failures",
                  "jacobian_evaluations", "last_order", "last_step_size"}
    for x in cs.modelVariables:
        if x.name in integrator or x.name.startswith("total_"):
            assert x.name not in v, x.name
            continue
        assert x.name in v, x.name
        assert (v[x.name].valueReference, v[x.name].causality, v[x.name].start) == (
            x.valueReference, x.causality, x.start), x.name
    for n in POSE_DDOT:
        assert v[n].causality == "output"


@pytest.mark.parametrize("version", VERSIONS)
def test_fmi_cross_check_rules(version):
    """What the FMI cross-check rules ask of an FMU: the archive's layout (description at the root,
    the binary where the platform's name says), a self-contained binary that exports only the FMI
    functions, both Model Exchange function sets present, and a run of the default experiment with
    the default start values (and with massless legs the free fall in closed form)."""
    import subprocess as sp
    import zipfile
    platform = "linux64" if version == "2.0" else "x86_64-linux"
    path = fmu_file("StewartPlantME", version)
    with zipfile.ZipFile(path) as z:
        assert set(z.namelist()) >= {"modelDescription.xml",
                                     f"binaries/{platform}/StewartPlantME.so"}
    so = BUILD / "fmu" / "StewartPlantME" / f"fmi{version[0]}" / "StewartPlantME.so"
    d = sp.run(["readelf", "-d", "-W", str(so)], capture_output=True, text=True, check=True)
    needed = {line.split("[")[1].split("]")[0] for line in d.stdout.splitlines()
              if "(NEEDED)" in line}
    assert needed <= {"libc.so.6", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1"}, needed
    syms = sp.run(["readelf", "--dyn-syms", "-W", str(so)], capture_output=True, text=True,
                  check=True).stdout.splitlines()
    exported = {f[7].split("@")[0] for f in map(str.split, syms)
                if len(f) >= 8 and f[0].endswith(":") and f[4] in ("GLOBAL", "WEAK")
                and f[6] != "UND"}
    prefix = f"fmi{version[0]}"
    assert exported and all(n.startswith(prefix) for n in exported)
    me_calls = ["SetTime", "SetContinuousStates", "GetContinuousStates", "EnterEventMode",
                "EnterContinuousTimeMode", "CompletedIntegratorStep", "GetEventIndicators",
                "GetNominalsOfContinuousStates", "InstantiateModelExchange" if version == "3.0"
                else "Instantiate", "GetDerivatives" if version == "2.0"
                else "GetContinuousStateDerivatives"]
    assert {prefix + c for c in me_calls} <= exported
    md = fmpy.read_model_description(path)
    assert md.defaultExperiment.stopTime == "1"
    result = fmpy.simulate_fmu(path)  # Model Exchange, fmpy's default solver and settings
    assert result["time"][-1] == pytest.approx(1.0)
    assert all(np.isfinite(result[n]).all() for n in result.dtype.names)
    # with massless legs and no forces the platform alone falls freely: z = 0.5 - g t^2 / 2
    result = fmpy.simulate_fmu(path, start_values={"fidelity": 1}, relative_tolerance=1e-10)
    assert np.abs(result["z"] - (0.5 - 9.81 / 2 * result["time"] ** 2)).max() < 1e-8


# ---------------------------------------------------------------- against the co-simulation plant

# tool and user frames and length offsets: the poses are the tool's in the user frame
FRAMES = dict({f"tool_frame[{i + 1}]": v for i, v in enumerate([0.01, -0.02, 0.05, 0.1, -0.05, 0.2])},
              **{f"user_frame[{i + 1}]": v for i, v in enumerate([0.02, 0.01, -0.03, 0.05, 0.04, -0.3])},
              **{f"length_offset[{k}]": 0.01 * k for k in range(1, 7)})


def co_simulation(version, fidelity, forces, t_end, h=1e-3, extra=None):
    """The co-simulation plant over [0, t_end] in steps of h, forces(t) held over each step: the
    rows (t, outputs COMPARED). extra: more parameters."""
    u = Instance("StewartPlant", version, "cs").init(fidelity=fidelity, **START, **(extra or {}))
    rows = [np.concatenate([[0.0], u.get(COMPARED)])]
    n = int(round(t_end / h))
    try:
        for i in range(n):
            t = i * h
            u.set_reals(F, forces(t))
            assert u.step(t, h) in (OK, WARNING)  # Warning: a leg outside its stroke
            rows.append(np.concatenate([[t + h], u.get(COMPARED)]))
    finally:
        u.free()
    return np.array(rows)


def model_exchange(version, fidelity, force_table, t_end, interval=1e-3, extra=None):
    """fmpy's CVODE on the ME plant (relative tolerance 1e-10): the rows (t, COMPARED)."""
    result = fmpy.simulate_fmu(
        fmu_file("StewartPlantME", version), fmi_type="ModelExchange", solver="CVode",
        relative_tolerance=1e-10, stop_time=t_end, output_interval=interval,
        start_values=dict(START, fidelity=fidelity, **(extra or {})), input=force_table,
        output=COMPARED)
    rows = np.column_stack([result["time"]] + [result[n] for n in COMPARED])
    # fmpy records a row before and after an event at the same time: keep the one after
    keep = np.append(np.diff(rows[:, 0]) > 0, True)
    return rows[keep]


def force_step(t_switch, before, after):
    """Forces that jump at t_switch (held on both sides): a function of t and fmpy's input table
    (a repeated time is an event there)."""
    before, after = np.asarray(before, float), np.asarray(after, float)
    table = np.array([(0.0, *before), (t_switch, *before), (t_switch, *after), (1e3, *after)],
                     dtype=[("time", float)] + [(n, float) for n in F])
    return (lambda t: before if t < t_switch - 1e-12 else after), table


FREE = force_step(1.0, np.zeros(6), np.zeros(6))
# about the static 196.8 N per leg at home (full fidelity), uneven, and swapped at 0.15 s
PUSH = force_step(0.15, [230, 180, 210, 190, 220, 170], [170, 220, 190, 210, 180, 230])


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
@pytest.mark.parametrize("case", ["free", "forced", "forced, frames"])
def test_cvode_equals_the_co_simulation_plant(version, fidelity, case):
    forces, table = FREE if case == "free" else PUSH
    extra = FRAMES if "frames" in case else None
    t_end = 0.3
    cs = co_simulation(version, fidelity, forces, t_end, extra=extra)
    me = model_exchange(version, fidelity, table, t_end, extra=extra)
    assert me.shape == cs.shape
    assert np.abs(me[:, 0] - cs[:, 0]).max() < 1e-12
    moved = np.abs(cs[-1, 1:13] - cs[0, 1:13]).max()
    assert moved > 0.01  # the platform moves: the comparison means something
    # both integrators at relative tolerance 1e-10: agreement to 1e-7 (m, rad, m/s, rad/s)
    err = np.abs(me[:, 1:] - cs[:, 1:]).max()
    assert err < 1e-7, f"max difference {err:.3g}"


# ---------------------------------------------------------------- second master: fixed-step RK4

def me_rk4(version, fidelity, h, t_end, forces_before, forces_after, t_switch):
    exe = BUILD / "me_rk4"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: build the project first")
    binary = BUILD / "fmu" / "StewartPlantME" / f"fmi{version[0]}" / "StewartPlantME.so"
    args = [str(exe), version[0], str(binary), str(fidelity), repr(h), repr(t_end), repr(t_switch)]
    args += [repr(float(f)) for f in list(forces_before) + list(forces_after)]
    args += [repr(START.get(n + "0", 0.5 if n == "z" else 0.0)) for n in STATES]
    out = subprocess.run(args, capture_output=True, text=True, timeout=300, check=True).stdout
    return np.array([[float(x) for x in line.split(",")] for line in out.split()])


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
def test_fixed_step_rk4_master_equals_the_co_simulation_plant(version, fidelity):
    before, after = [230, 180, 210, 190, 220, 170], [170, 220, 190, 210, 180, 230]
    forces, _ = force_step(0.15, before, after)
    t_end = 0.3
    cs = co_simulation(version, fidelity, forces, t_end)
    rk4 = me_rk4(version, fidelity, 1e-3, t_end, before, after, 0.15)
    assert rk4.shape == cs.shape
    assert np.abs(rk4[:, 0] - cs[:, 0]).max() < 1e-12
    # RK4 at h = 1 ms: global error O(h^4); measured 1e-12-ish, bound 1e-8
    err = np.abs(rk4[:, 1:] - cs[:, 1:]).max()
    assert err < 1e-8, f"max difference {err:.3g}"


# ---------------------------------------------------------------- derivatives

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
def test_derivatives_are_the_co_simulation_plants_motion(version, fidelity):
    """The accelerations against a central difference of the co-simulation plant's rates: start
    it at the state, push it h and -h in time (the latter by running it with the time-reversed
    state), and difference."""
    forces = np.array([230, 180, 210, 190, 220, 170], dtype=float)
    me = MEInstance(version).init(fidelity=fidelity, **START).continuous()
    me.set(**dict(zip(F, forces)))
    s, dx = me.derivatives()
    me.free()
    assert s == OK
    x0 = np.array([START.get(n + "0", 0.0) for n in STATES])
    x0[2] = 0.5
    assert np.array_equal(dx[:6], x0[6:])  # x' = x_dot
    h = 1e-4
    fwd = Instance("StewartPlant", version, "f").init(fidelity=fidelity, **START)
    fwd.set_reals(F, forces)
    assert fwd.step(0.0, h) == OK
    plus = fwd.get(POSE_DOT)
    fwd.free()
    # backwards in time: the state with reversed rates, run forward, is the motion at -h with
    # reversed rates, and its acceleration is the same (the forces do not depend on velocity)
    reversed_start = {k: -v for k, v in START.items()}
    bwd = Instance("StewartPlant", version, "b").init(fidelity=fidelity, **reversed_start)
    bwd.set_reals(F, forces)
    assert bwd.step(0.0, h) == OK
    minus = -bwd.get(POSE_DOT)
    bwd.free()
    # velocity-product terms are even in the rates, the applied forces too: the reversed run
    # is the motion at -h only if the accelerations are even in the rates, which they are
    fd = (plus - minus) / (2 * h)
    assert np.abs(dx[6:] - fd).max() < 1e-5 * max(1.0, np.abs(fd).max())


# ---------------------------------------------------------------- edges

def zero_length_state(me):
    """A pose (rotation at home) where leg 1 has zero length, found from the unit's own L[1]:
    L1^2(p) = |p + d|^2 for the platform at position p, so three displaced evaluations give d."""
    p0 = np.array([0.0, 0.0, 0.5])
    step = 0.05

    def l1_squared(p):
        x = np.zeros(12)
        x[:3] = p
        assert me.set_states(x) == OK
        assert me.derivatives()[0] == OK
        return me.get(["L[1]"])[0] ** 2

    base = l1_squared(p0)
    w = np.array([(l1_squared(p0 + step * e) - base - step ** 2) / (2 * step)
                  for e in np.eye(3)])
    x = np.zeros(12)
    x[:3] = p0 - w
    return x


@pytest.mark.parametrize("version", VERSIONS)
def test_zero_length_leg_and_pitch_at_90_degrees_are_refused_naming_the_value(version):
    me = MEInstance(version).init().continuous()
    good = np.array([0, 0, 0.5, 0, 0, 0] + [0] * 6, dtype=float)
    x = zero_length_state(me)
    assert me.set_states(x) == OK
    s, _ = me.derivatives()
    assert s == DISCARD
    assert "leg 1 has zero length" in me.messages[-1] and "L[1] = " in me.messages[-1]
    # the instance stays usable: a good state gives derivatives again
    assert me.set_states(good) == OK
    assert me.derivatives()[0] == OK
    for pitch in (np.pi / 2, -np.pi / 2):
        bad = good.copy()
        bad[4] = pitch
        assert me.set_states(bad) == OK
        s, _ = me.derivatives()
        assert s == DISCARD
        assert f"pitch = {pitch:.17g}" in me.messages[-1] and "90 degrees" in me.messages[-1]
    assert me.set_states(good) == OK
    assert me.derivatives()[0] == OK
    me.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_bad_forces_states_and_start(version):
    me = MEInstance(version).init().continuous()
    me.set(**{"F[3]": float("nan")})
    s, _ = me.derivatives()
    assert s == DISCARD and "F[3] = nan" in me.messages[-1]
    me.set(**{"F[3]": 0.0})
    assert me.derivatives()[0] == OK
    x = np.array([0, 0, 0.5, 0, 0, 0] + [0] * 6, dtype=float)
    x[7] = float("inf")
    assert me.set_states(x) == DISCARD and "y_dot = inf" in me.messages[-1]
    assert me.set_states(x[:11]) == ERROR  # wrong count: Error, instance in Error mode
    me.free()
    # a start at pitch +-90 degrees: Error at the end of initialisation naming pitch0
    me = MEInstance(version).init(pitch0=np.pi / 2)
    status = me.raw("ExitInitializationMode")
    assert status == ERROR and "pitch0" in me.messages[-1]
    me.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_call_order_and_interfaces(version):
    me = MEInstance(version).init()
    # not before the end of initialisation
    assert me.raw("EnterContinuousTimeMode") == ERROR
    assert "not allowed in initialization mode" in me.messages[-1]
    me.free()
    me = MEInstance(version).init().continuous()
    if version == "2.0":
        s = me.dll.fmi2DoStep(me.c, ctypes.c_double(0.0), ctypes.c_double(1e-3), 1)
        assert s == ERROR
    me.free()
    # the co-simulation plant refuses Model Exchange calls, saying so
    cs = Instance("StewartPlant", version, "cs").init()
    x = np.zeros(12)
    s = getattr(cs.fmu.dll, ("fmi2" if version == "2.0" else "fmi3") + "SetContinuousStates")(
        cs.fmu.component, x.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), ctypes.c_size_t(12))
    assert s == ERROR and "co-simulation only" in cs.messages[-1]
    cs.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_state_round_trip(version):
    me = MEInstance(version).init(**START).continuous()
    me.set(**dict(zip(F, [230, 180, 210, 190, 220, 170])))
    _, d0 = me.derivatives()
    state = me.fmu.getFMUstate() if me.v2 else me.fmu.getFMUState()
    blob = me.fmu.serializeFMUstate(state) if me.v2 else me.fmu.serializeFMUState(state)
    x = np.array([0.01, 0, 0.52, 0.1, 0, 0] + [0] * 6, dtype=float)
    assert me.set_states(x) == OK
    _, d1 = me.derivatives()
    assert not np.array_equal(d0, d1)
    restored = me.fmu.deSerializeFMUstate(blob) if me.v2 else me.fmu.deserializeFMUState(blob)
    (me.fmu.setFMUstate if me.v2 else me.fmu.setFMUState)(restored)
    s, d2 = me.derivatives()
    assert s == OK and np.array_equal(d0, d2)
    me.free()
