#!/usr/bin/env python3
"""Calibrates a hexapod from measured poses: identifies its joints and length offsets (or the
unknowns chosen with --identify) and writes a platform file of the calibrated machine.

usage: calibrate.py NOMINAL.json MEASURED.csv OUT.json [--identify WORDS] [--frames tool|user|both]
                    [--joint-tolerance L] [--offset-tolerance L] [--frame-tolerance L]
                    [--frame-angle-tolerance A] [--max-std L_OR_A]
                    [--loss linear|soft_l1|huber|cauchy|arctan] [--position-noise L]
                    [--angle-noise A] [--reading-noise L] [--report PREFIX]

Lengths L and angles A are numbers in m and rad, or with a unit: 0.5mm, 10um, 20urad, 0.01deg.
MEASURED.csv: a header x,y,z,roll,pitch,yaw,L1,...,L6 and one row per pose: the tracker's pose of
the tool frame in the user frame [m, rad] and the six sensor readings [m]. OUT.json is a platform
file (stewart-solve --platform, Platform.from_file, FMU parameters); PREFIX.txt (the report:
predicted pose accuracy, residuals, what the prior set, each unknown) and PREFIX.png (residuals
per pose before and after) go beside it (PREFIX: OUT without .json, plus "_report"). A bad file,
measurements no machine within its tolerances gives, a set of poses that cannot identify the
unknowns to --max-std, a failed fit or an output that cannot be written: exit 1 with a message
naming the line and column, the pose's line and leg, or the parameters, and nothing written.
"""
import argparse
import io
import os
import re
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stewart  # noqa: E402
from stewart.calibration_checks import MeasurementError  # noqa: E402
from stewart.calibration_io import (FileError, platform_file_text, read_measurements,  # noqa: E402
                                    read_platform)
from stewart.calibration_model import IDENTIFY_CHOICES  # noqa: E402

LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
ANGLE_UNITS = {"rad": 1.0, "mrad": 1e-3, "urad": 1e-6, "µrad": 1e-6, "deg": np.pi / 180,
               "arcsec": np.pi / 180 / 3600}


def quantity(units: dict, kind: str):
    """An argparse type: a number in SI, or a number with one of units (locale-independent)."""
    def parse(text: str) -> float:
        match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([a-zµ]*)\s*", text)
        try:
            value = float(match.group(1)) if match else None
        except ValueError:
            value = None
        unit = match.group(2) if match else ""
        if value is None or (unit and unit not in units):
            raise argparse.ArgumentTypeError(
                f"'{text}' is not a {kind}: a number in SI, or with a unit of "
                f"{', '.join(units)}")
        return value * units[unit] if unit else value
    return parse


LENGTH = quantity(LENGTH_UNITS, "length")
ANGLE = quantity(ANGLE_UNITS, "angle")
LENGTH_OR_ANGLE = quantity({**LENGTH_UNITS, **ANGLE_UNITS}, "length or angle")


def residual_plot(result, lines) -> bytes:
    """PNG of each pose's largest reading residual before and after calibration."""
    fig, ax = plt.subplots(figsize=(9, 4.5))
    rows = np.arange(len(lines))
    before = np.max(np.abs(result.residuals_before), axis=1) * 1e6
    after = np.max(np.abs(result.residuals_after), axis=1) * 1e6
    ax.semilogy(rows, before, "o-", label="nominal geometry")
    ax.semilogy(rows, after, "s-", label="calibrated geometry")
    for row in result.outliers:
        ax.annotate(f"outlier: line {lines[row]}", (row, after[row]), fontsize="small")
    ax.set_xlabel("pose (row of the measurement file)")
    ax.set_ylabel("largest |reading residual| [um]")
    ax.set_title("Reading residuals per pose, before and after calibration")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=110)
    plt.close(fig)
    return buffer.getvalue()


def arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("nominal", help="platform file of the machine as drawn (JSON)")
    parser.add_argument("measured", help="measurement CSV")
    parser.add_argument("out", help="platform file to write (JSON)")
    parser.add_argument("--identify", default="joints,offsets",
                        help="the unknowns, comma-separated: " + ", ".join(IDENTIFY_CHOICES)
                        + " (default joints,offsets)")
    parser.add_argument("--frames", choices=("tool", "user", "both"), default=None,
                        help="also identify the tool frame, the user frame or both")
    parser.add_argument("--joint-tolerance", type=LENGTH, default=1e-3,
                        help="prior standard deviation of each joint coordinate (default 1mm)")
    parser.add_argument("--offset-tolerance", type=LENGTH, default=1e-3,
                        help="prior standard deviation of each length offset (default 1mm)")
    parser.add_argument("--frame-tolerance", type=LENGTH, default=5e-3,
                        help="prior standard deviation of a frame's origin (default 5mm)")
    parser.add_argument("--frame-angle-tolerance", type=ANGLE, default=5e-3,
                        help="prior standard deviation of a frame's angles (default 5mrad)")
    parser.add_argument("--max-std", type=LENGTH_OR_ANGLE, default=None,
                        help="refuse when an unknown's standard deviation would exceed this "
                             "(default: no limit; the report gives the predicted accuracy)")
    parser.add_argument("--loss", default="linear", choices=stewart.calibration.LOSSES)
    parser.add_argument("--position-noise", type=LENGTH, default=10e-6, help="(default 10um)")
    parser.add_argument("--angle-noise", type=ANGLE, default=20e-6, help="(default 20urad)")
    parser.add_argument("--reading-noise", type=LENGTH, default=1e-6, help="(default 1um)")
    parser.add_argument("--report", default=None, help="prefix of the report's .txt and .png")
    return parser.parse_args(argv)


def check_writable(paths) -> None:
    """OSError naming the first path whose folder is missing or not writable, before any work."""
    for path in paths:
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            raise OSError(f"{path}: the folder {folder} does not exist")
        if not os.access(folder, os.W_OK) or (os.path.exists(path)
                                               and not os.access(path, os.W_OK)):
            raise OSError(f"{path}: not writable")
        if os.path.isdir(path):
            raise OSError(f"{path}: is a folder")


def write_all(files: dict) -> None:
    """Every file or none: each written to a temporary file beside it, then all renamed."""
    written = []
    try:
        for path, content in files.items():
            handle, temporary = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)),
                                                 prefix=".calibrate-")
            written.append((temporary, path))
            with os.fdopen(handle, "wb") as f:
                f.write(content)
        for temporary, path in written:
            os.replace(temporary, path)
    except OSError:
        for temporary, _ in written:
            if os.path.exists(temporary):
                os.remove(temporary)
        raise


def calibrate(args, measured):
    try:
        nominal = read_platform(args.nominal)
        return stewart.calibrate(nominal, measured.poses, measured.readings,
                                 identify=args.identify, frames=args.frames,
                                 joint_tolerance=args.joint_tolerance,
                                 offset_tolerance=args.offset_tolerance,
                                 frame_tolerance=args.frame_tolerance,
                                 frame_angle_tolerance=args.frame_angle_tolerance,
                                 max_std=args.max_std, loss=args.loss,
                                 position_noise=args.position_noise,
                                 angle_noise=args.angle_noise,
                                 reading_noise=args.reading_noise)
    except MeasurementError as e:
        lines = sorted({measured.lines[r] for r in e.rows if r < len(measured.lines)})
        where = (f" (pose row {e.rows[0]} is line {measured.lines[e.rows[0]]} of "
                 f"{args.measured}" + (f"; lines {', '.join(map(str, lines[:10]))}"
                                       if len(lines) > 1 else "") + ")") if lines else ""
        raise ValueError(f"{e}{where}") from None


def main(argv=None) -> int:
    args = arguments(argv)
    prefix = args.report or (args.out[:-5] if args.out.endswith(".json") else args.out) + "_report"
    outputs = [args.out, prefix + ".txt", prefix + ".png"]
    try:
        check_writable(outputs)
        measured = read_measurements(args.measured)
        result = calibrate(args, measured)
        outliers = ", ".join(f"line {measured.lines[row]} (leg {result.outlier_leg(row)})"
                             for row in result.outliers)
        report = (f"calibration of {args.nominal} from {args.measured}\n"
                  + (f"outliers (measurement file): {outliers}\n" if outliers else "")
                  + result.report())
        write_all({args.out: platform_file_text(result.platform).encode(),
                   outputs[1]: report.encode(),
                   outputs[2]: residual_plot(result, measured.lines)})
    except (FileError, ValueError, OSError) as e:  # UnobservableError, ReadingError: ValueErrors
        print(f"calibrate.py: {e}", file=sys.stderr)
        return 1
    accuracy = result.accuracy
    print(f"calibrate.py: wrote {', '.join(outputs)}; predicted pose error inside the "
          f"workspace: worst {accuracy.position_worst * 1e6:.2f} um, "
          f"{accuracy.orientation_worst * 1e6:.2f} urad; reading residual RMS "
          f"{result.rms('before') * 1e6:.2f} um -> {result.rms('after') * 1e6:.3f} um"
          + (f"; {result.undetermined} combination(s) set by the prior"
             if result.undetermined else "")
          + (f"; outliers: {outliers}" if outliers else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
