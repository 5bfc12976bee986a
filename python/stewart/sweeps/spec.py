"""Sweep specs: parsing, validation before any work, and the split into chunks.

A spec is JSON (docs/sweeps.md has the full format). Two kinds:

* ``"kind": "envelope"``: cases = payload_mass x payload_com x manoeuvre (scene x amplitude scale
  x frequency scale) x fidelity; each case is one trajectory; per case the peaks (work.py). A
  scene moves about the machine's home pose as scripts/run_scene.py --platform moves it
  (stewart.scenes.on_platform; ``"scale_to_ranges"`` scales it to the machine's axis ranges),
  unless its manoeuvre says ``"place": "absolute"`` (its poses as written).
* ``"kind": "workspace"``: slices of the pose space, each one or two pose components on a grid
  with the others fixed, moved to the machine's home as scenes are (unless the slice says
  ``"place": "absolute"``); per pose reachability within every limit, the limit margins, condition
  and static forces; optionally (``"volume"``) the constant-orientation workspace volume.

Every field is checked here, before anything is sent to a worker: a bad one raises SpecError
naming the field (``manoeuvres[1].amplitude``) and the value.
"""
from __future__ import annotations

import json
import math
import os
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import ParameterError
from .. import scenes
from ..choices import Fidelity
from ..params import read_platform_file
from ..platform import Platform
from ..scenes import POSE
from . import trajectory
from .volume import FIRST_CELLS, MAX_CELLS, checked_home

SOLVER_OPTIONS = ("tolerance", "max_iterations", "modified_newton", "warn_condition",
                  "singular_condition")
# Memory per item, rounded up, for the size checks before any work: a pose being solved (its
# inputs and InverseSolution, about 420 bytes), a row of a merged result table (about 30
# columns), a value of a range (a Python float in a list and its numpy source).
BYTES_PER_POSE = 512
BYTES_PER_ROW = 512
BYTES_PER_VALUE = 48
_COMMON = {"kind", "platform_file", "platform", "options", "fidelity", "title"}
_FIELDS = {
    "envelope": _COMMON | {"payload_mass", "payload_com", "manoeuvres", "duration", "step",
                           "cases_per_chunk", "scale_to_ranges"},
    "workspace": _COMMON | {"slices", "poses_per_chunk", "volume"},
}


class SpecError(ValueError):
    """A sweep spec (or OUT_DIR) that cannot run: the message names the field and its value."""


@dataclass(frozen=True)
class Chunk:
    """One unit of work: rows [start, stop) of a part (the cases, or one workspace slice)."""
    part: str
    index: int
    start: int
    stop: int

    @property
    def file_name(self) -> str:
        return f"{self.part}-{self.index:05d}.parquet"


def load(path: str | pathlib.Path, scene_dir: str | pathlib.Path,
         platform_file: str | pathlib.Path | None = None, scale_to_ranges: bool = False) -> dict:
    """The spec in JSON file `path`, checked and resolved (see resolve); a relative
    platform_file is found beside the spec. platform_file (a path from the working directory:
    `sweep.py --platform`) replaces the spec's; scale_to_ranges (`--scale-to-ranges`) sets an
    envelope's."""
    try:
        raw = json.loads(pathlib.Path(path).read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise SpecError(f"{path}: {e}") from None
    if isinstance(raw, dict) and platform_file is not None:
        raw = {**raw, "platform_file": str(pathlib.Path(platform_file).resolve())}
    if isinstance(raw, dict) and scale_to_ranges:
        if raw.get("kind") != "envelope":
            raise SpecError(f"--scale-to-ranges scales an envelope's scenes: {path} is a "
                            f"{raw.get('kind')!r} spec")
        raw = {**raw, "scale_to_ranges": True}
    return resolve(raw, scene_dir, pathlib.Path(path).parent)


def resolve(raw: Any, scene_dir: str | pathlib.Path,
            spec_dir: str | pathlib.Path = ".") -> dict:
    """A checked, self-contained spec: ranges expanded to lists, scenes read from scene_dir and
    the platform file (relative to spec_dir) read and embedded, so that workers need no files.
    Raises SpecError naming the first bad field."""
    if not isinstance(raw, dict):
        raise SpecError("the spec must be a JSON object")
    kind = raw.get("kind")
    if kind not in _FIELDS:
        raise SpecError(f"kind = {kind!r} must be 'envelope' or 'workspace'")
    unknown = sorted(set(raw) - _FIELDS[kind])
    if unknown:
        raise SpecError(f"unknown field {unknown[0]!r} for kind {kind!r} "
                        f"(known: {', '.join(sorted(_FIELDS[kind]))})")
    spec = {"kind": kind, "title": str(raw.get("title", "")),
            "platform": {**_platform_file(raw, pathlib.Path(spec_dir)), **_mapping(raw, "platform")},
            "options": _options(raw)}
    base = _platform(spec["platform"], {}, "platform")
    fidelity = raw.get("fidelity", ["massless"] if kind == "envelope" else "massless")
    if kind == "envelope":
        spec["fidelity"] = [_fidelity(f, f"fidelity[{i}]") for i, f in
                            enumerate(_list(fidelity, "fidelity"))]
        _check_options(base, spec["options"], spec["fidelity"])
        spec.update(_envelope(raw, spec, base, pathlib.Path(scene_dir),
                              pathlib.Path(spec_dir)))
    else:
        spec["fidelity"] = _fidelity(fidelity, "fidelity")
        _check_options(base, spec["options"], [spec["fidelity"]])
        home = base.check().home
        spec["slices"] = [_placed_slice(_slice(s, f"slices[{i}]"), home) for i, s in
                          enumerate(_list(raw.get("slices"), "slices"))]
        names = [s["name"] for s in spec["slices"]]
        if len(set(names)) != len(names):
            raise SpecError(f"slices: names {names} must differ")
        spec["poses_per_chunk"] = _positive_int(raw.get("poses_per_chunk", 65536), "poses_per_chunk")
        for i, s in enumerate(spec["slices"]):
            _fits(f"slices[{i}] ({s['name']}: "
                  f"{' x '.join(str(len(v)) for v in s['axes'].values())} grid)",
                  slice_size(s), BYTES_PER_ROW, "poses")
        _fits("poses_per_chunk", spec["poses_per_chunk"], BYTES_PER_POSE, "poses per chunk")
        if "volume" in raw:
            spec["volume"] = _volume(raw["volume"], "volume")
            try:  # the volume is searched from home: refused now, not after the maps
                checked_home(base, spec["options"].get("warn_condition"))
            except ValueError as e:
                raise SpecError(f"volume: {e}") from None
    return spec


def chunks(spec: dict) -> list[Chunk]:
    """The chunks of a resolved spec, in a fixed order that depends on the spec only (never on
    the number of workers), so that every run splits the work alike."""
    if spec["kind"] == "envelope":
        parts = [("cases", case_count(spec), spec["cases_per_chunk"])]
    else:
        parts = [(s["name"], slice_size(s), spec["poses_per_chunk"]) for s in spec["slices"]]
    out = []
    for part, n, size in parts:
        for i, start in enumerate(range(0, n, size)):
            out.append(Chunk(part, i, start, min(start + size, n)))
    return out


def case_count(spec: dict) -> int:
    """Number of envelope cases."""
    variants = sum(len(m["amplitude"]) * len(m["frequency"]) for m in spec["manoeuvres"])
    return len(spec["payload_mass"]) * len(spec["payload_com"]) * variants * len(spec["fidelity"])


def slice_size(s: dict) -> int:
    """Number of poses of a workspace slice."""
    return math.prod(len(v) for v in s["axes"].values())


# ---------------------------------------------------------------- envelope fields

def _envelope(raw: dict, spec: dict, base: Platform, scene_dir: pathlib.Path,
              spec_dir: pathlib.Path) -> dict:
    out: dict[str, Any] = {}
    inline = _mapping(raw, "platform")
    for key in ("payload_mass", "payload_com"):
        if key in inline and key in raw:
            raise SpecError(f"platform.{key} and the top-level {key} are both given: the "
                            f"envelope sweeps the top-level {key}; give it once")
        # The platform's own payload (its file's or the spec's) is the sweep's single value
        # unless the top-level list sweeps it.
        given = spec["platform"].pop(key, None)
        if key not in raw and given is not None:
            raw = {**raw, key: [given]}
    out["payload_mass"] = _values(raw.get("payload_mass", [0.0]), "payload_mass")
    coms = _list(raw.get("payload_com", [[0.0, 0.0, 0.0]]), "payload_com")
    out["payload_com"] = []
    for i, c in enumerate(coms):
        c = np.asarray(c, dtype=float) if _is_numbers(c) else None
        if c is None or c.shape != (3,) or not np.all(np.isfinite(c)):
            raise SpecError(f"payload_com[{i}] = {coms[i]!r} must be 3 finite numbers [m]")
        out["payload_com"].append(c.tolist())
    out["duration"] = _optional_positive(raw, "duration")
    out["step"] = _optional_positive(raw, "step")
    out["scale_to_ranges"] = raw.get("scale_to_ranges", False)
    if not isinstance(out["scale_to_ranges"], bool):
        raise SpecError(f"scale_to_ranges = {out['scale_to_ranges']!r} must be true or false")
    out["manoeuvres"] = [_manoeuvre(m, f"manoeuvres[{i}]", scene_dir, spec_dir, out, base)
                         for i, m in enumerate(_list(raw.get("manoeuvres"), "manoeuvres"))]
    out["cases_per_chunk"] = _positive_int(raw.get("cases_per_chunk", 8), "cases_per_chunk")
    _check_envelope_size({**spec, **out})
    for i, m in enumerate(out["payload_mass"]):
        for j, c in enumerate(out["payload_com"]):
            _platform(spec["platform"], {"payload_mass": m, "payload_com": c},
                      f"payload_mass[{i}] = {m} with payload_com[{j}] = {c}")
    return out


def _check_envelope_size(spec: dict) -> None:
    """SpecError unless one case's trajectory and the table of all cases fit in memory."""
    for i, m in enumerate(spec["manoeuvres"]):
        if "trajectory" in m:
            continue  # read whole already: its rows fit
        scene = m["scene"]
        samples = scenes.samples(scene, spec["step"], spec["duration"]) + 1
        where = (f"manoeuvres[{i}] ({m['name']}): duration {spec['duration'] or scene['duration']:g} s "
                 f"at step {spec['step'] or scene['step']:g} s")
        _fits(where, samples, BYTES_PER_POSE, "poses per case")
    _fits("the envelope (payload_mass x payload_com x manoeuvres x fidelity)", case_count(spec),
          BYTES_PER_ROW, "cases")


def _manoeuvre(m: Any, field: str, scene_dir: pathlib.Path, spec_dir: pathlib.Path,
               top: dict, base: Platform) -> dict:
    """A scene (a name in scene_dir or an inline scene object, whose duration and step default
    to the spec's), placed as its "place" says, or a CSV trajectory, with its amplitude and
    frequency scales."""
    if not isinstance(m, dict) or ("scene" in m) == ("csv" in m):
        raise SpecError(f"{field} = {m!r} must be an object with a 'scene' (a name in scenes/ "
                        "or an inline scene object) or a 'csv' (a trajectory file)")
    known = {"scene", "place", "amplitude", "frequency"} if "scene" in m else \
        {"csv", "name", "about", "amplitude", "frequency"}
    unknown = sorted(set(m) - known)
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: {', '.join(sorted(known))})")
    scales = {"amplitude": _values(m.get("amplitude", [1.0]), f"{field}.amplitude"),
              "frequency": _values(m.get("frequency", [1.0]), f"{field}.frequency")}
    if "csv" in m:
        bad = [f for f in scales["frequency"] if f <= 0]
        if bad:
            raise SpecError(f"{field}.frequency = {bad[0]!r} must be > 0 (it divides the "
                            "trajectory's times)")
        return {**_csv_manoeuvre(m, field, spec_dir, base), **scales}
    scene = m["scene"]
    try:
        if isinstance(scene, str):
            if not (scene_dir / f"{scene}.json").is_file():
                raise SpecError(f"{field}.scene = {scene!r}: there is no {scene_dir / scene}.json")
            name, scene = scene, scenes.load(scene, scene_dir)
        elif isinstance(scene, dict):
            name = str(scene.get("name", f"inline{field}"))
            # The spec's duration and step stand in for the ones an inline scene leaves out.
            scene = {**{k: top[k] for k in ("duration", "step") if top.get(k) is not None},
                     **scene}
            for key in ("duration", "step"):
                if key not in scene:
                    raise SpecError(f"{field}.scene has no {key}: give it in the scene or as "
                                    f"the spec's top-level {key}")
            scenes.check(scene, f"{field}.scene")
        else:
            raise SpecError(f"{field}.scene = {scene!r} must be a scene name or a scene object")
    except scenes.SceneError as e:
        raise SpecError(f"{field}.scene: {e}" if isinstance(m["scene"], str) else str(e)) from None
    if "move" in scene:  # planned on a platform, not a sum of sinusoids the sweep can scale
        raise SpecError(f"{field}.scene = {name!r} has a move section: an envelope sweeps "
                        "sinusoids; give the move's poses as a CSV trajectory ({\"csv\": ...})")
    if "pose" not in scene:
        raise SpecError(f"{field}.scene = {name!r} has no pose (a mechanism scene cannot be swept)")
    place = m.get("place", "home")
    if place == "home":
        if "place" not in m and "home" not in scene:
            _written_about_thesis_home(scene, base, field, name)
        scene = _placed(scene, base, top, field)
    elif place != "absolute":
        raise SpecError(f"{field}.place = {place!r} must be 'home' (the scene moved from the pose "
                        "it is written about to the machine's home) or 'absolute' (its poses as "
                        "written)")
    elif top["scale_to_ranges"]:
        raise SpecError(f"{field}.place = 'absolute' with scale_to_ranges: the scaling is about "
                        "the machine's home; place the scene at home, or do not scale")
    played = {"pose": scene["pose"], "duration": float(scene["duration"]),
              "step": float(scene["step"])}
    if place == "home":
        played["home"] = scene["home"]  # the machine's: where the scene was placed
    return {"name": name, "place": place, "scene": played, **scales}


def _written_about_thesis_home(scene: dict, base: Platform, field: str, name: str) -> None:
    """SpecError when a scene that states neither its home nor its place has its mean position
    nearer this machine's home than the thesis home it would be moved from: it was most likely
    written for this machine in absolute poses, and moving it would play it elsewhere."""
    mean = np.array([scene["pose"].get(p, {}).get("mean", 0.0) for p in scenes.POSE[:3]])
    try:
        home = base.check().home[:3]
    except ValueError:
        return  # _placed refuses a machine without a valid home, naming why
    thesis = np.asarray(scenes.THESIS_HOME[:3])
    if np.linalg.norm(mean - home) < np.linalg.norm(mean - thesis):
        raise SpecError(
            f"{field}.scene = {name!r}: its mean position {mean.tolist()} m is nearer this "
            f"machine's home {home.tolist()} m than the thesis home {thesis.tolist()} m it would "
            "be moved from; give \"place\": \"absolute\" to play its poses as written, or the "
            "scene's \"home\" (the pose it is written about)")


def _placed(scene: dict, base: Platform, top: dict, field: str) -> dict:
    """The scene moved from its home (the pose it is written about: its "home", default the
    thesis platform's, as the shipped scenes are) to the machine's home pose and scaled to its
    axis ranges with the spec's scale_to_ranges, as scripts/run_scene.py --platform moves it
    (stewart.scenes.on_platform); scaled, its samples are checked on the sweep's time grid."""
    on_grid = {**scene, **{k: top[k] for k in ("duration", "step") if top.get(k) is not None}}
    try:
        placed = scenes.on_platform({k: v for k, v in on_grid.items() if k != "move"}, base,
                                    scale_to_ranges=top["scale_to_ranges"])
    except ValueError as e:  # SceneError, or the machine's check (ParameterError)
        raise SpecError(f"{field}: {e}\n(\"place\": \"absolute\" plays the scene's poses as "
                        "written)") from None
    return {**scene, "pose": placed["pose"], "home": placed["home"]}


def _csv_manoeuvre(m: dict, field: str, spec_dir: pathlib.Path, base: Platform) -> dict:
    """A CSV trajectory read and embedded (the workers need no file), with the pose its
    amplitude scales about: "first" (its first row, the default), "home" (the machine's home
    pose) or 6 numbers."""
    name = m["csv"]
    if not isinstance(name, str) or not name:
        raise SpecError(f"{field}.csv = {name!r} must be the path of a CSV file")
    try:
        data = trajectory.read_csv(spec_dir / name)
    except trajectory.TrajectoryError as e:
        raise SpecError(f"{field}.csv: {e}") from None
    _fits(f"{field}.csv ({name})", len(data["t"]), BYTES_PER_POSE, "poses per case")
    about = m.get("about", "first")
    if about == "first":
        about = data["pose"][0]
    elif about == "home":
        try:
            about = base.check().home
        except ValueError as e:
            raise SpecError(f"{field}.about = 'home': {e}") from None
    elif _is_numbers(about) and len(about) == 6 and all(math.isfinite(v) for v in about):
        about = np.asarray(about, dtype=float)
    else:
        raise SpecError(f"{field}.about = {about!r} must be 'first', 'home' or 6 finite numbers "
                        "(x, y, z [m], roll, pitch, yaw [rad])")
    label = m.get("name", pathlib.Path(name).stem)
    if not isinstance(label, str) or not label:
        raise SpecError(f"{field}.name = {label!r} must be a text")
    return {"name": label, "trajectory": {
        "file": name, "t": data["t"].tolist(), "pose": data["pose"].tolist(),
        "rate": data["rate"].tolist(), "accel": data["accel"].tolist(),
        "about": np.asarray(about, dtype=float).tolist()}}


def manoeuvre_samples(spec: dict, m: dict, amplitude: float, frequency: float):
    """Times, poses, rates and accelerations of one variant of manoeuvre m of an envelope spec."""
    if "trajectory" in m:
        return trajectory.sample(m["trajectory"], amplitude, frequency)
    return scenes.sample(m["scene"], amplitude, frequency, spec["duration"], spec["step"])


# ---------------------------------------------------------------- workspace fields

def _slice(s: Any, field: str) -> dict:
    """A slice as written: its poses about its "home" (default the thesis platform's, as the
    shipped scenes are) unless "place" is "absolute"."""
    if not isinstance(s, dict):
        raise SpecError(f"{field} = {s!r} must be an object with name, fixed and axes")
    known = {"name", "fixed", "axes", "place", "home"}
    unknown = sorted(set(s) - known)
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: {', '.join(sorted(known))})")
    place = s.get("place", "home")
    if place not in ("home", "absolute"):
        raise SpecError(f"{field}.place = {place!r} must be 'home' (the slice moved from the "
                        "pose it is written about to the machine's home) or 'absolute' (its "
                        "poses as written)")
    written_about = s.get("home", list(scenes.THESIS_HOME))
    if not (_is_numbers(written_about) and len(written_about) == 6 and
            all(math.isfinite(v) for v in written_about)):
        raise SpecError(f"{field}.home = {written_about!r} must be 6 finite numbers (the pose "
                        "the slice is written about: x, y, z [m], roll, pitch, yaw [rad])")
    if place == "absolute" and "home" in s:
        raise SpecError(f"{field}: 'home' with place 'absolute': an absolute slice is not moved")
    name = s.get("name")
    if not isinstance(name, str) or not name.replace("_", "").replace("-", "").replace(".", "").isalnum():
        raise SpecError(f"{field}.name = {name!r} must be a word (letters, digits, _ - .)")
    fixed = _mapping(s, "fixed", f"{field}.fixed")
    axes = _mapping(s, "axes", f"{field}.axes")
    if not 1 <= len(axes) <= 2:
        raise SpecError(f"{field}.axes has {len(axes)} components: give 1 or 2")
    for comp in (*fixed, *axes):
        if comp not in POSE:
            raise SpecError(f"{field}: {comp!r} is not a pose component {POSE}")
    both = set(fixed) & set(axes)
    if both:
        raise SpecError(f"{field}: {sorted(both)[0]!r} is both fixed and an axis")
    if "z" not in fixed and "z" not in axes:
        raise SpecError(f"{field}: z is neither fixed nor an axis (the base plane is singular)")
    out_fixed = {}
    for comp, v in fixed.items():
        if not isinstance(v, (int, float)) or not math.isfinite(v):
            raise SpecError(f"{field}.fixed.{comp} = {v!r} must be a finite number")
        out_fixed[comp] = float(v)
    return {"name": name, "place": place, "home": [float(v) for v in written_about],
            "fixed": out_fixed,
            "axes": {comp: _values(v, f"{field}.axes.{comp}") for comp, v in axes.items()}}


def _placed_slice(s: dict, home: np.ndarray) -> dict:
    """Slice s moved by the machine's home (Platform.check().home) minus the pose it is written
    about, component by component, as a sweep's scenes are moved (stewart.scenes.on_platform):
    its fixed values, its axes' values, and a component it leaves out (0 about its home) where
    the two homes differ. An absolute slice is kept as written. The result's "home" is the
    machine's where the slice was placed."""
    if s["place"] == "absolute":
        return {k: v for k, v in s.items() if k != "home"}
    shift = np.asarray(home, dtype=float) - np.asarray(s["home"], dtype=float)
    fixed = {comp: float(v + shift[POSE.index(comp)]) for comp, v in s["fixed"].items()}
    for i, comp in enumerate(POSE):  # in POSE order: the same spec gives the same dict
        if comp not in fixed and comp not in s["axes"] and shift[i] != 0.0:
            fixed[comp] = float(shift[i])
    axes = {comp: [float(v + shift[POSE.index(comp)]) for v in values]
            for comp, values in s["axes"].items()}
    return {**s, "home": [float(v) for v in home], "fixed": fixed, "axes": axes}


def _volume(v: Any, field: str) -> dict:
    """{"orientation": [roll, pitch, yaw] (default: home's), "cells": columns per side of the
    first grid (48), "accuracy": relative (0.005)}."""
    if not isinstance(v, dict):
        raise SpecError(f"{field} = {v!r} must be an object with orientation, cells, accuracy")
    unknown = sorted(set(v) - {"orientation", "cells", "accuracy"})
    if unknown:
        raise SpecError(f"{field}: unknown field {unknown[0]!r} (known: accuracy, cells, "
                        "orientation)")
    orientation = v.get("orientation")
    if orientation is not None and not (_is_numbers(orientation) and len(orientation) == 3 and
                                        all(math.isfinite(x) for x in orientation)):
        raise SpecError(f"{field}.orientation = {orientation!r} must be 3 finite numbers "
                        "(roll, pitch, yaw [rad])")
    cells = v.get("cells", FIRST_CELLS)
    if not isinstance(cells, int) or isinstance(cells, bool) or not 2 <= cells <= MAX_CELLS:
        raise SpecError(f"{field}.cells = {cells!r} must be an integer in [2, {MAX_CELLS}]")
    accuracy = v.get("accuracy", 0.005)
    if not (isinstance(accuracy, (int, float)) and not isinstance(accuracy, bool) and
            1e-4 <= accuracy <= 0.5):
        raise SpecError(f"{field}.accuracy = {accuracy!r} must be a relative error in [1e-4, 0.5]")
    return {"orientation": None if orientation is None else [float(x) for x in orientation],
            "cells": cells, "accuracy": float(accuracy)}


# ---------------------------------------------------------------- shared helpers

def _values(v: Any, field: str) -> list[float]:
    """A list of finite numbers from a list, a number, or {"start", "stop", "num"}."""
    if isinstance(v, dict):
        unknown = sorted(set(v) - {"start", "stop", "num"})
        if unknown or not {"start", "stop", "num"} <= set(v):
            raise SpecError(f"{field} = {v!r}: a range needs exactly start, stop, num")
        num = v["num"]
        whole = isinstance(num, (int, float)) and not isinstance(num, bool) and \
            math.isfinite(num) and num == int(num)
        if not whole:
            raise SpecError(f"{field}.num = {num!r} must be a whole number >= 1 (how many values)")
        if num < 1:
            raise SpecError(f"{field}.num = {num!r}: the range is empty (num must be >= 1)")
        if not all(isinstance(v[k], (int, float)) and math.isfinite(v[k]) for k in ("start", "stop")):
            raise SpecError(f"{field} = {v!r}: start and stop must be finite numbers")
        _fits(f"{field}.num", num, BYTES_PER_VALUE, "values")
        return np.linspace(v["start"], v["stop"], int(num)).tolist()
    values = _list(v, field)
    if not _is_numbers(values) or not all(math.isfinite(x) for x in values):
        raise SpecError(f"{field} = {v!r} must be finite numbers")
    return [float(x) for x in values]


def memory_bytes() -> int:
    """The machine's physical memory [bytes]."""
    return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")


def _fits(field: str, count: float, bytes_each: int, what: str) -> None:
    """SpecError naming field unless count items of bytes_each fit in the machine's memory
    (checked before any work: a sweep that cannot fit would fail after hours, or swap)."""
    need, have = count * bytes_each, memory_bytes()
    if not need <= have:  # also refuses an infinite or NaN count
        raise SpecError(f"{field}: {count:.3g} {what} need about {need / 1e9:.3g} GB "
                        f"({bytes_each} bytes each), more than this machine's memory "
                        f"({have / 1e9:.3g} GB)")


def _list(v: Any, field: str) -> list:
    if v is None:
        raise SpecError(f"{field} is missing")
    values = v if isinstance(v, list) else [v]
    if not values:
        raise SpecError(f"{field} is empty: give at least one value")
    return values


def _is_numbers(v: Any) -> bool:
    return isinstance(v, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)


def _mapping(raw: dict, key: str, field: str | None = None) -> dict:
    v = raw.get(key, {})
    if not isinstance(v, dict):
        raise SpecError(f"{field or key} = {v!r} must be an object")
    return dict(v)


def _positive_int(v: Any, field: str) -> int:
    if not isinstance(v, int) or isinstance(v, bool) or v < 1:
        raise SpecError(f"{field} = {v!r} must be an integer >= 1")
    return v


def _optional_positive(raw: dict, key: str) -> float | None:
    v = raw.get(key)
    if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
        raise SpecError(f"{key} = {v!r} must be a number > 0")
    return None if v is None else float(v)


def _fidelity(v: Any, field: str) -> str:
    try:
        return Fidelity.of(v).name.lower()
    except ParameterError as e:
        raise SpecError(f"{field}: {e}") from None


def _options(raw: dict) -> dict:
    options = _mapping(raw, "options")
    for k in options:
        if k not in SOLVER_OPTIONS:
            raise SpecError(f"options: unknown option {k!r} (known: {', '.join(SOLVER_OPTIONS)})")
    return options


def _check_options(base: Platform, options: dict, levels: list[str]) -> None:
    for level in levels:
        try:
            base.inverse(np.zeros((0, 6)), fidelity=level, **options)
        except (ParameterError, TypeError, ValueError) as e:
            raise SpecError(f"options: {e}") from None


def _platform_file(raw: dict, spec_dir: pathlib.Path) -> dict:
    """The parameters of the spec's platform_file (none without one); `platform` changes them."""
    if "platform_file" not in raw:
        return {}
    name = raw["platform_file"]
    if not isinstance(name, str) or not name:
        raise SpecError(f"platform_file = {name!r} must be the path of a platform file")
    try:
        return read_platform_file(spec_dir / name)
    except ParameterError as e:
        raise SpecError(f"platform_file: {e}") from None


def _platform(params: dict, extra: dict, field: str) -> Platform:
    try:
        return Platform(**params, **extra)
    except ParameterError as e:
        raise SpecError(f"{field}: {e}") from None
