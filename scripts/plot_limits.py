"""docs/limits-axis-ranges.png: which limit a pose meets first, over two slices of the thesis
platform's pose space with vendor-like limits, and the axis ranges of one pose drawn across each
slice (Platform.limits, Platform.axis_ranges; docs/limits.md section 7).

usage: python scripts/plot_limits.py [OUT.png]"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

import stewart  # noqa: E402

LIMITS = dict(base_joint_limit=0.45, platform_joint_limit=0.45, leg_diameter=0.2)
WARN_CONDITION = 60.0
CLASSES = ("within", "stroke", "base joint", "platform joint", "interference", "condition")
COLOURS = ("#f4f4f4", "#4c72b0", "#dd8452", "#c44e52", "#8172b3", "#55a868")
POSE = np.array([0.03, -0.02, 0.52, 0.05, -0.03, 0.1])
SLICES = (("x", "y", 0, 1, 0.3), ("roll", "yaw", 3, 5, 0.8))


def main(out="docs/limits-axis-ranges.png"):
    platform = stewart.Platform(**LIMITS)
    ranges = platform.axis_ranges(POSE, warn_condition=WARN_CONDITION, details=True)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5), constrained_layout=True)
    for ax, (name_a, name_b, a, b, half) in zip(axes, SLICES):
        va = POSE[a] + np.linspace(-half, half, 241)
        vb = POSE[b] + np.linspace(-half, half, 241)
        grid = np.repeat(POSE[None, :], va.size * vb.size, axis=0)
        A, B = np.meshgrid(va, vb, indexing="ij")
        grid[:, a], grid[:, b] = A.ravel(), B.ravel()
        first = platform.limits(grid, warn_condition=WARN_CONDITION).first.reshape(A.shape)
        ax.pcolormesh(va, vb, first.T, cmap=ListedColormap(COLOURS), vmin=-0.5, vmax=5.5,
                      shading="nearest")
        for axis, horizontal in ((a, True), (b, False)):
            lo, hi = ranges.ends[0, axis]
            ends = ranges.limit[0, axis]
            line = ([lo, hi], [POSE[b]] * 2) if horizontal else ([POSE[a]] * 2, [lo, hi])
            ax.plot(*line, color="k", lw=2)
            for value, cls in zip((lo, hi), ends):
                point = (value, POSE[b]) if horizontal else (POSE[a], value)
                ax.plot(*point, "o", color=COLOURS[cls], mec="k", ms=8)
        ax.plot(POSE[a], POSE[b], "k*", ms=12)
        unit = "m" if a < 3 else "rad"
        ax.set_xlabel(f"{name_a} [{unit}]")
        ax.set_ylabel(f"{name_b} [{unit}]")
        ax.set_title(f"first limit met over {name_a}-{name_b}, the rest of the pose held")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in COLOURS]
    fig.legend(handles, CLASSES, loc="outside lower center", ncols=len(CLASSES))
    fig.suptitle("Thesis platform, joints 0.45 rad, legs 0.2 m thick, condition 60: the axis "
                 "ranges of the starred pose (ends coloured by the limit met)")
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main(*sys.argv[1:])
