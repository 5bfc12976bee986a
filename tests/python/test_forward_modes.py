"""Forward kinematics never returns another pose with the same lengths silently. With the joint
limits opened to 178 deg and strokes of 0.01-5 m, random poses far from home include poses whose
lengths have another pose on the working mode's side of every branch check (legs' sides,
platform up, sign of det J). Each such row must come back as the pose itself or be refused
naming another assembly mode: tracked from the row before, and cold. The lengths come from the
closed form |p + R b_k - a_k| written here (the library's inverse for files with frames or
units)."""
import json

import numpy as np
import pytest

import stewart
from test_platform_files import rotation

OPEN = dict(base_joint_limit=np.radians(178.0), platform_joint_limit=np.radians(178.0),
            stroke_min=0.01, stroke_max=5.0)
_TABLE = {p["name"]: p["defaults"] for p in stewart.parameters()}
MACHINES = ["thesis-defaults"] + sorted(stewart.platform_files())
POSES = 2000


def machine(name):
    """The platform with opened limits, and its joints (None: frames or units, use inverse)."""
    if name == "thesis-defaults":
        base, top = (np.reshape(_TABLE[k], (6, 3)) for k in ("base_joint", "platform_joint"))
        return stewart.Platform(**OPEN), base, top
    path = stewart.platform_files()[name]
    data = json.loads(path.read_text())
    platform = stewart.Platform.from_file(path, **OPEN)
    plain = (not any(k in data for k in ("tool_frame", "user_frame", "length_offset", "units"))
             and "base_joint" in data
             and all(isinstance(v, (int, float)) for v in data["base_joint"] + data["platform_joint"]))
    if not plain:
        return platform, None, None
    return platform, np.reshape(data["base_joint"], (6, 3)), np.reshape(data["platform_joint"], (6, 3))


def far_poses(platform, n, seed, ends=None):
    """n poses within every (opened) limit, drawn over `ends` (default: the axis ranges from
    home), that the solver takes as the working mode when started at the pose itself."""
    if ends is None:
        ends = platform.check().ranges.ends[0]
    rng = np.random.default_rng(seed)
    kept = []
    while sum(len(k) for k in kept) < n:
        q = rng.uniform(ends[:, 0], ends[:, 1], (4 * n, 6))
        q = q[platform.limits(q).within]
        if len(q):
            kept.append(q[platform.forward(closed_lengths(platform, q), guess=q, cold=True).status == 0])
    return np.concatenate(kept)[:n]


_JOINTS = {}


def closed_lengths(platform, q):
    base, top = _JOINTS[id(platform)]
    if base is None:
        return platform.inverse(q, fidelity="kinematic").length
    return np.array([np.linalg.norm(p[:3] + top @ rotation(*p[3:]).T - base, axis=1) for p in q])


def other_poses(found, q, scale):
    """Rows solved (status 0) whose pose is not q: position or rotation matrix (angles may be
    another triple)."""
    solved = found.status == 0
    far = np.array([max(np.abs(a[:3] - b[:3]).max() / scale,
                        np.abs(rotation(*a[3:]) - rotation(*b[3:])).max())
                    for a, b in zip(found.pose, q)])
    return solved & (far > 1e-7)


# The thesis platform over a wider box about home: a yaw of +-115 deg, roll and pitch +-69 deg.
WIDE = np.array([[-0.5, 0.5], [-0.5, 0.5], [0.1, 0.9], [-1.2, 1.2], [-1.2, 1.2], [-2.0, 2.0]])


@pytest.mark.parametrize("name, box", [(m, None) for m in MACHINES] + [("thesis-defaults", WIDE)])
def test_no_other_pose_silently(name, box):
    platform, base, top = machine(name)
    _JOINTS[id(platform)] = (base, top)
    q = far_poses(platform, POSES, seed=11, ends=box)
    lengths = closed_lengths(platform, q)
    scale = max(1.0, np.abs(q[:, :3]).max())
    cold = platform.forward(lengths, cold=True)
    tracked = platform.forward(lengths)
    wrong_cold, wrong_tracked = other_poses(cold, q, scale), other_poses(tracked, q, scale)
    print(f"{name}: {len(q)} poses; other pose returned: cold {wrong_cold.sum()}, "
          f"tracked {wrong_tracked.sum()}; refused: cold {(cold.status != 0).sum()}, "
          f"tracked {(tracked.status != 0).sum()}")
    assert wrong_cold.sum() == 0 and wrong_tracked.sum() == 0
    # what is refused is refused as another assembly mode or as singular, never solved
    from stewart.forward import STATUS_OTHER_BRANCH
    for found in (cold, tracked):
        refused = found.status[found.status != 0]
        assert np.isin(refused, [STATUS_OTHER_BRANCH, -3, -5]).all(), np.unique(refused)
