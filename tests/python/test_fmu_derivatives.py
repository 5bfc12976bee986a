"""Directional derivatives of the inverse unit (StewartPlatform) and the controller unit through
fmpy, against references independent of the code: the leg Jacobian written out here (dL/dq, and dL_dot/dq_dot, the same
matrix), central finite differences of the unit's own outputs (every differentiable output,
every input, fidelity 0, 1, 2, rate inputs and finite-difference rates, FMI 2 and 3), and the
model structure's dependencies against what a change of each input does to each output; every
(output, input) pair the model structure lists answers, the outputs without a library Jacobian
(condition, limit margins, axis ranges, residual) against central differences too; the
controller's against its gains. Units without derivatives (the plant: no output depends on an
input within a step; the scene: no inputs) keep answering Error; fmpy validate accepts the
descriptions."""
import math
import zipfile
from xml.etree import ElementTree

import numpy as np
import pytest

import fmpy
from fmpy.validation import validate_fmu

from fmu_support import (BASE_WRENCH, ERROR, F, L, L_DDOT, L_DOT, OK, POSE, POSE_DDOT, POSE_DOT,
                         VERSIONS, Unit, fmu_path)

INPUTS = POSE + POSE_DOT + POSE_DDOT
DIFFERENTIABLE = L + L_DOT + L_DDOT + F + BASE_WRENCH
# Central differences: at h = 1e-5 (m, rad, and their rates) the truncation error h^2 f'''/6 is
# about 1e-11 of the derivatives; rounding adds 16 eps |f| / h, subtracted from the error below.
# Forces, L_ddot and the base wrench are affine in the accelerations: h = 1e-4 there.
STEP = [1e-5] * 12 + [1e-4] * 6
RELATIVE = 1e-7


def started(version, fidelity, derivatives, pose, rate=None, accel=None, **params):
    u = Unit(version)
    values = {"fidelity": fidelity, "derivatives": derivatives, **params}
    values.update(dict(zip(POSE, pose)))
    if rate is not None:
        values.update(dict(zip(POSE_DOT, rate)))
        values.update(dict(zip(POSE_DDOT, accel)))
    assert u.init(**values) == OK
    return u


def directional(u, unknowns, knowns, seed):
    vu = [u.vr[n] for n in unknowns]
    vk = [u.vr[n] for n in knowns]
    return np.array(u.fmu.getDirectionalDerivative(vu, vk, list(seed)))


def jacobian(u, unknowns=DIFFERENTIABLE, knowns=INPUTS):
    """The unit's Jacobian, one unit seed per column."""
    J = np.zeros((len(unknowns), len(knowns)))
    for j in range(len(knowns)):
        seed = np.zeros(len(knowns))
        seed[j] = 1.0
        J[:, j] = directional(u, unknowns, knowns, seed)
    return J


def outputs_at(u, values, names=DIFFERENTIABLE):
    u.set_values(values)
    return u.get_reals(names)


def random_point(rng):
    pose = rng.uniform([-0.08, -0.08, 0.45, -0.12, -0.12, -0.2], [0.08, 0.08, 0.55, 0.12, 0.12, 0.2])
    return pose, rng.uniform(-0.5, 0.5, 6), rng.uniform(-2, 2, 6)


def row_groups(names):
    """Rows grouped by unit: lengths, rates, accelerations, forces, base force, base torque."""
    groups = {}
    for i, n in enumerate(names):
        groups.setdefault(n.split("[")[0], []).append(i)
    return groups.values()


def check_against_differences(J, differences, values, steps):
    """Largest block error (rows of one output family x columns of one input order) relative to
    the block's largest entry, rounding of the differences (16 eps |f| / h) not counted."""
    worst = 0.0
    for rows in row_groups(DIFFERENTIABLE):
        for c0 in (0, 6, 12):
            cols = slice(c0, c0 + 6)
            exact = J[np.ix_(rows, range(c0, c0 + 6))]
            diff = differences[np.ix_(rows, range(c0, c0 + 6))]
            rounding = 16 * np.finfo(float).eps * np.abs(values[rows]).max() / steps[c0]
            error = max(np.abs(exact - diff).max() - rounding, 0.0)
            scale = np.abs(exact).max()
            worst = max(worst, error / (scale if scale > 0 else 1.0))
            del cols
    return worst


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [0, 1, 2])
def test_derivatives_with_rate_inputs_equal_central_differences(version, fidelity):
    rng = np.random.default_rng(21 + fidelity)
    pose, rate, accel = random_point(rng)
    u = started(version, fidelity, 1, pose, rate, accel)
    point = dict(zip(INPUTS, np.concatenate([pose, rate, accel])))
    J = jacobian(u)
    values = outputs_at(u, point)
    differences = np.zeros_like(J)
    for j, name in enumerate(INPUTS):
        h = STEP[j]
        up = outputs_at(u, {**point, name: point[name] + h})
        down = outputs_at(u, {**point, name: point[name] - h})
        differences[:, j] = (up - down) / (2 * h)
    u.set_values(point)
    worst = check_against_differences(J, differences, values, STEP)
    print(f"FMI {version} fidelity {fidelity}: directional derivatives vs central differences, "
          f"worst block error {worst:.2e}")
    assert worst < RELATIVE
    if fidelity == 0:  # no forces, no base wrench: constant zero
        assert not J[18:].any()
    u.fmu.terminate()
    u.fmu.freeInstance()


def leg_jacobian_written_out(u, pose):
    """dL_k/dq: (n_k, ((R b_k) x n_k) . E), E = [Rz Ry e_x, Rz e_y, e_z], from the unit's
    parameters (circles of joints: the default geometry)."""
    rb, pb = u.get_reals(["base_radius", "platform_radius"])
    ba = u.get_reals([f"base_angle[{k}]" for k in range(1, 7)])
    pa = u.get_reals([f"platform_angle[{k}]" for k in range(1, 7)])
    x, y, z, roll, pitch, yaw = pose
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    R = np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                  [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                  [-sp, cp * sr, cp * cr]])
    E = np.array([[cy * cp, -sy, 0], [sy * cp, cy, 0], [-sp, 0, 1]])
    J = np.zeros((6, 6))
    for k in range(6):
        a = np.array([rb * math.cos(ba[k]), rb * math.sin(ba[k]), 0])
        arm = R @ np.array([pb * math.cos(pa[k]), pb * math.sin(pa[k]), 0])
        d = np.array([x, y, z]) + arm - a
        n = d / np.linalg.norm(d)
        J[k, :3] = n
        J[k, 3:] = np.cross(arm, n) @ E
    return J


@pytest.mark.parametrize("version", VERSIONS)
def test_length_derivatives_are_the_leg_jacobian(version):
    rng = np.random.default_rng(5)
    pose, rate, accel = random_point(rng)
    u = started(version, 2, 1, pose, rate, accel)
    expected = leg_jacobian_written_out(u, pose)
    assert np.allclose(jacobian(u, L, POSE), expected, rtol=0, atol=1e-13)
    assert np.allclose(jacobian(u, L_DOT, POSE_DOT), expected, rtol=0, atol=1e-13)
    assert np.allclose(jacobian(u, L_DDOT, POSE_DDOT), expected, rtol=0, atol=1e-13)
    assert not jacobian(u, L, POSE_DOT + POSE_DDOT).any()


@pytest.mark.parametrize("version", VERSIONS)
def test_derivatives_through_finite_difference_rates(version):
    """derivatives = 0: the rates are divided differences of the pose over the last communication
    points, so the outputs at the next point depend on the pose input through them too."""
    rng = np.random.default_rng(8)
    pose, _, _ = random_point(rng)
    u = started(version, 2, 0, pose)
    h = 0.01
    for i in range(2):  # two earlier poses: the quadratic through three
        u.set_values(dict(zip(POSE, pose + 0.01 * (i + 1) * np.arange(1, 7) / 6)))
        assert u.do_step(i * h, h) == OK
    point = dict(zip(POSE, pose + 0.03 * np.arange(1, 7) / 6))
    u.set_values(point)
    J = jacobian(u, DIFFERENTIABLE, POSE)
    values = u.get_reals(DIFFERENTIABLE)
    differences = np.zeros_like(J)
    for j, name in enumerate(POSE):
        up = outputs_at(u, {**point, name: point[name] + 1e-6})
        down = outputs_at(u, {**point, name: point[name] - 1e-6})
        differences[:, j] = (up - down) / 2e-6
    u.set_values(point)
    worst = 0.0
    for rows in row_groups(DIFFERENTIABLE):
        exact, diff = J[rows], differences[rows]
        rounding = 16 * np.finfo(float).eps * np.abs(values[rows]).max() / 1e-6
        worst = max(worst, max(np.abs(exact - diff).max() - rounding, 0) / np.abs(exact).max())
    print(f"FMI {version}, finite-difference rates: worst block error {worst:.2e}")
    assert worst < RELATIVE
    # the rate inputs are unused in this mode
    assert not jacobian(u, DIFFERENTIABLE, POSE_DOT + POSE_DDOT).any()


@pytest.mark.parametrize("version", VERSIONS)
def test_dependencies_are_exact(version):
    """Each output's listed dependencies against a change of each input (rate inputs, full
    fidelity, a generic point of a platform without symmetry: on the thesis platform a joint on
    the roll axis makes that leg's length independent of roll, and equal leg bodies make the base
    force independent of the velocity): an input not listed leaves the output bit for bit, a
    listed one changes it."""
    md = fmpy.read_model_description(str(fmu_path(version)))
    rng = np.random.default_rng(3)
    pose, rate, accel = random_point(rng)
    start = {v.name: v.start for v in md.modelVariables}
    generic = {f"platform_angle[{k}]": float(start[f"platform_angle[{k}]"]) + 0.05 * k
               for k in range(1, 7)}
    # equal leg bodies (the thesis') cancel the velocity terms of the base force exactly
    generic["piston_mass"] = 1.3 * float(start["piston_mass"])
    if "limit_outputs" in start:  # the limits' outputs are zero unless asked for
        generic["limit_outputs"] = 2
    # a drive on every leg, so that the drives' outputs move with the pose (zero without one)
    for k in range(1, 7):
        generic |= {f"screw_lead[{k}]": 0.005, f"torque_constant[{k}]": 0.5,
                    f"winding_resistance[{k}]": 1.2, f"rotor_inertia[{k}]": 1e-4}
    u = started(version, 2, 1, pose, rate, accel, **generic)
    point = dict(zip(INPUTS, np.concatenate([pose, rate, accel])))
    outputs = [o.variable.name for o in md.outputs]
    base = dict(zip(outputs, u.get(outputs)))
    changed = {n: set() for n in outputs}
    for name in INPUTS:
        u.set_values({**point, name: point[name] * 1.01 + 1e-3})
        after = dict(zip(outputs, u.get(outputs)))
        for n in outputs:
            if after[n] != base[n]:
                changed[n].add(name)
    u.set_values(point)
    for o in md.outputs:
        listed = {d.name for d in o.dependencies}
        assert o.dependencies is not None
        # the limits' outputs (docs/limits.md) are minima over legs and pairs of legs: a small
        # move may leave one unchanged; they are checked not to move with an unlisted input
        limits = o.variable.name.startswith(("limit_", "range_"))
        if o.variable.name in ("status", "newton_iterations", "residual") or limits or \
                o.variable.type in ("Integer", "Int32"):
            # status checks every input but changes only at a limit; the iterations and the
            # residual (rounding after a solve the closed-form guess starts) need not move
            assert changed[o.variable.name] <= listed
            continue
        assert changed[o.variable.name] == listed, o.variable.name


@pytest.mark.parametrize("version", VERSIONS)
def test_description_declares_derivatives(version):
    assert declared_attribute(fmu_path(version), version) == "true"
    assert validate_fmu(str(fmu_path(version))) == []


def declared_attribute(path, version, interface="CoSimulation"):
    """providesDirectionalDerivative (FMI 2) or providesDirectionalDerivatives (FMI 3) of the
    interface's element, read from the XML (fmpy 0.3.32 reads the FMI 2 name in FMI 3 too)."""
    with zipfile.ZipFile(path) as z:
        root = ElementTree.fromstring(z.read("modelDescription.xml"))
    name = "providesDirectionalDerivative" + ("" if version == "2.0" else "s")
    return root.find(interface).get(name, "false")


@pytest.mark.parametrize("version", VERSIONS)
def test_refused_requests(version):
    rng = np.random.default_rng(4)
    pose, rate, accel = random_point(rng)
    u = started(version, 2, 1, pose, rate, accel)
    for unknown, known in ((["status"], ["x"]), (["L[1]"], ["L[2]"]), (["x"], ["y"])):
        with pytest.raises(Exception):
            directional(u, unknown, known, [1.0])
        status, _, message = u.messages[-1]
        assert status == ERROR and "GetDirectionalDerivative" in message, message
    # an Error on a bad request leaves the unit in Error only as FMI says: here it stays usable
    # (the request is refused before anything runs)
    assert np.isfinite(directional(u, ["L[1]"], ["x"], [1.0])).all()


@pytest.mark.parametrize("version", VERSIONS)
def test_controller_derivatives_are_its_gains(version):
    """The PD controller unit: F_k = F_ff,k + kp (L_ref,k - L_k) + kd (L_dot_ref,k - L_dot_k),
    its directional derivatives against central differences of its outputs (exact: it is
    linear), its dependencies leg by leg, fmpy validate."""
    path = fmu_path(version).parent / "StewartController.fmu"
    assert declared_attribute(path, version) == "true"
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    forces = [f"F[{k}]" for k in range(1, 7)]
    fmu = fmpy.instantiate_fmu(fmpy.extract(str(path)), md, fmi_type="CoSimulation")
    kp, kd = 2.5e5, 3e3
    rng = np.random.default_rng(6)
    point = dict(zip(inputs, rng.uniform(0.4, 0.6, len(inputs))))
    if version == "2.0":
        fmu.setReal([vr["kp"], vr["kd"]], [kp, kd])
        fmu.setupExperiment(startTime=0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        set_reals, get_reals = fmu.setReal, fmu.getReal
    else:
        fmu.setFloat64([vr["kp"], vr["kd"]], [kp, kd])
        fmu.enterInitializationMode(startTime=0)
        fmu.exitInitializationMode()
        set_reals, get_reals = fmu.setFloat64, fmu.getFloat64
    set_reals([vr[n] for n in inputs], list(point.values()))
    out_vrs, in_vrs = [vr[n] for n in forces], [vr[n] for n in inputs]
    J = np.array([fmu.getDirectionalDerivative(out_vrs, in_vrs, list(np.eye(len(inputs))[j]))
                  for j in range(len(inputs))]).T
    differences = np.zeros_like(J)
    for j, name in enumerate(inputs):
        set_reals([vr[name]], [point[name] + 1e-3])
        up = np.array(get_reals(out_vrs))
        set_reals([vr[name]], [point[name] - 1e-3])
        down = np.array(get_reals(out_vrs))
        set_reals([vr[name]], [point[name]])
        differences[:, j] = (up - down) / 2e-3
    assert np.allclose(J, differences, rtol=1e-7, atol=1e-7 * kp)
    assert sorted(np.unique(np.abs(J))) == [0.0, 1.0, kd, kp]
    for o in md.outputs:
        if o.variable.name in forces:
            k = forces.index(o.variable.name)
            assert {d.name for d in o.dependencies} == {
                n for j, n in enumerate(inputs) if J[k, j] != 0}
    fmu.terminate()
    fmu.freeInstance()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("unit", ["StewartPlant", "StewartScene"])
def test_units_without_derivatives_say_so(version, unit):
    path = fmu_path(version).parent / f"{unit}.fmu"
    assert declared_attribute(path, version) == "false"
    assert validate_fmu(str(path)) == []
    md = fmpy.read_model_description(str(path))
    fmu = fmpy.instantiate_fmu(fmpy.extract(str(path)), md, fmi_type="CoSimulation")
    output = next(v for v in md.modelVariables if v.causality == "output")
    inputs = [v for v in md.modelVariables if v.causality == "input"] or [output]  # the scene
    # has no inputs: any known is refused, first as not supported
    with pytest.raises(Exception, match="status 3"):  # Error: not supported
        fmu.getDirectionalDerivative([output.valueReference], [inputs[0].valueReference], [1.0])
    fmu.freeInstance()


POSE_OUTPUTS = (["condition", "residual"] + [f"limit_margin[{k}]" for k in range(1, 6)]
                + [f"range_min[{k}]" for k in range(1, 7)]
                + [f"range_max[{k}]" for k in range(1, 7)])


def started_within_limits(version, derivatives, seed):
    """A unit with the limit outputs at a random point within every limit (the first of the
    seed's points whose initialisation warns of none), and that point."""
    rng = np.random.default_rng(seed)
    for _ in range(50):
        pose, rate, accel = random_point(rng)
        u = Unit(version)
        values = {"fidelity": 2, "derivatives": derivatives, "limit_outputs": 2,
                  **dict(zip(INPUTS, np.concatenate([pose, rate, accel])))}
        if u.init(**values) == OK:
            return u, {n: values[n] for n in INPUTS}
        u.fmu.freeInstance()
    raise AssertionError("no point within the limits")


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("derivatives", [0, 1])
def test_every_declared_pair_answers(version, derivatives):
    """Each Real output the model structure lists, with each input its dependencies name, has a
    finite directional derivative (FMI: in step mode every listed Real output is an unknown of
    GetDirectionalDerivative), and an unlisted input contributes nothing."""
    md = fmpy.read_model_description(str(fmu_path(version)))
    u, _ = started_within_limits(version, derivatives, 12 + derivatives)
    for o in md.outputs:
        if o.variable.type not in ("Real", "Float64"):
            continue
        listed = [d.name for d in o.dependencies]
        assert listed, o.variable.name
        row = directional(u, [o.variable.name], INPUTS, np.ones(len(INPUTS)))
        assert np.isfinite(row).all(), o.variable.name
        for name in listed:
            value = directional(u, [o.variable.name], [name], [1.0])
            assert np.isfinite(value).all(), (o.variable.name, name)
        others = [n for n in INPUTS if n not in listed]
        if others:
            assert not directional(u, [o.variable.name], others, np.ones(len(others))).any()
    u.fmu.terminate()
    u.fmu.freeInstance()


@pytest.mark.parametrize("version", VERSIONS)
def test_pose_outputs_equal_central_differences(version):
    """condition, the limit margins and the axis ranges: their derivatives with respect to the
    pose against central differences of the unit's own outputs (the margins and the condition at
    h = 1e-5; the unit differences the library's check at 1e-6 itself; the ranges at h = 1e-4:
    the unit's derivative comes from the margin that ends a range, not from differences of the
    search). The residual's derivative is zero: the solver's leftover, 1e-15 m, has none."""
    u, point = started_within_limits(version, 1, 31)
    J = jacobian(u, POSE_OUTPUTS, POSE)
    assert not J[1].any()  # residual
    assert not jacobian(u, POSE_OUTPUTS, POSE_DOT + POSE_DDOT).any()
    assert (np.abs(J[[0, 2, 3, 4, 6]]).max(axis=1) > 1e-2).all()  # not a comparison of zeros
    worst = {}
    for j, name in enumerate(POSE):
        for h, rows in ((1e-5, range(0, 7)), (1e-4, range(7, 19))):
            up = outputs_at(u, {**point, name: point[name] + h}, POSE_OUTPUTS)
            down = outputs_at(u, {**point, name: point[name] - h}, POSE_OUTPUTS)
            difference = (up - down) / (2 * h)
            for i in rows:
                if i == 1:  # the residual: differences of rounding
                    assert abs(difference[i]) <= 1e-13 / h
                    continue
                rounding = 16 * np.finfo(float).eps * abs(up[i]) / h
                error = max(abs(J[i, j] - difference[i]) - rounding, 0.0)
                scale = max(np.abs(J[i]).max(), 1e-3)
                worst[POSE_OUTPUTS[i]] = max(worst.get(POSE_OUTPUTS[i], 0.0), error / scale)
    u.set_values(point)
    print(f"FMI {version}: worst error relative to each row's largest derivative: "
          + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))
    for name, error in worst.items():
        assert error < (1e-6 if not name.startswith("range") else 1e-4), (name, error)
    u.fmu.terminate()
    u.fmu.freeInstance()
