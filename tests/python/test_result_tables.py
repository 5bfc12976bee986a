"""The Python result classes of the inverse and forward directions are made from the library's
output tables (stewart_outputs.h): every column of a table is an array of the result, in the
table's order, of its width and type, and the library writes it."""
import dataclasses

import numpy as np
import pytest

import stewart
from stewart import _core
from stewart.forward import ForwardSolution, empty_forward_solution
from stewart.inverse import InverseSolution, empty_inverse_solution
from stewart.simulate import Simulation, empty_simulation

DIRECTIONS = {
    "inverse": (InverseSolution, empty_inverse_solution, _core.inverse_columns),
    "forward": (ForwardSolution, empty_forward_solution, _core.forward_columns),
    "simulate": (Simulation, lambda n: empty_simulation(np.arange(n, dtype=float)),
                 _core.plant_columns),
}
NOT_FROM_TABLES = ("t", "status", "messages", "message", "statistics")


@pytest.mark.parametrize("direction", DIRECTIONS)
def test_every_table_column_is_an_array_of_the_result_in_the_table_order(direction):
    cls, empty, columns = DIRECTIONS[direction]
    table = columns()
    fields = [f.name for f in dataclasses.fields(cls) if f.name not in NOT_FROM_TABLES]
    assert fields == [name for name, *_ in table]
    result = empty(7)
    for name, count, dtype, unit, description in table:
        a = getattr(result, name)
        assert a.shape == ((7, count) if count > 1 else (7,)), name
        assert a.dtype == np.dtype(dtype), name
        assert description, name


# stroke_legs, the table's last column, reached Python only through the table: its bits against
# the lengths and the stroke set here (offsets 0, so a reading is the joint-to-joint length).
STROKE = (0.45, 0.65)


def _heave(n=41):
    q = np.zeros((n, 6))
    q[:, 2] = np.linspace(0.35, 0.75, n)
    q[:, 3] = 0.05 * np.sin(np.linspace(0, 6, n))
    return q


def _expected_stroke_bits(lengths):
    outside = (lengths < STROKE[0]) | (lengths > STROKE[1])
    return (outside * (1 << np.arange(6))).sum(axis=1)


def test_inverse_stroke_legs_name_the_legs_outside_the_stroke():
    p = stewart.Platform(stroke_min=STROKE[0], stroke_max=STROKE[1])
    sol = p.inverse(_heave(), fidelity="kinematic")
    assert sol.ok.all()
    expected = _expected_stroke_bits(sol.length)
    assert 0 < np.count_nonzero(expected) < len(expected)  # both kinds of row are tested
    np.testing.assert_array_equal(sol.stroke_legs, expected)
    np.testing.assert_array_equal(sol.warnings & 1, expected != 0)


def test_forward_stroke_legs_name_the_measured_lengths_outside_the_stroke():
    p = stewart.Platform(stroke_min=STROKE[0], stroke_max=STROKE[1])
    lengths = p.inverse(_heave(), fidelity="kinematic").length
    sol = p.forward(lengths)
    assert sol.ok.all()
    expected = _expected_stroke_bits(lengths)
    assert 0 < np.count_nonzero(expected) < len(expected)
    np.testing.assert_array_equal(sol.stroke_legs, expected)


def test_plant_stroke_legs_name_the_legs_outside_the_stroke():
    """The plant sinks from home under forces below its weight's share: its legs shorten through
    the lower stroke end."""
    p = stewart.Platform(stroke_min=STROKE[0], stroke_max=STROKE[1])
    t = np.linspace(0.0, 0.25, 51)
    sim = p.simulate(t, np.zeros((len(t), 6)), fidelity="massless")
    assert sim.completed
    expected = _expected_stroke_bits(sim.length)
    assert 0 < np.count_nonzero(expected) < len(expected)
    np.testing.assert_array_equal(sim.stroke_legs, expected)
    np.testing.assert_array_equal(sim.warnings & 1, expected != 0)


def test_an_output_array_the_library_cannot_write_in_place_is_refused_by_the_binding():
    """The binding never converts (a converted copy would take the results): even called
    directly, past the Python checks, a float32 column is refused naming it."""
    q = _heave(3)
    model = stewart.Platform()._model
    out = empty_inverse_solution(3)
    outputs = {name: getattr(out, name) for name, *_ in _core.inverse_columns()}
    outputs["force"] = outputs["force"].astype(np.float32)
    with pytest.raises(ValueError, match="output force"):
        _core.InverseRun(model, q, None, None, [], outputs, out.status)


@pytest.mark.parametrize("direction", DIRECTIONS)
def test_a_result_s_arrays_share_no_byte(direction):
    """A result's arrays are views of one memory block (results.table_arrays): each is C-ordered,
    aligned and writeable, and writing one leaves every other unchanged."""
    _, empty, _ = DIRECTIONS[direction]
    result = empty(5)
    arrays = {k: v for k, v in vars(result).items() if isinstance(v, np.ndarray)}
    for a in arrays.values():
        assert a.flags.c_contiguous and a.flags.aligned and a.flags.writeable
        a[...] = 0
    for name, a in arrays.items():
        a[...] = 1
        for other, b in arrays.items():
            assert np.all(b == (1 if other == name else 0)), (name, other)
        a[...] = 0
