"""stewart.view: one self-contained HTML page that shows a platform in 3D in a browser, at rest or
playing a result (docs/view.md). The page holds its data and its scripts (three.js, inlined from
the package's copy of the pinned npm package): it opens from a file with no server and no network.
"""
from __future__ import annotations

import base64
import os
import pathlib
from collections.abc import Mapping
from typing import Optional, Union

import numpy as np

from . import _core
from .limits import LIMIT_CLASSES, MARGIN_UNITS
from .params import parameter_values
from .platform import Platform
from .scenes import POSE
from .view_template import fill, script_json, template_parts

PathLike = Union[str, "os.PathLike[str]"]
#: The classes a leg is coloured by: the library's per-leg classes, then the force (when a
#: force limit and forces are given). The condition number is the pose's, shown beside the view.
LEG_CLASSES = ("stroke", "base_joint", "platform_joint", "interference", "force")
LEG_CLASS_UNITS = ("m", "rad", "rad", "m", "N")
NO_CLASS = 255  # a leg no class names at a frame (never: the stroke names every leg)
#: Results of up to this many rows get their axis ranges drawn unless told otherwise.
AXIS_RANGE_ROWS = 20000


def view(platform: Union[Platform, PathLike], result=None, poses=None,
         output: PathLike = "view.html", *, title: Optional[str] = None,
         force_limit=None, warn_condition: Optional[float] = None,
         axis_ranges: Optional[bool] = None, workspace=None) -> pathlib.Path:
    """Write one HTML page showing platform (a Platform or a platform file) and return its path.

    result: None (the platform at poses, or at home), a CSV or Parquet file, or a mapping of
    column names to arrays, with a column ``t`` [s] and the pose columns x, y, z, roll, pitch, yaw
    (the tool frame in the user frame, as every pose of the package); forces are read from
    F1..F6 (or F[1]..F[6]) when present. An inverse output has no pose columns: give its input
    poses as poses (a file or mapping with the pose columns, row for row). Without a result,
    poses may be an (N, 6) array or a file of poses to step through. force_limit: the largest
    |F_k| [N] (one number or six), which adds the force class to the legs' colours; None: the
    platform's leg_force_max (legs without one have no force class).
    warn_condition: the condition limit of the limit check (None: the library's 1e3).
    axis_ranges: draw each frame's axis ranges (Platform.axis_ranges) as arrows; None: for up
    to AXIS_RANGE_ROWS frames (about 50 us and 64 bytes of page a frame).
    workspace: None, True (the first frame's orientation) or (roll, pitch, yaw) [rad]: draws the
    constant-orientation workspace there (workspace_columns) as its top and bottom surfaces.
    ValueError names a missing column, a row count that differs, or a non-finite pose."""
    if not isinstance(platform, Platform):
        platform = Platform.from_file(platform)
    t, q, forces = _frames(platform, result, poses)
    data = _page_data(platform, t, q, forces, force_limit, warn_condition)
    if axis_ranges is None:
        axis_ranges = len(q) <= AXIS_RANGE_ROWS
    if axis_ranges:
        ends = platform.axis_ranges(q, warn_condition=warn_condition)
        data["ranges"] = _packed(ends - q[:, :, None], np.float32)  # (N, 6, 2) from the pose
    if workspace is not None and workspace is not False:
        orientation = q[0, 3:] if workspace is True else np.asarray(workspace, dtype=float)
        data["workspace"] = workspace_columns(platform, orientation, warn_condition=warn_condition)
    data["title"] = title or "Stewart platform"
    output = pathlib.Path(output)
    output.write_text(_page(data), encoding="utf-8")
    return output


def _frames(platform: Platform, result, poses):
    """(t, q, forces or None) of the frames to show: the result's, or poses', or home."""
    if result is None:
        if poses is None:
            return np.zeros(1), home_pose(platform)[None, :], None
        if isinstance(poses, (str, os.PathLike)) or isinstance(poses, Mapping):
            columns = read_columns(poses)
            q = _pose_columns(columns, poses)
            t = _times(columns["t"], poses) if "t" in columns else np.arange(len(q), dtype=float)
            return t, q, None
        q = np.array(poses, dtype=float, ndmin=2)
        if q.ndim != 2 or q.shape[1] != 6:
            raise ValueError(f"poses has shape {q.shape}: it must be (N, 6), "
                             "(x, y, z, roll, pitch, yaw) per row")
        return np.arange(len(q), dtype=float), _finite(q, "poses"), None
    columns = read_columns(result)
    if "t" not in columns:
        raise ValueError(f"{_name(result)} has no column t (the time [s] of each row)")
    t = _times(columns["t"], result)
    if all(p in columns for p in POSE):
        if poses is not None:
            raise ValueError(f"{_name(result)} has the pose columns already: give poses only with "
                             "an inverse output, whose poses are its input's")
        q = _pose_columns(columns, result)
    elif poses is None:
        raise ValueError(f"{_name(result)} has no pose columns ({', '.join(POSE)}): for an inverse "
                         "output give its input poses too (poses=, --poses IN.csv)")
    else:
        q = _pose_columns(read_columns(poses), poses)
        if len(q) != len(t):
            raise ValueError(f"{_name(poses)} has {len(q)} rows but {_name(result)} has {len(t)}: "
                             "the poses must be the result's input, row for row")
    return t, q, _leg_columns(columns, "F")


def read_columns(source) -> dict[str, np.ndarray]:
    """The numeric columns of a CSV or Parquet file (or a mapping of names to arrays) by name."""
    if isinstance(source, Mapping):
        return {str(k): np.asarray(v, dtype=float) for k, v in source.items()
                if np.asarray(v).dtype.kind in "biuf"}
    path = pathlib.Path(source)
    if path.suffix.lower() in (".parquet", ".pq"):
        try:
            import pyarrow.parquet as pq
        except ImportError:
            raise ValueError(f"{path}: reading Parquet needs pyarrow (pip install pyarrow)") \
                from None
        import pyarrow.types as types
        table = pq.read_table(path)
        return {field.name: table.column(field.name).to_numpy().astype(float)
                for field in table.schema
                if types.is_floating(field.type) or types.is_integer(field.type)}
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
    wanted = [i for i, name in enumerate(header) if _wanted(name)]
    if not wanted:
        return {}
    try:
        table = np.loadtxt(path, delimiter=",", skiprows=1, usecols=wanted, ndmin=2, quotechar='"')
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None
    return {header[i]: table[:, j] for j, i in enumerate(wanted)}


def _wanted(name: str) -> bool:
    return name == "t" or name in POSE or name.startswith("F")


def _name(source) -> str:
    return str(source) if isinstance(source, (str, os.PathLike)) else "the result"


def _times(t: np.ndarray, source) -> np.ndarray:
    """t, or ValueError naming the first row where it is not finite or goes back: the slider
    and the playback follow t."""
    t = np.asarray(t, dtype=float)
    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise ValueError(f"{_name(source)}: t = {t[bad[0]]} in row {bad[0]} is not finite")
    back = np.flatnonzero(np.diff(t) < 0)
    if back.size:
        raise ValueError(f"{_name(source)}: t goes back from {float(t[back[0]])!r} to "
                         f"{float(t[back[0] + 1])!r} at row {back[0] + 1}: the page plays rows in "
                         "the order of t")
    return t


def _pose_columns(columns: Mapping[str, np.ndarray], source) -> np.ndarray:
    missing = [p for p in POSE if p not in columns]
    if missing:
        raise ValueError(f"{_name(source)} has no column {', '.join(missing)} (the pose columns "
                         f"are {', '.join(POSE)})")
    return _finite(np.column_stack([columns[p] for p in POSE]), _name(source))


def _finite(q: np.ndarray, name: str) -> np.ndarray:
    bad = np.flatnonzero(~np.all(np.isfinite(q), axis=1))
    if bad.size:
        raise ValueError(f"{name}: row {bad[0]} has a pose that is not finite "
                         f"({q[bad[0]].tolist()}): the page cannot draw it; drop the row")
    return np.ascontiguousarray(q, dtype=float)


def _leg_columns(columns: Mapping[str, np.ndarray], prefix: str) -> Optional[np.ndarray]:
    for pattern in ("{}{}", "{}[{}]"):
        names = [pattern.format(prefix, k) for k in range(1, 7)]
        if all(n in columns for n in names):
            return np.column_stack([columns[n] for n in names])
    return None


def effective_parameters(platform: Platform) -> dict[str, np.ndarray]:
    """Every parameter's values for platform: the thesis defaults with the platform's changes."""
    return parameter_values(platform.params)


def home_pose(platform: Platform) -> np.ndarray:
    """The tool's pose in the user frame when the platform is at its home (0, 0, home_height, 0,
    0, 0) in the base frame: the check's (Platform.check().home), in the platform's rotation
    convention."""
    return platform.check().home


def _leg_margins(platform: Platform, values: dict, q: np.ndarray, lengths: np.ndarray,
                 forces: Optional[np.ndarray], force_limit, warn_condition):
    """Per frame and leg the margin to each class of LEG_CLASSES (each leg's own, from the
    library's check; NaN for interference when leg_diameter is 0: no check), the scale each
    margin is measured against, and the pose-level check (first class, condition)."""
    n = len(q)
    check = platform.limits(q, warn_condition=warn_condition)
    margin = np.full((n, 6, len(LEG_CLASSES)), np.nan)
    # The stroke of every leg from the library's lengths (Cardan to Cardan: reading + offset).
    joint_to_joint = lengths + values["length_offset"]
    smin, smax = values["stroke_min"], values["stroke_max"]
    margin[:, :, 0] = np.minimum(joint_to_joint - smin, smax - joint_to_joint)
    for c in (1, 2, 3):  # base joint, platform joint, interference: every leg's own margin
        margin[:, :, c] = check.leg_margin[:, c, :]
    scale = np.ones((6, len(LEG_CLASSES)))
    scale[:, 0] = 0.5 * (smax - smin)
    scale[:, 1] = values["base_joint_limit"][0]
    scale[:, 2] = values["platform_joint_limit"][0]
    diameter = float(values["leg_diameter"][0])
    if diameter > 0:
        scale[:, 3] = 5 * diameter  # a gap of five diameters is far
    else:
        margin[:, :, 3] = np.nan  # leg_diameter 0: no interference check
    if forces is not None:
        limit = _force_limits(values, force_limit)
        limited = limit > 0  # a leg without a limit: no force class
        margin[:, limited, 4] = limit[limited] - np.abs(forces[:, limited])
        scale[limited, 4] = limit[limited]
    return margin, scale, check


def _force_limits(values: dict, force_limit) -> np.ndarray:
    """Each leg's largest |F_k| [N]: force_limit when given, else the platform's leg_force_max
    (0: that leg has no force limit)."""
    if force_limit is None:
        return np.asarray(values["leg_force_max"], dtype=float).reshape(6)
    limit = np.broadcast_to(np.asarray(force_limit, dtype=float), (6,))
    if not np.all(np.isfinite(limit) & (limit > 0)):
        raise ValueError(f"force_limit = {force_limit!r} must be positive and finite (N)")
    return limit


def _nearest_class(margin: np.ndarray, scale: np.ndarray):
    """The class each leg is nearest to (its smallest margin over the scale) and that margin."""
    fraction = np.where(np.isnan(margin), np.inf, margin / scale)
    nearest = np.argmin(fraction, axis=2)
    chosen = np.take_along_axis(margin, nearest[..., None], axis=2)[..., 0]
    nearest = np.where(np.isnan(chosen), NO_CLASS, nearest).astype(np.uint8)
    return nearest, chosen


def _page_data(platform: Platform, t, q, forces, force_limit, warn_condition) -> dict:
    """The page's data: the keys docs/view.md ("The page's data") defines, as the command lines'
    --view writes them (csrc/cli/view_page.cpp)."""
    values = effective_parameters(platform)
    base, top = _core.model_joints(platform._model)
    solution = platform.inverse(q, fidelity="kinematic")
    lengths = np.where(solution.status[:, None] == 0, solution.length, np.nan)
    margin, scale, check = _leg_margins(platform, values, q, lengths, forces, force_limit,
                                        warn_condition)
    nearest, chosen = _nearest_class(margin, scale)
    scalar = {name: float(values[name][0]) for name in
              ("leg_diameter", "payload_mass", "home_height", "base_joint_limit",
               "platform_joint_limit")}
    vectors = {name: values[name].tolist() for name in
               ("tool_frame", "user_frame", "length_offset", "stroke_min", "stroke_max",
                "payload_com", "platform_com")}
    return {
        "machine": {"base_joint": list(base), "platform_joint": list(top), **scalar, **vectors,
                    "warn_condition": 1e3 if warn_condition is None else float(warn_condition)},
        "classes": list(LEG_CLASSES), "class_units": list(LEG_CLASS_UNITS),
        "pose_classes": ["none", *LIMIT_CLASSES], "pose_class_units": ["", *MARGIN_UNITS],
        "scale": scale.T.tolist(), "frames": len(q),
        "t": _packed(t, np.float64), "pose": _packed(q, np.float64),
        "force": None if forces is None else _packed(forces, np.float32),
        "leg_class": _packed(nearest, np.uint8), "leg_margin": _packed(chosen, np.float32),
        "first": _packed(check.first, np.uint8),
        "first_margin": _packed(np.take_along_axis(
            check.margin, np.maximum(check.first - 1, 0)[:, None].astype(np.intp), 1)[:, 0],
            np.float32),
        "condition": _packed(check.condition, np.float32),
        "ranges": None, "workspace": None,
    }


def _packed(a, dtype) -> str:
    """a as little-endian binary of dtype, base64: the page decodes it into a typed array."""
    return base64.b64encode(np.ascontiguousarray(a, dtype=np.dtype(dtype).newbyteorder("<"))
                            .tobytes()).decode("ascii")


def _page(data: dict) -> str:
    return fill(template_parts(), data["title"], script_json(data))


def workspace_columns(platform: Platform, orientation, cells: int = 32,
                      warn_condition: Optional[float] = None) -> dict:
    """The constant-orientation workspace at orientation (roll, pitch, yaw [rad]) as columns: on
    a cells x cells grid of (x, y) over its extent, the z interval [z_min, z_max] of the tool's
    origin (user frame) within every limit of Platform.limits, each end measured to 1e-6 m by
    Platform.axis_ranges from a feasible point of a scan (the longest run of the column's scan;
    a column with more than one feasible run shows that run only). x, y: the grid's cell
    centres; z_min, z_max: (cells, cells) lists, None where the column has no feasible z."""
    orientation = np.asarray(orientation, dtype=float)
    if orientation.shape != (3,) or not np.all(np.isfinite(orientation)):
        raise ValueError(f"workspace orientation = {orientation.tolist()} must be 3 finite "
                         "numbers (roll, pitch, yaw [rad])")
    base, top = (np.asarray(j).reshape(6, 3) for j in _core.model_joints(platform._model))
    values = effective_parameters(platform)
    reach = float(values["stroke_max"].max()) + np.linalg.norm(base, axis=1).max() + \
        np.linalg.norm(top, axis=1).max() + np.linalg.norm(values["user_frame"][:3]) + \
        np.linalg.norm(values["tool_frame"][:3])

    def feasible(points):
        poses = np.column_stack([points, np.repeat(orientation[None, :], len(points), 0)])
        return platform.limits(poses, warn_condition=warn_condition).within

    axes = [np.linspace(-reach, reach, 25)] * 3
    coarse = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    found = coarse[feasible(coarse)]
    empty = {"x": [], "y": [], "z_min": [], "z_max": [], "orientation": orientation.tolist()}
    if not len(found):
        return empty
    pitch = axes[0][1] - axes[0][0]
    lo, hi = found.min(axis=0) - pitch, found.max(axis=0) + pitch
    x, y = (np.linspace(lo[i], hi[i], cells + 2)[1:-1] for i in range(2))
    z = np.linspace(lo[2], hi[2], 48)
    grid = np.stack(np.meshgrid(x, y, z, indexing="ij"), axis=-1).reshape(-1, 3)
    ok = feasible(grid).reshape(cells, cells, len(z))
    seeds, where = [], []
    for i in range(cells):
        for j in range(cells):
            run = _longest_run(ok[i, j])
            if run is not None:
                seeds.append([x[i], y[j], z[run], *orientation])
                where.append((i, j))
    z_min = [[None] * cells for _ in range(cells)]
    z_max = [[None] * cells for _ in range(cells)]
    if seeds:
        ends = platform.axis_ranges(np.asarray(seeds), warn_condition=warn_condition)[:, 2, :]
        for (i, j), (a, b) in zip(where, ends):
            z_min[i][j], z_max[i][j] = float(a), float(b)
    return {"x": x.tolist(), "y": y.tolist(), "z_min": z_min, "z_max": z_max,
            "orientation": orientation.tolist()}


def _longest_run(column: np.ndarray) -> Optional[int]:
    """The middle index of the longest run of True in column, or None."""
    best, start, middle = 0, None, None
    for k, v in enumerate(np.append(column, False)):
        if v and start is None:
            start = k
        elif not v and start is not None:
            if k - start > best:
                best, middle = k - start, (start + k - 1) // 2
            start = None
    return middle
