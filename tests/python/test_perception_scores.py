"""stewart.cueing_scores against signals whose scores are known by construction: a copy shifted by
a whole or a fractional number of samples (the delay is the shift, the correlation at it 1), a
scaled and offset copy (correlation 1, the RMSE in closed form), independent white noise
(correlation within the 4-sigma band of 0), a flat channel and a shift past the search bound."""
import math

import numpy as np
import pytest

import stewart
from stewart.scores import _lagged_correlations

DT = 0.01


def smooth_noise(n, seed):
    """A seeded random signal with its energy below ~2 Hz (moving average of white noise)."""
    rng = np.random.default_rng(seed)
    return np.convolve(rng.standard_normal(n + 60), np.ones(30) / 30, mode="valid")[:n]


@pytest.mark.parametrize("shift", [0, 7, -12, 40])
def test_a_copy_shifted_by_whole_samples(shift):
    n = 3000
    x = smooth_noise(n + 100, seed=3)
    t = np.arange(n) * DT
    vehicle = x[50:50 + n]
    platform = x[50 - shift:50 - shift + n]  # platform[k + shift] = vehicle[k]: late by shift
    s = stewart.cueing_scores(t, vehicle, platform)
    assert s.channels == ("1",)
    assert s.peak_correlation[0] == pytest.approx(1.0, abs=1e-12)
    assert abs(s.delay[0] - shift * DT) < 0.05 * DT
    assert s.notes == ("",)
    # the zero-lag correlation is Pearson's coefficient (numpy's), below 1 when shifted
    assert s.correlation[0] == pytest.approx(np.corrcoef(vehicle, platform)[0, 1], abs=1e-12)
    assert (s.correlation[0] < 1 - 1e-3) == (shift != 0)


def test_lagged_correlations_are_pearson_on_the_overlap():
    """The FFT-and-end-sums correlations against numpy's corrcoef of the overlapping samples,
    for signals with large means and different scales."""
    v = 100.0 + smooth_noise(2000, seed=1)
    p = -3e-6 * smooth_noise(2000, seed=2) + 7.0
    lags = np.arange(-40, 41)
    c = _lagged_correlations(v, p, lags)
    n = v.size
    for lag, value in zip(lags, c):
        a = v[max(0, -lag):n - max(0, lag)]
        b = p[max(0, lag):n - max(0, -lag)]
        assert value == pytest.approx(np.corrcoef(a, b)[0, 1], abs=1e-12)


@pytest.mark.parametrize("delay", [0.123, 0.0049, -0.2567])
def test_a_copy_shifted_between_samples(delay):
    """Two sines evaluated at t - delay: the parabola through the correlation's samples finds the
    delay to a small fraction of a sample."""
    t = np.arange(0, 30, DT)

    def motion(time):
        return np.sin(2 * np.pi * 0.3 * time) + 0.5 * np.sin(2 * np.pi * 0.71 * time + 1.0)

    s = stewart.cueing_scores(t, motion(t), motion(t - delay))
    assert abs(s.delay[0] - delay) < 0.05 * DT
    assert s.peak_correlation[0] > 1 - 1e-3


def test_a_scaled_and_offset_copy():
    """p = a v + b with v = A sin over whole periods: correlation 1, delay 0, and
    RMSE = sqrt((a - 1)^2 A^2 / 2 + b^2)."""
    amplitude, a, b = 2.0, 0.6, 0.3
    t = np.arange(0, 20, DT)  # 10 periods of 0.5 Hz, end excluded
    v = amplitude * np.sin(2 * np.pi * 0.5 * t)
    s = stewart.cueing_scores(t, np.column_stack([v, -v]), np.column_stack([a * v + b, -a * v + b]))
    closed = math.sqrt((a - 1) ** 2 * amplitude ** 2 / 2 + b ** 2)
    assert s.rmse == pytest.approx([closed, closed], rel=1e-12)
    assert s.correlation == pytest.approx([1.0, 1.0], abs=1e-12)
    assert s.delay == pytest.approx([0.0, 0.0], abs=1e-12)
    # an inverted copy is perfectly anti-correlated
    assert stewart.cueing_scores(t, v, -v).correlation[0] == pytest.approx(-1.0, abs=1e-12)


def test_independent_white_noise_is_uncorrelated():
    n = 20000
    rng = np.random.default_rng(11)
    v, p = rng.standard_normal((2, n))
    t = np.arange(n) * DT
    s = stewart.cueing_scores(t, v, p, max_delay=0.5)
    band = 4 / math.sqrt(n)
    assert abs(s.correlation[0]) < band
    assert abs(s.peak_correlation[0]) < 2 * band  # the largest of 101 lags: still small
    assert s.rmse[0] == pytest.approx(math.sqrt(2), rel=0.03)


def test_perceived_pairs_flat_channels_and_the_search_bound():
    """Perceived inputs name their channels; a channel that does not vary has no correlation or
    delay (NaN, with a note); a shift past max_delay is reported at the bound with a note."""
    t = np.arange(0, 30, DT)
    n = t.size
    f = np.zeros((n, 3))
    f[:, 2] = 9.81
    f[:, 0] = np.sin(t)
    w = np.zeros((n, 3))
    w[:, 2] = np.sin(0.5 * t)
    vehicle = stewart.perception(t, f, w)
    later = np.roll(np.arange(n), 30)
    later[:30] = 0
    platform = stewart.Perceived(vehicle.specific_force[later], vehicle.angular_velocity[later])
    s = stewart.cueing_scores(t, vehicle, platform, max_delay=0.2)
    assert s.channels == ("f_x", "f_y", "f_z", "w_x", "w_y", "w_z")
    for j in (1, 2, 3, 4):
        assert math.isnan(s.correlation[j]) and math.isnan(s.delay[j])
        assert "not vary" in s.notes[j]
    for j in (0, 5):  # shifted by 0.3 s, searched up to 0.2 s
        assert s.delay[j] == pytest.approx(0.2) and "search bound" in s.notes[j]
    wide = stewart.cueing_scores(t, vehicle, platform, max_delay=1.0)
    assert wide.delay[[0, 5]] == pytest.approx([0.3, 0.3], abs=0.05 * DT)
    assert "channel" in s.table() and "f_x" in s.table()


@pytest.mark.parametrize("kwargs, message", [
    (dict(platform_perceived=np.zeros((5, 2))), "2 channels but vehicle_perceived has 1"),
    (dict(vehicle_perceived=np.zeros(4)), r"shape \(4,\)"),
    (dict(vehicle_perceived=np.array([0, 1, np.inf, 0, 1.0])), "not finite"),
    (dict(max_delay=0.0), "max_delay"),
    (dict(t=np.array([0, 0.1, 0.2, 0.4, 0.5])), "not uniformly spaced"),
])
def test_refusals(kwargs, message):
    args = dict(t=np.arange(5) * 0.1, vehicle_perceived=np.arange(5.0),
                platform_perceived=np.arange(5.0) ** 2)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        stewart.cueing_scores(**args)
