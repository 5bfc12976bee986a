"""Every shipped platform file (platforms/*.json) against numbers from its own source: the leg
lengths at the home pose against the neutral lengths the source publishes (or that follow from
the source's own numbers, in the source's own frame and units), home within the strokes, and the
inverse/forward round trip about home. The joints of the real machines are checked against the
source's coordinates through the frame change the file's description states, so a mirrored or
misnumbered transcription fails. platforms/README.md cites each source."""
import json
import math
import pathlib

import numpy as np
import pytest

import stewart

PLATFORMS = pathlib.Path(__file__).resolve().parents[2] / "platforms"
FILES = {p.stem: p for p in sorted(PLATFORMS.glob("*.json"))}
UM = 1e-6

# Rubin Observatory hexapods, lsst-ts/ts_mthexapod python/lsst/ts/mthexapod/constants.py
# (ACTUATOR_BASE_POSITIONS_*, ACTUATOR_MIRROR_POSITIONS_*, PIVOT_*), in micrometres, in Rubin's
# hexapod frame.
CAMERA_BASE_UM = [(227600, 653800, -525000), (-227600, 653800, -525000), (-680000, -129700, -525000),
                  (-452300, -524000, -525000), (452300, -524000, -525000), (680000, -129700, -525000)]
CAMERA_MIRROR_UM = [(472800, 512200, -121400), (-472800, 512200, -121400), (-680000, 153300, -121400),
                    (-207200, -665500, -121400), (207200, -665500, -121400), (680000, 153300, -121400)]
CAMERA_PIVOT_UM = (0, 0, -2758400)
M2_BASE_UM = [(0, 1701800, 114300), (-1542350, -719210, 114300), (1542350, -719210, 114300),
              (790, 1460490, 228600), (-1503370, 7660, 228600), (1503370, 7660, 228600)]
M2_MIRROR_UM = [(0, 1701800, 607300), (-1542350, -719210, 607300), (1542350, -719210, 607300),
                (493790, 1460490, 228600), (-1256870, -419290, 228600), (1256870, -419290, 228600)]
M2_PIVOT_UM = (0, 0, -703000)
# ACTUATOR_MIN_LENGTH / ACTUATOR_MAX_LENGTH of the same file: +-14100 um about neutral.
RUBIN_TRAVEL = 14100 * UM
# The design spreadsheet doc/CAMERA HEXAPOD STRUT FLEXURE COORDINATES.xlsx (same repository):
# plates 403.918 mm apart, every strut 493.315 mm between flexure centres.
CAMERA_SPREADSHEET_LENGTH = 0.493315


def rubin_neutral(base_um, mirror_um):
    """ts_mthexapod's s_norm = |p_base - p_mirror| (doc/algorithm/kinematics.rst), in metres."""
    return [math.dist(b, m) * UM for b, m in zip(base_um, mirror_um)]


def simona_joints():
    """SIMONA's upper and lower gimbals as MotionLimiterEngine.cc places them from the numbers
    of MotionLimiter.cxx ('SIMONA geometry data'), in SIMONA's frame (x forward, y right,
    z down): upper gimbal radius 1.600 m, spacing 2 asin(1/16); lower 1.650 m, spacing
    2 asin(3/16.5), 2.39 m below (the neutral height)."""
    ug_half, lg_half = math.asin(1 / 16), math.asin(3 / 16.5)
    upper, lower = np.zeros((6, 3)), np.zeros((6, 3))
    for i in range(6):
        pair = (i + 1) // 2
        a = (ug_half if i % 2 == 0 else -ug_half) + pair * 2 * math.pi / 3
        upper[i] = (1.6 * math.cos(a), 1.6 * math.sin(a), 0.0)
        b = math.pi / 3 + (-lg_half if i % 2 == 0 else lg_half) + (i // 2) * 2 * math.pi / 3
        lower[i] = (1.65 * math.cos(b), 1.65 * math.sin(b), 2.39)
    return upper, lower


# Per file: the neutral (home) lengths from the source [m] and their tolerance [m] (None: the
# file is made up and no source gives them), and the source in words.
SIMONA_UPPER, SIMONA_LOWER = simona_joints()
NEUTRAL = {
    "thesis": ([math.hypot(0.5, 2 * 0.5 * math.sin(math.radians(15)))] * 6, 1e-15,
               "docs/model.md: 0.5 m circles, base 0/30/.. deg, platform 330/60/.. deg, home 0.5 m"),
    # the header's joints, to 1e-4 in, give legs of 29.7464 .. 29.7468 in
    "genhexkins": ([29.7466 * 0.0254] * 6, 2.5e-4 * 0.0254,
                   "LinuxCNC configs/sim/axis/vismach/hexapod-sim/hexapod.ini: home leg 29.7466 in"),
    "paired_hexapod": ([0.285] * 6, 1e-5,  # joints given to 1 um
                       "made up; its description: strokes +-0.05 m about the home length (0.235..0.335)"),
    "non_planar": (None, None, "made up; no source gives its lengths"),
    "rubin_camera_hexapod": (rubin_neutral(CAMERA_BASE_UM, CAMERA_MIRROR_UM), 1e-12,
                             "ts_mthexapod constants.py, camera hexapod, micrometres"),
    "rubin_m2_hexapod": ([0.493, 0.493, 0.493, 0.493, 0.4929995461458357, 0.4929995461458357], 1e-12,
                         "ts_mthexapod constants.py, M2: z 607300 - 114300 um, x 493790 - 790 um, "
                         "legs 5-6 |(246500, -426950)| um"),
    "simona_motion_base": ([float(np.linalg.norm(u - l)) for u, l in zip(SIMONA_UPPER, SIMONA_LOWER)],
                           1e-12, "DUECA MotionLimiter.cxx SIMONA geometry data, MotionLimiterEngine.cc"),
}
# The drive files are their machine's geometry with drives added: its neutral lengths.
NEUTRAL["simona_motion_base_drives"] = NEUTRAL["simona_motion_base"]
NEUTRAL["rubin_m2_hexapod_drives"] = NEUTRAL["rubin_m2_hexapod"]


def load(name):
    return stewart.Platform.from_file(FILES[name]), json.loads(FILES[name].read_text())


def home_pose(data):
    """The tool frame's pose in the user frame with the platform at (0, 0, home_height): the
    shipped frames are translations only."""
    tool = np.array(data.get("tool_frame", [0.0] * 6))
    user = np.array(data.get("user_frame", [0.0] * 6))
    assert not tool[3:].any() and not user[3:].any(), "a turned frame: extend home_pose"
    return np.concatenate([tool[:3] + (0.0, 0.0, data.get("home_height", 0.5)) - user[:3], [0.0] * 3])


def test_every_shipped_file_is_recorded_here():
    """A new platform file needs its source's neutral lengths here (or a reason there are none)."""
    assert set(FILES) == set(NEUTRAL)
    assert set(stewart.platform_files()) <= set(FILES)


@pytest.mark.parametrize("name", sorted(NEUTRAL))
def test_home_lengths_are_the_published_neutral_lengths(name):
    platform, data = load(name)
    expected, tolerance, _ = NEUTRAL[name]
    sol = platform.inverse(home_pose(data)[None, :], fidelity="full")
    assert sol.status[0] == 0
    if expected is None:
        pytest.skip(NEUTRAL[name][2])
    assert np.max(np.abs(sol.length[0] - expected)) <= tolerance


# genhexkins' base joints coincide in pairs: the two legs of a pair share that joint, so they
# are not checked against each other (they interfered at every pose before).
WITHIN_LIMITS = sorted(NEUTRAL)


@pytest.mark.parametrize("name", WITHIN_LIMITS)
def test_home_is_within_every_limit(name):
    platform, data = load(name)
    check = platform.limits(home_pose(data))
    assert check.first[0] == 0 and check.failed[0] == 0
    assert np.all(check.margin[0, :4] > 0)


@pytest.mark.parametrize("name", sorted(NEUTRAL))
def test_inverse_forward_round_trip_about_home(name):
    """Poses spread over a fifth of each axis' range at home (within every limit), solved at
    the full level and back through forward kinematics, each row from home."""
    platform, data = load(name)
    home = home_pose(data)
    ranges = platform.axis_ranges(home)[0]
    rng = np.random.default_rng(33)
    poses = home + 0.2 * rng.uniform(ranges[:, 0] - home, ranges[:, 1] - home, (20, 6))
    sol = platform.inverse(poses, fidelity="full")
    assert np.all(sol.status == 0)
    size = max(1.0, float(np.max(np.abs(poses[:, :3]))))
    for row in range(len(poses)):
        back = platform.forward(sol.length[row:row + 1], guess=home)
        assert back.status[0] == 0
        assert np.max(np.abs(back.pose[0] - poses[row])) < 1e-12 * size


@pytest.mark.parametrize("name, base_um, mirror_um, pivot_um", [
    ("rubin_camera_hexapod", CAMERA_BASE_UM, CAMERA_MIRROR_UM, CAMERA_PIVOT_UM),
    ("rubin_m2_hexapod", M2_BASE_UM, M2_MIRROR_UM, M2_PIVOT_UM)])
def test_rubin_joints_strokes_and_pivot_are_the_sources(name, base_um, mirror_um, pivot_um):
    """The file's joints are Rubin's shifted along z only (the description's frame change), in
    the same leg order; strokes are +-14100 um about neutral; the tool frame is the pivot and the
    user frame its neutral position."""
    _, data = load(name)
    base, mirror, pivot = np.array(base_um) * UM, np.array(mirror_um) * UM, np.array(pivot_um) * UM
    file_base = np.array(data["base_joint"]).reshape(6, 3)
    file_plate = np.array(data["platform_joint"]).reshape(6, 3)
    base_shift = base[:, 2] - file_base[:, 2]
    plate_shift = mirror[:, 2] - (file_plate[:, 2] + data["home_height"])
    assert np.ptp(base_shift) < 1e-15 and np.ptp(plate_shift) < 1e-15
    assert abs(base_shift[0] - plate_shift[0]) < 1e-15
    assert np.max(np.abs(file_base[:, :2] - base[:, :2])) < 1e-15
    assert np.max(np.abs(file_plate[:, :2] - mirror[:, :2])) < 1e-15
    neutral = np.array(rubin_neutral(base_um, mirror_um))
    assert np.max(np.abs(np.array(data["stroke_min"]) - (neutral - RUBIN_TRAVEL))) < 1e-9
    assert np.max(np.abs(np.array(data["stroke_max"]) - (neutral + RUBIN_TRAVEL))) < 1e-9
    tool = np.array(data["tool_frame"][:3]) + (0, 0, data["home_height"]) + (0, 0, base_shift[0])
    assert np.max(np.abs(tool - pivot)) < 1e-15
    assert np.max(np.abs(np.array(data["user_frame"][:3]) + (0, 0, base_shift[0]) - pivot)) < 1e-15


def test_rubin_camera_agrees_with_the_design_spreadsheet_and_the_m2_actuators():
    """Two further sources: the design spreadsheet's struts (0.493315 m) and the M2 hexapod's
    identical actuators (0.493 m, Sneed et al. 2016) agree with the controller's camera
    coordinates to 0.4 mm."""
    platform, data = load("rubin_camera_hexapod")
    lengths = platform.inverse(home_pose(data)[None, :]).length[0]
    assert np.max(np.abs(lengths - CAMERA_SPREADSHEET_LENGTH)) < 4e-4
    assert np.max(np.abs(lengths - 0.493)) < 1e-4


def test_simona_is_turned_not_mirrored():
    """The file's joints are SIMONA's turned by 180 deg about x, (x, y, z) -> (x, -y, -z), with the
    base origin at the lower gimbals' centre: a mirrored transcription (z -> -z alone) fails."""
    _, data = load("simona_motion_base")
    turn = np.diag([1.0, -1.0, -1.0])
    base = np.array(data["base_joint"]).reshape(6, 3)
    plate = np.array(data["platform_joint"]).reshape(6, 3)
    assert np.max(np.abs(base - (SIMONA_LOWER @ turn.T + (0, 0, data["home_height"])))) < 1e-12
    assert np.max(np.abs(plate - SIMONA_UPPER @ turn.T)) < 1e-12
    assert data["home_height"] == 2.39


def test_simona_home_is_mid_stroke():
    """The published jack range 2.131..3.281 m: the neutral height puts every jack in its middle
    (2.706 m) to 0.1 mm."""
    platform, data = load("simona_motion_base")
    lengths = platform.inverse(home_pose(data)[None, :]).length[0]
    assert (data["stroke_min"], data["stroke_max"]) == (2.131, 3.281)
    assert np.max(np.abs(lengths - (2.131 + 3.281) / 2)) < 1e-4
