"""What every batch result shares: a status per row, and arrays made from the library's output
tables (stewart_outputs.h, through _core.inverse_columns, forward_columns, plant_columns)."""
from __future__ import annotations

import numpy as np

from . import _core

STATUS_OK = 0  #: stewart_status of a row that solved (or ran)
STATUS_NOT_RUN: int = _core.BATCH_NOT_RUN  #: a plant row after the one that stopped the run


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


def table_arrays(columns, n: int) -> dict:
    """Uninitialised arrays of n rows, one per output column of a library table: (n, count) or
    (n,) for a count of 1, of the table's dtype (the batch writes every row)."""
    return {name: np.empty((n, count) if count > 1 else n, dtype=dtype)
            for name, count, dtype, _unit, _description in columns}


def table_outputs(columns, result) -> dict:
    """The arrays of result the library writes, by the name of their table column."""
    return {name: getattr(result, name) for name, *_ in columns}
