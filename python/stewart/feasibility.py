"""The feasibility report of a trajectory (docs/moves.md): per row the first limit class met and
the margin to every class of Platform.limits (the geometric ones, and the legs' speed,
acceleration, jerk and force where the trajectory gives their data); in total the worst margin of
each class and when it happens.

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
from .limits import LEG_LIMITS, LIMIT_CLASSES, MARGIN_UNITS, leg_limits_of, with_leg_limits

#: The classes of the report in check order (Platform.limits'); index + 1 is the number in
#: Feasibility.first.
FEASIBILITY_CLASSES = LIMIT_CLASSES
#: The unit of each class's margin.
FEASIBILITY_UNITS = MARGIN_UNITS
#: The columns of the leg classes in a report's margin and leg arrays.
SPEED, ACCEL, JERK, FORCE = (LIMIT_CLASSES.index(c) for c in
                             ("leg_speed", "leg_accel", "leg_jerk", "leg_force"))


@dataclass
class Feasibility:
    """The report of N rows. first: (N,) the first class met (0 none, then 1 + the index in
    FEASIBILITY_CLASSES); margin: (N, len(FEASIBILITY_CLASSES)) each class's smallest margin
    (> 0 within; +inf for a leg class without its limit or its data); leg: the same shape, the
    leg where it is (1..6; the axis for the axis class); leg_margin: (N, classes, 6) each leg's
    own; worst: class name -> (the smallest margin over the rows, its time) for every class;
    unchecked: the leg classes with a limit on the platform but no data in the trajectory."""
    t: np.ndarray
    first: np.ndarray
    margin: np.ndarray
    leg: np.ndarray
    leg_margin: np.ndarray
    worst: dict
    unchecked: tuple = ()

    #: The name of each number of first: "none", then FEASIBILITY_CLASSES.
    names: ClassVar[tuple] = ("none",) + FEASIBILITY_CLASSES

    @property
    def within(self) -> np.ndarray:
        """(N,) True where the row is within every limit."""
        return self.first == 0

    def __str__(self) -> str:
        lines = [f"{len(self.t)} rows, {int(np.count_nonzero(~self.within))} beyond a limit"]
        for (name, (margin, when)), unit in zip(self.worst.items(), FEASIBILITY_UNITS):
            if name in self.unchecked:
                lines.append(f"  {name:15s} not checked: the trajectory has no data for it")
                continue
            state = "met" if margin < 0 else "within"
            lines.append(f"  {name:15s} worst margin {margin:.6g} {unit} at t = {when:.6g} s "
                         f"({state})")
        return "\n".join(lines)


def _unchecked(limits: dict, data: dict) -> tuple:
    """The leg classes that have a limit on some leg but no data."""
    return tuple(c for c, name in zip(LIMIT_CLASSES[SPEED:], LEG_LIMITS)
                 if np.any(limits[name] > 0) and data[name] is None)


def feasibility(platform, t, poses, rates=None, accels=None, jerks=None, *, forces=None,
                leg_speed_max=None, leg_accel_max=None, leg_jerk_max=None, leg_force_max=None,
                warn_condition: Optional[float] = None) -> Feasibility:
    """The feasibility report of a trajectory: t (N,) increasing times [s], poses (N, 6) and
    their rates, accelerations and jerks (time derivatives of the pose's components; the leg
    speed, acceleration and jerk classes need them), forces (N, 6) the legs' forces [N] or a
    fidelity ("massless", "full") to compute them with Platform.inverse (the leg force class).
    The leg limits are the platform's leg_speed_max, leg_accel_max, leg_jerk_max,
    leg_force_max unless given here (a scalar or 6 values per leg; 0: no limit); a limit given
    here without its data raises ValueError, one of the platform's is reported as unchecked.
    The classes and margins are Platform.limits'; a row the check refuses (a non-finite value,
    a leg of zero length with rates given) raises ValueError naming it."""
    q = rows6("poses", poses, None, "poses", POSE_LAYOUT)
    n = q.shape[0]
    time = times("t", t, n)
    data = {"leg_speed_max": rates, "leg_accel_max": accels, "leg_jerk_max": jerks,
            "leg_force_max": forces}
    needs = {"leg_speed_max": "rates=", "leg_accel_max": "rates= and accels=",
             "leg_jerk_max": "rates=, accels= and jerks=", "leg_force_max": "forces="}
    given = dict(zip(LEG_LIMITS, (leg_speed_max, leg_accel_max, leg_jerk_max, leg_force_max)))
    for name, value in given.items():
        if value is not None and np.any(np.asarray(value) != 0) and data[name] is None:
            raise ValueError(f"{name} needs the trajectory's data: give {needs[name]}")
    limited = with_leg_limits(platform, **given)
    check = limited.limits(q, rates, accels, jerks, forces=forces, warn_condition=warn_condition)
    margin, leg = check.margin, check.leg
    worst_rows = np.argmin(margin, axis=0)
    worst = {name: (float(margin[j, c]), float(time[j]))
             for c, (name, j) in enumerate(zip(FEASIBILITY_CLASSES, worst_rows))}
    return Feasibility(time, check.first.copy(), margin, leg, check.leg_margin, worst,
                       _unchecked(leg_limits_of(limited), data))
