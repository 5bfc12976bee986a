"""The FMU side of the reliability probe (issue 15): recovery from Error through FMU state, solver
data a state brings that the library refuses, the status and outputs of every Discard, messages
that name the culprit, and the probe's misuse checks (NULL instances, bad tokens and resource
URIs, states across instances, random serialised buffers, instances in threads). FMI 2 and FMI 3.
"""
import ctypes
import math
import struct
import sys
import threading

import numpy as np
import pytest

from fmu_support import (VERSIONS, REAL_OUTPUTS, INT_OUTPUTS, POSE, OK, WARNING, DISCARD, ERROR,
                         Unit, fidelity_available, thesis_manoeuvre, opened_unit)


def _step_messages(u, status):
    return [m for s, c, m in u.messages if s == status]


def _poses(n, t0=0.0, kind="roll", h=0.1):
    q, _, _ = thesis_manoeuvre(kind, t0 + h * np.arange(n))
    return q


def _drive(u, t, poses, h=0.1):
    """Sets each pose, steps from t, records every output after the step; returns (rows, t)."""
    rows = []
    for p in poses:
        u.set_values(dict(zip(POSE, p)))
        assert u.do_step(t, h) in (OK, WARNING)
        t += h
        r, i = u.outputs()
        rows.append(np.concatenate([r, [i["status"], i["newton_iterations"]]]))
    return np.array(rows), t


def _solver_block(blob):
    """Offset of the solver data block (the library's saved state) in a serialised FMU state:
    magic (8), sizeof(fmu_values) (uint64), the values, the block's size (uint64), the block."""
    n = int.from_bytes(blob[8:16], "little")
    size = int.from_bytes(blob[16 + n:24 + n], "little")
    assert size == len(blob) - (24 + n) and size > 0
    return 24 + n


def _full_model_state(version):
    """An instance at fidelity 2 after three steps, with a state taken there: (unit, t, state);
    skips where the build has no full model (the solver block is its state)."""
    if not fidelity_available(version, 2):
        pytest.skip("the solver block exists at fidelity 2")
    u = Unit(version)
    assert u.init(fidelity=2) in (OK, WARNING)
    _, t = _drive(u, 0.0, _poses(3))
    return u, t, u.get_state()


def _first_q(blob):
    """Offset of q[0] (the base body's x) in the solver block: tag (8), three uint64 counts, two
    int32 flags, then q (7 per body: position, then the Euler parameters)."""
    at = _solver_block(blob)
    assert blob[at:at + 8] == b"MBSSTAT1"
    return at + 8 + 24 + 8


# ---------------------------------------------------------------- 1. recovery from Error

@pytest.mark.parametrize("version", VERSIONS)
def test_set_state_recovers_from_error(version):
    """FMI 2 §2.1.3 and FMI 3 name restoring an FMU state as a way out of Error: after
    ExitInitializationMode returns Error (base_radius = -1), SetFMUState with a state saved
    earlier succeeds, the instance is back in the state's mode (step mode: doStep works) and
    reproduces what it did from that state bit for bit."""
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        _, t = _drive(u, 0.0, _poses(3))
        state = u.get_state()
        later = _poses(4, t)
        first, _ = _drive(u, t, later)
        assert u.reset() == OK
        u.set(base_radius=-1.0)
        assert u.enter_init() == OK
        assert u.exit_init() == ERROR          # the instance is in Error now
        assert u.do_step(t, 0.1) == ERROR
        u.set_state(state)                     # raises if refused ("not allowed in error")
        second, _ = _drive(u, t, later)
        assert first.tobytes() == second.tobytes()
        u.free_state(state)


@pytest.mark.parametrize("version", VERSIONS)
def test_state_before_initialisation_recovers_from_error_to_instantiated(version):
    """A state taken before initialisation brings an instance in Error back to that mode: it can
    be initialised again, with the state's (valid) parameters."""
    with opened_unit(version) as u:
        state = u.get_state()                   # instantiated, default parameters
        u.set(base_radius=-1.0)
        assert u.enter_init() == OK
        assert u.exit_init() == ERROR
        u.set_state(state)
        u.set(fidelity=1)
        assert u.enter_init() == OK
        assert u.exit_init() == OK
        assert u.get(["base_radius"])[0] == 0.5
        assert u.do_step(0.0, 0.1) == OK
        u.free_state(state)


# ---------------------------------------------------------------- 2. solver data the library refuses

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("index", [0, 3, 10])  # base x, base e0, a body further on
def test_solver_data_the_library_refuses_is_refused(version, index):
    """A serialised state whose solver block stewart_data_load refuses (here: a NaN in q, which
    the library has always refused) is an Error of DeserializeFMUState or SetFMUState with a
    message, never accepted with the data silently reset; the instance stays usable and the
    intact bytes still restore."""
    u, t, state = _full_model_state(version)
    try:
        blob = bytearray(u.serialize(state))
        struct.pack_into("<d", blob, _first_q(blob) + 8 * index, math.nan)
        u.messages.clear()
        refused = False
        try:
            restored = u.deserialize(bytes(blob))
        except Exception:
            refused = True
        else:
            try:
                u.set_state(restored)
            except Exception:
                refused = True
            u.free_state(restored)
        assert refused, "a solver block the library refuses was accepted"
        m = _step_messages(u, ERROR)
        assert m and "solver data" in m[-1] and "refused" in m[-1], u.messages
        good = u.deserialize(u.serialize(state))
        u.set_state(good)
        assert u.do_step(t, 0.1) in (OK, WARNING)
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
        u.free_state(good)
        u.free_state(state)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("value", [0.0, -1.0, 1e3, 1e300])
def test_corrupt_euler_parameter_is_refused_or_harmless(version, value):
    """The probe's case: one of the base body's Euler parameters changed inside a serialised
    state. Either the state is refused with a message, or the instance is not stuck: the next
    good steps give what the intact state gives."""
    u, t, state = _full_model_state(version)
    try:
        later = _poses(4, t)
        expected, _ = _drive(u, t, later)
        blob = bytearray(u.serialize(state))
        struct.pack_into("<d", blob, _first_q(blob) + 8 * 3, value)
        try:
            restored = u.deserialize(bytes(blob))
            u.set_state(restored)
        except Exception:
            assert "refused" in _step_messages(u, ERROR)[-1]
            return
        got, _ = _drive(u, t, later)
        np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-9)
    finally:
        u.free()


# ---------------------------------------------------------------- 5. every Discard: status 3, outputs kept

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("read_before", [False, True])
def test_taylor_advance_that_cannot_be_solved(version, read_before):
    """derivatives = 1 and x_dot = 1e8: the pose advanced to t + h cannot be solved. Discard,
    status = 3, the outputs keep their last valid values (not re-solved at t), time stays; a
    retry with a rate that can be followed succeeds."""
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=1, x_dot=0.01) == OK
        assert u.do_step(0.0, 0.1) == OK
        kept = u.get_reals(REAL_OUTPUTS)
        u.set(x_dot=1e8)
        if read_before:
            u.get_reals(REAL_OUTPUTS)            # the outputs at t with the new rate
            kept = u.get_reals(REAL_OUTPUTS)
        assert u.do_step(0.1, 0.1) == DISCARD
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == kept.tobytes()
        assert u.get(["status"])[0] == 3         # reading does not re-solve
        assert u.do_step(0.1, 0.1) == DISCARD    # the same retry: the same answer
        assert u.get(["status"])[0] == 3
        u.set(x_dot=0.01)
        assert u.do_step(0.1, 0.1) == OK
        assert u.get(["status"])[0] == 0


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("derivatives", [0, 1])
@pytest.mark.parametrize("bad", [{"x": math.nan}, {"pitch_ddot": math.inf},
                                 {"z": 0.0, "yaw": math.radians(30)},   # L[1] = 0: unreachable
                                 {"x": sys.float_info.max},
                                 {"z_dot": -5.0}])                      # advanced to z = 0
def test_every_discard_sets_status_3_and_keeps_the_outputs(version, derivatives, bad):
    """Whatever makes a step Discard (a non-finite input, an unreachable pose, a pose whose
    finite differences overflow, at t or advanced to t + h), status is 3 and the outputs are the
    last valid ones, read right after the step; the next good step succeeds."""
    if "z_dot" in bad and derivatives == 0:
        pytest.skip("z_dot is used with derivatives = 1 only")
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=derivatives) == OK
        assert u.do_step(0.0, 0.1) == OK
        kept = u.get_reals(REAL_OUTPUTS)
        good = dict(zip(bad, u.get(list(bad))))
        u.set_values(bad)
        s = u.do_step(0.1, 0.1)
        assert s == DISCARD, (s, u.messages[-3:])
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == kept.tobytes()
        u.set_values(good)
        assert u.do_step(0.1, 0.1) == OK
        assert u.get(["status"])[0] == 0


# ---------------------------------------------------------------- 8, 10. messages

@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name,value", [("x", sys.float_info.max), ("yaw", -sys.float_info.max),
                                        ("z", 1e308)])
def test_huge_pose_with_finite_differences_names_the_input(version, name, value):
    """derivatives = 0 and a pose coordinate of DBL_MAX: the finite differences overflow because
    of the input, not because the steps are small: the message names the input and its value."""
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=0) == OK
        assert u.do_step(0.0, 0.1) == OK
        u.set(**{name: value})
        u.messages.clear()
        assert u.do_step(0.1, 0.1) == DISCARD
        m = _step_messages(u, DISCARD)
        assert m, u.messages
        assert f"input {name} = " in m[-1] and "too large" in m[-1], m[-1]
        assert "too small" not in m[-1] and "larger steps" not in m[-1], m[-1]
        assert u.get(["status"])[0] == 3


@pytest.mark.parametrize("version", VERSIONS)
def test_set_state_null_says_the_state_is_null(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        u.messages.clear()
        f = u.dll.fmi2SetFMUstate if version == "2.0" else u.dll.fmi3SetFMUState
        assert f(u.c, None) == ERROR
        m = _step_messages(u, ERROR)
        assert m and "state is NULL" in m[-1] and "value reference" not in m[-1], m
        assert u.do_step(0.0, 0.1) == OK        # still usable


# ---------------------------------------------------------------- misuse (the probe's checks)

def _null_calls(version, dll):
    """Every call that takes an instance, with NULL for it (and harmless other arguments)."""
    vr = (ctypes.c_uint32 * 1)(0)
    real = (ctypes.c_double * 1)()
    integer = (ctypes.c_int32 * 1)()
    order = (ctypes.c_int32 * 1)(1)
    state = ctypes.c_void_p()
    size = ctypes.c_size_t()
    byte = (ctypes.c_ubyte * 8)()
    if version == "2.0":
        byte = ctypes.create_string_buffer(8)
        status, d = ctypes.c_int(), ctypes.c_double()
        return [
            lambda: dll.fmi2SetDebugLogging(None, 1, 0, None),
            lambda: dll.fmi2SetupExperiment(None, 0, 0.0, 0.0, 0, 0.0),
            lambda: dll.fmi2EnterInitializationMode(None),
            lambda: dll.fmi2ExitInitializationMode(None),
            lambda: dll.fmi2Terminate(None),
            lambda: dll.fmi2Reset(None),
            lambda: dll.fmi2GetReal(None, vr, 1, real),
            lambda: dll.fmi2GetInteger(None, vr, 1, integer),
            lambda: dll.fmi2SetReal(None, vr, 1, real),
            lambda: dll.fmi2SetInteger(None, vr, 1, integer),
            lambda: dll.fmi2GetBoolean(None, vr, 1, integer),
            lambda: dll.fmi2SetRealInputDerivatives(None, vr, 1, order, real),
            lambda: dll.fmi2GetFMUstate(None, ctypes.byref(state)),
            lambda: dll.fmi2SetFMUstate(None, None),
            lambda: dll.fmi2FreeFMUstate(None, ctypes.byref(state)),
            lambda: dll.fmi2SerializedFMUstateSize(None, None, ctypes.byref(size)),
            lambda: dll.fmi2SerializeFMUstate(None, None, byte, 8),
            lambda: dll.fmi2DeSerializeFMUstate(None, byte, 8, ctypes.byref(state)),
            lambda: dll.fmi2DoStep(None, 0.0, 0.1, 1),
            lambda: dll.fmi2CancelStep(None),
            lambda: dll.fmi2GetStatus(None, 0, ctypes.byref(status)),
            lambda: dll.fmi2GetRealStatus(None, 2, ctypes.byref(d)),
            lambda: dll.fmi2GetBooleanStatus(None, 4, ctypes.byref(status)),
            lambda: dll.fmi2GetDirectionalDerivative(None, vr, 1, vr, 1, real, real),
        ]
    flag, last = ctypes.c_bool(), ctypes.c_double()
    return [
        lambda: dll.fmi3SetDebugLogging(None, 1, 0, None),
        lambda: dll.fmi3EnterInitializationMode(None, 0, 0.0, 0.0, 0, 0.0),
        lambda: dll.fmi3ExitInitializationMode(None),
        lambda: dll.fmi3Terminate(None),
        lambda: dll.fmi3Reset(None),
        lambda: dll.fmi3GetFloat64(None, vr, 1, real, 1),
        lambda: dll.fmi3GetInt32(None, vr, 1, integer, 1),
        lambda: dll.fmi3SetFloat64(None, vr, 1, real, 1),
        lambda: dll.fmi3SetInt32(None, vr, 1, integer, 1),
        lambda: dll.fmi3GetFMUState(None, ctypes.byref(state)),
        lambda: dll.fmi3SetFMUState(None, None),
        lambda: dll.fmi3FreeFMUState(None, ctypes.byref(state)),
        lambda: dll.fmi3SerializedFMUStateSize(None, None, ctypes.byref(size)),
        lambda: dll.fmi3SerializeFMUState(None, None, byte, 8),
        lambda: dll.fmi3DeserializeFMUState(None, byte, 8, ctypes.byref(state)),
        lambda: dll.fmi3DoStep(None, 0.0, 0.1, 1, ctypes.byref(flag), ctypes.byref(flag),
                               ctypes.byref(flag), ctypes.byref(last)),
        lambda: dll.fmi3EnterStepMode(None),
        lambda: dll.fmi3GetNumberOfContinuousStates(None, ctypes.byref(size)),
    ]


@pytest.mark.parametrize("version", VERSIONS)
def test_null_instance_is_an_error_everywhere(version):
    with opened_unit(version) as u:
        for j, call in enumerate(_null_calls(version, u.dll)):
            assert call() == ERROR, j
        getattr(u.dll, "fmi2FreeInstance" if version == "2.0" else "fmi3FreeInstance")(None)
        assert u.init(fidelity=1) == OK         # the live instance is untouched
        assert u.do_step(0.0, 0.1) == OK


@pytest.mark.parametrize("version", VERSIONS)
def test_tokens_and_resource_uris(version):
    """A wrong, empty or NULL GUID / instantiationToken (and FMI 2 model exchange) gives no
    instance, with a message; any resource URI, also NULL or not a URI, gives a working one
    (the unit needs no resources)."""
    u = Unit(version)
    dll = u.dll
    messages = []
    try:
        if version == "2.0":
            from fmpy.fmi2 import (fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                                   fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE)
            import fmpy
            cb = fmi2CallbackFunctions()
            cb.logger = fmi2CallbackLoggerTYPE(lambda env, name, s, cat, msg: messages.append(msg))
            cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.fmi2.calloc)
            cb.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.fmi2.free)

            def make(token, resources, kind=1):
                return dll.fmi2Instantiate(b"probe", kind, token, resources, ctypes.byref(cb), 0, 1)
            free = dll.fmi2FreeInstance
        else:
            from fmpy.fmi3 import fmi3LogMessageCallback
            log = fmi3LogMessageCallback(lambda env, s, cat, msg: messages.append(msg))

            no_update = dll.fmi3InstantiateCoSimulation.argtypes[11]()   # a NULL callback

            def make(token, resources, kind=None):
                return dll.fmi3InstantiateCoSimulation(b"probe", token, resources, 0, 1, 0, 0,
                                                       None, 0, None, log, no_update)
            free = dll.fmi3FreeInstance
        token = u.md.guid.encode()
        for bad in (b"{00000000-0000-0000-0000-000000000000}", b"", None, token + b" "):
            messages.clear()
            assert not make(bad, b"file:///tmp/")
            assert messages and b"does not match" in messages[-1]
        if version == "2.0":
            assert not make(token, b"file:///tmp/", kind=0)   # model exchange
        for resources in (None, b"", b"not a uri", b"file:///does/not/exist/", b"\xff\xfe"):
            c = make(token, resources)
            assert c, resources
            free(c)
    finally:
        u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_state_moves_between_instances(version):
    """A state taken by one instance, set on another (with other parameters, in another mode,
    even after the first is freed, and through serialisation) makes the second reproduce the
    first's outputs bit for bit."""
    a, b = Unit(version, "a"), Unit(version, "b")
    c = None
    try:
        assert a.init(fidelity=1) == OK
        assert b.init(fidelity=0, base_radius=0.6) == OK
        _, t = _drive(a, 0.0, _poses(3))
        state = a.get_state()
        blob = a.serialize(state)
        later = _poses(5, t)
        expected, _ = _drive(a, t, later)
        b.set_state(state)
        got, _ = _drive(b, t, later)
        assert got.tobytes() == expected.tobytes()
        a.free_state(state)
        a.free()
        a = None
        c = Unit(version, "c")                  # instantiated, never initialised
        restored = c.deserialize(blob)
        c.set_state(restored)
        got, _ = _drive(c, t, later)
        assert got.tobytes() == expected.tobytes()
        c.free_state(restored)
    finally:
        for u in (a, b, c):
            if u is not None:
                u.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_random_serialised_buffers(version):
    """Random bytes, and random bytes behind a valid header and size, are refused with Error (or,
    should one be a valid state, restore to finite outputs); the instance stays usable."""
    rng = np.random.default_rng(15)
    with opened_unit(version, logging=False) as u:
        assert u.init(fidelity=1) == OK
        state = u.get_state()
        blob = u.serialize(state)
        n = int.from_bytes(blob[8:16], "little")
        f = u.dll.fmi2DeSerializeFMUstate if version == "2.0" else u.dll.fmi3DeserializeFMUState
        refused = 0
        for trial in range(300):
            kind = trial % 3
            if kind == 0:
                data = rng.integers(0, 256, int(rng.integers(0, 2 * len(blob))), dtype=np.uint8).tobytes()
            elif kind == 1:      # header and sizes intact, the values random
                data = blob[:16] + rng.integers(0, 256, len(blob) - 16, dtype=np.uint8).tobytes()
                data = data[:16 + n] + blob[16 + n:24 + n] + data[24 + n:]
            else:                # one random byte of the intact blob changed
                b = bytearray(blob)
                b[int(rng.integers(0, len(b)))] = int(rng.integers(0, 256))
                data = bytes(b)
            buf = data if version == "2.0" else \
                (ctypes.c_ubyte * max(len(data), 1)).from_buffer_copy(data or b"\0")
            s = ctypes.c_void_p()
            status = f(u.c, buf, len(data), ctypes.byref(s))
            if status == ERROR:
                refused += 1
                assert not s.value
                continue
            assert status == OK
            setter = u.dll.fmi2SetFMUstate if version == "2.0" else u.dll.fmi3SetFMUState
            if setter(u.c, s) == OK:
                assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
                assert 0 <= u.get(["status"])[0] <= 3
            u.free_state(s)
            u.set_state(state)
        assert refused >= 200    # kinds 0 and 1 are never states
        u.set_state(state)
        assert u.do_step(0.0, 0.1) == OK
        u.free_state(state)


def _run(version, fidelity, phase, steps=120):
    """One instance over a yaw manoeuvre shifted by `phase`: the outputs after each step."""
    with opened_unit(version, f"t{phase}", logging=False) as u:
        assert u.init(fidelity=fidelity) in (OK, WARNING)
        q = _poses(steps, 0.37 * phase, kind="yaw", h=0.01)
        rows, _ = _drive(u, 0.0, q, h=0.01)
        return rows.tobytes()


@pytest.mark.parametrize("version", VERSIONS)
def test_eight_instances_in_threads_equal_sequential_runs(version):
    """8 instances stepped at once in 8 threads give, bit for bit, what each gives alone (no
    shared mutable state; ctypes releases the GIL during each FMI call)."""
    fidelity = 2 if fidelity_available(version, 2) else 1
    sequential = [_run(version, fidelity, k) for k in range(8)]
    threaded = [None] * 8
    errors = []

    def work(k):
        try:
            threaded[k] = _run(version, fidelity, k)
        except BaseException as e:   # reported below: a thread's exception is otherwise lost
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert not errors, errors
    assert len(set(sequential)) == 8            # the runs differ from one another
    for k in range(8):
        assert threaded[k] == sequential[k], k
