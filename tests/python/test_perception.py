"""stewart.perception against the transfer functions of Telban & Cardullo (2005), written here as
polynomials from the published time constants and run through scipy.signal (its own state-space
realisation and matrix exponential): steps and sinusoids to 1e-9; the canal's step response
against its closed form with the 5.73 s and 80 s constants; the resting state; the refusals."""
import math

import numpy as np
import pytest
from scipy import signal

import stewart
from stewart.vestibular import Channel, VestibularModel

G = 9.81


def canal_tf():
    """w_hat/w = 80*5.73 s^2 (0.06 s + 1) / ((80 s + 1)(5.73 s + 1)(0.005 s + 1))."""
    num = np.polymul([80.0 * 5.73, 0.0, 0.0], [0.06, 1.0])
    den = np.polymul(np.polymul([80.0, 1.0], [5.73, 1.0]), [0.005, 1.0])
    return num, den


def otolith_tf():
    """f_hat/f = 0.4 (10 s + 1) / ((5 s + 1)(0.016 s + 1))."""
    return np.polymul([0.4], [10.0, 1.0]), np.polymul([5.0, 1.0], [0.016, 1.0])


def held(tf, t, u):
    """The continuous system's response to u held constant over each sample, from rest."""
    _, y, _ = signal.lsim(tf, u, t, interp=False)
    return y


def run(t, f=None, w=None, **kw):
    n = t.size
    f = np.zeros((n, 3)) if f is None else f
    w = np.zeros((n, 3)) if w is None else w
    return stewart.perception(t, f, w, **kw)


@pytest.mark.parametrize("dt", [0.01, 0.001])
def test_steps_match_the_transfer_functions(dt):
    """A step after the first sample (the filters start at rest), on every axis of each organ:
    the perceived signals equal scipy's response of the published transfer functions."""
    t = np.arange(0, 30, dt)
    step = np.where(np.arange(t.size) >= 1, 1.0, 0.0)
    f = np.outer(step, [1.0, -2.0, 0.5])
    w = np.outer(step, [0.3, 1.0, -0.7])
    felt = run(t, f, w)
    for axis in range(3):
        for tf, u, y in ((canal_tf(), w[:, axis], felt.angular_velocity[:, axis]),
                         (otolith_tf(), f[:, axis], felt.specific_force[:, axis])):
            expected = held(tf, t, u)
            assert np.max(np.abs(y - expected)) <= 1e-9 * np.max(np.abs(expected))


@pytest.mark.parametrize("hz", [0.05, 0.5, 3.0])
def test_sinusoids_match_the_transfer_functions(hz):
    t = np.arange(0, 40, 0.005)
    u = np.sin(2 * np.pi * hz * t)  # zero at t = 0: the filters start at rest
    felt = run(t, np.outer(u, [1, 0, 0]), np.outer(u, [0, 0, 1]))
    for tf, y in ((canal_tf(), felt.angular_velocity[:, 2]),
                  (otolith_tf(), felt.specific_force[:, 0])):
        expected = held(tf, t, u)
        assert np.max(np.abs(y - expected)) <= 1e-9 * np.max(np.abs(expected))
    assert np.all(felt.angular_velocity[:, :2] == 0) and np.all(felt.specific_force[:, 1:] == 0)


def test_steady_start_is_the_state_space_equilibrium_of_the_first_sample():
    """A motion that starts away from zero (an offset sinusoid): the default steady start equals
    scipy's simulation of the transfer function started at its state-space equilibrium for the
    first input, x0 = -A^-1 B u[0] (scipy's own realisation)."""
    t = np.arange(0, 20, 0.01)
    u = 2.0 + np.sin(2 * np.pi * 0.4 * t + 0.7)
    felt = run(t, np.outer(u, [0, 0, 1]), np.outer(u, [0, 1, 0]))
    for tf, y in ((canal_tf(), felt.angular_velocity[:, 1]),
                  (otolith_tf(), felt.specific_force[:, 2])):
        a, b, c, d = signal.tf2ss(*tf)
        x0 = -np.linalg.solve(a, b[:, 0] * u[0])
        _, expected, _ = signal.lsim((a, b, c, d), u, t, X0=x0, interp=False)
        assert np.max(np.abs(y - expected)) <= 1e-9 * np.max(np.abs(expected))


def test_sinusoid_amplitude_is_the_frequency_response():
    """In steady state a sinusoid comes out scaled by |H(j omega)| (scipy.signal.freqs) to the
    half-sample delay of the hold."""
    dt, hz = 0.0005, 0.2
    t = np.arange(0, 600, dt)
    u = np.sin(2 * np.pi * hz * t)
    felt = run(t, np.outer(u, [0, 1, 0]), np.outer(u, [1, 0, 0]))
    last = t > 400
    for tf, y in ((canal_tf(), felt.angular_velocity[:, 0]),
                  (otolith_tf(), felt.specific_force[:, 1])):
        _, h = signal.freqs(*tf, worN=[2 * np.pi * hz])
        assert np.max(np.abs(y[last])) == pytest.approx(abs(h[0]), rel=2e-3)


def test_canal_step_decays_with_the_cupula_and_reverses_with_adaptation():
    """The canal's response to a velocity step: after the lead/lag transient (tens of ms) it is
    tau_a/(tau_a - tau_L) exp(-t/tau_L) - tau_L/(tau_a - tau_L) exp(-t/tau_a) with tau_L = 5.73 s
    and tau_a = 80 s: it decays with the cupula's 5.73 s and reverses at
    t = ln(tau_a/tau_L) tau_a tau_L / (tau_a - tau_L) = 16.3 s (the post-rotatory reversal)."""
    tau_l, tau_a = 5.73, 80.0
    t = np.arange(0, 60, 0.001)
    w = np.zeros((t.size, 3))
    w[:, 2] = 1.0
    y = run(t, w=w, initial="rest").angular_velocity[:, 2]
    closed = (tau_a * np.exp(-t / tau_l) - tau_l * np.exp(-t / tau_a)) / (tau_a - tau_l)
    late = t > 0.5
    # the lead 0.06 s and lag 0.005 s add about (0.06 - 0.005) d/dt of the slow part: < 1e-2
    assert np.max(np.abs(y[late] - closed[late])) < 1e-2
    reversal = math.log(tau_a / tau_l) * tau_a * tau_l / (tau_a - tau_l)
    crossing = t[np.flatnonzero((y[:-1] > 0) & (y[1:] <= 0))[0]]
    assert crossing == pytest.approx(reversal, abs=0.1)
    # decay: from t = 1 s to t = 1 + 5.73 s the (mostly cupula) response falls by about 1/e
    i1, i2 = np.searchsorted(t, [1.0, 1.0 + tau_l])
    assert y[i2] / y[i1] == pytest.approx(closed[i2] / closed[i1], abs=5e-3)


def test_resting_person_feels_gravity_scaled_by_the_otolith_gain_and_no_rotation():
    """Steady start: a constant specific force is felt as K f from the first sample (the DC gain
    of the otolith's transfer function, 0.4), a constant rotation not at all (two zeros at
    s = 0)."""
    t = np.arange(0, 20, 0.01)
    f = np.tile([0.0, 0.0, G], (t.size, 1))
    w = np.tile([0.1, -0.2, 0.3], (t.size, 1))
    felt = run(t, f, w)
    num, den = otolith_tf()
    dc = np.polyval(num, 0) / np.polyval(den, 0)
    assert np.max(np.abs(felt.specific_force - dc * f)) < 1e-12 * G
    assert np.max(np.abs(felt.angular_velocity)) < 1e-12
    # from rest instead, gravity is a step: the otolith rises through its lead to K g
    rest = run(t, f, w, initial="rest").specific_force[:, 2]
    assert rest[0] == 0 and abs(rest[-1] - dc * G) < 0.2 * G


def test_a_model_of_ones_own():
    """A VestibularModel made here (a first-order lag on both organs) is applied as given."""
    lag = Channel(gain=1.0, differentiators=0, leads=(), lags=(0.5,))
    model = VestibularModel("lag", lag, lag, "here")
    t = np.arange(0, 5, 0.01)
    u = np.outer(np.where(np.arange(t.size) >= 1, 1.0, 0.0), [1, 1, 1])
    felt = run(t, u, u, model=model)
    expected = held(([1.0], [0.5, 1.0]), t, u[:, 0])
    assert np.max(np.abs(felt.specific_force[:, 1] - expected)) < 1e-12
    assert np.max(np.abs(felt.angular_velocity[:, 2] - expected)) < 1e-12


@pytest.mark.parametrize("change, message", [
    (dict(t=np.array([0.0, 0.01, 0.03])), "not uniformly spaced"),
    (dict(t=np.array([0.0, 0.02, 0.01])), "does not increase"),
    (dict(t=np.array([0.0])), "at least 2"),
    (dict(specific_force=np.zeros((3, 2))), "must be (3, 3)"),
    (dict(angular_velocity=np.array([[0, 0, 0], [0, np.nan, 0], [0, 0, 0]])), "not finite"),
    (dict(model="young"), "model = 'young'"),
    (dict(initial="zero"), "initial = 'zero'"),
])
def test_refusals_name_the_argument(change, message):
    args = dict(t=np.array([0.0, 0.01, 0.02]), specific_force=np.zeros((3, 3)),
                angular_velocity=np.zeros((3, 3)))
    options = {k: change.pop(k) for k in ("model", "initial") if k in change}
    args.update(change)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        stewart.perception(**args, **options)


@pytest.mark.parametrize("kwargs, message", [
    (dict(gain=1.0, differentiators=0, leads=(), lags=(1.0, 1.0)), "repeat"),
    (dict(gain=1.0, differentiators=2, leads=(), lags=(1.0,)), "proper"),
    (dict(gain=1.0, differentiators=0, leads=(), lags=(-1.0,)), "positive"),
])
def test_channels_refuse_what_has_no_modal_form(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Channel(**kwargs)
