"""Write one self-contained HTML page that shows a platform in 3D, at home or playing a result
(stewart.view, docs/view.md). The page needs nothing but a browser: open it from the file.

usage: python scripts/view.py --platform FILE.json [RESULT.csv|RESULT.parquet] [--poses IN.csv]
                              [-o view.html] [--title TEXT] [--force-limit N] [--workspace]

RESULT: any table with t and the pose columns x, y, z, roll, pitch, yaw (forward, plant, closed
loop, move, cueing outputs); forces from F1..F6 when present. An inverse output has no pose
columns: give its input poses with --poses IN.csv. Without RESULT, --poses alone steps through
the poses of IN.csv, and neither shows the platform at home. --workspace draws the
constant-orientation workspace at the first frame's orientation."""
import argparse
import pathlib
import sys

import stewart
from stewart.errors import ParameterError


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("result", nargs="?", help="result CSV or Parquet (t and pose columns)")
    parser.add_argument("--platform", required=True,
                        help="platform file (JSON, docs/geometry.md) or a shipped name: "
                             + ", ".join(stewart.platform_files()))
    parser.add_argument("--poses", help="the input poses of an inverse output (t and pose columns)")
    parser.add_argument("-o", "--output", default="view.html", help="the page to write")
    parser.add_argument("--title", help="the page's title (default: the platform file's name)")
    parser.add_argument("--force-limit", type=float,
                        help="largest |F_k| [N]: colours the legs by their force margin too")
    parser.add_argument("--workspace", action="store_true",
                        help="draw the constant-orientation workspace at the first frame's "
                             "orientation")
    args = parser.parse_args(argv)
    platform_file = stewart.platform_files().get(args.platform, args.platform)
    title = args.title or f"Stewart platform: {pathlib.Path(platform_file).name}"
    try:
        page = stewart.view(platform_file, args.result, args.poses, args.output,
                            title=title,
                            force_limit=args.force_limit, workspace=args.workspace or None)
    except (ParameterError, ValueError, OSError) as e:
        print(f"view: {e}", file=sys.stderr)
        return 2
    print(f"view: wrote {page} ({page.stat().st_size / 1e6:.1f} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
