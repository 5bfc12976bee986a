"""The plant driven by motor currents through the package: the inverse's forces turned into
currents with the drive's law written here (lossless screw, no friction: i = (F + m_r L_ddot) /
(c k_t), c = 2 pi N / lead, m_r = J c^2) and fed to Platform.simulate(input="current") bring the
cue's pose back as the forces themselves do; the drive outputs against the same law."""
import numpy as np
import pytest

import stewart
from stewart import scenes

DRIVE = dict(screw_lead=0.005, gear_ratio=3.0, rotor_inertia=2e-5, screw_inertia=9e-5,
             torque_constant=0.5, winding_resistance=1.2)


def motor_per_leg():
    return 2 * np.pi * DRIVE["gear_ratio"] / DRIVE["screw_lead"]


def motor_inertia():
    return DRIVE["rotor_inertia"] + DRIVE["screw_inertia"] / DRIVE["gear_ratio"] ** 2


@pytest.mark.parametrize("fidelity", ["massless", "full"])
def test_inverse_currents_reproduce_the_cue(fidelity):
    dt, duration = 2.5e-4, 1.0
    scene = scenes.load("combined")
    scene["duration"] = duration
    t = np.arange(0, duration + dt / 2, dt)
    q, qd, qdd = scenes.pose(scene, t)
    platform = stewart.Platform(**DRIVE)
    inv = platform.inverse(q, qd, qdd, fidelity=fidelity)
    c = motor_per_leg()
    m_r = motor_inertia() * c * c
    currents = (inv.force + m_r * inv.length_accel) / (c * DRIVE["torque_constant"])
    by_force = platform.simulate(t, inv.force, fidelity, q[0], qd[0], relative_tolerance=1e-12,
                                 absolute_tolerance=1e-14)
    by_current = platform.simulate(t, currents, fidelity, q[0], qd[0], input="current",
                                   relative_tolerance=1e-12, absolute_tolerance=1e-14)
    assert by_force.completed and by_current.completed, by_current.message
    force_error = np.max(np.abs(by_force.pose - q))
    current_error = np.max(np.abs(by_current.pose - q))
    print(f"{fidelity}: pose error by force {force_error:.3g}, by current {current_error:.3g}")
    assert force_error < 1e-6
    assert current_error < 1e-6
    # the outputs by the law: motor speed c L_dot, torque k_t i, voltage R i + k_t omega
    np.testing.assert_allclose(by_current.current, currents, rtol=0, atol=1e-12)
    np.testing.assert_allclose(by_current.motor_speed, c * by_current.length_rate, rtol=1e-12,
                               atol=1e-9)
    np.testing.assert_allclose(by_current.motor_torque, DRIVE["torque_constant"] * currents,
                               rtol=1e-12, atol=1e-12)
    voltage = DRIVE["winding_resistance"] * currents + DRIVE["torque_constant"] * by_current.motor_speed
    np.testing.assert_allclose(by_current.voltage, voltage, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(by_current.electrical_power, voltage * currents, rtol=1e-12,
                               atol=1e-9)
    # the leg forces the drives made are the inverse's, to the round trip's accuracy
    assert np.max(np.abs(by_current.force - inv.force)) < 1e-2 * np.max(np.abs(inv.force))
    # force input reports its input as the leg force
    np.testing.assert_array_equal(by_force.force, inv.force)


def test_current_input_without_drives_is_refused():
    with pytest.raises(stewart.ParameterError, match="screw_lead"):
        stewart.Platform().simulate([0, 1e-3], np.zeros((2, 6)), input="current")
