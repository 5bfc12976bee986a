"""The library's option tables (stewart_table.h) as the package sees them: each Platform call takes
exactly its table's options as keywords, the table's defaults are the library's own (a run with
every option given at its table default is the run with none given, bit for bit), and the one
generic setter refuses an unknown name or a bad value naming it."""
import inspect

import numpy as np
import pytest

import stewart
from stewart import _core
from stewart.simulate import run_simulate

# (Platform method, table, the options it takes positionally rather than by keyword)
CALLS = [("inverse", "inverse", {"fidelity"}),
         ("forward", "forward", set()),
         ("simulate", "plant", {"fidelity"})]


@pytest.fixture(scope="module")
def platform():
    return stewart.Platform()


@pytest.mark.parametrize("method, table, positional", CALLS)
def test_each_call_takes_its_tables_options(method, table, positional):
    names = [o["name"] for o in _core.option_table(table)]
    assert len(names) == len(set(names)), names
    parameters = inspect.signature(getattr(stewart.Platform, method)).parameters
    # the call's own keywords, not solver options: how many messages, where to write, the rows'
    # times (or the inverse's poses' jerks), and forward's rows solved each on its own
    own = {"max_messages", "out", "t", "jerks", "cold"}
    keywords = {n for n, p in parameters.items() if p.kind == p.KEYWORD_ONLY} - own
    assert keywords | positional == set(names)
    assert positional <= set(parameters)


def test_plant_table_describes_every_option():
    table = {o["name"]: o for o in _core.option_table("plant")}
    assert list(table) == ["fidelity", "method", "relative_tolerance", "absolute_tolerance",
                           "max_internal_steps", "fixed_steps", "input", "smoothing_speed"]
    assert [o["id"] for o in table.values()] == list(range(200, 208))  # the plant FMU's
    assert table["max_internal_steps"]["integer"] and not table["relative_tolerance"]["integer"]
    for o in table.values():
        assert o["description"] and o["min"] <= o["default"] <= o["max"], o


def test_unknown_table_is_refused_naming_it():
    with pytest.raises(ValueError, match="no option table 'plan'"):
        _core.option_table("plan")


def test_table_defaults_are_the_librarys(platform):
    """Every plant option given at its table default changes no bit of a run."""
    t = np.arange(0, 0.05, 1e-3)
    forces = np.tile(np.linspace(300, 900, t.size)[:, None], (1, 6))
    given = {o["name"]: o["default"] for o in _core.option_table("plant")}
    fidelity = stewart.Fidelity(int(given.pop("fidelity")))
    plain = platform.simulate(t, forces, fidelity=fidelity)
    explicit = platform.simulate(t, forces, fidelity=fidelity, **given)
    assert plain.completed and explicit.completed
    for name in ("pose", "pose_rate", "length", "length_rate", "steps"):
        assert np.array_equal(getattr(plain, name), getattr(explicit, name)), name


def test_generic_setter_refuses_by_name(platform):
    t, forces = np.arange(3) * 1e-3, np.zeros((3, 6))
    with pytest.raises(stewart.ParameterError, match="unknown plant option 'no_such'"):
        run_simulate(platform._model, t, forces, None, None, [("no_such", 1.0)])
    with pytest.raises(stewart.ParameterError, match=r"max_internal_steps = 2\.5 must be a whole number"):
        platform.simulate(t, forces, max_internal_steps=2.5)
    with pytest.raises(stewart.ParameterError, match=r"relative_tolerance = 1 must be"):
        platform.simulate(t, forces, relative_tolerance=1.0)
    # the set is still checked as a whole: fixed steps need an explicit method
    with pytest.raises(stewart.ParameterError, match="fixed_steps = 2 needs method 2 or 3"):
        platform.simulate(t, forces, method=0, fixed_steps=2)
