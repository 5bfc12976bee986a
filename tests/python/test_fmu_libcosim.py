"""The FMI 2 FMU co-simulates in libcosim (through libcosimpy), driven by libcosim's own input
mechanism (an override manipulator), and gives the same outputs as fmpy on the same call
sequence, and as stewart-solve on the same poses."""
import numpy as np
import pytest

from fmu_support import (POSE, L, L_DOT, L_DDOT, F, OK, Unit, backward_fd, fmu_path,
                         reference_matrix, stewart_solve, thesis_manoeuvre)

libcosimpy = pytest.importorskip("libcosimpy")
from libcosimpy.CosimExecution import CosimExecution  # noqa: E402
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level  # noqa: E402
from libcosimpy.CosimManipulator import CosimManipulator  # noqa: E402
from libcosimpy.CosimObserver import CosimObserver  # noqa: E402
from libcosimpy.CosimSlave import CosimLocalSlave  # noqa: E402

OUT = L + L_DOT + L_DDOT + F


@pytest.mark.parametrize("kind", ["heave", "pitch"])
def test_libcosim_equals_fmpy_and_stewart_solve(kind):
    log_output_level(CosimLogLevel.ERROR)
    h, n = 0.1, 40
    step_ns = int(round(h * 1e9))
    t = np.array([j * step_ns / 1e9 for j in range(n)])  # libcosim's times (integer ns)
    q, _, _ = thesis_manoeuvre(kind, t)
    fmpy_unit = Unit("2.0")
    vr = fmpy_unit.vr

    ex = CosimExecution.from_step_size(step_size=step_ns)
    slave = CosimLocalSlave(fmu_path=str(fmu_path("2.0")), instance_name="platform")
    i = ex.add_local_slave(slave)
    assert i >= 0
    assert ex.integer_initial_value(i, vr["fidelity"], 1)
    for name, value in zip(POSE, q[0]):
        assert ex.real_initial_value(i, vr[name], float(value))
    manipulator = CosimManipulator.create_override()
    observer = CosimObserver.create_last_value()
    ex.add_manipulator(manipulator)
    ex.add_observer(observer)

    try:
        assert fmpy_unit.init(fidelity=1, **dict(zip(POSE, q[0]))) == OK
        cosim_rows, fmpy_rows = [], []
        for j in range(n):
            # libcosim: inputs of t_j, doStep(t_j, h), then the outputs are observed
            assert manipulator.slave_real_values(i, [vr[p] for p in POSE], [float(v) for v in q[j]])
            assert ex.step()
            cosim_rows.append(observer.last_real_values(i, [vr[o] for o in OUT]))
            assert observer.last_integer_values(i, [vr["status"]]) == [0]
            # fmpy, the same sequence
            fmpy_unit.set_values(dict(zip(POSE, q[j])))
            assert fmpy_unit.do_step(t[j], h) == OK
            fmpy_rows.append(fmpy_unit.get_reals(OUT))
        assert abs(ex.status().current_time - n * h * 1e9) < 1
        cosim_rows, fmpy_rows = np.array(cosim_rows), np.array(fmpy_rows)
        assert cosim_rows.tobytes() == fmpy_rows.tobytes()
        # held over each step: the outputs belong to the pose set at t_j
        qd, qdd = backward_fd(t, q)
        ref = reference_matrix(stewart_solve(t, q, qd, qdd))
        np.testing.assert_allclose(cosim_rows, ref, rtol=1e-9, atol=1e-9)
    finally:
        fmpy_unit.free()
