"""Directional derivatives of the Model Exchange plant (StewartPlantME, FMI 2 and 3) against
references independent of their code: central finite differences of the unit's own
GetDerivatives (the state derivatives) and GetReal (the lengths, length rates and base wrench)
with respect to every state and force, at random states of both fidelities, with and without
tool and user frames (the states the tool's pose in the user frame); the model
structure's dependencies against what a change of each state and force does to each output and
derivative; the declaration in the description (fmpy validate); the requests it refuses."""
import numpy as np
import pytest

import fmpy
from fmpy.validation import validate_fmu

from fmu_support import VERSIONS
from test_fmu_derivatives import declared_attribute
from test_plant_fmu import F, L, L_DOT, WRENCH, fmu_file, static_forces
from test_frames import tool_pose
from test_plant_me_fmu import FRAMES, OK, POSE_DDOT, STATES, MEInstance

OUTPUTS = L + L_DOT + WRENCH
KNOWNS = STATES + F
# Central differences: at h = 1e-5 (m, rad and their rates) the truncation error h^2 f'''/6 is
# about 1e-11 of the derivatives; the accelerations and the base wrench are affine in the forces:
# h = 1e-2 N there. Rounding (16 eps |f| / h) is not counted in the error below.
STEP = [1e-5] * 12 + [1e-2] * 6
RELATIVE = 1e-7
# Driven by currents or voltages (input = 1, 2) the rates also pass through the drives' friction:
# its Stribeck term exp(-(v / v_st)^2) (v_st = 0.01 m/s below) has third derivatives of order
# 1 / v_st^3, a relative truncation error of order (h / v_st)^2 = 1e-6 at h = 1e-5: 1e-5 allowed.
# The inputs enter affinely (the power flow's direction held): h = 1e-2 A or V.
RELATIVE_DRIVEN = 1e-5
# A drive on every leg with a lossy screw and friction (test_plant_drives.DRIVE's motor).
DRIVEN = {f"{name}[{k}]": value for name, value in dict(
    screw_lead=0.005, gear_ratio=3.0, rotor_inertia=2e-5, screw_inertia=9e-5,
    torque_constant=0.5, winding_resistance=1.2, screw_efficiency=0.9, screw_back_efficiency=0.85,
    coulomb_friction=40.0, stribeck_friction=60.0, stribeck_speed=0.01,
    viscous_friction=300.0).items() for k in range(1, 7)}
HOLD = np.array([0.45, 0.40, 0.43, 0.41, 0.44, 0.42])  # currents about those holding it [A]
INPUT = {"force": 0, "current": 1, "voltage": 2}


def inputs(drive, fidelity, rng):
    """Forces about those that hold the platform, or such currents, or voltages of a few V."""
    if drive == "force":
        return static_forces(fidelity) * rng.uniform(0.8, 1.2, 6)
    if drive == "current":
        return HOLD * rng.uniform(0.8, 1.2, 6)
    return rng.uniform(-5.0, 5.0, 6)


def at_point(me, x, forces):
    """The state and forces set; (state derivatives, outputs) from GetDerivatives and GetReal."""
    assert me.set_states(x) == OK
    me.set_reals(F, forces)
    status, dx = me.derivatives()
    assert status == OK, me.messages[-1:]
    return dx, me.get(OUTPUTS)


def directional(me, unknowns, knowns, seed):
    return np.array(me.fmu.getDirectionalDerivative([me.vr[n] for n in unknowns],
                                                    [me.vr[n] for n in knowns], list(seed)))


def random_state(rng, frames=None):
    """Pose and rates near home; with frames (parameters as FRAMES) the tool's in the user frame
    at a random platform pose."""
    pose = rng.uniform([-0.08, -0.08, 0.45, -0.12, -0.12, -0.2],
                       [0.08, 0.08, 0.55, 0.12, 0.12, 0.2])
    if frames:
        tool = np.array([frames[f"tool_frame[{i}]"] for i in range(1, 7)])
        user = np.array([frames[f"user_frame[{i}]"] for i in range(1, 7)])
        pose = tool_pose(pose, tool, user)
    return np.concatenate([pose, rng.uniform(-0.5, 0.5, 6)])


def block_error(exact, differences, values, h):
    rounding = 16 * np.finfo(float).eps * np.abs(values).max() / h
    error = max(np.abs(exact - differences).max() - rounding, 0.0)
    scale = np.abs(exact).max()
    return error / (scale if scale > 0 else 1.0)


@pytest.mark.parametrize("drive", ["force", "current", "voltage"])
@pytest.mark.parametrize("framed", [False, True])
@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
def test_derivatives_equal_central_differences(version, fidelity, framed, drive):
    rng = np.random.default_rng(40 + fidelity)
    frames = FRAMES if framed else {}
    drives = {} if drive == "force" else dict(DRIVEN, input=INPUT[drive])
    me = MEInstance(version).init(fidelity=fidelity, **frames, **drives).continuous()
    unknowns = STATES[6:] + POSE_DDOT + OUTPUTS  # the state derivatives (x' = x_dot ..), outputs
    worst = 0.0
    for _ in range(3):
        x = random_state(rng, frames)
        forces = inputs(drive, fidelity, rng)
        dx, y = at_point(me, x, forces)
        J = np.array([directional(me, unknowns, KNOWNS, np.eye(18)[j]) for j in range(18)]).T
        differences = np.zeros_like(J)
        for j in range(18):
            up, down = x.copy(), x.copy()
            f_up, f_down = forces.copy(), forces.copy()
            if j < 12:
                up[j] += STEP[j]
                down[j] -= STEP[j]
            else:
                f_up[j - 12] += STEP[j]
                f_down[j - 12] -= STEP[j]
            a, b = at_point(me, up, f_up), at_point(me, down, f_down)
            differences[:, j] = np.concatenate([a[0] - b[0], a[1] - b[1]]) / (2 * STEP[j])
        values = np.concatenate([dx, y])
        # blocks: rows x' (rates), q_ddot, L, L_dot, base force, base torque; columns q, q_dot, F
        rows = [range(0, 6), range(6, 12), range(12, 18), range(18, 24), range(24, 27),
                range(27, 30)]
        for r in rows:
            for c0 in (0, 6, 12):
                c = range(c0, c0 + 6)
                worst = max(worst, block_error(J[np.ix_(r, c)], differences[np.ix_(r, c)],
                                               values[list(r)], STEP[c0]))
        # x' = x_dot exactly, the lengths and their rates do not depend on the forces
        assert np.array_equal(J[:6, :12], np.hstack([np.zeros((6, 6)), np.eye(6)]))
        assert not J[:6, 12:].any() and not J[12:24, 12:].any()
        assert not J[12:18, 6:12].any()  # the lengths on the pose alone
    print(f"FMI {version} fidelity {fidelity}{' framed' if framed else ''} {drive} input: ME "
          f"directional derivatives vs central differences, worst block error {worst:.2e}")
    assert worst < (RELATIVE if drive == "force" else RELATIVE_DRIVEN)
    me.free()


# the drives' outputs (tests/python/test_plant_drives.py)
DRIVE_OUTPUTS = {"force", "current", "voltage", "motor_speed", "motor_torque",
                 "electrical_power", "current_max_legs", "voltage_max_legs",
                 "motor_speed_max_legs"}


@pytest.mark.parametrize("version", VERSIONS)
def test_dependencies_are_exact(version):
    """Each output's and state derivative's listed dependencies against a change of each state
    and force (full fidelity, a platform without symmetry, as the inverse unit's test): a known
    not listed leaves it bit for bit, a listed one changes it."""
    path = fmu_file("StewartPlantME", version)
    md = fmpy.read_model_description(path)
    start = {v.name: v.start for v in md.modelVariables}
    generic = {f"platform_angle[{k}]": float(start[f"platform_angle[{k}]"]) + 0.05 * k
               for k in range(1, 7)}
    generic["piston_mass"] = 1.3 * float(start["piston_mass"])
    me = MEInstance(version).init(fidelity=2, **generic).continuous()
    rng = np.random.default_rng(12)
    x = random_state(rng)
    forces = static_forces(2) * rng.uniform(0.8, 1.2, 6)
    unknowns = md.outputs + md.derivatives
    names = [u.variable.name for u in unknowns]

    def values():
        status, _ = me.derivatives()
        assert status == OK
        return dict(zip(names, me.get(names)))

    at_point(me, x, forces)
    base = values()
    changed = {n: set() for n in names}
    for j, known in enumerate(KNOWNS):
        up, f_up = x.copy(), forces.copy()
        if j < 12:
            up[j] = up[j] * 1.01 + 1e-3
        else:
            f_up[j - 12] *= 1.01
        at_point(me, up, f_up)
        after = values()
        for n in names:
            if after[n] != base[n]:
                changed[n].add(known)
    for u in unknowns:
        name = u.variable.name
        assert u.dependencies is not None, name
        listed = {d.name for d in u.dependencies}
        if name == "status":  # changes only at a stroke limit or a refused state
            assert changed[name] <= listed
            continue
        if name.split("[")[0] in DRIVE_OUTPUTS:
            # declared for current or voltage input, the most they depend on (a model
            # description's structure cannot follow the `input` parameter); this is force input
            assert changed[name] <= listed, name
            continue
        assert changed[name] == listed, name
    me.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_description_declares_derivatives(version):
    path = fmu_file("StewartPlantME", version)
    assert declared_attribute(path, version, "ModelExchange") == "true"
    assert validate_fmu(path) == []


@pytest.mark.parametrize("version", VERSIONS)
def test_refused_requests(version):
    me = MEInstance(version).init().continuous()
    at_point(me, random_state(np.random.default_rng(2)), static_forces(2))
    for unknown, known in ((["fidelity"], ["x"]), (["L[1]"], ["L[2]"]), (["x_ddot"], ["z0"])):
        with pytest.raises(Exception):
            directional(me, unknown, known, [1.0])
        assert "GetDirectionalDerivative" in me.messages[-1], me.messages[-1]
    # the instance stays usable
    assert np.isfinite(directional(me, ["x_ddot"], ["x"], [1.0])).all()
    me.free()
