#!/usr/bin/env python3
"""The classical washout tuned to a machine on the shipped manoeuvres and scored by what a person
feels (docs/cueing.md, section 8): the numbers of its tables.

The grid: break frequencies w (translation_frequency = w, translation_washout_frequency = w / 5,
rotation_frequency = 0.4 w: the defaults' ratios) times one common scale k (surge_scale = ... =
yaw_scale = k, 0.1 to 1 by 0.1). Of the grid's points the limits admit, the one of the best
criterion, in three tunings:
  "machine":    one (w, k) for all the manoeuvres, the limiter idle on every one of them (scale 1
                at every sample: the filter alone stays within the limits; the conventional
                tuning of a simulator for its manoeuvres), by the mean criterion over them;
  "manoeuvre":  (w, k) per manoeuvre, the limiter idle (a tuning fitted offline to each
                manoeuvre by the machine's exact limits);
  "no cut":     (w, k) per manoeuvre, the limiter allowed to scale the cue down smoothly at run
                time but never to cut it (the exact limits used at every sample): the classical
                filter as aggressive as the limiter lets it be.
The criterion (lower is better): the mean over the channels the vehicle excites of the RMSE of the
perceived signals (stewart.perception, stewart.cueing_scores) divided by the standard deviation of
the vehicle's perceived signal. It weighs size and shape: the zero-lag correlation alone is blind
to the scale and picks the smallest, least felt cues. Everything else is the unit's default (tilt
coordination at most 15 deg and 3 deg/s; order 3 translation, order 2 rotation); the head at
head_x, head_y, head_z (default SIMONA's design eye point, 1.2075 m above the upper gimbal plane).

usage: cueing_tuning.py [--platform simona_motion_base] [--manoeuvre NAME ...]
                        [--head 0,0,1.2075] [--frequencies 0.5,0.75,1,1.5,2,2.5,3,4,5]
                        [--scales 0.1,0.2,...,1]
prints a Markdown table of the tunings and one of the per-channel scores.
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
import cueing as cueing_script  # noqa: E402  (scripts/cueing.py: the cue and its scores)

SCALES = ("surge_scale", "sway_scale", "heave_scale", "roll_scale", "pitch_scale", "yaw_scale")
TUNINGS = ("machine", "manoeuvre", "no cut")


def options(w, k, head):
    o = {name: k for name in SCALES}
    o.update(translation_frequency=w, translation_washout_frequency=w / 5,
             rotation_frequency=0.4 * w, head_x=head[0], head_y=head[1], head_z=head[2])
    return o


def excited(scores):
    """The channels along which the vehicle's perceived signal varies."""
    return [i for i, note in enumerate(scores.notes) if "vehicle's" not in note]


def criterion(result):
    """Mean over the excited channels of RMSE / std of the vehicle's perceived signal."""
    scores, vehicle = result["scores"], np.hstack(result["vehicle"])
    channels = excited(scores)
    return float(np.mean(scores.rmse[channels] / vehicle[:, channels].std(axis=0)))


def standing_still(platform, vehicle):
    """The criterion of a platform that does not move (it feels (0, 0, g) throughout): the
    reference a cue must beat."""
    t, f, w = vehicle
    rest = np.zeros((t.size, 6))
    rest[:, 2] = np.linalg.norm(_gravity(platform))
    felt = stewart.perception(t, rest[:, :3], rest[:, 3:])
    vehicle_felt = stewart.perception(t, f, w)
    return criterion({"scores": stewart.cueing_scores(t, vehicle_felt, felt),
                      "vehicle": vehicle_felt})


def _gravity(platform):
    return stewart.head_motion(platform, platform.check().home, np.zeros(6),
                               np.zeros(6)).specific_force[0]


def mean_correlation(result):
    """Mean correlation over the excited channels (a platform channel that does not vary: 0)."""
    scores = result["scores"]
    return float(np.mean(np.nan_to_num(scores.correlation[excited(scores)], nan=0.0)))


def tune(platform, vehicles, frequencies, scales, head):
    """{tuning: {manoeuvre: (w, k, run's result)}} over the grid frequencies x scales."""
    runs = {}  # (manoeuvre, w, k) -> result
    for name, vehicle in vehicles.items():
        for w in frequencies:
            for k in scales:
                runs[name, w, k] = cueing_script.run(platform, *vehicle, **options(w, k, head))

    def idle(r):
        return not r["cue"].limited.any()

    def no_cut(r):
        return not r["cue"].cut.any()

    tuned = {t: {} for t in TUNINGS}
    for tuning, admissible in (("manoeuvre", idle), ("no cut", no_cut)):
        for name in vehicles:
            points = [(w, k) for w in frequencies for k in scales
                      if admissible(runs[name, w, k])]
            if points:
                w, k = min(points, key=lambda p: criterion(runs[(name, *p)]))
                tuned[tuning][name] = (w, k, runs[name, w, k])
    shared = [(w, k) for w in frequencies for k in scales
              if all(idle(runs[name, w, k]) for name in vehicles)]
    if shared:
        w, k = min(shared, key=lambda p: np.mean([criterion(runs[(n, *p)]) for n in vehicles]))
        tuned["machine"] = {name: (w, k, runs[name, w, k]) for name in vehicles}
    return tuned, len(runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--platform", default="simona_motion_base")
    parser.add_argument("--manoeuvre", nargs="*", default=list(stewart.manoeuvre_files()))
    parser.add_argument("--head", default="0,0,1.2075", help="x,y,z [m], platform frame")
    parser.add_argument("--frequencies", default="0.5,0.75,1,1.5,2,2.5,3,4,5",
                        help="break frequencies w [rad/s]")
    parser.add_argument("--scales", default=",".join(f"{k / 10:g}" for k in range(1, 11)),
                        help="common scales k")
    args = parser.parse_args()
    scales = [float(v) for v in args.scales.split(",")]
    head = [float(v) for v in args.head.split(",")]
    frequencies = [float(v) for v in args.frequencies.split(",")]
    files = stewart.platform_files()
    platform = stewart.Platform.from_file(files.get(args.platform, args.platform))
    start = time.perf_counter()
    vehicles = {name: stewart.manoeuvre(name) for name in args.manoeuvre}
    tuned, count = tune(platform, vehicles, frequencies, scales, head)
    print(f"cueing_tuning: {args.platform}, head {head} m, break frequencies {frequencies} "
          f"rad/s, scales {scales}: {count} runs, {time.perf_counter() - start:.0f} s\n")
    print("| manoeuvre | tuning | w [rad/s] | k | criterion (RMSE/std) | mean correlation | "
          "limiter acting | smallest scale | largest tilt [deg] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in vehicles:
        print(f"| {name} | standing still | | | {standing_still(platform, vehicles[name]):.3f} "
              "| | | | |")
        for tuning in TUNINGS:
            if name not in tuned[tuning]:
                print(f"| {name} | {tuning} | no admissible point of the grid |||||||")
                continue
            w, k, result = tuned[tuning][name]
            cue = result["cue"]
            tilt = np.degrees(np.abs(cue.pose[:, 3:5]).max())
            print(f"| {name} | {tuning} | {w:g} | {k:.3f} | {criterion(result):.3f} | "
                  f"{mean_correlation(result):.3f} | {100 * cue.limited.mean():.1f} % | "
                  f"{cue.scale.min():.3f} | {tilt:.1f} |")
    print("\n| manoeuvre | channel | correlation: " + " / ".join(TUNINGS) + " | RMSE | delay [s] |")
    print("|---|---|---|---|---|")
    for name in vehicles:
        if any(name not in tuned[t] for t in TUNINGS):
            continue
        scores = [tuned[t][name][2]["scores"] for t in TUNINGS]
        for i in excited(scores[0]):
            unit = "m/s²" if scores[0].channels[i].startswith("f") else "rad/s"
            print(f"| {name} | {scores[0].channels[i]} | "
                  + " / ".join(f"{s.correlation[i]:.3f}" for s in scores) + " | "
                  + " / ".join(f"{s.rmse[i]:.3g}" for s in scores) + f" {unit} | "
                  + " / ".join(f"{s.delay[i]:.2f}" + ("*" if s.notes[i] else "")
                               for s in scores) + " |")
    print("\n*: at the bound of the delay search (1 s), or undefined (nan: the platform's signal "
          "does not vary).")


if __name__ == "__main__":
    main()
