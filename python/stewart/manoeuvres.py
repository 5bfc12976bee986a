"""Vehicle manoeuvres shipped with the package as data (manoeuvres/README.md,
docs/perception.md): the specific force and angular velocity at the driver's or pilot's head in
the vehicle frame (x forward, y left, z up; (0, 0, +9.81) m/s2 at rest), sampled at 100 Hz.

>>> import stewart
>>> t, f, w = stewart.manoeuvre("car_braking")
>>> f[0].tolist(), t.shape == (f.shape[0],) == (w.shape[0],)
([0.0, 0.0, 9.81], True)
"""
from __future__ import annotations

import numbers
import pathlib
from typing import Dict, Tuple

import numpy as np

from .arrays import times

#: The columns of a manoeuvre file, SI units: t [s], f [m/s2], w [rad/s].
COLUMNS = ("t", "f_x", "f_y", "f_z", "w_x", "w_y", "w_z")


def manoeuvre_files() -> Dict[str, pathlib.Path]:
    """The manoeuvre files shipped with the package, by name (the file's stem):
    "aircraft_takeoff", "aircraft_turn", "car_braking", "car_lane_change", "car_slalom"."""
    folder = pathlib.Path(__file__).resolve().parent / "manoeuvres"
    return {p.stem: p for p in sorted(folder.glob("*.csv"))}


def manoeuvre(name) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t (N,) [s], specific_force (N, 3) [m/s2], angular_velocity (N, 3) [rad/s]) of a shipped
    manoeuvre (a name of manoeuvre_files()) or of a file of the same columns (a path ending in
    .csv). ValueError names an unknown manoeuvre or a file that is not one."""
    files = manoeuvre_files()
    if isinstance(name, str) and name in files:
        path = files[name]
    elif str(name).endswith(".csv"):
        path = pathlib.Path(name)
    else:
        raise ValueError(f"no manoeuvre {name!r}: one of {', '.join(files) or '(none installed)'}, "
                         "or a .csv file with the columns " + ",".join(COLUMNS))
    return read_manoeuvre(path)


def random_vehicle(rng: np.random.Generator, t, force_peak: float = 2 * 9.81,
                   rate_peak: float = float(np.radians(200))) -> Tuple[np.ndarray, np.ndarray]:
    """A random vehicle motion at the times t (N,) [s], for trying cueing and limits on signals no
    one chose: per axis a sum of 1 to 3 steps, ramps and sines (random times, ramp lengths of 0.2
    to 5 s, frequencies of 0.05 to 3 Hz) scaled to a random peak of 0.2 to 1 times force_peak
    [m/s2] (about the rest value (0, 0, +9.81)) and rate_peak [rad/s]. Returns (specific_force
    (N, 3), angular_velocity (N, 3)); the same rng state gives the same signal.

    >>> import numpy as np, stewart
    >>> f, w = stewart.random_vehicle(np.random.default_rng(1), np.arange(0, 20, 0.01))
    >>> f.shape, w.shape, bool(np.abs(f - [0, 0, 9.81]).max() <= 2 * 9.81)
    ((2000, 3), (2000, 3), True)
    """
    t = times("t", t, None)
    for name, peak in (("force_peak", force_peak), ("rate_peak", rate_peak)):
        if not isinstance(peak, numbers.Real) or not np.isfinite(peak) or peak < 0:
            raise ValueError(f"{name} = {peak!r}: it must be a finite peak >= 0")
    n = len(t)
    if n == 0:
        return np.zeros((0, 3)), np.zeros((0, 3))

    def channel(limit):
        x = np.zeros(n)
        for _ in range(rng.integers(1, 4)):
            t0, kind, a = rng.uniform(t[0], t[-1]), rng.integers(3), rng.uniform(-1, 1)
            if kind == 0:
                x += a * (t > t0)
            elif kind == 1:
                x += a * np.clip((t - t0) / rng.uniform(0.2, 5), 0, 1)
            else:
                x += a * np.sin(2 * np.pi * rng.uniform(0.05, 3) * t + rng.uniform(0, 6.3))
        peak = np.max(np.abs(x))
        return x / peak * rng.uniform(0.2, 1.0) * limit if peak > 0 else x

    f = np.column_stack([channel(force_peak) for _ in range(3)]) + [0, 0, 9.81]
    w = np.column_stack([channel(rate_peak) for _ in range(3)])
    return f, w


def read_manoeuvre(path) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The columns of a manoeuvre file (header line COLUMNS, then comma-separated numbers with '.'
    decimals in any locale)."""
    path = pathlib.Path(path)
    try:
        with path.open(encoding="utf-8-sig") as stream:  # a spreadsheet's byte order mark
            header = stream.readline().strip()
            if tuple(header.split(",")) != COLUMNS:
                raise ValueError(f"{path}: the first line is {header!r}, not the columns "
                                 + ",".join(COLUMNS))
            data = np.loadtxt(stream, delimiter=",", ndmin=2)
    except OSError as e:
        raise ValueError(f"{path}: {e.strerror}") from None
    except ValueError as e:
        if str(e).startswith(str(path)):
            raise
        raise ValueError(f"{path}: {e}") from None
    if data.shape[1] != len(COLUMNS) or data.shape[0] < 2:
        raise ValueError(f"{path}: {data.shape[0]} rows of {data.shape[1]} columns; give at "
                         f"least 2 rows of {len(COLUMNS)}")
    if not np.all(np.isfinite(data)):
        row = int(np.argwhere(~np.isfinite(data))[0, 0])
        raise ValueError(f"{path}: data row {row + 1} has a value that is not finite")
    return data[:, 0].copy(), data[:, 1:4].copy(), data[:, 4:7].copy()
