"""What a master relies on: rollback, serialisation, several instances, reset, logging, bad
input, invalid parameters, warnings. FMI 2 and FMI 3."""
import math
import re

import numpy as np
import pytest

from fmu_support import (REPO, VERSIONS, REAL_OUTPUTS, L, POSE, POSE_DOT, POSE_DDOT, OK, WARNING,
                         DISCARD, ERROR, Unit, model_description,
                         require_fidelity, reference_matrix, stewart_solve, thesis_manoeuvre, opened_unit)
from reference import lengths as closed_form_lengths


def _drive(u, t0, poses, h=0.1):
    """Sets each pose at t0 + j h, records all outputs, steps; returns (n, m) outputs."""
    rows = []
    t = t0
    for p in poses:
        u.set_values(dict(zip(POSE, p)))
        r, i = u.outputs()
        rows.append(np.concatenate([r, [i["status"]]]))
        assert u.do_step(t, h) in (OK, WARNING)
        t += h
    return np.array(rows), t


def _poses(n, t0=0.0, kind="roll", h=0.1):
    q, _, _ = thesis_manoeuvre(kind, t0 + h * np.arange(n))
    return q


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("fidelity", [1, 2])
@pytest.mark.parametrize("derivatives", [0, 1])
def test_rollback_reproduces_outputs_bit_for_bit(version, fidelity, derivatives):
    require_fidelity(version, fidelity)
    with opened_unit(version) as u:
        assert u.init(fidelity=fidelity, derivatives=derivatives, x_dot=0.1, roll_ddot=0.5) == OK
        _, t = _drive(u, 0.0, _poses(5))
        state = u.get_state()
        poses = _poses(6, t)
        first, _ = _drive(u, t, poses)
        u.set_state(state)
        second, _ = _drive(u, t, poses)
        assert first.tobytes() == second.tobytes()
        # and through serialisation
        blob = u.serialize(state)
        u.free_state(state)
        _drive(u, t + 0.6, _poses(3, t + 0.6))
        restored = u.deserialize(blob)
        u.set_state(restored)
        third, _ = _drive(u, t, poses)
        assert first.tobytes() == third.tobytes()  # the solver's data block travels too
        assert u.serialize(restored) == blob
        u.free_state(restored)


def _nvr():
    """The arrays' length, FMU_NVR: above every value reference, with room to keep the model's
    pairs 16-byte aligned."""
    nvr = int(re.search(r"#define FMU_NVR (\d+)", (REPO / "fmu/models/inverse/config.h").read_text())[1])
    assert nvr > max(v.valueReference for v in model_description("3.0").modelVariables)
    return nvr


def _layout(u, blob):
    """Offsets of fields in a serialised state: magic (8 bytes), sizeof(fmu_values) (uint64), then
    fmu_values: real[NVR], integer[NVR] by value reference, ..., last_successful_time, mode (its
    last members). The test checks each offset against a known value before it corrupts it."""
    n = int.from_bytes(blob[8:16], "little")
    # the arrays' length, FMU_NVR, is above every value reference, with room to keep the
    # model's pairs 16-byte aligned
    nvr = _nvr()
    return dict(real=lambda vr: 16 + 8 * vr, integer=lambda vr: 16 + 8 * nvr + 4 * vr,
                last_successful_time=16 + n - 16, mode=16 + n - 8)


def _refused_then_intact_restores(u, blob, words, state, t):
    """The corrupted bytes `blob` are an Error whose message has `words`; the intact bytes of
    `state` (taken at t) still restore and step to finite outputs. Frees `state`."""
    u.messages.clear()
    with pytest.raises(Exception):
        u.deserialize(bytes(blob))
    m = [x for s, c, x in u.messages if s == ERROR]
    assert m and "corrupt state" in m[-1] and words in m[-1], u.messages
    restored = u.deserialize(bytes(u.serialize(state)))
    u.set_state(restored)
    assert u.do_step(t, 0.1) == OK
    assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
    u.free_state(restored)
    u.free_state(state)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("field,value,words", [
    ("L[1]", math.nan, "output L[1] is not finite"),
    ("F[6]", math.inf, "output F[6] is not finite"),
    ("status", 64, "status is not 0..3"),
    ("fidelity", 7, "fidelity = 7 is outside its declared range [0, 2]"),
    ("derivatives", -1, "derivatives = -1 is outside its declared range [0, 1]"),
    # the usual step's route (finite differences, two poses held) no longer what the values give
    ("limit_outputs", 1, "the usual step's route does not match the values"),
    ("mode", 0, "mode is not one of"),
    ("mode", 4 | 8, "mode is not one of"),
    ("mode", 16, "mode is not one of"),                 # error mode: no state is taken there
    ("last_successful_time", math.nan, "time is not finite"),
])
def test_corrupt_serialised_state_is_refused(version, field, value, words):
    """A serialised state whose bytes are intact in size and header but hold values no instance
    can have is an Error naming what is wrong, never a state that gives NaN outputs or an
    impossible status; the instance stays usable and the intact bytes still restore."""
    import struct
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        _, t = _drive(u, 0.0, _poses(3))
        state = u.get_state()
        blob = bytearray(u.serialize(state))
        at = _layout(u, blob)
        if field in ("mode", "last_successful_time"):
            offset = at[field]
            fmt = "<i" if field == "mode" else "<d"
            expected = 4 if field == "mode" else t   # MODE_STEP; the time after the last step
        else:
            var = u.vr[field]
            integer = field in ("status", "fidelity", "derivatives", "limit_outputs")
            offset, fmt = (at["integer"](var), "<i") if integer else (at["real"](var), "<d")
            expected = u.get([field])[0]
        assert struct.unpack_from(fmt, blob, offset)[0] == pytest.approx(expected, rel=1e-15)
        struct.pack_into(fmt, blob, offset, value)
        _refused_then_intact_restores(u, blob, words, state, t)


def _driven_state(u):
    """A massless unit with finite differences after three steps: its state, the state's bytes
    (to corrupt) and the time reached."""
    assert u.init(fidelity=1, derivatives=0) == OK
    _, t = _drive(u, 0.0, _poses(3))
    state = u.get_state()
    return state, bytearray(u.serialize(state)), t


@pytest.mark.parametrize("version", VERSIONS)
def test_corrupt_history_slot_is_refused(version):
    """The finite-difference history is two slots and the index of the newer one (the model's
    values follow the integers: n_history, then that index): an index other than 0 or 1 would
    read past the history, so a state holding one is an Error naming it; the intact bytes
    still restore and step."""
    import struct
    with opened_unit(version) as u:
        state, blob, t = _driven_state(u)
        n_history = 16 + 12 * _nvr()
        assert struct.unpack_from("<i", blob, n_history)[0] == 2  # two points held
        assert struct.unpack_from("<i", blob, n_history + 4)[0] in (0, 1)
        struct.pack_into("<i", blob, n_history + 4, 2)
        _refused_then_intact_restores(u, blob, "newer point is not 0 or 1", state, t)


@pytest.mark.parametrize("version", VERSIONS)
def test_history_without_a_step_is_refused(version):
    """The finite-difference history's points are committed by accepted steps, so the usual hold
    step leaves has_stepped as it is (issue 22): a state with a history and has_stepped 0 (the
    runtime's flag, 32 bytes before the values' end) is an Error naming it."""
    import struct
    with opened_unit(version) as u:
        state, blob, t = _driven_state(u)
        has_stepped = _layout(u, blob)["mode"] - 24
        assert struct.unpack_from("<i", blob, has_stepped)[0] == 1
        struct.pack_into("<i", blob, has_stepped, 0)
        _refused_then_intact_restores(u, blob, "history without a step", state, t)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("derivatives", [0, 1])
def test_step_after_terminate_is_refused_after_usual_steps(version, derivatives):
    """The usual doStep leaves the mode to the model's route, which is the full rules outside step
    mode (issue 22): after usual steps and Terminate, a doStep is still an Error naming the call
    order, the outputs stay, and FMI 3's lastSuccessfulTime is the unit's time, not t + h."""
    import ctypes
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=derivatives) == OK
        poses = _poses(5)
        _, t = _drive(u, 0.0, poses[:4])
        u.set_values(dict(zip(POSE, poses[4])))
        before = u.get_reals(REAL_OUTPUTS)
        assert getattr(u.dll, "fmi2Terminate" if version == "2.0" else "fmi3Terminate")(u.c) == OK
        u.messages.clear()
        if version == "2.0":
            assert u.dll.fmi2DoStep(u.c, t, 0.1, 1) == ERROR
        else:
            flags = [ctypes.c_bool(True) for _ in range(3)]
            last = ctypes.c_double(-1.0)
            assert u.dll.fmi3DoStep(u.c, ctypes.c_double(t), ctypes.c_double(0.1), ctypes.c_bool(True),
                                    *(ctypes.byref(f) for f in flags), ctypes.byref(last)) == ERROR
            assert last.value == t and not any(f.value for f in flags)
        assert any("DoStep" in m for s, c, m in u.messages if s == ERROR), u.messages
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()


@pytest.mark.parametrize("version", VERSIONS)
def test_serialised_state_with_options_beyond_their_declared_range(version):
    """Whatever initialisation accepted, deserialisation accepts: max_iterations at the top of
    its range (1000)."""
    with opened_unit(version) as u:
        assert u.init(fidelity=2, max_iterations=1000) in (OK, WARNING)
        state = u.get_state()
        restored = u.deserialize(u.serialize(state))
        u.set_state(restored)
        assert u.do_step(0.0, 0.1) in (OK, WARNING)
        u.free_state(restored)
        u.free_state(state)


@pytest.mark.parametrize("version", VERSIONS)
def test_step_from_before_the_units_time_is_an_error(version):
    """doStep(t, h) with t before the end of the last step (and after the one before) would take
    the pose of the unit's time for an earlier one: Error naming both times; a t off by a
    rounding is accepted."""
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        _, t = _drive(u, 0.0, _poses(3))       # t = 0.3; the last accepted point is 0.2
        before = u.get_reals(REAL_OUTPUTS)
        u.messages.clear()
        assert u.do_step(t - 0.05, 0.1) == ERROR
        m = [x for s, c, x in u.messages if s == ERROR]
        assert m and "is before the unit's time" in m[-1], u.messages
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        assert t == 0.30000000000000004       # the unit's time, 0.1 + 0.1 + 0.1
        assert u.do_step(0.3, 0.1) == OK        # one ulp earlier, as a master's n h gives it


@pytest.mark.parametrize("version", VERSIONS)
def test_rollback_with_a_variable_step(version):
    """A rejected step is redone with a smaller one: the result equals a fresh run that took the
    smaller step directly."""
    q = _poses(4)
    u, v = Unit(version, "a"), Unit(version, "b")
    try:
        for w in (u, v):
            assert w.init(fidelity=1) == OK
            _drive(w, 0.0, q[:3])
        s = u.get_state()
        u.set_values(dict(zip(POSE, q[3])))
        assert u.do_step(0.3, 0.1) == OK
        u.set_state(s)
        u.free_state(s)
        later = _poses(1, 0.35)[0]
        for w in (u, v):
            w.set_values(dict(zip(POSE, later)))
        assert u.get_reals(REAL_OUTPUTS).tobytes() == v.get_reals(REAL_OUTPUTS).tobytes()
    finally:
        u.free()
        v.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_two_instances_side_by_side(version):
    """Two instances with different parameters, stepped interleaved in one process, each equal
    to its own closed form / reference."""
    a, b = Unit(version, "a"), Unit(version, "b")
    try:
        assert a.init(fidelity=1) == OK
        assert b.init(fidelity=0, base_radius=0.6, platform_radius=0.45) == OK
        q = _poses(8, kind="yaw")
        ta = []
        for j, p in enumerate(q):
            for u in (a, b):
                u.set_values(dict(zip(POSE, p)))
            np.testing.assert_allclose(a.get_reals(L), closed_form_lengths(p), rtol=1e-12)
            np.testing.assert_allclose(b.get_reals(L), closed_form_lengths(p, 0.6, 0.45),
                                       rtol=1e-12)
            assert np.all(b.get_reals(("F[1]", "F[6]")) == 0.0)
            ta.append(a.get_reals(L + tuple(f"F[{k}]" for k in range(1, 7))))
            for u in (a, b):
                assert u.do_step(0.1 * j, 0.1) == OK
        from fmu_support import backward_fd
        t = 0.1 * np.arange(len(q))
        qd, qdd = backward_fd(t, q)
        ref = reference_matrix(stewart_solve(t, q, qd, qdd))
        np.testing.assert_allclose(np.array(ta), np.hstack([ref[:, :6], ref[:, 18:]]),
                                   rtol=1e-9, atol=1e-9)
    finally:
        a.free()
        b.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_reset(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1, base_radius=0.55) == OK
        u.set(z=0.6)
        first = u.get_reals(REAL_OUTPUTS)
        u.do_step(0.0, 0.1)
        assert u.reset() == OK
        # back to the start values
        assert u.enter_init() == OK
        assert u.get(["base_radius", "z", "fidelity"]) == [0.5, 0.5, 2]
        if version == "3.0":
            assert u.get(["time"])[0] == 0.0
        u.set(fidelity=1, base_radius=0.55, z=0.6)
        assert u.exit_init() == OK
        assert u.get_reals(REAL_OUTPUTS).tobytes() == first.tobytes()


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name,value", [("x", math.nan), ("yaw", math.inf), ("z_dot", -math.inf),
                                        ("pitch_ddot", math.nan)])
def test_non_finite_input_is_discarded(version, name, value):
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        q = _poses(3)
        _drive(u, 0.0, q[:2])
        before = u.get_reals(REAL_OUTPUTS)
        u.set_values({name: value})
        assert u.get(["status"])[0] == 3
        after = u.get_reals(REAL_OUTPUTS)
        assert after.tobytes() == before.tobytes()  # last valid outputs, no NaN
        assert u.do_step(0.2, 0.1) == DISCARD
        text = u.messages_text()
        assert f"input {name} = " in text and ("nan" in text or "inf" in text), text
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
        # the next good step succeeds
        u.set_values({name: 0.0})
        u.set_values(dict(zip(POSE, q[2])))
        assert u.get(["status"])[0] == 0
        assert u.do_step(0.2, 0.1) == OK
        np.testing.assert_allclose(u.get_reals(L), closed_form_lengths(q[2]), rtol=1e-12)


@pytest.mark.parametrize("version", VERSIONS)
def test_unreachable_pose_is_discarded(version):
    """z = 0 with yaw = 30 deg puts platform point 1 on base point 1 (closed form: L1 = 0)."""
    bad = [0.0, 0.0, 0.0, 0.0, 0.0, math.radians(30)]
    assert closed_form_lengths(bad)[0] < 1e-12
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        before = u.get_reals(REAL_OUTPUTS)
        u.set_values(dict(zip(POSE, bad)))
        assert u.do_step(0.0, 0.1) == DISCARD
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        discard = [m for s, c, m in u.messages if s == DISCARD]
        assert discard and "yaw" in discard[-1] and "0.523599" in discard[-1], u.messages
        assert all(c == "logStatusDiscard" for s, c, m in u.messages if s == DISCARD)
        u.set(z=0.5, yaw=0.0)
        assert u.do_step(0.0, 0.1) == OK
        assert u.get(["status"])[0] == 0


@pytest.mark.parametrize("version", VERSIONS)
def test_taylor_advance_into_an_unreachable_pose_is_discarded(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=1, z_dot=-5.0) == OK
        before = u.get_reals(REAL_OUTPUTS)
        assert u.do_step(0.0, 0.1) == DISCARD  # z would reach 0
        assert u.get_reals(REAL_OUTPUTS).tobytes() == before.tobytes()
        assert u.get(["z"])[0] == 0.5
        u.set(z_dot=0.0)
        assert u.do_step(0.0, 0.1) == OK


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name,value,words", [
    ("base_radius", -0.1, "base_radius"),
    ("platform_mass", math.nan, "platform_mass"),
    ("stroke_max[1]", 0.3, "stroke"),
    ("tolerance", 0.0, "tolerance"),
])
def test_invalid_parameter_at_initialisation_is_an_error(version, name, value, words):
    with opened_unit(version) as u:
        u.set_values({name: value})
        assert u.enter_init() == OK
        assert u.exit_init() == ERROR
        errors = [m for s, c, m in u.messages if s == ERROR]
        assert errors and words in errors[-1], u.messages
        assert u.reset() == OK  # and the instance can be reset and used
        assert u.init(fidelity=1) == OK


@pytest.mark.parametrize("version", VERSIONS)
def test_stroke_limit_gives_warning_and_status_1(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        u.set(z=0.75)  # closed form: every leg longer than stroke_max = 0.7 m
        assert np.all(closed_form_lengths([0, 0, 0.75, 0, 0, 0]) > 0.7)
        assert u.get(["status"])[0] == 1
        assert u.do_step(0.0, 0.1) == WARNING
        warnings = [(c, m) for s, c, m in u.messages if s == WARNING]
        assert warnings and warnings[-1][0] == "logStatusWarning" and "stroke" in warnings[-1][1]
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))


@pytest.mark.parametrize("version", VERSIONS)
def test_near_singular_gives_warning_and_status_2(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1, warn_condition=1.0) == WARNING
        assert u.get(["status"])[0] == 2
        assert u.do_step(0.0, 0.1) == WARNING
        assert any("singular" in m for s, c, m in u.messages if s == WARNING)


@pytest.mark.parametrize("version", VERSIONS)
def test_singular_is_discarded(version):
    with opened_unit(version) as u:
        s = u.init(fidelity=1, warn_condition=1.0, singular_condition=1.0)
        assert s == WARNING and u.get(["status"])[0] == 3  # initial pose not solved
        assert u.do_step(0.0, 0.1) == DISCARD
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))


@pytest.mark.parametrize("version", VERSIONS)
def test_only_enabled_log_categories_reach_the_logger(version):
    with opened_unit(version) as u:
        u.set_debug_logging(False, [])          # all off
        u.set_debug_logging(True, ["logStatusDiscard"])
        assert u.init(fidelity=1) == OK
        u.set(z=0.75)
        assert u.do_step(0.0, 0.1) == WARNING   # not logged: category off
        u.set(x=math.nan)
        assert u.do_step(0.1, 0.1) == DISCARD   # logged
        assert u.messages and all(c == "logStatusDiscard" for _, c, _ in u.messages), u.messages
        n = len(u.messages)
        u.set_debug_logging(False, ["logStatusDiscard"])
        u.set(x=math.inf)
        assert u.do_step(0.1, 0.1) == DISCARD
        assert len(u.messages) == n
    v = Unit(version, logging=False)
    try:
        v.set(x=math.nan)
        assert v.init(fidelity=1) == WARNING
        assert v.messages == []
    finally:
        v.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_calls_out_of_sequence_are_errors(version):
    with opened_unit(version) as u:
        assert u.do_step(0.0, 0.1) == ERROR
        assert u.init(fidelity=1) == OK
        vr = u.vr["base_radius"]
        setter = u.dll.fmi2SetReal if version == "2.0" else u.dll.fmi3SetFloat64
        import ctypes
        arr_vr = (ctypes.c_uint32 * 1)(vr)
        val = (ctypes.c_double * 1)(0.7)
        args = (u.c, arr_vr, 1, val) if version == "2.0" else (u.c, arr_vr, 1, val, 1)
        assert setter(*args) == ERROR  # fixed parameter after initialisation
        assert any("base_radius" in m for s, c, m in u.messages if s == ERROR)
        assert u.do_step(0.0, -0.1) == ERROR


@pytest.mark.parametrize("version", VERSIONS)
def test_misuse_returns_error_and_does_not_crash(version):
    import ctypes
    with opened_unit(version) as u:
        assert u.init(fidelity=1) == OK
        d, c = u.dll, u.c
        vr = (ctypes.c_uint32 * 1)(9999)
        vr_int = (ctypes.c_uint32 * 1)(u.vr["fidelity"])
        val = (ctypes.c_double * 1)()
        ival = (ctypes.c_int32 * 1)()
        if version == "2.0":
            assert d.fmi2GetReal(c, vr, 1, val) == ERROR            # no such variable
            assert d.fmi2GetReal(c, vr_int, 1, val) == ERROR        # an Integer asked as Real
            assert d.fmi2GetInteger(c, vr_int, 1, ival) == OK and ival[0] == 1
            assert d.fmi2GetReal(c, None, 1, None) == ERROR         # NULL arrays
            assert d.fmi2GetBoolean(c, vr, 1, ival) == ERROR
            assert d.fmi2SetRealInputDerivatives(c, vr_int, 1, (ctypes.c_int * 1)(1), val) == ERROR
            assert d.fmi2DeSerializeFMUstate(c, b"garbage", 7, ctypes.byref(ctypes.c_void_p())) == ERROR
            assert d.fmi2FreeFMUstate(c, ctypes.byref(ctypes.c_void_p())) == OK
            assert d.fmi2GetDerivatives(c, val, 1) == ERROR        # model exchange: not provided
            assert d.fmi2Terminate(c) == OK
            assert d.fmi2DoStep(c, 0.0, 0.1, 1) == ERROR            # after Terminate
            assert d.fmi2GetReal(c, (ctypes.c_uint32 * 1)(u.vr["L[1]"]), 1, val) == OK
        else:
            assert d.fmi3GetFloat64(c, vr, 1, val, 1) == ERROR
            assert d.fmi3GetFloat64(c, vr_int, 1, val, 1) == ERROR
            assert d.fmi3GetFloat64(c, (ctypes.c_uint32 * 1)(u.vr["L[1]"]), 1, val, 2) == ERROR
            assert d.fmi3GetInt32(c, vr_int, 1, ival, 1) == OK and ival[0] == 1
            assert d.fmi3GetFloat64(c, None, 1, None, 1) == ERROR
            assert d.fmi3GetBoolean(c, vr, 1, (ctypes.c_bool * 1)(), 1) == ERROR
            assert d.fmi3DeserializeFMUState(c, (ctypes.c_ubyte * 7)(*b"garbage"), 7,
                                             ctypes.byref(ctypes.c_void_p())) == ERROR
            assert d.fmi3EnterStepMode(c) == ERROR
            assert d.fmi3Terminate(c) == OK
            assert d.fmi3EnterInitializationMode(c, 0, 0.0, 0.0, 0, 0.0) == ERROR
        assert np.all(np.isfinite(u.get_reals(REAL_OUTPUTS)))
        assert any(c_ == "logStatusError" for s, c_, m in u.messages if s == ERROR)


@pytest.mark.parametrize("version", VERSIONS)
def test_instantiation_checks_the_token(version):
    from fmpy.fmi2 import FMU2Slave
    from fmpy.fmi3 import FMU3Slave
    from fmu_support import unzipped
    cls = FMU2Slave if version == "2.0" else FMU3Slave
    f = cls(guid="{00000000-0000-0000-0000-000000000000}", unzipDirectory=unzipped(version),
            modelIdentifier="StewartPlatform", instanceName="wrong")
    with pytest.raises(Exception):
        if version == "2.0":
            f.instantiate()
        else:
            f.instantiate(logMessage=lambda *a: None)
    f.freeLibrary()
