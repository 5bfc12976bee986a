"""Platform.inverse at the full level, Platform.forward and Platform.simulate carry a history from
row to row (warm starts, tracking, the plant's state): they go through the library in slices on
one solver object that keeps it, so the slices give the numbers of one call bit for bit, and
Ctrl-C mid-batch raises KeyboardInterrupt between slices with the finished rows valid (issue 23
item 7; the kinematic and massless levels are in test_api_batches.py)."""
import json
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import scenes

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")


@pytest.fixture(scope="module")
def platform():
    return stewart.Platform()


def _arrays(sol):
    return {k: v for k, v in vars(sol).items() if isinstance(v, np.ndarray)}


def _manoeuvre(duration=0.5, dt=0.005):
    scene = scenes.load("combined")
    scene["duration"] = duration
    t = scenes.times(scene, dt)
    return (t, *scenes.pose(scene, t))


def _full_inverse(p):
    t, q, qd, qdd = _manoeuvre()
    q[40, 2] = 5.0      # unreachable: a failed row, then the warm start goes on from row 39
    q[60, 0] = np.nan   # a second failing row, past the one message asked for
    return lambda: p.inverse(q, qd, qdd, "full", max_messages=1)


def _forward(p):
    t, q, qd, qdd = _manoeuvre()
    legs = p.inverse(q, qd, qdd, "kinematic")
    L = legs.length.copy()
    L[50] = 10.0        # lengths no pose has: tracking goes on from row 49
    return lambda: p.forward(L, legs.length_rate, legs.length_accel, t=t, max_messages=1)


def _simulate(p, stop_row=None):
    t, q, qd, qdd = _manoeuvre()
    forces = p.inverse(q, qd, qdd, "massless").force
    if stop_row is not None:
        forces[stop_row, 3] = np.inf  # a refused step: the run stops there
    return lambda: p.simulate(t, forces, "massless", start=q[0], start_rate=qd[0])


# direction -> (module, its slice size, the call of a batch over _manoeuvre)
CALLS = {
    "full inverse": (stewart.inverse, "FULL_SLICE_ROWS", _full_inverse),
    "forward": (stewart.forward, "SLICE_ROWS", _forward),
    "simulate": (stewart.simulate, "SLICE_ROWS", _simulate),
    "simulate stopped at row 75": (stewart.simulate, "SLICE_ROWS",
                                   lambda p: _simulate(p, stop_row=75)),
}


@pytest.mark.parametrize("direction", CALLS)
def test_slices_of_7_rows_give_the_numbers_of_one_call(monkeypatch, platform, direction):
    module, name, make = CALLS[direction]
    call = make(platform)
    monkeypatch.setattr(module, name, 10**9)
    whole = call()
    monkeypatch.setattr(module, name, 7)
    sliced = call()
    arrays = _arrays(whole)
    assert arrays["status"].size == 101
    assert (arrays["status"] == 0).all() == (direction == "simulate")  # else rows that fail
    for key, a in arrays.items():
        np.testing.assert_array_equal(getattr(sliced, key), a, err_msg=key)
    for key in ("messages", "message", "statistics"):
        if hasattr(whole, key):
            assert getattr(sliced, key) == getattr(whole, key), key


def test_the_history_matters_so_a_fresh_solver_per_slice_would_not_do(platform):
    """What the test above guards against: the rows from row 7 on from a fresh start (what a new
    solver per slice would do) differ from the same rows of one call. (The full inverse level's
    history is the side of its Euler parameters, which does not show along this manoeuvre.)"""
    t, q, qd, qdd = _manoeuvre()
    legs = platform.inverse(q, qd, qdd, "kinematic")
    whole = platform.forward(legs.length, legs.length_rate, t=t)
    fresh = platform.forward(legs.length[7:], legs.length_rate[7:], t=t[7:])
    assert not np.array_equal(fresh.start, whole.start[7:])
    forces = platform.inverse(q, qd, qdd, "massless").force
    whole = platform.simulate(t, forces, "massless", start=q[0], start_rate=qd[0])
    fresh = platform.simulate(t[7:], forces[7:], "massless", start=whole.pose[7],
                              start_rate=whole.pose_rate[7])
    assert not np.array_equal(fresh.pose, whole.pose[7:])


CHILD = textwrap.dedent("""
    import json, os, signal, sys, threading, time
    # Ctrl-C's handler whatever the parent left: a shell that starts a job with '&' and no job
    # control makes it ignore SIGINT, and Python keeps an ignored SIGINT ignored.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    import numpy as np
    import stewart
    direction, n = sys.argv[1], int(sys.argv[2])
    p = stewart.Platform()
    t = np.arange(n) * 1e-3
    w = 2 * np.pi * 0.5
    q = np.zeros((n, 6)); qd = np.zeros((n, 6)); qdd = np.zeros((n, 6))
    for i, (mean, amp) in enumerate([(0, 0.02), (0, 0.02), (0.5, 0.03), (0, 0.05), (0, 0.05),
                                     (0, 0.05)]):
        q[:, i] = mean + amp * np.sin(w * t + i)
        qd[:, i] = amp * w * np.cos(w * t + i)
        qdd[:, i] = -amp * w * w * np.sin(w * t + i)
    legs = p.inverse(q, qd, qdd, "kinematic")
    forces = p.inverse(q, qd, qdd, "massless").force
    calls = {
        "inverse": (stewart.inverse, "_new_solution", "FULL_SLICE_ROWS",
                    lambda m: p.inverse(q[:m], qd[:m], qdd[:m], "full")),
        "forward": (stewart.forward, "_new_solution", "SLICE_ROWS",
                    lambda m: p.forward(legs.length[:m], legs.length_rate[:m], t=t[:m])),
        "simulate": (stewart.simulate, "empty_simulation", "SLICE_ROWS",
                     lambda m: p.simulate(t[:m], forces[:m], "massless", start=q[0],
                                          start_rate=qd[0])),
    }
    module, factory, slice_name, call = calls[direction]
    made = []
    empty = getattr(module, factory)

    def marked(*args):  # the result arrays, rows the batch has not written marked 99
        new = empty(*args)  # the result, or (the result, its block, their placement)
        sol = new[0] if isinstance(new, tuple) else new
        sol.status[:] = 99
        made.append(sol)
        return new
    setattr(module, factory, marked)
    first_slice = getattr(module, slice_name)
    sent = []

    def interrupt():  # Ctrl-C once the library is past the first slice, mid-batch
        while not made or made[0].status[first_slice] == 99:
            time.sleep(0.0005)
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt, daemon=True).start()
    try:
        call(n)
        print(json.dumps({"interrupted": False}))
    except KeyboardInterrupt as e:
        latency = time.perf_counter() - sent[0]
        done = e.rows_done
        setattr(module, factory, empty)
        fresh = call(done)
        same = all(np.array_equal(getattr(e.result, k)[:done], v)
                   for k, v in vars(fresh).items() if isinstance(v, np.ndarray))
        print(json.dumps({"interrupted": True, "done": done, "same": same, "message": str(e),
                          "unwritten": int(np.sum(made[0].status == 99)),
                          "result_is_the_arrays": e.result is made[0], "latency": latency}))
""")


@pytest.mark.parametrize("direction, n", [("inverse", 400_000), ("forward", 2_000_000),
                                          ("simulate", 400_000)])
def test_ctrl_c_stops_a_batch_with_a_history_between_slices(direction, n):
    """A SIGINT mid-batch raises KeyboardInterrupt after the slice under way, not when the batch
    ends: rows are left unwritten, and the rows it reports done (in e.result) equal a fresh call
    over those rows alone."""
    r = subprocess.run([sys.executable, "-c", CHILD, direction, str(n)], capture_output=True,
                       text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    result = json.loads(r.stdout)
    print(f"{direction}: SIGINT to KeyboardInterrupt {1e3 * result.get('latency', 0):.1f} ms")
    assert result["interrupted"], result
    assert 0 < result["done"] < n and result["unwritten"] > 0, result
    assert result["same"] and result["result_is_the_arrays"], result
    assert f"after {result['done']} of {n} rows" in result["message"]
