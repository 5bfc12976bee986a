"""StewartCueing.fmu (the cueing unit on the FMU runtime), FMI 2 and FMI 3: its descriptions
(fmpy validate), the unit against stewart.cueing (the library) bit for bit on a vehicle signal
that makes the limiter act, with options and parameters set through the unit, state rollback bit
for bit (in the instance and through serialised bytes in another), and a non-finite input
refused with the state kept."""
import math

import numpy as np
import pytest
from fmpy.validation import validate_fmu

import stewart
from fmu_support import VERSIONS
from test_plant_fmu import DISCARD, OK, Instance, fmu_file

INPUTS = [f"specific_force[{i}]" for i in (1, 2, 3)] + [f"angular_velocity[{i}]" for i in (1, 2, 3)]
POSE = ["x", "y", "z", "roll", "pitch", "yaw"]
OUTPUTS = POSE + [p + "_dot" for p in POSE] + [p + "_ddot" for p in POSE] + ["scale"]
FLAGS = ["limited", "cut", "tilt_limited", "status", "leg_limits"]
OPTIONS = dict(surge_scale=1.0, sway_scale=0.8, heave_scale=1.0, yaw_scale=0.9, head_z=0.3,
               translation_order=2, rotation_filter_order=1, limiter_lookahead=0.3)
# the legs' speed and acceleration enforced (the leg limiter at work), their force reported
# through leg_limits
PARAMS = dict(leg_speed_max=0.3, leg_accel_max=4.0, leg_force_max=600.0)
FMU_PARAMS = {f"{name}[{k}]": value for name, value in PARAMS.items() for k in range(1, 7)}


def vehicle(n=1500, dt=2e-3):
    t = np.arange(n) * dt
    f = np.column_stack([6 * np.sin(2.1 * t), 5 * np.sign(np.sin(1.3 * t)),
                         9.81 + 3 * np.sin(5 * t)])
    w = np.column_stack([0.8 * np.sin(3 * t), 0.5 * np.cos(2 * t), 1.5 * (t > 1)])
    return t, f, w


def cueing_unit(version, name="cue"):
    return Instance("StewartCueing", version, name)


def start(u, first_input, **values):
    if u.v2:
        u.fmu.setupExperiment(startTime=0.0)
        u.fmu.enterInitializationMode()
    else:
        u.fmu.enterInitializationMode(startTime=0.0)
    u.set(**values)
    u.set_reals(INPUTS, first_input)
    u.fmu.exitInitializationMode()
    return u


@pytest.mark.parametrize("version", VERSIONS)
def test_description_validates(version):
    assert validate_fmu(fmu_file("StewartCueing", version)) == []


@pytest.mark.parametrize("version", VERSIONS)
def test_unit_against_the_library_bit_for_bit(version):
    t, f, w = vehicle()
    ref = stewart.cueing(stewart.Platform(**PARAMS), t, f, w, **OPTIONS)
    assert ref.limited.any()
    u = start(cueing_unit(version), np.append(f[0], w[0]), **OPTIONS, **FMU_PARAMS)
    try:
        want = np.column_stack([ref.pose, ref.pose_rate, ref.pose_accel, ref.scale])
        flags = np.column_stack([ref.limited, ref.cut, ref.tilt_limited, np.zeros(len(t)),
                                 ref.leg_limits])
        assert ref.leg_limits.any() and not ref.leg_limits.all()
        assert np.array_equal(u.get(OUTPUTS), want[0]) and np.array_equal(u.get(FLAGS), flags[0])
        for k in range(1, len(t)):
            u.set_reals(INPUTS, np.append(f[k], w[k]))
            assert u.step(t[k - 1], t[k] - t[k - 1]) == OK
            assert np.array_equal(u.get(OUTPUTS), want[k]), k
            assert np.array_equal(u.get(FLAGS), flags[k]), k
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_rollback_reproduces_the_outputs_bit_for_bit(version):
    t, f, w = vehicle(600)
    u = start(cueing_unit(version), np.append(f[0], w[0]), **OPTIONS)
    other = start(cueing_unit(version, "other"), np.append(f[0], w[0]), **OPTIONS)
    try:
        def run(unit, ks):
            out = []
            for k in ks:
                unit.set_reals(INPUTS, np.append(f[k], w[k]))
                assert unit.step(t[k - 1], t[k] - t[k - 1]) == OK
                out.append(np.append(unit.get(OUTPUTS), unit.get(FLAGS)))
            return np.array(out)
        run(u, range(1, 300))
        state = u.get_state()
        blob = u.serialize(state)
        first = run(u, range(300, 600))
        u.set_state(state)
        assert np.array_equal(run(u, range(300, 600)), first)
        other.set_state(other.deserialize(blob))
        assert np.array_equal(run(other, range(300, 600)), first)
    finally:
        u.free()
        other.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_non_finite_input_is_refused_and_the_state_kept(version):
    t, f, w = vehicle(200)
    a = start(cueing_unit(version, "a"), np.append(f[0], w[0]))
    b = start(cueing_unit(version, "b"), np.append(f[0], w[0]))
    try:
        for k in range(1, 200):
            for unit in (a, b):
                unit.set_reals(INPUTS, np.append(f[k], w[k]))
            if k == 100:
                a.set(**{"specific_force[2]": math.nan})
                assert a.step(t[k - 1], t[k] - t[k - 1]) == DISCARD
                assert any("specific_force y" in m for m in a.messages)
                assert a.get(["status"])[0] == 3
                a.set_reals(INPUTS, np.append(f[k], w[k]))
            assert a.step(t[k - 1], t[k] - t[k - 1]) == OK
            assert b.step(t[k - 1], t[k] - t[k - 1]) == OK
            assert np.array_equal(a.get(OUTPUTS), b.get(OUTPUTS))
    finally:
        a.free()
        b.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_bad_option_is_an_error_naming_it(version):
    u = cueing_unit(version)
    try:
        if u.v2:
            u.fmu.setupExperiment(startTime=0.0)
            u.fmu.enterInitializationMode()
        else:
            u.fmu.enterInitializationMode(startTime=0.0)
        u.set(translation_frequency=-1.0)
        with pytest.raises(Exception):
            u.fmu.exitInitializationMode()
        assert any("translation_frequency = -1" in m for m in u.messages)
    finally:
        u.free()
