"""The scene player (StewartScene.fmu) playing a trajectory file (its String parameter
trajectory_file; fmu/README.md, docs/closed-loop.md "Moves in the closed loop"), FMI 2 and FMI 3:
the outputs at the file's rows are the file's, and between rows the quintic Hermite of the two
rows, written here independently (a 6 x 6 solve for the monomials' coefficients, not the
player's closed form); the last pose held at rest after a file that ends at rest, Discard past a
file that does not; every refusal names the file, the line and the cause; numbers read the same
in any locale; a state restored replays bit for bit. Then scenes/move_line.json, planned on every
shipped machine, through the closed loop with the player in it (scripts/closed_loop.py --player,
as the OSP and SSP structures run it) tracks as the Python-driven loop does, and
scripts/machine_ssp.py writes a move scene's closed loop for libcosim."""
import json
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import closed_loop
import scenes
import stewart
from fmu_support import BUILD, VERSIONS
from test_move_scenes import DT, FILES, scene_on
from test_plant_fmu import DISCARD, OK, Instance

POSE = list(scenes.POSE)
DERIVED = POSE + list(scenes.DOT) + list(scenes.DDOT)
HEADER = ["t"] + DERIVED


def write(path, rows, header=HEADER, text=None):
    """A trajectory file of rows (t and the 18 values) under header, or the text given."""
    if text is None:
        text = ",".join(header) + "\n" + "".join(
            ",".join(repr(float(v)) for v in row) + "\n" for row in rows)
    path.write_text(text)
    return path


def random_rows(rng, n=7, rest=True):
    """n rows at uneven times: a sinusoid per component with its rates and accelerations, each
    value perturbed by up to 5 % (so that no quintic is the sinusoid); rates 0 in the last row if
    rest."""
    t = np.cumsum(np.r_[0.0, rng.uniform(0.01, 0.05, n - 1)])
    w, phase = rng.uniform(1.0, 5.0, 6), rng.uniform(0.0, 6.0, 6)
    angle = np.outer(t, w) + phase
    values = np.hstack([np.sin(angle), w * np.cos(angle), -w ** 2 * np.sin(angle)])
    values *= 1.0 + rng.uniform(-0.05, 0.05, values.shape)
    if rest:
        values[-1, 6:12] = 0.0
    return np.column_stack([t, values])


def player(version, path, name="i", **values):
    u = Instance("StewartScene", version, name)
    u.fmu.setString([u.vr["trajectory_file"]], [str(path)])
    return u.init(**values)


def hermite(row0, row1, t):
    """Pose, rate, acceleration at t of the quintic matching row0 and row1 (t, pose, rates,
    accelerations): coefficients of 1, s, ..., s^5 (s = (t - t0) / h, well conditioned) from
    the six end conditions by a linear solve."""
    h, s = row1[0] - row0[0], (t - row0[0]) / (row1[0] - row0[0])
    powers = np.arange(6)

    def rows_at(x):  # value, first and second derivative in s of each monomial at x
        return [x ** powers,
                np.r_[0.0, powers[1:] * x ** (powers[1:] - 1)],
                np.r_[0.0, 0.0, powers[2:] * (powers[2:] - 1) * x ** (powers[2:] - 2)]]

    M = np.array(rows_at(0.0) + rows_at(1.0))
    out = np.zeros((3, 6))
    for i in range(6):
        c = np.linalg.solve(M, [row0[1 + i], h * row0[7 + i], h * h * row0[13 + i],
                                row1[1 + i], h * row1[7 + i], h * h * row1[13 + i]])
        value, rate, accel = (m @ c for m in rows_at(s))
        out[:, i] = value, rate / h, accel / h ** 2
    return out.reshape(-1)


@pytest.mark.parametrize("version", VERSIONS)
def test_the_file_at_its_rows_and_the_quintic_between(tmp_path, version):
    rng = np.random.default_rng(11)
    rows = random_rows(rng)
    # the columns in another order, and one the player does not read
    order = rng.permutation(len(HEADER))
    header = [HEADER[k] for k in order] + ["comment"]
    table = np.column_stack([rows[:, order], np.zeros(len(rows))])
    u = player(version, write(tmp_path / "move.csv", table, header))
    try:
        assert np.array_equal(u.get(DERIVED), rows[0, 1:])  # at initialisation: row 0
        t = 0.0
        for k in range(len(rows) - 1):
            ends = rows[k, 0] + (rows[k + 1, 0] - rows[k, 0]) * np.array([0.21, 0.5, 0.93])
            for end in [*ends, rows[k + 1, 0]]:
                assert u.step(t, end - t) == OK
                t = end
                got = u.get(DERIVED)
                if end == rows[k + 1, 0]:
                    np.testing.assert_allclose(got, rows[k + 1, 1:], rtol=0, atol=1e-12)
                else:
                    # to rounding, relative to the segment's terms (pose, h rate, h^2
                    # acceleration, over h^order; the last segment stops: ~1e3)
                    h = rows[k + 1, 0] - rows[k, 0]
                    ends = rows[k:k + 2, 1:]
                    terms = (np.abs(ends[:, :6]).max() + h * np.abs(ends[:, 6:12]).max() +
                             h * h * np.abs(ends[:, 12:]).max())
                    tolerance = 1e-14 * np.repeat(terms / h ** np.arange(3), 6)
                    assert np.all(np.abs(got - hermite(rows[k], rows[k + 1], end)) <=
                                  np.maximum(tolerance, 1e-15))
        # past the end of a file that ends at rest: its pose, rates and accelerations 0
        assert u.step(t, 0.5) == OK
        held = u.get(DERIVED)
        assert np.array_equal(held[:6], rows[-1, 1:7]) and np.all(held[6:] == 0)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_reset_reads_the_file_anew(tmp_path, version):
    """After a reset, the next initialisation reads the file again: one written anew under the
    same name (a master rerunning a study) plays its own rows, not the rows read before."""
    rng = np.random.default_rng(5)
    first, second = random_rows(rng), random_rows(rng)
    path = write(tmp_path / "move.csv", first)
    u = player(version, path)
    try:
        assert np.array_equal(u.get(DERIVED), first[0, 1:])
        write(path, second)
        u.fmu.reset()
        u.fmu.setString([u.vr["trajectory_file"]], [str(path)])
        u.init()
        assert np.array_equal(u.get(DERIVED), second[0, 1:])
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_past_a_file_that_does_not_end_at_rest_is_discarded(tmp_path, version):
    rows = random_rows(np.random.default_rng(3), rest=False)
    path = write(tmp_path / "moving.csv", rows)
    u = player(version, path)
    try:
        end = rows[-1, 0]
        assert u.step(0.0, end) == OK  # to the last row itself
        np.testing.assert_allclose(u.get(DERIVED), rows[-1, 1:], rtol=0, atol=1e-12)
        assert u.step(end, 0.01) == DISCARD
        assert any("past the last row" in m and "moving.csv" in m and "not end at rest" in m
                   for m in u.messages), u.messages
        np.testing.assert_allclose(u.get(DERIVED), rows[-1, 1:], rtol=0, atol=1e-12)
    finally:
        u.free()


GOOD = ",".join(HEADER) + "\n" + "0," * 18 + "0\n" + "0.1," + "0," * 17 + "0\n"


@pytest.mark.parametrize("text, words", [
    (GOOD.replace("pitch_dot,", "pitch_rate,"), ["line 1", "no column pitch_dot"]),
    (GOOD + "0.05," + "0," * 17 + "0\n", ["line 4", "t = 0.05", "t must increase"]),
    (GOOD + "\n# a comment\n0.1," + "0," * 17 + "0\n", ["line 6", "t must increase"]),
    (GOOD.replace("\n0.1,0,0,", "\n0.1,0,nan,"), ["line 3", "y = \"nan\" is not finite"]),
    (GOOD.replace("\n0.1,0,0,", "\n0.1,0,inf,"), ["line 3", "y = \"inf\" is not finite"]),
    (GOOD.replace("\n0.1,0,0,", "\n0.1,0,0;5,"), ["line 3", "y = \"0;5\" is not a number"]),
    (GOOD.replace("\n0.1,0,0,", "\n0.1,0,,"), ["line 3", "y = \"\" is not a number"]),
    (GOOD + "0.2,0\n", ["line 4", "the row has 2 fields, the header 19"]),
    (",".join(HEADER) + "\n", ["no rows"]),
    ("", ["empty"]),
])
@pytest.mark.parametrize("version", VERSIONS)
def test_a_bad_file_is_refused_naming_the_line_and_cause(tmp_path, version, text, words):
    path = write(tmp_path / "bad.csv", None, text=text)
    u = Instance("StewartScene", version)
    try:
        u.fmu.setString([u.vr["trajectory_file"]], [str(path)])
        with pytest.raises(Exception):
            u.init()
        refusal = [m for m in u.messages if "bad.csv" in m]
        assert refusal and all(w in refusal[0] for w in words), (words, u.messages)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_spreadsheet_s_file_plays_as_the_plain_one(tmp_path, version):
    """A byte order mark before the header, CRLF line ends, blanks after the fields and numbers
    in scientific notation (a spreadsheet's "CSV UTF-8"): the same outputs, bit for bit, as the
    plain file at its rows and between them."""
    rows = random_rows(np.random.default_rng(5))
    plain = write(tmp_path / "plain.csv", rows)
    text = "\ufeff" + ",".join(HEADER) + "\r\n" + "".join(
        ",".join("%.17e " % v for v in row) + "\r\n" for row in rows)
    (tmp_path / "sheet.csv").write_bytes(text.encode("utf-8"))
    outputs = []
    for path in (plain, tmp_path / "sheet.csv"):
        u = player(version, path)
        try:
            got = [u.get(DERIVED)]
            for t0, t1 in zip(rows[:-1, 0], rows[1:, 0]):
                assert u.step(t0, 0.5 * (t1 - t0)) == OK
                got.append(u.get(DERIVED))
                assert u.step(0.5 * (t0 + t1), t1 - 0.5 * (t0 + t1)) == OK
                got.append(u.get(DERIVED))
            outputs.append(np.array(got))
        finally:
            u.free()
    assert np.array_equal(outputs[0], outputs[1])
    assert np.array_equal(outputs[0][0], rows[0, 1:])


@pytest.mark.parametrize("version", VERSIONS)
def test_an_unreadable_file_and_a_file_with_sinusoids_are_refused(tmp_path, version):
    for path, values, words in [
            (tmp_path / "missing.csv", {}, ["missing.csv", "no such file"]),
            (tmp_path, {}, [str(tmp_path), "directory"]),
            (write(tmp_path / "ok.csv", random_rows(np.random.default_rng(1))),
             {"roll_amplitude": 0.1}, ["roll_amplitude = 0.1", "ok.csv", "both"])]:
        u = Instance("StewartScene", version)
        try:
            u.fmu.setString([u.vr["trajectory_file"]], [str(path)])
            with pytest.raises(Exception):
                u.init(**values)
            assert any(all(w in m for w in words) for m in u.messages), (words, u.messages)
        finally:
            u.free()


def comma_locale(folder):
    """Environment variables under which de_DE.UTF-8 (decimal comma) can be set: as installed,
    or compiled into folder by localedef (glibc reads LOCPATH); None if neither."""
    import locale
    try:
        before = locale.setlocale(locale.LC_NUMERIC)
        locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")
        locale.setlocale(locale.LC_NUMERIC, before)
        return {}
    except locale.Error:
        pass
    subprocess.run(["localedef", "-i", "de_DE", "-f", "UTF-8",
                    str(folder / "de_DE.UTF-8")], capture_output=True)
    return {"LOCPATH": str(folder)} if (folder / "de_DE.UTF-8").exists() else None


def test_numbers_read_the_same_in_a_comma_locale(tmp_path):
    """In a process whose LC_NUMERIC is de_DE (strtod there reads "0,5" as a half and stops at
    the point of "0.5") the player reads the file as in the C locale."""
    import os
    rows = random_rows(np.random.default_rng(5))
    path = write(tmp_path / "move.csv", rows)
    env = comma_locale(tmp_path)
    if env is None:
        pytest.skip("no de_DE locale, and localedef cannot make one")
    code = f"""
import locale, sys
sys.path[:0] = {sys.path!r}
locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")
assert locale.localeconv()["decimal_point"] == ","
from test_plant_fmu import Instance
u = Instance("StewartScene")
u.fmu.setString([u.vr["trajectory_file"]], [{str(path)!r}])
u.init()
print(repr(list(u.get({DERIVED!r}))))
"""
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=str(pathlib.Path(__file__).parent), timeout=120,
                         env={**os.environ, **env})
    assert ran.returncode == 0, ran.stderr
    assert np.array_equal(np.array(eval(ran.stdout)), rows[0, 1:])


@pytest.mark.parametrize("version", VERSIONS)
def test_a_restored_state_replays_bit_for_bit(tmp_path, version):
    rows = random_rows(np.random.default_rng(9), n=40)
    u = player(version, write(tmp_path / "move.csv", rows))
    other = player(version, write(tmp_path / "other.csv", random_rows(
        np.random.default_rng(10), n=40)), name="other")
    try:
        h = 0.0037
        for j in range(20):
            assert u.step(j * h, h) == OK
        state = u.get_state()
        saved = u.serialize(state)
        first = []
        for j in range(20, 40):
            assert u.step(j * h, h) == OK
            first.append(u.get(DERIVED))
        u.set_state(state)
        again = []
        for j in range(20, 40):
            assert u.step(j * h, h) == OK
            again.append(u.get(DERIVED))
        assert np.array_equal(first, again)
        # the serialised state carries its file's path: another instance replays it too
        other.set_state(other.deserialize(saved))
        got = other.fmu.getString([other.vr["trajectory_file"]])[0]
        assert (got.decode() if isinstance(got, bytes) else got) == str(tmp_path / "move.csv")
        replay = []
        for j in range(20, 40):
            assert other.step(j * h, h) == OK
            replay.append(other.get(DERIVED))
        assert np.array_equal(first, replay)
    finally:
        u.free()
        other.free()


@pytest.mark.parametrize("name", sorted(FILES))
def test_the_closed_loop_with_the_player_tracks_as_the_python_loop(name):
    """move_line planned on the machine, played by the player unit in the loop, against the loop
    fed from Python: the same cue at every communication point (the player at t + h, the file's
    row at t: rounding of the time apart) and the same achieved poses."""
    scene, platform, _ = scene_on(name)
    kp, kd = closed_loop.machine_gains(platform)
    runs = [closed_loop.run(scene, None, DT, kp, kd, fmus=BUILD / "fmus" / "2.0",
                            machine=stewart.fmu_start_values(platform), platform=platform,
                            player=player)[0] for player in (False, True)]
    python, fmu = runs
    assert len(fmu["t"]) == len(python["t"])
    np.testing.assert_allclose(fmu["cue"], python["cue"], rtol=0, atol=1e-14)
    difference = np.abs(fmu["pose"] - python["pose"]).max()
    print(f"{name}: player - Python loop {difference:.1e}")
    assert difference <= 1e-12
    assert np.allclose(closed_loop.tracking_error(fmu), closed_loop.tracking_error(python),
                       rtol=1e-6, atol=0)


@pytest.mark.parametrize("name", sorted(FILES))
def test_machine_ssp_plays_a_move_scene_in_ecos_and_libcosim(name, tmp_path):
    """scripts/machine_ssp.py --scene move_line: the move planned on the machine, written next to
    the archive and named by the player's trajectory_file in the SSV set and the OSP structure.
    ecos (SSP, FMI 2 and FMI 3) and libcosim (OSP) run it alike, and the plant follows the fmpy
    loop fed from Python within the coupling error (1 % of the move's excursion, the bound of
    test_ssp.py's sinusoidal cue)."""
    import machine_ssp
    from fmu_support import libcosim_outputs
    from test_ssp import H, machine_ecos_run
    path = FILES[name]
    platform = stewart.Platform.from_file(path)
    scene, _, _ = scene_on(name)
    steps = len(scenes.trajectory(scene, platform, H)[0]) + 20  # and 20 steps held at the goal
    runs = []
    for version in ("2.0", "3.0"):
        archive = tmp_path / f"{name}_{version}.ssp"
        osp = tmp_path / f"{name}.xml"
        assert machine_ssp.write(path, archive, version, scale_to_ranges=True, scene="move_line",
                                 fmus=BUILD / "fmus" / "2.0", osp_out=osp) == name
        assert (tmp_path / f"{name}_{version}_trajectory.csv").exists()
        runs.append(machine_ecos_run(archive, name, steps)[0])
    np.testing.assert_allclose(runs[1], runs[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(libcosim_outputs(osp, steps)["plant"], runs[0], rtol=0,
                               atol=1e-9 * max(1.0, np.abs(runs[0]).max()))
    kp, kd = closed_loop.machine_gains(platform)
    loop = closed_loop.run(scene, steps * H, H, kp, kd, fmus=BUILD / "fmus" / "2.0",
                           machine=stewart.fmu_start_values(platform), platform=platform)[0]
    excursion = np.abs(loop["cue"] - loop["cue"][0]).max(axis=0)
    tolerance = 1e-2 * np.r_[[excursion[:3].max()] * 3, [max(excursion[3:].max(), 1e-6)] * 3]
    assert np.all(np.abs(runs[0] - loop["pose"][1:]) <= tolerance), name
    assert np.all(np.abs(runs[0][-1] - loop["cue"][-1]) <= tolerance), name


def test_control_design_runs_a_move_scene():
    """scripts/control_design.py --scene move_line: both loops run the planned move (no
    SceneError) over the move and its hold, and track it within the closed loop's goal (1 mm,
    1 mrad)."""
    ran = subprocess.run([sys.executable, str(scenes.ROOT / "scripts" / "control_design.py"),
                          "--scene", "move_line", "--fmus", str(BUILD / "fmus" / "2.0")],
                         capture_output=True, text=True, timeout=600)
    assert ran.returncode == 0, ran.stderr
    scene = scenes.load("move_line")
    duration = scenes.trajectory(scene, stewart.Platform(), DT)[0][-1]
    lines = [line for line in ran.stdout.splitlines() if f"move_line over {duration:g} s" in line]
    assert len(lines) == 2, ran.stdout
    for line in lines:
        position, angle = map(float, re.search(r"tracking error max (\S+) m, (\S+) rad",
                                               line).groups())
        assert position <= 1e-3 and angle <= 1e-3, line


@pytest.mark.parametrize("script", ["closed_loop.py", "cueing_loop.py"])
def test_the_loops_refuse_a_bad_step_or_a_unit_s_refusal_naming_the_cause(tmp_path, script):
    """A step or duration that is not a finite time > 0: the option named (was a traceback, or a
    division by zero); a step the plant refuses (0.3 s: the legs leave their strokes between
    steps): the unit, the time and the plant's own message, not only fmpy's status."""
    base = [sys.executable, str(closed_loop.ROOT / "scripts" / script), "--no-plot",
            "--fmus", str(BUILD / "fmus" / "2.0"), "--out", str(tmp_path)]
    base += (["--scene", "move_line", "--player"] if script == "closed_loop.py" else
             ["--manoeuvre", "car_braking", "--platform",
              str(FILES["simona_motion_base"])])
    for bad in (["--step", "0"], ["--step", "nan"], ["--duration", "-1"]):
        run = subprocess.run(base + bad, capture_output=True, text=True, timeout=300)
        assert run.returncode == 2 and f"argument {bad[0]}" in run.stderr, run.stderr
        assert "finite time > 0" in run.stderr and "Traceback" not in run.stderr
    if script == "closed_loop.py":
        run = subprocess.run(base + ["--step", "0.3"], capture_output=True, text=True,
                             timeout=300)
        assert run.returncode == 1 and "Traceback" not in run.stderr, run.stderr
        assert "unit plant" in run.stderr and "left the stroke" in run.stderr, run.stderr


def test_the_loop_plays_a_move_of_zero_length(tmp_path):
    """A scene whose move goes nowhere and holds for no time: one communication point at the
    start pose, without a division by its zero duration."""
    scene = tmp_path / "still.json"
    scene.write_text(json.dumps({"title": "still", "step": 0.001, "move": {
        "kind": "line", "goal": [0, 0, 0.5, 0, 0, 0], "leg_speed_max": 0.05,
        "leg_accel_max": 0.5, "hold": 0}}))
    run = subprocess.run([sys.executable, str(closed_loop.ROOT / "scripts" / "closed_loop.py"),
                          "--scene", str(scene), "--player", "--no-plot",
                          "--fmus", str(BUILD / "fmus" / "2.0"), "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and "Warning" not in run.stderr, run.stderr
    data = np.genfromtxt(tmp_path / "closed_loop.csv", delimiter=",", names=True)
    assert data.size == 1 and float(data["z"]) == 0.5
