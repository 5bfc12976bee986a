"""Scenes: pose trajectories as one sinusoid per pose component (scenes/*.json).

value = mean + amplitude sin(omega t + phase), so the rates and accelerations are exact. The one
place that reads, checks and samples a scene: the scripts (scripts/scenes.py, run_scene.py,
closed_loop.py) and the sweeps use it. The FMU StewartScene plays the same formula in C.
"""
from __future__ import annotations

import json
import math
import pathlib
from typing import Any, Optional, Union

import numpy as np

POSE = ("x", "y", "z", "roll", "pitch", "yaw")
DOT = tuple(f"{p}_dot" for p in POSE)
DDOT = tuple(f"{p}_ddot" for p in POSE)
SINUSOID = ("mean", "amplitude", "omega", "phase")


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
    numbers and a finite positive duration and step (the slider-crank scene has no pose)."""
    if not isinstance(scene, dict):
        raise SceneError(f"{where} = {scene!r} must be a scene object")
    if scene.get("mechanism") == "slider-crank":
        return
    pose = scene.get("pose")
    if not isinstance(pose, dict) or set(pose) - set(POSE):
        raise SceneError(f"{where}: pose = {pose!r} must map components of {POSE} to sinusoids")
    for comp, s in pose.items():
        if not isinstance(s, dict):
            raise SceneError(f"{where}.pose.{comp} = {s!r} must be an object (mean, amplitude, "
                             "omega, phase)")
        for key in SINUSOID:
            if not _finite(s.get(key, 0.0)):
                raise SceneError(f"{where}.pose.{comp}.{key} = {s.get(key)!r} must be a finite number")
    for key in ("duration", "step"):
        if not (_finite(scene.get(key)) and scene[key] > 0):
            raise SceneError(f"{where}.{key} = {scene.get(key)!r} must be a finite number > 0")
    home = scene.get("home", THESIS_HOME)
    if not (isinstance(home, (list, tuple)) and len(home) == 6 and all(map(_finite, home))):
        raise SceneError(f"{where}.home = {home!r} must be a pose of 6 finite numbers (the pose "
                         "the scene moves about)")


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
    every amplitude scaled by `amplitude` and every omega by `frequency`."""
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


def _finite(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


#: The pose the shipped scenes are written about: the thesis platform's home.
THESIS_HOME = (0.0, 0.0, 0.5, 0.0, 0.0, 0.0)


def on_platform(scene: dict, platform, scale_to_ranges: bool = False,
                fraction: float = 0.5) -> dict:
    """The scene moved to `platform` (a stewart.Platform): each component's motion about the
    scene's home (its "home" field, default THESIS_HOME, the pose the shipped scenes move
    about) becomes the same motion about the platform's home pose (Platform.check().home).
    With scale_to_ranges, each component's excursion from home (|mean offset| + amplitude) is
    scaled to `fraction` of the axis range from home on its nearer side (Platform.axis_ranges),
    then all of them together by the largest factor <= 1 for which every sample of the scene
    is within every limit (Platform.limits; halved until it is, at most 40 times). SceneError
    if home itself is not a valid pose or no such factor is found. The result is a scene dict
    like any other (sinusoids), with its "home" set to the platform's."""
    if not 0.0 < fraction <= 1.0:
        raise SceneError(f"fraction = {fraction!r} must be in (0, 1]")
    check(scene, scene.get("name", "scene"))
    report = platform.check()
    if not report.valid:
        raise SceneError(f"the platform's home pose is not valid, so no scene can move about it:"
                         f"\n{report.text}")
    old_home = np.asarray(scene.get("home", THESIS_HOME), dtype=float)
    home = report.home
    offset = np.array([scene["pose"].get(p, {}).get("mean", 0.0) - old_home[i]
                       for i, p in enumerate(POSE)])
    amplitude = np.array([abs(scene["pose"].get(p, {}).get("amplitude", 0.0)) for p in POSE])
    scale = np.ones(6)
    if scale_to_ranges:
        ends = report.ranges.ends[0]  # (6, 2): [min, max] from home
        room = np.minimum(home - ends[:, 0], ends[:, 1] - home)
        excursion = np.abs(offset) + amplitude
        moving = excursion > 0
        scale[moving] = fraction * room[moving] / excursion[moving]
    if scale_to_ranges:
        return _within_limits(scene, platform, home, offset, scale)
    return _scaled(scene, home, offset, scale)


def _scaled(scene: dict, home: np.ndarray, offset: np.ndarray, scale: np.ndarray) -> dict:
    """The scene with component i at home[i] + scale[i] (offset[i] + its sinusoid)."""
    moved = {k: v for k, v in scene.items() if k != "pose"}
    moved["home"] = [float(v) for v in home]
    moved["pose"] = {}
    for i, p in enumerate(POSE):
        s = dict(scene["pose"].get(p, {}))
        s["mean"] = float(home[i] + scale[i] * offset[i])
        s["amplitude"] = float(scale[i] * s.get("amplitude", 0.0))
        moved["pose"][p] = s
    return moved


def _within_limits(scene: dict, platform, home, offset, scale) -> dict:
    """The scene scaled by scale, or by scale halved until every sample is within every limit
    (SceneError if 40 halvings do not do it)."""
    t = times(scene)
    for _ in range(40):
        moved = _scaled(scene, home, offset, scale)
        if platform.limits(pose(moved, t)[0]).within.all():
            return moved
        scale = scale / 2
    raise SceneError("the scene leaves the platform's limits at every scale tried: check the "
                     "platform with Platform.check()")
