"""What a calibration leaves uncertain (docs/calibration.md §3): the posterior covariance of the
unknowns (data and prior), the combinations of unknowns the data could not move (the prior
dominates), and the pose error the covariance predicts at poses inside the workspace."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .calibration_model import Layout, angle_rate_matrices, readings_and_jacobian, stacked_jacobian
from .platform import Platform

PRIOR_DOMINATES = 0.5  # posterior std above this fraction of the prior's: the data hardly moved it


@dataclass(frozen=True)
class PoseAccuracy:
    """Predicted pose error (one standard deviation, as a distance [m] and a rotation angle
    [rad]) of the tool in the user frame over `samples` poses inside the workspace: the RMS and
    the worst over the poses, with the nominal geometry (its tolerances) and after calibration
    (the posterior covariance)."""
    samples: int
    position_rms_before: float
    position_worst_before: float
    orientation_rms_before: float
    orientation_worst_before: float
    position_rms: float
    position_worst: float
    orientation_rms: float
    orientation_worst: float
    region: str = "random poses within every limit"

    def lines(self) -> list[str]:
        return [f"predicted pose error inside the workspace ({self.samples} {self.region}; one "
                f"standard deviation):",
                f"  position: RMS {self.position_rms * 1e6:.3f} um, worst "
                f"{self.position_worst * 1e6:.3f} um (nominal geometry, its tolerances: RMS "
                f"{self.position_rms_before * 1e6:.1f} um, worst "
                f"{self.position_worst_before * 1e6:.1f} um)",
                f"  orientation: RMS {self.orientation_rms * 1e6:.3f} urad, worst "
                f"{self.orientation_worst * 1e6:.3f} urad (nominal: RMS "
                f"{self.orientation_rms_before * 1e6:.1f} urad, worst "
                f"{self.orientation_worst_before * 1e6:.1f} urad)"]


def pose_error_std(platform: Platform, layout: Layout, samples: np.ndarray,
                   basis: np.ndarray, covariance: np.ndarray):
    """Per sample pose, the standard deviation of the position [m] and orientation [rad] error
    of the poses platform computes from readings when its unknowns (parameters = nominal +
    basis z) have covariance `covariance` of z: forward kinematics to first order,
    dq = -J_pose⁻¹ J_parameters dθ."""
    _, derivatives = readings_and_jacobian(platform, samples)
    G = np.linalg.solve(derivatives["pose"], stacked_jacobian(layout, derivatives) @ basis)
    cov = G @ covariance @ np.swapaxes(G, 1, 2)
    E = angle_rate_matrices(samples)  # angle rates -> angular velocity: a small rotation
    rotation = E @ cov[:, 3:, 3:] @ np.swapaxes(E, 1, 2)
    position = np.sqrt(np.clip(np.trace(cov[:, :3, :3], axis1=1, axis2=2), 0, None))
    return position, np.sqrt(np.clip(np.trace(rotation, axis1=1, axis2=2), 0, None))


def pose_accuracy(nominal: Platform, calibrated: Platform, layout: Layout, samples: np.ndarray,
                  basis: np.ndarray, covariance: np.ndarray,
                  tolerance: np.ndarray, region: str) -> PoseAccuracy:
    """PoseAccuracy at samples (region: what they are, in words): before, the tolerances as the unknowns' covariance on the
    nominal machine; after, the posterior covariance on the calibrated machine."""
    prior_basis = np.eye(layout.size)[:, layout.free]
    before = pose_error_std(nominal, layout, samples, prior_basis,
                            np.diag(tolerance[layout.free] ** 2))
    after = pose_error_std(calibrated, layout, samples, basis, covariance)

    def rms(a):
        return float(np.sqrt(np.mean(a ** 2)))
    return PoseAccuracy(len(samples), rms(before[0]), float(before[0].max()), rms(before[1]),
                        float(before[1].max()), rms(after[0]), float(after[0].max()),
                        rms(after[1]), float(after[1].max()), region)


def undetermined(data_rows: np.ndarray, basis: np.ndarray, tolerance: np.ndarray,
                 names: list[str], free: np.ndarray):
    """The combinations of unknowns the data could not move: directions whose posterior
    standard deviation is above PRIOR_DOMINATES of the prior's (the generalised eigenvectors of
    the data's and the prior's information). Returns their count and the unknowns carrying them
    (by name), and per unknown the ratio posterior std / prior std."""
    prior_rows = basis / tolerance[:, None]
    Q = prior_rows.T @ prior_rows
    L = np.linalg.cholesky(Q)
    B = np.linalg.solve(L, data_rows.T).T  # data rows in prior-whitened coordinates
    _, sv, Vt = np.linalg.svd(B, full_matrices=True)
    sv = np.concatenate([sv, np.zeros(Vt.shape[0] - sv.size)])
    ratio = 1.0 / np.sqrt(1.0 + sv ** 2)
    # Physical directions in units of their tolerance: u = P T L⁻ᵀ v.
    directions = prior_rows @ np.linalg.solve(L.T, Vt.T)
    weak = np.flatnonzero(ratio > PRIOR_DOMINATES)
    posterior = directions @ np.diag(ratio ** 2) @ directions.T
    per_unknown = np.sqrt(np.clip(np.diag(posterior), 0, None))[free]
    if weak.size == 0:
        return 0, [], per_unknown
    basis_weak, _ = np.linalg.qr(directions[:, weak])
    weight = np.linalg.norm(basis_weak, axis=1)[free]
    return int(weak.size), [n for n, w in zip(names, weight) if w > 0.3], per_unknown
