"""--units on the plot scripts: what each panel draws is the SI series converted (factors written
here, not taken from the code), labels name the unit; the CSVs the scripts write stay SI."""
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import closed_loop
import plots

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_leg_plot_draws_lengths_in_the_unit_asked(tmp_path):
    rng = np.random.default_rng(4)
    t = np.linspace(0, 1, 11)
    series = {k: rng.normal(size=(11, 6)) for k in ("L", "L_dot", "F")}
    drawn = plots.plot_legs(t, series, tmp_path / "legs.png", "", "mm")
    assert set(drawn) == {"length L [mm]", "rate dL/dt [mm/s]", "force F [N]"}
    np.testing.assert_array_equal(drawn["length L [mm]"], series["L"] * 1e3)
    np.testing.assert_array_equal(drawn["rate dL/dt [mm/s]"], series["L_dot"] * 1e3)
    np.testing.assert_array_equal(drawn["force F [N]"], series["F"])
    si = plots.plot_legs(t, series, tmp_path / "si.png")
    np.testing.assert_array_equal(si["length L [m]"], series["L"])


def test_closed_loop_plot_draws_the_pose_in_the_units_asked(tmp_path):
    rng = np.random.default_rng(5)
    n = 21
    result = {"t": np.linspace(0, 0.02, n), "cue": rng.normal(size=(n, 6)),
              "pose": rng.normal(size=(n, 6)), "force": rng.normal(size=(n, 6))}
    drawn = closed_loop.plot(result, tmp_path / "loop.png", "um,deg")
    # each axis: its cue, then its achieved pose
    position = np.column_stack([result[k][:, i] for i in range(3) for k in ("cue", "pose")])
    angle = np.column_stack([result[k][:, i] for i in range(3, 6) for k in ("cue", "pose")])
    np.testing.assert_array_equal(drawn["position [um]"], position * 1e6)
    np.testing.assert_allclose(drawn["angle [deg]"], angle * 180 / math.pi, rtol=1e-15)
    np.testing.assert_array_equal(drawn["actuator force [N]"], result["force"])


def test_plot_legs_script_takes_units(build_dir, tmp_path):
    poses = tmp_path / "poses.csv"
    poses.write_text("t,x,y,z,roll,pitch,yaw\n0,0,0,0.5,0,0,0\n0.1,0.01,0,0.51,0.02,0,0\n"
                     "0.2,0.02,0,0.52,0.04,0,0.01\n")
    subprocess.run([str(build_dir / "stewart-solve"), poses, tmp_path / "out.csv"], check=True)
    script = [sys.executable, str(ROOT / "scripts" / "plot_legs.py"), str(tmp_path / "out.csv")]
    ok = subprocess.run(script + [str(tmp_path / "legs.png"), "--units", "mm"],
                        capture_output=True, text=True, timeout=120)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "legs.png").stat().st_size > 0
    bad = subprocess.run(script + [str(tmp_path / "bad.png"), "--units", "inch"],
                         capture_output=True, text=True, timeout=120)
    assert bad.returncode == 2 and "'inch' is neither a length unit" in bad.stderr
