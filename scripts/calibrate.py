#!/usr/bin/env python3
"""Calibrates a hexapod from measured poses: identifies its joints and length offsets (optionally
its tool and user frames) and writes a platform file of the calibrated machine.

usage: calibrate.py NOMINAL.json MEASURED.csv OUT.json [--frames tool|user|both]
                    [--loss linear|soft_l1|huber|cauchy|arctan] [--position-noise M]
                    [--angle-noise RAD] [--reading-noise M] [--report PREFIX]

MEASURED.csv: a header x,y,z,roll,pitch,yaw,L1,...,L6 and one row per pose: the tracker's pose of
the tool frame in the user frame [m, rad] and the six sensor readings [m]. OUT.json is a platform
file (stewart-solve --platform, Platform.from_file, FMU parameters); PREFIX.txt (the report) and
PREFIX.png (residuals per pose before and after) go beside it (PREFIX: OUT without .json, plus
"_report"). A bad file, a set of poses that cannot identify the geometry or a failed fit: exit 1
with a message naming the line and column or the parameters, and nothing written.
"""
import argparse
import io
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stewart  # noqa: E402
from stewart.calibration_io import (FileError, platform_file_text, read_measurements,  # noqa: E402
                                    read_platform)


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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("nominal", help="platform file of the machine as drawn (JSON)")
    parser.add_argument("measured", help="measurement CSV")
    parser.add_argument("out", help="platform file to write (JSON)")
    parser.add_argument("--frames", choices=("tool", "user", "both"), default=None,
                        help="also identify the tool frame, the user frame or both")
    parser.add_argument("--loss", default="linear", choices=stewart.calibration.LOSSES)
    parser.add_argument("--position-noise", type=float, default=10e-6, help="[m]")
    parser.add_argument("--angle-noise", type=float, default=20e-6, help="[rad]")
    parser.add_argument("--reading-noise", type=float, default=1e-6, help="[m]")
    parser.add_argument("--report", default=None, help="prefix of the report's .txt and .png")
    args = parser.parse_args(argv)
    prefix = args.report or (args.out[:-5] if args.out.endswith(".json") else args.out) + "_report"
    try:
        nominal = read_platform(args.nominal)
        measured = read_measurements(args.measured)
        result = stewart.calibrate(nominal, measured.poses, measured.readings,
                                   frames=args.frames, loss=args.loss,
                                   position_noise=args.position_noise,
                                   angle_noise=args.angle_noise,
                                   reading_noise=args.reading_noise)
    except (FileError, ValueError) as e:  # UnobservableError and ReadingError are ValueErrors
        print(f"calibrate.py: {e}", file=sys.stderr)
        return 1
    outliers = ", ".join(f"line {measured.lines[row]}" for row in result.outliers)
    report = (f"calibration of {args.nominal} from {args.measured}\n"
              + (f"outliers (measurement file): {outliers}\n" if outliers else "")
              + result.report())
    files = {args.out: platform_file_text(result.platform).encode(),
             prefix + ".txt": report.encode(),
             prefix + ".png": residual_plot(result, measured.lines)}
    for path, content in files.items():
        with open(path, "wb") as f:
            f.write(content)
    print(f"calibrate.py: wrote {', '.join(files)}; reading residual RMS "
          f"{result.rms('before') * 1e6:.2f} um -> {result.rms('after') * 1e6:.3f} um, "
          f"condition {result.condition:.3g}" + (f"; outliers: {outliers}" if outliers else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
