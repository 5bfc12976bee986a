"""Envelope sweeps on every shipped machine: a scene moves about the machine's home pose (as
scripts/run_scene.py --platform moves it, stewart.scenes.on_platform) and scales to its axis
ranges with scale_to_ranges; the poses each case solves against the home pose and the scene's
sinusoid written here, the home against the frames' closed form, the stroke margins against the
lengths at home. A scene written about an absolute pose plays as written with "place":
"absolute", or moves from its own "home". scripts/sweep.py takes --platform and
--scale-to-ranges. Workspace slices move to the machine's home the same way, their poses against
the frames' closed form of home plus the offsets written here."""
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
pq = pytest.importorskip("pyarrow.parquet")
pytest.importorskip("distributed")
from stewart.sweeps import SpecError, chunks, resolve  # noqa: E402
from stewart.sweeps.spec import manoeuvre_samples  # noqa: E402
from stewart.sweeps.work import envelope_chunk  # noqa: E402
from test_workspace_volume import home as frames_home  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"
FILES = stewart.platform_files()
HEAVE = (0.04, 5.0)  # scenes/heave.json: z amplitude [m] and omega [rad/s] about z = 0.5 m
DURATION, STEP = 1.0, 0.01


def _heave_sweep(path, scale_to_ranges):
    spec = resolve({"kind": "envelope", "platform_file": str(path), "duration": DURATION,
                    "step": STEP, "scale_to_ranges": scale_to_ranges,
                    "manoeuvres": [{"scene": "heave", "amplitude": [0.0, 1.0]}]}, SCENES)
    table, _ = envelope_chunk(spec, chunks(spec)[0])
    return spec, {k: table[k].to_pylist() for k in table.column_names}


def _offsets(amplitude):
    """The heave scene's motion about its home, written here: z = amplitude sin(omega t)."""
    t = np.arange(int(round(DURATION / STEP)) + 1) * STEP
    q = np.zeros((t.size, 6))
    q[:, 2] = amplitude * np.sin(HEAVE[1] * t)
    return q


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_heave_sweep_moves_about_the_machine_home(name):
    """Before, the heave played about the thesis' z = 0.5 m on every machine (SIMONA: a stroke
    margin of -0.77 m, every case infeasible)."""
    platform = stewart.Platform.from_file(FILES[name])
    report = platform.check()
    assert report.valid
    np.testing.assert_allclose(report.home, frames_home(platform), rtol=0, atol=1e-15)
    spec, rows = _heave_sweep(FILES[name], False)
    m = spec["manoeuvres"][0]
    for amplitude in (0.0, 1.0):
        q = manoeuvre_samples(spec, m, amplitude, 1.0)[1]
        np.testing.assert_allclose(q, report.home + _offsets(amplitude * HEAVE[0]), rtol=0,
                                   atol=1e-15)
    lengths = platform.inverse(report.home + _offsets(HEAVE[0]), fidelity="kinematic").length
    assert rows["length_max"][1] == pytest.approx(lengths.max(), abs=1e-12)
    assert rows["length_min"][1] == pytest.approx(lengths.min(), abs=1e-12)
    # amplitude 0: the machine at home, whose stroke margin is the check's lengths'
    at_home = np.minimum(report.length - report.stroke_min, report.stroke_max - report.length)
    assert rows["margin_stroke"][0] == pytest.approx(at_home.min(), abs=1e-12)
    assert rows["margin_stroke"][0] > 0 and rows["feasible"][0]


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_heave_scaled_to_the_ranges_is_feasible_on_every_machine(name):
    """scale_to_ranges: the heave's excursion from home is at most half of home's z axis range
    on its nearer side, and every pose is within every limit (stroke margins positive)."""
    platform = stewart.Platform.from_file(FILES[name])
    home = platform.check().home
    spec, rows = _heave_sweep(FILES[name], True)
    assert rows["feasible"] == [True, True] and min(rows["margin_stroke"]) > 0
    q = manoeuvre_samples(spec, spec["manoeuvres"][0], 1.0, 1.0)[1]
    offsets = _offsets(HEAVE[0])
    scale = (q - home)[:, 2] @ offsets[:, 2] / (offsets[:, 2] @ offsets[:, 2])
    assert scale > 0
    np.testing.assert_allclose(q, home + scale * offsets, rtol=0, atol=1e-14)
    low, high = platform.axis_ranges(home)[0, 2]
    assert scale * HEAVE[0] <= 0.5 * min(home[2] - low, high - home[2]) * (1 + 1e-12)
    assert platform.limits(q).within.all()


def test_a_scene_written_about_an_absolute_pose_plays_as_written_or_from_its_home():
    """"place": "absolute" plays the poses as written; a scene with its own "home" moves from
    it to the machine's (run_scene.py's convention), one without from the thesis home."""
    path = FILES["simona_motion_base"]
    home = stewart.Platform.from_file(path).check().home
    written = {"name": "bob", "duration": DURATION, "step": STEP,
               "pose": {"z": {"mean": 2.3, "amplitude": 0.05, "omega": 2.0}}}
    t = np.arange(int(round(DURATION / STEP)) + 1) * STEP
    bob = 0.05 * np.sin(2.0 * t)
    for manoeuvre, z in (({"scene": written, "place": "absolute"}, 2.3 + bob),
                         ({"scene": {**written, "home": [0, 0, 2.2, 0, 0, 0]}}, home[2] + 0.1 + bob),
                         ({"scene": {**written, "pose": {"z": {**written["pose"]["z"],
                                                               "mean": 0.6}}}},
                          home[2] + 0.1 + bob)):
        spec = resolve({"kind": "envelope", "platform_file": str(path),
                        "manoeuvres": [manoeuvre]}, SCENES)
        q = manoeuvre_samples(spec, spec["manoeuvres"][0], 1.0, 1.0)[1]
        np.testing.assert_allclose(q[:, 2], z, rtol=0, atol=1e-14)
        np.testing.assert_allclose(q[:, [0, 1, 3, 4, 5]], 0.0, atol=0)
    # Stating neither: a scene about the thesis home (z 0.6 above) moves; one whose poses lie
    # nearer this machine's home than the thesis' was written for it and is refused, not moved
    # 1.7 m up.
    with pytest.raises(SpecError, match=r"(?s)manoeuvres\[0\].scene = 'bob'.*nearer this "
                                        r"machine's home.*\"place\": \"absolute\""):
        resolve({"kind": "envelope", "platform_file": str(path),
                 "manoeuvres": [{"scene": written}]}, SCENES)


@pytest.mark.parametrize("change, words", [
    ({"place": "there"}, ["manoeuvres[0].place = 'there' must be 'home'", "'absolute'"]),
    ({"place": "absolute", "scale": True}, ["manoeuvres[0].place = 'absolute' with "
                                            "scale_to_ranges"]),
])
def test_bad_placements_are_refused_naming_the_field(change, words):
    manoeuvre = {"scene": "heave", **{k: v for k, v in change.items() if k != "scale"}}
    with pytest.raises(SpecError) as e:
        resolve({"kind": "envelope", "manoeuvres": [manoeuvre],
                 "scale_to_ranges": bool(change.get("scale"))}, SCENES)
    for w in words:
        assert w in str(e.value)


def test_a_scene_with_a_move_is_refused_not_cut_to_its_sinusoids():
    """Before, a scene with sinusoids and a move was swept as its sinusoids alone, and a move
    alone was refused as "a mechanism scene"."""
    sinusoids = {"name": "nod_then_go", "duration": 1.0, "step": 0.01,
                 "pose": {"z": {"mean": 0.5, "amplitude": 0.01, "omega": 1.5 * np.pi,
                                "phase": 0.0}},
                 "move": {"goal": [0.02, 0, 0.49, 0, 0, 0]}}
    for scene in ("move_line", sinusoids):
        with pytest.raises(SpecError, match=r"manoeuvres\[0\].scene = '(move_line|nod_then_go)' "
                                            r"has a move section"):
            resolve({"kind": "envelope", "manoeuvres": [{"scene": scene}]}, SCENES)


def test_a_home_beyond_a_limit_refuses_the_placement_and_says_what_to_do():
    spec = {"kind": "envelope", "platform": {"stroke_max": 0.45},
            "manoeuvres": [{"scene": "heave"}]}
    with pytest.raises(SpecError, match=r"(?s)manoeuvres\[0\]: the platform's home pose is not "
                                        r"valid.*\"place\": \"absolute\" plays"):
        resolve(spec, SCENES)


def test_the_sweep_script_takes_a_platform(tmp_path):
    """scripts/sweep.py SPEC OUT --platform FILE --scale-to-ranges: the spec's thesis platform
    replaced by SIMONA's file, the heave about SIMONA's home and scaled to its ranges."""
    path = FILES["simona_motion_base"]
    out = tmp_path / "out"
    result = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "sweep.py"),
         str(ROOT / "examples" / "sweeps" / "heave_envelope.json"), str(out), "--workers", "1",
         "--no-progress", "--platform", str(path), "--scale-to-ranges"],
        capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    spec = json.loads((out / "spec.json").read_text())
    machine = json.loads(path.read_text())
    assert spec["platform"]["base_joint"] == pytest.approx(np.ravel(machine["base_joint"]).tolist())
    rows = pq.read_table(out / "envelope.parquet").to_pydict()
    assert all(rows["feasible"]) and min(rows["margin_stroke"]) > 0
    home = stewart.Platform.from_file(path).check().home
    assert spec["manoeuvres"][0]["scene"]["pose"]["z"]["mean"] == home[2]


# A workspace slice written about the thesis' home (the docs' and the shipped specs' way): an xy
# grid and a roll line about z = 0.5 m, offsets small enough for the precision hexapods' ±14 mm.
XY = [-2e-4, 0.0, 2e-4]
SLICES = [{"name": "xy", "fixed": {"z": 0.5}, "axes": {"x": XY, "y": XY}},
          {"name": "roll", "fixed": {"x": 1e-4, "z": 0.5}, "axes": {"roll": [-1e-4, 0.0, 1e-4]}}]


def _slice_tables(spec):
    from stewart.sweeps.work import workspace_chunk
    return {c.part: {k: np.asarray(v) for k, v in
                     ((k, workspace_chunk(spec, c)[0][k].to_pylist()) for k in
                      ("x", "y", "z", "roll", "pitch", "yaw", "reachable"))}
            for c in chunks(spec)}


def _written_offsets(name):
    """The slices' poses about their home, written here: (9 or 3, 6), row-major over the axes."""
    if name == "xy":
        return np.array([[x, y, 0, 0, 0, 0] for x in XY for y in XY])
    return np.array([[1e-4, 0, 0, r, 0, 0] for r in (-1e-4, 0.0, 1e-4)])


@pytest.mark.parametrize("name", sorted(FILES))
def test_a_workspace_slice_moves_about_the_machine_home(name):
    """Before, a slice's fixed values and axes were absolute: on any machine whose home is not
    the thesis' z = 0.5 m (the Rubin hexapods' home is the zero pose, SIMONA's z = 2.39 m) every
    pose was unreachable. Now each pose is the machine's home (the frames' closed form) plus
    the slice's offset from the pose it is written about, and the grid about home is reachable."""
    platform = stewart.Platform.from_file(FILES[name])
    spec = resolve({"kind": "workspace", "platform_file": str(FILES[name]), "slices": SLICES},
                   SCENES)
    home = frames_home(platform)
    for part, t in _slice_tables(spec).items():
        q = np.column_stack([t[c] for c in ("x", "y", "z", "roll", "pitch", "yaw")])
        np.testing.assert_allclose(q, home + _written_offsets(part), rtol=0, atol=1e-15)
        assert t["reachable"].all(), (name, part)


def test_an_absolute_slice_plays_as_written_and_a_slice_moves_from_its_own_home():
    path = FILES["rubin_m2_hexapod"]
    home = stewart.Platform.from_file(path).check().home
    for change, z in (({"place": "absolute"}, 0.5),
                      ({"home": [0, 0, 0.495, 0, 0, 0]}, home[2] + 0.005), ({}, home[2])):
        s = {**SLICES[0], **change}
        spec = resolve({"kind": "workspace", "platform_file": str(path), "slices": [s]}, SCENES)
        t = _slice_tables(spec)["xy"]
        np.testing.assert_allclose(t["z"], z, rtol=0, atol=1e-15)
        # As written, z = 0.5 m is far beyond the ±14 mm strokes: nothing reachable.
        assert t["reachable"].all() == ("place" not in change), change


@pytest.mark.parametrize("change, words", [
    ({"place": "there"}, ["slices[0].place = 'there' must be 'home'", "'absolute'"]),
    ({"home": [0, 0, 0.5]}, ["slices[0].home = [0, 0, 0.5] must be 6 finite numbers"]),
    ({"place": "absolute", "home": [0, 0, 0.5, 0, 0, 0]}, ["slices[0]: 'home' with place "
                                                           "'absolute'"]),
])
def test_bad_slice_placements_are_refused_naming_the_field(change, words):
    with pytest.raises(SpecError) as e:
        resolve({"kind": "workspace", "slices": [{**SLICES[0], **change}]}, SCENES)
    for w in words:
        assert w in str(e.value)
