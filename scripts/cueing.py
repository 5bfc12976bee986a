#!/usr/bin/env python3
"""Motion cueing of a vehicle's motion on a machine, scored by what a person feels
(docs/cueing.md): the vehicle's specific force and angular velocity through stewart.cueing, the
platform's poses back to the motion at the head (stewart.head_motion), both through the
vestibular model (stewart.perception) and compared per channel (stewart.cueing_scores).

usage: cueing.py (VEHICLE.csv | --manoeuvre NAME) --platform FILE [--algorithm classical]
                 [--option NAME=VALUE ...] [--max-delay 1.0] [-o OUT.csv] [--no-plot]

VEHICLE.csv has the manoeuvre files' columns (t, f_x, f_y, f_z [m/s2], w_x, w_y, w_z [rad/s]; at
the head, x forward, y left, z up, uniformly sampled); --manoeuvre takes a shipped one
(stewart.manoeuvre_files()). --option sets a cueing option (stewart.cueing's keywords, e.g.
--option surge_scale=0.6 --option head_z=1.2; its head_x, head_y, head_z are also where the
platform's motion is felt). Writes
  OUT.csv            the platform trajectory: t, x .. yaw, x_dot .. yaw_dot, x_ddot .. yaw_ddot
                     (stewart-solve's input columns; the tool in the user frame, SI)
  OUT_perceived.csv  t; the vehicle's input and the platform's motion at the head
                     (vehicle_f_x .. platform_w_z); what each makes one feel (perceived_vehicle_f_x
                     .. perceived_platform_w_z); the limiter's scale, limited, cut, tilt_limited
  OUT_scores.csv     channel, rmse, correlation, delay [s], peak_correlation, note
  OUT.png            the perceived signals of vehicle and platform, the pose
and prints the scores table. Exit status 2 for bad arguments (the message names them).
"""
import argparse
import pathlib
import sys

import numpy as np

import stewart
from stewart.cueing import option_names
from stewart.scores import PERCEIVED_CHANNELS as CHANNELS

POSE = ("x", "y", "z", "roll", "pitch", "yaw")
HEAD = ("head_x", "head_y", "head_z")


def run(platform, t, specific_force, angular_velocity, algorithm="classical", max_delay=1.0,
        **options):
    """The cue and its scores: a dict with t, cue (stewart.Cueing), head (the platform's motion
    at the head, HeadMotion), vehicle and platform (what each makes one feel, Perceived) and
    scores (CueingScores)."""
    cue = stewart.cueing(platform, t, specific_force, angular_velocity, algorithm=algorithm,
                         **options)
    head = stewart.head_motion(platform, cue.pose, cue.pose_rate, cue.pose_accel,
                               head=[options.get(name, 0.0) for name in HEAD])
    vehicle = stewart.perception(t, specific_force, angular_velocity)
    felt = stewart.perception(t, head.specific_force, head.angular_velocity)
    return {"t": np.asarray(t, float), "cue": cue, "head": head,
            "vehicle_input": (np.asarray(specific_force, float),
                              np.asarray(angular_velocity, float)),
            "vehicle": vehicle, "platform": felt,
            "scores": stewart.cueing_scores(t, vehicle, felt, max_delay=max_delay)}


def _write(path, columns, table):
    with open(path, "w", encoding="utf-8") as stream:
        stream.write(",".join(columns) + "\n")
        for row in table:
            stream.write(",".join(repr(float(v)) for v in row) + "\n")


def write(result, out):
    """OUT.csv, OUT_perceived.csv and OUT_scores.csv (module docstring); returns their paths."""
    out = pathlib.Path(out)
    stem = out.with_suffix("")
    cue, t = result["cue"], result["t"]
    paths = [out, pathlib.Path(f"{stem}_perceived.csv"), pathlib.Path(f"{stem}_scores.csv")]
    _write(paths[0], ["t", *POSE, *(f"{p}_dot" for p in POSE), *(f"{p}_ddot" for p in POSE)],
           np.column_stack([t, cue.pose, cue.pose_rate, cue.pose_accel]))
    groups = {"vehicle": result["vehicle_input"], "platform": result["head"],
              "perceived_vehicle": result["vehicle"], "perceived_platform": result["platform"]}
    columns = ["t"] + [f"{g}_{c}" for g in groups for c in CHANNELS] + [
        "scale", "limited", "cut", "tilt_limited"]
    _write(paths[1], columns, np.column_stack(
        [t] + [np.hstack(pair) for pair in groups.values()] +
        [cue.scale, cue.limited, cue.cut, cue.tilt_limited]))
    s = result["scores"]
    with open(paths[2], "w", encoding="utf-8") as stream:
        stream.write("channel,rmse,correlation,delay,peak_correlation,note\n")
        for i, name in enumerate(s.channels):
            note = s.notes[i].replace('"', "'")
            values = ",".join(repr(float(getattr(s, key)[i]))
                              for key in ("rmse", "correlation", "delay", "peak_correlation"))
            stream.write(f"{name},{values},\"{note}\"\n")
    return paths


def plot(result, path, title=""):
    """The six perceived channels, vehicle against platform, and the pose; returns what each
    panel draws (plots.drawn)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import plots
    t, cue = result["t"], result["cue"]
    vehicle = np.hstack(result["vehicle"])
    platform = np.hstack(result["platform"])
    fig, axes = plt.subplots(4, 2, figsize=(12, 11), sharex=True)
    for i, name in enumerate(CHANNELS):
        ax = axes[i % 3, i // 3]
        ax.plot(t, vehicle[:, i], lw=1.0, label="vehicle")
        ax.plot(t, platform[:, i], lw=1.0, label="platform")
        unit = "m/s²" if name.startswith("f") else "rad/s"
        ax.set_ylabel(f"perceived {name} [{unit}]")
    for i, name in enumerate(POSE[:3]):
        axes[3, 0].plot(t, cue.pose[:, i], lw=1.0, label=name)
    axes[3, 0].set_ylabel("position [m]")
    for i, name in enumerate(POSE[3:]):
        axes[3, 1].plot(t, np.degrees(cue.pose[:, 3 + i]), lw=1.0, label=name)
    axes[3, 1].set_ylabel("angle [deg]")
    for ax in axes.flat:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for ax in axes[3]:
        ax.set_xlabel("t [s]")
    fig.suptitle(title or "Motion cueing: what the vehicle and the platform make one feel")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return plots.drawn(axes.flat)


def options_of(pairs, parser):
    """{name: value} of --option NAME=VALUE arguments; parser.error names a bad one."""
    known = set(option_names()) - {"algorithm"}
    options = {}
    for text in pairs or []:
        name, sep, value = text.partition("=")
        name = name.strip()
        if not sep or not name:
            parser.error(f"--option {text!r}: give NAME=VALUE, e.g. surge_scale=0.6")
        if name not in known:
            parser.error(f"--option {name}: not a cueing option ({', '.join(sorted(known))})")
        try:
            options[name] = float(value)
        except ValueError:
            parser.error(f"--option {text!r}: {value!r} is not a number")
    return options


def add_vehicle_arguments(parser):
    """The vehicle (a CSV or --manoeuvre), --platform and the repeated --option NAME=VALUE."""
    parser.add_argument("vehicle", nargs="?", help="a vehicle CSV (the manoeuvre files' columns)")
    parser.add_argument("--manoeuvre", help="a shipped manoeuvre: " +
                        ", ".join(stewart.manoeuvre_files()))
    parser.add_argument("--platform", required=True, help="a platform file (docs/geometry.md)")
    parser.add_argument("--option", action="append", metavar="NAME=VALUE",
                        help="a cueing option (docs/cueing.md, section 3); repeat for more")


def vehicle_of(args, parser, script):
    """(t, specific_force, angular_velocity, platform, options) of add_vehicle_arguments's
    arguments; a bad or missing one exits with its usage error or a message naming the cause."""
    if (args.vehicle is None) == (args.manoeuvre is None):
        parser.error("give either VEHICLE.csv or --manoeuvre NAME")
    options = options_of(args.option, parser)
    try:
        t, f, w = stewart.manoeuvre(args.manoeuvre if args.manoeuvre else args.vehicle)
        platform = stewart.Platform.from_file(args.platform)
    except (ValueError, TypeError) as e:  # ParameterError is a ValueError
        parser.exit(2, f"{script}: {e}\n")
    return t, f, w, platform, options


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_vehicle_arguments(parser)
    parser.add_argument("--algorithm", default="classical", choices=stewart.CUEING_ALGORITHMS)
    parser.add_argument("--max-delay", type=float, default=1.0,
                        help="bound of the delay search [s] (default 1)")
    parser.add_argument("-o", "--out", default="cueing.csv", help="OUT.csv (default cueing.csv)")
    parser.add_argument("--no-plot", action="store_true")
    args = parser.parse_args(argv)
    t, f, w, platform, options = vehicle_of(args, parser, "cueing.py")
    try:
        result = run(platform, t, f, w, args.algorithm, args.max_delay, **options)
    except (ValueError, TypeError) as e:  # ParameterError is a ValueError
        parser.exit(2, f"cueing.py: {e}\n")
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    paths = write(result, out)
    name = args.manoeuvre or pathlib.Path(args.vehicle).name
    if not args.no_plot:
        paths.append(out.with_suffix(".png"))
        plot(result, paths[-1], f"{name} on {pathlib.Path(args.platform).stem} "
                                f"({args.algorithm})")
    cue = result["cue"]
    print(f"cueing.py: {name}, {t[-1] - t[0]:g} s, {args.algorithm} on {args.platform}")
    print(f"cueing.py: limiter acting {100 * cue.limited.mean():.1f} % of the samples, "
          f"cut {int(cue.cut.sum())}, smallest scale {cue.scale.min():.3f}")
    print(result["scores"].table())
    print("cueing.py: wrote " + ", ".join(str(p) for p in paths))
    return 0


if __name__ == "__main__":
    sys.exit(main())
