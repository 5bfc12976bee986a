"""Every unit enforces the min and max its own modelDescription.xml declares: for every parameter
and input with a declared min or max, of every unit the build writes (FMI 2 and FMI 3, read from
each FMU's description, so that a new unit or variable is covered without a line here), a value
just outside is refused at the set with an Error naming the variable, its value and the range,
nothing of the call is set, and the boundary values are taken. A serialised state holding a value
outside a declared range is refused the same way."""
import math
import re
import struct

import fmpy
import pytest
from fmpy.fmi2 import FMU2Model, FMU2Slave
from fmpy.fmi3 import FMU3Model, FMU3Slave

from fmu_support import BUILD, REPO, VERSIONS
from test_plant_fmu import Instance

INT32_MIN, INT32_MAX = -2**31, 2**31 - 1
INTEGER_TYPES = ("Integer", "Int32")


def _units(version):
    units = sorted(p.stem for p in (BUILD / "fmus" / version).glob("*.fmu"))
    if not units:
        pytest.fail(f"no FMUs in {BUILD / 'fmus' / version}: build the project first")
    return units


def _description(unit, version):
    return fmpy.read_model_description(str(BUILD / "fmus" / version / f"{unit}.fmu"))


def _ranged(unit, version):
    """(name, type, min, max, start) of every parameter and input with a declared min or max."""
    out = []
    for v in _description(unit, version).modelVariables:
        if v.causality not in ("parameter", "input") or (v.min is None and v.max is None):
            continue
        number = int if v.type in INTEGER_TYPES else float
        low = number(v.min) if v.min is not None else None
        high = number(v.max) if v.max is not None else None
        out.append((v.name, v.type, low, high, number(v.start)))
    return out


def _cases():
    return [(version, unit, *variable) for version in VERSIONS for unit in _units(version)
            for variable in _ranged(unit, version)]


def _instance(unit, version):
    """An instance in initialisation mode, where parameters are set and read."""
    model_exchange = _description(unit, version).coSimulation is None
    classes = (FMU2Model, FMU3Model) if model_exchange else (FMU2Slave, FMU3Slave)
    u = Instance(unit, version, classes=classes)
    if u.v2:
        u.fmu.setupExperiment(startTime=0.0)
        u.fmu.enterInitializationMode()
    else:
        u.fmu.enterInitializationMode(startTime=0.0)
    return u


def _text(x):
    """The value as the runtime prints it (%.17g)."""
    return str(x) if isinstance(x, int) else "%.17g" % x


def _outside(kind, low, high):
    """The values just outside [low, high] that the variable's type can hold."""
    integer = kind in INTEGER_TYPES
    out = []
    if low is not None and (not integer or low > INT32_MIN):
        out.append(low - 1 if integer else math.nextafter(low, -math.inf))
    if high is not None and (not integer or high < INT32_MAX):
        out.append(high + 1 if integer else math.nextafter(high, math.inf))
    return out


def test_the_units_declare_ranges_to_check():
    """The cases below are not empty, and hold the variable whose range went unchecked
    (StewartController's output, max 1) and the plant's options from the library's table."""
    for version in VERSIONS:
        names = {(unit, name) for v, unit, name, *rest in _cases() if v == version}
        assert ("StewartController", "output") in names
        assert ("StewartPlant", "method") in names and ("StewartPlantME", "input") in names


@pytest.mark.parametrize("version,unit,name,kind,low,high,start", _cases())
def test_value_outside_declared_range_is_refused_naming_it(version, unit, name, kind, low, high,
                                                          start):
    u = _instance(unit, version)
    try:
        for x in _outside(kind, low, high):
            u.messages.clear()
            with pytest.raises(Exception):  # fmpy raises on the Error status
                u.set(**{name: x})
            words = f"{name} = {_text(x)} is outside its declared range [{low}, {high}]"
            assert any(words in m for m in u.messages), u.messages
            assert u.get([name])[0] == start  # nothing of the call was set
        for boundary in (low, high):
            if boundary is None:
                continue
            u.messages.clear()
            u.set(**{name: boundary})
            assert u.get([name])[0] == boundary, u.messages
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_one_refused_value_sets_none_of_the_call(version):
    """A call that sets two values, the second out of range: the first is not set either."""
    u = _instance("StewartController", version)
    try:
        with pytest.raises(Exception):
            setter = u.fmu.setInteger if version == "2.0" else u.fmu.setInt32
            setter([u.vr["output"], u.vr["output"]], [1, 2])
        assert u.get(["output"])[0] == 0
        assert any("output = 2 is outside its declared range [0, 1]" in m for m in u.messages)
    finally:
        u.free()


def _nvr(unit):
    """FMU_NVR of the unit's model folder: the length of the state's value arrays."""
    for config in (REPO / "fmu" / "models").glob("*/config.h"):
        text = config.read_text()
        if re.search(rf'#define FMU_MODEL_IDENTIFIER "{unit}"', text):
            return int(re.search(r"#define FMU_NVR (\d+)", text)[1])
    pytest.fail(f"no fmu/models/*/config.h names {unit}")


def _state_cases():
    """One ranged Integer variable per unit that has one (its last)."""
    cases = {}
    for version, unit, name, kind, low, high, start in _cases():
        if kind in INTEGER_TYPES and low is not None and high is not None and high < INT32_MAX:
            cases[(version, unit)] = (name, low, high, start)
    return [(version, unit, *rest) for (version, unit), rest in sorted(cases.items())]


@pytest.mark.parametrize("version,unit,name,low,high,start", _state_cases())
def test_deserialised_state_outside_declared_range_is_refused(version, unit, name, low, high,
                                                              start):
    """The state's bytes: magic (8), sizeof(fmu_values) (8), then real[NVR], integer[NVR]."""
    u = _instance(unit, version)
    try:
        state = u.get_state()
        blob = bytearray(u.serialize(state))
        offset = 16 + 8 * _nvr(unit) + 4 * u.vr[name]
        assert struct.unpack_from("<i", blob, offset)[0] == start
        struct.pack_into("<i", blob, offset, high + 1)
        u.messages.clear()
        with pytest.raises(Exception):
            u.deserialize(bytes(blob))
        words = f"corrupt state: {name} = {high + 1} is outside its declared range [{low}, {high}]"
        assert any(words in m for m in u.messages), u.messages
        for boundary in (low, high):
            # the range takes its ends; the model may still refuse one with other values (e.g.
            # the controller's output = 1 without drives), but not as out of range
            struct.pack_into("<i", blob, offset, boundary)
            u.messages.clear()
            try:
                u.set_state(u.deserialize(bytes(blob)))
                assert u.get([name])[0] == boundary
            except Exception:
                assert u.messages and not any("declared range" in m for m in u.messages)
    finally:
        u.free()
