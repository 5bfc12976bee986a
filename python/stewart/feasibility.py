"""The feasibility report of a trajectory (docs/moves.md): per row the first limit class met and
the margin to every class, the geometric ones of Platform.limits and the legs' speed and
acceleration; in total the worst margin of each class and when it happens.

>>> import numpy as np, stewart
>>> p = stewart.Platform()
>>> m = stewart.move(p, [0, 0, 0.5, 0, 0, 0], [0.01, 0, 0.5, 0, 0, 0], leg_accel_max=0.5)
>>> r = stewart.feasibility(p, m.t, m.pose, m.pose_rate, m.pose_accel, leg_accel_max=0.4)
>>> r.worst["leg_accel"][0] < 0 and r.names[r.first[1]] == "leg_accel"
True
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Optional

import numpy as np

from .arrays import POSE_LAYOUT, rows6, times
from .limits import LIMIT_CLASSES, MARGIN_UNITS

#: The classes of the report in check order; index + 1 is the number in Feasibility.first.
FEASIBILITY_CLASSES = LIMIT_CLASSES + ("leg_speed", "leg_accel")
#: The unit of each class's margin.
FEASIBILITY_UNITS = MARGIN_UNITS + ("m/s", "m/s^2")
#: The columns of the leg speed and acceleration classes in a report's margin and leg arrays.
SPEED, ACCEL = len(LIMIT_CLASSES), len(LIMIT_CLASSES) + 1


@dataclass
class Feasibility:
    """The report of N rows. first: (N,) the first class met (0 none, then 1 + the index in
    FEASIBILITY_CLASSES); margin: (N, len(FEASIBILITY_CLASSES)) each class's smallest margin
    (> 0 within; +inf for a leg class without its limit); leg: the same shape, the leg where it
    is (1..6; the axis for the axis class); worst: class name ->
    (the smallest margin over the rows, its time) for every class."""
    t: np.ndarray
    first: np.ndarray
    margin: np.ndarray
    leg: np.ndarray
    worst: dict

    #: The name of each number of first: "none", then FEASIBILITY_CLASSES.
    names: ClassVar[tuple] = ("none",) + FEASIBILITY_CLASSES

    @property
    def within(self) -> np.ndarray:
        """(N,) True where the row is within every limit."""
        return self.first == 0

    def __str__(self) -> str:
        lines = [f"{len(self.t)} rows, {int(np.count_nonzero(~self.within))} beyond a limit"]
        for (name, (margin, when)), unit in zip(self.worst.items(), FEASIBILITY_UNITS):
            state = "met" if margin < 0 else "within"
            lines.append(f"  {name:15s} worst margin {margin:.6g} {unit} at t = {when:.6g} s "
                         f"({state})")
        return "\n".join(lines)


def _leg_margin(values: Optional[np.ndarray], limit, n: int):
    """(margin, leg) of a leg rate against its limit (None or 0: no limit, margin +inf)."""
    if limit is None:
        return np.full(n, np.inf), np.zeros(n, np.int32)
    bound = np.broadcast_to(np.asarray(limit, dtype=float), (6,))
    if not np.all(np.isfinite(bound)) or np.any(bound < 0):
        raise ValueError(f"leg limit {np.asarray(limit).tolist()} must be finite and >= 0 "
                         "(0: no limit)")
    excess = np.where(bound > 0, bound - np.abs(values), np.inf)
    leg = np.argmin(excess, axis=1)
    return excess[np.arange(n), leg], (leg + 1).astype(np.int32)


def feasibility(platform, t, poses, rates=None, accels=None, *, leg_speed_max=None,
                leg_accel_max=None, warn_condition: Optional[float] = None) -> Feasibility:
    """The feasibility report of a trajectory: t (N,) increasing times [s], poses (N, 6) and
    their rates and accelerations (time derivatives of the pose's components; needed only for
    the leg speed and acceleration limits, which are scalars or 6 values per leg, 0 or None: no
    limit). The geometric classes are Platform.limits'; the leg speed and acceleration come
    from Platform.inverse at the kinematic level. A row the inverse cannot solve (an
    unreachable pose) raises ValueError naming it."""
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    n = q.shape[0]
    time = times("t", t, n)
    needs_rates = leg_speed_max is not None or leg_accel_max is not None
    if needs_rates and rates is None:
        raise ValueError("the leg speed and acceleration limits need the pose rates (and "
                         "accels for leg_accel_max): give rates=, accels=")
    if leg_accel_max is not None and accels is None:
        raise ValueError("leg_accel_max needs the pose accelerations: give accels=")
    check = platform.limits(q, warn_condition=warn_condition)
    margin = np.column_stack([check.margin, np.full((n, 2), np.inf)])
    leg = np.column_stack([check.leg, np.zeros((n, 2), np.int32)])
    if needs_rates:
        legs = platform.inverse(q, rates, accels, fidelity="kinematic")
        bad = np.flatnonzero(legs.status != 0)
        if bad.size:
            raise ValueError(f"row {bad[0]} (t = {time[bad[0]]:.6g} s): "
                             f"{legs.messages.get(bad[0], legs.status_name(bad[0]))}")
        for column, values, limit in ((SPEED, legs.length_rate, leg_speed_max),
                                      (ACCEL, legs.length_accel, leg_accel_max)):
            margin[:, column], leg[:, column] = _leg_margin(values, limit, n)
    first = np.where(check.first != 0, check.first, 0).astype(np.int32)
    for column in (SPEED, ACCEL):
        first = np.where((first == 0) & (margin[:, column] < 0), column + 1, first)
    worst_rows = np.argmin(margin, axis=0)
    worst = {name: (float(margin[j, c]), float(time[j]))
             for c, (name, j) in enumerate(zip(FEASIBILITY_CLASSES, worst_rows))}
    return Feasibility(time, first, margin, leg, worst)
