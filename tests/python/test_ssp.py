"""The closed loop as SSP (scenes/closed_loop/SystemStructure.ssd, packed by the build with the
FMUs into build/ssp/<v>/closed_loop.ssp for FMI 2.0 and 3.0) in a master that reads SSP (ecos,
through ecospy): the same motion for both FMI versions, the same as libcosim running the OSP
structure (another master, the other format), and the fmpy master's (scripts/closed_loop.py)
within the coupling error of a master that hands values over after each step."""
import pathlib
import shutil
import sys
import zipfile

import numpy as np
import pytest

from fmu_support import BUILD, POSE

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
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    log_output_level(CosimLogLevel.ERROR)
    (tmp_path / "scenes" / "closed_loop").mkdir(parents=True)
    shutil.copy(STRUCTURE / "OspSystemStructure.xml", tmp_path / "scenes" / "closed_loop")
    shutil.copytree(BUILD / "fmus" / "2.0", tmp_path / "build" / "fmus" / "2.0")
    ex = CosimExecution.from_osp_config_file(
        str(tmp_path / "scenes" / "closed_loop" / "OspSystemStructure.xml"))
    observer = CosimObserver.create_last_value()
    ex.add_observer(observer)
    plant = {s.name.decode(): s.index for s in ex.slave_infos()}["plant"]
    reference = {v.name.decode(): v.reference for v in ex.slave_variables(plant)}
    poses = []
    for _ in range(STEPS):
        assert ex.step()
        poses.append(observer.last_real_values(plant, [reference[p] for p in POSE]))
    return np.array(poses)


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
