"""Long batches in slices (Platform.inverse, forward, simulate): one solver object of the library
(a _core run) does a call's rows a slice at a time, keeping its history between slices (the full
level's warm starts, forward tracking, the plant's state), so the numbers are those of one call;
Python takes signals between slices, so that Ctrl-C stops a long batch within about a slice."""
from __future__ import annotations

from typing import Callable


def run_in_slices(what: str, n: int, slice_rows: int, run_rows: Callable[[int, int], bool],
                  result) -> None:
    """Calls run_rows(first, stop) over [0, n) in order, slice_rows rows at a time, until it
    returns False (a run that cannot go on). Ctrl-C (KeyboardInterrupt) between slices is raised
    again as a KeyboardInterrupt saying how far the batch got, with rows_done (rows
    [0, rows_done) of result are finished and valid, the others are not) and result."""
    done = 0
    try:
        while done < n:
            stop = min(done + max(slice_rows, 1), n)
            go_on = run_rows(done, stop)
            done = stop
            if not go_on:
                break
    except KeyboardInterrupt:
        stopped = KeyboardInterrupt(f"{what} stopped after {done} of {n} rows: rows [0, {done}) "
                                    "of the result are finished, the others are not")
        stopped.rows_done = done
        stopped.result = result
        raise stopped from None


def keeping_messages(run, messages: dict, max_messages: int) -> Callable[[int, int], bool]:
    """run_rows for run_in_slices over a _core run whose rows(first, stop, max_messages) returns
    [(row, message)] of up to max_messages failing rows: the messages of the first max_messages
    failing rows of the whole batch go into messages."""
    def run_rows(first: int, stop: int) -> bool:
        messages.update(run.rows(first, stop, min(max_messages - len(messages), stop - first)))
        return True
    return run_rows
