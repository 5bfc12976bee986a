"""The cost of the check a user runs first (docs/geometry.md): per shipped machine the time of
Platform.check() on a built platform, of Platform.from_file + check() (what `stewart-solve
--check` does in the library: read the file, make the model, check home), and the time of the
whole `stewart-solve --check FILE` process (start-up included), wall and CPU. The goal is 10 ms
for the check. Medians and minima over REPEAT calls, CPU time for the in-process calls. A
benchmark, not a test: it prints numbers.

usage: python studies/bench/check.py [PLATFORM.json ...] [--repeat N] [--build BUILD_DIR]
(default: every shipped platform file)."""
import argparse
import os
import pathlib
import resource
import statistics
import subprocess
import time

import stewart

ROOT = pathlib.Path(__file__).resolve().parents[2]


def cpu_ms(call, repeat):
    """(median, min) CPU time of call() over repeat calls [ms]."""
    times = []
    for _ in range(repeat):
        start = time.process_time()
        call()
        times.append((time.process_time() - start) * 1e3)
    return statistics.median(times), min(times)


def process_ms(command, repeat):
    """(median wall, min wall, median CPU) time of running command [ms] (its exit status
    ignored: an invalid home exits 1 after the same work). The CPU time (user + system of the
    child) is what a loaded machine does not inflate."""
    times, cpu = [], []
    for _ in range(repeat):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        times.append((time.perf_counter() - start) * 1e3)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append((after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime) * 1e3)
    return statistics.median(times), min(times), statistics.median(cpu)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("platforms", nargs="*")
    parser.add_argument("--repeat", type=int, default=50)
    parser.add_argument("--build", default=os.environ.get("STEWART_BUILD_DIR", ROOT / "build"))
    args = parser.parse_args()
    files = ({pathlib.Path(p).stem: p for p in args.platforms} if args.platforms
             else stewart.platform_files())
    solve = pathlib.Path(args.build) / "stewart-solve"
    print(f"load average {os.getloadavg()[0]:.2f}; median (min) over {args.repeat} runs [ms]")
    print(f"{'machine':22s} {'valid':>5s} {'check()':>15s} {'from_file+check':>16s} "
          f"{'stewart-solve --check':>22s} {'its CPU':>8s}")
    for name, path in sorted(files.items()):
        platform = stewart.Platform.from_file(path)
        valid = platform.check().valid
        check = cpu_ms(platform.check, args.repeat)
        whole = cpu_ms(lambda: stewart.Platform.from_file(path).check(), args.repeat)
        cli = (process_ms([str(solve), "--check", str(path)], max(5, args.repeat // 5))
               if solve.exists() else (float("nan"),) * 3)
        print(f"{name:22s} {str(valid):>5s} {check[0]:7.3f} ({check[1]:5.3f}) "
              f"{whole[0]:8.3f} ({whole[1]:5.3f}) {cli[0]:13.2f} ({cli[1]:6.2f}) {cli[2]:8.2f}")


if __name__ == "__main__":
    main()
