"""Kinematic calibration: a machine's joints, length offsets (and, when asked, tool and user
frames) identified from measured poses and the length sensors' readings (docs/calibration.md).

>>> result = stewart.calibrate(nominal, poses, readings)      # doctest: +SKIP
>>> result.platform.params                                    # a platform file's content

The model (stewart_calibration.h): at a measured pose q (tool frame in the user frame) leg k's
sensor reads |p + R b_k - a_k| - o_k with the platform at T_user · T_q · T_tool⁻¹. A maximum a
posteriori fit: nonlinear least squares (scipy.optimize.least_squares) on the residuals measured
- predicted readings, weighted by the measurement noise seen through the readings (Noise), stacked
on the unknowns' distance from nominal in units of their tolerance (Prior), with the library's
closed-form Jacobian; the unknowns are scaled to unit columns, the scale in which `condition` is
reported. The checks that refuse measurements are in calibration_checks.py, the posterior's
consequences (pose accuracy, what the prior set) in calibration_accuracy.py.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .arrays import POSE_LAYOUT, LEG_LAYOUT, rows6
from .calibration_accuracy import PoseAccuracy, pose_accuracy, pose_error_std, undetermined
from .calibration_checks import (FAR_FRACTION, FAR_MOVE, MeasurementError, check_measurements,
                                 check_options, refuse_far_moves, refuse_gross_errors)
from .calibration_model import (Layout, Noise, Prior, check_conventions, nominal_geometry,
                                platform_with, readings_and_jacobian, scaled_basis,
                                stacked_jacobian, whitening)
from .platform import Platform

LOSSES = ("linear", "soft_l1", "huber", "cauchy", "arctan")
ACCURACY_POSES = 500  # sample poses inside the workspace for the predicted pose error


class UnobservableError(ValueError):
    """The measurements cannot identify the unknowns to max_std: `unobservable` names the
    parameters whose standard deviation is above it; no geometry is made up for them."""

    def __init__(self, message: str, unobservable: list[str], condition: float) -> None:
        super().__init__(message)
        self.unobservable = unobservable
        self.condition = condition


@dataclass(frozen=True)
class Calibration:
    """The result of stewart.calibrate.

    platform: the calibrated Platform (geometry 1: joints as coordinates); its params are a
    platform file's content. identify: the words chosen; names: the unknowns by table name
    ("base_joint[4]"); nominal, values, std, tolerance: their nominal and identified values,
    posterior standard deviations and prior tolerances (m, rad); correlation: (p, p).
    residuals_before, residuals_after: (N, 6) measured - predicted readings [m] with the
    nominal and the calibrated geometry. condition: the condition number of the weighted
    identification Jacobian, prior rows included, with unit columns (at the solution; the gauge
    removed). variance_factor: the weighted residuals' sum of squares per degree of freedom
    (about 1 when the noise given is the true one; the standard deviations include it when
    above 1). undetermined: how many combinations of unknowns the data could not move (their
    posterior standard deviation is above half the prior's: the prior set them), and
    undetermined_names the unknowns carrying them. accuracy: the predicted pose error inside
    the workspace (PoseAccuracy). outliers: pose rows whose weighted residual exceeds
    outlier_threshold robust standard deviations. frames: the frames identified; gauge: how the
    solution was fixed. seconds: identification time."""
    platform: Platform
    identify: tuple[str, ...]
    names: list[str]
    nominal: np.ndarray
    values: np.ndarray
    std: np.ndarray
    tolerance: np.ndarray
    correlation: np.ndarray
    residuals_before: np.ndarray
    residuals_after: np.ndarray
    condition: float
    variance_factor: float
    undetermined: int
    undetermined_names: list[str]
    accuracy: PoseAccuracy
    outliers: list[int]
    frames: tuple[str, ...]
    gauge: str
    iterations: int
    seconds: float
    parameters: dict[str, np.ndarray] = field(repr=False)
    posterior: tuple = field(repr=False, default=())  # (layout, basis T, covariance of z)

    def predicted_pose_error(self, poses):
        """The predicted error (one standard deviation) of the poses the calibrated platform
        computes from readings, at poses (N, 6) of the tool in the user frame: (position [m],
        orientation [rad]) arrays of N, from the posterior covariance to first order."""
        q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
        layout, basis, covariance = self.posterior
        return pose_error_std(self.platform, layout, q, basis, covariance)

    def outlier_leg(self, row: int) -> int:
        """The leg (1..6) of pose row's largest reading residual after calibration."""
        return int(np.argmax(np.abs(self.residuals_after[row]))) + 1

    def rms(self, which: str = "after") -> float:
        """RMS of the residuals before or after calibration [m]."""
        r = self.residuals_after if which == "after" else self.residuals_before
        return float(np.sqrt(np.mean(r ** 2)))

    def report(self) -> str:
        """A text report: the predicted pose accuracy, residuals, observability, what the prior
        set, outliers, and each unknown with its change, standard deviation and tolerance."""
        lines = [f"poses: {self.residuals_before.shape[0]}, unknowns: {len(self.names)} "
                 f"(identify: {','.join(self.identify)})"]
        lines += self.accuracy.lines()
        lines += [f"reading residual RMS: before {self.rms('before') * 1e6:.3f} um, "
                  f"after {self.rms('after') * 1e6:.3f} um",
                  f"observability: condition number of the scaled identification Jacobian "
                  f"(prior rows included) {self.condition:.4g}",
                  f"variance factor (weighted residuals per degree of freedom): "
                  f"{self.variance_factor:.4g}",
                  _undetermined_text(self.undetermined, self.undetermined_names),
                  f"gauge: {self.gauge}",
                  "outliers (pose rows, 0-based; the leg of the largest residual): "
                  + (", ".join(f"{row} (leg {self.outlier_leg(row)})" for row in self.outliers)
                     if self.outliers else "none"),
                  f"identification: {self.iterations} evaluations, {self.seconds:.3f} s", "",
                  f"{'parameter':<20}{'nominal':>14}{'identified':>14}{'change':>12}"
                  f"{'std':>12}{'tolerance':>12}"]
        for name, n, v, s, t in zip(self.names, self.nominal, self.values, self.std,
                                    self.tolerance):
            lines.append(f"{name:<20}{n:>14.6f}{v:>14.6f}{(v - n) * 1e3:>10.4f}e-3"
                         f"{s * 1e3:>10.4f}e-3{t * 1e3:>10.4f}e-3")
        return "\n".join(lines) + "\n"


def _undetermined_text(count: int, names: list[str]) -> str:
    if count == 0:
        return "set by the prior: nothing (the data moved every combination of unknowns)"
    return (f"set by the prior: {count} combination(s) of unknowns the data could not move "
            f"(posterior std above half the tolerance), carried by {_ranges(names)}; they "
            f"stay near nominal and matter only as far as the predicted pose error says")


@dataclass(frozen=True)
class _Problem:
    """The linearised identification at the nominal geometry: the unknowns' layout, nominal
    values, tolerances, the readings' whitening W, the scaled gauge-fixed basis T (parameters =
    nominal + T z) and the weighted, scaled data rows A = W J T."""
    layout: Layout
    geometry0: dict
    theta0: np.ndarray
    tolerance: np.ndarray
    predicted0: np.ndarray
    W: np.ndarray
    J: np.ndarray
    T: np.ndarray
    A: np.ndarray


def _problem(nominal: Platform, q: np.ndarray, identify, frames, noise: Noise,
             prior: Prior) -> _Problem:
    noise.check()
    prior.check()
    check_conventions(nominal, "calibration")
    layout = Layout.of(identify, frames)
    geometry0 = nominal_geometry(nominal)
    theta0 = np.concatenate([geometry0[g] for g in layout.groups])
    tolerance = prior.vector(layout)
    predicted0, derivatives = readings_and_jacobian(nominal, q)
    W = whitening(derivatives["pose"], q, noise)
    J = stacked_jacobian(layout, derivatives)
    rows = (W @ J).reshape(-1, layout.size)
    T = scaled_basis(layout, geometry0, rows, tolerance)
    return _Problem(layout, geometry0, theta0, tolerance, predicted0, W, J, T, rows @ T)


def _prior_rows(problem: _Problem) -> np.ndarray:
    return problem.T / problem.tolerance[:, None]


def calibrate(nominal: Platform, poses, readings, *, identify=None,
              frames: Optional[str] = None, joint_tolerance: float = 1e-3,
              offset_tolerance: float = 1e-3, frame_tolerance: float = 5e-3,
              frame_angle_tolerance: float = 5e-3, loss: str = "linear",
              position_noise: float = 10e-6, angle_noise: float = 20e-6,
              reading_noise: float = 1e-6, outlier_threshold: float = 5.0,
              max_std: Optional[float] = None, max_evaluations: int = 200) -> Calibration:
    """Identifies the geometry of a built machine from measured poses and sensor readings.

    nominal: the Platform as drawn. poses: (N, 6) measured poses of the tool frame in the user
    frame (x, y, z [m], roll, pitch, yaw [rad]); readings: (N, 6) the length sensors' readings at
    them [m]. identify: the unknowns, words or one comma-separated string of "offsets"
    (length_offset), "joints" (base_joint and platform_joint), "joints-xy" (their x and y),
    "base", "platform" (one plate's joints), "tool", "user" (tool_frame, user_frame); default
    "joints,offsets". frames="tool", "user" or "both" adds those frames.

    Prior (a maximum a posteriori fit): the built machine's parameters are taken as the nominal
    ones with standard deviations joint_tolerance, offset_tolerance [m] and, for frames,
    frame_tolerance [m] and frame_angle_tolerance [rad]. What the data determine, they
    determine; a combination of unknowns the poses cannot see stays near nominal and is named
    (`undetermined`). Gauge: a frame identified together with all the joints it carries is
    fixed by holding those joints' net rigid motion at zero (docs/calibration.md).

    Noise (standard deviations): position_noise [m] and angle_noise [rad] of each measured pose
    (the tracker), reading_noise [m] of each sensor; they weight the residuals. loss: "linear"
    or a robust loss of scipy's least_squares ("soft_l1", "huber", "cauchy", "arctan", scale 3
    noise standard deviations). A pose whose weighted residual exceeds outlier_threshold robust
    standard deviations is named in `outliers`.

    Refusals (ValueError subclasses, nothing returned): a bad argument (named); MeasurementError
    for no poses or more than 20,000, values not finite, a pose at pitch +-90 deg, readings no
    machine within the tolerances gives (a few named by row and leg as outliers, many as a units
    or set-up mistake), a fit that moves an unknown more than 10 tolerances or a quarter of the
    machine's size; UnobservableError when max_std [m or rad] is given and an unknown's
    posterior standard deviation is above it; ReadingError when the model has no reading at a
    pose; ValueError when the fit does not converge in max_evaluations."""
    started = time.perf_counter()
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    s = rows6("readings", readings, q.shape[0], "poses", LEG_LAYOUT)
    check_options(loss, LOSSES, outlier_threshold, max_std, max_evaluations)
    check_measurements(q, s)
    problem = _problem(nominal, q, identify, frames, Noise(position_noise, angle_noise,
                                                          reading_noise),
                       Prior(joint_tolerance, offset_tolerance, frame_tolerance,
                             frame_angle_tolerance))
    refuse_gross_errors(s, problem.predicted0, _reading_spread(problem), q)
    if max_std is not None:
        _refuse_unobservable(problem, max_std)
    fit, evaluate = _fit(nominal, q, s, problem, loss, max_evaluations)
    return _result(nominal, q, s, problem, fit, evaluate, outlier_threshold, started)


def _reading_spread(problem: _Problem) -> np.ndarray:
    """Standard deviation of each reading about the nominal machine's: the tolerances through
    the readings' derivatives, and the measurement noise (W⁻¹ W⁻ᵀ)."""
    free = problem.layout.free
    tolerance_part = np.sum((problem.J[:, :, free] * problem.tolerance[free]) ** 2, axis=2)
    Winv = np.linalg.inv(problem.W)
    return np.sqrt(tolerance_part + np.sum(Winv ** 2, axis=2))


def _fit(nominal, q, s, problem: _Problem, loss: str, max_evaluations: int):
    layout, T, W = problem.layout, problem.T, problem.W
    prior_rows = _prior_rows(problem)
    cache: dict = {}

    def evaluate(z):
        key = z.tobytes()
        if key not in cache:
            cache.clear()
            theta = problem.theta0 + T @ z
            platform = platform_with(nominal, _geometry(layout, theta, problem.geometry0))
            predicted, derivatives = readings_and_jacobian(platform, q)
            rows = W @ stacked_jacobian(layout, derivatives)
            cache[key] = (predicted, rows.reshape(-1, layout.size), platform)
        return cache[key]

    def residual(z):
        predicted = evaluate(z)[0]
        data = np.einsum("nij,nj->ni", W, s - predicted).reshape(-1)
        return np.concatenate([data, prior_rows @ z])

    def jacobian(z):
        return np.vstack([-evaluate(z)[1] @ T, prior_rows])

    try:
        from scipy.optimize import least_squares  # only calibration needs scipy
    except ImportError as e:
        raise ImportError("stewart.calibrate needs scipy: pip install 'stewart[calibration]' "
                          "(from a checkout: pip install '.[calibration]')") from e

    method = "lm" if loss == "linear" else "trf"
    with np.errstate(all="ignore"):
        fit = least_squares(residual, np.zeros(T.shape[1]), jac=jacobian, method=method,
                            loss=loss, f_scale=3.0, x_scale=1.0, xtol=1e-12, ftol=1e-12,
                            gtol=1e-12, max_nfev=max_evaluations)
    if not np.all(np.isfinite(fit.fun)) or not np.all(np.isfinite(fit.x)):
        raise MeasurementError("the fit's residuals are not finite: the measurements do not "
                               "describe this machine (check the units and the outliers)")
    if fit.status <= 0:
        raise ValueError(f"the identification did not converge in {max_evaluations} evaluations "
                         f"of the readings (scipy: {fit.message}): check the nominal platform "
                         f"and the measurements, or allow more (max_evaluations)")
    return fit, evaluate


def _move_limit(nominal: Platform, problem: _Problem) -> np.ndarray:
    """How far each parameter may move from nominal: FAR_MOVE tolerances, and for joints and
    offsets at most FAR_FRACTION of the machine's size (its largest joint radius)."""
    joints = np.concatenate([problem.geometry0["base_joint"],
                             problem.geometry0["platform_joint"]]).reshape(-1, 3)
    size = float(np.max(np.linalg.norm(joints, axis=1)))
    limit = FAR_MOVE * problem.tolerance
    joint_or_offset = ~np.isin(np.arange(problem.layout.size),
                               np.flatnonzero(_frame_mask(problem.layout)))
    limit[joint_or_offset] = np.minimum(limit[joint_or_offset], FAR_FRACTION * size)
    return limit


def _frame_mask(layout: Layout) -> np.ndarray:
    mask = np.zeros(layout.size, bool)
    for g, sl in layout.slices().items():
        mask[sl] = g.endswith("_frame")
    return mask


def _result(nominal, q, s, problem: _Problem, fit, evaluate, outlier_threshold: float,
            started: float) -> Calibration:
    layout, T = problem.layout, problem.T
    free = layout.free
    theta = problem.theta0 + T @ fit.x
    predicted, Jw, platform = evaluate(fit.x)
    weighted = np.einsum("nij,nj->ni", problem.W, s - predicted)
    worst_rows = np.argsort(-np.max(np.abs(weighted), axis=1))[:3].tolist()
    refuse_far_moves(layout.names, (theta - problem.theta0)[free], problem.tolerance[free],
                     _move_limit(nominal, problem)[free], worst_rows)
    A = Jw @ T
    prior_rows = _prior_rows(problem)
    information = A.T @ A + prior_rows.T @ prior_rows
    cov_z = np.linalg.inv(information)
    effective = float(np.trace(A.T @ A @ cov_z))  # parameters the data determine
    r = weighted.reshape(-1)
    variance_factor = float(r @ r / max(r.size - effective, 1.0))
    cov_z = max(variance_factor, 1.0) * cov_z
    cov = (T @ cov_z @ T.T)[np.ix_(free, free)]
    std = np.sqrt(np.clip(np.diag(cov), 0, None))
    denominator = np.outer(std, std)
    correlation = np.divide(cov, denominator, out=np.zeros_like(cov), where=denominator > 0)
    count, names, _ = undetermined(A, T, problem.tolerance, layout.names, free)
    from .calibration_poses import limits_failed_at_home
    samples, beyond = accuracy_samples(nominal), limits_failed_at_home(nominal)
    region = ("random poses within every limit" if not beyond else
              f"random poses within every limit but {' and '.join(beyond)}, which the home pose "
              f"is beyond as drawn")
    if len(samples) == 0:  # no random pose inside the limits: the poses the machine reached
        samples, region = q, "measured poses (no random pose was found inside the limits)"
    accuracy = pose_accuracy(nominal, platform, layout, samples, T, cov_z, problem.tolerance,
                             region)
    frames = layout.identified_frames()
    return Calibration(
        platform=platform, identify=layout.words, names=layout.names,
        nominal=problem.theta0[free], values=theta[free], std=std,
        tolerance=problem.tolerance[free], correlation=correlation,
        residuals_before=s - problem.predicted0, residuals_after=s - predicted,
        condition=_condition(np.vstack([A, prior_rows])), variance_factor=variance_factor,
        undetermined=count, undetermined_names=names, accuracy=accuracy,
        outliers=_outliers(weighted, A, information, outlier_threshold), frames=frames,
        gauge=_gauge_text(layout, frames), iterations=int(fit.nfev),
        seconds=time.perf_counter() - started,
        parameters=_geometry(layout, theta, problem.geometry0), posterior=(layout, T, cov_z))


def accuracy_samples(nominal: Platform, count: int = ACCURACY_POSES) -> np.ndarray:
    """Poses inside every limit of nominal (the region calibration_poses draws from), a fixed
    draw: where the report predicts the pose error."""
    from .calibration_poses import random_poses_inside_limits
    try:
        return random_poses_inside_limits(nominal, count, np.random.default_rng(12345))
    except ValueError:  # no box to draw from (home cannot move)
        return np.zeros((0, 6))


def observability(nominal: Platform, poses, *, identify=None, frames: Optional[str] = None,
                  joint_tolerance: float = 1e-3, offset_tolerance: float = 1e-3,
                  frame_tolerance: float = 5e-3, frame_angle_tolerance: float = 5e-3,
                  position_noise: float = 10e-6, angle_noise: float = 20e-6,
                  reading_noise: float = 1e-6, max_std: Optional[float] = None) -> float:
    """The condition number calibrate would report at these poses with the nominal geometry:
    that of the weighted identification Jacobian, prior rows included, with unit columns and
    the gauge removed (the same identify, tolerances and noise). About 1 is ideal; the prior
    bounds it where the poses leave combinations of unknowns free, so a large value means the
    prior, not the data, sets them. Infinite when calibrate would refuse the poses for
    observability: no poses, or an unknown's standard deviation above max_std."""
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    if q.shape[0] == 0:
        return float("inf")
    check_measurements(q, np.zeros_like(q))
    problem = _problem(nominal, q, identify, frames,
                       Noise(position_noise, angle_noise, reading_noise),
                       Prior(joint_tolerance, offset_tolerance, frame_tolerance,
                             frame_angle_tolerance))
    if max_std is not None:
        if not (np.isfinite(max_std) and max_std > 0):
            raise ValueError(f"max_std = {max_std!r} must be None or finite and > 0")
        try:
            _refuse_unobservable(problem, max_std)
        except UnobservableError:
            return float("inf")
    return _condition(np.vstack([problem.A, _prior_rows(problem)]))


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


def _geometry(layout: Layout, theta: np.ndarray, geometry0: dict) -> dict[str, np.ndarray]:
    geometry = {g: v.copy() for g, v in geometry0.items()}
    geometry.update({g: v.copy() for g, v in layout.split(theta).items()})
    return geometry


def _condition(A: np.ndarray) -> float:
    sv = np.linalg.svd(A, compute_uv=False)
    return float(sv[0] / sv[-1]) if sv[-1] > 0 else float("inf")


#: The most poses, as a multiple of those given, a refusal of max_std looks for.
MORE_POSES_MAX = 10.0


def _posterior_std(problem: _Problem, information: np.ndarray) -> np.ndarray:
    """Each free unknown's standard deviation [m or rad] from the information (scaled)."""
    cov_z = np.linalg.inv(information)
    std = np.sqrt(np.clip(np.diag(problem.T @ cov_z @ problem.T.T), 0, None))
    return std[problem.layout.free]


def _refuse_unobservable(problem: _Problem, max_std: float) -> None:
    """UnobservableError when an unknown's standard deviation from these poses (data and
    prior, at the nominal geometry) would be above max_std [m or rad], naming those unknowns
    and what would pass: the poses needed if more poses of the same spread would do (the data's
    information grows with their number, the prior's does not), else that none would."""
    prior_rows = _prior_rows(problem)
    data, prior = problem.A.T @ problem.A, prior_rows.T @ prior_rows
    std = _posterior_std(problem, data + prior)
    over = np.flatnonzero(std > max_std)
    if over.size == 0:
        return
    names = [problem.layout.names[i] for i in over]
    condition = _condition(np.vstack([problem.A, prior_rows]))
    poses = problem.A.shape[0] // 6  # six whitened readings a pose
    needed = next((k for k in np.arange(1.25, MORE_POSES_MAX + 1e-9, 0.25)
                   if _posterior_std(problem, k * data + prior).max() <= max_std), None)
    if needed is not None:
        more = math.ceil(needed * poses)
        advice = (f"About {more} poses of the same spread would (stewart.calibration_poses("
                  f"platform, {more}) with the same identify and tolerances; "
                  f"stewart.observability(..., max_std=) checks them before measuring)")
    else:
        advice = (f"No number of poses of this spread would (not {MORE_POSES_MAX:g} times as "
                  "many): the data barely see these unknowns, as on a machine whose legs hardly "
                  "turn, where a joint's shift along its leg reads as its length offset. Leave "
                  "max_std out: the fit then keeps what the data cannot see near nominal, and its "
                  "report's predicted pose error says what that costs; or identify fewer "
                  "unknowns (identify=, --identify; stewart.observability(..., identify=, "
                  "max_std=) says whether a choice passes)")
    raise UnobservableError(
        f"these poses cannot identify the geometry to max_std = {max_std:g} (m or rad): "
        f"{over.size} unknown(s) would have a larger standard deviation (up to "
        f"{std.max():.4g}, {std.max() / max_std:.4g} times max_std; condition number "
        f"{condition:.3g}): {_ranges(names)}. {advice}; or accept a max_std of "
        f"{_round_up(std.max())} (--max-std)", names, condition)


def _round_up(value: float) -> str:
    """value rounded up to 2 significant digits, as text that reads back as at least value (the
    product with the power of ten can round onto an integer just below it)."""
    if not (math.isfinite(value) and value > 0):
        return f"{value:g}"
    digits = 1 - math.floor(math.log10(value))
    scale = 10.0 ** -digits  # the second significant digit's unit
    if not scale > 0:  # below the smallest double's second digit
        return f"{value:g}"
    steps = math.ceil(value / scale)
    while float(f"{steps * scale:g}") < value:
        steps += 1
    return f"{steps * scale:g}"


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


def _outliers(weighted: np.ndarray, A: np.ndarray, information: np.ndarray,
              threshold: float) -> list[int]:
    """Pose rows with a weighted residual above threshold robust standard deviations (the
    median absolute residual's, which one bad pose does not inflate), found one at a time: each
    pose named is taken out of the linearised fit (A: weighted, scaled data rows; information:
    AᵀA + the prior's), so that its pull on the others' residuals does not name them too."""
    n = weighted.shape[0]
    rows = A.reshape(n, 6, -1)
    named: list[int] = []
    residual = weighted.copy()
    for _ in range(max(1, n // 5)):
        keep = np.setdiff1d(np.arange(n), named)
        spread = 1.4826 * np.median(np.abs(residual[keep]))
        if spread <= 0:
            break
        size = np.max(np.abs(residual), axis=1)
        size[named] = -np.inf
        worst = int(np.argmax(size))
        if size[worst] <= threshold * spread:
            break
        named.append(worst)
        out = rows[named].reshape(-1, rows.shape[2])
        # Without the named poses, z moves by -(H - A_Sᵀ A_S)⁻¹ A_Sᵀ r_S (linearised; the
        # residual is measured - predicted, predicted moving by A dz).
        step = np.linalg.solve(information - out.T @ out,
                               out.T @ weighted[named].reshape(-1))
        residual = weighted + rows @ step
    return sorted(named)


def _gauge_text(layout: Layout, frames: tuple[str, ...]) -> str:
    from .calibration_model import gauge_constraints
    fixed = gauge_constraints(layout, {"base_joint": np.zeros(18), "platform_joint": np.zeros(18)})
    if not frames:
        return ("the nominal tool and user frames fix the platform and base frames; every "
                "unknown is identified relative to them")
    if fixed is None:
        return ("the frames identified without all the joints they carry: the prior splits "
                "what a frame and its joints cannot tell apart")
    free = layout.split(layout.free)
    held = {"user_frame": "base joints' net rigid motion from nominal held at zero (fixes the "
                          "base frame; the user frame is identified in it)",
            "tool_frame": "platform joints' net rigid motion from nominal held at zero (fixes "
                          "the platform frame; the tool frame is identified in it)"}
    pairs = {"user_frame": "base_joint", "tool_frame": "platform_joint"}
    return "; ".join(held[f] if np.all(free[pairs[f]]) else
                     f"{f}: the prior splits it from the joints it carries" for f in frames)
