"""StewartPlantME's warnings at accepted states: CompletedIntegratorStep returns Warning while a leg
is outside its stroke, a joint is beyond its angle limit or two legs interfere, and logs each when
it starts (as the co-simulation plant's steps), never at the trial states of GetDerivatives. The
reference is Platform.limits on the same pose (the library's limit check, called here from
Python), with limits chosen between their values at two poses so that one pose is within and the
other beyond each of them."""
import ctypes

import numpy as np
import pytest

import stewart
from fmu_support import VERSIONS
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
