"""The Python tests' independent reference for the platform's closed forms, in numpy, written from
docs/model.md (§3 conventions, §4 closed-form levels) and not from the C code it checks.

Poses are (x, y, z, roll, pitch, yaw); rates and accelerations are the time derivatives of those six
components (model.md §3). Angles of the attachment points are in radians.
"""
import json
import math

import numpy as np

G = 9.81  # m/s^2, along -z
RHO_ALUMINIUM = 2700.0  # kg/m^3
M_PLATFORM = RHO_ALUMINIUM * math.pi * 0.5 ** 2 * 0.05  # the thesis' disc, model.md §2
BETA = np.radians([0, 30, 120, 150, 240, 270])  # base angles of legs 1..6
TAU = np.radians([330, 60, 90, 180, 210, 300])  # platform angles of legs 1..6


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch),
                              math.cos(yaw), math.sin(yaw))
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx


def geometry(rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """Base points a_k (world, rows) and platform points b_k (platform frame, rows)."""
    beta, tau = np.asarray(beta, dtype=float), np.asarray(tau, dtype=float)
    a = rb * np.column_stack([np.cos(beta), np.sin(beta), np.zeros(len(beta))])
    b = rt * np.column_stack([np.cos(tau), np.sin(tau), np.zeros(len(tau))])
    return a, b


def leg_vectors(pose, rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """d_k = p + R b_k - a_k (rows) and the platform arms R b_k (rows), world frame."""
    a, b = geometry(rb, rt, beta, tau)
    arms = b @ rotation(*pose[3:]).T
    return np.asarray(pose[:3], dtype=float) + arms - a, arms


def lengths(pose, rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """L_k = |p + R b_k - a_k|."""
    d, _ = leg_vectors(pose, rb, rt, beta, tau)
    return np.linalg.norm(d, axis=1)


def leg_axes(pose, rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """Unit leg axes n_k (base point to platform point, rows) and the arms R b_k (rows)."""
    d, arms = leg_vectors(pose, rb, rt, beta, tau)
    return d / np.linalg.norm(d, axis=1)[:, None], arms


def angular_velocity_map(roll, pitch, yaw):
    """E with omega = E (roll_dot, pitch_dot, yaw_dot), world frame: the columns are the world
    directions of the roll, pitch and yaw axes, Rz Ry e_x, Rz e_y, e_z."""
    rz = rotation(0.0, 0.0, yaw)
    ry = rotation(0.0, pitch, 0.0)
    return np.column_stack([rz @ ry @ [1.0, 0.0, 0.0], rz @ [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def angular_motion(pose, pose_dot, pose_ddot):
    """omega and its time derivative, E theta_dot and E theta_ddot + (dE/dt) theta_dot."""
    theta, theta_dot = np.asarray(pose[3:], float), np.asarray(pose_dot[3:], float)
    E = angular_velocity_map(*theta)
    # dE/dt column by column: the yaw axis is fixed, the pitch axis Rz e_y turns with the yaw rate,
    # the roll axis Rz Ry e_x with the yaw and pitch rates (d/dt Rz Ry e_x = w_yaw x Rz Ry e_x +
    # Rz (w_pitch x Ry e_x), and Rz (a x b) = Rz a x Rz b).
    yaw_axis, pitch_axis, roll_axis = E[:, 2], E[:, 1], E[:, 0]
    yaw_rate, pitch_rate = theta_dot[2] * yaw_axis, theta_dot[1] * pitch_axis
    E_dot = np.column_stack([np.cross(yaw_rate + pitch_rate, roll_axis),
                             np.cross(yaw_rate, pitch_axis), np.zeros(3)])
    omega = E @ theta_dot
    alpha = E @ np.asarray(pose_ddot[3:], float) + E_dot @ theta_dot
    return omega, alpha


def length_rates_and_accelerations(pose, pose_dot, pose_ddot, rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """L_dot_k = n_k . d_dot_k and L_ddot_k = n_k . d_ddot_k + (|d_dot_k|^2 - L_dot_k^2) / L_k with
    d_dot_k = p_dot + omega x R b_k, d_ddot_k = p_ddot + alpha x R b_k + omega x (omega x R b_k)."""
    d, arms = leg_vectors(pose, rb, rt, beta, tau)
    L = np.linalg.norm(d, axis=1)
    n = d / L[:, None]
    omega, alpha = angular_motion(pose, pose_dot, pose_ddot)
    d_dot = np.asarray(pose_dot[:3], float) + np.cross(omega, arms)
    d_ddot = (np.asarray(pose_ddot[:3], float) + np.cross(alpha, arms)
              + np.cross(omega, np.cross(omega, arms)))
    L_dot = np.einsum("ij,ij->i", n, d_dot)
    L_ddot = np.einsum("ij,ij->i", n, d_ddot) + (np.einsum("ij,ij->i", d_dot, d_dot) - L_dot ** 2) / L
    return L_dot, L_ddot


def leg_jacobian(pose, rb=0.5, rt=0.5, beta=BETA, tau=TAU, scale=None):
    """J with rows (n_k, (R b_k) x n_k / scale): L_dot = J (p_dot, omega scale). scale defaults to
    the platform radius rt (the `condition` output's scaling, model.md §4.3); scale=1 gives the
    unscaled map whose transpose takes the forces to the wrench about the platform origin."""
    n, arms = leg_axes(pose, rb, rt, beta, tau)
    return np.hstack([n, np.cross(arms, n) / (rt if scale is None else scale)])


def condition(pose, rb=0.5, rt=0.5, beta=BETA, tau=TAU):
    """1-norm condition number of the scaled leg Jacobian (the unit's `condition` output), computed
    as cond_inf(J^T), which is the same number."""
    return np.linalg.cond(leg_jacobian(pose, rb, rt, beta, tau).T, np.inf)


def static_forces(pose, mass=M_PLATFORM, com=(0.0, 0.0, 0.0), rb=0.5, rt=0.5, gravity=G):
    """Massless legs, platform at rest (model.md §1.6): sum F_k n_k + m g = 0 and
    sum (R b_k) x F_k n_k + (R c) x m g = 0, moments about the platform origin."""
    weight = np.array([0.0, 0.0, -mass * gravity])
    c = rotation(*pose[3:]) @ np.asarray(com, dtype=float)
    J = leg_jacobian(pose, rb, rt, scale=1.0)
    return np.linalg.solve(J.T, -np.concatenate([weight, np.cross(c, weight)]))


def shipped_machine(path):
    """Base joints a, platform joints b (6, 3), strokes (6,) each and the translations of the
    tool and user frames of a platform file (ValueError for a turned frame: the closed form here
    has no rotation of a frame)."""
    with open(path, encoding="utf-8") as stream:
        d = json.load(stream)
    for frame in ("tool_frame", "user_frame"):
        if np.any(d.get(frame, [0] * 6)[3:]):
            raise ValueError(f"{path}: a turned {frame} needs its rotation here")
    strokes = [np.broadcast_to(np.asarray(d[k], float), 6) for k in ("stroke_min", "stroke_max")]
    return (np.reshape(d["base_joint"], (6, 3)), np.reshape(d["platform_joint"], (6, 3)), *strokes,
            np.asarray(d.get("tool_frame", [0] * 6)[:3], float),
            np.asarray(d.get("user_frame", [0] * 6)[:3], float))


def machine_lengths(machine, poses):
    """|R b + p - a| per leg (N, 6) of a shipped_machine at poses (N, 6) of the tool in the user
    frame, with p the platform origin: user origin + tool position - R tool origin."""
    a, b, _, _, tool, user = machine
    out = np.empty((len(poses), 6))
    for i, q in enumerate(poses):
        R = rotation(*q[3:])
        out[i] = np.linalg.norm(b @ R.T + user + q[:3] - R @ tool - a, axis=1)
    return out

