"""Platform.linearize with current and voltage input (the C side is checked against central
differences of the plant's right-hand side in tests/unit/test_linearize_drives.c): the layout
Python gives (states, inputs, shapes), the windings' rows against di/dt = (V - R i - k_t c L_dot)
/ L_w written here, the voltage-driven plant's current columns against the current-driven
plant's B at the same currents, and the refusals."""
import numpy as np
import pytest

import stewart

DRIVE = dict(screw_lead=0.005, gear_ratio=3.0, rotor_inertia=2e-5, screw_inertia=9e-5,
             torque_constant=0.5, winding_resistance=1.2, winding_inductance=2e-3,
             screw_efficiency=0.9, screw_back_efficiency=0.85, coulomb_friction=40.0,
             viscous_friction=300.0)
POSE = [0.01, -0.005, 0.51, 0.02, -0.01, 0.03]
RATE = [0.05, -0.03, 0.04, 0.02, -0.03, 0.04]


def test_voltage_with_inductance_has_the_windings_as_states():
    platform = stewart.Platform(**DRIVE)
    volts, amps = np.linspace(3.0, 8.0, 6), np.linspace(0.3, 0.6, 6)
    lin = platform.linearize(POSE, RATE, volts, "full", input="voltage", winding_current=amps)
    assert lin.A.shape == (18, 18) and lin.B.shape == (18, 6) and lin.C.shape == (24, 18)
    assert lin.states[12] == "winding_current[1]" and lin.inputs[0] == "voltage[1]"
    R, Lw, kt = DRIVE["winding_resistance"], DRIVE["winding_inductance"], DRIVE["torque_constant"]
    c = 2 * np.pi * DRIVE["gear_ratio"] / DRIVE["screw_lead"]
    L_dot = lin.output[18:24]
    np.testing.assert_allclose(lin.state_rate[12:], (volts - R * amps - kt * c * L_dot) / Lw,
                               rtol=1e-12)
    np.testing.assert_allclose(lin.A[12:, 12:], -R / Lw * np.eye(6), rtol=1e-14)
    np.testing.assert_allclose(lin.B[12:], np.eye(6) / Lw, rtol=1e-14)
    np.testing.assert_allclose(lin.A[12:, :12], -kt * c / Lw * lin.C[18:24, :12], rtol=1e-12,
                               atol=1e-9)
    by_current = platform.linearize(POSE, RATE, amps, "full", input="current")
    assert by_current.A.shape == (12, 12) and by_current.inputs[0] == "current[1]"
    np.testing.assert_allclose(lin.A[6:12, 12:], by_current.B[6:12], rtol=1e-12)
    np.testing.assert_allclose(lin.A[:12, :12], by_current.A, rtol=1e-12, atol=1e-12)
    assert lin.not_smooth_legs == 0  # moving: no kink


def test_refusals():
    with pytest.raises(stewart.ParameterError, match="screw_lead"):
        stewart.Platform().linearize(POSE, None, np.ones(6), input="current")
    with pytest.raises(ValueError, match="needs the inputs"):
        stewart.Platform(**DRIVE).linearize(POSE, input="current")
    with pytest.raises(stewart.ParameterError, match="input = 'torque'"):
        stewart.Platform(**DRIVE).linearize(POSE, None, np.ones(6), input="torque")
    # arguments the linearisation would ignore: no winding states with current input, no
    # drives in the plant with force input
    with pytest.raises(ValueError, match="winding_current: the windings' currents are states"):
        stewart.Platform(**DRIVE).linearize(POSE, None, np.ones(6), input="current",
                                            winding_current=np.ones(6))
    with pytest.raises(ValueError, match="are for input = current or voltage"):
        stewart.Platform(**DRIVE).linearize(POSE, None, None, smoothing_speed=1e-3)
