"""Platform parameters by name: the one place where Python names become library assignments.

The names are the FMU's (and `stewart-solve --param`'s), from the library's parameter table
(stewart_table.h): scalars by name (``payload_mass``), arrays as sequences (``base_angle=[...]``)
that become ``base_angle[1]`` .. ``base_angle[6]`` (elements counted from 1); a per-leg
parameter that was a scalar (``stroke_min``) also takes one number, which fills every leg.
The library sets each element (`stewart_params_set`, which names the nearest parameter on a
typo) and checks every value when the model is built; Python keeps no copy of the parameter list.
"""
from __future__ import annotations

import functools
import os
import pathlib
from collections.abc import Mapping, Sequence
from typing import Any, Union

import numpy as np

from . import _core
from .errors import ParameterError

ParameterValue = Union[float, Sequence[float], np.ndarray]


@functools.lru_cache(maxsize=1)
def _table() -> tuple[dict[str, Any], ...]:
    return tuple(_core.parameter_table())


def parameters() -> list[dict[str, Any]]:
    """The library's parameter table, one dict per parameter in declaration order: name, count
    (1, 3 for x y z, 6 for legs 1..6, 18 for x y z of legs 1..6), unit (SI), description,
    defaults (the thesis platform), min and max (the valid range of each element), scalar_fills
    (one number given for it fills every leg)."""
    return [dict(p) for p in _table()]


def parameter_assignments(params: Mapping[str, ParameterValue]) -> list[tuple[str, float]]:
    """(library name, value) pairs for a mapping of parameter names to scalars or sequences.

    Raises ParameterError for a name the library does not know (with its nearest name) and for a
    value with the wrong number of elements."""
    counts = {p["name"]: p["count"] for p in _table()}
    fills = {p["name"] for p in _table() if p["scalar_fills"]}
    assignments: list[tuple[str, float]] = []
    for name, value in params.items():
        try:
            values = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ParameterError(f"{name} = {value!r} is not a number") from None
        count = counts.get(name)
        if count is None:  # an unknown name, or one element ("base_angle[2]") by its own name
            known, message = _core.parameter_known(name)
            if not known:
                raise ParameterError(message)
            count = 1
        if name in fills and values.ndim == 0:
            assignments.append((name, float(values)))  # the library fills every leg
            continue
        if count == 1:
            if values.ndim != 0:
                raise ParameterError(f"{name} = {value!r} must be one number")
            assignments.append((name, float(values)))
            continue
        if values.shape != (count,):
            raise ParameterError(f"{name} has {values.size} values ({value!r}): it needs {count}, "
                                 f"one per element {name}[1]..{name}[{count}]")
        assignments.extend((f"{name}[{k}]", float(v)) for k, v in enumerate(values, start=1))
    return assignments


def parameter_values(params: Mapping[str, ParameterValue]) -> dict[str, np.ndarray]:
    """Every parameter's values (an array of its count) for a mapping of parameter names to
    values, as the library takes them: the defaults (the thesis platform) with params applied,
    a whole array, one element (``gear_ratio[2]``) or one number that fills every leg."""
    values = {p["name"]: np.array(p["defaults"], dtype=float) for p in _table()}
    for name, value in parameter_assignments(params):
        base, _, index = name.partition("[")
        if index:
            values[base][int(index.rstrip("]")) - 1] = value
        else:
            values[base][:] = value  # a scalar, or one number that fills every leg
    return values


def option_values(**options: Any) -> list[tuple[str, float]]:
    """(name, value) pairs of the options given (None: the library's default), or ParameterError
    naming an option whose value is not a number."""
    pairs = []
    for name, value in options.items():
        if value is None:
            continue
        try:
            pairs.append((name, float(value)))
        except (TypeError, ValueError):
            raise ParameterError(f"{name} = {value!r} is not a number") from None
    return pairs


def read_platform_file(path: Union[str, "os.PathLike[str]"]) -> dict[str, ParameterValue]:
    """The parameters a platform file gives (docs/geometry.md), read and checked by the library
    (the reader of ``--platform``, which also converts the file's units to SI and its
    stroke_neutral and stroke_travel to stroke_min and stroke_max): scalars as floats, arrays as
    lists. ParameterError names the file, the line and column, and the field; a path that is not
    a regular file, or one larger than PLATFORM_FILE_MAX_BYTES (1 MiB), is refused at once."""
    try:
        fields = _core.read_platform_file(os.fsdecode(os.fspath(path)))
    except ValueError as e:
        raise ParameterError(f"{path}: {e}") from None
    return {name: values[0] if len(values) == 1 else list(values) for name, values in fields}


#: The largest platform file read, in bytes (the library's STEWART_PLATFORM_FILE_MAX_BYTES).
PLATFORM_FILE_MAX_BYTES: int = _core.PLATFORM_FILE_MAX_BYTES


def platform_files() -> dict[str, pathlib.Path]:
    """The platform files shipped with the package, by name (the file's stem): "thesis",
    "paired_hexapod", "genhexkins", "non_planar" and the real machines "rubin_camera_hexapod",
    "rubin_m2_hexapod", "simona_motion_base", and two of them with electric drives,
    "rubin_m2_hexapod_drives", "simona_motion_base_drives" (platforms/README.md says where each
    comes from)."""
    folder = pathlib.Path(__file__).resolve().parent / "platforms"
    return {p.stem: p for p in sorted(folder.glob("*.json"))}
