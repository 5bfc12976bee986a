"""The closed loop as SSP (scenes/closed_loop/SystemStructure.ssd, packed by the build with the
FMUs into build/ssp/<v>/closed_loop.ssp for FMI 2.0 and 3.0) in masters that read SSP: ecos
(through ecospy): the same motion for both FMI versions, the same as libcosim running the OSP
structure (another master, the other format), and the fmpy master's (scripts/closed_loop.py)
within the coupling error of a master that hands values over after each step; fmpy's SSP master
(fmpy.ssp, FMI 2) as docs/closed-loop.md runs it, equal to ecos. The SSD has what masters need:
a start value for every input connector (its source's once the units are initialised), a default
experiment with the documented stop time, OMSimulator's annotation."""
import pathlib
import shutil
import sys
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from fmu_support import BUILD, POSE, libcosim_outputs

ROOT = pathlib.Path(__file__).resolve().parents[2]
STRUCTURE = ROOT / "scenes" / "closed_loop"
STEPS, H = 1000, 1e-3
sys.path.insert(0, str(ROOT / "scripts"))
import closed_loop  # noqa: E402
import osp_to_ssd  # noqa: E402


def ssp(version):
    return BUILD / "ssp" / version / "closed_loop.ssp"


def test_the_ssd_is_written_from_the_osp_structure():
    """One source for the system: the committed SSD is what scripts/osp_to_ssd.py writes from
    OspSystemStructure.xml (components, initial values, connections)."""
    assert (STRUCTURE / "SystemStructure.ssd").read_text() == \
        osp_to_ssd.convert(STRUCTURE / "OspSystemStructure.xml")


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_the_archive_holds_the_ssd_and_this_builds_fmus(version):
    with zipfile.ZipFile(ssp(version)) as z:
        assert z.read("SystemStructure.ssd") == (STRUCTURE / "SystemStructure.ssd").read_bytes()
        units = {n for n in z.namelist() if n.endswith(".fmu")}
        assert units == {f"resources/{u}.fmu" for u in
                         ("StewartScene", "StewartPlatform", "StewartController", "StewartPlant")}
        for name in units:
            assert z.read(name) == (BUILD / "fmus" / version / pathlib.Path(name).name).read_bytes()


def ecos_run(version):
    """The plant's pose after each of STEPS steps of H, ecos running the archive."""
    ecospy = pytest.importorskip("ecospy")
    simulation = ecospy.EcosSimulation(step_size=H, ssp_path=str(ssp(version)))
    try:
        simulation.init(parameter_set=osp_to_ssd.PARAMETER_SET)
        poses = []
        for _ in range(STEPS):
            simulation.step()
            poses.append([simulation.get_real(f"plant::{p}") for p in POSE])
        return np.array(poses)
    finally:
        simulation.terminate()
        simulation.free()


def libcosim_run(tmp_path):
    """The same with libcosim from the OSP structure (its FMUs relative to it: this build's)."""
    (tmp_path / "scenes" / "closed_loop").mkdir(parents=True)
    shutil.copy(STRUCTURE / "OspSystemStructure.xml", tmp_path / "scenes" / "closed_loop")
    shutil.copytree(BUILD / "fmus" / "2.0", tmp_path / "build" / "fmus" / "2.0")
    return libcosim_outputs(tmp_path / "scenes" / "closed_loop" / "OspSystemStructure.xml",
                            STEPS)["plant"]


def test_ecos_runs_the_ssp_for_both_fmi_versions_like_libcosim_and_fmpy(tmp_path):
    fmi2, fmi3 = ecos_run("2.0"), ecos_run("3.0")
    # 1. FMI 2 and FMI 3: the same units, the same numbers
    np.testing.assert_array_equal(fmi3, fmi2)
    # 2. libcosim on the OSP structure: the same coupling, equal to rounding (3e-16 measured)
    np.testing.assert_allclose(fmi2, libcosim_run(tmp_path), rtol=0, atol=1e-12)
    # 3. the fmpy master hands the controller's force to the plant in the same step, these
    # masters one step later: within that coupling error (1.4e-6 m, 4.8e-7 rad measured), and
    # on the cue within the goal (1 mm, 1 mrad)
    loop = closed_loop.run("combined", STEPS * H, H, fmus=BUILD / "fmus" / "2.0")[0]
    difference = np.abs(fmi2 - loop["pose"][1:])
    assert difference[:, :3].max() <= 5e-6 and difference[:, 3:].max() <= 2e-6
    error = np.abs(fmi2 - loop["cue"][1:])
    assert error[:, :3].max() <= 1e-3 and error[:, 3:].max() <= 1e-3


NS = {"ssd": osp_to_ssd.SSD, "ssc": osp_to_ssd.SSC, "ssv": osp_to_ssd.SSV, "oms": osp_to_ssd.OMS}


def test_the_ssd_has_what_masters_need():
    """Every input connector has a start value in its unit's bound parameter set, the default
    experiment runs the documented 12 s, and OMSimulator finds its fixed-step master at the OSP's
    step."""
    root = ET.parse(STRUCTURE / "SystemStructure.ssd").getroot()
    for component in root.findall("ssd:System/ssd:Elements/ssd:Component", NS):
        inputs = {c.get("name") for c in component.findall("ssd:Connectors/ssd:Connector", NS)
                  if c.get("kind") == "input"}
        bound = {p.get("name") for p in component.findall(".//ssv:Parameter", NS)}
        assert inputs <= bound, (component.get("name"), inputs - bound)
    experiment = root.find("ssd:DefaultExperiment", NS)
    assert float(experiment.get("startTime")) == 0.0
    assert float(experiment.get("stopTime")) == 12.0 == closed_loop_duration()
    master = root.find("ssd:System/ssd:Annotations/ssc:Annotation[@type='org.openmodelica']/"
                       "oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster", NS)
    assert master is not None and float(master.get("stepSize")) == H


def closed_loop_duration():
    """The combined cue's duration (scenes/combined.json), the run docs/closed-loop.md shows."""
    import json
    return json.loads((ROOT / "scenes" / "combined.json").read_text())["duration"]


def test_start_values_are_the_sources_at_the_start():
    """The inverse unit's pose inputs start at the scene's pose at t = 0 (its formula, mean +
    amplitude sin(phase)), not at 0: no master hands it the singular pose z = 0."""
    import scenes
    root = ET.parse(STRUCTURE / "SystemStructure.ssd").getroot()
    inverse = root.find("ssd:System/ssd:Elements/ssd:Component[@name='inverse']", NS)
    bound = {p.get("name"): float(p.find("ssv:Real", NS).get("value"))
             for p in inverse.findall(".//ssv:Parameter", NS) if p.find("ssv:Real", NS) is not None}
    cue, cue_dot, cue_ddot = scenes.pose(scenes.load("combined"), np.array([0.0]))
    for names, values in ((POSE, cue[0]), ([f"{p}_dot" for p in POSE], cue_dot[0]),
                          ([f"{p}_ddot" for p in POSE], cue_ddot[0])):
        np.testing.assert_allclose([bound[n] for n in names], values, rtol=1e-15, atol=1e-16)


def fmpy_ssp_run(version, stop_time):
    """The plant's pose per step with fmpy's SSP master as docs/closed-loop.md runs it: the SSD's
    bindings as its parameter set, the connectors started from the initialised units."""
    import fmpy.ssp.simulation as fmpy_ssp
    from fmpy.ssp.ssd import ParameterSet, read_ssd
    archive = str(ssp(version))
    bound = ParameterSet(name=osp_to_ssd.PARAMETER_SET)
    for unit in read_ssd(archive).system.elements:
        for binding in unit.parameterBindings:
            for values in binding.parameterValues:
                for parameter in values.parameters:
                    parameter.name = f"{unit.name}.{parameter.name}"
                    bound.parameters.append(parameter)
    instantiate = fmpy_ssp.instantiate_fmu

    def instantiate_and_start_connectors(component, *args, **kwargs):
        instantiate(component, *args, **kwargs)
        for connector in component.connectors:
            connector.value = fmpy_ssp.get_value(component, connector.name)

    fmpy_ssp.instantiate_fmu = instantiate_and_start_connectors
    try:
        result = fmpy_ssp.simulate_ssp(archive, stop_time=stop_time, step_size=H,
                                       parameter_set=bound)
    finally:
        fmpy_ssp.instantiate_fmu = instantiate
    return np.column_stack([result[f"plant.{p}"] for p in POSE])


def test_fmpy_ssp_runs_the_fmi2_archive_like_ecos():
    """fmpy.ssp couples like ecos (Jacobi): over 1 s the same poses; and within the coupling
    error of the project's fmpy loop, on the cue within the goal."""
    poses = fmpy_ssp_run("2.0", STEPS * H)[:STEPS]
    assert poses.shape == (STEPS, 6)
    ecos = ecos_run("2.0")
    difference = np.abs(poses - ecos).max()
    print(f"fmpy.ssp against ecos over {STEPS} steps: {difference:.1e}")
    np.testing.assert_allclose(poses, ecos, rtol=0, atol=1e-12)
    loop = closed_loop.run("combined", STEPS * H, H, fmus=BUILD / "fmus" / "2.0")[0]
    coupling = np.abs(poses - loop["pose"][1:])
    assert coupling[:, :3].max() <= 5e-6 and coupling[:, 3:].max() <= 2e-6


def test_fmpy_ssp_alone_starts_the_inverse_unit_at_the_singular_pose():
    """Why docs/closed-loop.md starts the connectors: fmpy.ssp as it is (every connector at 0.0)
    hands the inverse unit z = 0 at t = 0, which it refuses."""
    import fmpy.ssp.simulation as fmpy_ssp
    with pytest.raises(Exception, match="fmi2DoStep failed with status 2"):  # Discard
        fmpy_ssp.simulate_ssp(str(ssp("2.0")), stop_time=0.01, step_size=H)


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_the_package_ships_the_archives(version):
    """pip install . ships both archives (stewart.ssp_path): the committed SSD and the FMUs the
    package ships beside them."""
    import stewart
    with zipfile.ZipFile(stewart.ssp_path(version)) as z:
        assert z.read("SystemStructure.ssd") == (STRUCTURE / "SystemStructure.ssd").read_bytes()
        for name in (n for n in z.namelist() if n.endswith(".fmu")):
            unit = pathlib.Path(name).stem
            assert z.read(name) == stewart.fmu_path(version, unit).read_bytes(), name
    with pytest.raises(ValueError, match="1.0"):
        stewart.ssp_path("1.0")


MACHINES = sorted(__import__("stewart").platform_files())


def machine_ecos_run(archive, name, steps):
    """ecos on a machine's archive with its parameter set: the plant's pose after each step, the
    scene's means and the plant's base joints as the units hold them."""
    ecospy = pytest.importorskip("ecospy")
    simulation = ecospy.EcosSimulation(step_size=H, ssp_path=str(archive))
    try:
        simulation.init(parameter_set=name)
        means = [simulation.get_real(f"scene::{p}_mean") for p in POSE]
        joints = [simulation.get_real(f"plant::base_joint[{k}]") for k in range(1, 19)]
        poses = []
        for _ in range(steps):
            simulation.step()
            poses.append([simulation.get_real(f"plant::{p}") for p in POSE])
        return np.array(poses), np.array(means), np.array(joints)
    finally:
        simulation.terminate()
        simulation.free()


@pytest.mark.parametrize("name", MACHINES)
def test_a_platform_file_is_a_parameter_set_of_the_ssp_closed_loop(name, tmp_path):
    """scripts/machine_ssp.py: the package's archive with the machine's SSV files; ecos runs it
    with the set named after the file: the units hold the file's joints, the cue moves about the
    machine's home (Platform.check().home), and the plant follows the fmpy loop of
    scripts/closed_loop.py on the same machine within the coupling error (1 % of the cue's
    excursion, as the fmpy loop tracks on every machine)."""
    import machine_ssp
    import stewart
    path = stewart.platform_files()[name]
    platform = stewart.Platform.from_file(path)
    archive, osp = tmp_path / f"{name}.ssp", tmp_path / f"{name}.xml"
    assert machine_ssp.write(path, archive, scale_to_ranges=True, fmus=BUILD / "fmus" / "2.0",
                             osp_out=osp) == name
    steps = 300
    poses, means, joints = machine_ecos_run(archive, name, steps)
    home = platform.check().home
    np.testing.assert_allclose(means, home, rtol=0, atol=1e-15)
    values = stewart.fmu_start_values(platform)
    np.testing.assert_array_equal(joints, [values[f"base_joint[{k}]"] for k in range(1, 19)])
    scene = stewart.scenes.on_platform(scenes_module().load("combined"), platform,
                                       scale_to_ranges=True)
    kp, kd = closed_loop.machine_gains(platform)
    loop = closed_loop.run(scene, steps * H, H, kp, kd, fmus=BUILD / "fmus" / "2.0",
                           machine=values)[0]
    excursion = np.abs(loop["cue"] - home).max(axis=0)
    tolerance = 1e-2 * np.r_[[excursion[:3].max()] * 3, [max(excursion[3:].max(), 1e-6)] * 3]
    assert np.all(np.abs(poses - loop["pose"][1:]) <= tolerance), name
    assert np.all(np.abs(poses - loop["cue"][1:]) <= tolerance), name
    # libcosim on the OSP structure of the same values: the same coupling as ecos
    np.testing.assert_allclose(libcosim_outputs(osp, steps)["plant"], poses, rtol=0,
                               atol=1e-9 * max(1.0, np.abs(home).max()))


def scenes_module():
    import scenes
    return scenes
