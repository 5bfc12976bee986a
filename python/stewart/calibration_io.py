"""Calibration files: the measurement CSV (x, y, z, roll, pitch, yaw, L1..L6 per pose) and the
platform file (a JSON object of table parameter names, arrays as lists: an FMU parameter set).
Every error names the file, its line and column; nothing is half read."""
from __future__ import annotations

import csv
import json
import math
import os
import stat
from dataclasses import dataclass

import numpy as np

from .calibration_checks import MAX_POSES
from .platform import Platform

MAX_CSV_BYTES = 64 * 2 ** 20  # a CSV read whole; 20,000 poses take about 6 MB
MEASUREMENT_COLUMNS = ("x", "y", "z", "roll", "pitch", "yaw", "L1", "L2", "L3", "L4", "L5", "L6")


class FileError(ValueError):
    """A file that cannot be used: the message names the file, and the line and column."""


@dataclass(frozen=True)
class Measurements:
    """poses (N, 6) of the tool frame in the user frame, readings (N, 6), and the file line of
    each row (to name a pose in a report)."""
    poses: np.ndarray
    readings: np.ndarray
    lines: list[int]


def read_measurements(path: str) -> Measurements:
    """The measurement CSV at path: a header naming the 12 columns (any order; nothing else),
    then one pose per line of 12 finite numbers; blank lines and lines starting with # are
    skipped; a UTF-8 byte order mark (a spreadsheet's "CSV UTF-8") is read past. FileError
    naming the line and column of the first problem, or the number of rows when there are more
    than calibrate takes."""
    try:
        status = os.stat(path)
    except OSError as e:
        raise FileError(f"{path}: cannot be read ({e})") from None
    if not stat.S_ISREG(status.st_mode):
        raise FileError(f"{path}: not a regular file (a measurement CSV is read whole)")
    if status.st_size > MAX_CSV_BYTES:
        raise FileError(f"{path}: {status.st_size} bytes, larger than a calibration's "
                        f"{MAX_CSV_BYTES} (at most {MAX_POSES} poses)")
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise FileError(f"{path}: cannot be read ({e})") from None
    rows = [(number, text) for number, text in enumerate(lines, start=1)
            if text.strip() and not text.lstrip().startswith("#")]
    if not rows:
        raise FileError(f"{path}: no header: the first line must name the columns "
                        f"{','.join(MEASUREMENT_COLUMNS)}")
    if len(rows) - 1 > MAX_POSES:
        raise FileError(f"{path}: {len(rows) - 1} measurement rows; a calibration takes at most "
                        f"{MAX_POSES} (tens of well-spread poses identify a machine: "
                        f"stewart.calibration_poses chooses them): give a subset")
    header_line, header_text = rows[0]
    header = [name.strip() for name in next(csv.reader([header_text]))]
    for column, name in enumerate(header, start=1):
        if name not in MEASUREMENT_COLUMNS:
            raise FileError(f"{path} line {header_line} column {column}: unknown column "
                            f"'{name}' (the columns are {','.join(MEASUREMENT_COLUMNS)})")
        if header.index(name) != column - 1:
            raise FileError(f"{path} line {header_line} column {column}: column '{name}' "
                            f"appears twice")
    missing = [name for name in MEASUREMENT_COLUMNS if name not in header]
    if missing:
        raise FileError(f"{path} line {header_line}: missing column(s) {','.join(missing)}")
    order = [header.index(name) for name in MEASUREMENT_COLUMNS]
    values, numbers = [], []
    for number, text in rows[1:]:
        fields = next(csv.reader([text]))
        if len(fields) != len(header):
            raise FileError(f"{path} line {number}: {len(fields)} values, the header has "
                            f"{len(header)}")
        row = []
        for column, field in enumerate(fields, start=1):
            try:
                value = float(field)
            except ValueError:
                raise FileError(f"{path} line {number} column {column} ({header[column - 1]}): "
                                f"'{field.strip()}' is not a number") from None
            if not math.isfinite(value):
                raise FileError(f"{path} line {number} column {column} ({header[column - 1]}): "
                                f"{field.strip()} is not finite")
            row.append(value)
        values.append([row[i] for i in order])
        numbers.append(number)
    if not values:
        raise FileError(f"{path}: no measurement after the header (line {header_line})")
    data = np.array(values)
    return Measurements(poses=data[:, :6].copy(), readings=data[:, 6:].copy(), lines=numbers)


def read_platform(path: str) -> Platform:
    """The platform file at path (Platform.from_file), or FileError with the library's message
    (the file, the line and the field)."""
    try:
        return Platform.from_file(path)
    except (OSError, ValueError) as e:  # ParameterError is a ValueError
        raise FileError(f"{path}: {e}" if str(path) not in str(e) else str(e)) from None


def platform_file_text(platform: Platform) -> str:
    """platform's parameters as a platform file: a JSON object of table names, arrays as lists
    (full precision), which stewart-solve --platform, Platform.from_file and an FMU take."""
    params = {}
    for name, value in platform.params.items():
        array = np.asarray(value, dtype=float)
        params[name] = float(array) if array.ndim == 0 else [float(v) for v in array]
    return json.dumps(params, indent=2) + "\n"
