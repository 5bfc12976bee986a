"""Scenes with a move section (docs/moves.md "Moves in scenes"): scenes/move_line.json on every
shipped platform file, scaled to its ranges, through the inverse unit (scripts/run_scene.py) and
the closed loop (scripts/closed_loop.py). The unit's lengths are checked against the closed-form
lengths of the planned poses (tests/python/test_moves.py's, written independently of the
library), its length rates against central differences of those lengths, the rows against the
plan stewart.move makes from the scene's section, and the loop's tracking against the bound the
sinusoidal scenes meet (1 % of the cue's excursion, test_machine_scripts.py). Then the section's
parsing: refusals by field, the move after sinusoids that end at rest, moves about a machine's
home."""
import json
import subprocess
import sys

import numpy as np
import pytest

import closed_loop
import run_scene
import scenes
import stewart
from fmu_support import BUILD
from test_moves import lengths

ROOT = scenes.ROOT
FILES = stewart.platform_files()
DT = 0.001
EPS = np.finfo(float).eps


def scene_on(name):
    """move_line.json moved to the machine and scaled to its ranges, the machine, its data."""
    platform = stewart.Platform.from_file(FILES[name])
    scene = stewart.scenes.on_platform(scenes.load("move_line"), platform, scale_to_ranges=True)
    return scene, platform, json.loads(FILES[name].read_text())


def planned(scene, platform):
    """The plan stewart.move makes from the scene's section (what the scene must play)."""
    section = dict(scene["move"])
    section.pop("hold")
    start, goal, kind = scene["home"], section.pop("goal"), section.pop("kind")
    return stewart.move(platform, start, goal, kind, sample_time=DT, **section)


@pytest.mark.parametrize("name", sorted(FILES))
def test_the_inverse_unit_plays_the_planned_move(name):
    scene, platform, data = scene_on(name)
    result = run_scene.run(BUILD / "fmus/2.0/StewartPlatform.fmu", scene, fidelity=1,
                           derivatives=1, parameters=stewart.fmu_start_values(platform),
                           platform=platform)
    plan = planned(scene, platform)
    q = np.column_stack([result[c] for c in scenes.POSE])
    n, held = len(plan.t), int(round(scene["move"]["hold"] / DT))
    assert len(q) == n + held and np.allclose(np.diff(result["t"]), DT, rtol=0, atol=1e-12)
    assert np.array_equal(q[:n], plan.pose) and np.all(q[n:] == plan.pose[-1])
    # The unit's lengths are the closed form's of the planned poses.
    L = lengths(data, q)
    unit_L = run_scene.legs(result, "L")
    assert np.max(np.abs(unit_L - L)) <= 1e-12, np.max(np.abs(unit_L - L))
    # Its rates (from the exact pose rates) are the lengths' derivatives: a central difference
    # is off by at most dt / 2 max |L_ddot| (a mean over two samples), plus rounding.
    rate = run_scene.legs(result, "L_dot")
    diff = (L[2:] - L[:-2]) / (2 * DT)
    bound = 0.5 * DT * np.max(np.abs(run_scene.legs(result, "L_ddot"))) * 1.01 \
        + 16 * EPS * np.max(L) / DT
    assert np.max(np.abs(diff - rate[1:-1])) <= bound
    assert np.max(np.abs(rate)) <= scene["move"]["leg_speed_max"] * (1 + 1e-9)
    assert np.all(rate[n:] == 0) and result["status"].max() == 0


@pytest.mark.parametrize("name", sorted(FILES))
def test_the_closed_loop_tracks_the_move(name):
    """The loop fed the planned move (and the goal held after it) tracks it within 1 % of the
    move's excursion, the bound the combined cue meets on every machine, and ends at the goal."""
    scene, platform, _ = scene_on(name)
    kp, kd = closed_loop.machine_gains(platform)
    result = closed_loop.run(scene, None, DT, kp, kd, fmus=BUILD / "fmus" / "2.0",
                             machine=stewart.fmu_start_values(platform), platform=platform)[0]
    plan = planned(scene, platform)
    cue = result["cue"]
    assert np.array_equal(cue[:len(plan.t)], plan.pose)
    excursion = np.abs(cue - cue[0]).max(axis=0)
    error = np.abs(result["pose"] - cue).max(axis=0)
    assert np.all(np.isfinite(result["pose"]))
    assert np.all(error[:3] <= 1e-2 * excursion[:3].max()), (error, excursion)
    assert np.all(error[3:] <= 1e-2 * excursion[3:].max()), (error, excursion)


def test_the_scripts_run_a_move_scene(tmp_path):
    path = FILES["rubin_m2_hexapod"]
    ran = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "run_scene.py"), "move_line", "--platform",
         str(path), "--scale-to-ranges", "--compare", "", "--fidelity", "1",
         "--fmu", str(BUILD / "fmus/2.0/StewartPlatform.fmu"), "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=300)
    assert ran.returncode == 0, ran.stderr
    data = np.genfromtxt(tmp_path / "move_line.csv", delimiter=",", names=True)
    scene, platform, _ = scene_on("rubin_m2_hexapod")
    plan = planned(scene, platform)
    assert data["z"][len(plan.t) - 1] == plan.pose[-1, 2] and data["status"].max() == 0
    loop = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "closed_loop.py"), "--scene", "move_line",
         "--platform", str(path), "--scale-to-ranges", "--no-plot",
         "--fmus", str(BUILD / "fmus/2.0"), "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=300)
    assert loop.returncode == 0, loop.stderr
    assert f"{plan.duration + scene['move']['hold']:g} s at h = 0.001 s" in loop.stdout


def heave_then_move():
    """Heave sinusoid ending where it turns (omega t = pi/2 on a whole step: at rest), then a
    move."""
    return {"name": "heave_then_move", "step": DT, "duration": 0.1,
            "pose": {"z": {"mean": 0.5, "amplitude": 0.02, "omega": 5 * np.pi}},
            "move": {"kind": "line", "goal": [0.01, 0.0, 0.5, 0.0, 0.0, 0.03],
                     "leg_speed_max": 0.05, "leg_accel_max": 0.5}}


def test_a_move_after_sinusoids_starts_where_they_end_at_rest():
    scene = heave_then_move()
    stewart.scenes.check(scene, "heave_then_move")
    t, q, qd, qdd = stewart.scenes.trajectory(scene)
    signals = stewart.scenes.times(scene)
    k = len(signals) - 1
    z_end = 0.5 + 0.02 * np.sin(5 * np.pi * signals[-1])
    assert q[k, 2] == z_end and np.max(np.abs(qd[k])) <= 1e-9
    plan = stewart.move(stewart.Platform(), q[k], scene["move"]["goal"], "line",
                        leg_speed_max=0.05, leg_accel_max=0.5)
    assert np.array_equal(q[k:], plan.pose) and np.array_equal(qd[k + 1:], plan.pose_rate[1:])
    assert np.allclose(np.diff(t), DT, rtol=0, atol=1e-12)
    # A duration cuts the run, or holds the goal at rest to it.
    longer = stewart.scenes.trajectory(scene, duration=t[-1] + 0.05)
    assert len(longer[0]) == len(t) + 50 and np.all(longer[1][-50:] == q[-1])
    assert not longer[2][-50:].any() and not longer[3][-50:].any()
    shorter = stewart.scenes.trajectory(scene, duration=0.1)
    assert len(shorter[0]) == 101 and np.array_equal(shorter[1], q[:101])


def test_a_move_after_sinusoids_that_do_not_end_at_rest_is_refused():
    scene = heave_then_move()
    scene["duration"] = 0.15
    with pytest.raises(stewart.scenes.SceneError, match="not at rest"):
        stewart.scenes.trajectory(scene)


@pytest.mark.parametrize("change, words", [
    ({"goal": [0, 0, 0.5]}, "goal"),
    ({"kind": "circle"}, "kind"),
    ({"frame": "base"}, "frame"),
    ({"speed": 1.0}, "the fields are"),
    ({"via": [[0, 0, 0.5, 0, 0]]}, "via"),
    ({"leg_speed_max": -1.0}, "leg_speed_max"),
    ({"hold": float("nan")}, "hold"),
])
def test_bad_move_sections_are_refused_by_field(change, words):
    scene = {"step": DT, "move": {"goal": [0.01, 0, 0.5, 0, 0, 0], "leg_accel_max": 0.5,
                                   **change}}
    with pytest.raises(stewart.scenes.SceneError, match=words):
        stewart.scenes.check(scene, "s")


def test_a_move_scene_is_not_sampled_as_sinusoids():
    with pytest.raises(stewart.scenes.SceneError, match="trajectory"):
        stewart.scenes.pose(scenes.load("move_line"), [0.0])


def test_a_move_the_platform_cannot_make_names_the_limit():
    scene = {"name": "far", "step": DT, "move": {"goal": [0, 0, 0.9, 0, 0, 0],
                                                 "leg_accel_max": 0.5}}
    with pytest.raises(stewart.MoveError) as info:
        stewart.scenes.trajectory(scene)
    assert info.value.limit_class == "stroke"
    no_limit = {"name": "free", "step": DT, "move": {"goal": [0.01, 0, 0.5, 0, 0, 0]}}
    with pytest.raises(ValueError, match="leg_accel_max"):
        stewart.scenes.trajectory(no_limit)


def test_a_move_moves_about_the_machine_home():
    """Absolute points keep their offset from home, a relative goal stays the displacement."""
    platform = stewart.Platform.from_file(FILES["rubin_camera_hexapod"])
    home = platform.check().home
    thesis = np.array(stewart.scenes.THESIS_HOME)
    via = [0.001, 0.0, 0.5, 0.0, 0.0, 0.0]
    scene = {"step": DT, "move": {"start": [0.0, 0.001, 0.5, 0, 0, 0],
                                  "goal": [0.002, 0.0, 0.501, 0, 0, 0.001], "via": [via],
                                  "leg_accel_max": 0.1}}
    moved = stewart.scenes.on_platform(scene, platform)
    for key, value in (("start", scene["move"]["start"]), ("goal", scene["move"]["goal"]),
                       ("via", via)):
        got = moved["move"][key][0] if key == "via" else moved["move"][key]
        np.testing.assert_allclose(np.array(got) - home, np.array(value) - thesis, atol=1e-15)
    relative = {"step": DT, "move": {"goal": [0.001, 0, 0, 0, 0, 0.001], "frame": "tool",
                                     "leg_accel_max": 0.1}}
    assert stewart.scenes.on_platform(relative, platform)["move"]["goal"] == \
        relative["move"]["goal"]
    t, q, _, _ = stewart.scenes.trajectory(stewart.scenes.on_platform(relative, platform),
                                           platform)
    assert np.array_equal(q[0], home)
