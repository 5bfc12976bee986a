"""Platform.inverse's batch handling: out= arrays that the library cannot write in place are
refused (never a silent copy), the batch goes in slices whose results equal one call, Ctrl-C
stops a long batch between slices with the finished rows valid, and arguments that are not
numbers are refused naming the argument."""
import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")


def _poses(n, seed=3):
    rng = np.random.default_rng(seed)
    q = np.column_stack([rng.uniform(-0.1, 0.1, (n, 2)), rng.uniform(0.45, 0.55, n),
                         rng.uniform(-0.15, 0.15, (n, 3))])
    q[::5, 2] = 5.0     # unreachable rows: failed status and a message
    q[::13, 0] = np.nan  # non-finite rows
    return q, 0.1 * np.cos(q), -0.2 * np.sin(q)


def _arrays(sol):
    return {k: v for k, v in vars(sol).items() if isinstance(v, np.ndarray)}


def _fortran(a):
    return np.asfortranarray(a) if a.ndim == 2 else a[::-1].copy()[::-1]  # 1-D: a reversed view


def _strided(a):
    big = np.zeros((2 * a.shape[0], *a.shape[1:]), dtype=a.dtype)
    return big[::2]


BAD_ARRAYS = {
    "float32": lambda a: np.zeros(a.shape, np.float32 if a.dtype == np.float64 else np.int64),
    "int64": lambda a: np.zeros(a.shape, np.int64),
    "fortran or reversed": _fortran,
    "strided": _strided,
    "read-only": lambda a: np.lib.stride_tricks.as_strided(a, writeable=False),
}


@pytest.mark.parametrize("field", list(_arrays(stewart.inverse.empty_inverse_solution(1))))
@pytest.mark.parametrize("kind", BAD_ARRAYS)
def test_out_arrays_the_library_cannot_write_in_place_are_refused_naming_them(field, kind):
    """nanobind converts such an array into a temporary copy and writes there: the results would
    be lost (stale forces, a NaN row with status 0). Each is refused, naming out.<field>."""
    q, qd, qdd = _poses(12)
    p = stewart.Platform()
    out = stewart.inverse.empty_inverse_solution(len(q))
    bad = BAD_ARRAYS[kind](getattr(out, field))
    if bad.dtype == getattr(out, field).dtype and bad.flags.c_contiguous and bad.flags.writeable:
        pytest.skip(f"{kind} leaves a {getattr(out, field).ndim}-D {field} writable in place")
    setattr(out, field, bad)
    with pytest.raises(ValueError, match=rf"out\.{field}\b"):
        p.inverse(q, qd, qdd, fidelity="massless", out=out)


def test_a_valid_out_is_written_in_place():
    q, qd, qdd = _poses(40)
    p = stewart.Platform()
    fresh = p.inverse(q, qd, qdd, fidelity="massless")
    out = stewart.inverse.empty_inverse_solution(len(q))
    arrays = _arrays(out)
    assert p.inverse(q, qd, qdd, fidelity="massless", out=out) is out
    for name, a in _arrays(fresh).items():
        assert arrays[name] is getattr(out, name)
        np.testing.assert_array_equal(a, getattr(out, name), err_msg=name)


@pytest.mark.parametrize("fidelity", ["kinematic", "massless"])
def test_slices_give_the_numbers_and_messages_of_one_call(monkeypatch, fidelity):
    """Rows at these levels are independent: slices of 7 rows equal one call into the library,
    bit for bit, messages (first max_messages failing rows, numbered in the whole batch)
    included."""
    q, qd, qdd = _poses(100)
    p = stewart.Platform()
    monkeypatch.setattr(stewart.inverse, "SLICE_ROWS", 10**9)
    whole = p.inverse(q, qd, qdd, fidelity=fidelity, max_messages=9)
    monkeypatch.setattr(stewart.inverse, "SLICE_ROWS", 7)
    sliced = p.inverse(q, qd, qdd, fidelity=fidelity, max_messages=9)
    for name, a in _arrays(whole).items():
        np.testing.assert_array_equal(getattr(sliced, name), a, err_msg=name)
    failing = int(np.sum(~whole.ok))
    assert failing > 7 and sliced.messages == whole.messages
    assert len(whole.messages) == min(9, failing)


CHILD = textwrap.dedent("""
    import json, os, signal, sys, threading, time
    # Ctrl-C's handler whatever the parent left: a shell that starts a job with '&' and no job
    # control makes it ignore SIGINT, and Python keeps an ignored SIGINT ignored.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    import numpy as np
    import stewart
    n = int(sys.argv[1])
    rng = np.random.default_rng(5)
    q = np.column_stack([rng.uniform(-0.1, 0.1, (n, 2)), rng.uniform(0.45, 0.55, n),
                         rng.uniform(-0.15, 0.15, (n, 3))])
    p = stewart.Platform()
    out = stewart.inverse.empty_inverse_solution(n)
    out.status[:] = 99  # rows the batch has not written keep it
    first_slice = stewart.inverse.SLICE_ROWS

    def interrupt():  # Ctrl-C once the library is past the first slice, mid-batch
        while out.status[first_slice] == 99:
            time.sleep(0.0005)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt, daemon=True).start()
    try:
        p.inverse(q, fidelity="massless", out=out)
        print(json.dumps({"interrupted": False}))
    except KeyboardInterrupt as e:
        done = e.rows_done
        fresh = p.inverse(q[:done], fidelity="massless")
        same = all(np.array_equal(getattr(out, k)[:done], v) for k, v in vars(fresh).items()
                   if isinstance(v, np.ndarray))
        print(json.dumps({"interrupted": True, "done": done, "same": same, "message": str(e),
                          "unwritten": int(np.sum(out.status == 99))}))
""")


def test_ctrl_c_stops_a_long_batch_between_slices_with_the_finished_rows_valid():
    """A SIGINT mid-batch raises KeyboardInterrupt after the slice under way, not when the
    batch ends: rows are left unwritten, and the rows it reports done equal a fresh solve."""
    n = 64 * stewart.inverse.SLICE_ROWS
    r = subprocess.run([sys.executable, "-c", CHILD, str(n)], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    result = json.loads(r.stdout)
    assert result["interrupted"], result
    assert 0 < result["done"] < n and result["unwritten"] > 0, result
    assert result["same"], result
    assert f"after {result['done']} of {n} rows" in result["message"]


@pytest.mark.parametrize("call, words", [
    (lambda p: stewart.Platform(payload_mass="heavy"), ["payload_mass = 'heavy'", "not a number"]),
    (lambda p: stewart.Platform(base_angle=["a"] * 6), ["base_angle", "not a number"]),
    (lambda p: p.inverse([["0", "0", "half", 0, 0, 0]]), ["poses", "not a number"]),
    (lambda p: p.inverse(np.zeros((1, 6)), rates=[["x"] * 6]), ["rates", "not a number"]),
    (lambda p: p.inverse(np.zeros((1, 6)), tolerance="tight"), ["tolerance = 'tight'", "not a number"]),
    (lambda p: p.forward(np.full((1, 6), 0.55), guess=["home"] * 6), ["guess", "not a number"]),
    (lambda p: p.forward(np.full((1, 6), 0.55), max_iterations="many"), ["max_iterations = 'many'"]),
    (lambda p: p.simulate(["zero"], np.zeros((1, 6))), ["t has a value", "not a number"]),
    (lambda p: p.simulate([0.0], np.zeros((1, 6)), relative_tolerance="low"),
     ["relative_tolerance = 'low'"]),
])
def test_arguments_that_are_not_numbers_are_refused_naming_them(call, words):
    """Not numpy's bare "could not convert string to float": the message names the argument."""
    with pytest.raises(ValueError) as e:
        call(stewart.Platform())
    for w in words:
        assert w in str(e.value), str(e.value)


def _same_solution(a, b, where):
    for name, v in _arrays(a).items():
        np.testing.assert_array_equal(getattr(b, name), v, err_msg=f"{where}: {name}")
    assert b.messages == a.messages, where


@pytest.mark.parametrize("fidelity", ["kinematic", "massless"])
def test_a_platform_s_kept_solvers_give_the_numbers_of_a_new_one(fidelity):
    """A Platform keeps its closed-form levels' solvers between calls (binding: InversePool).
    Calls in any order, with other options between, and from threads at once give what a new
    Platform's first call gives, bit for bit, messages included."""
    from concurrent.futures import ThreadPoolExecutor
    q, qd, qdd = _poses(300)
    calls = {"plain": {}, "warn": {"warn_condition": 20.0},
             "singular": {"warn_condition": 20.0, "singular_condition": 40.0}}
    reference = {k: stewart.Platform().inverse(q, qd, qdd, fidelity=fidelity, **o)
                 for k, o in calls.items()}
    assert len(reference["plain"].messages) > 10  # failing rows: the solver had errors to forget
    if fidelity == "massless":  # the options' solvers differ where a condition is computed
        assert not np.array_equal(reference["plain"].warnings, reference["warn"].warnings)
    p = stewart.Platform()
    for k in ["plain", "warn", "plain", "singular", "plain", "warn"]:
        _same_solution(reference[k], p.inverse(q, qd, qdd, fidelity=fidelity, **calls[k]), k)
    order = list(calls) * 8
    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(
            lambda k: p.inverse(q, qd, qdd, fidelity=fidelity, **calls[k]), order))
    for k, sol in zip(order, results):
        _same_solution(reference[k], sol, f"threads, {k}")
