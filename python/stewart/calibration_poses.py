"""Which poses to measure for a calibration: stewart.calibration_poses (docs/calibration.md §4).

Criterion: D-optimality, the largest determinant of the information matrix JᵀJ of the weighted
identification Jacobian (the gauge removed) over n poses chosen from random candidates inside the
limits. The determinant is the volume of the parameters' confidence ellipsoid's inverse and does
not depend on the units or scaling of the unknowns; it also keeps the scaled condition number low
(studies/calibration_study.py measures it). Search: greedy construction (each pose adds the most
log-determinant), then Fedorov exchange passes (each chosen pose swapped for the candidate that
raises the determinant most) until no swap helps.
"""
from __future__ import annotations

from typing import Optional

import numpy as np

from .calibration_model import (JOINT_GROUPS, Layout, Noise, frame_groups, nominal_geometry,
                                parameter_value, scaled_basis, weighted_rows)
from .platform import Platform


def calibration_poses(platform: Platform, n: int, *, frames: Optional[str] = None,
                      candidates: int = 2000, seed: int = 0,
                      position_range: Optional[float] = None,
                      angle_range: Optional[float] = None, max_passes: int = 10,
                      position_noise: float = 10e-6, angle_noise: float = 20e-6,
                      reading_noise: float = 1e-6) -> np.ndarray:
    """n poses (n, 6) of the tool frame in the user frame at which to measure platform for
    stewart.calibrate (with the same frames), D-optimal among `candidates` random poses.

    Candidates are drawn uniformly around home: x, y, z within +-position_range [m] (default: 2/3 of
    the smallest stroke range), roll, pitch, yaw within +-angle_range [rad] (default: 2.5
    position_range over the largest platform joint radius, at most 0.5), and kept only where the
    library solves them (massless level) with no warning: every leg inside [stroke_min, stroke_max]
    and the leg Jacobian's condition number below warn_condition, and within every limit of
    Platform.limits (joint angles and leg interference too).
    seed makes the draw repeatable. ValueError if n is too small to identify the unknowns (each
    pose gives 6 readings) or if too few candidates are inside the limits."""
    layout = Layout(JOINT_GROUPS + frame_groups(frames))
    free = layout.size - 6 * len(frame_groups(frames))  # each identified frame's gauge: 6
    if not isinstance(n, (int, np.integer)) or 6 * n < free:
        raise ValueError(f"n = {n!r}: identifying {free} independent unknowns needs an integer "
                         f"of at least {-(-free // 6)} poses (6 readings each)")
    if candidates < n:
        raise ValueError(f"candidates = {candidates} must be at least n = {n}")
    noise = Noise(position_noise, angle_noise, reading_noise)
    noise.check()
    rng = np.random.default_rng(seed)
    pool = random_poses_inside_limits(platform, candidates, rng, position_range, angle_range)
    if pool.shape[0] < n:
        raise ValueError(f"only {pool.shape[0]} random poses are inside the limits, fewer than "
                         f"n = {n}: give a smaller position_range or angle_range")
    _, _, J = weighted_rows(platform, pool, layout, noise)
    basis = scaled_basis(layout, nominal_geometry(platform), J.reshape(-1, layout.size))
    X = J @ basis  # (candidates, 6, r): each candidate's rows of the information matrix
    chosen = _d_optimal(X, n, max_passes)
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


def random_poses_inside_limits(platform: Platform, count: int, rng,
                               position_range: Optional[float] = None,
                               angle_range: Optional[float] = None) -> np.ndarray:
    """Up to count random poses (tool frame in the user frame) around home inside the limits
    (calibration_poses says which box and which limits); rng: a numpy Generator."""
    strokes = parameter_value(platform, "stroke_max") - parameter_value(platform, "stroke_min")
    if position_range is None:
        position_range = 2.0 / 3.0 * float(np.min(strokes))
    if angle_range is None:
        from . import _core
        _, top = _core.model_joints(platform._model)
        radius = float(np.max(np.linalg.norm(np.reshape(top, (6, 3)), axis=1)))
        angle_range = min(0.5, 2.5 * position_range / radius) if radius > 0 else 0.5
    for name, value in (("position_range", position_range), ("angle_range", angle_range)):
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} must be finite and > 0")
    home = _home(platform)
    kept = []
    for _ in range(50):  # batches until enough are inside the limits
        q = home + rng.uniform(-1, 1, (4 * count, 6)) * np.repeat(
            [position_range, angle_range], 3)
        solved = platform.inverse(q, fidelity="massless")
        # Solvable with no warning, and within every limit (joint angles, interference too).
        inside = (solved.status == 0) & (solved.warnings == 0) & platform.limits(q).within
        kept.append(q[inside])
        if sum(len(k) for k in kept) >= count:
            break
    return np.concatenate(kept)[:count]


def _gains(X: np.ndarray, M_inverse: np.ndarray) -> np.ndarray:
    """log det(M + X_cᵀ X_c) - log det M for every candidate c: log det(I + X_c M⁻¹ X_cᵀ)."""
    S = (X @ M_inverse) @ np.swapaxes(X, 1, 2)
    return np.linalg.slogdet(np.eye(X.shape[1]) + S)[1]


def _d_optimal(X: np.ndarray, n: int, max_passes: int) -> np.ndarray:
    """Indices of n candidates with a large det(sum X_cᵀ X_c): greedy, then Fedorov exchange."""
    information = np.einsum("cip,ciq->cpq", X, X)
    # A small ridge lets the greedy start before n poses make the matrix invertible.
    ridge = 1e-9 * np.trace(information.mean(axis=0)) / X.shape[2] * np.eye(X.shape[2])
    M = ridge.copy()
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
