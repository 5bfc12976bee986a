#!/usr/bin/env python3
"""Scenes: small data files (scenes/*.json) that describe a pose trajectory and its parameters.

A scene's pose is a sum of one sinusoid per component, value = mean + amplitude sin(omega t + phase),
so its first and second derivatives are exact (the package's stewart.scenes reads and samples
them); or a move section, a rest-to-rest move that stewart.move plans (docs/moves.md). The thesis manoeuvres (heave, roll, pitch, yaw) and a combined cue are in scenes/;
scenes/slider_crank.json ("mechanism": "slider-crank") is the thesis' other mechanism, run by
build/slider-crank-solve instead of the FMU.

usage: scenes.py SCENE OUT.csv [--dt DT] [--no-derivatives]
  writes the scene's poses as a stewart-solve input CSV (SCENE is a name in scenes/ or a path).
"""
import argparse
import pathlib

import numpy as np
# the scripts' names
from stewart.scenes import DDOT, DOT, POSE, pose, times, trajectory  # noqa: F401
from stewart import scenes

ROOT = pathlib.Path(__file__).resolve().parents[1]


def load(scene):
    """A scene dict from a name in scenes/ (e.g. 'yaw') or a path to a JSON file."""
    return scenes.load(scene, ROOT / "scenes")


def add_platform_arguments(parser):
    """--platform FILE.json and --scale-to-ranges, for every script that runs a scene."""
    parser.add_argument("--platform", help="a platform file (docs/geometry.md): the machine the "
                        "scene runs on; the scene then moves about the machine's home pose")
    parser.add_argument("--scale-to-ranges", action="store_true",
                        help="scale the scene to half the machine's (--platform's) axis "
                             "ranges from home (and less until every sample is within every "
                             "limit)")


def on_platform(scene, args):
    """(scene, platform, FMU start values) for the script's arguments: the scene as given with
    the thesis platform when there is no --platform; else the scene moved to the machine's home
    (and scaled with --scale-to-ranges), the machine and its parameters as FMU start values."""
    import stewart
    from stewart.scenes import on_platform as move_scene
    if not args.platform:
        if args.scale_to_ranges:
            raise SystemExit("--scale-to-ranges needs --platform")
        return scene, stewart.Platform(**scene.get("parameters", {})), {}
    platform = stewart.Platform.from_file(args.platform)
    moved = move_scene(scene, platform, scale_to_ranges=args.scale_to_ranges)
    return moved, platform, stewart.fmu_start_values(platform)


def write_pose_csv(scene, path, dt=None, derivatives=True, platform=None):
    """The scene's poses (a move planned on platform, default the thesis') as a CSV."""
    if isinstance(scene, (str, pathlib.Path)):
        scene = load(scene)
    t, q, qd, qdd = trajectory(scene, platform, dt)
    write_trajectory(path, t, q, qd, qdd, derivatives)


def write_trajectory(path, t, q, qd, qdd, derivatives=True):
    """Times, poses, rates and accelerations as a stewart-solve input CSV (the scene player's
    trajectory file), every number as the shortest text that reads back to the same double."""
    columns = ["t", *POSE] + ([*DOT, *DDOT] if derivatives else [])
    table = np.column_stack([t, q] + ([qd, qdd] if derivatives else []))
    with open(path, "w") as f:
        f.write(",".join(columns) + "\n")
        for row in table:
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def player_values(scene, path, platform=None, step=None, duration=None):
    """The scene player's (StewartScene.fmu) parameters that play the scene: its sinusoids; for
    a scene with a move, its trajectory (trajectory(): the move planned by stewart.move on
    platform at `step`, held at rest to `duration`) written to the file `path` and that file's
    absolute path as trajectory_file (the player reads it when it is initialised)."""
    if "move" not in scene:
        return {f"{p}_{key}": float(scene["pose"].get(p, {}).get(key, 0.0))
                for p in POSE for key in scenes.SINUSOID}
    path = pathlib.Path(path).resolve()
    write_trajectory(path, *trajectory(scene, platform, step, duration))
    return {"trajectory_file": str(path)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--dt", type=float, help="sample spacing [s] (default: the scene's step)")
    parser.add_argument("--no-derivatives", action="store_true",
                        help="pose columns only (stewart-solve then uses finite differences)")
    args = parser.parse_args()
    try:
        write_pose_csv(args.scene, args.out, args.dt, not args.no_derivatives)
    except ValueError as e:  # SceneError, stewart.MoveError: the message names the cause
        raise SystemExit(f"scenes.py: {e}") from None


if __name__ == "__main__":
    main()
