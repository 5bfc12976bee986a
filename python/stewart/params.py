"""Platform parameters by name: the one place where Python names become library assignments.

The names are the FMU's (and `stewart-solve --param`'s): scalars by name (``payload_mass``),
arrays as sequences (``base_angle=[...]``) that become ``base_angle[1]`` .. ``base_angle[6]``
(elements counted from 1). The library checks every name (`stewart_params_set`, which also
suggests the nearest name on a typo) and every value (when the model is built); Python keeps no
copy of the parameter list. When the library's parameter table lands, this module is the one to
switch to it.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Union

import numpy as np

from . import _core
from .errors import ParameterError

ParameterValue = Union[float, Sequence[float], np.ndarray]


def parameter_assignments(params: Mapping[str, ParameterValue]) -> list[tuple[str, float]]:
    """(library name, value) pairs for a mapping of parameter names to scalars or sequences.

    Raises ParameterError for a name the library does not know, and for an array given with the
    wrong number of elements (too many: the library refuses the extra element's name; too few:
    the library knows one more element than was given)."""
    assignments: list[tuple[str, float]] = []
    for name, value in params.items():
        values = np.asarray(value, dtype=float)
        if values.ndim == 0:
            _require_known(name)
            assignments.append((name, float(values)))
            continue
        if values.ndim != 1 or values.size == 0:
            raise ParameterError(f"{name} = {value!r}: give a number or a flat sequence of numbers")
        for k, v in enumerate(values, start=1):
            _require_known(f"{name}[{k}]", whole=name)
            assignments.append((f"{name}[{k}]", float(v)))
        if _core.parameter_known(f"{name}[{values.size + 1}]")[0]:
            raise ParameterError(f"{name} has {values.size} values: it needs one per element "
                                 f"({name}[{values.size + 1}] exists)")
    return assignments


def _require_known(name: str, whole: str | None = None) -> None:
    known, message = _core.parameter_known(name)
    if not known:
        raise ParameterError(f"{whole}: {message}" if whole else message)
