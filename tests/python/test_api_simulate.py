"""Platform.simulate: free fall against the closed form, the same numbers as `stewart-simulate` on
the same forces CSV, the inverse side's forces along a manoeuvre giving back its poses (round trip,
docs/forward-dynamics.md), a refused step stopping the run, and bad arguments."""
import numpy as np
import pytest

import scenes
import stewart
from test_cli import read
from test_simulate_cli import write_forces

NOT_RUN = stewart.simulate.STATUS_NOT_RUN


@pytest.fixture(scope="module")
def platform():
    return stewart.Platform()


def manoeuvre(name, duration, dt):
    scene = scenes.load(name)
    scene["duration"] = duration
    t = scenes.times(scene, dt)
    return (t, *scenes.pose(scene, t))


def test_free_fall_is_the_closed_form(platform):
    t = np.arange(0, 0.2001, 0.01)
    sim = platform.simulate(t, np.zeros((t.size, 6)), fidelity="massless")
    assert sim.completed and sim.message == ""
    np.testing.assert_allclose(sim.pose[:, 2], 0.5 - 0.5 * 9.81 * t ** 2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sim.pose_rate[:, 2], -9.81 * t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sim.pose[:, [0, 1, 3, 4, 5]], 0, atol=1e-12)
    assert sim.steps[0] == 0 and (sim.steps[1:] >= 1).all()
    assert sim.statistics["steps"] == sim.steps.sum()


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_same_numbers_as_stewart_simulate(platform, build_dir, tmp_path, fidelity):
    import subprocess
    t, q, qd, qdd = manoeuvre("combined", duration=0.3, dt=0.005)
    forces = platform.inverse(q, qd, qdd, fidelity=fidelity).force
    write_forces(tmp_path / "in.csv", t, forces)
    start = q[0] + [0.001, 0, 0, 0, 0, 0]
    args = []
    for i, name in enumerate(scenes.POSE):
        args += ["--param", f"{name}0={float(start[i])!r}", "--param",
                 f"{name}_dot0={float(qd[0, i])!r}"]
    r = subprocess.run([str(build_dir / "stewart-simulate"), "--fidelity", fidelity, *args,
                        "--param", "method=3", tmp_path / "in.csv", tmp_path / "out.csv"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    header, cli = read(tmp_path / "out.csv")
    col = {name: cli[:, i] for i, name in enumerate(header)}
    sim = platform.simulate(t, forces, fidelity, start=start, start_rate=qd[0], method="erk5")
    assert sim.completed
    np.testing.assert_array_equal(sim.t, col["t"])
    np.testing.assert_array_equal(sim.pose, np.column_stack([col[p] for p in scenes.POSE]))
    np.testing.assert_array_equal(sim.pose_rate, np.column_stack([col[p] for p in scenes.DOT]))
    np.testing.assert_array_equal(sim.length, np.column_stack([col[f"L{k}"] for k in range(1, 7)]))
    np.testing.assert_array_equal(sim.length_rate,
                                  np.column_stack([col[f"L_dot{k}"] for k in range(1, 7)]))
    for name in ["warnings", "steps", "rhs_evaluations", "nonlinear_iterations",
                 "error_test_failures"]:
        np.testing.assert_array_equal(getattr(sim, name), col[name])


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_forces_of_the_inverse_side_give_back_the_manoeuvre(platform, fidelity):
    """docs/forward-dynamics.md: forces linear between samples reproduce the cue to 1.4e-7 at
    0.25 ms samples over 1 s (required there: 1e-6)."""
    t, q, qd, qdd = manoeuvre("combined", duration=1.0, dt=2.5e-4)
    inverse = platform.inverse(q, qd, qdd, fidelity=fidelity)
    assert inverse.ok.all()
    sim = platform.simulate(t, inverse.force, fidelity, start=q[0], start_rate=qd[0],
                            relative_tolerance=1e-12, absolute_tolerance=1e-14)
    assert sim.completed, sim.message
    error = np.max(np.abs(sim.pose - q))
    print(f"{fidelity}: max pose error {error:.3g}")
    assert error < 1e-6
    np.testing.assert_allclose(sim.length, inverse.length, rtol=0, atol=1e-6)


def test_a_refused_step_stops_the_run_and_marks_the_rest_not_run(platform):
    t = np.linspace(0, 0.2, 21)
    forces = np.full((21, 6), 300.0)
    whole = platform.simulate(t, forces, "massless")
    forces[12, 3] = np.inf
    sim = platform.simulate(t, forces, "massless")
    assert not sim.completed
    assert sim.status[12] == -1 and sim.status_name(12) == "invalid argument"
    assert (sim.status[13:] == NOT_RUN).all() and sim.status_name(20) == "not run"
    assert sim.ok[:12].all()
    assert "row 12" in sim.message and "inf" in sim.message
    np.testing.assert_array_equal(sim.pose[:12], whole.pose[:12])  # the rows before it ran
    assert (sim.pose[12:] == 0).all()


def test_a_start_no_plant_can_take_is_row_0(platform):
    t = np.linspace(0, 0.1, 5)
    sim = platform.simulate(t, np.zeros((5, 6)), "massless", start=[0, 0, 0.5, 0, np.pi / 2, 0])
    assert sim.status[0] < 0 and (sim.status[1:] == NOT_RUN).all()
    assert "pitch" in sim.message, sim.message


@pytest.mark.parametrize("call, error, words", [
    (lambda p: p.simulate([0, 1, 1], np.zeros((3, 6))), ValueError, ["t[2]", "does not increase"]),
    (lambda p: p.simulate([0, np.nan], np.zeros((2, 6))), ValueError, ["t[1]", "nan"]),
    (lambda p: p.simulate([[0, 1]], np.zeros((2, 6))), ValueError, ["t", "(1, 2)"]),
    (lambda p: p.simulate([0, 1], np.zeros((3, 6))), ValueError, ["forces", "3 rows"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), start=[0, 0, 0.5]), ValueError, ["start", "3"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), start_rate=[np.nan] * 6), ValueError,
     ["start_rate", "nan"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), "kinematic"), stewart.ParameterError,
     ["fidelity", "kinematic"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), "fast"), stewart.ParameterError,
     ["fidelity", "fast"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), method="rk9"), stewart.ParameterError,
     ["method", "rk9"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), relative_tolerance=-1), stewart.ParameterError,
     ["relative_tolerance", "-1"]),
    (lambda p: p.simulate([0, 1], np.zeros((2, 6)), max_internal_steps=0.5),
     stewart.ParameterError, ["max_internal_steps", "0.5"]),
])
def test_bad_arguments_raise_naming_them(platform, call, error, words):
    with pytest.raises(error) as e:
        call(platform)
    for w in words:
        assert w in str(e.value)


def test_a_plant_that_cannot_be_made_raises_value_error_naming_why():
    """Parameters whose plant cannot take a first step raise ValueError with the library's
    message, not MemoryError: gravity of 1e300 m/s2 (the accelerations would pass 1e100) is
    refused with the platform, naming the field; an absolute tolerance no plant can use, at the
    first simulate."""
    with pytest.raises(ValueError, match=r"gravity\[3\] = -1e\+300 m/s2 is beyond any machine"):
        stewart.Platform(gravity=[0.0, 0.0, -1e300])
    t = np.arange(0, 0.0101, 0.01)
    with pytest.raises(ValueError, match="absolute_tolerance"):
        stewart.Platform().simulate(t, np.zeros((t.size, 6)), fidelity="massless",
                                    absolute_tolerance=1e-300)


def test_fixed_steps_bound_the_work_and_follow_the_adaptive_default():
    """fixed_steps = N: N steps of the 5-stage ERK 4(3) per communication step and one evaluation
    at its start (the integrator restarts each step), whatever the motion: 5 N + 1 right-hand
    sides. Under slowly changing forces the pose stays with the error-controlled default."""
    p = stewart.Platform()
    t = np.arange(201) * 1e-3
    home = np.array([0.0, 0.0, 0.55, 0.0, 0.0, 0.0])
    hover = p.inverse(np.tile(home, (1, 1)), fidelity="full").force[0]
    forces = hover * (1 + 0.01 * np.sin(5 * t))[:, None]
    adaptive = p.simulate(t, forces, fidelity="full", start=home)
    for n in (1, 2):
        fixed = p.simulate(t, forces, fidelity="full", start=home, fixed_steps=n)
        assert fixed.completed
        assert (fixed.rhs_evaluations[1:] == 5 * n + 1).all(), fixed.rhs_evaluations[:5]
        assert (fixed.steps[1:] == n).all()
        assert np.abs(fixed.pose - adaptive.pose).max() < 1e-9


@pytest.mark.parametrize("bad", [-1, 1001, 2.5])
def test_fixed_steps_out_of_range_is_refused_naming_it(bad):
    p = stewart.Platform()
    with pytest.raises(stewart.ParameterError, match="fixed_steps"):
        p.simulate(np.arange(3) * 1e-3, np.zeros((3, 6)), fidelity="massless", fixed_steps=bad)
