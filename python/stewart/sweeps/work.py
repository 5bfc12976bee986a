"""The work of one chunk, run on a Dask worker (or in-process): poses in, a pyarrow Table out.

Each chunk starts from fresh data blocks and depends only on the spec and its own row range, so
a result is the same bit for bit whichever worker computes it and however many there are."""
from __future__ import annotations

import itertools
import threading
import time
from typing import Callable, Optional

import numpy as np
import pyarrow as pa

from .. import _core
from ..inverse import INVERSE_TABLE, InverseSolution, empty_inverse_solution
from ..limits import LIMIT_CLASSES, POSE_CLASSES, LimitCheck, smallest_margins
from ..platform import Platform, _warn_condition
from ..scenes import POSE
from ..sizing import rms
from .spec import Chunk, manoeuvre_samples

LEGS = range(1, 7)


def envelope_cases(spec: dict):
    """Every case as (payload_mass, payload_com, manoeuvre index, amplitude, frequency, fidelity),
    in the fixed order the chunks cut."""
    variants = [(i, a, f) for i, m in enumerate(spec["manoeuvres"])
                for a in m["amplitude"] for f in m["frequency"]]
    for mass, com, (i, a, f), level in itertools.product(
            spec["payload_mass"], spec["payload_com"], variants, spec["fidelity"]):
        yield mass, com, i, a, f, level


#: The drives' numbers per leg (docs/drives.md; null for a platform without drives).
ENVELOPE_DRIVE_METRICS = [f"{name}_{k}" for name in (
    "peak_motor_torque", "rms_motor_torque", "peak_current", "peak_motor_speed",
    "peak_electrical_power") for k in LEGS]
ENVELOPE_METRICS = ([f"peak_force_{k}" for k in LEGS] +
                    ["peak_length_rate", "peak_length_accel", "length_min", "length_max",
                     "stroke_used", "max_condition", "min_inverse_condition", "peak_power"] +
                    ENVELOPE_DRIVE_METRICS)


def envelope_metrics(sol: InverseSolution, t: np.ndarray, drives: bool) -> list[float | None]:
    """Per case: peak |F_k| per leg [N], peak |dL/dt| [m/s] and |d2L/dt2| [m/s^2] over legs,
    shortest and longest length [m], stroke used (the largest length excursion of one leg [m]),
    largest condition number and its reciprocal (the smallest distance to a singularity, 0 at
    one; null at the kinematic level, which computes no condition), peak |sum_k F_k dL_k/dt| [W];
    with drives, per leg the peak and time-weighted RMS motor torque [N m], peak current [A],
    motor speed [rad/s] and electrical power [W] (stewart.sizing's numbers)."""
    cond = float(sol.condition.max())
    excursion = (sol.length.max(axis=0) - sol.length.min(axis=0)).max()
    if drives:
        per_leg = [np.abs(sol.motor_torque).max(axis=0), rms(t, sol.motor_torque),
                   np.abs(sol.current).max(axis=0), np.abs(sol.motor_speed).max(axis=0),
                   np.abs(sol.electrical_power).max(axis=0)]
        drive = [float(v) for values in per_leg for v in values]
    else:
        drive = [None] * len(ENVELOPE_DRIVE_METRICS)
    return ([float(v) for v in np.abs(sol.force).max(axis=0)] +
            [float(np.abs(sol.length_rate).max()), float(np.abs(sol.length_accel).max()),
             float(sol.length.min()), float(sol.length.max()), float(excursion),
             cond if cond > 0 else None, 1.0 / cond if cond > 0 else None,
             float(np.abs(sol.power).max())] + drive)


ENVELOPE_LIMITS = ["feasible", "limit_class", "limit_t", *[f"margin_{c}" for c in POSE_CLASSES]]


def envelope_limits(platform: Platform, t: np.ndarray, q: np.ndarray,
                    warn_condition) -> list:
    """Per case, Platform.limits over its poses: feasible (every pose within every limit), the
    first class met (0: none) and the time of the first pose beyond a limit (None: none), and
    each class's smallest margin over the poses [m, rad, rad, m, 1]."""
    check = platform.limits(q, warn_condition=warn_condition)
    beyond = np.flatnonzero(~check.within)
    first = int(beyond[0]) if beyond.size else None
    return [first is None, 0 if first is None else int(check.first[first]),
            None if first is None else float(t[first]),
            *[float(v) for v in smallest_margins(platform, check)[:len(POSE_CLASSES)]]]


def envelope_chunk(spec: dict, chunk: Chunk) -> tuple[pa.Table, dict]:
    """Cases [chunk.start, chunk.stop): one row each, failures with status and message, and
    every case's limits (a case beyond a limit is a row like any other: its limit class, where
    and by how much)."""
    started = time.perf_counter()
    cases = itertools.islice(envelope_cases(spec), chunk.start, chunk.stop)
    platforms: dict[tuple, Platform] = {}
    columns: dict[str, list] = {k: [] for k in (
        "case", "fidelity", "payload_mass", "payload_com_x", "payload_com_y", "payload_com_z",
        "manoeuvre", "amplitude", "frequency", "poses", *ENVELOPE_METRICS, *ENVELOPE_LIMITS,
        "status", "message")}
    warn_condition = _warn_condition(spec["options"].get("warn_condition"))
    limits: dict[tuple, list] = {}  # the limits do not depend on the payload or the level
    poses = 0
    for case, (mass, com, i, a, f, level) in enumerate(cases, start=chunk.start):
        key = (mass, tuple(com))
        if key not in platforms:
            platforms[key] = Platform(**spec["platform"], payload_mass=mass, payload_com=com)
        m = spec["manoeuvres"][i]
        t, q, qd, qdd = manoeuvre_samples(spec, m, a, f)
        drives = _core.model_has_drives(platforms[key]._model)
        sol = platforms[key].inverse(q, qd, qdd, fidelity=level, max_messages=1,
                                     t=t if drives else None, **spec["options"])
        if (i, a, f) not in limits:
            limits[(i, a, f)] = envelope_limits(platforms[key], t, q, warn_condition)
        within = limits[(i, a, f)]
        poses += len(t)
        failed = np.flatnonzero(~sol.ok)
        if failed.size:
            j = int(failed[0])
            metrics = [None] * len(ENVELOPE_METRICS)
            status = int(sol.status[j])
            message = f"row {j + 1} (t = {t[j]:g} s): {sol.status_name(j)}: {sol.messages[j]}"
            within = [False, *within[1:]]
        else:
            metrics, status, message = envelope_metrics(sol, t, drives), 0, ""
        row = [case, level, mass, *com, m["name"], a, f, len(t), *metrics, *within, status, message]
        for name, value in zip(columns, row):
            columns[name].append(value)
    stats = {"seconds": time.perf_counter() - started, "poses": poses, "cases": chunk.stop - chunk.start}
    # Typed columns: a chunk whose cases all failed (null metrics) or met no limit (null
    # limit_t) has the same schema as the others.
    types = {**{k: pa.float64() for k in ENVELOPE_METRICS + ENVELOPE_LIMITS[2:]},
             "feasible": pa.bool_(), "limit_class": pa.int8()}
    return pa.table({k: pa.array(v, type=types.get(k)) for k, v in columns.items()}), stats


#: Rows solved and checked at a time within a workspace chunk at the kinematic and massless
#: levels, whose rows are independent (the same bits at any place in a batch): the solver's and
#: the limit check's arrays (about 470 B a row) are then this many rows, not the chunk's.
BLOCK_ROWS = 65536


class _Scratch:
    """One worker thread's arrays for workspace chunks of n rows, kept from one chunk to the
    next: fresh arrays cost their first touch (page faults, the kernel zeroing pages) in every
    chunk. The table's columns (one array row each, about 220 B a pose) are n rows (a chunk, or
    a block when the chunk is written block by block), the solver's and limit check's a block. Only for a table written before the next chunk
    starts (compute_chunk writing its own file): the table's columns are views of these arrays."""

    def __init__(self, n: int, n_axes: int, block: int):
        self.n, self.block = n, block
        self.row = np.empty(n, np.int64)
        self.ramp = np.arange(n, dtype=np.int64)     # 0, 1, ..., n - 1
        self.rest = np.empty(n, np.int64)
        self.codes = np.empty((2, n), np.int32)      # the slice and message columns' indices
        self.index = np.empty((n_axes, n), np.int64)  # one row per axis: the table's columns
        self.pose = np.empty((6, n))                 # the poses, one row per component
        self.q = np.empty((block, 6))                # a block of them as the library reads them
        self.sol = empty_inverse_solution(block)
        k = len(LIMIT_CLASSES)
        self.leg_margin = np.empty((block, k * 6))
        self.check = LimitCheck(np.empty(block, np.int32), np.empty(block, np.int32),
                                np.empty((block, k)), np.empty((block, k), np.int32),
                                np.empty((block, k), np.int32), np.empty(block),
                                self.leg_margin.reshape(block, k, 6))
        self.status = np.empty(n, self.sol.status.dtype)
        self.condition = np.empty(n)
        self.margin = np.empty((len(POSE_CLASSES), n))  # the poses' classes: no rates here
        self.length = np.empty((6, n))
        self.force = np.empty((6, n))
        self.limit_class = np.empty(n, np.int8)
        self.reachable = np.empty(n, bool)

    def rows(self, m: int) -> tuple[np.ndarray, InverseSolution, LimitCheck]:
        """The block arrays' first m rows (C-contiguous views: out= takes them)."""
        if m == self.block:
            return self.q, self.sol, self.check
        sol = InverseSolution(**{name: getattr(self.sol, name)[:m]
                                 for name, _, _ in INVERSE_TABLE.columns})
        c = self.check
        return self.q[:m], sol, LimitCheck(c.first[:m], c.failed[:m], c.margin[:m], c.leg[:m],
                                           c.other_leg[:m], c.condition[:m], c.leg_margin[:m])


# Per thread: a worker process with several threads computes chunks side by side.
_scratch = threading.local()


def _scratch_for(n: int, n_axes: int, block: int) -> _Scratch:
    """This thread's arrays for chunks of n rows (one size at a time: a sweep's chunks all have
    one size but its slices' last ones)."""
    b = getattr(_scratch, "arrays", None)
    if b is None or (b.n, b.index.shape[0], b.block) != (n, n_axes, block):
        _scratch.arrays = None  # free the old ones first
        b = _scratch.arrays = _Scratch(n, n_axes, block)
    return b


def workspace_chunk(spec: dict, chunk: Chunk, reuse: bool = False,
                    write: Optional[Callable[[pa.Table], None]] = None) -> tuple[Optional[pa.Table], dict]:
    """Poses [chunk.start, chunk.stop) of one slice at rest: status, reachability within every
    limit (Platform.limits: stroke, joint angles, leg interference, the condition number against
    the options' warn_condition), the first failing limit class and the margin to each,
    condition, lengths and static forces for the spec's platform and payload.

    reuse: build the chunk in this thread's arrays of the previous chunk (_Scratch) instead of
    fresh ones; the table's columns are then views of them, valid only until the next call with
    reuse (write it first). The values are the same either way.

    write: instead of returning one table, hand the chunk's rows to write block by block (one
    table of BLOCK_ROWS rows at a time, in row order, at the kinematic and massless levels; a
    ParquetWriter's write_table, one row group each), each valid only until write returns; the
    table's columns are then block-sized too, not chunk-sized. Returns (None, stats). The rows
    are the same as the one table's, bit for bit (the message column dictionary-encoded per
    block)."""
    started = time.perf_counter()
    s = next(x for x in spec["slices"] if x["name"] == chunk.part)
    n = chunk.stop - chunk.start
    axes = list(s["axes"].items())
    # The full level starts each pose from the previous solution: one block, as one call.
    block = n if spec["fidelity"] == "full" else min(n, BLOCK_ROWS)
    # Rows per table: the whole chunk, or one block when each block is written as it is done.
    rows = block if write is not None else n
    b = _scratch_for(rows, len(axes), block) if reuse else _Scratch(rows, len(axes), block)
    platform = Platform(**spec["platform"])
    warn_condition = _warn_condition(spec["options"].get("warn_condition"))
    values = [np.asarray(v, dtype=float) for _, v in axes]
    table = None
    for start in range(0, n, rows):
        m = min(rows, n - start)
        row, pose = _grid_poses(b, s, axes, values, chunk.start + start, m)
        messages = _solve_and_check(b, platform, spec, warn_condition, pose, m, block)
        table = _workspace_table(b, s, row, pose, m, messages)
        if write is not None:
            write(table)
            table = None
    stats = {"seconds": time.perf_counter() - started, "poses": n, "cases": 0}
    return table, stats


def _grid_poses(b: _Scratch, s: dict, axes: list, values: list, first: int,
                m: int) -> tuple[np.ndarray, np.ndarray]:
    """The m grid rows from row `first` of slice s: their row numbers and their poses (6 x m),
    built column by column in b's arrays (no strided copies); the grid indices (row-major over
    the axes in their spec order) in b.index."""
    row = b.row[:m]
    np.add(b.ramp[:m], first, out=row)
    rest = row
    for col in range(len(axes) - 1, -1, -1):
        size = len(axes[col][1])
        np.remainder(rest, size, out=b.index[col, :m])
        rest = np.floor_divide(rest, size, out=b.rest[:m])
    pose = b.pose[:, :m]
    pose.fill(0.0)
    for comp, v in s["fixed"].items():
        pose[POSE.index(comp)].fill(v)
    for col, (comp, _) in enumerate(axes):
        np.take(values[col], b.index[col, :m], out=pose[POSE.index(comp)])
    return row, pose


def _solve_and_check(b: _Scratch, platform: Platform, spec: dict, warn_condition: float,
                     pose: np.ndarray, m: int, block: int) -> dict[int, str]:
    """The inverse solve and the limit check of the m poses, block by block, into b's columns;
    returns the messages of the rows that failed, by row."""
    messages: dict[int, str] = {}
    for lo in range(0, m, block):
        hi = min(lo + block, m)
        q, sol, check = b.rows(hi - lo)
        np.copyto(q, pose[:, lo:hi].T)
        platform.inverse(q, fidelity=spec["fidelity"], max_messages=hi - lo, **spec["options"],
                         out=sol)
        messages.update((lo + j, text) for j, text in sol.messages.items())
        _core.limits_check(platform._model, q, None, None, None, None, warn_condition,
                           check.first, check.failed, check.margin, check.leg, check.other_leg,
                           check.condition, b.leg_margin[:hi - lo])
        np.logical_and(sol.ok, check.within, out=b.reachable[lo:hi])
        np.copyto(b.limit_class[lo:hi], check.first, casting="unsafe")
        np.copyto(b.margin[:, lo:hi], check.margin[:, :len(POSE_CLASSES)].T)
        np.copyto(b.length[:, lo:hi], sol.length.T)
        np.copyto(b.force[:, lo:hi], sol.force.T)
        np.copyto(b.status[lo:hi], sol.status)
        np.copyto(b.condition[lo:hi], sol.condition)
    return messages


def _workspace_table(b: _Scratch, s: dict, row: np.ndarray, pose: np.ndarray, m: int,
                     messages: dict[int, str]) -> pa.Table:
    """The m rows' table of slice s, its columns views of b's arrays."""
    columns = {"slice": dictionary_column(m, s["name"], {}, out=b.codes[0, :m]), "row": row}
    for col, comp in enumerate(s["axes"]):
        columns[f"i_{comp}"] = b.index[col, :m]
    for i, comp in enumerate(POSE):
        columns[comp] = pose[i]
    columns["status"] = b.status[:m]
    columns["reachable"] = b.reachable[:m]
    columns["limit_class"] = b.limit_class[:m]
    for c, name in enumerate(POSE_CLASSES):
        columns[f"margin_{name}"] = b.margin[c, :m]
    columns["condition"] = b.condition[:m]
    for k in LEGS:
        columns[f"L{k}"] = b.length[k - 1, :m]
    for k in LEGS:
        columns[f"F{k}"] = b.force[k - 1, :m]
    columns["message"] = dictionary_column(m, "", messages, out=b.codes[1, :m])
    return pa.table(columns)


def dictionary_column(n: int, default: str, texts: dict[int, str],
                      out: Optional[np.ndarray] = None) -> pa.DictionaryArray:
    """n rows of text, texts[j] in row j and default elsewhere, dictionary-encoded as
    pa.array([texts.get(j, default) for j in range(n)]).dictionary_encode() encodes it (int32
    indices, the dictionary in order of first appearance), without a Python loop over the rows:
    a workspace chunk's rows are mostly default. out: n int32 for the indices (the result views
    it), instead of fresh ones."""
    rows = sorted(texts)
    # the first row not in texts (rows are distinct and sorted: where rows[j] != j)
    first_default = next((j for j, r in enumerate(rows) if r != j), len(rows))
    order = [texts[r] for r in rows[:first_default]]
    if first_default < n:
        order.append(default)
    order += [texts[r] for r in rows[first_default:]]
    code: dict[str, int] = {}
    for text in order:
        code.setdefault(text, len(code))
    indices = np.empty(n, np.int32) if out is None else out
    indices.fill(code.get(default, 0))
    indices[np.asarray(rows, dtype=np.intp)] = [code[texts[r]] for r in rows]
    return pa.DictionaryArray.from_arrays(pa.array(indices), pa.array(list(code), pa.string()))
