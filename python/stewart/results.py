"""What every batch result shares: a status per row, and arrays made from the library's output
tables (stewart_outputs.h, through _core.inverse_columns, forward_columns, plant_columns)."""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from . import _core

STATUS_OK = 0  #: stewart_status of a row that solved (or ran)
STATUS_NOT_RUN: int = _core.BATCH_NOT_RUN  #: a plant row after the one that stopped the run
#: Byte alignment of each array inside a result's block (a cache line).
BLOCK_ALIGNMENT = 64


class RowStatus:
    """Mixed into the result dataclasses, which have a `status` array of one entry per row."""
    status: np.ndarray

    def __len__(self) -> int:
        return len(self.status)

    @property
    def ok(self) -> np.ndarray:
        """(N,) True where the row solved (or ran)."""
        return self.status == STATUS_OK

    def status_name(self, row: int) -> str:
        """The library's name of row's status ("ok", "unreachable pose", ...), or "not run"."""
        s = int(self.status[row])
        return "not run" if s == STATUS_NOT_RUN else _core.status_name(s)


class Column(NamedTuple):
    """One array of a result: its name, values per row (1: an (N,) array) and dtype."""
    name: str
    count: int
    dtype: np.dtype


class Table(NamedTuple):
    """A result's arrays: a library output table's columns (read once, at import), then the
    result's own (status, a simulation's t). names: the table's columns, which the library
    writes through the binding."""
    columns: tuple[Column, ...]
    names: tuple[str, ...]


def table(columns, *extra: Column) -> Table:
    """The Table of a library output table (a _core.*_columns() list) and extra columns."""
    own = tuple(Column(name, count, np.dtype(dtype)) for name, count, dtype, *_ in columns)
    return Table(own + extra, tuple(c.name for c in own))


STATUS_COLUMN = Column("status", 1, np.dtype(np.int32))


def table_arrays(layout: Table, n: int) -> dict:
    """Uninitialised arrays of n rows, one per column: (n, count) or (n,) for a count of 1, of
    the column's dtype (the batch writes every row). They are C-ordered views of one memory block
    (one allocation per result: a freed result's block is reused by the next one of its size,
    where a dozen arrays of their own would each be mapped and page-faulted anew)."""
    size, placed = _placement(layout, n)
    block = np.empty(size, dtype=np.uint8)
    view = np.ndarray
    return {name: view(shape, dtype, block, offset) for name, shape, dtype, offset in placed}


@functools.lru_cache(maxsize=64)
def _placement(layout: Table, n: int) -> tuple[int, tuple]:
    """The block size of layout's arrays of n rows and each array's (name, shape, dtype, byte
    offset in the block), kept for the sizes last used: a loop of equal calls places them once."""
    placed, size = [], 0
    for name, count, dtype in layout.columns:
        placed.append((name, (n, count) if count > 1 else (n,), dtype, size))
        size += -(-n * count * dtype.itemsize // BLOCK_ALIGNMENT) * BLOCK_ALIGNMENT
    return size, tuple(placed)


def table_outputs(layout: Table, result) -> dict:
    """The arrays of result the library writes, by the name of their table column."""
    return {name: getattr(result, name) for name in layout.names}
