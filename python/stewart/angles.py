"""Rotation orders of a pose's angles (the platform parameter ``rotation_order``,
docs/geometry.md "Rotation order and frames") and the conversion between them.

Order 0: R = Rz(yaw) Ry(pitch) Rx(roll), the default. Order 1: R = Rx(roll) Ry(pitch) Rz(yaw),
rotations about the moving x, then y, then z (PI's U -> V -> W). Rates and accelerations are the
time derivatives of the angles of each.

>>> import numpy as np, stewart
>>> xyz = stewart.convert_angles([0.1, 0.2, 0.3], 0, 1)
>>> np.allclose(stewart.convert_angles(xyz, 1, 0), [0.1, 0.2, 0.3], rtol=0, atol=1e-15)
True
"""
from __future__ import annotations

import numpy as np

ROTATION_ORDERS = {0: "Rz Ry Rx", 1: "Rx Ry Rz"}
_NAMES = {"zyx": 0, "xyz": 1, "uvw": 1}


def rotation_order(order) -> int:
    """0 or 1 from 0, 1, "zyx" (Rz Ry Rx), "xyz" or "uvw" (Rx Ry Rz); ValueError otherwise."""
    if isinstance(order, str) and order.lower() in _NAMES:
        return _NAMES[order.lower()]
    if not isinstance(order, str) and order in ROTATION_ORDERS:
        return int(order)
    raise ValueError(f"rotation order {order!r} must be 0 or 'zyx' (R = Rz Ry Rx), 1, 'xyz' or "
                     f"'uvw' (R = Rx Ry Rz)")


def rotation_matrix(angles, order=0) -> np.ndarray:
    """R (..., 3, 3) of (..., 3) angles (roll, pitch, yaw) [rad] in `order`."""
    a = np.asarray(angles, dtype=float)
    cr, cp, cy = np.cos(a[..., 0]), np.cos(a[..., 1]), np.cos(a[..., 2])
    sr, sp, sy = np.sin(a[..., 0]), np.sin(a[..., 1]), np.sin(a[..., 2])
    if rotation_order(order) == 0:
        rows = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr]]
    else:
        rows = [[cp * cy, -cp * sy, sp],
                [cr * sy + sr * sp * cy, cr * cy - sr * sp * sy, -sr * cp],
                [sr * sy - cr * sp * cy, sr * cy + cr * sp * sy, cr * cp]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _rate_matrix(a, order):
    """E (..., 3, 3) with omega = E angles_dot."""
    cr, cp, cy = np.cos(a[..., 0]), np.cos(a[..., 1]), np.cos(a[..., 2])
    sr, sp, sy = np.sin(a[..., 0]), np.sin(a[..., 1]), np.sin(a[..., 2])
    zero, one = np.zeros_like(cr), np.ones_like(cr)
    if order == 0:  # [Rz Ry e_x, Rz e_y, e_z]
        rows = [[cy * cp, -sy, zero], [sy * cp, cy, zero], [-sp, zero, one]]
    else:  # [e_x, Rx e_y, Rx Ry e_z]
        rows = [[one, zero, sp], [zero, cr, -sr * cp], [zero, sr, cr * cp]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _rate_matrix_dot(a, rates, order):
    """dE/dt (..., 3, 3) at angles a moving at rates."""
    cr, cp, cy = np.cos(a[..., 0]), np.cos(a[..., 1]), np.cos(a[..., 2])
    sr, sp, sy = np.sin(a[..., 0]), np.sin(a[..., 1]), np.sin(a[..., 2])
    rd, pd, yd = rates[..., 0], rates[..., 1], rates[..., 2]
    zero = np.zeros_like(cr)
    if order == 0:
        rows = [[-sy * yd * cp - cy * sp * pd, -cy * yd, zero],
                [cy * yd * cp - sy * sp * pd, -sy * yd, zero],
                [-cp * pd, zero, zero]]
    else:
        rows = [[zero, zero, cp * pd],
                [zero, -sr * rd, -cr * cp * rd + sr * sp * pd],
                [zero, cr * rd, -sr * cp * rd - cr * sp * pd]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _angles_of(R, order, near):
    """Angles of R in `order`: pitch in [-pi/2, pi/2], roll and yaw nearest to near's."""
    if order == 0:
        pitch = np.arcsin(np.clip(-R[..., 2, 0], -1.0, 1.0))
        roll = np.arctan2(R[..., 2, 1], R[..., 2, 2])
        yaw = np.arctan2(R[..., 1, 0], R[..., 0, 0])
    else:
        pitch = np.arcsin(np.clip(R[..., 0, 2], -1.0, 1.0))
        roll = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
        yaw = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    roll = roll + 2 * np.pi * np.round((near[..., 0] - roll) / (2 * np.pi))
    yaw = yaw + 2 * np.pi * np.round((near[..., 2] - yaw) / (2 * np.pi))
    return np.stack([roll, pitch, yaw], axis=-1)


def convert_angles(angles, from_order, to_order, rates=None, accelerations=None):
    """The same rotations' angles (roll, pitch, yaw) [rad] in `to_order`, from `angles` (..., 3)
    in `from_order` (0 or "zyx": R = Rz Ry Rx; 1, "xyz" or "uvw": R = Rx Ry Rz). Pitch comes in
    [-pi/2, pi/2], roll and yaw on the branch (2 pi apart) nearest to the given ones.

    With `rates` (..., 3), the time derivatives of the given angles, returns (angles, rates) of the
    same motion (the same angular velocity); with `accelerations` too, (angles, rates,
    accelerations). ValueError at pitch +-90 deg of either order, where the rates are not defined.
    """
    source, target = rotation_order(from_order), rotation_order(to_order)
    a = np.asarray(angles, dtype=float)
    if a.shape[-1:] != (3,):
        raise ValueError(f"angles have shape {a.shape}: the last axis must be (roll, pitch, yaw)")
    out = a.copy() if source == target else _angles_of(rotation_matrix(a, source), target, a)
    if rates is None:
        if accelerations is not None:
            raise ValueError("accelerations need the rates")
        return out
    r = np.broadcast_to(np.asarray(rates, dtype=float), a.shape)
    if source == target:
        result = (out, r.copy())
        return result if accelerations is None else result + (
            np.broadcast_to(np.asarray(accelerations, dtype=float), a.shape).copy(),)
    E_to = _rate_matrix(out, target)
    if np.any(np.abs(np.cos(out[..., 1])) <= 1e-12) or np.any(np.abs(np.cos(a[..., 1])) <= 1e-12):
        raise ValueError("a pitch is at +-90 degrees, where roll and yaw rates are not defined")
    omega = np.einsum("...ij,...j->...i", _rate_matrix(a, source), r)
    out_rates = np.linalg.solve(E_to, omega[..., None])[..., 0]
    if accelerations is None:
        return out, out_rates
    acc = np.broadcast_to(np.asarray(accelerations, dtype=float), a.shape)
    alpha = (np.einsum("...ij,...j->...i", _rate_matrix(a, source), acc)
             + np.einsum("...ij,...j->...i", _rate_matrix_dot(a, r, source), r))
    bias = np.einsum("...ij,...j->...i", _rate_matrix_dot(out, out_rates, target), out_rates)
    out_acc = np.linalg.solve(E_to, (alpha - bias)[..., None])[..., 0]
    return out, out_rates, out_acc
