"""The jerk-limited time law of a move (docs/moves.md "Jerk"): a rest-to-rest seven-segment
S-curve s(t) of the path parameter (jerk +-j, acceleration up to a, speed up to v), its shape
(v and a for a given j) chosen by a Nelder-Mead search and its time scale in closed form, so that
along the whole path the legs' speed L' ds/dt, acceleration L' s'' + L'' s'^2 and jerk
L' s''' + 3 L'' s' s'' + L''' s'^3 stay within their limits with one of them met.

Stretching a law's time by k divides the legs' speeds by k, accelerations by k^2 and jerks by
k^3 (every term of each has the same order in d/dt), so the shortest stretch of a shape is
max(speed ratio, sqrt(acceleration ratio), cbrt(jerk ratio)) of its peaks: exact, no search.
Where the legs' lengths are affine in s (L' constant, the limit of a short move) the shortest
law is a seven-segment S-curve, so this family holds the time optimum; along curved leg paths it
is near it (docs/moves.md gives the measured gap to a lower bound).
"""
from __future__ import annotations

import math

import numpy as np

#: Evaluation points per S-curve segment when the legs' peaks of a shape are sought (both ends
#: of each segment included, where the jerk jumps).
PEAK_POINTS = 48
#: Nelder-Mead iterations of the shape search, and its relative tolerance on the duration.
SEARCH_ITERATIONS = 120
SEARCH_TOLERANCE = 1e-6


class SCurve:
    """A rest-to-rest S-curve from s = 0 to 1 with speed bound v, acceleration bound a and jerk
    j: seven segments (jerk +j, 0, -j, cruise, -j, 0, +j), durations in `durations`, the state
    (s, s', s'') at each segment's start in `starts`."""

    def __init__(self, v: float, a: float, j: float) -> None:
        def accel_time(peak):  # from rest to the speed `peak` and the ramp time
            return (peak / a + a / j, a / j) if peak >= a * a / j else \
                (2 * math.sqrt(peak / j), math.sqrt(peak / j))
        peak = v
        if v * accel_time(v)[0] > 1.0:  # no cruise: the peak speed covers the distance
            q = a * a / j
            peak = 0.5 * (-q + math.sqrt(q * q + 4 * a))
            if peak < q:
                peak = (j / 4) ** (1 / 3)
        total, ramp = accel_time(peak)
        hold = total - 2 * ramp
        cruise = max(0.0, 1.0 / peak - total)
        self.durations = np.array([ramp, hold, ramp, cruise, ramp, hold, ramp])
        self.jerks = np.array([j, 0.0, -j, 0.0, -j, 0.0, j])
        self.times = np.concatenate([[0.0], np.cumsum(self.durations)])
        self.duration = float(self.times[-1])
        state = np.zeros(3)
        starts = [state]
        for d, jk in zip(self.durations, self.jerks):
            state = _advance(state, jk, d)
            starts.append(state)
        self.starts = np.array(starts)

    def at(self, tau: np.ndarray):
        """s, s', s'', s''' at times tau (clipped to [0, duration])."""
        tau = np.clip(tau, 0.0, self.duration)
        k = np.clip(np.searchsorted(self.times, tau, side="right") - 1, 0, 6)
        return self.in_segment(k, tau - self.times[k])

    def in_segment(self, k, d):
        s0, v0, a0 = self.starts[k, 0], self.starts[k, 1], self.starts[k, 2]
        jk = self.jerks[k]
        return (s0 + d * (v0 + d * (a0 / 2 + d * jk / 6)), v0 + d * (a0 + d * jk / 2),
                a0 + d * jk, jk + 0 * d)

    def peak_samples(self):
        """s, s', s'', s''' on PEAK_POINTS points of every segment, its ends included (the
        jerk from inside the segment)."""
        d = np.linspace(0.0, 1.0, PEAK_POINTS)[None, :] * self.durations[:, None]
        k = np.broadcast_to(np.arange(7)[:, None], d.shape)
        return tuple(x.ravel() for x in self.in_segment(k, d))


def _advance(state, jerk, d):
    s, v, a = state
    return np.array([s + d * (v + d * (a / 2 + d * jerk / 6)), v + d * (a + d * jerk / 2),
                     a + d * jerk])


class LegPeaks:
    """The legs' L', L'', L''' (and the Cartesian speeds per unit ds/dt) on a grid of s, and
    the limits they are held to (inf: none): the stretch a time law of s needs."""

    def __init__(self, s, Lp, Lpp, Lppp, speed_per_rate, speed, accel, jerk) -> None:
        self.s = s
        self.columns = np.hstack([Lp, Lpp, Lppp, speed_per_rate])
        self.speed, self.accel, self.jerk = speed, accel, jerk

    def stretch(self, curve: SCurve) -> float:
        """The smallest k with the law s(t / k) within every limit, from its peaks."""
        s, v, a, j = curve.peak_samples()
        i = np.clip(np.searchsorted(self.s, s, side="right") - 1, 0, self.s.size - 2)
        w = ((s - self.s[i]) / (self.s[i + 1] - self.s[i]))[:, None]
        c = self.columns[i] * (1 - w) + self.columns[i + 1] * w
        Lp, Lpp, Lppp, cart = c[:, :6], c[:, 6:12], c[:, 12:18], c[:, 18:]
        v, a, j = v[:, None], a[:, None], j[:, None]
        speed = np.max(np.abs(np.hstack([Lp, cart]) * v) / self.speed)
        accel = np.max(np.abs(Lp * a + Lpp * v * v) / self.accel)
        jerk = np.max(np.abs(Lp * j + 3 * Lpp * v * a + Lppp * v ** 3) / self.jerk)
        return max(speed, math.sqrt(accel), jerk ** (1 / 3))


def jerk_limited_law(peaks: LegPeaks):
    """The S-curve whose stretched duration is the shortest found, and its stretch k (the law
    is s(t / k), of duration k curve.duration)."""
    Lp = np.abs(peaks.columns[:, :6])
    top = np.max(Lp, axis=0)
    # A shape of the right order: each bound the legs' own limit over the largest L'.
    v0 = float(np.min(np.divide(np.append(peaks.speed[:6], np.inf), np.append(top, 1.0))))
    a0 = float(np.min(peaks.accel / top))
    j0 = float(np.min(peaks.jerk / top))
    if not math.isfinite(v0):  # no speed limit: a bound the accelerations never let it reach
        v0 = 10 * math.sqrt(a0)

    def duration(x):
        curve = SCurve(v0 * math.exp(x[0]), a0 * math.exp(x[1]), j0)
        return peaks.stretch(curve) * curve.duration

    best = _nelder_mead(duration, np.zeros(2), 0.3)
    curve = SCurve(v0 * math.exp(best[0]), a0 * math.exp(best[1]), j0)
    return curve, peaks.stretch(curve)


def _nelder_mead(f, x0, step):
    """A minimum of f near x0 by the Nelder-Mead simplex (2-D here)."""
    n = x0.size
    simplex = [x0] + [x0 + step * np.eye(n)[i] for i in range(n)]
    values = [f(x) for x in simplex]
    for _ in range(SEARCH_ITERATIONS):
        order = np.argsort(values)
        simplex = [simplex[i] for i in order]
        values = [values[i] for i in order]
        if values[-1] - values[0] <= SEARCH_TOLERANCE * values[0]:
            break
        centre = np.mean(simplex[:-1], axis=0)
        reflected = centre + (centre - simplex[-1])
        fr = f(reflected)
        if fr < values[0]:
            expanded = centre + 2 * (centre - simplex[-1])
            fe = f(expanded)
            simplex[-1], values[-1] = (expanded, fe) if fe < fr else (reflected, fr)
        elif fr < values[-2]:
            simplex[-1], values[-1] = reflected, fr
        else:
            inner = centre + 0.5 * (simplex[-1] - centre)
            fi = f(inner)
            if fi < values[-1]:
                simplex[-1], values[-1] = inner, fi
            else:
                simplex = [simplex[0] + 0.5 * (x - simplex[0]) for x in simplex]
                values = [values[0]] + [f(x) for x in simplex[1:]]
    return simplex[int(np.argmin(values))]


def sample_law(curve: SCurve, stretch: float, sample_time: float):
    """Sample times (the duration rounded up to whole samples by stretching the law further,
    which keeps every limit) and s, ds/dt, d2s/dt2, d3s/dt3 at them."""
    duration = stretch * curve.duration
    count = max(1, math.ceil(duration / sample_time - 1e-9))
    if count > 100_000_000:
        raise ValueError(f"the move takes {duration:.6g} s: {count} samples of {sample_time} s "
                         "are too many; give a larger sample_time")
    k = count * sample_time / curve.duration
    t = np.arange(count + 1) * sample_time
    s, v, a, j = curve.at(t / k)
    s, v = np.clip(s, 0.0, 1.0), np.maximum(v, 0.0)
    s[0], v[0], a[0], s[-1], v[-1], a[-1] = 0.0, 0.0, 0.0, 1.0, 0.0, 0.0
    return t, s, v / k, a / k ** 2, j / k ** 3
