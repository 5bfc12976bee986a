"""The check a user runs first on a platform (Platform.check, `stewart-solve --check`): the home
pose against every limit, the axis ranges it leaves, and hints in words where the numbers look
like an entry mistake (stewart/stewart_check.h, docs/geometry.md)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _core
from .limits import AxisRanges, LimitCheck
from .limits import check as check_limits
from .limits import ranges as limit_ranges

#: The hints' names and their library bits.
HINTS = {"units": _core.CHECK_UNITS, "swapped_legs": _core.CHECK_SWAPPED_LEGS,
         "frame": _core.CHECK_FRAME}


@dataclass
class HomeCheck:
    """What the check of a platform's home pose finds. str() gives the report as
    `stewart-solve --check` prints it."""
    home: np.ndarray        #: (6,) the home pose (the tool in the user frame) [m, rad]
    length: np.ndarray      #: (6,) each leg's joint-to-joint length at home [m]
    stroke_min: np.ndarray  #: (6,) each leg's stroke [m]
    stroke_max: np.ndarray  #: (6,)
    joint_spread: float     #: the largest distance between two joints of one plate [m]
    limits: LimitCheck      #: the limit check at home (one row)
    ranges: AxisRanges      #: the axis ranges from home (one row)
    crossing: tuple         #: the first two legs (1..6) that cross seen from above, else (0, 0)
    hints: frozenset        #: names of HINTS that apply: "units", "swapped_legs", "frame"
    valid: bool             #: home is within every limit
    text: str               #: the report as text, in `units`
    units: tuple = ("m", "deg")  #: (length, angle) units of the text; the fields stay SI

    def __str__(self) -> str:
        return self.text


def text_units(file_units: tuple, units: Optional[str]) -> tuple:
    """The check text's (length, angle) units: the words of units ("mm,deg", either order,
    either alone; the names a platform file may use, stewart_unit_per_si) over file_units (a
    platform file's, "" where it states none), m and deg where neither says. ValueError names a
    word that is not a unit."""
    length, angle = file_units[0] or "m", file_units[1] or "deg"
    for word in ([] if units is None else str(units).split(",")):
        found = _core.unit_per_si(word.strip())
        if found is None:
            raise ValueError(f"units = {units!r}: {word.strip()!r} is neither a length unit (m, "
                             "cm, mm, um, nm, in) nor an angle unit (rad, deg, mrad, urad)")
        if found[0] == "m":
            length = word.strip()
        else:
            angle = word.strip()
    return length, angle


def check_home(model, warn_condition: Optional[float], units: tuple = ("m", "deg")) -> HomeCheck:
    """The check of model's home pose (warn_condition None: the library's default), its text in
    units (length, angle)."""
    d = _core.check_home(model, warn_condition, *units)
    home = np.array(d["home"])
    q = home.reshape(1, 6).copy()
    return HomeCheck(
        home=home, length=np.array(d["length"]), stroke_min=np.array(d["stroke_min"]),
        stroke_max=np.array(d["stroke_max"]), joint_spread=float(d["joint_spread"]),
        limits=check_limits(model, q, warn_condition), ranges=limit_ranges(model, q, warn_condition),
        crossing=tuple(d["crossing"]),
        hints=frozenset(name for name, bit in HINTS.items() if d["hints"] & bit),
        valid=bool(d["valid"]), text=d["text"], units=tuple(units))
