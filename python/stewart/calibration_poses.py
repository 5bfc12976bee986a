"""Which poses to measure for a calibration: stewart.calibration_poses (docs/calibration.md §4).

Criterion: D-optimality, the largest determinant of the posterior information matrix (JᵀJ of
the weighted identification Jacobian, the gauge removed, plus the prior's) over n poses chosen
from random candidates inside the limits. The determinant is the inverse of the volume of the
parameters' posterior ellipsoid and does not depend on the units or scaling of the unknowns; it
also keeps the scaled condition number low (studies/calibration_study.py measures it). Search: greedy construction (each pose adds the most
log-determinant), then Fedorov exchange passes (each chosen pose swapped for the candidate that
raises the determinant most) until no swap helps.
"""
from __future__ import annotations

import warnings
from typing import Optional

import numpy as np

from .calibration_model import (Layout, Noise, Prior, check_conventions, nominal_geometry,
                                parameter_value, scaled_basis, weighted_rows)
from .limits import LIMIT_CLASSES
from .platform import Platform


def calibration_poses(platform: Platform, n: int, *, identify=None,
                      frames: Optional[str] = None, candidates: int = 2000, seed: int = 0,
                      position_range: Optional[float] = None,
                      angle_range: Optional[float] = None, max_passes: int = 10,
                      joint_tolerance: float = 1e-3, offset_tolerance: float = 1e-3,
                      frame_tolerance: float = 5e-3, frame_angle_tolerance: float = 5e-3,
                      position_noise: float = 10e-6, angle_noise: float = 20e-6,
                      reading_noise: float = 1e-6) -> np.ndarray:
    """n poses (n, 6) of the tool frame in the user frame at which to measure platform for
    stewart.calibrate (with the same identify, frames, tolerances and noise), D-optimal among
    `candidates` random poses inside the limits.

    Candidates are drawn uniformly in the box of the machine's own axis ranges at home
    (Platform.axis_ranges: how far each axis of the tool moves alone, within every limit),
    shrunk where too few combined moves stay inside, and kept only where the library solves
    them (massless level) with no warning and within every limit of Platform.limits (a limit
    the home pose itself is beyond is not applied, with a warning that names it). Given
    position_range [m] and angle_range [rad], the box is home +- those instead. seed makes the
    draw repeatable. ValueError if n is too small to identify the unknowns (6 readings a pose)
    or if too few candidates are inside the limits."""
    check_conventions(platform, "calibration_poses (poses for calibration)")
    layout = Layout.of(identify, frames)
    if not isinstance(n, (int, np.integer)) or n < 1 or 6 * n < min(layout.free.sum(), 42):
        raise ValueError(f"n = {n!r}: identifying {int(layout.free.sum())} unknowns needs an "
                         f"integer of at least {-(-min(int(layout.free.sum()), 42) // 6)} "
                         f"poses (6 readings each)")
    if candidates < n:
        raise ValueError(f"candidates = {candidates} must be at least n = {n}")
    noise = Noise(position_noise, angle_noise, reading_noise)
    noise.check()
    prior = Prior(joint_tolerance, offset_tolerance, frame_tolerance, frame_angle_tolerance)
    prior.check()
    beyond = limits_failed_at_home(platform)
    if beyond:
        warnings.warn(f"calibration_poses: the machine's home pose is beyond its "
                      f"{' and '.join(beyond)} limit as drawn; the poses are chosen within the "
                      f"other limits only (check the platform file: stewart-solve --limits)",
                      stacklevel=2)
    rng = np.random.default_rng(seed)
    pool = random_poses_inside_limits(platform, candidates, rng, position_range, angle_range)
    if pool.shape[0] < n:
        raise ValueError(f"only {pool.shape[0]} random poses are inside the limits, fewer than "
                         f"n = {n}: give a smaller position_range or angle_range")
    _, _, J = weighted_rows(platform, pool, layout, noise)
    basis = scaled_basis(layout, nominal_geometry(platform), J.reshape(-1, layout.size),
                         prior.vector(layout))
    X = J @ basis  # (candidates, 6, r): each candidate's rows of the information matrix
    prior_information = (basis / prior.vector(layout)[:, None])
    chosen = _d_optimal(X, n, max_passes, prior_information.T @ prior_information)
    return pool[chosen]


def _home(platform: Platform) -> np.ndarray:
    """The home pose of the tool frame in the user frame (platform at (0, 0, home_height))."""
    tool, user = parameter_value(platform, "tool_frame"), parameter_value(platform, "user_frame")
    height = parameter_value(platform, "home_height")[0]
    Rt, Ru = _rotation(tool[3:]), _rotation(user[3:])
    home = np.empty(6)
    home[:3] = Ru.T @ (np.array([0, 0, height]) + tool[:3] - user[:3])
    home[3:] = _angles(Ru.T @ Rt)
    return home


def limits_failed_at_home(platform: Platform) -> list[str]:
    """The limit classes the machine's home pose is beyond (as drawn, e.g. joints so close that
    the legs touch): poses are then chosen within the other limits only."""
    failed = int(platform.limits(_home(platform)).failed[0])
    return [name.replace("_", " ") for c, name in enumerate(LIMIT_CLASSES) if failed & (1 << c)]


def random_poses_inside_limits(platform: Platform, count: int, rng,
                               position_range: Optional[float] = None,
                               angle_range: Optional[float] = None) -> np.ndarray:
    """Up to count random poses (tool frame in the user frame) inside the limits, drawn in the
    box calibration_poses says; rng: a numpy Generator. Limits the home pose is beyond
    (limits_failed_at_home) are not applied."""
    home = _home(platform)
    ignored = int(platform.limits(home).failed[0])
    low, high = _box(platform, home, position_range, angle_range, ignored)
    kept, shrink = [], 1.0
    for _ in range(50):  # batches until enough are inside the limits
        middle, half = (low + high) / 2, (high - low) / 2 * shrink
        q = middle + rng.uniform(-1, 1, (4 * count, 6)) * half
        solved = platform.inverse(q, fidelity="massless")
        # Solvable with no warning, and within every limit (joint angles, interference too).
        inside = ((solved.status == 0) & (solved.warnings == 0)
                  & ((platform.limits(q).failed & ~ignored) == 0))
        kept.append(q[inside])
        if sum(len(k) for k in kept) >= count:
            break
        if inside.mean() < 0.1:  # combined moves leave the box's corners: draw nearer home
            shrink *= 0.8
    return np.concatenate(kept)[:count]


def _box(platform: Platform, home: np.ndarray, position_range, angle_range, ignored: int):
    """The candidates' box (low, high per axis): home +- the ranges given, else the axis
    ranges at home (each axis alone, within every limit); when home is beyond a limit (ignored:
    its bits), home +- 2/3 of the smallest stroke range and 2.5 times that over the platform
    joints' radius (at most 0.5 rad)."""
    for name, value in (("position_range", position_range), ("angle_range", angle_range)):
        if value is not None and not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} must be finite and > 0")
    if ignored:
        strokes = parameter_value(platform, "stroke_max") - parameter_value(platform, "stroke_min")
        position_range = position_range or 2.0 / 3.0 * float(np.min(strokes))
        if angle_range is None:
            from . import _core
            _, top = _core.model_joints(platform._model)
            radius = float(np.max(np.linalg.norm(np.reshape(top, (6, 3)), axis=1)))
            angle_range = min(0.5, 2.5 * position_range / radius) if radius > 0 else 0.5
    low, high = home.copy(), home.copy()
    if position_range is None or angle_range is None:
        ends = platform.axis_ranges(home)[0]
        if np.any(ends[:, 1] - ends[:, 0] <= 0):
            raise ValueError("the machine cannot move from its home pose within its limits (an "
                             "axis range is empty): check the platform file "
                             "(stewart-solve --limits)")
        low, high = ends[:, 0].copy(), ends[:, 1].copy()
    if position_range is not None:
        low[:3], high[:3] = home[:3] - position_range, home[:3] + position_range
    if angle_range is not None:
        low[3:], high[3:] = home[3:] - angle_range, home[3:] + angle_range
    return low, high


def _gains(X: np.ndarray, M_inverse: np.ndarray) -> np.ndarray:
    """log det(M + X_cᵀ X_c) - log det M for every candidate c: log det(I + X_c M⁻¹ X_cᵀ)."""
    S = (X @ M_inverse) @ np.swapaxes(X, 1, 2)
    return np.linalg.slogdet(np.eye(X.shape[1]) + S)[1]


def _d_optimal(X: np.ndarray, n: int, max_passes: int, prior: np.ndarray) -> np.ndarray:
    """Indices of n candidates with a large det(prior + sum X_cᵀ X_c) (the posterior
    information): greedy, then Fedorov exchange."""
    information = np.einsum("cip,ciq->cpq", X, X)
    # A small ridge as well lets the greedy start however weak the prior.
    ridge = 1e-9 * np.trace(information.mean(axis=0)) / X.shape[2] * np.eye(X.shape[2])
    M = ridge + prior
    chosen: list[int] = []
    for _ in range(n):
        gains = _gains(X, np.linalg.inv(M))
        gains[chosen] = -np.inf
        best = int(np.argmax(gains))
        chosen.append(best)
        M += information[best]
    for _ in range(max_passes):
        swapped = False
        for slot in range(n):
            without = M - information[chosen[slot]]
            gains = _gains(X, np.linalg.inv(without))
            others = [c for i, c in enumerate(chosen) if i != slot]
            gains[others] = -np.inf
            best = int(np.argmax(gains))
            if gains[best] > gains[chosen[slot]] + 1e-9:
                chosen[slot] = best
                M = without + information[best]
                swapped = True
        if not swapped:
            break
    return np.array(chosen)


def _rotation(angles) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = np.cos(angles[0]), np.sin(angles[0])
    cp, sp = np.cos(angles[1]), np.sin(angles[1])
    cy, sy = np.cos(angles[2]), np.sin(angles[2])
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _angles(R: np.ndarray) -> np.ndarray:
    """(roll, pitch, yaw) of R = Rz Ry Rx."""
    return np.array([np.arctan2(R[2, 1], R[2, 2]), -np.arcsin(np.clip(R[2, 0], -1, 1)),
                     np.arctan2(R[1, 0], R[0, 0])])
