#!/usr/bin/env python3
"""Cold-start convergence of the forward kinematics over the workspace: the figure of
docs/forward-kinematics.md.

Runs `bench-forward --map` (one cold start from home per point of three slices through home:
x-y, roll-pitch, yaw-z; every other pose component at home), then draws per slice the Newton
iterations and the outcome against the pose the lengths came from.

usage: forward_convergence.py [--build BUILD_DIR] [--out docs/forward-convergence.png]
"""
import argparse
import csv
import pathlib
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
SLICES = {"x-y": ("x [m]", "y [m]"), "roll-pitch": ("roll [rad]", "pitch [rad]"),
          "yaw-z": ("yaw [rad]", "z [m]")}
# Outcomes, in the order of the colour map.
OUTCOMES = ("the pose (working mode)", "another pose, same lengths (truth on another mode)",
            "reported: other assembly mode", "error (singular, no pose)")
STATUS_OK, STATUS_OTHER_BRANCH = 0, -8


def read_map(build):
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "map.csv"
        subprocess.run([str(pathlib.Path(build) / "bench-forward"), "--map", str(path)], check=True)
        with open(path) as f:
            return list(csv.DictReader(f))


def outcome(row):
    status = int(row["status"])
    if status == STATUS_OK:
        if float(row["error"]) <= 1e-9:
            return 0
        if int(row["truth_branch"]) != 0:
            return 1
        raise SystemExit(f"wrong pose returned silently: {row}")  # never expected
    return 2 if status == STATUS_OTHER_BRANCH else 3


def grid(rows, key):
    u = np.array(sorted({float(r["u"]) for r in rows}))
    v = np.array(sorted({float(r["v"]) for r in rows}))
    z = np.full((v.size, u.size), np.nan)
    for r in rows:
        z[np.searchsorted(v, float(r["v"])), np.searchsorted(u, float(r["u"]))] = key(r)
    return u, v, z


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--out", default=str(ROOT / "docs" / "forward-convergence.png"))
    args = parser.parse_args()
    rows = read_map(args.build)

    fig, axes = plt.subplots(2, 3, figsize=(12, 7.5))
    outcome_map = ListedColormap(["#4daf4a", "#a6d96a", "#fdae61", "#d7191c"])
    summary = []
    for col, (name, (u_label, v_label)) in enumerate(SLICES.items()):
        sl = [r for r in rows if r["slice"] == name]
        u, v, iterations = grid(sl, lambda r: int(r["iterations"]) if int(r["status"]) in
                                (STATUS_OK, STATUS_OTHER_BRANCH) else np.nan)
        _, _, result = grid(sl, outcome)
        _, _, inside = grid(sl, lambda r: int(r["inside_stroke"]))
        extent = (u[0], u[-1], v[0], v[-1])
        ax = axes[0, col]
        image = ax.imshow(iterations, origin="lower", extent=extent, aspect="auto",
                          cmap="viridis", vmin=0, vmax=max(8, np.nanmax(iterations)))
        ax.contour(u, v, inside, levels=[0.5], colors="white", linewidths=1.5)
        ax.set_title(f"{name}: Newton iterations from home")
        fig.colorbar(image, ax=ax)
        ax = axes[1, col]
        ax.imshow(result, origin="lower", extent=extent, aspect="auto", cmap=outcome_map,
                  vmin=-0.5, vmax=3.5, interpolation="nearest")
        ax.contour(u, v, inside, levels=[0.5], colors="black", linewidths=1.5)
        ax.set_title(f"{name}: outcome")
        for a in axes[:, col]:
            a.set_xlabel(u_label)
            a.set_ylabel(v_label)
        inside_rows = [r for r in sl if r["inside_stroke"] == "1"]
        right = sum(outcome(r) == 0 for r in inside_rows)
        working = [r for r in sl if r["truth_branch"] == "0"]
        summary.append(f"{name}: inside the stroke {right}/{len(inside_rows)} right; "
                       f"every pose on the working mode {sum(outcome(r) == 0 for r in working)}"
                       f"/{len(working)} right")
    handles = [plt.Rectangle((0, 0), 1, 1, color=outcome_map(i)) for i in range(4)]
    fig.legend(handles, OUTCOMES, loc="lower center", ncol=4, fontsize="small")
    fig.suptitle("Forward kinematics, cold start from home (thesis platform); line: the stroke "
                 "workspace boundary")
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(args.out, dpi=70)
    print("\n".join(summary))


if __name__ == "__main__":
    main()
