"""The workspace volume's cost (stewart.sweeps.workspace_volume, docs/sweeps.md): per machine the
volume, its error estimate, the grids, the limit checks and axis ranges it called, and its time,
wall and CPU of this (single-threaded) process, the fastest of REPEAT runs. A benchmark, not a
test: it prints numbers.

usage: python studies/bench/workspace_volume.py [PLATFORM.json ...] [--repeat N]
(default: every shipped platform file, and the thesis platform with turned tool and user
frames)."""
import argparse
import time

import stewart
from stewart.sweeps import volume as volume_module
from stewart.sweeps import workspace_volume

FRAMES = dict(tool_frame=[0.03, -0.02, 0.12, 0.1, -0.05, 0.3],
              user_frame=[0.2, 0.1, 0.05, -0.04, 0.08, -0.6])


def machines(paths):
    if paths:
        return {p: stewart.Platform.from_file(p) for p in paths}
    out = {name: stewart.Platform.from_file(path) for name, path in stewart.platform_files().items()}
    out["thesis+frames"] = stewart.Platform.from_file(stewart.platform_files()["thesis"], **FRAMES)
    return out


class Counting(volume_module._Limits):
    """The module's limit calls, counted across one volume."""
    totals = {"checks": 0, "ranges": 0}

    def within(self, points):
        Counting.totals["checks"] += len(points)
        return super().within(points)

    def ends(self, points):
        Counting.totals["ranges"] += len(points)
        return super().ends(points)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("platforms", nargs="*")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    volume_module._Limits = Counting
    print(f"{'machine':16s} {'volume [m^3]':>13s} {'error est.':>10s} {'grids':>10s} "
          f"{'checks':>8s} {'ranges':>7s} {'wall [s]':>8s} {'cpu [s]':>8s}")
    for name, plat in machines(args.platforms).items():
        best_wall = best_cpu = float("inf")
        for _ in range(args.repeat):
            Counting.totals = {"checks": 0, "ranges": 0}
            wall, cpu = time.perf_counter(), time.process_time()
            try:
                result = workspace_volume(plat, details=True)
            except ValueError as e:
                print(f"{name:16s} refused: {e}")
                break
            best_wall = min(best_wall, time.perf_counter() - wall)
            best_cpu = min(best_cpu, time.process_time() - cpu)
        else:
            grids = "/".join(str(g[0]) for g in result.grids)
            print(f"{name:16s} {result.volume:13.6e} {result.relative_error:10.1e} {grids:>10s} "
                  f"{Counting.totals['checks']:8d} {Counting.totals['ranges']:7d} "
                  f"{best_wall:8.3f} {best_cpu:8.3f}" + (f"  note: {result.note}" if result.note else ""))


if __name__ == "__main__":
    main()
