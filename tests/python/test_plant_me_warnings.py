"""StewartPlantME's warnings at accepted states: CompletedIntegratorStep and the event update
(NewDiscreteStates / UpdateDiscreteStates, with the event info filled: Warning is a status whose
outputs are valid) return Warning while a leg is outside its stroke, a joint is beyond its angle
limit or two legs interfere, and log each when it starts (as the co-simulation plant's steps), never
at the trial states of GetDerivatives. The
reference is Platform.limits on the same pose (the library's limit check, called here from
Python), with limits chosen between their values at two poses so that one pose is within and the
other beyond each of them."""
import ctypes

import fmpy
import numpy as np
import pytest

import stewart
from fmu_support import VERSIONS
from test_plant_fmu import POSE, fmu_file
from test_frames import TOOL, USER, tool_pose
from test_plant_fmu import static_forces
from test_plant_me_fmu import OK, MEInstance

WARNING = 1
HOME = np.array([0, 0, 0.5, 0, 0, 0.0])
MOVED = HOME + np.array([0.04, -0.03, 0.0, 0.12, -0.1, 0.6])  # the platform's, base frame
# the limit classes' bits in LimitCheck.failed
STROKE, BASE_JOINT, PLATFORM_JOINT, INTERFERENCE = 1, 2, 4, 8
DEFAULT_JOINT_LIMIT, DEFAULT_LEG_DIAMETER = np.pi / 2, 0.015  # the parameter table's defaults


def completed(me):
    """CompletedIntegratorStep's status."""
    flag = ctypes.c_int if me.v2 else ctypes.c_bool
    event, terminate = flag(0), flag(0)
    return me.raw("CompletedIntegratorStep", flag(1), ctypes.byref(event),
                  ctypes.byref(terminate))


def limits_between(poses, frames):
    """Python keywords that put poses[0] within and poses[1] beyond the stroke, the base joints'
    angle limit and the legs' clearance: each limit halfway between its values at the two poses
    (Platform.limits' margins under the default limits give the angles and clearances)."""
    platform = stewart.Platform(**frames)
    check = platform.limits(poses)
    lengths = platform.inverse(poses, fidelity="kinematic").length.max(axis=1)
    angle = DEFAULT_JOINT_LIMIT - check.margin[:, 1]
    clearance = check.margin[:, 3] + DEFAULT_LEG_DIAMETER
    assert lengths[1] > lengths[0] and angle[1] > angle[0] and clearance[1] < clearance[0]
    return {**frames, "stroke_max": [0.5 * (lengths[0] + lengths[1])] * 6,
            "base_joint_limit": 0.5 * (angle[0] + angle[1]),
            "leg_diameter": 0.5 * (clearance[0] + clearance[1])}


def fmu_names(keywords):
    """The unit's parameters for Python keywords (lists as name[1..n])."""
    out = {}
    for name, value in keywords.items():
        if np.ndim(value):
            out.update({f"{name}[{k}]": float(v) for k, v in enumerate(value, 1)})
        else:
            out[name] = float(value)
    return out


@pytest.mark.parametrize("framed", [False, True])
@pytest.mark.parametrize("version", VERSIONS)
def test_warnings_at_accepted_states(version, framed):
    frames = {"tool_frame": list(TOOL), "user_frame": list(USER)} if framed else {}
    poses = np.array([tool_pose(p) for p in (HOME, MOVED)]) if framed else np.array([HOME, MOVED])
    params = limits_between(poses, frames)
    # the reference: the library's limit check with these parameters
    check = stewart.Platform(**params).limits(poses)
    assert check.failed[0] == 0
    assert check.failed[1] & STROKE and check.failed[1] & BASE_JOINT
    assert check.failed[1] & INTERFERENCE
    me = MEInstance(version).init(**fmu_names(params)).continuous()
    me.set(**{f"F[{k}]": f for k, f in enumerate(static_forces(2), 1)})
    statuses = []
    for pose in (poses[0], poses[1], poses[1], poses[0]):
        assert me.set_states(np.concatenate([pose, np.zeros(6)])) == OK
        status, _ = me.derivatives()
        assert status == OK  # trial states: no warning there
        logged = len(me.messages)
        statuses.append((completed(me), me.messages[logged:]))
    assert statuses[0] == (OK, [])
    status, new = statuses[1]
    assert status == WARNING
    text = " ".join(new)
    assert "left the stroke" in text and "angle limit" in text and "leg_diameter" in text, new
    assert statuses[2] == (WARNING, [])  # still beyond, logged once
    assert statuses[3] == (OK, [])
    me.free()


def event_update(me):
    """(status, the event info as a list): NewDiscreteStates / UpdateDiscreteStates, its outputs
    preset to what a filled event info never holds (all true, next event time -1)."""
    if me.v2:
        info = fmpy.fmi2.fmi2EventInfo(1, 1, 1, 1, 1, -1.0)
        status = me.raw("NewDiscreteStates", ctypes.byref(info))
        return status, [info.newDiscreteStatesNeeded, info.terminateSimulation,
                        info.nominalsOfContinuousStatesChanged,
                        info.valuesOfContinuousStatesChanged, info.nextEventTimeDefined,
                        info.nextEventTime]
    flags = [ctypes.c_bool(True) for _ in range(5)]
    next_time = ctypes.c_double(-1.0)
    status = me.raw("UpdateDiscreteStates", *[ctypes.byref(f) for f in flags],
                    ctypes.byref(next_time))
    return status, [f.value for f in flags] + [next_time.value]


FILLED = [0, 0, 0, 0, 0, 0.0]  # nothing discrete changes, no next time event


def start_at(pose):
    """The start-state parameters x0 .. yaw0 for a pose, at rest."""
    return {f"{name}0": float(q) for name, q in zip(POSE, pose)}


@pytest.mark.parametrize("version", VERSIONS)
def test_warning_at_the_event_update(version):
    poses = np.array([HOME, MOVED])
    params = limits_between(poses, {})
    check = stewart.Platform(**params).limits(poses)  # the reference
    assert check.failed[0] == 0 and check.failed[1] & STROKE and check.failed[1] & BASE_JOINT
    for pose, beyond in zip(poses, (False, True)):
        me = MEInstance(version).init(**fmu_names(params), **start_at(pose))
        me.fmu.exitInitializationMode()
        logged = len(me.messages)
        status, info = event_update(me)
        assert (status, [float(x) for x in info]) == (WARNING if beyond else OK, FILLED)
        new = me.messages[logged:]
        if beyond:
            text = " ".join(new)
            assert "left the stroke" in text and "angle limit" in text, new
            if check.failed[1] & INTERFERENCE:
                assert "leg_diameter" in text, new
        else:
            assert new == []
        # the same state again: the same status, nothing logged twice
        logged = len(me.messages)
        assert event_update(me)[0] == status and me.messages[logged:] == []
        assert me.raw("EnterContinuousTimeMode") == OK
        assert completed(me) == status and me.messages[logged:] == []
        # back within every limit: OK at the next accepted state and event update
        assert me.set_states(np.concatenate([HOME, np.zeros(6)])) == OK
        assert completed(me) == OK
        assert me.raw("EnterEventMode") == OK
        assert event_update(me) == (OK, FILLED)
        me.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_runs_through_the_event_update_warning(version):
    """fmpy's Model Exchange simulation (CVODE) from a start beyond the limits: the first event
    update is Warning (not a failure), each limit is logged once, and the run completes."""
    poses = np.array([HOME, MOVED])
    params = limits_between(poses, {})
    assert stewart.Platform(**params).limits(poses).failed[1] & STROKE  # the reference
    events = []
    result = fmpy.simulate_fmu(
        fmu_file("StewartPlantME", version), stop_time=0.01, output_interval=1e-3,
        start_values={**fmu_names(params), **start_at(MOVED),
                      **{f"F[{k}]": f for k, f in enumerate(static_forces(2), 1)}},
        debug_logging=True, logger=lambda *args: events.append(("log", args[-1].decode())),
        fmi_call_logger=lambda call: events.append(("call", call)))
    assert result["time"][-1] == pytest.approx(0.01)
    update = "fmi2NewDiscreteStates" if version == "2.0" else "fmi3UpdateDiscreteStates"
    calls = [i for i, (kind, text) in enumerate(events) if kind == "call" and update in text]
    assert calls and events[calls[0]][1].endswith("-> WARNING"), events[calls[0]]
    logs = [text for kind, text in events if kind == "log" and text.startswith("t = ")]
    assert any("left the stroke" in text for text in logs) and any(
        "angle limit" in text for text in logs), logs
    # logged once per start: no leg (L[k] = ...) or limit named twice
    named = [text.split(": ", 1)[1].split(" = ", 1)[0] for text in logs]
    assert len(named) == len(set(named)), logs
