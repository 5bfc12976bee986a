"""The constant-orientation workspace volume of a platform [m^3]: the set of positions the tool
frame's origin can take, in the user frame, at one orientation of the tool, within every limit
of Platform.limits (strokes, joint angles, leg interference, condition number).

How it is measured (docs/sweeps.md, "The workspace volume"):

1. The box. Home (Platform.check().home: the tool's pose in the user frame with the platform at
   (0, 0, home_height)) must be within every limit. The box starts as the x, y and z axis
   ranges (Platform.axis_ranges) of the home position at the chosen orientation, and each face on which a grid of points finds
   a position within the limits is moved out to the farthest axis-range end from those points,
   until no face holds one: the box follows the machine's own size, whatever its units or
   frames.
2. Columns. On n x n columns (x, y) over the box, the feasible z of each column is a union of
   intervals, each measured exactly by the z axis range (stroke ends are roots in closed form,
   the other classes proven steps; to 1e-6 m) from a seed within the limits. Seeds come from a
   scan of the column and from the neighbouring columns' intervals (so a column whose feasible
   interval is shorter than the scan's pitch is still found). The volume is the sum of cell area
   x feasible length: the midpoint rule over the columns, with each column's length exact.
3. Refinement. The columns are recomputed on grids 1.5 times finer until two successive volumes
   differ by less than half the accuracy asked for (default 0.5 %); the result is the last
   grid's volume and the error estimate is that difference. A seed whose x, y or z range ends
   beyond the box grows the box, and the columns start again.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Optional, Sequence

import numpy as np

from .. import _core
from ..params import parameters
from ..platform import Platform, _warn_condition

#: Columns per side of the first grid, and the largest grid the refinement goes to.
FIRST_CELLS = 48
MAX_CELLS = 400
#: Points per side of the grid checked on each face of the box while it grows.
FACE_POINTS = 24
#: z samples per column in the scan for seeds (the neighbours' intervals seed the rest).
SCAN_POINTS = 24


@dataclass
class WorkspaceVolume:
    """The volume [m^3] and how it was measured: error_estimate [m^3] is the difference between
    the last two grids' volumes (the refinement stops when it is below half the accuracy asked
    for); box (2, 3) [min, max] holds the workspace (its faces hold no position within the
    limits); grids: (columns per side, volume) of each grid computed; note: why the volume
    could not be measured to the accuracy asked for, else ""."""
    volume: float
    error_estimate: float
    orientation: tuple
    box: np.ndarray
    cells: int
    grids: list = field(default_factory=list)
    note: str = ""

    @property
    def relative_error(self) -> float:
        return self.error_estimate / self.volume if self.volume > 0 else math.inf


def _value(platform: Platform, name: str) -> np.ndarray:
    entry = next(p for p in parameters() if p["name"] == name)
    value = platform.params.get(name, entry["defaults"])
    return np.broadcast_to(np.asarray(value, dtype=float), (entry["count"],)).copy()


def checked_home(platform: Platform, warn_condition: Optional[float] = None) -> np.ndarray:
    """The home pose (Platform.check().home: the tool's pose in the user frame with the platform
    at (0, 0, home_height)), or ValueError naming the first limit it is beyond and by how
    much."""
    report = platform.check(warn_condition=warn_condition)
    if not report.valid:
        raise ValueError(_invalid_home(report.home, report.limits))
    return report.home


def reach_radius(platform: Platform) -> tuple[np.ndarray, float]:
    """(centre, radius): a ball in the user frame that holds every position of the tool with all
    legs within stroke_max (each leg at most stroke_max long plus its sensor offset, the joints
    at their distances from their frames' origins, the tool at its offset)."""
    base, top = (np.reshape(j, (6, 3)) for j in _core.model_joints(platform._model))
    stroke = float(np.max(_value(platform, "stroke_max") + np.abs(_value(platform, "length_offset"))))
    tool, user = _value(platform, "tool_frame"), _value(platform, "user_frame")
    # The tool at R_u^T (p + R d - u), the platform origin p within |a_k| + L_k + |b_k| of the
    # base origin (leg k joins them): a ball about the user origin.
    radius = (float(np.linalg.norm(base, axis=1).max()) + stroke +
              float(np.linalg.norm(top, axis=1).max()) + float(np.linalg.norm(tool[:3])) +
              float(np.linalg.norm(user[:3])))
    return np.zeros(3), radius


class _Limits:
    """The limit check and the axis ranges of positions at one orientation."""

    def __init__(self, platform: Platform, orientation: np.ndarray, warn_condition):
        self.platform, self.orientation = platform, orientation
        self.warn_condition = _warn_condition(warn_condition)
        # The smallest box holding every axis-range end found since reset_extent: where the
        # workspace reaches along x, y and z from the seeds.
        self.extent = np.array([[np.inf] * 3, [-np.inf] * 3])

    def reset_extent(self) -> None:
        self.extent = np.array([[np.inf] * 3, [-np.inf] * 3])

    def poses(self, points: np.ndarray) -> np.ndarray:
        q = np.empty((len(points), 6))
        q[:, :3] = points
        q[:, 3:] = self.orientation
        return q

    def within(self, points: np.ndarray) -> np.ndarray:
        if not len(points):
            return np.zeros(0, bool)
        return self.platform.limits(self.poses(points), warn_condition=self.warn_condition).within

    def ends(self, points: np.ndarray) -> np.ndarray:
        """(N, 3, 2): the x, y, z axis ranges of points (within the limits)."""
        if not len(points):
            return np.zeros((0, 3, 2))
        ends = self.platform.axis_ranges(self.poses(points),
                                         warn_condition=self.warn_condition)[:, :3, :]
        self.extent[0] = np.minimum(self.extent[0], ends[:, :, 0].min(axis=0))
        self.extent[1] = np.maximum(self.extent[1], ends[:, :, 1].max(axis=0))
        return ends


def workspace_volume(platform: Platform, orientation: Optional[Sequence[float]] = None,
                     cells: int = FIRST_CELLS, warn_condition: Optional[float] = None,
                     box: Optional[np.ndarray] = None, accuracy: float = 0.005,
                     details: bool = False):
    """The volume [m^3] of the positions of the tool frame's origin (in the user frame) within
    every limit of Platform.limits at the tool orientation `orientation` (roll, pitch, yaw
    [rad]; None: home's), to `accuracy` (relative; the module says how it is measured and
    checked). cells: columns per side of the first grid. box: (2, 3) [min, max] to start the
    search from instead of home's axis ranges (it still grows until its faces are outside).
    details=True returns a WorkspaceVolume (the error estimate, the box, the grids).

    ValueError if the home pose is not within every limit (the search starts there), or an
    argument is out of range. At an orientation where neither the home position nor a grid of
    the home box is within the limits the volume is 0.0, with a RuntimeWarning saying so."""
    if not (isinstance(cells, (int, np.integer)) and 2 <= cells <= MAX_CELLS):
        raise ValueError(f"cells = {cells!r} must be an integer in [2, {MAX_CELLS}]")
    if not (isinstance(accuracy, (int, float)) and 1e-4 <= accuracy <= 0.5):
        raise ValueError(f"accuracy = {accuracy!r} must be a relative error in [1e-4, 0.5]")
    home = checked_home(platform, warn_condition)
    at_home = _Limits(platform, home[3:], warn_condition)
    target = home[3:] if orientation is None else _orientation(orientation)
    limits = _Limits(platform, target, warn_condition)
    start = _start_box(at_home, limits, home[:3], box)
    if start is None:
        result = WorkspaceVolume(0.0, 0.0, tuple(target), np.array([home[:3], home[:3]]), 0,
                                 note="no position within every limit at this orientation: "
                                      "neither home's position nor a 32^3 grid of twice home's "
                                      "axis-range box is within the limits")
        warnings.warn(f"workspace_volume: {result.note}", RuntimeWarning, stacklevel=2)
        return result if details else 0.0
    seed, box = start
    result = _refine(limits, seed, box, int(cells), accuracy, reach_radius(platform))
    return result if details else result.volume


def _orientation(orientation) -> np.ndarray:
    o = np.asarray(orientation, dtype=float)
    if o.shape != (3,) or not np.all(np.isfinite(o)):
        raise ValueError(f"orientation = {orientation!r} must be 3 finite numbers (roll, pitch, "
                         "yaw [rad])")
    return o


def _invalid_home(home: np.ndarray, check) -> str:
    from ..limits import MARGIN_UNITS, class_name
    c = int(check.first[0]) - 1
    return (f"the home pose ({', '.join(f'{v:.6g}' for v in home)}) is not within every limit: "
            f"{class_name(c + 1)} margin {check.margin[0, c]:.6g} {MARGIN_UNITS[c]} at leg "
            f"{int(check.leg[0, c])}; the workspace is searched from home, so check the "
            "platform's geometry, strokes and limits (and their units)")


def _start_box(at_home: _Limits, limits: _Limits, home: np.ndarray, box) -> Optional[tuple]:
    """(seed, box): a position within the limits at the target orientation and the box to grow
    from; None if none is found."""
    home_ends = at_home.ends(home[None, :])[0]
    if box is not None:
        box = np.asarray(box, dtype=float)
        if box.shape != (2, 3) or not np.all(np.isfinite(box)) or np.any(box[1] <= box[0]):
            raise ValueError(f"box = {box.tolist()!r} must be [[x0, y0, z0], [x1, y1, z1]] "
                             "with x0 < x1, y0 < y1, z0 < z1 [m]")
    if limits.within(home[None, :])[0]:
        seed = home
    else:
        # Twice home's box, on a grid: the position within the limits nearest home.
        centre, half = home, np.maximum(home_ends[:, 1] - home_ends[:, 0], 1e-9)
        if box is not None:
            centre, half = box.mean(axis=0), box[1] - box[0]
        axes = [np.linspace(c - h, c + h, 32) for c, h in zip(centre, half)]
        grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        ok = limits.within(grid)
        if not ok.any():
            return None
        found = grid[ok]
        seed = found[np.argmin(np.linalg.norm(found - home, axis=1))]
    ends = limits.ends(seed[None, :])[0]
    start = np.array([ends[:, 0], ends[:, 1]])
    if box is not None:
        start = np.array([np.minimum(start[0], box[0]), np.maximum(start[1], box[1])])
    # A box of some thickness on every axis (an axis range can be a point on a limit).
    size = max(float(np.max(start[1] - start[0])), 1e-9)
    start[0] -= 1e-3 * size
    start[1] += 1e-3 * size
    return seed, start


def _grow(limits: _Limits, box: np.ndarray, reach) -> tuple[np.ndarray, bool]:
    """The box with each face that holds a position within the limits (on a FACE_POINTS grid)
    moved out past the farthest axis-range end of those positions; the second value is False
    when the box reached the reach ball's bound on some face (it cannot hold more)."""
    centre, radius = reach
    bound = np.array([centre - radius, centre + radius])
    box = box.copy()
    for _ in range(64):
        moved = False
        for axis in range(3):
            for side in (0, 1):
                others = [a for a in range(3) if a != axis]
                u = np.linspace(box[0, others[0]], box[1, others[0]], FACE_POINTS)
                v = np.linspace(box[0, others[1]], box[1, others[1]], FACE_POINTS)
                points = np.empty((FACE_POINTS * FACE_POINTS, 3))
                uu, vv = np.meshgrid(u, v, indexing="ij")
                points[:, others[0]], points[:, others[1]] = uu.ravel(), vv.ravel()
                points[:, axis] = box[side, axis]
                ok = limits.within(points)
                if not ok.any():
                    continue
                ends = limits.ends(points[ok])[:, axis, side]
                far = ends.max() if side else ends.min()
                pad = 0.02 * (box[1, axis] - box[0, axis])
                new = far + pad if side else far - pad
                new = min(new, bound[1, axis]) if side else max(new, bound[0, axis])
                if new != box[side, axis]:
                    box[side, axis] = new
                    moved = True
        if not moved:
            break
    inside_bound = bool(np.all(box[0] > bound[0]) and np.all(box[1] < bound[1]))
    return box, inside_bound


def _refine(limits: _Limits, seed, box, cells, accuracy, reach) -> WorkspaceVolume:
    box, _ = _grow(limits, box, reach)
    grids: list[tuple[int, float]] = []
    n = cells
    note = ""
    while True:
        volume, grown = _columns(limits, seed, box, n)
        if grown is not None:  # the workspace leaves the box: grow and start again
            centre, radius = reach
            grown = np.clip(grown, centre - radius, centre + radius)
            if not np.array_equal(grown, box):
                box, ok = _grow(limits, grown, reach)
                grids.clear()
                n = cells
                if not ok:
                    note = "the box reached the bound of every leg's reach"
                continue
            note = "the workspace reaches the bound of every leg's reach"
        grids.append((n, volume))
        if len(grids) >= 2:
            error = abs(grids[-1][1] - grids[-2][1])
            if error <= 0.5 * accuracy * volume:
                break
        nxt = int(math.ceil(1.5 * n))
        if nxt > MAX_CELLS:
            note = note or (f"the grids did not converge to {accuracy:g} by {n} columns per "
                            "side: the error estimate is the last two grids' difference")
            break
        n = nxt
    error = abs(grids[-1][1] - grids[-2][1]) if len(grids) >= 2 else math.inf
    return WorkspaceVolume(grids[-1][1], error, tuple(float(v) for v in limits.orientation),
                           box, grids[-1][0], grids, note)


def _columns(limits: _Limits, seed, box, n):
    """(volume on n x n columns over the box, None), or (that volume, a grown box) if the
    workspace leaves the box (the x, y or z range of a seed ends beyond it)."""
    limits.reset_extent()
    xe = np.linspace(box[0, 0], box[1, 0], n + 1)
    ye = np.linspace(box[0, 1], box[1, 1], n + 1)
    xc, yc = 0.5 * (xe[:-1] + xe[1:]), 0.5 * (ye[:-1] + ye[1:])
    nz = SCAN_POINTS
    zc = box[0, 2] + (np.arange(nz) + 0.5) * (box[1, 2] - box[0, 2]) / nz
    ix, iy, iz = np.meshgrid(np.arange(n), np.arange(n), np.arange(nz), indexing="ij")
    scan = np.column_stack([xc[ix.ravel()], yc[iy.ravel()], zc[iz.ravel()]])
    ok = limits.within(scan).reshape(n, n, nz)
    starts = ok & ~np.concatenate([np.zeros((n, n, 1), bool), ok[:, :, :-1]], axis=2)
    si, sj, sk = np.nonzero(starts)
    # The seed's own column: the workspace holds at least the seed.
    i0 = int(np.clip(np.searchsorted(xe, seed[0]) - 1, 0, n - 1))
    j0 = int(np.clip(np.searchsorted(ye, seed[1]) - 1, 0, n - 1))
    col = np.concatenate([si * n + sj, [i0 * n + j0]])
    z = np.concatenate([zc[sk], [seed[2]]])
    points = np.column_stack([xc[col // n], yc[col % n], z])
    keep = limits.within(points)
    col, points = col[keep], points[keep]
    intervals = _merge(col, *_z_ends(limits, points))
    frontier = intervals
    for _ in range(4 * n + 16):
        frontier = _from_neighbours(limits, frontier, intervals, n, xc, yc)
        if not len(frontier[0]):
            break
        intervals = _merge(*(np.concatenate([a, b]) for a, b in zip(intervals, frontier)))
    col, lo, hi = intervals
    beyond = np.array([limits.extent[0] < box[0], limits.extent[1] > box[1]])
    if beyond.any():
        # A seed's x, y or z range leaves the box: grow it past the farthest end.
        pad = 0.02 * (box[1] - box[0])
        grown = np.array([np.minimum(box[0], limits.extent[0] - pad * beyond[0]),
                          np.maximum(box[1], limits.extent[1] + pad * beyond[1])])
    else:
        grown = None
    area = (xe[1] - xe[0]) * (ye[1] - ye[0])
    return float(area * np.sum(hi - lo)), grown


def _z_ends(limits: _Limits, points: np.ndarray):
    ends = limits.ends(points)[:, 2, :]
    return ends[:, 0], ends[:, 1]


def _merge(col, lo, hi):
    """Intervals sorted by column and start, the overlapping ones of a column merged."""
    if not len(col):
        return col, lo, hi
    order = np.lexsort((lo, col))
    col, lo, hi = col[order], lo[order], hi[order]
    # The running maximum of hi within each column (columns offset apart so that one
    # accumulate does every column): it decides where a merged interval starts.
    offset = (float(hi.max() - lo.min()) + 1.0) * col
    reach = np.maximum.accumulate(hi + offset) - offset
    starts = np.ones(len(col), bool)
    starts[1:] = (col[1:] != col[:-1]) | (lo[1:] > reach[:-1])
    first = np.flatnonzero(starts)
    return col[first], lo[first], np.maximum.reduceat(hi, first)


def _covered(intervals, col, z) -> np.ndarray:
    """Whether z lies in one of column col's (merged, sorted) intervals."""
    c, lo, hi = intervals
    if not len(c) or not len(col):
        return np.zeros(len(col), bool)
    # (column, z) as one sortable number: the column plus z scaled into [0.25, 0.75]
    z0 = min(float(lo.min()), float(z.min()))
    scale = 0.5 / (max(float(hi.max()), float(z.max())) - z0 + 1e-300)
    keys = c + 0.25 + (lo - z0) * scale
    pos = np.searchsorted(keys, col + 0.25 + (z - z0) * scale, side="right") - 1
    found = pos >= 0
    pos = np.maximum(pos, 0)
    return found & (c[pos] == col) & (hi[pos] >= z)


def _from_neighbours(limits: _Limits, frontier, intervals, n, xc, yc):
    """New intervals found from seeds at three points of each frontier interval in each of its
    four neighbouring columns, where those points are within the limits and not yet covered."""
    c, lo, hi = frontier
    if not len(c):
        return frontier
    i, j = c // n, c % n
    cand_col, cand_z = [], []
    for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        ni, nj = i + di, j + dj
        inside = (ni >= 0) & (ni < n) & (nj >= 0) & (nj < n)
        for f in (0.1, 0.5, 0.9):
            cand_col.append((ni * n + nj)[inside])
            cand_z.append((lo + f * (hi - lo))[inside])
    col, z = np.concatenate(cand_col), np.concatenate(cand_z)
    fresh = ~_covered(intervals, col, z)
    col, z = col[fresh], z[fresh]
    if not len(col):
        return col, z, z
    points = np.column_stack([xc[col // n], yc[col % n], z])
    ok = limits.within(points)
    col, points = col[ok], points[ok]
    if not len(col):
        return col, points[:, 2], points[:, 2]
    new = _merge(col, *_z_ends(limits, points))
    # Keep only what is not covered yet (two seeds may find the same interval).
    mid = 0.5 * (new[1] + new[2])
    fresh = ~_covered(intervals, new[0], mid)
    return new[0][fresh], new[1][fresh], new[2][fresh]
