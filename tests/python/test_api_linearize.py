"""Platform.linearize and Platform.linearize_inverse against references independent of them:
the plant's own simulation (the linear model predicts the response to small force steps to
second order in the step), central differences of the state rate, and the inverse solver; with
tool and user frames too (the poses the tool's in the user frame, as everywhere)."""
import numpy as np
import pytest

import stewart
from stewart.errors import ParameterError
from test_frames import TOOL, USER, tool_pose

HOME = np.array([0, 0, 0.5, 0, 0, 0.0])


def step_response(A, b, t):
    """x(t) - x(0) of dx/dt = A x + b from rest: the integral of exp(A s) b over [0, t], from the
    exponential of the augmented matrix [[A, b], [0, 0]] (eigen-decomposition free: a scaled and
    squared Taylor series, enough for |A t| of order 1)."""
    n = A.shape[0]
    M = np.zeros((n + 1, n + 1))
    M[:n, :n], M[:n, n] = A * t, b * t
    squarings = max(0, int(np.ceil(np.log2(max(np.abs(M).sum(axis=1).max(), 1e-300)))) + 1)
    M /= 2.0 ** squarings
    E, term = np.eye(n + 1), np.eye(n + 1)
    for k in range(1, 30):
        term = term @ M / k
        E += term
    for _ in range(squarings):
        E = E @ E
    return E[:n, n]


@pytest.mark.parametrize("framed", [False, True])
@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_linear_model_predicts_small_force_steps(fidelity, framed):
    """At the home pose at rest under its static forces (an equilibrium: f = 0), a step of the
    forces by eps times a pattern of the static forces: the plant's pose and rates after 50 ms
    against the linear model's, for eps = 4e-3, 2e-3, 1e-3. The difference is second order:
    it falls by 4 when eps halves, and it is a small part of the response itself. Framed: the
    same in the tool's pose in the user frame (test_frames.py's frames)."""
    platform = stewart.Platform(tool_frame=TOOL, user_frame=USER) if framed else stewart.Platform()
    home = tool_pose(HOME) if framed else HOME
    lin = platform.linearize(home, fidelity=fidelity)
    static = platform.linearize_inverse(home, fidelity=fidelity).force
    assert np.abs(lin.state_rate).max() < 1e-9  # an equilibrium
    pattern = np.array([1.0, -0.7, 0.4, 0.9, -0.3, -0.8])
    t = np.linspace(0, 0.05, 51)
    errors, responses = [], []
    for eps in (4e-3, 2e-3, 1e-3):
        du = eps * pattern * static
        forces = np.tile(static + du, (t.size, 1))
        run = platform.simulate(t, forces, fidelity=fidelity, start=home,
                                relative_tolerance=1e-13, absolute_tolerance=1e-15)
        assert run.completed, run.message
        nonlinear = np.concatenate([run.pose[-1] - home, run.pose_rate[-1]])
        linear = step_response(lin.A, lin.B @ du, t[-1])
        errors.append(np.abs(nonlinear - linear).max())
        responses.append(np.abs(nonlinear).max())
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    print(f"{fidelity}{' framed' if framed else ''}: 50 ms after a force step of eps x static, |nonlinear - linear| = "
          + ", ".join(f"{e:.3e}" for e in errors) + f" (eps = 4e-3, 2e-3, 1e-3; ratios "
          + ", ".join(f"{r:.2f}" for r in ratios) + f"); response {responses[-1]:.3e}")
    for r in ratios:
        assert 3.5 < r < 4.5
    assert errors[-1] < 1e-2 * responses[-1]


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_state_rate_differences(fidelity):
    """A and B against central differences of the state rate Platform.linearize returns."""
    platform = stewart.Platform()
    rng = np.random.default_rng(1)
    q = HOME + rng.uniform(-0.05, 0.05, 6)
    qd = rng.uniform(-0.3, 0.3, 6)
    F = platform.linearize_inverse(q, qd, fidelity=fidelity).force * 1.1
    lin = platform.linearize(q, qd, F, fidelity=fidelity)
    assert lin.A.shape == (12, 12) and lin.B.shape == (12, 6)
    assert lin.C.shape == (24, 12) and lin.D.shape == (24, 6) and not lin.D.any()
    x, h = np.concatenate([q, qd]), 1e-5
    for j in range(18):
        def rate(sign):
            xj, Fj = x.copy(), F.copy()
            if j < 12:
                xj[j] += sign * h
            else:
                Fj[j - 12] += sign * 1e-2
            return platform.linearize(xj[:6], xj[6:], Fj, fidelity=fidelity).state_rate
        column = (rate(1) - rate(-1)) / (2 * (h if j < 12 else 1e-2))
        exact = lin.A[:, j] if j < 12 else lin.B[:, j - 12]
        assert np.abs(column - exact).max() <= 1e-6 * max(np.abs(exact).max(), 1)


def test_inverse_side_matches_the_inverse_solver():
    platform = stewart.Platform()
    q = HOME + np.array([0.02, -0.01, 0.03, 0.05, -0.04, 0.1])
    qd = np.array([0.1, 0.2, -0.1, 0.3, 0.1, -0.2])
    qdd = np.array([1.0, -0.5, 0.3, 2.0, -1.0, 0.5])
    jac = platform.linearize_inverse(q, qd, qdd, fidelity="full")
    solved = platform.inverse(q[None], qd[None], qdd[None], fidelity="full")
    assert np.allclose(jac.length, solved.length[0], rtol=0, atol=1e-12)
    assert np.allclose(jac.force, solved.force[0], rtol=1e-12, atol=1e-9)
    assert jac.jacobian.shape == (30, 18)


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_inverse_side_with_frames_against_differences(fidelity):
    """With tool and user frames: the inverse side's Jacobian against central differences of
    Platform.inverse (the same frames; steps 1e-5 in pose and rates, 1e-4 in accelerations), each
    block within 1e-7 of its largest entry beyond the differences' rounding; the values equal."""
    platform = stewart.Platform(tool_frame=TOOL, user_frame=USER)
    rng = np.random.default_rng(21)
    q = tool_pose(HOME + rng.uniform(-0.04, 0.04, 6))
    qd, qdd = rng.uniform(-0.3, 0.3, 6), rng.uniform(-1, 1, 6)
    jac = platform.linearize_inverse(q, qd, qdd, fidelity=fidelity)

    def outputs(z):
        r = platform.inverse(z[None, :6], z[None, 6:12], z[None, 12:], fidelity=fidelity)
        assert r.ok.all()
        return np.concatenate([r.length[0], r.length_rate[0], r.length_accel[0], r.force[0],
                               r.base_force[0], r.base_torque[0]])

    z = np.concatenate([q, qd, qdd])
    values = outputs(z)
    exact_values = np.concatenate([jac.length, jac.length_rate, jac.length_accel, jac.force,
                                   jac.base_force, jac.base_torque])
    np.testing.assert_allclose(exact_values, values, rtol=1e-10, atol=1e-9)
    worst = 0.0
    for c0 in (0, 6, 12):
        h = 1e-5 if c0 < 12 else 1e-4
        columns = []
        for j in range(c0, c0 + 6):
            up, down = z.copy(), z.copy()
            up[j] += h
            down[j] -= h
            columns.append((outputs(up) - outputs(down)) / (2 * h))
        differences = np.array(columns).T
        for r0, r1 in ((0, 6), (6, 12), (12, 18), (18, 24), (24, 27), (27, 30)):
            exact = jac.jacobian[r0:r1, c0:c0 + 6]
            rounding = 16 * np.finfo(float).eps * np.abs(values[r0:r1]).max() / h
            error = max(np.abs(exact - differences[r0:r1]).max() - rounding, 0.0)
            worst = max(worst, error / max(np.abs(exact).max(), 1e-300))
    print(f"{fidelity} framed: inverse Jacobian vs central differences, worst block {worst:.2e}")
    assert worst < 1e-7


def test_bad_input():
    platform = stewart.Platform()
    with pytest.raises(ParameterError, match="kinematic"):
        platform.linearize(HOME, fidelity="kinematic")
    with pytest.raises(ValueError, match="pitch"):
        platform.linearize([0, 0, 0.5, 0, np.pi / 2, 0], forces=np.zeros(6))
    with pytest.raises(ValueError, match="pose must hold 6"):
        platform.linearize([0, 0, 0.5])
    with pytest.raises(ValueError, match=r"forces\[2\]"):
        platform.linearize(HOME, forces=[0, 0, np.nan, 0, 0, 0])


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_a_singular_pose_is_named(fidelity):
    """At z = 0 every leg of the thesis platform lies in the base plane: no forces hold the
    platform there, and the message says it is a singular pose (it once said "reciprocal
    condition nan")."""
    with pytest.raises(ValueError) as refused:
        stewart.Platform().linearize([0, 0, 0, 0, 0, 0], fidelity=fidelity)
    assert "singular pose" in str(refused.value) and "nan" not in str(refused.value)
