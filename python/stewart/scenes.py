"""Scenes: pose trajectories as one sinusoid per pose component (scenes/*.json), and moves.

value = mean + amplitude sin(omega t + phase), so the rates and accelerations are exact. A scene
may instead (or after its sinusoids) hold a `move` section: a rest-to-rest move planned with
stewart.move on the platform the scene runs on (docs/moves.md "Scenes"). The one place that
reads, checks and samples a scene: the scripts (scripts/scenes.py, run_scene.py,
closed_loop.py) and the sweeps use it. The FMU StewartScene plays the sinusoids in C.
"""
from __future__ import annotations

import json
import math
import pathlib
from typing import Any, Optional, Union

import numpy as np

from .limits import POSE_CLASSES

POSE = ("x", "y", "z", "roll", "pitch", "yaw")
DOT = tuple(f"{p}_dot" for p in POSE)
DDOT = tuple(f"{p}_ddot" for p in POSE)
SINUSOID = ("mean", "amplitude", "omega", "phase")
#: The fields of a scene's move section: stewart.move's arguments of the same names, and hold
#: [s], the time the goal is held at rest after the move.
MOVE_FIELDS = ("kind", "start", "goal", "frame", "via", "blend", "leg_speed_max",
               "leg_accel_max", "leg_jerk_max", "speed_max", "angular_speed_max", "hold")
#: Rates below this [m/s, rad/s] at the end of a scene's sinusoids count as rest (a move after
#: them starts at rest).
REST_RATE = 1e-9


class SceneError(ValueError):
    """A scene that cannot be played: the message names the field and its value."""


def load(scene: Union[str, pathlib.Path], scene_dir: Optional[Union[str, pathlib.Path]] = None) -> dict:
    """A checked scene dict from a name in scene_dir (e.g. 'yaw') or a path to a JSON file;
    SceneError names the file and what is wrong."""
    path = pathlib.Path(scene)
    if not path.suffix:
        if scene_dir is None:
            raise SceneError(f"scene = {str(scene)!r} is a name: give the folder of scenes too")
        path = pathlib.Path(scene_dir) / f"{scene}.json"
    try:
        data = json.loads(path.read_text())
    except OSError as e:
        raise SceneError(f"scene {str(scene)!r}: cannot read {path}: {e.strerror}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise SceneError(f"scene {str(scene)!r}: {path} is not JSON: {e}") from None
    if not isinstance(data, dict):
        raise SceneError(f"scene {str(scene)!r}: {path} holds a {type(data).__name__}, "
                         "not a scene object")
    data.setdefault("name", path.stem)
    check(data, str(path))
    return data


def check(scene: Any, where: str) -> None:
    """SceneError naming `where` and the field unless scene has a pose of sinusoids with finite
    numbers and a finite positive duration, or a move section (or both), and a finite positive
    step (the slider-crank scene has no pose)."""
    if not isinstance(scene, dict):
        raise SceneError(f"{where} = {scene!r} must be a scene object")
    if scene.get("mechanism") == "slider-crank":
        return
    if "move" in scene:
        _check_move(scene["move"], f"{where}.move")
    if "pose" in scene or "move" not in scene:
        _check_pose(scene, where)
    if not (_finite(scene.get("step")) and scene["step"] > 0):
        raise SceneError(f"{where}.step = {scene.get('step')!r} must be a finite number > 0")
    home = scene.get("home", THESIS_HOME)
    if not _is_pose(home):
        raise SceneError(f"{where}.home = {home!r} must be a pose of 6 finite numbers (the pose "
                         "the scene moves about)")


def _check_pose(scene: dict, where: str) -> None:
    pose = scene.get("pose")
    if not isinstance(pose, dict) or set(pose) - set(POSE):
        raise SceneError(f"{where}: pose = {pose!r} must map components of {POSE} to sinusoids "
                         "(or give a move section instead)")
    for comp, s in pose.items():
        if not isinstance(s, dict):
            raise SceneError(f"{where}.pose.{comp} = {s!r} must be an object (mean, amplitude, "
                             "omega, phase)")
        for key in SINUSOID:
            if not _finite(s.get(key, 0.0)):
                raise SceneError(f"{where}.pose.{comp}.{key} = {s.get(key)!r} must be a finite number")
    if not (_finite(scene.get("duration")) and scene["duration"] > 0):
        raise SceneError(f"{where}.duration = {scene.get('duration')!r} must be a finite "
                         "number > 0")


def _check_move(move: Any, where: str) -> None:
    """The move section's shape; stewart.move checks the rest when it plans."""
    if not isinstance(move, dict):
        raise SceneError(f"{where} = {move!r} must be an object with a goal")
    unknown = set(move) - set(MOVE_FIELDS)
    if unknown:
        raise SceneError(f"{where} has {sorted(unknown)}: the fields are {MOVE_FIELDS}")
    if not _is_pose(move.get("goal")):
        raise SceneError(f"{where}.goal = {move.get('goal')!r} must be 6 finite numbers (a pose, "
                         "or with frame a displacement)")
    if "start" in move and not _is_pose(move["start"]):
        raise SceneError(f"{where}.start = {move['start']!r} must be 6 finite numbers")
    via = move.get("via", [])
    if not (isinstance(via, list) and all(map(_is_pose, via))):
        raise SceneError(f"{where}.via = {via!r} must be a list of poses of 6 finite numbers")
    if move.get("kind", "point") not in ("point", "line"):
        raise SceneError(f"{where}.kind = {move.get('kind')!r} must be 'point' or 'line'")
    if move.get("frame") not in (None, "user", "tool"):
        raise SceneError(f"{where}.frame = {move.get('frame')!r} must be null, 'user' or 'tool'")
    for key in ("blend", "speed_max", "angular_speed_max", "hold"):
        if key in move and not (_finite(move[key]) and move[key] >= 0):
            raise SceneError(f"{where}.{key} = {move[key]!r} must be a finite number >= 0")
    for key in ("leg_speed_max", "leg_accel_max", "leg_jerk_max"):
        value = move.get(key, 0.0)
        values = value if isinstance(value, list) and len(value) == 6 else [value]
        if not all(_finite(v) and v >= 0 for v in values):
            raise SceneError(f"{where}.{key} = {value!r} must be a number or 6 numbers >= 0 "
                             "(0: none)")


def _is_pose(value: Any) -> bool:
    return isinstance(value, (list, tuple)) and len(value) == 6 and all(map(_finite, value))


def samples(scene: dict, dt: Optional[float] = None, duration: Optional[float] = None) -> float:
    """The number of time steps of times() as a float (it may be too large to hold)."""
    return (duration or scene["duration"]) / (dt or scene["step"])


def times(scene: dict, dt: Optional[float] = None, duration: Optional[float] = None) -> np.ndarray:
    """The scene's time grid 0, dt, 2 dt, ... up to duration (default: the scene's step and
    duration)."""
    dt = dt or scene["step"]
    n = int(round((duration or scene["duration"]) / dt))
    return np.arange(n + 1) * dt


def pose(scene: dict, t, amplitude: float = 1.0,
         frequency: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pose, first and second derivative at times t: three arrays of shape (len(t), 6), with
    every amplitude scaled by `amplitude` and every omega by `frequency`. A scene with a move
    is sampled with trajectory() instead (the move is planned on a platform)."""
    if "move" in scene:
        raise SceneError(f"scene {scene.get('name', '')!r} has a move: sample it with "
                         "stewart.scenes.trajectory(scene, platform), which plans the move")
    return _sinusoids(scene, t, amplitude, frequency)


def _sinusoids(scene: dict, t, amplitude: float = 1.0,
               frequency: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.asarray(t, dtype=float)
    q, qd, qdd = (np.zeros((t.size, 6)) for _ in range(3))
    for i, name in enumerate(POSE):
        s = scene["pose"].get(name, {})
        a, w = amplitude * s.get("amplitude", 0.0), frequency * s.get("omega", 0.0)
        phase = w * t + s.get("phase", 0.0)
        q[:, i] = s.get("mean", 0.0) + a * np.sin(phase)
        qd[:, i] = a * w * np.cos(phase)
        qdd[:, i] = -a * w * w * np.sin(phase)
    return q, qd, qdd


def sample(scene: dict, amplitude: float = 1.0, frequency: float = 1.0,
           duration: Optional[float] = None,
           step: Optional[float] = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Times and exact pose, rate and acceleration (each (n, 6)) of the scene scaled as pose()
    does, on the scene's time grid or duration/step when given."""
    t = times(scene, step, duration)
    return (t, *pose(scene, t, amplitude, frequency))


def trajectory(scene: dict, platform=None, step: Optional[float] = None,
               duration: Optional[float] = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Times and exact pose, rate and acceleration (each (n, 6)) of any scene at `step`
    (default: the scene's): its sinusoids over their duration, then its move planned with
    stewart.move on `platform` (default: the thesis platform with the scene's "parameters"),
    then the goal held at rest for the move's `hold`. The move starts at its `start`, else where
    the sinusoids end (they must end at rest, SceneError if not), else at the scene's home.
    `duration` cuts the run or holds its last pose at rest up to it. stewart.MoveError (a
    ValueError) names the limit a move cannot keep, SceneError a section it cannot use."""
    step = step or scene["step"]
    if "move" not in scene:
        return sample(scene, duration=duration, step=step)
    import stewart
    platform = platform or stewart.Platform(**scene.get("parameters", {}))
    parts = [_sinusoids(scene, times(scene, step))] if "pose" in scene else []
    if parts and np.max(np.abs(parts[0][1][-1])) > REST_RATE:
        raise SceneError(f"scene {scene.get('name', '')!r}: its move starts where its sinusoids "
                         f"end, at t = {times(scene, step)[-1]:.6g} s, but they are not at rest "
                         f"there (rates {parts[0][1][-1].tolist()}): end them where every one "
                         "turns (omega t + phase = pi/2 + k pi), or give the move a start and "
                         "no sinusoids")
    default_start = parts[0][0][-1] if parts else np.asarray(scene.get("home", THESIS_HOME))
    planned = plan_move(scene, platform, step, default_start)
    rows = [planned.pose, planned.pose_rate, planned.pose_accel]
    if parts:  # the move's first row is the sinusoids' last
        rows = [np.vstack([part, row[1:]]) for part, row in zip(parts[0], rows)]
    held = int(round(scene["move"].get("hold", 0.0) / step))
    if duration is not None:
        held = int(round(duration / step)) + 1 - len(rows[0])
    q, qd, qdd = (np.vstack([r, np.zeros((max(held, 0), 6))]) for r in rows)
    q[len(rows[0]):] = rows[0][-1]
    if held < 0:
        q, qd, qdd = q[:held], qd[:held], qdd[:held]
    return (np.arange(len(q)) * step, q, qd, qdd)


def plan_move(scene: dict, platform, step: float, default_start) -> "stewart.Move":
    """The scene's move section planned by stewart.move on platform at sample time `step`; the
    start is the section's, else default_start."""
    import stewart
    section = dict(scene["move"])
    section.pop("hold", None)
    start = section.pop("start", default_start)
    goal = section.pop("goal")
    kind = section.pop("kind", "point")
    return stewart.move(platform, start, goal, kind, sample_time=step, **section)


def _finite(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


#: The pose the shipped scenes are written about: the thesis platform's home.
THESIS_HOME = (0.0, 0.0, 0.5, 0.0, 0.0, 0.0)


def on_platform(scene: dict, platform, scale_to_ranges: bool = False,
                fraction: float = 0.5) -> dict:
    """The scene moved to `platform` (a stewart.Platform): each component's motion about the
    scene's home (its "home" field, default THESIS_HOME, the pose the shipped scenes move
    about) becomes the same motion about the platform's home pose (Platform.check().home); a
    move's start, goal and waypoints move with it (a relative goal, with a frame, stays a
    displacement). With scale_to_ranges, each component's excursion from home (|mean offset| +
    amplitude, and the move's largest offset or displacement) is scaled to `fraction` of the
    axis range from home on its nearer side (Platform.axis_ranges), then all of them together
    by the largest factor <= 1 for which every sample of the sinusoids is within every limit
    (Platform.limits) and the move can be planned without crossing a geometric limit (halved
    until they are, at most 40 times). SceneError if home itself is not a valid pose or no such
    factor is found. The result is a scene dict like any other, with its "home" set to the
    platform's."""
    if not 0.0 < fraction <= 1.0:
        raise SceneError(f"fraction = {fraction!r} must be in (0, 1]")
    check(scene, scene.get("name", "scene"))
    report = platform.check()
    if not report.valid:
        raise SceneError(f"the platform's home pose is not valid, so no scene can move about it:"
                         f"\n{report.text}")
    old_home = np.asarray(scene.get("home", THESIS_HOME), dtype=float)
    home = report.home
    scale = np.ones(6)
    if not scale_to_ranges:
        return _scaled(scene, old_home, home, scale)
    ends = report.ranges.ends[0]  # (6, 2): [min, max] from home
    room = np.minimum(home - ends[:, 0], ends[:, 1] - home)
    excursion = _excursion(scene, old_home)
    moving = excursion > 0
    scale[moving] = fraction * room[moving] / excursion[moving]
    return _within_limits(scene, platform, old_home, home, scale)


def _excursion(scene: dict, home: np.ndarray) -> np.ndarray:
    """Each component's largest distance from home: the sinusoids' |mean - home| + amplitude,
    the move's points' |p - home| (a relative goal: its start's plus the displacement's)."""
    out = np.zeros(6)
    if "pose" in scene:
        for i, p in enumerate(POSE):
            s = scene["pose"].get(p, {})
            out[i] = abs(s.get("mean", 0.0) - home[i]) + abs(s.get("amplitude", 0.0))
    if "move" in scene:
        move = scene["move"]
        start = np.abs(np.asarray(move.get("start", home), dtype=float) - home)
        points = [start]
        if move.get("frame") is None:
            points += [np.abs(np.asarray(p, dtype=float) - home)
                       for p in [move["goal"], *move.get("via", [])]]
        else:
            points.append(start + np.abs(np.asarray(move["goal"], dtype=float)))
        out = np.maximum(out, np.max(points, axis=0))
    return out


def _scaled(scene: dict, old_home: np.ndarray, home: np.ndarray, scale: np.ndarray) -> dict:
    """The scene with component i at home[i] + scale[i] (its offset from old_home[i] + its
    sinusoid), and its move's points likewise (a relative goal scaled)."""
    moved = {k: v for k, v in scene.items() if k not in ("pose", "move")}
    moved["home"] = [float(v) for v in home]

    def place(p):
        return [float(v) for v in home + scale * (np.asarray(p, dtype=float) - old_home)]
    if "pose" in scene:
        moved["pose"] = {}
        for i, p in enumerate(POSE):
            s = dict(scene["pose"].get(p, {}))
            s["mean"] = float(home[i] + scale[i] * (s.get("mean", 0.0) - old_home[i]))
            s["amplitude"] = float(scale[i] * s.get("amplitude", 0.0))
            moved["pose"][p] = s
    if "move" in scene:
        move = dict(scene["move"])
        if "start" in move:
            move["start"] = place(move["start"])
        if move.get("frame") is None:
            move["goal"] = place(move["goal"])
        else:
            move["goal"] = [float(v) for v in scale * np.asarray(move["goal"], dtype=float)]
        if "via" in move:
            move["via"] = [place(p) for p in move["via"]]
        moved["move"] = move
    return moved


def _fits(scene: dict, platform) -> bool:
    """Every sample of the sinusoids within every limit, and the move planned without crossing
    a geometric limit (a move refused for another reason raises)."""
    from .moves import MoveError
    if "pose" in scene and not platform.limits(_sinusoids(scene, times(scene))[0]).within.all():
        return False
    if "move" in scene:
        try:
            trajectory(scene, platform)
        except MoveError as e:
            if e.limit_class in (*POSE_CLASSES, "unreachable"):
                return False
            raise
    return True


def _within_limits(scene: dict, platform, old_home, home, scale) -> dict:
    """The scene scaled by scale, or by scale halved until it fits (SceneError if 40 halvings
    do not do it)."""
    for _ in range(40):
        moved = _scaled(scene, old_home, home, scale)
        if _fits(moved, platform):
            return moved
        scale = scale / 2
    raise SceneError("the scene leaves the platform's limits at every scale tried: check the "
                     "platform with Platform.check()")
