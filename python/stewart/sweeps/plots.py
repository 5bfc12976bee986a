"""PNG plots of a finished sweep: load envelopes per fidelity, workspace heat maps per slice."""
from __future__ import annotations

import pathlib

import numpy as np
import pyarrow.parquet as pq

from .units import Units


def plot(spec: dict, out: pathlib.Path, units: Units = Units()) -> list[pathlib.Path]:
    """Writes the plots of whatever parts are merged in out (their values already in units);
    returns their paths."""
    import matplotlib
    matplotlib.use("Agg")
    if spec["kind"] == "envelope":
        return _envelope(out) if (out / "envelope.parquet").exists() else []
    return [p for s in spec["slices"] if (out / f"workspace_{s['name']}.parquet").exists()
            for p in [_slice(s, out, units)]]


def _envelope(out: pathlib.Path) -> list[pathlib.Path]:
    """Per fidelity: the worst case over centre of mass, amplitude and frequency of each
    manoeuvre against payload mass, over the feasible cases (solved and within every limit):
    peak leg force, peak power, smallest distance to singularity."""
    import matplotlib.pyplot as plt
    t = pq.read_table(out / "envelope.parquet")
    cols = {k: t[k].to_numpy(zero_copy_only=False) for k in t.column_names}
    force = np.max(np.column_stack([np.asarray(cols[f"peak_force_{k}"], dtype=float)
                                       for k in range(1, 7)]), axis=1)
    panels = (("peak |F| over legs [N]", force),
              ("peak |power| [W]", np.asarray(cols["peak_power"], dtype=float)),
              ("smallest 1/condition", np.asarray(cols["min_inverse_condition"], dtype=float)))
    paths = []
    for level in sorted(set(cols["fidelity"])):
        fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8, 9))
        for ax, (label, values) in zip(axes, panels):
            for name in sorted(set(cols["manoeuvre"])):
                sel = ((cols["fidelity"] == level) & (cols["manoeuvre"] == name) &
                       (cols["status"] == 0) & cols["feasible"].astype(bool))
                masses = np.unique(cols["payload_mass"][sel])
                worst = [(np.min if label.startswith("smallest") else np.nanmax)(
                    values[sel & (cols["payload_mass"] == m)]) for m in masses]
                ax.plot(masses, worst, marker="o", label=name)
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
        axes[0].legend(fontsize="small")
        axes[-1].set_xlabel("payload mass [kg]")
        level_rows = cols["fidelity"] == level
        failed = int(np.sum(level_rows & (cols["status"] != 0)))
        beyond = int(np.sum(level_rows & (cols["status"] == 0) & ~cols["feasible"].astype(bool)))
        notes = [f"{failed} failed cases"] * bool(failed) + \
            [f"{beyond} cases beyond a limit, not drawn"] * bool(beyond)
        fig.suptitle(f"load envelope, {level} level" + (f" ({'; '.join(notes)})" if notes else ""))
        fig.tight_layout()
        path = out / f"envelope_{level}.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths


def _slice(s: dict, out: pathlib.Path, units: Units) -> pathlib.Path:
    """A two-axis slice: log10 condition and peak static |F| where reachable, the boundary drawn;
    a one-axis slice: the same as curves."""
    import matplotlib.pyplot as plt
    t = pq.read_table(out / f"workspace_{s['name']}.parquet",
                      columns=["reachable", "condition", *[f"F{k}" for k in range(1, 7)]])
    axes_items = list(s["axes"].items())
    shape = [len(v) for _, v in axes_items]
    reachable = t["reachable"].to_numpy().reshape(shape)
    cond = np.where(reachable, t["condition"].to_numpy().reshape(shape), np.nan)
    force = np.abs(np.column_stack([t[f"F{k}"].to_numpy() for k in range(1, 7)])).max(axis=1)
    force = np.where(reachable, force.reshape(shape), np.nan)
    fig, panels = plt.subplots(1, 2, figsize=(12, 5))
    fixed = ", ".join(f"{k} = {v * units.axis(k):g} {units.unit(k)}" for k, v in s["fixed"].items())
    axes_items = [(name, np.asarray(v) * units.axis(name)) for name, v in axes_items]
    for ax, values, label in zip(panels, (np.log10(np.where(cond > 0, cond, np.nan)), force),
                                 ("log10 condition", "peak static |F| [N]")):
        if len(shape) == 2:
            (n0, v0), (n1, v1) = axes_items
            mesh = ax.pcolormesh(v0, v1, values.T, shading="nearest")
            ax.contour(v0, v1, reachable.T.astype(float), levels=[0.5], colors="k", linewidths=1)
            ax.set_xlabel(f"{n0} [{units.unit(n0)}]")
            ax.set_ylabel(f"{n1} [{units.unit(n1)}]")
            fig.colorbar(mesh, ax=ax, label=label)
        else:
            (n0, v0), = axes_items
            ax.plot(v0, values)
            ax.set_xlabel(f"{n0} [{units.unit(n0)}]")
            ax.set_ylabel(label)
        ax.set_title(f"{s['name']}: {label} (blank: unreachable)")
    fig.suptitle(f"workspace slice {s['name']} ({fixed})")
    fig.tight_layout()
    path = out / f"workspace_{s['name']}.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
