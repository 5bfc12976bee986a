"""Enumerations a caller may give by member, number or name, with errors naming the argument."""
from __future__ import annotations

import enum

from .errors import ParameterError


class Choice(enum.IntEnum):
    """An IntEnum whose `of` accepts a member, its number or its name (any case); subclasses set
    ARGUMENT, the argument name that errors quote."""

    @classmethod
    def of(cls, value):
        """The member for value, or ParameterError naming the argument, the value and the
        choices."""
        if isinstance(value, cls):
            return value
        if isinstance(value, str):
            try:
                return cls[value.upper()]
            except KeyError:
                names = ", ".join(m.name.lower() for m in cls)
                raise ParameterError(f"{cls._argument()} = {value!r} must be one of {names}") from None
        try:
            number = int(value)
            if number != value:  # 1.5 names no member: not truncated to 1
                raise ValueError(value)
            return cls(number)
        except (ValueError, TypeError, OverflowError):
            numbers = ", ".join(f"{m.value} ({m.name.lower()})" for m in cls)
            raise ParameterError(f"{cls._argument()} = {value!r} must be one of {numbers}") from None

    @classmethod
    def _argument(cls) -> str:
        # looked up only for an error: an Enum class's missing attribute costs microseconds
        return getattr(cls, "ARGUMENT", cls.__name__.lower())


class Fidelity(Choice):
    """The library's fidelity levels (stewart_fidelity); Fidelity.of takes a member, its number
    or its name ("kinematic", "massless", "full")."""
    KINEMATIC = 0  #: lengths, rates, accelerations; forces zero
    MASSLESS = 1   #: plus forces, legs as massless two-force members
    FULL = 2       #: the 14-body constraint-and-multiplier model
