"""A Platform keeps the library's solver objects between calls (the binding's SolverPool: the
inverse at every level, forward, linearisation, limits), reset when taken again. Each call must
still give what a new Platform's first call gives, bit for bit: calls here follow other calls on
other inputs and options (which leave a solver's history behind: the full level's and the
forward tracking's last pose), and run from threads at once."""
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")


def _poses(n, seed):
    rng = np.random.default_rng(seed)
    q = np.column_stack([rng.uniform(-0.08, 0.08, (n, 2)), rng.uniform(0.45, 0.55, n),
                         rng.uniform(-0.12, 0.12, (n, 3))])
    return q, 0.1 * np.cos(q), -0.2 * np.sin(q)


def _same(a, b, where):
    for name, value in vars(a).items():
        other = getattr(b, name)
        if isinstance(value, np.ndarray):
            assert value.dtype == other.dtype and value.shape == other.shape, (where, name)
            assert value.tobytes() == other.tobytes(), (where, name)
        else:
            assert value == other, (where, name)


def _check_calls(calls):
    """calls: {key: f(platform)}. Each key's call on a Platform that ran the others (in an order
    that repeats every key after another) and from threads, against a new Platform's."""
    reference = {k: f(stewart.Platform()) for k, f in calls.items()}
    p = stewart.Platform()
    order = [k for _ in range(3) for k in calls]
    for k in order:
        _same(reference[k], calls[k](p), k)
    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(lambda k: calls[k](p), order * 3))
    for k, result in zip(order * 3, results):
        _same(reference[k], result, f"threads, {k}")


def test_the_full_level_s_kept_solver_forgets_the_last_call_s_poses():
    a, b = _poses(40, 1), _poses(40, 2)
    calls = {"a": lambda p: p.inverse(*a, fidelity="full"),
             "b": lambda p: p.inverse(*b, fidelity="full"),
             "b1": lambda p: p.inverse(*(x[:1] for x in b), fidelity="full"),
             "tol": lambda p: p.inverse(*a, fidelity="full", tolerance=1e-6)}
    _check_calls(calls)


def test_the_forward_solver_kept_starts_each_call_cold():
    p = stewart.Platform()
    lengths = {s: p.inverse(*_poses(30, s), fidelity="kinematic") for s in (3, 4)}
    calls = {f"track{s}": (lambda p, L=L: p.forward(L.length, L.length_rate, L.length_accel))
             for s, L in lengths.items()}
    calls["one"] = lambda p: p.forward(lengths[3].length[7])
    calls["cold"] = lambda p: p.forward(lengths[4].length, cold=True)
    calls["tol"] = lambda p: p.forward(lengths[3].length, tolerance=1e-6)
    _check_calls(calls)


def test_kept_linearisations_and_limits_give_a_new_one_s_numbers():
    q, qd, qdd = _poses(3, 5)
    calls = {}
    for i in range(3):
        for level in ("massless", "full"):
            calls[f"plant{i}{level}"] = lambda p, i=i, level=level: p.linearize(
                q[i], qd[i], fidelity=level)
            calls[f"inverse{i}{level}"] = lambda p, i=i, level=level: p.linearize_inverse(
                q[i], qd[i], qdd[i], fidelity=level)
    calls["limits"] = lambda p: p.limits(q)
    calls["limits_warn"] = lambda p: p.limits(q, warn_condition=20.0)
    calls["ranges"] = lambda p: p.axis_ranges(q[:1], details=True)
    _check_calls(calls)


def test_a_failing_call_leaves_no_message_behind():
    """A linearisation that fails (pitch at 90 degrees) and then one that succeeds on the same
    Platform: the second is a new one's; a limits check of a non-finite pose raises the same
    message twice."""
    p = stewart.Platform()
    with pytest.raises(ValueError) as first:
        p.linearize([0, 0, 0.5, 0, np.pi / 2, 0], fidelity="massless")
    good = stewart.Platform().linearize([0.01, 0, 0.5, 0, 0, 0], fidelity="massless")
    _same(good, p.linearize([0.01, 0, 0.5, 0, 0, 0], fidelity="massless"), "after a failure")
    with pytest.raises(ValueError) as again:
        p.linearize([0, 0, 0.5, 0, np.pi / 2, 0], fidelity="massless")
    assert str(first.value) == str(again.value)
    bad = np.array([[0, 0, np.nan, 0, 0, 0]])
    messages = []
    for _ in range(2):
        with pytest.raises(ValueError) as e:
            p.limits(bad)
        messages.append(str(e.value))
    assert messages[0] == messages[1] and "row 0" in messages[0]
