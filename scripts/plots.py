"""Plots shared by the scripts: per-leg time series, forces per fidelity, platform animation."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402

LEG_PANELS = (("L", "length L [m]"), ("L_dot", "rate dL/dt [m/s]"), ("F", "force F [N]"))
UNITS_HELP = ("units of the plots' lengths (m, mm, um) and angles (rad, deg, mrad, urad), e.g. "
              "mm,deg (default m,rad; the CSVs stay SI)")


def units(text="m,rad"):
    """The Units of a --units argument ('mm,deg'; stewart.sweeps.units, as sweep.py's)."""
    from stewart.sweeps.units import Units
    return Units.parse(text)


def parse_args_with_units(parser, argv=None):
    """parser's arguments with a --units argument added, and the Units it names; a bad --units
    is the parser's usage error."""
    parser.add_argument("--units", default="m,rad", help=UNITS_HELP)
    args = parser.parse_args(argv)
    try:
        return args, units(args.units)
    except ValueError as e:
        parser.error(f"--units: {e}")


def drawn(axes):
    """{y label: (N, lines) array of what each panel draws}: the numbers as plotted."""
    return {ax.get_ylabel(): np.column_stack([line.get_ydata() for line in ax.lines])
            for ax in axes}
FIDELITY_NAMES = {0: "kinematic", 1: "massless legs", 2: "full 14-body"}


def _leg_style(k):
    return {"label": f"leg {k}", "linestyle": "-" if k % 2 else "--"}


def _stacked_panels(t, panels, draw, path, title, legend=False):
    """One panel per (key, label) against time, drawn by draw(ax, key), saved to path."""
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(9, 9))
    for ax, (key, label) in zip(axes, panels):
        draw(ax, key)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    if legend:
        axes[0].legend(ncol=6, fontsize="small", loc="lower center", bbox_to_anchor=(0.5, 1.0))
    axes[-1].set_xlabel("time t [s]")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return drawn(axes)


def plot_legs(t, series, path, title="", unit_text="m,rad"):
    """series: {'L': (N, 6), 'L_dot': (N, 6), 'F': (N, 6)} in SI → one panel each, a line per
    leg, lengths in unit_text's length unit; returns drawn()."""
    length = units(unit_text).length
    factor = {"L": units(unit_text).factor("L1"), "L_dot": units(unit_text).factor("L1"),
              "F": 1.0}
    panels = (("L", f"length L [{length}]"), ("L_dot", f"rate dL/dt [{length}/s]"),
              LEG_PANELS[2])

    def draw(ax, key):
        for k in range(6):
            ax.plot(t, series[key][:, k] * factor[key], **_leg_style(k + 1))
    return _stacked_panels(t, panels, draw, path, title, legend=True)


def plot_forces_per_fidelity(t, forces, path, title=""):
    """forces: {fidelity: (N, 6)} → top: every leg's force at each level; bottom: each level's
    difference from the highest level given."""
    levels = sorted(forces)
    best = levels[-1]
    style = {best: "-"} | dict(zip(levels[:-1][::-1], ("--", ":")))
    style_name = {"-": "solid", "--": "dashed", ":": "dotted"}
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 8),
                                      gridspec_kw={"height_ratios": [2, 1]})
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for level in levels:
        for k in range(6):
            top.plot(t, forces[level][:, k], color=colors[k], linestyle=style[level],
                     label=f"leg {k + 1}" if level == best else None)
    for level in levels[:-1]:
        for k in range(6):
            bottom.plot(t, forces[level][:, k] - forces[best][:, k], color=colors[k],
                        linestyle=style[level])
    top.set_ylabel("force F [N]")
    top.set_title(", ".join(f"{FIDELITY_NAMES[lv]} {style_name[style[lv]]}" for lv in levels[::-1]),
                  fontsize="small")
    top.legend(ncol=6, fontsize="small", loc="lower center", bbox_to_anchor=(0.5, 1.08))
    bottom.set_ylabel(f"F − F({FIDELITY_NAMES[best]}) [N]")
    bottom.set_xlabel("time t [s]")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def rotation(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def animate_platform(t, q, path, base_points, platform_points, title="", frames=60):
    """A GIF of the platform moving: base and platform joints joined in leg order, and the six
    legs; q are poses of the platform frame in the base frame (no tool or user frame)."""
    idx = np.linspace(0, len(t) - 1, min(frames, len(t))).astype(int)
    fig = plt.figure(figsize=(5, 5), dpi=80)
    ax = fig.add_subplot(projection="3d")
    tops = [q[i, :3] + platform_points @ rotation(*q[i, 3:]).T for i in idx]
    points = np.vstack([base_points, *tops])
    centre = (points.max(axis=0) + points.min(axis=0)) / 2
    half = 0.6 * np.max(points.max(axis=0) - points.min(axis=0))  # equal axes: no distortion
    ax.set_xlim(centre[0] - half, centre[0] + half), ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_xlabel("x [m]"), ax.set_ylabel("y [m]"), ax.set_zlabel("z [m]")
    closed = list(range(6)) + [0]
    ax.plot(*base_points[closed].T, color="gray")
    plate, = ax.plot([], [], [], color="tab:blue", linewidth=2)
    legs = [ax.plot([], [], [], color="tab:orange")[0] for _ in range(6)]
    label = ax.set_title(title)

    def draw(frame):
        i = idx[frame]
        top = q[i, :3] + platform_points @ rotation(*q[i, 3:]).T
        plate.set_data_3d(*top[closed].T)
        for k, line in enumerate(legs):
            line.set_data_3d(*np.vstack([base_points[k], top[k]]).T)
        label.set_text(f"{title}  t = {t[i]:.2f} s")
        return [plate, *legs]

    anim = animation.FuncAnimation(fig, draw, frames=len(idx), blit=False)
    anim.save(path, writer=animation.PillowWriter(fps=15))
    plt.close(fig)


def plot_slider_crank(data, path, title=""):
    """data: slider-crank-solve columns → slider position, velocity, acceleration and crank torque."""
    panels = (("slider_x", "slider x [m]"), ("slider_v", "slider velocity [m/s]"),
              ("slider_a", "slider acceleration [m/s²]"), ("crank_torque", "crank torque [N m]"))
    _stacked_panels(data["t"], panels, lambda ax, key: ax.plot(data["t"], data[key]), path, title)
