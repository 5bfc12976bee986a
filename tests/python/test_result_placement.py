"""A new result's arrays lie in stacks of one block (results.place) and the binding finds them by
their byte offsets (a _core Placement): each array its own bytes, aligned and C-ordered, the
columns the batch does not write left zero, a placement that does not fit its block refused, and
the numbers those of a result whose arrays are given by name (an earlier result as out=)."""
import dataclasses

import numpy as np
import pytest

import stewart
from stewart import _core
from stewart.arrays import all_finite
from stewart.forward import ForwardSolution, empty_forward_solution
from stewart.inverse import DRIVE_COLUMNS, INVERSE_TABLE, InverseSolution, empty_inverse_solution
from stewart.results import SMALL_BLOCK_BYTES, place, result_of, table_arrays

# 1 and 5 rows lie in one small block; 3000 do not (SMALL_BLOCK_BYTES), so the drive columns of
# a model without drives get a block of their own.
ROWS = (1, 5, 3000)


def _arrays(result):
    return {k: v for k, v in vars(result).items() if isinstance(v, np.ndarray)}


def _spans(arrays):
    """Each array's [first, last) byte address."""
    return {name: (a.ctypes.data, a.ctypes.data + a.nbytes) for name, a in arrays.items()}


@pytest.mark.parametrize("n", ROWS)
@pytest.mark.parametrize("drives", [True, False])
def test_every_array_of_a_new_result_has_bytes_of_its_own(n, drives):
    """No two arrays overlap (compared by address, which a shared byte could not pass), each is
    C-ordered, aligned, writeable and of its column's shape."""
    assert (place(INVERSE_TABLE, n).written_bytes <= SMALL_BLOCK_BYTES) == (n < 3000)
    arrays = _arrays(empty_inverse_solution(n, drives))
    for name, count, dtype in INVERSE_TABLE.columns:
        a = arrays[name]
        assert a.shape == ((n, count) if count > 1 else (n,)) and a.dtype == dtype, name
        assert a.flags.c_contiguous and a.flags.aligned and a.flags.writeable, name
    spans = sorted(_spans(arrays).items(), key=lambda item: item[1])
    for (name, (_, end)), (other, (start, _)) in zip(spans, spans[1:]):
        assert end <= start, (name, other)


@pytest.mark.parametrize("n", ROWS)
def test_without_drives_the_drive_columns_are_zeros_the_binding_is_not_given(n):
    placement = place(INVERSE_TABLE, n, frozenset(DRIVE_COLUMNS))
    offsets = dict(zip(placement.names, placement.offsets))
    assert {name for name, offset in offsets.items() if offset < 0} == set(DRIVE_COLUMNS)
    sol = empty_inverse_solution(n, drives=False)
    for name in DRIVE_COLUMNS:
        assert not getattr(sol, name).any(), name
    q = np.tile([0.01, -0.02, 0.5, 0.03, 0.02, -0.01], (n, 1))
    result = stewart.Platform().inverse(q, fidelity="massless")
    assert result.ok.all() and (result.length > 0).all()
    for name in DRIVE_COLUMNS:
        assert not getattr(result, name).any(), name


@pytest.mark.parametrize("cls, empty", [(InverseSolution, empty_inverse_solution),
                                        (ForwardSolution, empty_forward_solution)])
def test_a_result_made_at_once_is_the_dataclass_s_own(cls, empty):
    """results.result_of sets the fields as the dataclass's __init__ does (which it may, as the
    result classes have no __post_init__): the same fields, in the same order, the same arrays."""
    assert not hasattr(cls, "__post_init__")
    fast = empty(3)
    arrays = {f.name: getattr(fast, f.name) for f in dataclasses.fields(cls)}
    slow = cls(**arrays)
    assert list(vars(fast)) == [f.name for f in dataclasses.fields(cls)] + [
        k for k in vars(fast) if k.startswith("_")]
    for f in dataclasses.fields(cls):
        assert getattr(fast, f.name) is getattr(slow, f.name) or \
            getattr(fast, f.name) == getattr(slow, f.name), f.name
    again = result_of(cls, dict(arrays))
    assert list(vars(again)) == list(vars(slow))


@pytest.mark.parametrize("level", ["kinematic", "massless", "full"])
@pytest.mark.parametrize("n", [1, 5])
def test_a_new_result_holds_the_numbers_of_one_whose_arrays_are_given_by_name(level, n):
    """The two ways the binding takes a result's arrays (offsets in a new result's block; an
    earlier result's arrays by name, out=) write the same bytes."""
    p = stewart.Platform.from_file(stewart.platform_files()["simona_motion_base_drives"])
    rng = np.random.default_rng(3)
    q = np.column_stack([rng.uniform(-0.05, 0.05, (n, 2)), rng.uniform(-0.03, 0.03, n),
                         rng.uniform(-0.05, 0.05, (n, 3))]) + p.check().home
    qd, qdd = 0.1 * np.cos(q), -0.2 * np.sin(q)
    new = p.inverse(q, qd, qdd, fidelity=level)
    given = p.inverse(q, qd, qdd, fidelity=level, out=empty_inverse_solution(n))
    assert new.ok.all()
    for name, a in _arrays(new).items():
        assert a.tobytes() == getattr(given, name).tobytes(), name


def test_a_placement_that_does_not_fit_its_block_is_refused():
    """The binding checks a placement when it is made (every column inside the block, aligned for
    its type, none over another) and a block against its placement (its size and its start's
    alignment), so no offset can send the library outside or write one column over another."""
    placement = place(INVERSE_TABLE, 4)
    offsets = list(placement.offsets)
    _core.inverse_placement(4, placement.written_bytes, offsets)  # the right one is taken
    with pytest.raises(ValueError, match="offsets"):
        _core.inverse_placement(4, placement.written_bytes, offsets[:-1])
    assert offsets[-1] == max(offsets)  # status, 4 int32 values, lies last
    status_end = offsets[-1] + 4 * 4
    _core.inverse_placement(4, status_end, offsets)
    with pytest.raises(ValueError, match="beyond the block"):
        _core.inverse_placement(4, status_end - 1, offsets)
    with pytest.raises(ValueError, match="misaligned"):
        _core.inverse_placement(4, placement.written_bytes, [o + 1 for o in offsets])
    core = _core.inverse_placement(4, placement.written_bytes, offsets)
    model = stewart.Platform()._model
    q = np.tile([0, 0, 0.5, 0, 0, 0.0], (4, 1))
    with pytest.raises(ValueError, match="does not match its placement"):
        _core.InverseRun(model, q, None, None, [], np.empty(placement.written_bytes - 1, np.uint8),
                         core)
    with pytest.raises(ValueError, match="does not match its placement"):
        _core.InverseRun(model, q[:3], None, None, [],
                         np.empty(placement.written_bytes, np.uint8), core)
    # A block that starts off the alignment of its doubles is refused, and so are two columns
    # placed over each other (each alone inside the block and aligned).
    with pytest.raises(ValueError, match="does not match its placement"):
        _core.InverseRun(model, q, None, None, [],
                         np.empty(placement.written_bytes + 9, np.uint8)[1:], core)
    placed = [o for o in offsets if o >= 0]
    overlapping = [placed[0] if o == placed[1] else o for o in offsets]
    with pytest.raises(ValueError, match="overlap"):
        _core.inverse_placement(4, placement.written_bytes, overlapping)


def test_table_arrays_of_a_large_result_leave_the_zeroed_columns_in_a_block_of_their_own():
    n = 3000
    arrays = table_arrays(INVERSE_TABLE, n, frozenset(DRIVE_COLUMNS))
    written = {a.base.ctypes.data for name, a in arrays.items() if name not in DRIVE_COLUMNS}
    zeroed = {a.base.ctypes.data for name, a in arrays.items() if name in DRIVE_COLUMNS}
    assert len(written) == 1 and len(zeroed) == 1 and written != zeroed


@pytest.mark.parametrize("size", [1, 6, 64, 65, 1000])
def test_all_finite_agrees_with_numpy_on_small_and_large_arrays(size):
    rng = np.random.default_rng(size)
    a = rng.normal(size=size)
    assert all_finite(a)
    for bad in (np.nan, np.inf, -np.inf):
        for i in {0, size // 2, size - 1}:
            b = a.copy()
            b[i] = bad
            assert all_finite(b) == bool(np.isfinite(b).all()) is False
    assert all_finite(a.reshape(-1, 1)) and all_finite(np.zeros((0,)))
