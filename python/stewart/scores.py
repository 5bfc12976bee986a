"""How alike two motions feel: RMSE, normalised correlation and delay per channel of the perceived
signals of a vehicle and of the platform that imitates it (docs/perception.md).

For each channel, with v the vehicle's perceived signal and p the platform's over N samples:

* rmse = sqrt(mean((p - v)^2)), in the channel's unit;
* correlation = the zero-lag normalised cross-correlation, sum((v - mean v)(p - mean p)) /
  sqrt(sum (v - mean v)^2 sum (p - mean p)^2), in [-1, 1]: 1 when p is v scaled and offset;
* delay = the lag [s] at which the normalised cross-correlation c(l) of v[k] and p[k + l] (the
  same formula on the overlapping samples) is largest, l within +-max_delay, refined between
  samples by the parabola through c at the best lag and its two neighbours; positive when the
  platform's cue comes late. peak_correlation is c at the best sampled lag.

A channel along which v or p does not vary (by more than FLAT_TOLERANCE of its magnitude, plus
FLAT_TOLERANCE in SI units) has no correlation or delay: they are NaN and notes says why.

>>> import numpy as np, stewart
>>> t = np.arange(0, 20, 0.01)
>>> v = np.sin(t)[:, None]
>>> s = stewart.cueing_scores(t, v, 0.5 * np.sin(t - 0.1)[:, None])
>>> round(float(s.delay[0]), 3), round(float(s.peak_correlation[0]), 6)
(0.1, 1.0)
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import numpy as np

from .arrays import floats, times
from .vestibular import Perceived, _time_step

#: The channels of a Perceived pair: specific force then angular velocity, x, y, z.
PERCEIVED_CHANNELS = ("f_x", "f_y", "f_z", "w_x", "w_y", "w_z")
#: A channel varying by less than this (relative to its magnitude, plus this in SI units) is flat.
FLAT_TOLERANCE = 1e-9
#: The default bound of the delay search [s].
MAX_DELAY = 1.0


@dataclass(frozen=True)
class CueingScores:
    """Per channel (the order of channels): rmse, correlation [-1, 1], delay [s], peak_correlation;
    notes[i] is "" or why channel i has no correlation or delay (NaN) or why its delay is a
    bound."""
    channels: Tuple[str, ...]
    rmse: np.ndarray
    correlation: np.ndarray
    delay: np.ndarray
    peak_correlation: np.ndarray
    notes: Tuple[str, ...]

    def table(self) -> str:
        """The scores as a text table, one channel a line."""
        lines = [f"{'channel':8} {'rmse':>11} {'correlation':>11} {'delay [s]':>10}  note"]
        for i, name in enumerate(self.channels):
            lines.append(f"{name:8} {self.rmse[i]:11.4g} {self.correlation[i]:11.4f} "
                         f"{self.delay[i]:10.4f}  {self.notes[i]}".rstrip())
        return "\n".join(lines)


def cueing_scores(t, vehicle_perceived, platform_perceived, max_delay: float = MAX_DELAY
                  ) -> CueingScores:
    """The scores of platform_perceived against vehicle_perceived, sampled at t (N,) [s],
    uniformly spaced: each a Perceived (as stewart.perception returns; channels
    PERCEIVED_CHANNELS) or an (N, k) or (N,) array (channels "1".."k"). max_delay [s] > 0 bounds
    the delay search (at most half the record). ValueError names a bad argument."""
    t = times("t", t, None)
    if t.shape[0] < 3:
        raise ValueError(f"t has {t.shape[0]} sample(s): give at least 3")
    dt = _time_step(t)
    v, names = _channels("vehicle_perceived", vehicle_perceived, t.shape[0])
    p, _ = _channels("platform_perceived", platform_perceived, t.shape[0])
    if p.shape != v.shape:
        raise ValueError(f"platform_perceived has {p.shape[1]} channels but vehicle_perceived "
                         f"has {v.shape[1]}")
    max_delay = float(max_delay)
    if not (np.isfinite(max_delay) and max_delay > 0):
        raise ValueError(f"max_delay = {max_delay!r}: a positive number of seconds")
    max_lag = max(1, min(int(round(max_delay / dt)), t.shape[0] // 2))
    k = v.shape[1]
    rmse = np.sqrt(np.mean((p - v) ** 2, axis=0))
    correlation, delay, peak = np.full(k, np.nan), np.full(k, np.nan), np.full(k, np.nan)
    notes = []
    for j in range(k):
        flat = [who for who, x in (("vehicle's", v[:, j]), ("platform's", p[:, j])) if _flat(x)]
        if flat:
            what = "signals do not vary" if len(flat) == 2 else "signal does not vary"
            notes.append(f"the {' and the '.join(flat)} {what}: no correlation or delay")
            continue
        correlation[j] = _pearson(v[:, j], p[:, j])
        delay[j], peak[j], at_edge = _delay(v[:, j], p[:, j], max_lag, dt)
        notes.append(f"delay at the search bound ({max_lag * dt:g} s): it may be longer; "
                     "raise max_delay" if at_edge else "")
    return CueingScores(tuple(names), rmse, correlation, delay, peak, tuple(notes))


def _delay(v: np.ndarray, p: np.ndarray, max_lag: int, dt: float) -> Tuple[float, float, bool]:
    """(delay [s], c at the best lag, whether the best lag is the bound)."""
    lags = np.arange(-max_lag, max_lag + 1)
    c = _lagged_correlations(v, p, lags)
    best = int(np.argmax(c))
    if not np.isfinite(c[best]):
        return float("nan"), float("nan"), False
    at_edge = best in (0, lags.size - 1)
    shift = 0.0
    if not at_edge and np.isfinite(c[best - 1]) and np.isfinite(c[best + 1]):
        curvature = c[best - 1] - 2.0 * c[best] + c[best + 1]
        if curvature < 0:  # a maximum: the parabola's vertex, within half a sample
            shift = float(np.clip(0.5 * (c[best - 1] - c[best + 1]) / curvature, -0.5, 0.5))
    return (float(lags[best]) + shift) * dt, float(c[best]), at_edge


def _lagged_correlations(v: np.ndarray, p: np.ndarray, lags: np.ndarray) -> np.ndarray:
    """Pearson's coefficient of v[k] and p[k + lag] over the overlapping samples, per lag (-inf
    where an overlap does not vary). Both are centred first (no digits lost to large means); the
    sums of products come from one FFT, the sums over an overlap from the whole record less the
    at most max|lag| samples it leaves out (no long running sums)."""
    n = v.shape[0]
    v = v - v.mean()
    p = p - p.mean()
    size = 1 << (2 * n - 1).bit_length()
    cross = np.fft.irfft(np.conj(np.fft.rfft(v, size)) * np.fft.rfft(p, size), size)[lags % size]
    out = int(np.max(np.abs(lags)))

    def ends(x):  # sums of x and x^2 over the first and the last j samples, j = 0..out
        first = [np.concatenate([[0.0], np.cumsum(y[:out])]) for y in (x, x * x)]
        last = [np.concatenate([[0.0], np.cumsum(y[::-1][:out])]) for y in (x, x * x)]
        return first, last, (x.sum(), np.dot(x, x))

    (v_first, v_last, v_all), (p_first, p_last, p_all) = ends(v), ends(p)
    j = np.abs(lags)
    late = lags >= 0  # p later than v: v loses its last j samples, p its first j
    sums = []
    for k in range(2):
        sums.append(v_all[k] - np.where(late, v_last[k][j], v_first[k][j]))
        sums.append(p_all[k] - np.where(late, p_first[k][j], p_last[k][j]))
    sa, sb, saa, sbb = sums[0], sums[1], sums[2], sums[3]
    m = n - j
    var_a = saa - sa * sa / m
    var_b = sbb - sb * sb / m
    c = np.full(lags.shape, -np.inf)
    # below 1e-15 of the whole record's sum of squares: what rounding leaves of no variation
    ok = (var_a > 1e-15 * v_all[1]) & (var_b > 1e-15 * p_all[1])
    c[ok] = (cross[ok] - sa[ok] * sb[ok] / m[ok]) / np.sqrt(var_a[ok] * var_b[ok])
    return c


def _pearson(a: np.ndarray, b: np.ndarray) -> float:
    a = a - a.mean()
    b = b - b.mean()
    norm = np.sqrt(np.dot(a, a) * np.dot(b, b))
    return float(np.dot(a, b) / norm) if norm > 0 else float("nan")


def _flat(x: np.ndarray) -> bool:
    return float(np.ptp(x)) <= FLAT_TOLERANCE * (float(np.max(np.abs(x))) + 1.0)


def _channels(name: str, value, n: int):
    if isinstance(value, Perceived) or (isinstance(value, tuple) and len(value) == 2):
        parts = [floats(f"{name}[{i}]", part) for i, part in enumerate(value)]
        if any(part.shape != (n, 3) for part in parts):
            raise ValueError(f"{name} has shapes {[part.shape for part in parts]}: a Perceived "
                             f"pair of ({n}, 3) arrays")
        a, names = np.hstack(parts), list(PERCEIVED_CHANNELS)
    else:
        a = floats(name, value)
        if a.ndim not in (1, 2) or a.shape[0] != n:
            raise ValueError(f"{name} has shape {a.shape}: it must be ({n},) or ({n}, k), one "
                             "row per time of t")
        a = a.reshape(n, -1)
        names = [str(i + 1) for i in range(a.shape[1])]
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        i, j = bad[0]
        raise ValueError(f"{name}: channel {names[j]} at row {i} is {float(a[i, j])!r}, not finite")
    return a, names
