#!/usr/bin/env python3
"""Scenes: small data files (scenes/*.json) that describe a pose trajectory and its parameters.

A scene's pose is a sum of one sinusoid per component, value = mean + amplitude sin(omega t + phase),
so its first and second derivatives are exact (the package's stewart.scenes reads and samples
them). The thesis manoeuvres (heave, roll, pitch, yaw) and a combined cue are in scenes/;
scenes/slider_crank.json ("mechanism": "slider-crank") is the thesis' other mechanism, run by
build/slider-crank-solve instead of the FMU.

usage: scenes.py SCENE OUT.csv [--dt DT] [--no-derivatives]
  writes the scene's poses as a stewart-solve input CSV (SCENE is a name in scenes/ or a path).
"""
import argparse
import pathlib

import numpy as np
from stewart.scenes import DDOT, DOT, POSE, pose, times  # noqa: F401  (the scripts' names)
from stewart import scenes

ROOT = pathlib.Path(__file__).resolve().parents[1]


def load(scene):
    """A scene dict from a name in scenes/ (e.g. 'yaw') or a path to a JSON file."""
    return scenes.load(scene, ROOT / "scenes")


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
