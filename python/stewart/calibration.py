"""Kinematic calibration: a machine's joints, length offsets (and, when asked, tool and user
frames) identified from measured poses and the length sensors' readings (docs/calibration.md).

>>> result = stewart.calibrate(nominal, poses, readings)      # doctest: +SKIP
>>> result.platform.params                                    # a platform file's content

The model (stewart_calibration.h): at a measured pose q (tool frame in the user frame) leg k's
sensor reads |p + R b_k - a_k| - o_k with the platform at T_user · T_q · T_tool⁻¹. Nonlinear least
squares (scipy.optimize.least_squares) on the residuals measured - predicted readings, weighted by
the measurement noise seen through the readings (Noise), with the library's closed-form Jacobian;
the unknowns are scaled to unit Jacobian columns, the scale in which `condition` is reported.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .arrays import POSE_LAYOUT, LEG_LAYOUT, rows6
from .calibration_model import (JOINT_GROUPS, Layout, Noise, frame_groups, nominal_geometry,
                                platform_with, readings_and_jacobian, scaled_basis,
                                stacked_jacobian, weighted_rows)
from .platform import Platform

LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")


class UnobservableError(ValueError):
    """The measurements cannot identify every unknown: `unobservable` names the parameters
    involved in the combinations they leave free; no geometry is made up for them."""

    def __init__(self, message: str, unobservable: list[str], condition: float) -> None:
        super().__init__(message)
        self.unobservable = unobservable
        self.condition = condition


@dataclass(frozen=True)
class Calibration:
    """The result of stewart.calibrate.

    platform: the calibrated Platform (geometry 1: joints as coordinates); its params are a
    platform file's content. names: the unknowns by table name ("base_joint[4]"); nominal,
    values, std: their nominal and identified values and standard deviations (m, rad);
    correlation: (p, p). residuals_before, residuals_after: (N, 6) measured - predicted readings
    [m] with the nominal and the calibrated geometry. condition: the condition number of the
    weighted identification Jacobian with unit columns (at the solution; the gauge removed).
    variance_factor: the weighted residuals' sum of squares per degree of freedom (about 1 when
    the noise given is the true one; the standard deviations include it). outliers: pose rows
    whose weighted residual exceeds outlier_threshold robust standard deviations. frames: which
    frames were identified; gauge: how the solution was fixed. seconds: identification time."""
    platform: Platform
    names: list[str]
    nominal: np.ndarray
    values: np.ndarray
    std: np.ndarray
    correlation: np.ndarray
    residuals_before: np.ndarray
    residuals_after: np.ndarray
    condition: float
    variance_factor: float
    outliers: list[int]
    frames: tuple[str, ...]
    gauge: str
    iterations: int
    seconds: float
    parameters: dict[str, np.ndarray] = field(repr=False)

    def rms(self, which: str = "after") -> float:
        """RMS of the residuals before or after calibration [m]."""
        r = self.residuals_after if which == "after" else self.residuals_before
        return float(np.sqrt(np.mean(r ** 2)))

    def report(self) -> str:
        """A text report: residuals, observability, outliers, and each unknown with its change
        and standard deviation."""
        lines = [f"poses: {self.residuals_before.shape[0]}, unknowns: {len(self.names)} "
                 f"(frames identified: {', '.join(self.frames) or 'none'})",
                 f"reading residual RMS: before {self.rms('before') * 1e6:.3f} um, "
                 f"after {self.rms('after') * 1e6:.3f} um",
                 f"observability: condition number of the scaled identification Jacobian "
                 f"{self.condition:.4g}",
                 f"variance factor (weighted residuals per degree of freedom): "
                 f"{self.variance_factor:.4g}",
                 f"gauge: {self.gauge}",
                 "outliers (pose rows, 0-based): "
                 + (", ".join(map(str, self.outliers)) if self.outliers else "none"),
                 f"identification: {self.iterations} evaluations, {self.seconds:.3f} s", "",
                 f"{'parameter':<20}{'nominal':>14}{'identified':>14}{'change':>12}{'std':>12}"]
        for name, n, v, s in zip(self.names, self.nominal, self.values, self.std):
            lines.append(f"{name:<20}{n:>14.6f}{v:>14.6f}{(v - n) * 1e3:>10.4f}e-3"
                         f"{s * 1e3:>10.4f}e-3")
        return "\n".join(lines) + "\n"


def calibrate(nominal: Platform, poses, readings, *, frames: Optional[str] = None,
              loss: str = "linear", position_noise: float = 10e-6, angle_noise: float = 20e-6,
              reading_noise: float = 1e-6, outlier_threshold: float = 5.0,
              max_std: float = 1e-3, max_evaluations: int = 200) -> Calibration:
    """Identifies the geometry of a built machine from measured poses and sensor readings.

    nominal: the Platform as drawn. poses: (N, 6) measured poses of the tool frame in the user
    frame (x, y, z [m], roll, pitch, yaw [rad]); readings: (N, 6) the length sensors' readings at
    them [m]. Unknowns: base_joint, platform_joint (36 coordinates) and length_offset (6);
    frames="tool", "user" or "both" adds tool_frame, user_frame or both (6 each).

    Gauge: a frame and the joints it carries move together without changing a reading. With
    frames=None the nominal tool and user frames are taken as exact: they fix the platform and
    base frames, and every one of the 42 unknowns is identifiable from poses of varied
    orientation. An identified frame brings 6 free combinations; they are fixed by holding the
    net rigid motion of the joints it carries at zero (the base or platform frame stays where
    the nominal joints put it, as a best fit): see docs/calibration.md.

    Noise (standard deviations): position_noise [m] and angle_noise [rad] of each measured pose
    (the tracker), reading_noise [m] of each sensor; they weight the residuals. loss: "linear"
    (least squares) or a robust loss of scipy's least_squares ("soft_l1", "huber", "cauchy",
    "arctan", on residuals in units of their noise, scale 3) that down-weights a bad pose. A pose
    whose weighted residual exceeds outlier_threshold robust standard deviations is named in
    `outliers`; with a robust loss the standard deviations are those of the unweighted linear
    model (approximate). Raises UnobservableError naming the parameters when some combination
    of unknowns would have a standard deviation above max_std (m or rad) from these poses (e.g.
    every pose at one orientation), ReadingError when the model has no reading at a pose, and
    ValueError naming a bad argument or when the fit does not converge in max_evaluations."""
    started = time.perf_counter()
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    s = rows6("readings", readings, q.shape[0], "poses", LEG_LAYOUT)
    _check_finite("poses", q)
    _check_finite("readings", s)
    if loss not in LOSSES:
        raise ValueError(f"loss = {loss!r} must be one of {', '.join(LOSSES)}")
    for name, value in (("outlier_threshold", outlier_threshold), ("max_std", max_std)):
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} = {value!r} must be finite and > 0")
    if not isinstance(max_evaluations, (int, np.integer)) or max_evaluations < 1:
        raise ValueError(f"max_evaluations = {max_evaluations!r} must be an integer >= 1")
    noise = Noise(position_noise, angle_noise, reading_noise)
    noise.check()
    frame_names = frame_groups(frames)
    layout = Layout(JOINT_GROUPS + frame_names)
    geometry0 = nominal_geometry(nominal)
    theta0 = np.concatenate([geometry0[g] for g in layout.groups])

    predicted0, W, J0 = weighted_rows(nominal, q, layout, noise)
    J0 = J0.reshape(-1, layout.size)
    to_theta = scaled_basis(layout, geometry0, J0)  # theta = theta0 + to_theta z

    _refuse_unobservable(J0 @ to_theta, to_theta, layout.names, max_std)

    cache: dict = {}

    def evaluate(z):
        key = z.tobytes()
        if key not in cache:
            cache.clear()
            theta = theta0 + to_theta @ z
            platform = platform_with(nominal, _geometry(layout, theta, geometry0))
            predicted, derivatives = readings_and_jacobian(platform, q)
            rows = W @ stacked_jacobian(layout, derivatives)
            cache[key] = (predicted, rows.reshape(-1, layout.size))
        return cache[key]

    def residual(z):
        predicted, _ = evaluate(z)
        return np.einsum("nij,nj->ni", W, s - predicted).reshape(-1)

    def jacobian(z):
        return -evaluate(z)[1] @ to_theta

    from scipy.optimize import least_squares  # only calibration needs scipy

    method = "lm" if loss == "linear" and 6 * q.shape[0] >= to_theta.shape[1] else "trf"
    fit = least_squares(residual, np.zeros(to_theta.shape[1]), jac=jacobian, method=method,
                        loss=loss, f_scale=3.0, x_scale=1.0, xtol=1e-12, ftol=1e-12,
                        gtol=1e-12, max_nfev=max_evaluations)
    if fit.status <= 0:
        raise ValueError(f"the identification did not converge in {max_evaluations} evaluations "
                         f"of the readings (scipy: {fit.message}): check the nominal platform "
                         f"and the measurements, or allow more (max_evaluations)")
    theta = theta0 + to_theta @ fit.x
    predicted, Jw = evaluate(fit.x)
    r = residual(fit.x)
    A = Jw @ to_theta
    dof = max(r.size - A.shape[1], 1)
    variance_factor = float(r @ r / dof)
    cov_z = variance_factor * np.linalg.pinv(A.T @ A)
    cov = to_theta @ cov_z @ to_theta.T
    std = np.sqrt(np.clip(np.diag(cov), 0, None))
    denominator = np.outer(std, std)
    correlation = np.divide(cov, denominator, out=np.zeros_like(cov), where=denominator > 0)
    geometry = _geometry(layout, theta, geometry0)
    return Calibration(
        platform=platform_with(nominal, geometry), names=layout.names, nominal=theta0,
        values=theta, std=std, correlation=correlation, residuals_before=s - predicted0,
        residuals_after=s - predicted, condition=_condition(A), variance_factor=variance_factor,
        outliers=_outliers(r.reshape(-1, 6), outlier_threshold), frames=frame_names,
        gauge=_gauge_text(frame_names), iterations=int(fit.nfev),
        seconds=time.perf_counter() - started, parameters=geometry)


def observability(nominal: Platform, poses, *, frames: Optional[str] = None,
                  position_noise: float = 10e-6, angle_noise: float = 20e-6,
                  reading_noise: float = 1e-6) -> float:
    """The condition number of the weighted identification Jacobian with unit columns (the gauge
    removed) that calibrate would have at poses with the nominal geometry: about 1 is ideal,
    infinite means some combination of unknowns cannot be identified."""
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    _check_finite("poses", q)
    noise = Noise(position_noise, angle_noise, reading_noise)
    noise.check()
    layout = Layout(JOINT_GROUPS + frame_groups(frames))
    _, _, J = weighted_rows(nominal, q, layout, noise)
    J = J.reshape(-1, layout.size)
    return _condition(J @ scaled_basis(layout, nominal_geometry(nominal), J))


def forward_poses(platform: Platform, readings, guess, tolerance: float = 1e-13,
                  max_iterations: int = 30) -> np.ndarray:
    """The poses (tool frame in the user frame) at which platform's sensors read `readings`
    (N, 6), by Newton's method from guess (N, 6) on the calibration model's readings and their
    pose derivatives (stewart_geometry_jacobian): how far the calibrated model puts the tool.
    ValueError naming the rows that did not converge to tolerance [m]."""
    s = rows6("readings", readings, None, "readings", LEG_LAYOUT)
    q = rows6("guess", guess, s.shape[0], "readings", POSE_LAYOUT).copy()
    for _ in range(max_iterations):
        predicted, derivatives = readings_and_jacobian(platform, q)
        error = s - predicted
        if np.max(np.abs(error), initial=0.0) <= tolerance:
            return q
        q += np.linalg.solve(derivatives["pose"], error[:, :, None])[:, :, 0]
    rows = np.flatnonzero(np.max(np.abs(error), axis=1) > tolerance)
    raise ValueError(f"forward kinematics did not converge to {tolerance} m in "
                     f"{max_iterations} iterations at reading rows {rows.tolist()}")


def _check_finite(name: str, a: np.ndarray) -> None:
    bad = np.argwhere(~np.isfinite(a))
    if bad.size:
        row, col = bad[0]
        raise ValueError(f"{name}[{row}, {col}] = {float(a[row, col])!r} is not finite")


def _geometry(layout: Layout, theta: np.ndarray, geometry0: dict) -> dict[str, np.ndarray]:
    geometry = {g: v.copy() for g, v in geometry0.items()}
    geometry.update({g: v.copy() for g, v in layout.split(theta).items()})
    return geometry


def _condition(A: np.ndarray) -> float:
    sv = np.linalg.svd(A, compute_uv=False)
    return float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")


def _refuse_unobservable(A: np.ndarray, to_theta: np.ndarray, names: list[str],
                         max_std: float) -> None:
    """UnobservableError when a combination of unknowns (a right singular vector of the
    weighted, scaled Jacobian A) would have a standard deviation above max_std [m or rad]: it
    names the unknowns carrying those combinations (projection above 0.1)."""
    # Every right singular vector; the full U only when A is wide (then V needs it too).
    _, sv, Vt = np.linalg.svd(A, full_matrices=A.shape[0] < A.shape[1])
    sv = np.concatenate([sv, np.zeros(Vt.shape[0] - sv.size)])
    directions = to_theta @ Vt.T  # physical change per unit of each combination
    size = np.linalg.norm(directions, axis=0)
    with np.errstate(divide="ignore"):
        std = np.where(sv > sv[0] * 1e-14, size / np.where(sv > 0, sv, 1.0), np.inf)
    free = np.flatnonzero(std > max_std)
    if free.size == 0:
        return
    basis, _ = np.linalg.qr(directions[:, free])
    weight = np.linalg.norm(basis, axis=1)
    involved = [names[i] for i in np.flatnonzero(weight > 0.1)]
    condition = float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")
    raise UnobservableError(
        f"these poses cannot identify the geometry: {free.size} combination(s) of unknowns would "
        f"have a standard deviation above max_std = {max_std:g} (condition number "
        f"{condition:.3g}); they involve {_ranges(involved)}. Measure poses of varied "
        f"orientation and position (stewart.calibration_poses) or identify fewer unknowns.",
        involved, condition)


def _ranges(names: list[str]) -> str:
    """base_joint[1], base_joint[2], base_joint[3] -> base_joint[1..3]."""
    groups: list[list] = []
    for name in names:
        base, index = name[:-1].split("[")
        index = int(index)
        if groups and groups[-1][0] == base and groups[-1][2] == index - 1:
            groups[-1][2] = index
        else:
            groups.append([base, index, index])
    return ", ".join(f"{b}[{i}]" if i == j else f"{b}[{i}..{j}]" for b, i, j in groups)


def _outliers(weighted: np.ndarray, threshold: float) -> list[int]:
    """Pose rows with a weighted residual above threshold robust standard deviations (the
    median absolute residual's, which one bad pose does not inflate)."""
    spread = 1.4826 * np.median(np.abs(weighted))
    if spread <= 0:
        return []
    return np.flatnonzero(np.max(np.abs(weighted), axis=1) > threshold * spread).tolist()


def _gauge_text(frames: tuple[str, ...]) -> str:
    if not frames:
        return ("the nominal tool and user frames fix the platform and base frames; every "
                "joint and offset is identified relative to them")
    held = {"user_frame": "base joints' net rigid motion from nominal held at zero (fixes the "
                          "base frame; the user frame is identified in it)",
            "tool_frame": "platform joints' net rigid motion from nominal held at zero (fixes "
                          "the platform frame; the tool frame is identified in it)"}
    return "; ".join(held[f] for f in frames)
