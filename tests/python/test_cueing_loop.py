"""The cueing closed loop in fmpy (scripts/cueing_loop.py, docs/cueing.md): cueing unit -> inverse
unit -> controller -> plant on SIMONA's motion base with a shipped manoeuvre. The cue in the loop
is stewart.cueing's for the same samples bit for bit (the loop is wired as documented), within
every limit, and the plant tracks it within the tolerance the scene loops meet (1 mm and 1 mrad,
and 1 % of the cue's excursion: docs/closed-loop.md, tests/python/test_ssp.py); without the PD
part the same run drifts far more."""
import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
import closed_loop  # noqa: E402  (scripts/, on the path by conftest.py)
import cueing_loop  # noqa: E402
from fmu_support import BUILD, libcosim_outputs  # noqa: E402

FMUS = BUILD / "fmus" / "2.0"
# The lane change on SIMONA, tuned as studies/cueing_tuning.py found for it (docs/cueing.md).
OPTIONS = dict(head_z=1.2075, surge_scale=0.4, sway_scale=0.4, heave_scale=0.4, roll_scale=0.4,
               pitch_scale=0.4, yaw_scale=0.4, translation_frequency=0.75,
               translation_washout_frequency=0.15, rotation_frequency=0.3)


@pytest.fixture(scope="module")
def simona():
    return stewart.Platform.from_file(stewart.platform_files()["simona_motion_base"])


@pytest.fixture(scope="module")
def lane_change(simona):
    t, f, w = stewart.manoeuvre("car_lane_change")
    return cueing_loop.run(simona, t, f, w, OPTIONS, fmus=FMUS)[0]


def test_the_cue_in_the_loop_is_the_librarys(simona, lane_change):
    r = lane_change
    library = stewart.cueing(simona, r["t"], r["vehicle"][:, :3], r["vehicle"][:, 3:], **OPTIONS)
    np.testing.assert_array_equal(r["cue"], library.pose)
    np.testing.assert_array_equal(r["cue_rate"], library.pose_rate)
    np.testing.assert_array_equal(r["cue_accel"], library.pose_accel)
    assert np.all(simona.limits(r["cue"]).within)
    home = simona.check().home
    assert np.abs(r["cue"][:, 1] - home[1]).max() > 0.05  # the lane change moves the cabin


def test_the_plant_tracks_the_cue(simona, lane_change):
    position, angle = closed_loop.tracking_error(lane_change)
    print(f"cueing loop, lane change on SIMONA: {position:.2e} m, {angle:.2e} rad")
    assert position <= 1e-3 and angle <= 1e-3
    excursion = np.abs(lane_change["cue"] - simona.check().home).max(axis=0)
    error = np.abs(lane_change["pose"] - lane_change["cue"]).max(axis=0)
    assert np.all(error[:3] <= 1e-2 * excursion[:3].max())
    assert np.all(error[3:] <= 1e-2 * excursion[3:].max())
    assert np.all(simona.limits(lane_change["pose"]).within)


def test_without_feedback_the_plant_drifts(simona, lane_change):
    t, f, w = stewart.manoeuvre("car_lane_change")
    horizon = 3.0
    open_loop = cueing_loop.run(simona, t, f, w, OPTIONS, duration=horizon, kp=0.0, kd=0.0,
                                fmus=FMUS)[0]
    n = open_loop["t"].size
    np.testing.assert_array_equal(open_loop["cue"], lane_change["cue"][:n])
    closed = {key: lane_change[key][:n] for key in ("cue", "pose")}
    position, angle = closed_loop.tracking_error(closed)
    open_position, open_angle = closed_loop.tracking_error(open_loop)
    assert open_position > 10 * position and open_angle > 10 * angle


def osp_file(folder, platform, options, inputs):
    """cueing_loop.osp_structure written to folder/cueing_loop.xml; its path."""
    import xml.etree.ElementTree as ET
    path = folder / "cueing_loop.xml"
    ET.ElementTree(cueing_loop.osp_structure(platform, options, inputs, FMUS)).write(
        path, encoding="utf-8", xml_declaration=True)
    return path


def test_libcosim_runs_the_osp_structure_of_the_loop(simona, tmp_path):
    """cueing_loop.osp_structure with a braking step and a yaw rate from rest: libcosim's cue is
    stewart.cueing's for the held input (to rounding: its dt is the step, the library's the
    difference of the times), and its plant follows the fmpy loop and the cue within 1 % of the
    cue's excursion (libcosim hands each unit the others' values of the last step)."""
    pytest.importorskip("libcosimpy")
    options = {"head_z": 1.2075, "surge_scale": 0.4}
    inputs = [-3.0, 0.0, 9.81, 0.0, 0.0, 0.1]
    n = 1000
    run = libcosim_outputs(osp_file(tmp_path, simona, options, inputs), n, ("cueing", "plant"))
    cues, poses = run["cueing"], run["plant"]
    t = np.arange(n + 1) * 1e-3
    held = np.tile(inputs, (n + 1, 1))
    library = stewart.cueing(simona, t, held[:, :3], held[:, 3:], **options)
    np.testing.assert_allclose(cues, library.pose[1:], rtol=0, atol=1e-12)
    loop = cueing_loop.run(simona, np.array([0.0, 1.0]), held[:2, :3], held[:2, 3:], options,
                           fmus=FMUS)[0]
    np.testing.assert_array_equal(loop["cue"], library.pose)
    excursion = np.abs(loop["cue"] - simona.check().home).max(axis=0)
    tolerance = 1e-2 * np.r_[[excursion[:3].max()] * 3, [excursion[3:].max()] * 3]
    assert excursion[0] > 0.1 and excursion[5] > 0.01
    assert np.all(np.abs(np.array(poses) - loop["pose"][1:]) <= tolerance)
    assert np.all(np.abs(np.array(poses) - loop["cue"][1:]) <= tolerance)


def test_ecos_runs_the_ssp_archive_of_the_loop_as_libcosim_the_osp_structure(simona, tmp_path):
    """cueing_loop.write_ssp: ecos (SSP) and libcosim (OSP) couple alike (every unit from the
    values of the last step), so on the same loop their plants agree to rounding."""
    ecospy = pytest.importorskip("ecospy")
    pytest.importorskip("libcosimpy")
    options = {"head_z": 1.2075, "sway_scale": 0.5}
    inputs = [0.0, 2.0, 9.81, 0.1, 0.0, 0.0]
    archive = tmp_path / "cueing_loop.ssp"
    cueing_loop.write_ssp(simona, options, inputs, archive, FMUS)
    steps = 300
    simulation = ecospy.EcosSimulation(step_size=1e-3, ssp_path=str(archive))
    try:
        simulation.init(parameter_set="initialValues")
        ecos = []
        for _ in range(steps):
            simulation.step()
            ecos.append([simulation.get_real(f"plant::{p}") for p in closed_loop.POSE])
    finally:
        simulation.terminate()
        simulation.free()
    cosim = libcosim_outputs(osp_file(tmp_path, simona, options, inputs), steps)["plant"]
    ecos = np.array(ecos)
    assert np.abs(ecos[:, 1] - simona.check().home[1]).max() > 1e-3  # the sway moves the cabin
    np.testing.assert_allclose(ecos, cosim, rtol=0, atol=1e-12)


def test_a_recorded_vehicle_drives_the_osp_structure(simona, tmp_path):
    """The slalom's first 3 s as recorded samples (cueing_loop.vehicle_events): libcosim with the
    scenario of libcosim_scenario gives stewart.cueing's cue for the same samples (to rounding:
    its dt is the step) and its plant follows the cue within 1 % of the cue's excursion."""
    pytest.importorskip("libcosimpy")
    import xml.etree.ElementTree as ET
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    log_output_level(CosimLogLevel.ERROR)
    t_vehicle, f, w = stewart.manoeuvre("car_slalom")
    t, vehicle = cueing_loop.vehicle_samples(t_vehicle, f, w, 1e-3, 3.0)
    n = len(t) - 1
    path = tmp_path / "cueing_loop.xml"
    ET.ElementTree(cueing_loop.osp_structure(simona, OPTIONS, vehicle[0], FMUS)).write(
        path, encoding="utf-8", xml_declaration=True)
    scenario = tmp_path / "vehicle_scenario.json"
    scenario.write_text(cueing_loop.libcosim_scenario(t, vehicle))
    ex = CosimExecution.from_osp_config_file(str(path))
    observer = CosimObserver.create_last_value()
    ex.add_observer(observer)
    manager = CosimManipulator.create_scenario_manager()
    ex.add_manipulator(manager)
    assert ex.load_scenario(manager, str(scenario))
    index = {s.name.decode(): s.index for s in ex.slave_infos()}
    reference = {name: {v.name.decode(): v.reference for v in ex.slave_variables(i)}
                 for name, i in index.items()}
    pose = list(closed_loop.POSE)
    cosim = {"cueing": [], "plant": []}
    for _ in range(n):
        assert ex.step()
        for unit, out in cosim.items():
            out.append(observer.last_real_values(index[unit], [reference[unit][p] for p in pose]))
    cosim = {unit: np.array(values) for unit, values in cosim.items()}
    library = stewart.cueing(simona, t, vehicle[:, :3], vehicle[:, 3:], **OPTIONS)
    np.testing.assert_allclose(cosim["cueing"], library.pose[1:], rtol=0, atol=1e-12)
    excursion = np.abs(library.pose - simona.check().home).max(axis=0)
    assert excursion[1] > 0.01  # the slalom sways the cabin
    tolerance = 1e-2 * np.r_[[excursion[:3].max()] * 3, [excursion[3:].max()] * 3]
    assert np.all(np.abs(cosim["plant"] - library.pose[1:]) <= tolerance)
