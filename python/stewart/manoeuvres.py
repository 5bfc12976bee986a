"""Vehicle manoeuvres shipped with the package as data (manoeuvres/README.md,
docs/perception.md): the specific force and angular velocity at the driver's or pilot's head in
the vehicle frame (x forward, y left, z up; (0, 0, +9.81) m/s2 at rest), sampled at 100 Hz.

>>> import stewart
>>> t, f, w = stewart.manoeuvre("car_braking")
>>> f[0].tolist(), t.shape == (f.shape[0],) == (w.shape[0],)
([0.0, 0.0, 9.81], True)
"""
from __future__ import annotations

import pathlib
from typing import Dict, Tuple

import numpy as np

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


def read_manoeuvre(path) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The columns of a manoeuvre file (header line COLUMNS, then comma-separated numbers with '.'
    decimals in any locale)."""
    path = pathlib.Path(path)
    try:
        with path.open() as stream:
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
