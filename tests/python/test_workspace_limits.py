"""The workspace under every limit (stewart.sweeps): a slice's reachability against lengths and
joint angles computed in numpy (test_limits' helpers); the constant-orientation volume against
a spherical shell's closed form and a Monte Carlo estimate written here; the spec's volume
field checked by name."""
import numpy as np
import pytest

import test_limits as ref

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
pytest.importorskip("pyarrow")
from stewart.sweeps import SpecError, resolve, workspace_volume  # noqa: E402
from stewart.sweeps.spec import Chunk, slice_size  # noqa: E402
from stewart.sweeps.work import workspace_chunk  # noqa: E402

LIMITS = dict(stroke_min=0.43, stroke_max=0.68, base_joint_limit=0.3, platform_joint_limit=0.35)


def test_workspace_slice_is_reachable_exactly_within_strokes_and_joint_angles():
    spec = resolve({"kind": "workspace", "platform": LIMITS, "slices": [
        {"name": "xy", "fixed": {"z": 0.52, "roll": 0.05},
         "axes": {"x": {"start": -0.25, "stop": 0.25, "num": 41},
                  "y": {"start": -0.2, "stop": 0.2, "num": 33}}}]}, ".")
    s = spec["slices"][0]
    table, _ = workspace_chunk(spec, Chunk("xy", 0, 0, slice_size(s)))
    t = {k: table[k].to_numpy(zero_copy_only=False) for k in table.column_names}
    p = ref.THESIS | LIMITS
    inside, near = [], []
    for pose in np.column_stack([t[c] for c in ("x", "y", "z", "roll", "pitch", "yaw")]):
        a, top, R = ref.legs(p, pose)
        L = np.linalg.norm(top - a, axis=1)
        base = ref.angle(top - a, ref.home_directions(p))
        plat = ref.angle(top - a, ref.home_directions(p) @ R.T)
        margins = np.concatenate([L - LIMITS["stroke_min"], LIMITS["stroke_max"] - L,
                                  LIMITS["base_joint_limit"] - base,
                                  LIMITS["platform_joint_limit"] - plat])
        inside.append(margins.min() >= 0)
        near.append(np.abs(margins).min() < 1e-12)
    inside, near = np.array(inside), np.array(near)
    assert not np.any((inside != t["reachable"]) & ~near)
    assert 0.1 < inside.mean() < 0.9
    # the joints, not only the strokes, cut the slice
    assert {2, 3} & set(t["limit_class"][~t["reachable"]].tolist())


def test_volume_of_a_spherical_shell():
    """Joints (nearly) at the centres, no joint or interference limit: the positions with every
    leg length within [0.3, 0.7] m fill a spherical shell, cut only by the base plane z = 0
    (singular: the legs all lie in it), which has no volume."""
    plat = stewart.Platform(base_radius=1e-3, platform_radius=1e-3, stroke_min=0.3, stroke_max=0.7,
                            base_joint_limit=np.pi, platform_joint_limit=np.pi, leg_diameter=0)
    exact = 4 / 3 * np.pi * (0.7 ** 3 - 0.3 ** 3)
    # Near-singular everywhere (point joints): each axis range is slow, so a coarse first grid.
    result = workspace_volume(plat, cells=24, warn_condition=1e300, details=True)
    assert result.relative_error <= 0.0025 and not result.note
    assert result.volume == pytest.approx(exact, rel=0.005)


def test_volume_of_the_thesis_platform_against_monte_carlo():
    plat = stewart.Platform(**LIMITS)
    volume = workspace_volume(plat, orientation=(0.0, 0.05, 0.1))
    rng = np.random.default_rng(7)
    box = np.array([[-0.35, -0.35, 0.25], [0.35, 0.35, 0.75]])
    n = 200000
    points = rng.uniform(box[0], box[1], (n, 3))
    poses = np.column_stack([points, np.tile([0.0, 0.05, 0.1], (n, 1))])
    inside = plat.limits(poses).within
    # every feasible point lies well within the box: the box holds the workspace
    found = points[inside]
    assert (found.min(axis=0) > box[0] + 0.02).all() and (found.max(axis=0) < box[1] - 0.02).all()
    box_volume = np.prod(box[1] - box[0])
    estimate = inside.mean() * box_volume
    sigma = np.sqrt(inside.mean() * (1 - inside.mean()) / n) * box_volume
    assert abs(volume - estimate) < 4 * sigma + 0.005 * estimate, (volume, estimate, sigma)


@pytest.mark.parametrize("volume, words", [
    ({"cells": 1}, ["volume.cells = 1"]),
    ({"orientation": [0, 0]}, ["volume.orientation", "3 finite numbers"]),
    ({"size": 3}, ["volume", "unknown field 'size'"]),
    ({"accuracy": 0}, ["volume.accuracy = 0", "[1e-4, 0.5]"]),
])
def test_volume_field_is_checked_by_name(volume, words):
    spec = {"kind": "workspace", "slices": [{"name": "z", "fixed": {}, "axes": {"z": [0.5]}}],
            "volume": volume}
    with pytest.raises(SpecError) as e:
        resolve(spec, ".")
    for w in words:
        assert w in str(e.value)


def test_a_volume_for_a_machine_whose_home_is_beyond_a_limit_is_refused_at_once():
    spec = {"kind": "workspace", "platform": {"stroke_min": 0.6, "stroke_max": 0.8},
            "slices": [{"name": "z", "fixed": {}, "axes": {"z": [0.5]}}], "volume": {}}
    with pytest.raises(SpecError, match=r"volume: the home pose .* stroke margin -0\.\d+ m"):
        resolve(spec, ".")
