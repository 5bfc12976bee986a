"""The FMUs under fmpy's own master (fmpy.simulate_fmu), FMI 2 and FMI 3.

(fmpy 0.3.32's set_input_derivatives=True only works with exactly nine continuous inputs, a
fixed-size buffer in fmpy.simulation.Input, so fmi2SetRealInputDerivatives is tested directly in
test_fmu_manoeuvres.py instead.)"""
import numpy as np
import pytest

from fmpy import simulate_fmu

from fmu_support import (VERSIONS, L, L_DOT, L_DDOT, F, POSE, backward_fd, fmu_path, reference_matrix, stewart_solve, thesis_manoeuvre)

OUT = L + L_DOT + L_DDOT + F


def _signal(t, q):
    dtype = [("time", np.float64)] + [(p, np.float64) for p in POSE]
    s = np.zeros(len(t), dtype=dtype)
    s["time"] = t
    for i, p in enumerate(POSE):
        s[p] = q[:, i]
    return s


def _recorded(result):
    return np.column_stack([result[name] for name in OUT])


@pytest.mark.parametrize("version", VERSIONS)
def test_simulate_fmu_holds_the_inputs(version):
    """fmpy sets the inputs of t_j, steps, and records at t_j+1: with derivatives = 0 that is the
    solution for the pose of t_j (finite differences over the earlier communication points)."""
    h, n = 0.1, 21
    t = h * np.arange(n)
    q, _, _ = thesis_manoeuvre("roll", t)
    q[:, 2] += 0.01 * np.sin(3 * t)  # and some heave
    result = simulate_fmu(str(fmu_path(version)), start_values={"fidelity": 1},
                          input=_signal(t, q), output=list(OUT), output_interval=h,
                          stop_time=t[-1])
    rt = result["time"]
    np.testing.assert_allclose(rt, t, atol=1e-12)
    qd, qdd = backward_fd(t, q)
    ref = reference_matrix(stewart_solve(t, q, qd, qdd))
    got = _recorded(result)
    np.testing.assert_allclose(got[0], ref[0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(got[1:], ref[:-1], rtol=1e-9, atol=1e-9)

