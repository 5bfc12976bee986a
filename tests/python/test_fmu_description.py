"""The model descriptions: committed = generated, FMI 2 and FMI 3 agree, the interface of issue 4,
the value references of the C tables, fmpy validate, and the self-contained binaries."""
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import pytest

from fmu_support import (BUILD, REPO, VERSIONS, L, L_DOT, L_DDOT, F, POSE, POSE_DOT, POSE_DDOT,
                         Unit, fmu_path, model_description, opened_unit)

import fmpy
from fmpy.validation import validate_fmu


def test_committed_model_description_is_the_generated_fmi2_one():
    committed = (REPO / "modelDescription.xml").read_bytes()
    generated = (BUILD / "fmu" / "StewartPlatform" / "modelDescription2.xml").read_bytes()
    with zipfile.ZipFile(fmu_path("2.0")) as z:
        packed = z.read("modelDescription.xml")
    assert generated == packed
    assert committed == generated, (
        "modelDescription.xml is stale: run `cmake --build build --target update_model_description`")


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_layout(version):
    platform = "linux64" if version == "2.0" else "x86_64-linux"
    with zipfile.ZipFile(fmu_path(version)) as z:
        names = set(z.namelist())
    assert "modelDescription.xml" in names
    assert f"binaries/{platform}/StewartPlatform.so" in names


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validate_is_clean(version):
    assert validate_fmu(str(fmu_path(version))) == []


def _variables(version):
    md = model_description(version)
    return {v.name: v for v in md.modelVariables}


def test_fmi2_and_fmi3_descriptions_agree():
    v2, v3 = _variables("2.0"), _variables("3.0")
    # FMI 3 adds the independent variable it requires; otherwise the same list, same order
    assert [n for n in v3 if v3[n].causality != "independent"] == list(v2)
    assert [v3[n].causality for n in v3].count("independent") == 1
    type_map = {"Real": "Float64", "Integer": "Int32"}
    for name in v2:
        a, b = v2[name], v3[name]
        assert a.valueReference == b.valueReference, name
        assert a.causality == b.causality, name
        assert a.variability == b.variability, name
        assert type_map[a.type] == b.type, name
        assert a.start == b.start, name
        assert a.unit == b.unit and a.displayUnit == b.displayUnit, name
        assert a.description == b.description, name
    m2, m3 = model_description("2.0"), model_description("3.0")
    assert m2.guid == m3.guid
    assert [c for c in m2.logCategories] == [c for c in m3.logCategories] or \
        [c.name for c in m2.logCategories] == [c.name for c in m3.logCategories]


def test_interface_of_issue_4():
    v = _variables("2.0")
    for n in POSE + POSE_DOT + POSE_DDOT:
        assert (v[n].causality, v[n].variability, v[n].type) == ("input", "continuous", "Real"), n
    for n in L + L_DOT + L_DDOT + F + ("condition", "residual") + tuple(
            f"base_{w}[{k}]" for w in ("force", "torque") for k in (1, 2, 3)):
        assert (v[n].causality, v[n].type) == ("output", "Real"), n
    for n in ("newton_iterations", "status"):
        assert (v[n].causality, v[n].type) == ("output", "Integer"), n
    for n in ("fidelity", "derivatives"):
        assert (v[n].causality, v[n].type) == ("parameter", "Integer"), n
    assert v["fidelity"].start == "2" and v["derivatives"].start == "0"
    assert v["tolerance"].causality == "parameter" and v["tolerance"].type == "Real"
    units = {"L[1]": "m", "F[1]": "N", "x": "m", "roll": "rad", "base_torque[1]": "N.m"}
    for n, u in units.items():
        assert v[n].unit == u, n
    # every geometry, mass and payload parameter of the library, angles in rad shown in deg
    for n in ("base_radius", "platform_radius", "home_height", "platform_mass", "payload_mass",
              "cylinder_mass", "piston_mass", "cylinder_com", "piston_com"):
        assert v[n].causality == "parameter" and v[n].unit, n
    assert v["geometry"].causality == "parameter"
    for g, count in (("base_angle", 6), ("platform_angle", 6), ("gravity", 3),
                     ("stroke_min", 6), ("stroke_max", 6), ("base_joint", 18),
                     ("platform_joint", 18), ("base_cardan_axis", 18),
                     ("platform_cardan_axis", 18),
                     ("platform_com", 3), ("platform_inertia", 3), ("payload_com", 3),
                     ("payload_inertia", 3), ("cylinder_inertia", 3), ("piston_inertia", 3)):
        for k in range(1, count + 1):
            assert v[f"{g}[{k}]"].causality == "parameter", (g, k)
    for k in range(1, 7):
        assert v[f"base_angle[{k}]"].unit == "rad" and v[f"base_angle[{k}]"].displayUnit == "deg"


def test_capabilities():
    m2, m3 = model_description("2.0"), model_description("3.0")
    cs2, cs3 = m2.coSimulation, m3.coSimulation
    assert cs2.canHandleVariableCommunicationStepSize and cs3.canHandleVariableCommunicationStepSize
    assert cs2.canGetAndSetFMUstate and cs2.canSerializeFMUstate and cs2.canInterpolateInputs
    assert cs3.canGetAndSetFMUstate and cs3.canSerializeFMUstate
    assert m2.modelExchange is None and m3.modelExchange is None
    names = [c.name if hasattr(c, "name") else c for c in m2.logCategories]
    assert {"logStatusWarning", "logStatusDiscard", "logStatusError", "logEvents"} <= set(names)


@pytest.mark.parametrize("version", VERSIONS)
def test_value_references_agree_with_the_c_tables(version):
    """Each variable's XML start value is what the binary returns for its value reference, and
    parameter defaults equal stewart-solve's platform (checked through the outputs elsewhere).
    Setting a distinct value through each Real input/parameter vr and reading all back, and
    each Integer one in turn to another value of its declared range, finds no two vrs sharing
    storage."""
    with opened_unit(version) as u:
        assert u.enter_init() == 0
        md = model_description(version)
        settable = [v for v in md.modelVariables if v.causality in ("input", "parameter")]
        for v in settable:
            got = u.get([v.name])[0]
            assert float(got) == float(v.start), (v.name, got, v.start)
        reals = [v for v in settable if v.type in ("Real", "Float64")]
        values = {v.name: (i + 1) * 1.25 for i, v in enumerate(reals)}
        u.set_values(values)
        for n, x in values.items():
            assert u.get([n])[0] == x, n
        integers = [v for v in settable if v not in reals]
        names = [v.name for v in integers]
        for v in integers:
            before = u.get(names)
            other = int(v.min) if int(v.start) != int(v.min) else int(v.max)
            u.set_values({v.name: other})
            after = u.get(names)
            assert [n for n, a, b in zip(names, before, after) if a != b] == [v.name]
            u.set_values({v.name: int(v.start)})


@pytest.mark.parametrize("version", VERSIONS)
def test_binary_is_self_contained(version):
    so = BUILD / "fmu" / "StewartPlatform" / f"fmi{version[0]}" / "StewartPlatform.so"
    d = subprocess.run(["readelf", "-d", "-W", str(so)], capture_output=True, text=True, check=True)
    needed = {line.split("[")[1].split("]")[0] for line in d.stdout.splitlines() if "(NEEDED)" in line}
    assert needed <= {"libc.so.6", "libm.so.6", "libstdc++.so.6", "libgcc_s.so.1"}, needed
    s = subprocess.run(["readelf", "--dyn-syms", "-W", str(so)], capture_output=True, text=True,
                       check=True)
    exported = []
    for line in s.stdout.splitlines():
        f = line.split()
        # Num: Value Size Type Bind Vis Ndx Name
        if len(f) >= 8 and f[0].endswith(":") and f[4] in ("GLOBAL", "WEAK") and f[6] != "UND":
            exported.append(f[7].split("@")[0])
    assert exported, "no exported symbols"
    prefix = f"fmi{version[0]}"
    assert all(n.startswith(prefix) for n in exported), sorted(n for n in exported
                                                             if not n.startswith(prefix))
    for required in (f"{prefix}DoStep", f"{prefix}GetFMUState" if version == "3.0"
                     else "fmi2GetFMUstate", f"{prefix}Reset"):
        assert required in exported
