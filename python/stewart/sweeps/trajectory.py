"""Manoeuvres from CSV trajectories: a pose table read as stewart-solve reads it (columns t, x, y,
z, roll, pitch, yaw, optionally x_dot .. yaw_dot and x_ddot .. yaw_ddot, any order; a missing
derivative group by the same three-point differences), scaled into amplitude and frequency
families for the envelope sweep."""
from __future__ import annotations

import csv
import math
import pathlib

import numpy as np

from ..scenes import DDOT, DOT, POSE


class TrajectoryError(ValueError):
    """A trajectory file that cannot be read: the message names the file, line and column."""


def read_csv(path: pathlib.Path) -> dict:
    """{"t": (n,), "pose", "rate", "accel": (n, 6)} from the CSV at path, the derivatives
    differenced where the file has none. Numbers are read with Python's float (the same in
    every locale)."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        raise TrajectoryError(f"cannot read {path}: {getattr(e, 'strerror', None) or e}") from None
    rows = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
    if not rows:
        raise TrajectoryError(f"{path} is empty: expected the header t,x,y,z,roll,pitch,yaw")
    header = [c.strip() for c in rows[0]]
    groups = {"pose": POSE, "rate": DOT, "accel": DDOT}
    missing = [c for c in ("t", *POSE) if c not in header]
    if missing:
        raise TrajectoryError(f"{path}: the header must contain t,x,y,z,roll,pitch,yaw "
                              f"({missing[0]!r} is missing)")
    for name, cols in (("rate", DOT), ("accel", DDOT)):
        present = [c for c in cols if c in header]
        if present and len(present) != 6:
            suffix = cols[0][1:]
            raise TrajectoryError(f"{path}: the {suffix} columns must be all six (x{suffix} ... "
                                  f"yaw{suffix}) or none")
    values = np.empty((len(rows) - 1, len(header)))
    for line, r in enumerate(rows[1:], start=2):
        if len(r) != len(header):
            raise TrajectoryError(f"{path} line {line}: {len(r)} values for {len(header)} columns")
        for c, cell in enumerate(r):
            try:
                v = float(cell.strip())
            except ValueError:
                v = math.nan
            if not math.isfinite(v):
                raise TrajectoryError(f"{path} line {line}: column {header[c]} = {cell.strip()!r} "
                                      "is not a finite number")
            values[line - 2, c] = v
    if not len(values):
        raise TrajectoryError(f"{path} has no data rows")
    t = values[:, header.index("t")]
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        raise TrajectoryError(f"{path} line {bad[0] + 3}: t = {t[bad[0] + 1]!r} does not increase")
    out = {"t": t}
    for name, cols in groups.items():
        if cols[0] in header:
            out[name] = values[:, [header.index(c) for c in cols]]
    for order, name in ((1, "rate"), (2, "accel")):
        if name not in out:
            out[name] = np.column_stack([finite_difference(t, out["pose"][:, i], order)
                                         for i in range(6)])
    return out


def finite_difference(t: np.ndarray, f: np.ndarray, order: int) -> np.ndarray:
    """d/dt (order 1) or d2/dt2 (order 2) of samples f at increasing times t: the derivative of
    the quadratic through each three consecutive samples at the middle one, through the three
    end samples at the ends (stewart-solve's formula, in its order of operations); one sample:
    zero; two: the slope (and zero acceleration)."""
    n = len(t)
    d = np.zeros(n)
    if n < 2:
        return d
    if n == 2:
        if order == 1:
            d[:] = (f[1] - f[0]) / (t[1] - t[0])
        return d
    h1, h2 = t[1:-1] - t[:-2], t[2:] - t[1:-1]
    d1 = (f[1:-1] - f[:-2]) / h1
    dd = ((f[2:] - f[1:-1]) / h2 - d1) / (h1 + h2)
    if order == 1:
        d[1:-1] = d1 + dd * h1
        d[0] = d1[0] + dd[0] * -h1[0]
        d[-1] = d1[-1] + dd[-1] * (h1[-1] + 2 * h2[-1])
    else:
        d[1:-1] = 2 * dd
        d[0], d[-1] = d[1], d[-2]
    return d


def sample(trajectory: dict, amplitude: float = 1.0,
           frequency: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Times, poses, rates and accelerations of the trajectory scaled about its reference pose
    `about`: q = about + amplitude (q_file - about), played `frequency` times as fast (times
    t0 + (t - t0) / frequency, rates times amplitude x frequency, accelerations times amplitude
    x frequency^2)."""
    t = np.asarray(trajectory["t"], dtype=float)
    about = np.asarray(trajectory["about"], dtype=float)
    q = about + amplitude * (np.asarray(trajectory["pose"], dtype=float) - about)
    qd = amplitude * frequency * np.asarray(trajectory["rate"], dtype=float)
    qdd = amplitude * frequency * frequency * np.asarray(trajectory["accel"], dtype=float)
    return t[0] + (t - t[0]) / frequency, q, qd, qdd
