#!/usr/bin/env python3
"""Runs a sweep (a load envelope or workspace maps) on Dask; results into OUT_DIR.

usage: sweep.py SPEC.json OUT_DIR [--workers N] [--scheduler ADDRESS] [--units mm,deg] [--no-progress]
                [--platform FILE.json] [--scale-to-ranges]

With no --scheduler it starts a LocalCluster of N worker processes (default: one per core) on
this machine; with one (tcp://host:8786, as `dask scheduler` prints) it uses that cluster's
workers. A bad spec or OUT_DIR fails before any work (exit 2), naming the field. Run again on
the same OUT_DIR, it computes only the chunks that are missing. --platform FILE.json is the
machine (it replaces the spec's platform_file); an envelope's scenes move about the machine's
home (as run_scene.py --platform moves them), scaled to its axis ranges with --scale-to-ranges.
The results are in m and rad unless --units asks for others (mm or um, deg, mrad or urad) for
the merged tables, the CSV, volume.json and the plots. docs/sweeps.md has the spec format.
"""
import argparse
import pathlib
import sys

import scenes
from stewart.sweeps import SpecError, load, run
from stewart.sweeps.units import Units

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("spec", help="the sweep spec (JSON)")
    parser.add_argument("out_dir", help="directory for the results")
    parser.add_argument("--workers", type=int, help="LocalCluster worker processes (default: cores)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("--scenes", default=str(ROOT / "scenes"), help="where scene names are found")
    parser.add_argument("--units", default="m,rad",
                        help="length and angle units of the results, e.g. mm,deg (default m,rad)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    scenes.add_platform_arguments(parser)  # --platform replaces the spec's platform_file
    parser.add_argument("--view", action="store_true", help="a workspace sweep: also write "
                        "workspace.html, its platform and workspace in 3D (docs/view.md)")
    args = parser.parse_args()
    if args.workers is not None and args.workers < 1:
        parser.error(f"--workers = {args.workers} must be >= 1")
    try:
        units = Units.parse(args.units)
    except ValueError as e:
        parser.error(f"--units: {e}")
    try:
        summary = run(args.spec, args.out_dir, args.scenes, workers=args.workers,
                      scheduler=args.scheduler, progress=not args.no_progress,
                      log=lambda m: print(m, file=sys.stderr), units=units,
                      platform_file=args.platform, scale_to_ranges=args.scale_to_ranges)
    except SpecError as e:
        print(f"sweep.py: {e}", file=sys.stderr)  # names the field, or OUT_DIR
        return 2
    except RuntimeError as e:
        print(f"sweep.py: {e}", file=sys.stderr)
        return 1
    if args.view and (spec := load(args.spec, args.scenes, args.platform))["kind"] == "workspace":
        import stewart
        stewart.view(stewart.Platform(**spec["platform"]), title=spec["title"],
                     output=pathlib.Path(args.out_dir) / "workspace.html",
                     workspace=spec.get("volume", {}).get("orientation", (0.0, 0.0, 0.0)))
    print(f"sweep.py: {len(summary['computed'])} chunks computed in "
          f"{summary['wall_seconds']:.2f} s; results in {args.out_dir}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
