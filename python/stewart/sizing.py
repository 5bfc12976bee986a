"""Motor sizing over duty cycles (docs/drives.md, "Sizing a machine's motors"): the inverse with
drives along each trajectory, reduced per leg to the numbers a motor and drive are chosen by."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Optional, Sequence, Union

import numpy as np

from .calibration_model import parameter_value
from .choices import Fidelity
from .inverse import InverseSolution

POSE = ("x", "y", "z", "roll", "pitch", "yaw")

#: The report's per-leg numbers, each a (T, 6) array: one row per trajectory, one column per leg.
REPORT_FIELDS = ("peak_torque", "rms_torque", "peak_current", "rms_current", "peak_power",
                 "rms_power", "peak_speed", "energy", "regenerated_energy", "inertia_share")


def integral(t: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The trapezoidal integral of f (N, ...) over t (N,) along the rows."""
    dt = np.diff(t).reshape((-1,) + (1,) * (f.ndim - 1))
    return np.sum(0.5 * (f[1:] + f[:-1]) * dt, axis=0)


def rms(t: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Time-weighted RMS of f over t: sqrt(integral(f^2) / duration); f itself for one row."""
    if t.shape[0] < 2:
        return np.abs(f[0])
    return np.sqrt(integral(t, f * f) / (t[-1] - t[0]))


@dataclass
class SizingReport:
    """Per leg, per trajectory (arrays (T, 6): row i is trajectory i, column k leg k+1):
    peaks are of absolute values; RMS weighted by time (trapezoids); energy the electrical
    energy the leg's motor takes over the trajectory (< 0: it gives back more than it takes),
    regenerated_energy what it gives back (>= 0: the integral of -min(P, 0)); inertia_share the
    RMS of the drive inertia's torque J (2 pi N / lead) L'' over the RMS of the whole torque."""
    names: list                #: the trajectories' names (file paths, or "trajectory i")
    peak_torque: np.ndarray    #: [N m]
    rms_torque: np.ndarray     #: [N m]
    peak_current: np.ndarray   #: [A]
    rms_current: np.ndarray    #: [A]
    peak_power: np.ndarray     #: electrical [W]
    rms_power: np.ndarray      #: electrical [W]
    peak_speed: np.ndarray     #: motor [rad/s]
    energy: np.ndarray         #: electrical, per trajectory [J]
    regenerated_energy: np.ndarray  #: [J]
    inertia_share: np.ndarray  #: [1]
    limits: dict               #: current_max, voltage_max, motor_speed_max, torque_constant,
    #: winding_resistance: (6,) arrays of the platform's drive (0: not given)
    solutions: list = field(default_factory=list)  #: (t, InverseSolution) per trajectory

    def summary(self) -> str:
        """A text table: per leg, the largest of each number over the trajectories (energies:
        the largest per cycle)."""
        units = {"peak_torque": "N.m", "rms_torque": "N.m", "peak_current": "A",
                 "rms_current": "A", "peak_power": "W", "rms_power": "W",
                 "peak_speed": "rad/s", "energy": "J", "regenerated_energy": "J",
                 "inertia_share": "1"}
        lines = [f"{'':22s}" + "".join(f"{'leg ' + str(k + 1):>12s}" for k in range(6))]
        for name in REPORT_FIELDS:
            worst = np.max(getattr(self, name), axis=0)
            lines.append(f"{name + ' [' + units[name] + ']':22s}" +
                         "".join(f"{v:12.4g}" for v in worst))
        return "\n".join(lines)

    def plot(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """A PNG at path: each leg's motor torque against motor speed over every trajectory,
        with the motors' limits over it (torque at current_max, motor_speed_max, and the torque
        the voltage_max leaves at each speed: (V_max - k_t |w|) k_t / R), once for legs whose
        drives are alike and named by their legs where they differ."""
        if not self.solutions:
            raise ValueError("the report keeps no solutions (sizing(..., keep=False)): size "
                             "again with keep=True to plot")
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 5))
        for k in np.flatnonzero(self.limits["torque_constant"] > 0):  # the legs with a drive
            w = np.concatenate([s.motor_speed[:, k] for _, s in self.solutions])
            tau = np.concatenate([s.motor_torque[:, k] for _, s in self.solutions])
            ax.scatter(w, tau, s=2, label=f"leg {k + 1}")
        lim = self.limits
        speed = max(np.max(self.peak_speed), np.max(lim["motor_speed_max"])) * 1.1 or 1.0
        for legs, (kt, R, i_max, u_max, w_max) in _limit_groups(lim):
            # legs whose drives differ each get their own lines, named by their legs
            which = "" if len(legs) == 6 else " (legs " + ", ".join(map(str, legs)) + ")"
            for sign in (1, -1) if i_max > 0 else ():
                ax.axhline(sign * i_max * kt, color="k", linestyle="--",
                           label="current_max x k_t" + which if sign > 0 else None)
            for sign in (1, -1) if w_max > 0 else ():
                ax.axvline(sign * w_max, color="k", linestyle=":",
                           label="motor_speed_max" + which if sign > 0 else None)
            if u_max > 0 and R > 0:
                w = np.linspace(-speed, speed, 201)
                for sign in (1, -1):  # the torque of the same sign as w is what the voltage caps
                    ax.plot(w, sign * (u_max - kt * np.abs(w)) * kt / R, "r-.",
                            label="voltage_max" + which if sign > 0 else None)
        ax.set_xlabel("motor speed [rad/s]")
        ax.set_ylabel("motor torque [N m]")
        ax.set_xlim(-speed, speed)
        ax.legend(fontsize="small", markerscale=4)
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)


def _limit_groups(limits: dict) -> list:
    """The driven legs (torque_constant > 0) grouped by equal (torque_constant,
    winding_resistance, current_max, voltage_max, motor_speed_max): [(legs 1-based, values)]."""
    keys = ("torque_constant", "winding_resistance", "current_max", "voltage_max",
            "motor_speed_max")
    groups: dict = {}
    for k in range(6):
        values = tuple(float(limits[key][k]) for key in keys)
        if values[0] > 0:
            groups.setdefault(values, []).append(k + 1)
    return [(legs, values) for values, legs in groups.items()]


def read_trajectory(path: Union[str, "os.PathLike[str]"]):
    """(t, poses, rates, accels) of a pose CSV as stewart-solve reads it (header t, x .. yaw,
    optionally x_dot .. yaw_dot and x_ddot .. yaw_ddot; None for a group not given)."""
    data = np.genfromtxt(path, delimiter=",", names=True, dtype=float, encoding="utf-8")
    names = data.dtype.names or ()
    missing = [c for c in ("t",) + POSE if c not in names]
    if missing:
        raise ValueError(f"{path}: no column {missing[0]} (the header must give t, x, y, z, "
                         "roll, pitch, yaw)")
    data = np.atleast_1d(data)

    def group(suffix):
        cols = [c + suffix for c in POSE]
        if not all(c in names for c in cols):
            return None
        return np.column_stack([data[c] for c in cols])
    return data["t"], group(""), group("_dot"), group("_ddot")


def _arrays(trajectory, i: int):
    """(name, t, poses, rates, accels) of one trajectory: a CSV path or (t, poses[, rates[,
    accels]]); rates and accels not given: differences of the samples (numpy.gradient)."""
    if isinstance(trajectory, (str, os.PathLike)):
        name, (t, q, qd, qdd) = str(trajectory), read_trajectory(trajectory)
    else:
        items = list(trajectory) + [None] * (4 - len(trajectory))
        name, (t, q, qd, qdd) = f"trajectory {i + 1}", items[:4]
    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    if t.ndim != 1 or t.shape[0] < 2:
        raise ValueError(f"{name}: a trajectory needs at least two times, as a (N,) array")
    if q.shape != (t.shape[0], 6):  # before numpy.gradient, whose message names no argument
        raise ValueError(f"{name}: poses has shape {q.shape}: it must be ({t.shape[0]}, 6), one "
                         "row (x, y, z, roll, pitch, yaw) per time")
    qd, qdd = (None if v is None else np.asarray(v, dtype=float) for v in (qd, qdd))
    if not np.all(np.isfinite(t)):
        raise ValueError(f"{name}: t[{np.flatnonzero(~np.isfinite(t))[0]}] is not a finite number")
    for label, values in (("poses", q), ("rates", qd), ("accels", qdd)):
        # before numpy.gradient spreads a NaN (a CSV's unreadable cell) to the rows beside it
        if values is not None and values.shape == q.shape and not np.all(np.isfinite(values)):
            j, c = np.argwhere(~np.isfinite(values))[0]
            raise ValueError(f"{name}: {label} row {j} (t = {t[j]:g}): {POSE[c]} = "
                             f"{values[j, c]} is not a finite number")
    if qd is None:
        qd = np.gradient(q, t, axis=0)
    if qdd is None:
        qdd = np.gradient(qd, t, axis=0)
    return name, t, q, qd, qdd


def sizing(platform, trajectories: Sequence, fidelity: Union[Fidelity, int, str] = Fidelity.FULL,
           keep: bool = True) -> SizingReport:
    """The sizing report of platform's drives (it must have drives: screw_lead > 0) over the
    trajectories (each a pose CSV path, or (t, poses[, rates[, accels]]) arrays: a duty cycle),
    through Platform.inverse at fidelity with t, so the voltages hold L dI/dt. keep: the report
    keeps each trajectory's InverseSolution (report.solutions, which plot draws); False for many
    long trajectories (about 1.1 kB a pose): the numbers only, one result's arrays reused.
    ValueError if the platform has no drive or a row of a trajectory does not solve (its
    message)."""
    if isinstance(trajectories, (str, os.PathLike)) or (
            isinstance(trajectories, (list, tuple)) and len(trajectories)
            and isinstance(trajectories[0], np.ndarray) and trajectories[0].ndim == 1):
        # one trajectory: its path's characters, or its t and poses, would be taken as several
        raise ValueError("trajectories is one trajectory: give a list of them, [path] or "
                         "[(t, poses)]")
    lead = parameter_value(platform, "screw_lead")
    if not np.any(lead > 0):
        raise ValueError("the platform has no drive (every screw_lead is 0): give its drives "
                         "(docs/drives.md) to size them")
    gear = parameter_value(platform, "gear_ratio")
    ratio = np.where(lead > 0, 2 * np.pi * gear / np.where(lead > 0, lead, 1), 0)
    inertia = np.where(ratio > 0, platform.reflected_mass / np.where(ratio > 0, ratio, 1) ** 2, 0)
    rows = {name: [] for name in REPORT_FIELDS}
    names, solutions = [], []
    for i, trajectory in enumerate(trajectories):
        name, t, q, qd, qdd = _arrays(trajectory, i)
        reuse = None if keep or not solutions or len(solutions[-1][1]) != len(t) else \
            solutions.pop()[1]
        sol = platform.inverse(q, qd, qdd, fidelity, t=t, out=reuse)
        bad = np.flatnonzero(sol.status != 0)
        if bad.size:
            raise ValueError(f"{name}: row {bad[0]} (t = {t[bad[0]]:g}) does not solve: "
                             f"{sol.messages.get(int(bad[0]), sol.status_name(int(bad[0])))}")
        power = sol.electrical_power
        inertia_torque = inertia * sol.motor_accel
        torque_rms = rms(t, sol.motor_torque)
        values = {
            "peak_torque": np.max(np.abs(sol.motor_torque), axis=0), "rms_torque": torque_rms,
            "peak_current": np.max(np.abs(sol.current), axis=0), "rms_current": rms(t, sol.current),
            "peak_power": np.max(np.abs(power), axis=0), "rms_power": rms(t, power),
            "peak_speed": np.max(np.abs(sol.motor_speed), axis=0),
            "energy": integral(t, power),
            "regenerated_energy": integral(t, -np.minimum(power, 0.0)),
            "inertia_share": np.divide(rms(t, inertia_torque), torque_rms,
                                       out=np.zeros(6), where=torque_rms > 0)}
        for key, v in values.items():
            rows[key].append(v)
        names.append(name)
        solutions.append((t, sol))
    if not names:
        raise ValueError("no trajectory given")
    if not keep:
        solutions = []
    limits = {n: parameter_value(platform, n) for n in
              ("current_max", "voltage_max", "motor_speed_max", "torque_constant",
               "winding_resistance")}
    return SizingReport(names=names, **{k: np.array(v) for k, v in rows.items()}, limits=limits,
                        solutions=solutions)
