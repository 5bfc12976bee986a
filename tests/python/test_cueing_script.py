"""scripts/cueing.py (docs/cueing.md, section 8) on every shipped manoeuvre, on SIMONA's motion base
and the thesis platform: what it writes read back and checked against the package's pieces run
here (the trajectory within every limit, the platform's felt motion from the written trajectory,
the perceived signals, the scores recomputed from the written columns, the plot's lines), bad arguments refused with
exit status 2 naming them; and studies/cueing_tuning.py's choices within their admissible sets."""
import csv
import pathlib
import sys

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
pytest.importorskip("scipy.signal")
import cueing as cueing_script  # noqa: E402  (scripts/, on the path by conftest.py)

MACHINES = ("simona_motion_base", "thesis")
HEAD = {"simona_motion_base": 1.2075, "thesis": 0.3}


def read(path):
    with open(path, encoding="utf-8") as stream:
        header = stream.readline().strip().split(",")
        return header, np.loadtxt(stream, delimiter=",", ndmin=2)


@pytest.mark.parametrize("machine", MACHINES)
@pytest.mark.parametrize("name", sorted(stewart.manoeuvre_files()))
def test_script_writes_the_cue_its_perception_and_scores(machine, name, tmp_path, capsys):
    path = stewart.platform_files()[machine]
    out = tmp_path / "cue.csv"
    head = [0.0, 0.0, HEAD[machine]]
    assert cueing_script.main([f"--manoeuvre={name}", f"--platform={path}",
                               f"--option=head_z={head[2]}", "--option=surge_scale=0.4",
                               f"-o={out}"]) == 0
    printed = capsys.readouterr().out
    assert "f_x" in printed and "wrote" in printed
    platform = stewart.Platform.from_file(path)
    t, f, w = stewart.manoeuvre(name)
    header, trajectory = read(out)
    assert header[:7] == ["t", "x", "y", "z", "roll", "pitch", "yaw"] and len(header) == 19
    np.testing.assert_array_equal(trajectory[:, 0], t)
    pose, rate, accel = trajectory[:, 1:7], trajectory[:, 7:13], trajectory[:, 13:19]
    assert np.all(platform.limits(pose).within)
    columns, perceived = read(tmp_path / "cue_perceived.csv")
    column = {c: perceived[:, i] for i, c in enumerate(columns)}

    def group(prefix):
        return np.column_stack([column[f"{prefix}_{c}"] for c in cueing_script.CHANNELS])

    np.testing.assert_array_equal(group("vehicle"), np.hstack([f, w]))
    felt = stewart.head_motion(platform, pose, rate, accel, head=head)
    np.testing.assert_allclose(group("platform"), np.hstack(felt), rtol=0, atol=1e-9)
    vehicle_perceived = stewart.perception(t, f, w)
    platform_perceived = stewart.perception(t, *felt)
    np.testing.assert_allclose(group("perceived_vehicle"), np.hstack(vehicle_perceived),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(group("perceived_platform"), np.hstack(platform_perceived),
                               rtol=0, atol=1e-9)
    assert set(np.unique(column["limited"])) <= {0.0, 1.0}
    scores = stewart.cueing_scores(t, group("perceived_vehicle"), group("perceived_platform"))
    with open(tmp_path / "cue_scores.csv", encoding="utf-8") as stream:
        rows = list(csv.DictReader(stream))
    assert [r["channel"] for r in rows] == list(cueing_script.CHANNELS)
    for i, row in enumerate(rows):
        for key in ("rmse", "correlation", "delay", "peak_correlation"):
            np.testing.assert_allclose(float(row[key]), getattr(scores, key)[i], rtol=1e-6,
                                       atol=1e-9, equal_nan=True, err_msg=f"{row['channel']} {key}")
    assert (tmp_path / "cue.png").stat().st_size > 10_000


def test_plot_draws_the_perceived_signals(tmp_path):
    platform = stewart.Platform.from_file(stewart.platform_files()["thesis"])
    t, f, w = stewart.manoeuvre("car_lane_change")
    result = cueing_script.run(platform, t, f, w, surge_scale=0.3, sway_scale=0.3)
    drawn = cueing_script.plot(result, tmp_path / "plot.png")
    np.testing.assert_array_equal(drawn["perceived f_y [m/s²]"][:, 0],
                                  result["vehicle"].specific_force[:, 1])
    np.testing.assert_array_equal(drawn["perceived w_z [rad/s]"][:, 1],
                                  result["platform"].angular_velocity[:, 2])


@pytest.mark.parametrize("arguments, message", [
    (["--manoeuvre=car_braking"], "--platform"),
    (["--platform=x.json"], "either VEHICLE.csv or --manoeuvre"),
    (["--manoeuvre=car_braking", "--platform=PLATFORM", "--option=surge=1"], "not a cueing option"),
    (["--manoeuvre=car_braking", "--platform=PLATFORM", "--option=surge_scale"], "NAME=VALUE"),
    (["--manoeuvre=car_braking", "--platform=PLATFORM", "--option=surge_scale=a"], "not a number"),
    (["--manoeuvre=car_braking", "--platform=PLATFORM", "--option=surge_scale=20"], "surge_scale"),
    (["--manoeuvre=no_such", "--platform=PLATFORM"], "no manoeuvre 'no_such'"),
])
def test_bad_arguments_are_refused_by_name(arguments, message, tmp_path, capsys):
    path = str(stewart.platform_files()["thesis"])
    arguments = [a.replace("PLATFORM", path) for a in arguments] + [f"-o={tmp_path / 'o.csv'}"]
    with pytest.raises(SystemExit) as stop:
        cueing_script.main(arguments)
    assert stop.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "o.csv").exists()


def test_tuning_study_keeps_within_its_admissible_sets():
    """studies/cueing_tuning.py on a small grid: the per-manoeuvre tuning leaves the limiter idle,
    the no-cut one never cuts and, choosing from a superset of points, scores no worse; the
    machine tuning is one point idle on every manoeuvre; a platform standing still scores >= 1
    (its RMSE is the vehicle's RMS about the rest value, at least its standard deviation)."""
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "studies"))
    import cueing_tuning
    platform = stewart.Platform.from_file(stewart.platform_files()["simona_motion_base"])
    vehicles = {n: stewart.manoeuvre(n) for n in ("car_braking", "car_lane_change")}
    tuned, count = cueing_tuning.tune(platform, vehicles, [0.5, 2.0], [0.2, 1.0], [0, 0, 1.2])
    assert count == 8
    for name in vehicles:
        idle, no_cut = tuned["manoeuvre"][name], tuned["no cut"][name]
        assert not idle[2]["cue"].limited.any() and not no_cut[2]["cue"].cut.any()
        assert cueing_tuning.criterion(no_cut[2]) <= cueing_tuning.criterion(idle[2])
        assert not tuned["machine"][name][2]["cue"].limited.any()
        assert cueing_tuning.standing_still(platform, vehicles[name]) >= 1.0
    assert len({tuned["machine"][n][:2] for n in vehicles}) == 1
