"""One platform file everywhere: stewart.fmu_start_values gives the units the library's machine,
scenes move about a machine's home and scale to its ranges (stewart.scenes.on_platform), and the
scripts take --platform: the closed loop tracks on every shipped machine."""
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import closed_loop
import scenes
import stewart
from fmu_support import BUILD, assert_unit_solves_as_the_library

ROOT = pathlib.Path(__file__).resolve().parents[2]
MACHINES = sorted(stewart.platform_files())


@pytest.mark.parametrize("version", ["2.0", "3.0"])
@pytest.mark.parametrize("name", MACHINES)
def test_start_values_give_the_unit_the_machine(name, version):
    path = stewart.platform_files()[name]
    platform = stewart.Platform.from_file(path)
    values = stewart.fmu_start_values(path, fmi_version=version)
    assert values == stewart.fmu_start_values(platform)
    home = platform.check().home
    pose = home + [0.001, -0.0005, 0.0008, 0.002, -0.001, 0.0015]
    assert_unit_solves_as_the_library(values, platform, pose, version)


def test_start_values_refuse_what_is_not_a_platform(tmp_path):
    with pytest.raises(TypeError):
        stewart.fmu_start_values(3.5)
    with pytest.raises(ValueError):
        stewart.fmu_start_values({}, fmi_version="1.0")
    bad = tmp_path / "bad.json"
    bad.write_text('{"payload_mass": -1}')
    with pytest.raises(stewart.ParameterError, match="payload_mass"):
        stewart.fmu_start_values(bad)


def home_lengths(path):
    """The readings at home from the z-up platform file alone: |platform joint + (0, 0,
    home_height) - base joint| - length_offset (the joints as the model places them)."""
    from stewart import _core
    platform = stewart.Platform.from_file(path)
    base, top = (np.reshape(j, (6, 3)) for j in _core.model_joints(platform._model))
    height = platform.params.get("home_height", 0.5)
    offset = np.broadcast_to(platform.params.get("length_offset", 0.0), (6,))
    return np.linalg.norm(top + [0.0, 0.0, height] - base, axis=1) - offset


def z_down_file(path, tmp_path):
    """A z-up platform file without frames turned into z-down frames (frame_convention 1): the
    same machine, joints and centres of mass turned by 180 deg about x."""
    turn = np.diag([1.0, -1.0, -1.0])
    data = json.loads(pathlib.Path(path).read_text())
    assert not {"tool_frame", "user_frame", "frame_convention"} & data.keys()
    for name in ("base_joint", "platform_joint"):
        data[name] = (np.reshape(data[name], (6, 3)) @ turn).ravel().tolist()
    for name in ("payload_com", "platform_com"):
        if name in data:
            data[name] = (turn @ data[name]).tolist()
    data["frame_convention"] = 1
    out = tmp_path / "z_down.json"
    out.write_text(json.dumps(data))
    return out


@pytest.mark.parametrize("version", ["2.0", "3.0"])
@pytest.mark.parametrize("model", ["StewartPlant", "StewartPlantME"])
@pytest.mark.parametrize("name", MACHINES + ["simona_motion_base z down"])
def test_plant_start_values_start_at_the_machine_home(name, model, version, tmp_path):
    """The plant started from fmu_start_values(..., model=plant) sits at the machine's home: its
    leg readings at t = 0 are the home lengths of the file's geometry (z down: those of the same
    machine z up), its rates zero."""
    import fmpy
    path = stewart.platform_files()[name.split()[0]]
    expected = home_lengths(path)
    if name.endswith("z down"):
        path = z_down_file(path, tmp_path)
    values = stewart.fmu_start_values(path, fmi_version=version, model=model)
    assert values.keys() >= {"x0", "z0", "yaw0", "x_dot0", "yaw_dot0"}
    result = fmpy.simulate_fmu(BUILD / "fmus" / version / f"{model}.fmu", stop_time=1e-3,
                               output_interval=1e-3, start_values={**values, "fidelity": 1},
                               output=[*(f"L[{k}]" for k in range(1, 7)), "z", "z_dot"])
    lengths = np.array([result[f"L[{k}]"][0] for k in range(1, 7)])
    np.testing.assert_allclose(lengths, expected, rtol=0, atol=1e-12 * expected.max())
    assert result["z_dot"][0] == 0.0
    if name.endswith("z down"):
        assert result["z"][0] < 0  # the platform above the base: z down is negative


def test_start_values_name_the_units_that_take_a_platform():
    with pytest.raises(ValueError, match="StewartPlant"):
        stewart.fmu_start_values(stewart.Platform(), model="StewartController")
    assert "z0" not in stewart.fmu_start_values(stewart.Platform())  # the inverse unit has none


@pytest.mark.parametrize("name", MACHINES)
def test_a_scene_moves_about_the_machine_home(name):
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    combined = scenes.load("combined")
    moved = stewart.scenes.on_platform(combined, platform)
    home = platform.check().home
    t = stewart.scenes.times(combined)
    q0 = stewart.scenes.pose(combined, t)[0]
    q1 = stewart.scenes.pose(moved, t)[0]
    np.testing.assert_allclose(q1 - home, q0 - stewart.scenes.THESIS_HOME, atol=1e-12)
    scaled = stewart.scenes.on_platform(combined, platform, scale_to_ranges=True)
    q2 = stewart.scenes.pose(scaled, t)[0]
    assert platform.limits(q2).within.all()
    # the same motion, scaled: each component's excursion from home a fixed multiple of the
    # scene's, at most half the axis range from home on its nearer side
    excursion0 = q0 - stewart.scenes.THESIS_HOME
    excursion2 = q2 - home
    ends = platform.axis_ranges(home)[0]
    room = np.minimum(home - ends[:, 0], ends[:, 1] - home)
    for i in range(6):
        if np.ptp(q0[:, i]) == 0 and excursion0[0, i] == 0:
            assert np.all(excursion2[:, i] == 0)
            continue
        scale = excursion2[:, i] @ excursion0[:, i] / (excursion0[:, i] @ excursion0[:, i])
        assert scale > 0
        np.testing.assert_allclose(excursion2[:, i], scale * excursion0[:, i], atol=1e-12)
        assert np.abs(excursion2[:, i]).max() <= 0.5 * room[i] * (1 + 1e-12)


@pytest.mark.parametrize("name", MACHINES)
def test_the_closed_loop_tracks_on_every_machine(name):
    """The combined cue scaled to the machine, 0.3 s at 1 ms with the machine's PD gains: the
    error stays below 1 % of the cue's excursion (the thesis loop: 1e-5)."""
    platform = stewart.Platform.from_file(stewart.platform_files()[name])
    scene = stewart.scenes.on_platform(scenes.load("combined"), platform, scale_to_ranges=True)
    kp, kd = closed_loop.machine_gains(platform)
    result = closed_loop.run(scene, 0.3, 1e-3, kp, kd, fmus=BUILD / "fmus" / "2.0",
                             machine=stewart.fmu_start_values(platform))[0]
    cue = result["cue"]
    excursion = np.abs(cue - cue[0]).max(axis=0)
    error = np.abs(result["pose"] - cue).max(axis=0)
    assert np.all(np.isfinite(result["pose"]))
    assert np.all(error[:3] <= 1e-2 * excursion[:3].max()), (error, excursion)
    assert np.all(error[3:] <= 1e-2 * max(excursion[3:].max(), 1e-6)), (error, excursion)


def test_thesis_gains_are_kept_on_the_thesis():
    kp, kd = closed_loop.machine_gains(stewart.Platform())
    assert kp == pytest.approx(closed_loop.THESIS_KP, rel=1e-12)
    assert kd == pytest.approx(closed_loop.THESIS_KD, rel=1e-12)


def test_run_scene_takes_a_platform(tmp_path):
    path = stewart.platform_files()["paired_hexapod"]
    result = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "run_scene.py"), "heave", "--platform", str(path),
         "--scale-to-ranges", "--compare", "", "--fmu", str(BUILD / "fmus/2.0/StewartPlatform.fmu"),
         "--out", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    data = np.genfromtxt(tmp_path / "heave.csv", delimiter=",", names=True)
    platform = stewart.Platform.from_file(path)
    q = np.column_stack([data[c] for c in ("x", "y", "z", "roll", "pitch", "yaw")])
    expected = platform.inverse(q, fidelity="kinematic").length
    np.testing.assert_allclose(np.column_stack([data[f"L{k}"] for k in range(1, 7)]), expected,
                               rtol=0, atol=1e-12)
    assert data["status"].max() == 0  # every pose inside the strokes
