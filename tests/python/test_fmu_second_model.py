"""A second model on the FMU runtime (tests/importer/integrator_model: y' = gain u, built by one
stewart_fmu line): its own inputs, outputs and state go through the same runtime and layers as
the Stewart platform's, for FMI 2 and FMI 3. Checked against the closed form of the integral."""
import ctypes
import math

import numpy as np
import pytest

import fmpy
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

from fmu_support import BUILD, VERSIONS


def _path(version):
    p = BUILD / "tests" / "fmus" / version / "RuntimeIntegrator.fmu"
    if not p.exists():
        pytest.fail(f"{p} is missing: build the project first")
    return str(p)


def _initialised(version, **parameters):
    """An instance in step mode with these parameters: (slave, vr, set_real, get_real, is_fmi2)."""
    d = fmpy.extract(_path(version))
    md = fmpy.read_model_description(_path(version))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    cls = FMU2Slave if version == "2.0" else FMU3Slave
    f = cls(guid=md.guid, unzipDirectory=d, modelIdentifier="RuntimeIntegrator", instanceName="i")
    f.instantiate()
    v2 = version == "2.0"
    set_real = f.setReal if v2 else f.setFloat64
    get_real = f.getReal if v2 else f.getFloat64
    if parameters:
        set_real([vr[n] for n in parameters], list(parameters.values()))
    if v2:
        f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    f.exitInitializationMode()
    return f, vr, set_real, get_real, v2


@pytest.mark.parametrize("version", VERSIONS)
def test_description_is_valid_and_its_own(version):
    md = fmpy.read_model_description(_path(version), validate=True)
    names = {v.name: v for v in md.modelVariables}
    assert {"u", "y", "steps", "gain", "y0"} <= set(names)
    assert "x" not in names and "L[1]" not in names
    assert names["gain"].start in ("1", "1.0", 1.0) or float(names["gain"].start) == 1.0
    assert md.coSimulation.modelIdentifier == "RuntimeIntegrator"


@pytest.mark.parametrize("version", VERSIONS)
def test_integral_of_a_held_input(version):
    """u steps through 1, -2, 0.5 (set before each 0.1 s step, as a master does): with u held
    over each step, y(t_n) = y0 + gain h sum_{k<n} u(t_k), exactly (to rounding)."""
    f, vr, set_real, get_real, v2 = _initialised(version, gain=3.0, y0=2.0)
    try:
        t = 0.1 * np.arange(11)
        u = np.where(t < 0.25, 1.0, np.where(t < 0.55, -2.0, 0.5))
        y = [get_real([vr["y"]])[0]]
        for k in range(10):
            set_real([vr["u"]], [u[k]])
            f.doStep(t[k], 0.1)
            y.append(get_real([vr["y"]])[0])
        expected = 2.0 + 3.0 * 0.1 * np.concatenate([[0.0], np.cumsum(u[:-1])])
        np.testing.assert_allclose(y, expected, rtol=0, atol=1e-12)
        steps = (f.getInteger if v2 else f.getInt32)([vr["steps"]])[0]
        assert steps == 10
    finally:
        f.terminate()
        f.freeInstance()


@pytest.mark.parametrize("version", VERSIONS)
def test_state_rollback_and_discard(version):
    """The model's own state travels in an FMU state (in memory and serialised), and a Discard
    (u not finite) leaves it and time unchanged, as the runtime promises for every model."""
    f, vr, set_real, get_real, v2 = _initialised(version)
    try:
        set_real([vr["u"]], [1.0])
        for k in range(3):
            f.doStep(0.1 * k, 0.1)
        state = f.getFMUstate() if v2 else f.getFMUState()
        blob = (f.serializeFMUstate if v2 else f.serializeFMUState)(state)
        for k in range(3, 6):
            f.doStep(0.1 * k, 0.1)
        assert get_real([vr["y"]])[0] == pytest.approx(0.6, abs=1e-15)
        (f.setFMUstate if v2 else f.setFMUState)(state)
        assert get_real([vr["y"]])[0] == pytest.approx(0.3, abs=1e-15)
        restored = (f.deSerializeFMUstate if v2 else f.deserializeFMUState)(blob)
        f.doStep(0.3, 0.1)
        (f.setFMUstate if v2 else f.setFMUState)(restored)
        assert get_real([vr["y"]])[0] == pytest.approx(0.3, abs=1e-15)
        set_real([vr["u"]], [math.nan])
        if v2:
            assert f.dll.fmi2DoStep(f.component, 0.3, 0.1, 1) == 2     # Discard
        else:
            flags = [ctypes.c_bool() for _ in range(3)]
            last = ctypes.c_double()
            assert f.dll.fmi3DoStep(f.component, 0.3, 0.1, 1, *map(ctypes.byref, flags),
                                    ctypes.byref(last)) == 2
            assert last.value == pytest.approx(0.3, abs=1e-15)
        assert get_real([vr["y"]])[0] == pytest.approx(0.3, abs=1e-15)
        set_real([vr["u"]], [2.0])
        f.doStep(0.3, 0.1)
        assert get_real([vr["y"]])[0] == pytest.approx(0.5, abs=1e-15)
        for s in (state, restored):
            (f.freeFMUstate if v2 else f.freeFMUState)(s)
    finally:
        f.terminate()
        f.freeInstance()
