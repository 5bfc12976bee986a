#!/usr/bin/env python3
"""Plots a stewart-solve output CSV: actuator lengths, rates and forces per leg against time.

usage: plot_legs.py IN.csv OUT.png [--title TEXT]
"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = (("L", "length L [m]"), ("L_dot", "rate dL/dt [m/s]"), ("F", "force F [N]"))


def read_columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    data = read_columns(args.csv)
    fig, axes = plt.subplots(len(PANELS), 1, sharex=True, figsize=(9, 9))
    for ax, (prefix, label) in zip(axes, PANELS):
        for k in range(1, 7):
            ax.plot(data["t"], data[f"{prefix}{k}"], label=f"leg {k}",
                    linestyle="-" if k % 2 else "--")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(ncol=6, fontsize="small", loc="upper center", bbox_to_anchor=(0.5, 1.25))
    axes[-1].set_xlabel("time t [s]")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)


if __name__ == "__main__":
    main()
