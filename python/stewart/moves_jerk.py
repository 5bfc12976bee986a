"""The jerk-limited time law of a move (docs/moves.md "Jerk limits"): s(t) = w(sigma(t)), a
rest-to-rest seven-segment S-curve sigma(t) (jerk +-j while speeding up, acceleration up to a,
speed up to v, and its own jerk and deceleration bounds while braking) through a cubic warp w of
the path parameter, its shape chosen by a Nelder-Mead search and its time scale in closed form,
so that along the whole path the legs' speed L' ds/dt, acceleration L' s'' + L'' s'^2 and jerk
L' s''' + 3 L'' s' s'' + L''' s'^3 stay within their limits with one of them met.

Stretching a law's time by k divides the legs' speeds by k, accelerations by k^2 and jerks by
k^3 (every term of each has the same order in d/dt), so the shortest stretch of a shape is
max(speed ratio, sqrt(acceleration ratio), cbrt(jerk ratio)) of its peaks: exact, no search.
Where the legs' lengths are affine in s (L' constant, the limit of a short move) the shortest
law is a symmetric seven-segment S-curve, so this family holds the time optimum; along curved
leg paths it is near it (docs/moves.md gives the measured gap to a lower bound).
"""
from __future__ import annotations

import functools
import math

import numpy as np

#: Evaluation points per S-curve segment when the legs' peaks of a shape are sought (both ends
#: of each segment included, where the jerk jumps): few while the shape is searched; for the
#: stretch of the shape found, enough that between two of them the legs' rates (varying along
#: s) cannot peak above them by more than about 1e-6, well inside moves.PLAN_MARGIN (with 64 a
#: long cruise missed a speed peak by 2.7e-5 of the limit).
SEARCH_POINTS = 16
PEAK_POINTS = 1024
#: Nelder-Mead iterations of the shape search, and its relative tolerance on the duration.
SEARCH_ITERATIONS = 200
#: The shape search's starting simplex sizes (in the logarithms of the ratios and in the warp's
#: coefficients), and the size of the last search from the best of those.
START_STEPS = (0.3,)
POLISH_STEP = 0.1
#: The warp's |b| + |c| stays below this (below 1 its derivative stays positive: at least 0.1).
WARP_MAX = 0.9
SEARCH_TOLERANCE = 1e-5


class SCurve:
    """A rest-to-rest S-curve from s = 0 to 1: it speeds up with jerk +-j up to acceleration a,
    cruises at speed v if the distance leaves room, and brakes with jerk +-j_brake down to
    deceleration a_brake (those of the speeding up unless given). Seven segments (jerk +j, 0,
    -j, cruise, -j_brake, 0, +j_brake) of `durations`; the state (s, s', s'') at each segment's
    start in `starts`."""

    def __init__(self, v: float, a: float, j: float, a_brake=None, j_brake=None) -> None:
        a2 = a if a_brake is None else a_brake
        j2 = j if j_brake is None else j_brake

        def distance(w):
            return _rise(w, a, j)[1] + _rise(w, a2, j2)[1]
        peak = v
        if distance(v) > 1.0:  # no cruise: the peak speed that covers the distance, bisected
            # from a bound near it (a rise to w covers at least w^2 / 2a and, by AM-GM, w^1.5 /
            # sqrt(j)), so that 64 halvings resolve it however large v is
            lo, hi = 0.0, min(v, math.sqrt(2 / (1 / a + 1 / a2)),
                              (1 / math.sqrt(j) + 1 / math.sqrt(j2)) ** (-2 / 3))
            for _ in range(64):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if distance(mid) <= 1.0 else (lo, mid)
            peak = lo
        (ramp, hold), (ramp2, hold2) = _rise(peak, a, j)[0], _rise(peak, a2, j2)[0]
        cruise = max(0.0, (1.0 - distance(peak)) / peak)
        self.durations = np.array([ramp, hold, ramp, cruise, ramp2, hold2, ramp2])
        self.jerks = np.array([j, 0.0, -j, 0.0, -j2, 0.0, j2])
        self.times = np.concatenate([[0.0], np.cumsum(self.durations)])
        self.duration = float(self.times[-1])
        state = (0.0, 0.0, 0.0)
        starts = [state]
        for d, jk in zip((ramp, hold, ramp, cruise, ramp2, hold2, ramp2),
                         (j, 0.0, -j, 0.0, -j2, 0.0, j2)):
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

    def peak_samples(self, points: int = PEAK_POINTS):
        """s, s', s'', s''' on `points` points of every segment, its ends included (the jerk
        from inside the segment)."""
        unit, k = _unit_grid(points)
        return self.in_segment(k, (unit * self.durations[:, None]).ravel())


@functools.lru_cache(maxsize=4)
def _unit_grid(points):
    """`points` fractions of a segment from 0 to 1 as a row, and the segment of each of the
    7 x points values of a grid of every segment, flattened (read-only: shared by every call)."""
    unit, segment = np.linspace(0.0, 1.0, points)[None, :], np.repeat(np.arange(7), points)
    unit.setflags(write=False)
    segment.setflags(write=False)
    return unit, segment


def _rise(w, a, j):
    """From rest to speed w (or from w to rest) with jerk j and acceleration up to a: the ramp
    and hold times of the acceleration (a trapezoid; a triangle when w < a^2 / j), and the
    distance covered: w times half the time."""
    if w >= a * a / j:
        ramp, hold = a / j, w / a - a / j
    else:
        ramp, hold = math.sqrt(w / j), 0.0
    return (ramp, hold), w * (ramp + hold / 2)


def _advance(state, jerk, d):
    s, v, a = state
    return (s + d * (v + d * (a / 2 + d * jerk / 6)), v + d * (a + d * jerk / 2), a + d * jerk)


class LegPeaks:
    """The legs' L', L'', L''' (and the Cartesian speeds per unit ds/dt) on a grid of s, and
    the limits they are held to (inf: none): the stretch a time law of s needs. The columns
    are kept divided by their limits, the speed ones by their largest (|L'| ds/dt is largest
    where |L'| is), so a stretch is a few products."""

    def __init__(self, s, Lp, Lpp, Lppp, speed_per_rate, speed, accel, jerk) -> None:
        self.s = s
        self.columns = np.hstack([Lp, Lpp, Lppp, speed_per_rate])
        self.speed, self.accel, self.jerk = speed, accel, jerk
        self.uniform = np.allclose(np.diff(s), 1.0 / (s.size - 1), rtol=1e-12, atol=0)
        with np.errstate(divide="ignore"):
            inv = [np.where(np.isfinite(x), 1.0 / x, 0.0) for x in (speed, accel, jerk)]
        speeds = np.max(np.abs(np.hstack([Lp, speed_per_rate])) * inv[0], axis=1)
        table = np.hstack([speeds[:, None], Lp * inv[1], Lpp * inv[1], Lp * inv[2],
                           3 * Lpp * inv[2], Lppp * inv[2]])
        self.table, self.table_steps = table, np.diff(table, axis=0)

    def stretch(self, curve, points: int = PEAK_POINTS) -> float:
        """The smallest k with the law s(t / k) within every limit, from its peaks on `points`
        points of each segment (the columns linear between grid nodes)."""
        s, v, a, j = curve.peak_samples(points)
        n = self.s.size - 1
        if self.uniform:
            at = np.clip(s, 0.0, 1.0) * n
            i = np.minimum(at.astype(np.intp), n - 1)
            w = (at - i)[:, None]
        else:
            i = np.clip(np.searchsorted(self.s, s, side="right") - 1, 0, n - 1)
            w = ((s - self.s[i]) / (self.s[i + 1] - self.s[i]))[:, None]
        c = self.table[i] + self.table_steps[i] * w
        v, a, j = v[:, None], a[:, None], j[:, None]
        speed = np.max(c[:, 0] * v[:, 0])
        accel = np.max(np.abs(c[:, 1:7] * a + c[:, 7:13] * (v * v)))
        jerk = np.max(np.abs(c[:, 13:19] * j + c[:, 19:25] * (v * a) + c[:, 25:31] * v ** 3))
        return max(speed, math.sqrt(accel), jerk ** (1 / 3))


class WarpedLaw:
    """The time law s = w(sigma(t)): an S-curve sigma(t) from 0 to 1 through the warp
    w(x) = x + b x (1 - x) + c x (1 - x) (2 x - 1), a cubic from 0 to 1 that lets the path go
    faster where the legs allow it (b > 0: faster at the start); |b| + |c| < 1 keeps w' > 0.
    Its derivatives are exact by the chain rule."""

    def __init__(self, curve: SCurve, b: float = 0.0, c: float = 0.0) -> None:
        if abs(b) + abs(c) >= WARP_MAX:
            raise ValueError(f"the warp's |b| + |c| = {abs(b) + abs(c):.3g} must be below "
                             f"{WARP_MAX}: the path parameter would not increase")
        self.curve, self.b, self.c, self.duration = curve, b, c, curve.duration

    def _through(self, x, xv, xa, xj):
        b, c = self.b, self.c
        u = x * (1 - x)
        s = x + b * u + c * u * (2 * x - 1)
        d1 = 1 + b * (1 - 2 * x) + c * (6 * u - 1)
        d2 = -2 * b + c * (6 - 12 * x)
        d3 = -12 * c
        return (s, d1 * xv, d2 * xv * xv + d1 * xa,
                d3 * xv ** 3 + 3 * d2 * xv * xa + d1 * xj)

    def at(self, tau):
        """s, s', s'', s''' at times tau (clipped to [0, duration])."""
        return self._through(*self.curve.at(tau))

    def peak_samples(self, points: int = PEAK_POINTS):
        return self._through(*self.curve.peak_samples(points))


def jerk_limited_law(peaks: LegPeaks):
    """The warped S-curve whose stretched duration is the shortest found, and its stretch k
    (the law is s(t / k), of duration k law.duration). The shape has six free ratios: the
    cruise speed, the acceleration and braking bounds and the braking jerk (to the jerk of
    speeding up), since the speeding up and the braking happen on different parts of the path
    where the legs allow different bounds; and the warp's b and c, which let the cruise and the
    ramps go faster where the legs' L' is smaller."""
    columns = np.abs(peaks.columns)
    top = np.max(columns[:, :6], axis=0)
    moving = top > 0
    # A shape of the right order: each bound the legs' own limit over the largest L'.
    speed_top = np.max(np.hstack([columns[:, :6], columns[:, 18:]]), axis=0)
    with np.errstate(divide="ignore"):
        v0 = float(np.min(peaks.speed / speed_top))
    a0 = float(np.min(peaks.accel[moving] / top[moving], initial=math.inf))
    j0 = float(np.min(peaks.jerk[moving] / top[moving], initial=math.inf))
    if not math.isfinite(a0):  # no leg's length changes (a move below its rounding): any shape
        a0 = 1.0
    if not math.isfinite(v0):  # no speed limit: a bound the accelerations never let it reach
        v0 = 10 * math.sqrt(a0)
    if not math.isfinite(j0):  # no moving leg has a jerk limit: ramps short beside the move's
        j0 = 100 * a0 ** 1.5

    def law(x):
        curve = SCurve(v0 * math.exp(x[0]), a0 * math.exp(x[1]), j0, a0 * math.exp(x[2]),
                       j0 * math.exp(x[3]))
        return WarpedLaw(curve, x[4], x[5])

    def duration(x):
        if abs(x[4]) + abs(x[5]) >= WARP_MAX:
            return math.inf
        shape = law(x)
        return peaks.stretch(shape, SEARCH_POINTS) * shape.duration

    # The duration is the largest of several ratios (a minimax): a simplex can stall on a
    # ridge where two limits trade places, so the best of the starts is searched again from a
    # small simplex.
    best = min((_nelder_mead(duration, np.zeros(6), step) for step in START_STEPS),
               key=duration)
    shape = law(_nelder_mead(duration, best, POLISH_STEP))
    return shape, peaks.stretch(shape)


def _nelder_mead(f, x0, step):
    """A minimum of f near x0 by the Nelder-Mead simplex."""
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


def sample_law(curve, stretch: float, sample_time: float):
    """Sample times (the duration rounded up to whole samples by stretching the law further,
    which keeps every limit) and s, ds/dt, d2s/dt2, d3s/dt3 at them."""
    duration = stretch * curve.duration
    count = max(1, math.ceil(duration / sample_time - 1e-9))
    if count > 100_000_000:
        raise ValueError(f"the move takes {duration:.6g} s: {count:.6g} samples of {sample_time} s "
                         "are too many; give a larger sample_time")
    k = count * sample_time / curve.duration
    t = np.arange(count + 1) * sample_time
    s, v, a, j = curve.at(t / k)
    s, v = np.clip(s, 0.0, 1.0), np.maximum(v, 0.0)
    s[0], v[0], a[0], s[-1], v[-1], a[-1] = 0.0, 0.0, 0.0, 1.0, 0.0, 0.0
    return t, s, v / k, a / k ** 2, j / k ** 3
