"""The inverse unit's check that every input is finite, now made when a value is set (the runtime
flags a value that is not finite, so that the usual doStep need not look at every input): the
paths that reach the inputs some other way still name the input. A finite pose that overflows when
the Taylor advance takes it to t + h, and a serialised state whose flag was cleared while an input
is NaN (the flag in the bytes is not trusted). FMI 2 and FMI 3."""
import math
import struct

import pytest

from fmu_support import VERSIONS, REAL_OUTPUTS, OK, DISCARD, Unit, opened_unit

BIG = 1.7e308  # finite; BIG + 0.5 * 1e308 is not


@pytest.mark.parametrize("version", VERSIONS)
def test_taylor_advance_that_overflows_names_the_input(version):
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=1) == OK
        assert u.do_step(0.0, 0.1) == OK
        kept = u.get_reals(REAL_OUTPUTS)
        u.set(x=BIG, x_dot=1e308)
        u.messages.clear()
        assert u.do_step(0.1, 0.5) == DISCARD
        text = u.messages_text()
        # reported against t + h, where the advanced x is infinite
        assert "t = 0.59999999999999998: input x = inf is not finite" in text, text
        assert u.get(["status"])[0] == 3
        assert u.get_reals(REAL_OUTPUTS).tobytes() == kept.tobytes()
        assert u.get(["x", "x_dot"]) == [BIG, 1e308]  # the inputs of t, not the advanced ones
        u.set(x=0.0, x_dot=0.0)
        assert u.do_step(0.1, 0.1) == OK
        assert u.get(["status"])[0] == 0


@pytest.mark.parametrize("version", VERSIONS)
def test_restored_state_is_checked_whatever_its_flag_says(version):
    """derivatives = 0: without the check the NaN would reach the finite differences, which
    blame the step size instead of naming the input."""
    with opened_unit(version) as u:
        assert u.init(fidelity=1, derivatives=0) == OK
        assert u.do_step(0.0, 0.1) == OK
        assert u.do_step(0.1, 0.1) == OK
        u.set(x=math.nan)
        state = u.get_state()
        blob = bytearray(u.serialize(state))
        # fmu_values ends: ..., outputs_current, inputs_unchecked, last_step_status (ints),
        # last_successful_time (double), mode (int, padded)
        n = int.from_bytes(blob[8:16], "little")
        flag = 16 + n - 24
        assert struct.unpack_from("<i", blob, flag)[0] == 1  # set by the NaN
        assert struct.unpack_from("<d", blob, flag + 8)[0] == pytest.approx(0.2)  # the offset
        struct.pack_into("<i", blob, flag, 0)
        u.set(x=0.0)
        assert u.do_step(0.2, 0.1) == OK
        restored = u.deserialize(bytes(blob))
        u.set_state(restored)
        u.messages.clear()
        assert u.do_step(0.2, 0.1) == DISCARD
        assert "input x = nan is not finite" in u.messages_text(), u.messages_text()
        u.free_state(restored)
        u.free_state(state)
