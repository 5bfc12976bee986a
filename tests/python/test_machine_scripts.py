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
