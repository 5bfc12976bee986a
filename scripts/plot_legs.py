#!/usr/bin/env python3
"""Plots a stewart-solve output CSV: actuator lengths, rates and forces per leg against time.

usage: plot_legs.py IN.csv OUT.png [--title TEXT] [--units mm]

IN.csv is stewart-solve's output in SI (its default); --units says the plot's units.
"""
import argparse

import numpy as np

import plots


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--title", default="")
    args, _ = plots.parse_args_with_units(parser)
    data = np.genfromtxt(args.csv, delimiter=",", names=True)
    series = {key: np.column_stack([data[f"{key}{k}"] for k in range(1, 7)])
              for key, _ in plots.LEG_PANELS}
    plots.plot_legs(data["t"], series, args.png, args.title, args.units)


if __name__ == "__main__":
    main()
