"""The constant-orientation workspace volume (stewart.sweeps.workspace_volume) against a Monte
Carlo estimate written here: 10^6 uniform samples, checked by the library's limit check in one
batch, in a box found here by sampling outward from home until no sample within the limits lies
near its faces. Every shipped platform file, a small-stroke precision hexapod with a far pivot
written here (strokes +-14 mm: a workspace of centimetres in a machine of a metre), and framed
variants (tool and user frames turned and moved); the framed volume also against the unframed
one at the same platform orientation (a rigid change of coordinates keeps the volume)."""
import numpy as np
import pytest

from test_limits import rotation

stewart = pytest.importorskip("stewart", reason="the package is not installed: pip install .")
from stewart.sweeps import workspace_volume  # noqa: E402

SAMPLES = 2 * 10**6


def _joints(radius, angles, spread):
    """Joints in pairs at radius: at each angle +- spread [deg], z = 0."""
    a = np.radians(np.repeat(angles, 2) + np.tile([-spread, spread], 3))
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros(6)])


def precision_hexapod():
    """A precision hexapod of the kind of issue 33's: base joints in pairs on 0.3 m, platform
    joints in pairs on 0.2 m, home 0.35 m up, strokes +-14 mm about the home lengths, moves
    commanded about a pivot 2.6 m below the top plate."""
    base = _joints(0.30, [0, 120, 240], 10)
    top = np.roll(_joints(0.20, [60, 180, 300], 12), -1, axis=0)
    height = 0.35
    home = np.linalg.norm(top + [0, 0, height] - base, axis=1)
    return dict(geometry=1, base_joint=base.ravel().tolist(), platform_joint=top.ravel().tolist(),
                home_height=height, stroke_min=(home - 0.014).tolist(),
                stroke_max=(home + 0.014).tolist(), tool_frame=[0, 0, -2.6, 0, 0, 0],
                leg_diameter=0.02)


FRAMES = dict(tool_frame=[0.03, -0.02, 0.12, 0.1, -0.05, 0.3],
              user_frame=[0.2, 0.1, 0.05, -0.04, 0.08, -0.6])


def machines():
    out = {name: stewart.Platform.from_file(path) for name, path in stewart.platform_files().items()}
    out["thesis+frames"] = stewart.Platform.from_file(stewart.platform_files()["thesis"], **FRAMES)
    out["precision"] = stewart.Platform(**precision_hexapod())
    out["precision+frames"] = stewart.Platform(**{**precision_hexapod(), **FRAMES,
                                                  "tool_frame": [0.01, 0.0, -2.6, 0.0, 0.02, 0.4]})
    return out


MACHINES = machines()


def home(plat):
    """The tool's pose in the user frame at the platform's home, from the frames (docs/api.md):
    R_t = R_u^T R_d, p_t = R_u^T ((0, 0, h) + d - u)."""
    p = plat.params
    d = np.asarray(p.get("tool_frame", np.zeros(6)), float)
    u = np.asarray(p.get("user_frame", np.zeros(6)), float)
    h = float(p.get("home_height", 0.5))
    Ru, Rd = rotation(*u[3:]), rotation(*d[3:])
    R = Ru.T @ Rd
    angles = [np.arctan2(R[2, 1], R[2, 2]), -np.arcsin(R[2, 0]), np.arctan2(R[1, 0], R[0, 0])]
    return np.concatenate([Ru.T @ (np.array([0.0, 0.0, h]) + d[:3] - u[:3]), angles])


def monte_carlo(plat, orientation, rng, samples=SAMPLES):
    """(estimate, standard error, box): uniform samples in a box grown here from home's axis
    ranges until the samples within the limits keep 3 % of its size from every face, then
    tightened to 5 % around what 4 x 10^5 samples found (the smaller box, the smaller the
    error); no sample of the estimate within the limits may come within 1 % of a face."""
    q0 = np.concatenate([home(plat)[:3], orientation])
    ends = np.reshape(plat.axis_ranges(q0), (-1, 6, 2))[0, :3]
    box = np.array([ends[:, 0], ends[:, 1]])
    for _ in range(40):
        size = box[1] - box[0]
        points = rng.uniform(box[0], box[1], (200000, 3))
        found = points[_within(plat, points, orientation)]
        low = found.min(axis=0) < box[0] + 0.03 * size
        high = found.max(axis=0) > box[1] - 0.03 * size
        if not (low.any() or high.any()):
            break
        box[0] -= 0.5 * size * low
        box[1] += 0.5 * size * high
    else:
        raise AssertionError("the Monte Carlo box did not settle")
    points = rng.uniform(box[0], box[1], (400000, 3))
    found = points[_within(plat, points, orientation)]
    extent = found.max(axis=0) - found.min(axis=0)
    box = np.array([found.min(axis=0) - 0.05 * extent, found.max(axis=0) + 0.05 * extent])
    points = rng.uniform(box[0], box[1], (samples, 3))
    inside = _within(plat, points, orientation)
    found = points[inside]
    size = box[1] - box[0]
    assert np.all(found.min(axis=0) > box[0] + 0.01 * size)
    assert np.all(found.max(axis=0) < box[1] - 0.01 * size)
    fraction = inside.mean()
    box_volume = float(np.prod(size))
    return fraction * box_volume, np.sqrt(fraction * (1 - fraction) / samples) * box_volume, box


def _within(plat, points, orientation):
    poses = np.column_stack([points, np.broadcast_to(orientation, (len(points), 3))])
    return plat.limits(poses).within


@pytest.mark.parametrize("name", sorted(MACHINES))
def test_volume_against_monte_carlo(name):
    """Within 0.5 % of the Monte Carlo estimate (plus three of its standard errors); a machine
    whose home is beyond a limit (LinuxCNC's genhexkins joints coincide in pairs: closer than
    the legs are thick, they interfere at every pose) is refused, naming the limit."""
    plat = MACHINES[name]
    orientation = home(plat)[3:]
    at_home = plat.limits(home(plat))
    if not at_home.within[0]:
        with pytest.raises(ValueError, match="home pose .* is not within every limit"):
            workspace_volume(plat)
        return
    result = workspace_volume(plat, details=True)
    np.testing.assert_allclose(result.orientation, orientation, atol=1e-12)
    estimate, sigma, box = monte_carlo(plat, orientation, np.random.default_rng(11))
    assert result.volume > 0
    assert result.relative_error <= 0.0025 and not result.note, result
    assert abs(result.volume - estimate) <= 0.005 * estimate + 3 * sigma, \
        (result.volume, estimate, sigma, result.grids)
    # The box the volume was found in holds every sample found within the limits.
    assert np.all(box[0] <= result.box[1]) and np.all(result.box[0] <= box[1])


def test_volume_at_another_orientation_against_monte_carlo():
    plat = MACHINES["thesis+frames"]
    orientation = home(plat)[3:] + [0.05, -0.08, 0.2]
    volume = workspace_volume(plat, orientation)
    estimate, sigma, _ = monte_carlo(plat, orientation, np.random.default_rng(5))
    assert abs(volume - estimate) <= 0.005 * estimate + 3 * sigma, (volume, estimate, sigma)


@pytest.mark.parametrize("name", ["thesis", "precision"])
def test_frames_move_the_workspace_rigidly(name):
    """The framed machine's volume at home's orientation equals the unframed one's at the
    platform's home orientation: the same set of platform poses in other coordinates."""
    framed = {"thesis": "thesis+frames", "precision": "precision+frames"}[name]
    plain = MACHINES[name]
    if name == "precision":
        plain = stewart.Platform(**{**precision_hexapod(), "tool_frame": [0] * 6})
    a = workspace_volume(plain, details=True)
    b = workspace_volume(MACHINES[framed], details=True)
    assert abs(a.volume - b.volume) <= 0.005 * a.volume, (a, b)


def test_a_small_stroke_machine_far_from_the_origin_has_its_volume():
    """Strokes of +-14 mm on a machine whose joints are 0.3 m out, the pivot 2.6 m away: the
    workspace is centimetres across and 2.6 m below the platform origin, nowhere near a box
    from the machine's overall size; its volume is of the order of the stroke cubed."""
    result = workspace_volume(MACHINES["precision"], details=True)
    assert 1e-7 < result.volume < (2 * 0.014) ** 3 * 8
    # The box is the machine's: centimetres around the pivot, not a box of the legs' reach.
    assert np.all(result.box[1] - result.box[0] < 0.2)
    assert np.all(np.abs(result.box.mean(axis=0) - home(MACHINES["precision"])[:3]) < 0.05)


def test_a_home_beyond_a_limit_is_refused_naming_it():
    plat = stewart.Platform(stroke_min=0.6, stroke_max=0.8)  # the thesis' home legs are shorter
    with pytest.raises(ValueError, match=r"home pose .* is not within every limit: stroke margin "
                                         r"-0\.\d+ m at leg \d"):
        workspace_volume(plat)


def test_an_orientation_with_no_workspace_is_zero_with_a_warning():
    plat = stewart.Platform()
    with pytest.warns(RuntimeWarning, match="no position within every limit"):
        assert workspace_volume(plat, (0.0, 0.0, 1.55), warn_condition=20) == 0.0


def test_an_orientation_that_home_s_position_cannot_take_against_monte_carlo():
    """At roll 0.35 rad the thesis platform's home position is beyond a limit, other positions
    are not: the search starts from the grid point nearest home within the limits. Monte Carlo
    here: 2 x 10^6 samples in a 2 m box around home find the workspace, a box 25 % larger than
    what they found holds it (checked on the final samples), 2 x 10^6 samples there."""
    plat = MACHINES["thesis"]
    orientation = np.array([0.35, 0.0, 0.0])
    assert not plat.limits(np.r_[home(plat)[:3], orientation]).within[0]
    volume = workspace_volume(plat, orientation)
    rng = np.random.default_rng(21)
    box = np.array([home(plat)[:3] - 1.0, home(plat)[:3] + 1.0])
    for _ in range(2):
        points = rng.uniform(box[0], box[1], (SAMPLES, 3))
        found = points[_within(plat, points, orientation)]
        extent = found.max(axis=0) - found.min(axis=0)
        box = np.array([found.min(axis=0) - 0.25 * extent, found.max(axis=0) + 0.25 * extent])
    points = rng.uniform(box[0], box[1], (SAMPLES, 3))
    inside = _within(plat, points, orientation)
    size = box[1] - box[0]
    assert np.all(points[inside].min(axis=0) > box[0] + 0.05 * size)
    assert np.all(points[inside].max(axis=0) < box[1] - 0.05 * size)
    fraction = inside.mean()
    estimate = fraction * np.prod(size)
    sigma = np.sqrt(fraction * (1 - fraction) / SAMPLES) * np.prod(size)
    assert abs(volume - estimate) <= 0.005 * estimate + 3 * sigma, (volume, estimate, sigma)
