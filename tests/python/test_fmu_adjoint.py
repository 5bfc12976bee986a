"""fmi3GetAdjointDerivative (sensitivity = J^T seed: one seed per unknown, one sensitivity per
known) of the FMI 3 units that provide directional derivatives: the inverse unit, the controller
and the Model Exchange plant. Checked against central finite differences of each unit's own
outputs (independent of the derivative code), against the transpose of the Jacobian its
directional derivatives give, by the dot-product identity w . (J v) = (J^T w) . v, and for the
declaration (providesAdjointDerivatives in FMI 3 descriptions, fmpy validate) and the refused
requests."""
import zipfile
from xml.etree import ElementTree

import numpy as np
import pytest

from fmpy.validation import validate_fmu

from fmu_support import ERROR, fmu_path
from test_fmu_derivatives import (DIFFERENTIABLE, INPUTS, STEP, jacobian, outputs_at,
                                  random_point, started)
from test_plant_fmu import F, static_forces
from test_plant_me_derivatives import OUTPUTS, at_point, random_state
from test_plant_me_fmu import POSE_DDOT, STATES, MEInstance

VERSION = "3.0"  # FMI 2 has no adjoint


def adjoint(fmu, vr, unknowns, knowns, seed):
    return np.array(fmu.getAdjointDerivative([vr[n] for n in unknowns], [vr[n] for n in knowns],
                                             list(seed), nSensitivity=len(knowns)))


def provides_adjoint(path, interface):
    with zipfile.ZipFile(path) as z:
        root = ElementTree.fromstring(z.read("modelDescription.xml"))
    return root.find(interface).get("providesAdjointDerivatives", "false")


@pytest.mark.parametrize("fidelity", [0, 2])
def test_inverse_adjoint_is_the_transposed_jacobian(fidelity):
    rng = np.random.default_rng(40 + fidelity)
    pose, rate, accel = random_point(rng)
    u = started(VERSION, fidelity, 1, pose, rate, accel)
    point = dict(zip(INPUTS, np.concatenate([pose, rate, accel])))
    w = rng.standard_normal(len(DIFFERENTIABLE))
    a = adjoint(u.fmu, u.vr, DIFFERENTIABLE, INPUTS, w)
    # central differences of the unit's outputs, weighted by w (a scalar function of the inputs)
    differences = np.zeros(len(INPUTS))
    for j, name in enumerate(INPUTS):
        h = STEP[j]
        up = outputs_at(u, {**point, name: point[name] + h})
        down = outputs_at(u, {**point, name: point[name] - h})
        differences[j] = w @ (up - down) / (2 * h)
    u.set_values(point)
    scale = np.abs(w).sum() * np.abs(outputs_at(u, point)).max() + 1.0
    assert np.abs(a - differences).max() < 1e-6 * scale, (a, differences)
    J = jacobian(u)
    assert np.allclose(a, J.T @ w, rtol=1e-12, atol=1e-12 * np.abs(J.T @ w).max())
    v = rng.standard_normal(len(INPUTS))
    assert abs(w @ (J @ v) - a @ v) <= 1e-12 * np.abs(w).sum() * np.abs(J).max() * np.abs(v).sum()
    u.fmu.terminate()
    u.fmu.freeInstance()


def test_model_exchange_adjoint_is_the_transposed_jacobian():
    me = MEInstance(VERSION).init(fidelity=2).continuous()
    rng = np.random.default_rng(41)
    x, forces = random_state(rng), static_forces(2)
    at_point(me, x, forces)
    unknowns = STATES[6:] + POSE_DDOT + OUTPUTS  # the state derivatives, in at_point's order
    knowns = STATES + F
    w = rng.standard_normal(len(unknowns))
    a = adjoint(me.fmu, me.vr, unknowns, knowns, w)
    J = np.array([me.fmu.getDirectionalDerivative([me.vr[n] for n in unknowns],
                                                  [me.vr[n] for n in knowns],
                                                  list(np.eye(len(knowns))[j]))
                  for j in range(len(knowns))]).T
    assert np.allclose(a, J.T @ w, rtol=1e-12, atol=1e-12 * np.abs(J.T @ w).max())
    # w . (derivatives, outputs) by central differences in each state and force
    step = [1e-5] * len(STATES) + [1e-2] * len(F)
    for j in range(len(knowns)):
        up, down, f_up, f_down = x.copy(), x.copy(), forces.copy(), forces.copy()
        if j < len(STATES):
            up[j] += step[j]
            down[j] -= step[j]
        else:
            f_up[j - len(STATES)] += step[j]
            f_down[j - len(STATES)] -= step[j]
        y_up, y_down = np.concatenate(at_point(me, up, f_up)), np.concatenate(
            at_point(me, down, f_down))
        difference = w @ (y_up - y_down) / (2 * step[j])
        assert abs(a[j] - difference) < 1e-6 * (np.abs(w) @ np.abs(J[:, j]) + 1.0), (j, a[j],
                                                                                   difference)
    me.free()


@pytest.mark.parametrize("unit,interface,provides", [
    ("StewartPlatform", "CoSimulation", "true"), ("StewartController", "CoSimulation", "true"),
    ("StewartPlantME", "ModelExchange", "true"), ("StewartPlant", "CoSimulation", "false"),
    ("StewartScene", "CoSimulation", "false"), ("StewartCueing", "CoSimulation", "false")])
def test_descriptions_declare_the_adjoint(unit, interface, provides):
    path = fmu_path(VERSION).parent / f"{unit}.fmu"
    assert provides_adjoint(path, interface) == provides
    assert validate_fmu(str(path)) == []


def test_refused_requests():
    rng = np.random.default_rng(42)
    pose, rate, accel = random_point(rng)
    u = started(VERSION, 2, 1, pose, rate, accel)
    with pytest.raises(Exception):  # an input as unknown
        adjoint(u.fmu, u.vr, ["x"], ["y"], [1.0])
    status, _, message = u.messages[-1]
    assert status == ERROR and "fmi3GetAdjointDerivative" in message, message
    with pytest.raises(Exception):  # one seed per unknown, not per known
        u.fmu.getAdjointDerivative([u.vr["L[1]"], u.vr["L[2]"]], [u.vr["x"]], [1.0],
                                   nSensitivity=1)
    status, _, message = u.messages[-1]
    assert status == ERROR and "nSeed = 1 must equal nUnknowns = 2" in message, message
    # the unit stays usable
    assert np.isfinite(adjoint(u.fmu, u.vr, ["L[1]"], ["x"], [1.0])).all()
    u.fmu.terminate()
    u.fmu.freeInstance()


def test_model_exchange_discard_names_the_adjoint():
    """At a state without derivatives (pitch at 90 degrees) the adjoint is Discard and its message
    names fmi3GetAdjointDerivative (not the directional derivative it is made of); the instance
    stays usable."""
    me = MEInstance(VERSION).init(fidelity=2).continuous()
    x = random_state(np.random.default_rng(43))
    at_point(me, x, static_forces(2))
    bad = x.copy()
    bad[4] = np.pi / 2
    assert me.set_states(bad) == 0
    with pytest.raises(Exception):
        adjoint(me.fmu, me.vr, ["x_ddot"], ["x", "F[1]"], [1.0])
    message = me.messages[-1]
    assert "fmi3GetAdjointDerivative" in message and "GetDirectionalDerivative" not in message, (
        message)
    at_point(me, x, static_forces(2))
    assert np.isfinite(adjoint(me.fmu, me.vr, ["x_ddot"], ["x", "F[1]"], [1.0])).all()
    me.free()


def test_model_exchange_derivatives_follow_the_point():
    """The unit keeps its linearisation for the states and forces it was made at: asked again at
    another point it answers for that point (against the differences of its own outputs there),
    and back at the first it answers bit for bit as before."""
    me = MEInstance(VERSION).init(fidelity=2).continuous()
    rng = np.random.default_rng(44)
    unknowns, knowns = POSE_DDOT + OUTPUTS, STATES + F
    w = rng.standard_normal(len(unknowns))
    x1, x2 = random_state(rng), random_state(rng)
    f1, f2 = static_forces(2), static_forces(2) * 1.05
    at_point(me, x1, f1)
    first = adjoint(me.fmu, me.vr, unknowns, knowns, w)
    at_point(me, x2, f2)
    second = adjoint(me.fmu, me.vr, unknowns, knowns, w)
    # the second against central differences in x (pose and rates) at the second point
    for j in range(len(STATES)):
        up, down = x2.copy(), x2.copy()
        up[j] += 1e-5
        down[j] -= 1e-5
        y_up, y_down = (np.concatenate(at_point(me, p, f2))[6:] for p in (up, down))
        difference = w @ (y_up - y_down) / 2e-5
        assert abs(second[j] - difference) < 1e-6 * (np.abs(second).max() + 1.0), j
    at_point(me, x1, f1)
    assert np.array_equal(adjoint(me.fmu, me.vr, unknowns, knowns, w), first)
    assert not np.array_equal(first, second)
    me.free()
