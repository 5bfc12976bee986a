"""The plant driven by motor currents through the package: the inverse's forces turned into
currents with the drive's law written here (lossless screw, no friction: i = (F + m_r L_ddot) /
(c k_t), c = 2 pi N / lead, m_r = J c^2) and fed to Platform.simulate(input="current") bring the
cue's pose back as the forces themselves do; the drive outputs against the same law."""
import numpy as np
import pytest

import stewart
import scenes

DRIVE = dict(screw_lead=0.005, gear_ratio=3.0, rotor_inertia=2e-5, screw_inertia=9e-5,
             torque_constant=0.5, winding_resistance=1.2)


def motor_per_leg():
    return 2 * np.pi * DRIVE["gear_ratio"] / DRIVE["screw_lead"]


def motor_inertia():
    return DRIVE["rotor_inertia"] + DRIVE["screw_inertia"] / DRIVE["gear_ratio"] ** 2


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_inverse_currents_reproduce_the_cue(fidelity):
    dt, duration = 2.5e-4, 1.0
    scene = scenes.load("combined")
    scene["duration"] = duration
    t = np.arange(0, duration + dt / 2, dt)
    q, qd, qdd = scenes.pose(scene, t)
    platform = stewart.Platform(**DRIVE)
    inv = platform.inverse(q, qd, qdd, fidelity=fidelity)
    c = motor_per_leg()
    m_r = motor_inertia() * c * c
    currents = (inv.force + m_r * inv.length_accel) / (c * DRIVE["torque_constant"])
    by_force = platform.simulate(t, inv.force, fidelity, q[0], qd[0], relative_tolerance=1e-12,
                                 absolute_tolerance=1e-14)
    by_current = platform.simulate(t, currents, fidelity, q[0], qd[0], input="current",
                                   relative_tolerance=1e-12, absolute_tolerance=1e-14)
    assert by_force.completed and by_current.completed, by_current.message
    force_error = np.max(np.abs(by_force.pose - q))
    current_error = np.max(np.abs(by_current.pose - q))
    print(f"{fidelity}: pose error by force {force_error:.3g}, by current {current_error:.3g}")
    assert force_error < 1e-6
    assert current_error < 1e-6
    # the outputs by the law: motor speed c L_dot, torque k_t i, voltage R i + k_t omega
    np.testing.assert_allclose(by_current.current, currents, rtol=0, atol=1e-12)
    np.testing.assert_allclose(by_current.motor_speed, c * by_current.length_rate, rtol=1e-12,
                               atol=1e-9)
    np.testing.assert_allclose(by_current.motor_torque, DRIVE["torque_constant"] * currents,
                               rtol=1e-12, atol=1e-12)
    voltage = DRIVE["winding_resistance"] * currents + DRIVE["torque_constant"] * by_current.motor_speed
    np.testing.assert_allclose(by_current.voltage, voltage, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(by_current.electrical_power, voltage * currents, rtol=1e-12,
                               atol=1e-9)
    # the leg forces the drives made are the inverse's, to the round trip's accuracy
    assert np.max(np.abs(by_current.force - inv.force)) < 1e-2 * np.max(np.abs(inv.force))
    # force input reports its input as the leg force
    np.testing.assert_array_equal(by_force.force, inv.force)


def test_current_input_without_drives_is_refused():
    with pytest.raises(stewart.ParameterError, match="screw_lead"):
        stewart.Platform().simulate([0, 1e-3], np.zeros((2, 6)), input="current")
    with pytest.raises(stewart.ParameterError, match="input = 'torque' must be one of force, current, voltage"):
        stewart.Platform(**DRIVE).simulate([0, 1e-3], np.zeros((2, 6)), input="torque")


@pytest.mark.parametrize("value", [1.5, 0.999, float("inf"), float("nan")])
def test_input_number_that_names_no_kind_is_refused(value):
    # int() would take 1.5 or 0.999 for another kind (current, force) and fail on inf unhandled
    with pytest.raises(stewart.ParameterError, match="input = .* must be one of 0 .force."):
        stewart.Platform(**DRIVE).simulate([0, 1e-3], np.zeros((2, 6)), input=value)
    assert stewart.PlantInput.of(1.0) is stewart.PlantInput.CURRENT


# ---------------------------------------------------------------- the plant FMUs

def test_stiff_windings_name_their_cure():
    # L / R = 1e-7 s: the explicit default fails within a step; the message says why and what
    # takes it (BDF runs the same)
    platform = stewart.Platform(**{**DRIVE, "winding_resistance": 1.0}, winding_inductance=1e-7)
    t = np.linspace(0.0, 0.01, 11)
    volts = np.full((11, 6), 2.0)
    run = platform.simulate(t, volts, input="voltage", max_internal_steps=2000)
    assert not run.completed
    assert "stiff windings (L/R = 1e-07 s: take method = bdf)" in run.message, run.message
    # the plant's first step (its creation) fails so when L/R is far below the step it tries
    with pytest.raises(stewart.ParameterError, match=r"stiff windings \(L/R = 1e-12 s: take "
                       r"method = bdf\)"):
        stewart.Platform(**{**DRIVE, "winding_resistance": 1.0},
                         winding_inductance=1e-12).simulate(t, volts, input="voltage")
    assert platform.simulate(t, volts, input="voltage", method="bdf").completed


def fmu_drive(input_kind=1):
    """The drive's parameters as the FMUs name them (one per leg), and the input kind."""
    values = {f"{name}[{k}]": v for name, v in DRIVE.items() for k in range(1, 7)}
    values["input"] = input_kind
    return values


HOLD = [0.45, 0.40, 0.43, 0.41, 0.44, 0.42]  # currents about those that hold the platform [A]


@pytest.mark.parametrize("version", ["2.0", "3.0"])
@pytest.mark.parametrize("fidelity", [1, 2])
def test_co_simulation_fmu_takes_currents_as_the_library_does(version, fidelity):
    """StewartPlant with input = 1: its F[k] inputs carry currents, held over each step; its pose
    and drive outputs are Platform.simulate's on the same currents, to rounding."""
    from test_plant_fmu import Instance
    h, n = 1e-3, 200
    t = np.arange(n + 1) * h
    currents = np.tile(HOLD, (n + 1, 1))
    lib = stewart.Platform(**DRIVE).simulate(t, currents, fidelity, input="current")
    assert lib.completed, lib.message
    u = Instance("StewartPlant", version, "driven").init(fidelity=fidelity, **fmu_drive())
    names = (list(scenes.POSE) + [f"current[{k}]" for k in range(1, 7)] +
             [f"motor_speed[{k}]" for k in range(1, 7)] + [f"force[{k}]" for k in range(1, 7)] +
             [f"electrical_power[{k}]" for k in range(1, 7)])
    try:
        got = []
        for j in range(n):
            u.set_reals([f"F[{k}]" for k in range(1, 7)], currents[j])
            assert u.step(t[j], h) == 0, u.messages[-3:]
            got.append(u.get(names))
        got = np.array(got)
    finally:
        u.free()
    want = np.column_stack([lib.pose, lib.current, lib.motor_speed, lib.force,
                            lib.electrical_power])[1:]
    assert np.abs(lib.pose[-1] - lib.pose[0]).max() > 1e-4  # the currents did move it
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_model_exchange_fmu_under_cvode_follows_the_co_simulation_plant(version):
    """StewartPlantME with input = 1 under fmpy's CVODE against StewartPlant under the same
    currents (held): the two integrators agree to their tolerances."""
    from test_plant_fmu import Instance, fmu_file
    import fmpy
    t_end, h = 0.2, 1e-3
    names = list(scenes.POSE) + [f"motor_speed[{k}]" for k in range(1, 7)]
    table = np.array([(0.0, *HOLD), (1e3, *HOLD)],
                     dtype=[("time", float)] + [(f"F[{k}]", float) for k in range(1, 7)])
    result = fmpy.simulate_fmu(fmu_file("StewartPlantME", version), fmi_type="ModelExchange",
                               solver="CVode", relative_tolerance=1e-10, stop_time=t_end,
                               output_interval=h, start_values=fmu_drive(), input=table,
                               output=names)
    u = Instance("StewartPlant", version, "cs").init(**fmu_drive())
    try:
        rows = [u.get(names)]
        for j in range(int(round(t_end / h))):
            u.set_reals([f"F[{k}]" for k in range(1, 7)], HOLD)
            assert u.step(j * h, h) == 0
            rows.append(u.get(names))
    finally:
        u.free()
    me = np.column_stack([result[n] for n in names])
    keep = np.append(np.diff(result["time"]) > 0, True)
    me = me[keep]
    cs = np.array(rows)
    assert me.shape == cs.shape
    err = np.abs(me[:, :6] - cs[:, :6]).max()
    print(f"ME under CVODE against CS, FMI {version}: pose {err:.3g}")
    assert err < 1e-7
    np.testing.assert_allclose(me[:, 6:], cs[:, 6:], rtol=1e-6, atol=1e-6)


def test_stewart_simulate_takes_the_input_option(tmp_path):
    """stewart-simulate --param input=1 with the drive's parameters: Platform.simulate's rows."""
    import subprocess
    from fmu_support import BUILD
    h, n = 1e-3, 50
    t = np.arange(n + 1) * h
    currents = np.tile(HOLD, (n + 1, 1))
    with open(tmp_path / "in.csv", "w") as f:
        f.write("t,F1,F2,F3,F4,F5,F6\n")
        for ti, row in zip(t, currents):
            f.write(",".join(repr(float(v)) for v in (ti, *row)) + "\n")
    params = [a for name, v in DRIVE.items() for a in ("--param", f"{name}={v!r}")]
    r = subprocess.run([str(BUILD / "stewart-simulate"), *params, "--param", "input=1",
                        str(tmp_path / "in.csv"), str(tmp_path / "out.csv")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    out = np.genfromtxt(tmp_path / "out.csv", delimiter=",", names=True)
    lib = stewart.Platform(**DRIVE).simulate(t, currents, input="current")
    np.testing.assert_allclose(out["z"], lib.pose[:, 2], rtol=0, atol=1e-12)
    np.testing.assert_allclose(out["current1"], lib.current[:, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(out["motor_speed3"], lib.motor_speed[:, 2], rtol=0, atol=1e-9)


LOSSES = dict(screw_efficiency=0.9, screw_back_efficiency=0.8, coulomb_friction=40.0,
              stribeck_friction=60.0, stribeck_speed=0.01, viscous_friction=300.0)


def law_currents(force, rate, accel, vs):
    """The plant's drive law (docs/drives.md) solved for the current, written here: the nut
    pushes F + friction, the screw's factor e = 1 + (eta - 1) x (x >= 0) or
    1 - (1 / eta_back - 1) x with x = sign(F_nut) v / sqrt(v^2 + v_s^2), then
    i = (F_nut / e + m_r L_ddot) / (c k_t)."""
    s = rate / np.sqrt(rate ** 2 + vs ** 2)
    slide = LOSSES["coulomb_friction"] + (LOSSES["stribeck_friction"] - LOSSES["coulomb_friction"]) * np.exp(
        -(rate / LOSSES["stribeck_speed"]) ** 2)
    nut = force + slide * s + LOSSES["viscous_friction"] * rate
    x = np.where(nut >= 0, 1.0, -1.0) * s
    e = np.where(x >= 0, 1 + (LOSSES["screw_efficiency"] - 1) * x,
                 1 - (1 / LOSSES["screw_back_efficiency"] - 1) * x)
    c = motor_per_leg()
    return (nut / e + motor_inertia() * c * c * accel) / (c * DRIVE["torque_constant"])


@pytest.mark.parametrize("smoothing_speed", [1e-2, 1e-4])
def test_inverse_currents_with_losses_reproduce_the_cue(smoothing_speed):
    """Friction and the screw's efficiency in both directions: the currents of the law reproduce
    the cue within the force round trip's bound (1e-6) where the samples resolve the law's turns
    (v_s = 1e-2 m/s: 2.9e-8); at the default v_s = 1e-4 m/s a leg's reversal takes about 1e-4 s,
    which 0.25 ms samples linear in between do not resolve (measured 1.8e-6): bound 1e-5."""
    dt, duration = 2.5e-4, 1.0
    scene = scenes.load("combined")
    scene["duration"] = duration
    t = np.arange(0, duration + dt / 2, dt)
    q, qd, qdd = scenes.pose(scene, t)
    platform = stewart.Platform(**DRIVE, **LOSSES)
    inv = platform.inverse(q, qd, qdd, fidelity="full")
    currents = law_currents(inv.force, inv.length_rate, inv.length_accel, smoothing_speed)
    run = platform.simulate(t, currents, "full", q[0], qd[0], input="current",
                            smoothing_speed=smoothing_speed, relative_tolerance=1e-12,
                            absolute_tolerance=1e-14)
    assert run.completed, run.message
    error = np.max(np.abs(run.pose - q))
    reversals = int(np.sum(np.diff(np.sign(inv.length_rate), axis=0) != 0))
    print(f"losses, v_s {smoothing_speed:g}: pose error {error:.3g} ({reversals} leg reversals)")
    assert reversals > 0  # the law's turns are crossed
    assert error < (1e-6 if smoothing_speed >= 1e-2 else 1e-5)


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_voltage_with_inductance_in_the_fmu_rolls_back_and_is_the_librarys(version):
    """StewartPlant with input = 2 and winding inductances: the windings' currents are states;
    the FMU's state (get, serialise, set) carries them, so a rollback repeats the steps bit for
    bit, and the run is Platform.simulate's on the same voltages."""
    from test_plant_fmu import Instance
    inductance = {f"winding_inductance[{k}]": 5e-3 for k in range(1, 7)}
    h, n = 1e-3, 40
    t = np.arange(n + 1) * h
    volts = 1.2 * np.tile(HOLD, (n + 1, 1))  # held: the FMU's zero-order hold is the library's line
    lib = stewart.Platform(**DRIVE, **{"winding_inductance": 5e-3}).simulate(
        t, volts, input="voltage")
    assert lib.completed, lib.message
    assert lib.current[0].max() == 0 and lib.current[-1].min() > 0.1  # from 0, rising
    u = Instance("StewartPlant", version, "volts").init(**fmu_drive(2), **inductance)
    names = list(scenes.POSE) + [f"current[{k}]" for k in range(1, 7)]
    F = [f"F[{k}]" for k in range(1, 7)]

    def run(first, last):
        rows = []
        for j in range(first, last):
            u.set_reals(F, volts[j])
            assert u.step(t[j], h) == 0, u.messages[-3:]
            rows.append(u.get(names))
        return np.array(rows)

    try:
        head = run(0, 20)
        state = u.get_state()
        blob = u.serialize(state)
        tail = run(20, n)
        u.set_state(u.deserialize(blob))
        again = run(20, n)
    finally:
        u.free()
    assert again.tobytes() == tail.tobytes()
    want = np.column_stack([lib.pose, lib.current])[1:]
    # within the integrator's tolerance (rtol 1e-10), as the force-driven FMU and the library
    # agree (test_plant_fmu): measured 3e-11 relative on the currents
    np.testing.assert_allclose(np.vstack([head, tail]), want, rtol=1e-9, atol=1e-12)
