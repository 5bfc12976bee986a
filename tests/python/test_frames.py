"""Tool and user frames and length_offset through Python keywords, `stewart-solve --param` and the
inverse FMU's parameters (docs/api.md, "Tool and user frames"): poses transformed by hand here
(numpy, the rotations of calibration_truth.py), pose rates by differences in time of the
transformed pose; bad frames refused by name; sensor readings against lengths computed here."""
import math

import numpy as np
import pytest

import stewart
from fmu_support import L, OK, POSE, VERSIONS, Unit, opened_unit
from calibration_truth import angles, rotation
from reference import lengths as closed_form_lengths
from test_cli import column, read

TOOL = np.array([0.02, -0.01, 0.10, 0.05, -0.04, 0.30])
USER = np.array([0.01, -0.02, 0.45, 0.02, -0.03, 0.40])
OFFSET = np.array([0.001, -0.002, 0.3, 0.0, 0.0005, -0.1])


def tool_pose(q, tool=TOOL, user=USER):
    """The tool's pose in the user frame with the platform at q in the base frame."""
    Rp, Ru, Rd = rotation(*q[3:]), rotation(*user[3:]), rotation(*tool[3:])
    origin = q[:3] + Rp @ tool[:3]
    return np.concatenate([Ru.T @ (origin - user[:3]), angles(Ru.T @ Rp @ Rd)])


def platform_pose(q, tool=TOOL, user=USER):
    """The platform's pose in the base frame with the tool at q in the user frame."""
    Rt, Ru, Rd = rotation(*q[3:]), rotation(*user[3:]), rotation(*tool[3:])
    Rp = Ru @ Rt @ Rd.T
    return np.concatenate([user[:3] + Ru @ q[:3] - Rp @ tool[:3], angles(Rp)])


def platform_path(t):
    """A smooth manoeuvre inside the thesis platform's workspace (N, 6)."""
    t = np.asarray(t)[:, None]
    amplitude = np.array([0.04, 0.03, 0.03, 0.08, 0.06, 0.12])
    omega = np.array([3.0, 2.0, 4.0, 2.5, 3.5, 1.5])
    q = amplitude * np.sin(omega * t + np.arange(6))
    q[:, 2] += 0.5
    return q


def framed(**more):
    return stewart.Platform(tool_frame=TOOL, user_frame=USER, **more)


def test_inverse_and_forward_take_and_give_the_tool_pose():
    t = np.linspace(0, 1, 41)
    q = platform_path(t)
    tool = np.array([tool_pose(p) for p in q])
    plain = stewart.Platform().inverse(q, fidelity="kinematic")
    mine = framed().inverse(tool, fidelity="kinematic")
    assert mine.ok.all() and plain.ok.all()
    np.testing.assert_allclose(mine.length, plain.length, atol=1e-13)
    back = framed().forward(plain.length, t=t)
    assert back.ok.all(), back.messages
    np.testing.assert_allclose(back.pose, tool, atol=1e-11)
    # the guess is the tool's pose: the exact one needs no Newton iteration
    one = framed().forward(plain.length[7:8], guess=tool[7])
    assert one.ok.all() and stewart.forward.START_NAMES[one.start[0]] == "guess" and one.iterations[0] <= 1


def test_forward_rates_are_the_tool_pose_rates():
    """Rates of the lengths in, the tool pose's rates out: against central differences in time of
    the hand-transformed pose."""
    dt = 1e-5
    t = np.linspace(0.1, 0.9, 9)
    q, q_ahead, q_behind = platform_path(t), platform_path(t + dt), platform_path(t - dt)
    plain = stewart.Platform()
    L = plain.inverse(q, fidelity="kinematic").length
    L_dot = (plain.inverse(q_ahead, fidelity="kinematic").length
             - plain.inverse(q_behind, fidelity="kinematic").length) / (2 * dt)
    out = framed().forward(L, rates=L_dot, t=t)
    assert out.ok.all(), out.messages
    tool_rate = (np.array([tool_pose(p) for p in q_ahead])
                 - np.array([tool_pose(p) for p in q_behind])) / (2 * dt)
    np.testing.assert_allclose(out.pose_rate, tool_rate, atol=1e-8)


def test_simulate_starts_at_and_returns_the_tool_pose():
    t = np.linspace(0, 0.02, 21)
    plain = stewart.Platform()
    start = platform_path([0.0])[0]
    forces = np.tile(plain.inverse(start[None, :]).force, (t.size, 1))
    a = plain.simulate(t, forces, fidelity="massless", start=start)
    b = framed().simulate(t, forces, fidelity="massless", start=tool_pose(start))
    assert a.completed and b.completed, b.message
    np.testing.assert_allclose(b.pose, [tool_pose(p) for p in a.pose], atol=1e-9)
    np.testing.assert_allclose(b.length, a.length, atol=1e-9)
    # rates: central differences of the transformed poses at the inner rows
    by_hand = np.array([tool_pose(p) for p in a.pose])
    differences = (by_hand[2:] - by_hand[:-2]) / (t[2:] - t[:-2])[:, None]
    np.testing.assert_allclose(b.pose_rate[1:-1], differences, atol=1e-5)


def test_length_offset_gives_readings():
    q = platform_path(np.linspace(0, 1, 11))
    p = stewart.Platform(length_offset=OFFSET)
    out = p.inverse(q, fidelity="kinematic")
    assert out.ok.all()
    expected = np.array([closed_form_lengths(pose) for pose in q]) - OFFSET
    np.testing.assert_allclose(out.length, expected, atol=1e-14)
    assert not out.warnings.any()  # leg 3 reads 0.2 m, but its Cardans are 0.5 m apart
    back = p.forward(out.length)
    np.testing.assert_allclose(back.pose, q, atol=1e-11)


@pytest.mark.parametrize("name,value,words", [
    ("tool_frame", [math.nan, 0, 0, 0, 0, 0], "tool_frame[1]"),
    ("user_frame", [0, 1e300, 0, 0, 0, 0], "user_frame[2]"),
    ("tool_frame", [0, 0, 0, 0, 0, 5e3], "tool_frame[6]"),
    ("length_offset", [0, 0, math.inf, 0, 0, 0], "length_offset[3]"),
    ("tool_frame", [0, 0, 0], "tool_frame has 3 values"),
])
def test_bad_frames_are_refused_by_name(name, value, words):
    with pytest.raises(stewart.ParameterError, match=words.replace("[", r"\[").replace("]", r"\]")):
        stewart.Platform(**{name: value})


def test_command_line_param(solve, tmp_path):
    """--param tool_frame[k]=..., user_frame[k]=..., length_offset[k]=...: the readings of the
    platform's pose behind the tool's, computed here."""
    tool = np.array([0.01, 0.02, 0.03, 0.02, 0.01, 0.2])
    pose = np.array([0.01, -0.02, 0.05, 0.05, -0.03, 0.1])
    pose_csv, out_csv = tmp_path / "in.csv", tmp_path / "out.csv"
    pose_csv.write_text("t,x,y,z,roll,pitch,yaw\n0," + ",".join(repr(float(v)) for v in pose) + "\n")
    args = []
    for k in range(6):
        args += ["--param", f"tool_frame[{k + 1}]={float(tool[k])!r}",
                 "--param", f"user_frame[{k + 1}]={float(USER[k])!r}",
                 "--param", f"length_offset[{k + 1}]={float(OFFSET[k])!r}"]
    result = solve(*args, pose_csv, out_csv)
    assert result.returncode == 0, result.stderr
    header, data = read(out_csv)
    got = np.array([column(header, data, f"L{k}")[0] for k in range(1, 7)])
    expected = closed_form_lengths(platform_pose(pose, tool, USER)) - OFFSET
    np.testing.assert_allclose(got, expected, atol=1e-13)


@pytest.mark.parametrize("version", VERSIONS)
def test_inverse_fmu_parameters(version):
    pose = np.array([0.01, -0.02, 0.05, 0.05, -0.03, 0.1])
    with opened_unit(version) as u:
        params = {f"tool_frame[{k + 1}]": TOOL[k] for k in range(6)}
        params.update({f"user_frame[{k + 1}]": USER[k] for k in range(6)})
        params.update({f"length_offset[{k + 1}]": OFFSET[k] for k in range(6)})
        params.update(dict(zip(POSE, pose)))
        assert u.init(fidelity=0, **params) == OK
        got = np.array(u.get(L))
    expected = closed_form_lengths(platform_pose(pose)) - OFFSET
    np.testing.assert_allclose(got, expected, atol=1e-13)
