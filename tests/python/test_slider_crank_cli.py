"""slider-crank-solve: the thesis' slider-crank against its closed form."""
import subprocess

import numpy as np


def test_slider_follows_the_closed_form(build_dir, tmp_path):
    out = tmp_path / "sc.csv"
    result = subprocess.run([str(build_dir / "slider-crank-solve"), "--dt", "0.005", str(out)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    d = np.genfromtxt(out, delimiter=",", names=True)
    phi, r, l = d["crank_angle"], 1.0, 2.0
    x = r * np.cos(phi) + np.sqrt(l ** 2 - (r * np.sin(phi)) ** 2)
    np.testing.assert_allclose(d["slider_x"], x, atol=1e-11)
    assert abs(d["slider_x"].min() - 1.0) < 1e-3 and abs(d["slider_x"].max() - 3.0) < 1e-3
    np.testing.assert_allclose(d["slider_v"][1:-1], np.gradient(d["slider_x"], d["t"])[1:-1], atol=1e-4)
    # crank horizontal: the crank's weight at 0.5 m plus half the rod's weight at 1 m
    assert abs(d["crank_torque"][0] - (1.0 * 9.81 * 0.5 + 2.0 * 9.81 / 2 * 1.0)) < 1e-9
    assert len(d) == 2401  # two turns at 10 rpm = 12 s


def test_bad_arguments(build_dir, tmp_path):
    def run(*args):
        return subprocess.run([str(build_dir / "slider-crank-solve"), *args], capture_output=True,
                              text=True, timeout=60)
    assert run("--rpm", "-3", str(tmp_path / "x.csv")).returncode == 2
    assert run().returncode == 2
    assert run("--dt", "abc", str(tmp_path / "x.csv")).returncode == 2
