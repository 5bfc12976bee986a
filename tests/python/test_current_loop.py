"""The closed loop on currents (docs/drives.md, "Closing the loop on currents"): the controller's
cascade (output = 1) against its law written here, a held static load against the drive law's
closed form, and the loop inverse unit -> cascade -> current-driven plant tracking the combined
cue and a planned move on every shipped machine with drives, at both master clocks, FMI 2 and 3,
Gauss-Seidel and Jacobi coupling, within a bound derived from the force loop on the same
machine."""
import math

import numpy as np
import pytest

import closed_loop
import scenes
import stewart
from fmu_support import VERSIONS
from test_plant_fmu import DISCARD, OK, Instance

POSE = list(scenes.POSE)
LEGS = closed_loop.legs
INPUTS = LEGS("L_ref") + LEGS("L_dot_ref") + LEGS("F_ff") + LEGS("L") + LEGS("L_dot")
DRIVE_MACHINES = sorted(name for name in stewart.platform_files() if name.endswith("_drives"))
H = 1e-3


def cascade_law(drive, gains, ref, rate_ref, feed_forward, length, rate, integral):
    """The cascade as docs/drives.md writes it, one leg at a time (arrays over the legs):
    c = 2 pi N / lead; omega_cmd = c L_dot_ref + Kp c (L_ref - L) within +-motor_speed_max;
    tau = Kv (omega_cmd - c L_dot + z / Ti); i = i_ff + tau / k_t within +-current_max.
    Returns (i, speed error)."""
    c = 2 * np.pi * drive["gear_ratio"] / drive["screw_lead"]
    omega = c * rate_ref + gains["position_gain"] * c * (ref - length)
    limit = drive["motor_speed_max"]
    omega = np.where(limit > 0, np.clip(omega, -limit, limit), omega)
    error = omega - c * rate
    ti = gains["speed_integral_time"]
    torque = gains["speed_gain"] * (error + (integral / ti if ti > 0 else 0.0))
    current = feed_forward + torque / drive["torque_constant"]
    limit = drive["current_max"]
    return np.where(limit > 0, np.clip(current, -limit, limit), current), error


def drive_parameters(drive):
    return {f"{name}[{k + 1}]": value[k] for name, value in drive.items() for k in range(6)}


@pytest.mark.parametrize("version", VERSIONS)
def test_cascade_is_its_law(version):
    """Random inputs on legs with different drives: the currents equal the law above to
    rounding, the integral is h times the speed error per step with the inputs held, both limits
    cut where they should, and a current held at its limit stops the integral (no wind-up)."""
    rng = np.random.default_rng(11)
    drive = {"screw_lead": rng.uniform(0.004, 0.02, 6), "gear_ratio": rng.uniform(1, 3, 6),
             "torque_constant": rng.uniform(0.3, 1.2, 6), "current_max": np.r_[0, 0, 0, 40, 40, 40],
             "motor_speed_max": np.r_[0, 300, 0, 300, 0, 300]}
    gains = {"position_gain": 80.0, "speed_gain": 0.9, "speed_integral_time": 0.05}
    u = Instance("StewartController", version).init(output=1, **gains, **drive_parameters(drive))
    try:
        integral = np.zeros(6)
        for trial in range(6):
            ref, rate_ref = 0.5 + rng.normal(0, 0.01, 6), rng.normal(0, 0.05, 6)
            length, rate = ref + rng.normal(0, 2e-3, 6), rate_ref + rng.normal(0, 0.05, 6)
            feed_forward = rng.normal(0, 10, 6)
            u.set_reals(INPUTS, [*ref, *rate_ref, *feed_forward, *length, *rate])
            expected, error = cascade_law(drive, gains, ref, rate_ref, feed_forward, length, rate,
                                          integral)
            np.testing.assert_allclose(u.get(LEGS("F")), expected, rtol=1e-13, atol=1e-12)
            assert u.step(trial * H, H) == OK  # the inputs held over the step
            held = (np.abs(expected) >= drive["current_max"]) & (drive["current_max"] > 0) & (
                error * expected > 0)
            integral = np.where(held, integral, integral + H * error)
            after, _ = cascade_law(drive, gains, ref, rate_ref, feed_forward, length, rate,
                                   integral)
            np.testing.assert_allclose(u.get(LEGS("F")), after, rtol=1e-13, atol=1e-12)
        # the limits met on the legs that have them: a large error
        u.set_reals(LEGS("L"), ref - 0.05)
        current = u.get(LEGS("F"))
        assert np.all(np.abs(current[3:]) == 40.0)
        before = u.get(LEGS("F"))
        for j in range(3):  # held at +40 A with a positive speed error: the integral stays
            assert u.step((6 + j) * H, H) == OK
        np.testing.assert_array_equal(u.get(LEGS("F"))[3:], before[3:])
        u.set(**{"L[2]": math.nan})
        assert u.step(9 * H, H) == DISCARD and u.get(["status"])[0] == 3
        assert any("L[2]" in m for m in u.messages), u.messages
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_force_mode_is_unchanged_by_the_drive_parameters(version):
    """output = 0 (the default) with every cascade parameter given: F = F_ff + kp (L_ref - L) +
    kd (L_dot_ref - L_dot), the PD, bit for bit as without them, and steps keep no state."""
    rng = np.random.default_rng(3)
    values = [*(0.5 + rng.normal(0, 0.01, 6)), *rng.normal(0, 0.1, 6), *rng.normal(300, 50, 6),
              *(0.5 + rng.normal(0, 0.01, 6)), *rng.normal(0, 0.1, 6)]
    runs = []
    for extra in ({}, {"position_gain": 50.0, "speed_gain": 2.0, "speed_integral_time": 0.1,
                       **drive_parameters({"screw_lead": np.full(6, 0.01),
                                           "torque_constant": np.full(6, 0.5),
                                           "current_max": np.full(6, 1.0)})}):
        u = Instance("StewartController", version).init(kp=2e5, kd=3e3, **extra)
        try:
            u.set_reals(INPUTS, values)
            first = u.get(LEGS("F"))
            assert u.step(0.0, H) == OK and u.step(H, H) == OK
            runs.append((first.tobytes(), u.get(LEGS("F")).tobytes()))
        finally:
            u.free()
    assert runs[0] == runs[1] and runs[0][0] == runs[0][1]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("bad,words", [
    ({"speed_gain": 0.0}, ["speed_gain", "speed gain > 0"]),
    ({"screw_lead[3]": 0.0}, ["screw_lead[3]", "drive on every leg"]),
    ({"torque_constant[6]": -1.0}, ["torque_constant[6]"]),
    ({"current_max[2]": -1.0}, ["current_max[2]", ">= 0"]),
    ({"speed_integral_time": math.nan}, ["speed_integral_time", "finite"]),
    ({"output": 2}, ["output = 2", "outside its declared range [0, 1]"]),
    ({"screw_lead[2]": 1e-310}, ["screw_lead[2] = 1e-310", "overflows a double"])])
def test_current_mode_without_a_drive_is_refused(version, bad, words):
    parameters = {"output": 1, "speed_gain": 1.0,
                  **drive_parameters({"screw_lead": np.full(6, 0.01),
                                      "torque_constant": np.full(6, 0.5)}), **bad}
    u = Instance("StewartController", version)
    try:
        with pytest.raises(Exception):  # fmpy raises on the Error status
            u.init(**parameters)
        assert any(all(w in m for w in words) for m in u.messages), u.messages
    finally:
        u.free()


def machine_units(name, version, drive, fidelity=2, **plant_start):
    """The three units of the loop on the shipped machine `name` with the controller's `drive`
    ("force": the PD of machine_gains; "current": the cascade of cascade_gains)."""
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    machine = stewart.fmu_start_values(platform, version)
    if drive == "force":
        kp, kd = closed_loop.machine_gains(platform)
        controls = {"kp": kp, "kd": kd}
    else:
        controls = closed_loop.controller_parameters(platform, machine)
    units = {"inverse": Instance("StewartPlatform", version, "inverse").init(
                 fidelity=fidelity, derivatives=1, **machine),
             "controller": Instance("StewartController", version, "controller").init(**controls),
             "plant": Instance("StewartPlant", version, "plant").init(
                 fidelity=fidelity, input=closed_loop.DRIVES.index(drive), **machine,
                 **plant_start)}
    return platform, units, controls


def test_held_static_load_needs_the_drive_laws_current():
    """simona_motion_base_drives held at home, at rest, by the cascade fed forward with the
    inverse unit's currents. The inverse takes the screw's forward efficiency at rest (docs/
    drives.md), so its current is F lead / (2 pi N eta k_t) for the static leg force F; the plant
    takes the screw lossless at rest (its efficiency fades to 1 below smoothing_speed), so it
    is held by F lead / (2 pi N k_t): the speed loop's integral must carry the difference.
    After 3 s the current is that closed form to 1e-6 and the legs are at their references to
    1e-9 m."""
    name = "simona_motion_base_drives"
    home = stewart.Platform.from_file(stewart.platform_files()[name]).check().home
    start = {f"{p}0": v for p, v in zip(POSE, home)}
    platform, units, _ = machine_units(name, "2.0", "current", **start)
    try:
        inverse, controller, plant = units["inverse"], units["controller"], units["plant"]
        inverse.set_reals(POSE, home)
        reference = inverse.get(LEGS("L") + LEGS("L_dot") + LEGS("current"))
        force = inverse.get(LEGS("F"))
        p = closed_loop.leg_values(platform)
        lead, n, kt, eta = p["screw_lead"], p["gear_ratio"], p["torque_constant"], \
            p["screw_efficiency"]
        np.testing.assert_allclose(reference[12:], force * lead / (2 * np.pi * n * eta * kt),
                                   rtol=1e-12)
        for j in range(3000):
            measured = plant.get(LEGS("L") + LEGS("L_dot"))
            controller.set_reals(INPUTS, [*reference, *measured])
            sent = controller.get(LEGS("F"))
            plant.set_reals(LEGS("F"), sent)
            for u in units.values():
                assert u.step(j * H, H) == OK
        np.testing.assert_array_equal(plant.get(LEGS("current")), sent)  # the plant took it
        measured = plant.get(LEGS("L") + LEGS("L_dot"))
        controller.set_reals(INPUTS, [*reference, *measured])
        held = controller.get(LEGS("F"))
        print("held current", held, "closed form", force * lead / (2 * np.pi * n * kt))
        np.testing.assert_allclose(held, force * lead / (2 * np.pi * n * kt), rtol=1e-6)
        np.testing.assert_allclose(measured[:6], reference[:6], rtol=0, atol=1e-9)
    finally:
        for u in units.values():
            u.free()


def machine_loop(name, version, coupling, clock, drive, horizon=1.0, scene="combined"):
    """The loop on machine `name` over `horizon` of `scene` scaled to its ranges (a move's
    horizon None: the move and its hold):
    (cue, achieved pose, reference lengths, rates and feed-forward, measured lengths) per
    communication point, and the inverse unit's leg forces. coupling "gauss-seidel":
    scripts/closed_loop.py's order (the plant's command at t computed from its state at t);
    "jacobi": libcosim's (every unit steps from the values transferred after the last step: the
    command one step late). clock "j*h": the master
    passes t = j h, "t+=h": the sum of its steps."""
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    scene = stewart.scenes.on_platform(scenes.load(scene), platform, scale_to_ranges=True)
    t, cue, cue_dot, cue_ddot = scenes.trajectory(scene, platform, H, horizon)
    start = {f"{p}0": v for p, v in zip(POSE, cue[0])}
    start.update({f"{p}_dot0": v for p, v in zip(POSE, cue_dot[0])})
    _, units, _ = machine_units(name, version, drive, **start)
    inverse, controller, plant = units["inverse"], units["controller"], units["plant"]
    feed_forward = "F" if drive == "force" else "current"
    n = len(t) - 1
    pose, reference, measured = np.zeros((n + 1, 6)), np.zeros((n + 1, 18)), np.zeros((n + 1, 6))
    force = np.zeros((n + 1, 6))

    def transfer(j, command_from_new_inputs):
        inverse.set_reals(POSE + list(scenes.DOT) + list(scenes.DDOT),
                          [*cue[j], *cue_dot[j], *cue_ddot[j]])
        late = controller.get(LEGS("F"))  # from the inputs of the last transfer
        reference[j] = inverse.get(LEGS("L") + LEGS("L_dot") + LEGS(feed_forward))
        force[j] = inverse.get(LEGS("F"))
        lengths = plant.get(LEGS("L") + LEGS("L_dot"))
        measured[j], pose[j] = lengths[:6], plant.get(POSE)
        controller.set_reals(INPUTS, [*reference[j], *lengths])
        plant.set_reals(LEGS("F"), controller.get(LEGS("F")) if command_from_new_inputs else late)

    try:
        transfer(0, True)  # both couplings start from the initialised chain
        time = 0.0
        for j in range(n):
            now = j * H if clock == "j*h" else time
            for u in units.values():
                assert u.step(now, H) == OK, (name, j)
            time += H
            transfer(j + 1, coupling == "gauss-seidel")
        return cue, pose, reference, measured, force
    finally:
        for u in units.values():
            u.free()


@pytest.fixture(scope="module")
def force_loops():
    cache = {}

    def get(name, version, coupling, clock, scene):
        key = (name, version, coupling, clock, scene)
        if key not in cache:
            cache[key] = machine_loop(name, version, coupling, clock, "force",
                                      SCENES[scene], scene)
        return cache[key]
    return get


# The cues: 1 s of the combined scene's sinusoids, and a planned move with its hold at rest.
SCENES = {"combined": 1.0, "move_line": None}


@pytest.mark.parametrize("name", DRIVE_MACHINES)
@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("coupling", ["gauss-seidel", "jacobi"])
@pytest.mark.parametrize("clock", ["j*h", "t+=h"])
@pytest.mark.parametrize("scene", SCENES)
def test_current_loop_tracks_the_cue(name, version, coupling, clock, scene, force_loops):
    """The bound, derived: the cascade on the motor side is the PD of machine_gains on the
    leg's side (speed bandwidth kd / m, position gain kp / kd) with the drive's inertia added to
    m and a speed integral, so its leg-length error is the force loop's plus what the
    feed-forward misses. The inverse's current takes the screw's efficiency by the exact sign of
    the power flow; the plant fades it to 1 within smoothing_speed of rest; so the force the
    feed-forward current makes differs from the leg force F_ff by at most
    |F_ff| max(1/eta - 1, 1 - eta_back) (the plant's blend between those ends). A force
    disturbance dF moves a P loop of stiffness K = speed_gain position_gain c^2 (per leg, on the
    leg's side) by dF / K, the overdamped loop never more, and the integral only removes it:
        max |L - L_ref| (current) <= max |L - L_ref| (force) + max |F_ff| max(1/eta - 1,
        1 - eta_back) / K.
    And both loops stay within 1 % of the cue's excursion (the machines' bound of
    test_ssp.py)."""
    cue, pose, reference, measured, force = machine_loop(name, version, coupling, clock,
                                                         "current", SCENES[scene], scene)
    f_cue, f_pose, f_reference, f_measured, _ = force_loops(name, version, coupling, clock,
                                                            scene)
    np.testing.assert_array_equal(cue, f_cue)
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    gains = closed_loop.cascade_gains(platform)
    p = closed_loop.leg_values(platform)
    c = 2 * np.pi * p["gear_ratio"] / p["screw_lead"]
    stiffness = gains["speed_gain"] * gains["position_gain"] * np.min(c)**2
    loss = max(np.max(1 / p["screw_efficiency"] - 1), np.max(1 - p["screw_back_efficiency"]))
    leg_error = np.abs(measured - reference[:, :6]).max()
    force_leg_error = np.abs(f_measured - f_reference[:, :6]).max()
    bound = force_leg_error + np.abs(force).max() * loss / stiffness
    position, angle = np.abs(pose - cue)[:, :3].max(), np.abs(pose - cue)[:, 3:].max()
    f_position, f_angle = np.abs(f_pose - f_cue)[:, :3].max(), np.abs(f_pose - f_cue)[:, 3:].max()
    print(f"{name} {scene} {version} {coupling} {clock}: legs {leg_error:.2e} m (force loop "
          f"{force_leg_error:.2e}, bound {bound:.2e}); pose {position:.2e} m, {angle:.2e} rad "
          f"(force loop {f_position:.2e} m, {f_angle:.2e} rad)")
    assert leg_error <= bound
    home = platform.check().home
    excursion = np.abs(cue - home).max(axis=0)
    assert position <= 1e-2 * excursion[:3].max() and f_position <= 1e-2 * excursion[:3].max()
    assert angle <= 1e-2 * max(excursion[3:].max(), 1e-6)


def test_script_runs_the_loop_on_currents(tmp_path):
    """scripts/closed_loop.py --drive current: the same loop as the Gauss-Seidel master above
    (FMI 2, t = j h), to rounding."""
    name = "rubin_m2_hexapod_drives"
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    scene = stewart.scenes.on_platform(scenes.load("combined"), platform, scale_to_ranges=True)
    result = closed_loop.run(scene, 0.3, H, machine=stewart.fmu_start_values(platform),
                             platform=platform, drive="current")[0]
    cue, pose, reference, _, _ = machine_loop(name, "2.0", "gauss-seidel", "j*h", "current", 0.3)
    np.testing.assert_array_equal(result["cue"], cue)
    np.testing.assert_allclose(result["pose"], pose, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result["feed_forward"], reference[:, 12:], rtol=1e-14)
    with pytest.raises(ValueError, match="drives"):
        closed_loop.run("combined", 0.01, H, drive="current")


@pytest.mark.parametrize("version", VERSIONS)
def test_cascade_derivatives_are_its_slopes(version):
    """Directional derivatives in current mode against central differences of the outputs (the
    cascade is piecewise linear: exact away from a limit's edge), with a nonzero integral; legs 3
    and 4 at their speed limit (the position and reference-rate paths cut), legs 5 and 6 at
    their current limit (every slope 0)."""
    drive = {"screw_lead": np.full(6, 0.01), "gear_ratio": np.full(6, 2.0),
             "torque_constant": np.full(6, 0.7), "current_max": np.r_[0, 0, 0, 0, 5, 5],
             "motor_speed_max": np.r_[0, 0, 50, 50, 0, 0]}
    u = Instance("StewartController", version).init(
        output=1, position_gain=60.0, speed_gain=0.4, speed_integral_time=0.03,
        **drive_parameters(drive))
    try:
        ref = np.full(6, 0.5)
        length = ref - np.r_[1e-4, -1e-4, 0.02, -0.02, 0.05, -0.05]
        point = [*ref, *np.full(6, 0.01), *np.full(6, 0.3), *length, *np.full(6, 0.005)]
        u.set_reals(INPUTS, point)
        assert u.step(0.0, H) == OK  # a nonzero integral
        outs, ins = [u.vr[n] for n in LEGS("F")], [u.vr[n] for n in INPUTS]
        J = np.array([u.fmu.getDirectionalDerivative(outs, ins, list(np.eye(30)[j]))
                      for j in range(30)]).T
        differences = np.zeros_like(J)
        for j, name in enumerate(INPUTS):
            step = 1e-7
            u.set_reals([name], [point[j] + step])
            up = u.get(LEGS("F"))
            u.set_reals([name], [point[j] - step])
            down = u.get(LEGS("F"))
            u.set_reals([name], [point[j]])
            differences[:, j] = (up - down) / (2 * step)
        np.testing.assert_allclose(J, differences, rtol=1e-6, atol=1e-6)
        c = 2 * np.pi * 2.0 / 0.01
        assert J[0, 0] == pytest.approx(0.4 * 60.0 * c / 0.7, rel=1e-14)  # dI/dL_ref
        assert J[2, 2] == 0 and J[2, 14] == 1 and J[2, 26] != 0  # speed limit: no position path
        assert not J[4:].any()  # at the current limit
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_cascade_state_rolls_back(version):
    """The speed loop's integral is part of the FMU state: restore a state, step again with the
    same inputs, the same output bytes; serialised and back, the same."""
    drive = {"screw_lead": np.full(6, 0.01), "torque_constant": np.full(6, 0.7)}
    u = Instance("StewartController", version).init(
        output=1, position_gain=60.0, speed_gain=0.4, speed_integral_time=0.03,
        **drive_parameters(drive))
    try:
        u.set_reals(INPUTS, [*np.full(6, 0.5), *np.zeros(6), *np.zeros(6),
                             *np.full(6, 0.499), *np.zeros(6)])
        assert u.step(0.0, H) == OK
        saved = u.get_state()
        blob = u.serialize(saved)
        outputs = []
        for j in range(2):
            assert u.step(H, H) == OK and u.step(2 * H, H) == OK
            outputs.append(u.get(LEGS("F")).tobytes())
            u.set_state(saved if j == 0 else u.deserialize(blob))
        assert outputs[0] == outputs[1]
        assert u.get(LEGS("F")).tobytes() != outputs[0]  # the integral went back
    finally:
        u.free()


def test_script_command_line(tmp_path):
    """--drive current: the CSV holds the commands as currents (current1..6, current_ff1..6);
    refused without a platform with drives, with a cascade gain for the force loop, and with a
    speed gain of 0, each with a message naming the cause."""
    import subprocess
    import sys
    from fmu_support import BUILD
    script = [sys.executable, str(closed_loop.ROOT / "scripts" / "closed_loop.py"),
              "--duration", "0.02", "--no-plot", "--out", str(tmp_path),
              "--fmus", str(BUILD / "fmus" / "2.0")]
    drives = ["--platform", str(stewart.platform_files()["rubin_m2_hexapod_drives"]),
              "--scale-to-ranges"]
    run = subprocess.run(script + drives + ["--drive", "current"], capture_output=True,
                         text=True, check=True)
    assert "current cascade: position_gain = 100 1/s" in run.stdout
    header = (tmp_path / "closed_loop.csv").read_text().splitlines()[0].split(",")
    assert header[13:25] == [f"current{k}" for k in range(1, 7)] + [
        f"current_ff{k}" for k in range(1, 7)]
    for extra, words in (
            (["--drive", "current"], "needs --platform with drives"),
            (["--platform", str(stewart.platform_files()["simona_motion_base"]), "--drive",
              "current"], "a drive on every leg"),
            (drives + ["--speed-gain", "1"], "for --drive current only"),
            (drives + ["--drive", "current", "--speed-gain", "0"], "--speed-gain = 0"),
            # these crashed (IndexError, an FMI error) or ran no step and printed inf
            (drives + ["--drive", "current", "--duration", "-1"],
             "--duration: -1: give a finite time > 0"),
            (drives + ["--drive", "current", "--step", "0"], "--step: 0: give a finite time > 0"),
            (drives + ["--drive", "current", "--duration", "0.0005"], "shorter than one --step")):
        refused = subprocess.run(script + extra, capture_output=True, text=True)
        assert refused.returncode != 0 and words in refused.stderr, (extra, refused.stderr)



@pytest.mark.parametrize("name, leg_changes", [(name, {}) for name in DRIVE_MACHINES] + [
    (DRIVE_MACHINES[0], {"gear_ratio[2]": 2.0, "torque_constant[5]": 0.5})])
def test_cascade_turns_legs_into_motors_as_the_library_does(name, leg_changes):
    """The controller states the drive's transmission c = 2 pi N / lead itself (it links only
    libm); the library's drive law gives it as the inverse unit's motor_speed / L_dot. The
    cascade's slope d i / d L_dot = -speed_gain c / k_t holds the library's c to rounding, also
    with one leg's gear ratio and another's torque constant set by element."""
    platform = stewart.Platform.from_file(stewart.platform_files()[name], **leg_changes)
    machine = stewart.fmu_start_values(platform)
    controls = closed_loop.controller_parameters(platform, machine)
    inverse = Instance("StewartPlatform", name="inverse").init(derivatives=1, **machine)
    controller = Instance("StewartController", name="controller").init(**controls)
    try:
        home = platform.check().home
        inverse.set_reals(POSE + list(scenes.DOT), [*home, 0.01, -0.02, 0.015, 0.01, 0.02, -0.01])
        c = inverse.get(LEGS("motor_speed")) / inverse.get(LEGS("L_dot"))
        controller.set_reals(INPUTS, [*inverse.get(LEGS("L")), *np.zeros(12),
                                      *inverse.get(LEGS("L")), *np.zeros(6)])
        outs, ins = [controller.vr[n] for n in LEGS("F")], [controller.vr[n] for n in LEGS("L_dot")]
        slope = np.array([controller.fmu.getDirectionalDerivative(outs, ins, list(np.eye(6)[k]))
                          for k in range(6)]).diagonal()
        kt = closed_loop.leg_values(platform)["torque_constant"]
        np.testing.assert_allclose(-slope * kt / controls["speed_gain"], c, rtol=1e-13)
    finally:
        inverse.free()
        controller.free()
