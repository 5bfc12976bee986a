#!/usr/bin/env python3
"""Scenes: small data files (scenes/*.json) that describe a pose trajectory and its parameters.

A scene's pose is a sum of one sinusoid per component, value = mean + amplitude sin(omega t + phase),
so its first and second derivatives are exact. The thesis manoeuvres (heave, roll, pitch, yaw) and
a combined cue are in scenes/; scenes/slider_crank.json ("mechanism": "slider-crank") is the
thesis' other mechanism, run by build/slider-crank-solve instead of the FMU.

usage: scenes.py SCENE OUT.csv [--dt DT] [--no-derivatives]
  writes the scene's poses as a stewart-solve input CSV (SCENE is a name in scenes/ or a path).
"""
import argparse
import json
import pathlib

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
POSE = ("x", "y", "z", "roll", "pitch", "yaw")
DOT = tuple(f"{p}_dot" for p in POSE)
DDOT = tuple(f"{p}_ddot" for p in POSE)


def load(scene):
    """A scene dict from a name in scenes/ (e.g. 'yaw') or a path to a JSON file."""
    path = pathlib.Path(scene)
    if not path.suffix:
        path = ROOT / "scenes" / f"{scene}.json"
    data = json.loads(path.read_text())
    data.setdefault("name", path.stem)
    unknown = set(data.get("pose", {})) - set(POSE)
    if unknown:
        raise ValueError(f"{path}: unknown pose components {sorted(unknown)}")
    return data


def times(scene, dt=None):
    dt = dt or scene["step"]
    n = int(round(scene["duration"] / dt))
    return np.arange(n + 1) * dt


def pose(scene, t):
    """Pose, first and second derivative at times t: three arrays of shape (len(t), 6)."""
    t = np.asarray(t, dtype=float)
    q, qd, qdd = (np.zeros((t.size, 6)) for _ in range(3))
    for i, name in enumerate(POSE):
        s = scene["pose"].get(name, {})
        a, w, phi = s.get("amplitude", 0.0), s.get("omega", 0.0), s.get("phase", 0.0)
        q[:, i] = s.get("mean", 0.0) + a * np.sin(w * t + phi)
        qd[:, i] = a * w * np.cos(w * t + phi)
        qdd[:, i] = -a * w * w * np.sin(w * t + phi)
    return q, qd, qdd


def write_pose_csv(scene, path, dt=None, derivatives=True):
    if isinstance(scene, (str, pathlib.Path)):
        scene = load(scene)
    t = times(scene, dt)
    q, qd, qdd = pose(scene, t)
    columns = ["t", *POSE] + ([*DOT, *DDOT] if derivatives else [])
    table = np.column_stack([t, q] + ([qd, qdd] if derivatives else []))
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for row in table:
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--dt", type=float, help="sample spacing [s] (default: the scene's step)")
    parser.add_argument("--no-derivatives", action="store_true",
                        help="pose columns only (stewart-solve then uses finite differences)")
    args = parser.parse_args()
    write_pose_csv(args.scene, args.out, args.dt, not args.no_derivatives)


if __name__ == "__main__":
    main()
