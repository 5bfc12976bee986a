"""The units of a sweep's results: SI inside (chunks, spec), the user's length and angle units in
the merged tables, the CSV, volume.json and the plots when asked (`--units mm,deg`)."""
from __future__ import annotations

from dataclasses import dataclass

from .. import _core
from ..limits import POSE_CLASSES

# What an SI value is multiplied by in each unit: the library's one table (stewart_unit_per_si,
# as stewart-solve --units and the check).
LENGTHS = {name: _core.unit_per_si(name)[1] for name in ("m", "mm", "um")}
ANGLES = {name: _core.unit_per_si(name)[1] for name in ("rad", "deg", "mrad", "urad")}

# The SI quantity of each result column: L length, A angle, L/s, L/s2 rates of lengths; the rest
# (forces, powers, condition numbers, times, counts) do not change with the units.
_KIND = {
    **{c: "L" for c in ("x", "y", "z", "payload_com_x", "payload_com_y", "payload_com_z",
                        "length_min", "length_max", "stroke_used", "margin_stroke",
                        "margin_interference", *[f"L{k}" for k in range(1, 7)])},
    **{c: "A" for c in ("roll", "pitch", "yaw", "margin_base_joint", "margin_platform_joint")},
    "peak_length_rate": "L/s", "peak_length_accel": "L/s2",
}
_OTHER = {**{f"peak_force_{k}": "N" for k in range(1, 7)}, **{f"F{k}": "N" for k in range(1, 7)},
          "peak_power": "W", "payload_mass": "kg", "limit_t": "s", "condition": "1",
          "max_condition": "1", "min_inverse_condition": "1", "margin_condition": "1",
          # the nearest software position limit's axis: m for x, y, z, rad for the angles (so
          # it stays SI whatever the units asked)
          "margin_axis": "m or rad"}
assert all(f"margin_{c}" in {**_KIND, **_OTHER} for c in POSE_CLASSES)


@dataclass(frozen=True)
class Units:
    """A length unit and an angle unit of LENGTHS and ANGLES."""
    length: str = "m"
    angle: str = "rad"

    @classmethod
    def parse(cls, text: str) -> "Units":
        """'mm,deg' (either order, either alone; the other stays SI). ValueError names what
        is not a unit."""
        length, angle = "m", "rad"
        for word in (w.strip() for w in str(text).split(",")):
            if word in LENGTHS:
                length = word
            elif word in ANGLES:
                angle = word
            else:
                raise ValueError(f"units = {text!r}: {word!r} is neither a length unit "
                                 f"({', '.join(LENGTHS)}) nor an angle unit ({', '.join(ANGLES)})")
        return cls(length, angle)

    @property
    def si(self) -> bool:
        return (self.length, self.angle) == ("m", "rad")

    def factor(self, column: str) -> float:
        """What an SI value of the column is multiplied by."""
        kind = _KIND.get(column)
        if kind is None:
            return 1.0
        return ANGLES[self.angle] if kind == "A" else LENGTHS[self.length]

    def unit(self, column: str) -> str:
        """The column's unit ("" for text, flags, indices)."""
        kind = _KIND.get(column)
        if kind is None:
            return _OTHER.get(column, "")
        return {"L": self.length, "A": self.angle, "L/s": f"{self.length}/s",
                "L/s2": f"{self.length}/s^2"}[kind]

    def axis(self, component: str) -> float:
        """The factor of a pose component (x .. yaw)."""
        return self.factor(component)
