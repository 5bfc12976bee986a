"""Argument arrays checked at the boundary: shapes and values, errors naming the argument."""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

POSE_LAYOUT = "(x, y, z, roll, pitch, yaw) per row"
LEG_LAYOUT = "legs 1..6 per row"


def rows6(name: str, value, n: Optional[int], first: str, layout: str) -> np.ndarray:
    """value as a C-contiguous float64 (n, 6) array (a single row of 6 values is one row), or
    ValueError naming it; first names the argument that set n."""
    a = floats(name, value)
    if a.ndim == 1 and a.shape[0] == 6:
        a = a.reshape(1, 6)
    if a.ndim != 2 or a.shape[1] != 6:
        raise ValueError(f"{name} has shape {a.shape}: it must be (N, 6), {layout}")
    if n is not None and a.shape[0] != n:
        raise ValueError(f"{name} has {a.shape[0]} rows but {first} has {n}")
    return a


def vector(name: str, value, size: int) -> np.ndarray:
    """value as a C-contiguous float64 array of size finite values, or ValueError naming it."""
    a = floats(name, value).reshape(-1)
    if a.shape[0] != size:
        raise ValueError(f"{name} has {a.shape[0]} values: it must have {size}")
    if not all_finite(a):
        raise ValueError(f"{name} = {a.tolist()} has a value that is not finite")
    return a


#: Up to this many values all_finite checks them as Python floats.
SMALL_CHECK = 64


def all_finite(a: np.ndarray) -> bool:
    """True if every value of the float64 array a is finite. A few values (a pose, a guess) are
    checked as Python floats: numpy's isfinite and its reduction cost ten times that to set up."""
    if a.size <= SMALL_CHECK:
        return all(map(math.isfinite, a.ravel().tolist()))
    return bool(np.isfinite(a).all())


def rows3(name: str, value, n: int) -> np.ndarray:
    """value as a C-contiguous float64 (n, 3) array of finite values (x, y, z per row of t), or
    ValueError naming it and its first value that is not finite."""
    a = floats(name, value)
    if a.shape != (n, 3):
        raise ValueError(f"{name} has shape {a.shape}: it must be ({n}, 3), x, y, z per row of t")
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        i, j = bad[0]
        raise ValueError(f"{name}[{i}, {j}] = {float(a[i, j])!r} is not finite")
    return a


def times(name: str, value, n: Optional[int]) -> np.ndarray:
    """value as (n,) float64 times, finite and increasing (n None: any length), or ValueError
    naming the first bad entry and its value."""
    t = floats(name, value)
    if t.ndim != 1 or (n is not None and t.shape[0] != n):
        rows = "N" if n is None else n
        raise ValueError(f"{name} has shape {t.shape}: it must be ({rows},), one time per row")
    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise ValueError(f"{name}[{bad[0]}] = {float(t[bad[0]])!r} is not finite")
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        j = bad[0] + 1
        raise ValueError(f"{name}[{j}] = {float(t[j])!r} does not increase "
                         f"(t[{j - 1}] = {float(t[j - 1])!r})")
    return t


def floats(name: str, value) -> np.ndarray:
    """value as a C-contiguous float64 array, or ValueError naming it when a value is not a
    number (a string, None, a ragged list)."""
    try:
        return np.ascontiguousarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name} has a value that is not a number ({e}): {_short(value)}") from None


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."
