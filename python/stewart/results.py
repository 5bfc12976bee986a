"""What every batch result shares: a status per row, and arrays made from the library's output
tables (stewart_outputs.h, through _core.inverse_columns, forward_columns, plant_columns)."""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from . import _core

STATUS_OK = 0  #: stewart_status of a row that solved (or ran)
STATUS_NOT_RUN: int = _core.BATCH_NOT_RUN  #: a plant row after the one that stopped the run
#: Each array of a result starts a multiple of this many bytes after its block's start.
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


#: A result's arrays up to this size lie in one zeroed block, the columns left zero among them;
#: a larger result's zeroed columns get a calloc'd block of their own, whose pages the batch never
#: touches (zeroing them would cost a large batch a quarter of its solving).
SMALL_BLOCK_BYTES = 8192


class Placement(NamedTuple):
    """Where the arrays of a result of `rows` rows lie (place): names, the layout's columns in
    order (and a dict of them to copy, never changed: copying it costs a sixth of making it);
    blocks, per block its size in bytes, whether it is zeroed, and its stacks (the names
    of the columns of one width and dtype; the stack's shape, strides and dtype; its byte offset
    in the block); written_bytes and offsets, the size of the first block and each column's byte
    offset in it (-1: a column left zero), for the binding."""
    rows: int
    names: dict
    blocks: tuple
    written_bytes: int
    offsets: tuple[int, ...]


def place(layout: Table, n: int, zeroed: frozenset = frozenset()) -> Placement:
    """The placement of layout's arrays of n rows, the columns in zeroed left zero (the binding
    is not given them). The columns of one width and dtype lie in one stack, each at a multiple
    of BLOCK_ALIGNMENT: iterating the stack makes their arrays, a fraction of the cost of making
    each on its own (a one-row call makes two dozen)."""
    names = tuple(c.name for c in layout.columns)
    small = _stacks(layout, n, lambda name: True)[1] <= SMALL_BLOCK_BYTES
    parts = ([(lambda name: True, bool(zeroed))] if small else
             [(lambda name: name not in zeroed, False), (lambda name: name in zeroed, True)])
    blocks = []
    for member, zero in parts:
        stacks, size = _stacks(layout, n, member)
        if stacks:
            blocks.append((max(size, 1), zero, stacks))
    offsets = dict.fromkeys(names, -1)
    for members, shape, strides, dtype, offset in blocks[0][2]:
        offsets.update((m, offset + k * strides[0]) for k, m in enumerate(members)
                       if m not in zeroed)
    return Placement(n, dict.fromkeys(names), tuple(blocks), blocks[0][0],
                     tuple(offsets.values()))


def _stacks(layout: Table, n: int, member) -> tuple[tuple, int]:
    """The stacks of the columns of layout for which member(name) is true, and their bytes."""
    groups: dict = {}
    for name, count, dtype in layout.columns:
        if member(name):
            groups.setdefault((count, dtype), []).append(name)
    stacks, size = [], 0
    for (count, dtype), members in groups.items():
        row_bytes = count * dtype.itemsize
        # each column starts BLOCK_ALIGNMENT-aligned: the stack's step from one to the next
        column_bytes = -(-n * row_bytes // BLOCK_ALIGNMENT) * BLOCK_ALIGNMENT
        shape = (len(members), n, count) if count > 1 else (len(members), n)
        strides = (column_bytes, row_bytes, dtype.itemsize)[:len(shape)]
        stacks.append((tuple(members), shape, strides, dtype, size))
        size += len(members) * column_bytes
    return tuple(stacks), size


def table_arrays(layout: Table, n: int, zeroed: frozenset = frozenset()) -> dict:
    """Arrays of n rows, one per column in the layout's order: (n, count) or (n,) for a count of
    1, of the column's dtype; uninitialised (the batch writes every row) but for the columns named
    in zeroed, which are zeros. They are C-ordered views of one memory block (one allocation per
    result: a freed result's block is reused by the next one of its size, where a dozen arrays of
    their own would each be mapped and page-faulted anew), the zeroed ones of a second, calloc'd
    block (pages the batch never touches cost nothing; a small result's are zeroed with the
    rest, SMALL_BLOCK_BYTES)."""
    return new_table(place(layout, n, zeroed))[0]


def new_table(placement: Placement) -> tuple[dict, np.ndarray]:
    """The arrays of a placement (table_arrays) and the block placement.offsets places them in
    for the binding (uint8)."""
    arrays = placement.names.copy()
    blocks = []
    for size, zero, stacks in placement.blocks:
        block = np.zeros(size, np.uint8) if zero else np.empty(size, np.uint8)
        blocks.append(block)
        for names, shape, strides, dtype, offset in stacks:
            arrays.update(zip(names, np.ndarray(shape, dtype, block, offset, strides)))
    return arrays, blocks[0]


def result_of(cls, arrays: dict, **fields):
    """A result dataclass cls made from its arrays (every array field, by name) and its other
    fields, the same object cls(**arrays, **fields) is: the dataclass's __init__ only assigns
    its fields (the result classes have no __post_init__), which for two dozen arrays costs
    several times setting the object's attributes at once."""
    result = cls.__new__(cls)
    result.__dict__ = arrays
    arrays.update(fields)
    return result


def table_outputs(layout: Table, result) -> dict:
    """The arrays of result the library writes, by the name of their table column."""
    return {name: getattr(result, name) for name in layout.names}
